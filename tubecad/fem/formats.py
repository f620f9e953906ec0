"""The finite-element formats by extension: the one table ``tubecad mesh`` and the API use."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path


def _inp(mesh, path: Path, material=None, step=None, title: str = "tubecad mesh") -> None:
    from tubecad.fem.inp import write_inp

    write_inp(mesh, path, material, step, title)


def _msh(mesh, path: Path, **_) -> None:
    from tubecad.fem.meshio_formats import write_msh

    write_msh(mesh, path)


def _vtu(mesh, path: Path, **_) -> None:
    from tubecad.fem.meshio_formats import write_vtu

    write_vtu(mesh, path)


@dataclass(frozen=True)
class FEFormat:
    extension: str
    description: str
    write: Callable[..., None]


FE_FORMATS = {
    f.extension: f
    for f in (
        FEFormat(
            ".inp",
            "CalculiX/Abaqus deck: nodes, elements, named node and element sets, exact normals (*NORMAL), "
            "material, shell and beam sections, and the pressure step when there is one",
            _inp,
        ),
        FEFormat(".msh", "gmsh 4.1: nodes, elements, one physical group per block (wall, ring_03_web, ...)", _msh),
        FEFormat(
            ".vtu",
            "VTK XML: nodes, elements, normals and principal directions per node, block and panel per "
            "element (ParaView)",
            _vtu,
        ),
    )
}
