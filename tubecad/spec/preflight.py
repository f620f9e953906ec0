"""What a checked spec and a command's options decide before the CAD kernel loads.

Importing OCCT and build123d takes 3-6 s; everything a spec and the command line alone can
decide is decided first, so that a mistake is refused in a fraction of a second and nothing is
written: the outputs (known extensions, formats the spec's kind can be written as, folders
that exist and take a file), the mesh tolerances, and a command's external program
(``ccx`` for ``tubecad analyse``). The spec's own keys, ranges, reachable fit tolerance,
regularity and stiffener indices are checked by :func:`tubecad.spec.parse.parse_spec`.
This module imports neither OCCT nor build123d.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from tubecad.core.errors import ParameterError, SpecError
from tubecad.spec.parse import AnySpec

__all__ = [
    "MESH_OPTIONS",
    "check_analysis",
    "check_build_outputs",
    "check_flat",
    "check_output_folder",
    "check_shop",
    "check_mesh_options",
    "mesh_tolerance_for",
    "split_outputs",
]

#: how the command line names the mesh tolerances (in messages)
MESH_OPTIONS = ("--mesh-tolerance", "--mesh-angle")


def split_outputs(outputs: Iterable[str | Path]) -> tuple[list[Path], list[Path]]:
    """Shape outputs (CAD, mesh and picture formats) and polyline outputs (.csv, .json).

    Args:
        outputs: output paths; the format is chosen by extension (tubecad.export.registry).

    Returns:
        (shape outputs, polyline outputs), in the given order.

    Raises:
        ParameterError: an extension no format has, listing every allowed one.
    """
    from tubecad.export.registry import output_format

    paths = [Path(p) for p in outputs]
    kinds = {p: output_format(p).kind for p in paths}
    return [p for p in paths if kinds[p] != "polylines"], [p for p in paths if kinds[p] == "polylines"]


def check_mesh_options(outputs: Iterable[str | Path], mesh_tolerance: float | None, mesh_angle: float | None) -> None:
    """--mesh-tolerance and --mesh-angle only with a mesh output among ``outputs``.

    Args:
        outputs: output paths or names with an extension.
        mesh_tolerance: the --mesh-tolerance given, or None.
        mesh_angle: the --mesh-angle given, or None.

    Raises:
        ParameterError: a mesh option given and no mesh output asked for.
    """
    from tubecad.export.registry import EXTENSIONS

    outputs = list(outputs)
    if mesh_tolerance is None and mesh_angle is None or any(Path(p).suffix.lower() not in EXTENSIONS for p in outputs):
        return  # an unknown extension is refused by split_outputs, listing them all
    if not any(getattr(EXTENSIONS.get(Path(p).suffix.lower()), "kind", "") == "mesh" for p in outputs):
        meshes = ", ".join(ext for ext, fmt in EXTENSIONS.items() if fmt.kind == "mesh")
        raise ParameterError(f"{' and '.join(MESH_OPTIONS)} apply to mesh outputs ({meshes}); none is asked for")


def mesh_tolerance_for(
    spec: AnySpec, linear: float | None = None, angle_deg: float | None = None
) -> tuple[float, float]:
    """The spec's mesh tolerances, checked against its smallest tube radius.

    Args:
        spec: the checked spec.
        linear: the linear deflection asked for (model units), or None for the default.
        angle_deg: the angular deflection asked for (degrees), or None for the default.

    Returns:
        (linear deflection, angular deflection in radians), as tubecad.export.meshing sets them.

    Raises:
        SpecError: naming the option and its range.
    """
    from tubecad.export.meshing import checked_tolerance

    radius = spec.min_radius  # a tube's constant radius, or a canal surface's smallest r
    if spec.wall is not None:
        try:
            radius += spec.wall.offsets()[0]
        except ParameterError:
            pass  # the build says what is wrong with [wall]
    try:
        return checked_tolerance(linear, angle_deg, radius, MESH_OPTIONS)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key) from None


def check_build_outputs(
    spec: AnySpec,
    outputs: Iterable[str | Path],
    report_path: Path | None = None,
    mesh_tolerance: float | None = None,
    mesh_angle: float | None = None,
) -> tuple[float, float]:
    """Everything ``tubecad build`` can refuse about its outputs before building.

    Every extension is known, the spec's kind can be written in it (a junction as CAD files
    and pictures only), each output's folder exists and takes a file, and the mesh
    tolerances are in range.

    Args:
        spec: the checked spec.
        outputs: the -o paths.
        report_path: the --report path, or None.
        mesh_tolerance: --mesh-tolerance, or None.
        mesh_angle: --mesh-angle, or None.

    Returns:
        The mesh outputs' (linear, angular) deflections, as :func:`mesh_tolerance_for`.

    Raises:
        ParameterError: an unknown extension, a mesh option without a mesh output, an
            unwritable output.
        SpecError: an output the spec's kind is not written as; mesh tolerances out of range.
    """
    from tubecad.core.atomic import check_writable
    from tubecad.export.registry import output_format
    from tubecad.spec.design import design_class

    paths = [Path(p) for p in outputs]
    split_outputs(paths)
    check_mesh_options(paths, mesh_tolerance, mesh_angle)
    kind = design_class(spec)
    for path in paths:
        fmt = output_format(path)
        if not {fmt.kind, fmt.name} & kind.WRITTEN_AS:
            raise SpecError(
                f"{spec.source}: output {path.name!r}: {kind.WHAT} is written as "
                f"{', '.join(sorted(kind.WRITTEN_AS))} files, not {fmt.name.upper()} (not made yet)",
                key="output",
            )
    for path in (*paths, *([report_path] if report_path is not None else [])):
        check_writable(path)
    return mesh_tolerance_for(spec, mesh_tolerance, mesh_angle)


def check_analysis(spec: AnySpec) -> str:
    """Everything ``tubecad analyse`` needs besides the spec's keys: [analysis], [wall] and
    CalculiX.

    Args:
        spec: the checked spec.

    Returns:
        The path of the ``ccx`` executable.

    Raises:
        SpecError: no [analysis] or [wall] section, or ``ccx`` not installed.
    """
    from tubecad.fem.calculix import CalculixError, ccx_executable

    if spec.analysis is None:
        raise SpecError(
            f"{spec.source}: has no [analysis] section (pressure, ends, youngs_modulus, poisson_ratio)", key="analysis"
        )
    if spec.wall is None:
        raise SpecError(f"{spec.source}: an analysis needs the wall's thickness: add a [wall] section", key="wall")
    try:
        return ccx_executable()
    except CalculixError as exc:
        raise SpecError(str(exc)) from None


def check_output_folder(folder: str | Path) -> Path:
    """An output folder that exists or can be made: not a file, under folders that are
    folders, its nearest existing one writable. Nothing is created.

    Args:
        folder: the -o folder of ``tubecad shop``, ``flat`` or ``analyse``.

    Returns:
        ``folder`` as a Path.

    Raises:
        ParameterError: (key ``output``) naming the folder and why it cannot be made.
    """
    import os

    folder = Path(folder)
    existing = folder
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        part = "" if existing == folder else f": {str(existing)!r} is a file"
        raise ParameterError(f"output folder {str(folder)!r} cannot be made{part}", key="output")
    if not os.access(existing if str(existing) else ".", os.W_OK | os.X_OK):
        raise ParameterError(
            f"output folder {str(folder)!r} cannot be made: {str(existing)!r} is not writable", key="output"
        )
    return folder


def check_shop(spec: AnySpec, output: str | Path) -> None:
    """Everything ``tubecad shop`` can refuse before building: a [wall], something for the
    shop ([stiffeners] or [panels], or [[branches]]), the [fabrication] settings, the folder.

    Args:
        spec: the checked spec.
        output: the -o folder.

    Raises:
        SpecError: a missing section or a bad [fabrication] value, naming it.
        ParameterError: an output folder that cannot be made.
    """
    from tubecad.spec.design import design_class
    from tubecad.spec.model import FabricationSection

    if spec.wall is None and spec.host is None:  # a face's webs stand on the face itself
        raise SpecError(
            f"{spec.source}: has no [wall] section; the shop package is made of a wall's stiffeners and panels",
            key="wall",
        )
    if design_class(spec).SHOP_NEEDS_PARTS and spec.stiffeners is None and spec.panels is None:
        raise SpecError(
            f"{spec.source}: has neither [stiffeners] nor [panels]; there is nothing for the shop", key="stiffeners"
        )
    try:
        (spec.fabrication or FabricationSection()).settings(spec.length_unit)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key or "fabrication") from None
    check_output_folder(output)


def check_flat(spec: AnySpec, output: str | Path) -> None:
    """Everything ``tubecad flat`` can refuse before building: [stiffeners] and the folder.

    Args:
        spec: the checked spec.
        output: the -o folder.

    Raises:
        SpecError: no [stiffeners] section.
        ParameterError: an output folder that cannot be made.
    """
    if spec.stiffeners is None:
        raise SpecError(
            f"{spec.source}: has no [stiffeners] section, so there are no webs to flatten", key="stiffeners"
        )
    check_output_folder(output)
