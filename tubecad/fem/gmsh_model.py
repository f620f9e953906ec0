"""gmsh with an OCCT shape loaded: the one way tubecad starts gmsh, used by the junction's and
the net's shell models (:mod:`tubecad.fem.junction`, :mod:`tubecad.fem.net_shell`).

gmsh is started if it is not (without reading its configuration files, its SIGPIPE handler
undone: it would end the process on a closed pipe) and stopped again afterwards; its terminal
output is off; the shape file is imported into a model of its own, removed afterwards.
:func:`quad_options` are the meshing options both models take: frontal-Delaunay recombined
into quadrilaterals by Blossom (measured the best quads after recombination), the size from
``size`` and the boundary only.
"""

from __future__ import annotations

import signal
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from tubecad.core.errors import TubecadError


@contextmanager
def gmsh_model(shape_file: Path, name: str, what: str) -> Iterator[Any]:
    """gmsh's module with ``shape_file`` (STEP or BREP) imported and synchronised in the model
    ``name``, for the block; a TubecadError saying ``what`` needs gmsh where it is missing."""
    try:
        import gmsh
    except ImportError:
        raise TubecadError(f"meshing {what} needs gmsh: pip install gmsh (or tubecad[fem])") from None
    started = gmsh.isInitialized()
    if not started:
        pipe = signal.getsignal(signal.SIGPIPE)
        gmsh.initialize(readConfigFiles=False, interruptible=False)
        signal.signal(signal.SIGPIPE, pipe)  # gmsh sets its default (end the process on a closed pipe)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(name)
        try:
            gmsh.model.occ.importShapes(str(shape_file))
            gmsh.model.occ.synchronize()
            yield gmsh
        finally:
            gmsh.model.remove()
    finally:
        if not started:
            gmsh.finalize()


def quad_options(gmsh: Any, size: float) -> None:
    """Set the quadrilateral meshing options (module docstring) for elements of ``size``."""
    for option, value in (
        ("Mesh.MeshSizeMax", size),
        ("Mesh.MeshSizeMin", 0.0),
        ("Mesh.MeshSizeFromCurvature", 0),
        ("Mesh.MeshSizeExtendFromBoundary", 1),
        ("Mesh.Algorithm", 6),  # frontal-Delaunay
        ("Mesh.RecombineAll", 1),
        ("Mesh.RecombinationAlgorithm", 1),  # Blossom
    ):
        gmsh.option.setNumber(option, value)
