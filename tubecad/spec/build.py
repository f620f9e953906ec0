"""From a checked spec to B-rep: layout, wall and fit sections (docs/spec-files.md),
and :func:`build_and_export`, the body of ``tubecad build`` for one spec."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

from tubecad.brep import TubeBuild
from tubecad.core.errors import SpecError
from tubecad.core.progress import Progress, ProgressCallback
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.design.result import BuildResult, write_outputs
from tubecad.design.wall import WallResult
from tubecad.spec.design import design_of, spec_errors, wall_design
from tubecad.spec.model import StiffenerSelection
from tubecad.spec.parse import AnySpec, TubeSpec
from tubecad.spec.preflight import (  # light: the outputs' checks, made again here for a script's call
    MESH_OPTIONS,
    check_build_outputs,
    check_mesh_options,
    mesh_tolerance_for,
    split_outputs,
)

__all__ = [
    "MESH_OPTIONS",
    "SpecBuild",
    "StiffenerSelection",
    "build_and_export",
    "build_from_spec",
    "build_spec",
    "check_mesh_options",
    "check_output",
    "export_build",
    "mesh_deflection",
    "mesh_tolerance_for",
    "panels_from_spec",
    "split_outputs",
    "stiffener_selection",
    "stiffeners_from_spec",
    "wall_lines",
]


def build_from_spec(spec: TubeSpec, progress: ProgressCallback | None = None) -> TubeBuild:
    """The wall solid if the spec has [wall], else the capped tube solid (no stiffeners, no
    panels); ``progress(step, done, total)`` is called as it is built. A spec with
    [[branches]] is refused: this makes the main tube alone (:func:`build_spec` builds the
    junction)."""
    from tubecad.design.wall import build_solid

    refuse_branches(spec)
    design = wall_design(spec)
    with spec_errors(spec):
        return build_solid(design, progress)


def refuse_branches(spec: TubeSpec) -> None:
    """Refuse a spec with [[branches]] where only the main tube would be made (flat, the
    viewer): nothing of a spec is dropped without a word."""
    if spec.branches:
        raise SpecError(
            f"{spec.source}: [[branches]]: this command does not make junctions yet (tubecad build writes them as CAD files, "
            "meshes and a PNG, tubecad mesh and analyse as shell models); remove [[branches]] for the main "
            "tube alone",
            key="branches",
        )


def stiffener_selection(spec: TubeSpec, build: TubeBuild) -> StiffenerSelection | None:
    """The checked [stiffeners] section on ``build``'s layout (the one check of the section,
    :meth:`~tubecad.spec.model.StiffenersSection.select`, that the mesh makes too), each
    ring once (a closed tube's closing ring is its first), or None if the spec has none."""
    if spec.stiffeners is None:
        return None
    from tubecad.stiffeners.assembly import distinct_rings

    selection = spec.stiffeners.select(build.layout, spec.source, spec.length_unit)
    return replace(selection, rings=distinct_rings(build, selection.rings))


def stiffeners_from_spec(
    spec: TubeSpec, build: TubeBuild, progress: ProgressCallback | None = None
) -> tuple[list, StiffenerSelection | None]:
    """The [stiffeners] section's stiffener solids on ``build``'s wall ([] without the section);
    ``progress(name, done, total)`` after each."""
    from tubecad.design.wall import build_wall_stiffeners

    selection = stiffener_selection(spec, build)
    if selection is None:
        return [], None
    with spec_errors(spec):
        return build_wall_stiffeners(wall_design(spec), build, progress), selection


def panels_from_spec(spec: TubeSpec, build: TubeBuild) -> list:
    """The [panels] section's panels of the wall ([] without the section)."""
    from tubecad.design.wall import build_panels

    with spec_errors(spec):
        return build_panels(wall_design(spec), build)


def wall_lines(build: TubeBuild) -> list:
    """The layout's curvature lines on every wall surface (``..._inner`` on the inner one)."""
    from tubecad.stiffeners import net_lines

    lines = net_lines(build.surfaces[0], build.layout)
    if len(build.surfaces) > 1:
        lines += net_lines(build.surfaces[1], build.layout, "_inner")
    return lines


def mesh_deflection(build: TubeBuild) -> float:
    """The default linear deflection of mesh outputs: 1e-3 of the smallest tube radius."""
    from tubecad.export.meshing import checked_tolerance

    return checked_tolerance(None, None, min(build.radii))[0]


def check_output(
    tmp: Path,
    fmt,
    target: Path,
    shape,
    build: TubeBuild,
    wall_solids: int | None,
    deflection: float,
    length_unit: str = DEFAULT_LENGTH_UNIT,
    angular: float | None = None,
) -> dict[str, Any]:
    """Read a just-written temporary file back and measure it (tubecad.export.readback);
    raises if it does not hold the build's tolerance, so the file is never moved into place.
    ``shape``: the shape written (or its :class:`~tubecad.export.readback.WrittenShape`);
    ``wall_solids``: for an assembly, how many of its first solids are the wall;
    ``length_unit``: the model's unit, which the file is read back into. (A build result
    checks its own files: :meth:`tubecad.design.result.BuildResult.check_file`.)"""
    from tubecad.export.readback import mesh_report, picture_report, readback_report

    if fmt.kind == "cad":
        return readback_report(tmp, shape, build, target, wall_solids, length_unit)
    if fmt.kind == "mesh":
        return mesh_report(tmp, fmt.name, build, deflection, target, wall_solids, length_unit, angular)
    if fmt.kind == "picture":
        return picture_report(tmp, fmt.name, build)
    return {"bytes": tmp.stat().st_size, "lines": len(wall_lines(build))}


#: what :func:`build_spec` returns for a spec without [[branches]] (the name of earlier versions)
SpecBuild = WallResult


def build_spec(spec: AnySpec, progress: Progress | None = None, grid: tuple[int, int] = (64, 501)) -> BuildResult:
    """Build what ``spec`` describes, whatever it is (its design: :func:`tubecad.spec.design.design_of`):
    the wall with [wall], else the capped tube, its [stiffeners] and [panels] (then the
    named assembly), or with [[branches]] the junction; and measure it: the report of
    ``tubecad build``, the exact surface's checks on a ``grid`` = (nu, ns) grid. Nothing is
    written.

    Args:
        spec: the checked spec, as :func:`~tubecad.spec.parse.load_spec` returns it.
        progress: a :class:`~tubecad.core.progress.Progress` that shows the build's stages
            as they advance, or None (default) for none.
        grid: (nu, ns), the numbers of points around and along the surface where the report
            measures the exact surface (default (64, 501)).

    Returns:
        the :class:`~tubecad.design.result.BuildResult` (shape, solids, named edges, report).

    Raises:
        SpecError: naming the section and the key of what cannot be built.
    """
    design = design_of(spec, grid)
    with spec_errors(spec):
        return design.build(progress)


def build_wall_spec(spec: TubeSpec, progress: Progress | None = None, grid: tuple[int, int] = (64, 501)) -> WallResult:
    """:func:`build_spec` of a spec without [[branches]] (refused naming them), typed as what
    it is: the :class:`~tubecad.design.wall.WallResult` (its B-rep build, stiffeners and panels)."""
    from tubecad.design.wall import build_wall

    refuse_branches(spec)
    design = wall_design(spec, grid)
    with spec_errors(spec):
        return build_wall(design, progress)


def export_build(
    built: BuildResult,
    outputs,
    step_schema: str = "AP214",
    written: list[Path] | None = None,
    deflection: float | None = None,
    angular: float | None = None,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Write ``built``'s shape to each of ``outputs`` (the format by extension), each read
    back and measured before it is moved into place; returns what was measured per file
    (also ``built.report["exports"]``, by path). ``deflection``, ``angular``: the mesh
    outputs' tolerances (default :func:`tubecad.design.result.mesh_tolerances`'s)."""
    return write_outputs(built, outputs, step_schema, deflection, angular, written, progress)


def build_and_export(
    spec: AnySpec,
    outputs,
    step_schema: str = "AP214",
    report_path: Path | None = None,
    written: list[Path] | None = None,
    mesh_tolerance: float | None = None,
    mesh_angle: float | None = None,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Build ``spec`` (:func:`build_spec`: a tube, a wall, a stiffened or paneled wall, a
    junction), write each of ``outputs``, read each back, and return the report (also written
    to ``report_path`` if given).

    ``tubecad build`` runs this for its one spec and for every job of a batch. Every file is
    written atomically and read back before it is moved into place: a file that does not
    hold the tolerance (see tubecad.export.readback) is refused and never left behind.
    Each path is appended to ``written`` once it is complete. Mesh outputs are meshed to
    ``mesh_tolerance`` (model units) and ``mesh_angle`` (degrees), checked before anything is
    built (:func:`mesh_tolerance_for`). ``progress`` hears of each stage (the wall, each
    stiffener, each file written and read back); it shows nothing by default.
    (:func:`build_spec` and :func:`export_build` are its two halves.)
    """
    from tubecad.core.atomic import write_text
    from tubecad.spec.report import to_json

    written = [] if written is None else written
    progress = progress if progress is not None else Progress(enabled=False)
    outputs = [Path(p) for p in outputs]
    # a bad output is refused, naming it, before anything is built or written
    deflection, angular = check_build_outputs(spec, outputs, report_path, mesh_tolerance, mesh_angle)
    built = build_spec(spec, progress)
    with spec_errors(spec):  # a file that does not hold the build names [fit] tolerance or [units] length
        export_build(built, outputs, step_schema, written, deflection, angular, progress)
    if report_path is not None:
        written.append(write_text(report_path, to_json(built.report)))
    return built.report
