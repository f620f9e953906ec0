"""From a checked spec to B-rep: layout, wall and fit sections (docs/spec-files.md),
and :func:`build_and_export`, the body of ``tubecad build`` for one spec."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import Any

from tubecad.brep import TubeBuild, build_tube_solid, build_wall_solid
from tubecad.core.errors import ParameterError, RegularityError, SpecError, TubecadError
from tubecad.core.progress import Progress, ProgressCallback
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.fitting import FitError
from tubecad.spec.model import StiffenerSelection
from tubecad.spec.parse import TubeSpec
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
    """The wall solid if the spec has [wall], else the capped tube solid; ``progress(step,
    done, total)`` is called as it is built."""
    from tubecad.core.tolerance import check_tolerance

    refuse_branches(spec)
    tube = spec.tube
    try:
        layout = spec.layout.net(tube)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [layout] {exc}", key=_within("layout", exc)) from None
    try:  # parse_spec checked it; a model made by a script is checked here, so the build's own errors are [wall]'s
        tolerance = check_tolerance("tolerance", spec.fit.tolerance)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}", key="fit.tolerance") from None
    wall = spec.wall
    try:
        if wall is None:
            return build_tube_solid(tube, layout, tolerance, progress)
        return build_wall_solid(tube, wall.thickness, wall.side, layout, tolerance, progress)
    except FitError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}", key="fit.tolerance") from None
    except RegularityError as exc:
        raise SpecError(
            f"{spec.source}: [wall] the wall's outer surface is not regular: {exc}", key="wall.thickness"
        ) from None
    except ParameterError as exc:
        section = "fit" if exc.key in FIT_KEYS else "wall"
        raise SpecError(f"{spec.source}: [{section}] {exc}", key=_within(section, exc)) from None


def refuse_branches(spec: TubeSpec) -> None:
    """Refuse a spec with [[branches]] where only the main tube would be made (flat, the
    viewer): nothing of a spec is dropped without a word."""
    if spec.branches:
        raise SpecError(
            f"{spec.source}: [[branches]]: this command does not make junctions yet (tubecad build writes them "
            "as STEP, IGES or BREP, tubecad mesh and analyse as shell models); remove [[branches]] for the main "
            "tube alone",
            key="branches",
        )


#: the keys of a ParameterError about the fit's tolerances (a [fit] error, not [wall]'s)
FIT_KEYS = ("tolerance", "orthogonality", "fit.tolerance")


def _within(section: str, exc: TubecadError) -> str:
    """The spec key of an error about ``section``: ``section.key``, or the section."""
    key = exc.key
    if key is None:
        return section
    return key if key == section or key.startswith(f"{section}.") else f"{section}.{key}"


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
    from tubecad.stiffeners.assembly import build_stiffeners

    selection = stiffener_selection(spec, build)
    if selection is None:
        return [], None
    try:
        return build_stiffeners(
            build, selection.rings, selection.stringers, selection.profile, selection.side, build.tolerance, progress
        ), selection
    except (ParameterError, RegularityError, FitError) as exc:
        raise SpecError(f"{spec.source}: [stiffeners] {exc}", key=_within("stiffeners", exc)) from None


def panels_from_spec(spec: TubeSpec, build: TubeBuild) -> list:
    """The [panels] section's panels of the wall ([] without the section)."""
    from tubecad.stiffeners.panels import split_into_panels

    section = spec.panels
    if section is None:
        return []
    n_s, n_r = len(build.layout.stringers_deg), len(build.layout.s_rings)
    try:
        return split_into_panels(build, section.seam_indices(n_s), section.ring_indices())
    except ParameterError as exc:
        raise SpecError(
            f"{spec.source}: [panels] {exc} (the layout has {n_s} stringers and {n_r} rings)",
            key=_within("panels", exc),
        ) from None


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
    ``length_unit``: the model's unit, which the file is read back into."""
    from tubecad.export.readback import mesh_report, readback_report

    if fmt.kind == "cad":
        return readback_report(tmp, shape, build, target, wall_solids, length_unit)
    if fmt.kind == "mesh":
        return mesh_report(tmp, fmt.name, build, deflection, target, wall_solids, length_unit, angular)
    if fmt.kind == "picture":
        from tubecad.export.readback import picture_report

        return picture_report(tmp, fmt.name, build)
    return {"bytes": tmp.stat().st_size, "lines": len(wall_lines(build))}


@dataclass
class SpecBuild:
    """A spec built: the wall (or tube) ``build``, its stiffeners and panels, the ``shape``
    its files are written from (the named assembly with [stiffeners] or [panels], else the
    solid) and the ``report`` so far (the tube's measures, the B-rep's, the stiffeners')."""

    spec: TubeSpec
    build: TubeBuild
    stiffeners: list = field(default_factory=list)
    selection: StiffenerSelection | None = None
    panels: list = field(default_factory=list)
    shape: Any = None
    report: dict[str, Any] = field(default_factory=dict)

    @property
    def named(self) -> bool:
        """Whether ``shape`` is the named assembly (wall or panels, stiffeners, lines)."""
        return bool(self.stiffeners or self.panels)

    @property
    def wall_solids(self) -> int | None:
        """For the assembly, how many of its first solids are the wall (or its panels)."""
        return (len(self.panels) or 1) if self.named else None


def build_spec(spec: TubeSpec, progress: Progress | None = None, grid: tuple[int, int] = (64, 501)) -> SpecBuild:
    """Build ``spec``'s solid (the wall with [wall], else the capped tube), its [stiffeners]
    and [panels] (then the named assembly), and measure them: the report of ``tubecad
    build``, the tube's checks on a ``grid`` = (nu, ns) grid. Nothing is written."""
    from tubecad.brep.properties import volume
    from tubecad.core.units import steel_density
    from tubecad.spec.report import build_report, stiffener_report, tube_report
    from tubecad.stiffeners import net_lines
    from tubecad.stiffeners.assembly import named_assembly

    progress = progress if progress is not None else Progress(enabled=False)
    unit = spec.length_unit  # [units] length: the model's unit, stated in every file and the report
    kind = "wall" if spec.wall is not None else "tube"
    progress.step(f"building the {kind}", 4 if kind == "wall" else 3)
    result = build_from_spec(spec, progress.update)
    report = tube_report(spec.tube, *grid, length_unit=unit)
    report["brep"] = build_report(result, spec.tube)
    if spec.stiffeners is not None:
        progress.step("building stiffeners")
    stiffeners, selection = stiffeners_from_spec(spec, result, progress.update)
    if spec.panels is not None:
        progress.step("splitting the wall into panels")
    panels = panels_from_spec(spec, result)
    built = SpecBuild(spec, result, stiffeners, selection, panels, result.shape, report)
    if built.named:
        fuse = bool(selection and selection.fuse)
        progress.step("assembling" + (" (fusing the stiffeners into the wall)" if fuse else ""))
        lines = net_lines(result.surfaces[0], result.layout)
        built.shape = named_assembly(result, stiffeners, lines, fuse=fuse, panels=panels)
        density = selection.density if selection else steel_density(unit)
        report["stiffeners"] = stiffener_report(stiffeners, lines, density, unit)
        report["panels"] = [
            {
                "name": p.name,
                "s": list(p.s_range),
                "angles_deg": list(p.angles_deg),
                "outer_area": p.outer_area,
                "volume": volume(p.solid),
                "mass_kg": p.mass(density),
            }
            for p in panels
        ]
    return built


def export_build(
    built: SpecBuild,
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
    outputs' tolerances (default :func:`mesh_tolerance_for`'s)."""
    from tubecad.export.readback import WrittenShape
    from tubecad.export.registry import Exportable, OutputFormat, write_output

    written = [] if written is None else written
    progress = progress if progress is not None else Progress(enabled=False)
    spec, result, shape = built.spec, built.build, built.shape
    unit = spec.length_unit
    if deflection is None or angular is None:
        default = mesh_tolerance_for(spec)
        deflection, angular = deflection or default[0], angular or default[1]
    exports = built.report["exports"] = {}
    item = Exportable(
        shape,
        lambda: wall_lines(result),
        step_schema,
        mesh_deflection=deflection,
        length_unit=unit,
        mesh_angular=angular,
        build=result,
    )

    reference = WrittenShape(shape)  # its area and volume integrated once for all the files
    if shape is result.shape and "volume" in built.report.get("brep", {}):
        reference = WrittenShape(shape, {"volume": built.report["brep"]["volume"]})  # build_report's, of this shape

    def check(tmp: Path, fmt: OutputFormat, path: Path) -> dict[str, Any]:
        progress.advance(1, f"wrote {path.name}")
        return check_output(tmp, fmt, path, reference, result, built.wall_solids, deflection, unit, angular)

    progress.step("writing and reading back files", 2 * len(outputs))
    for path in map(Path, outputs):  # STEP of an assembly keeps its names: wall, ring_03, line_ring_03, ...
        done, info = write_output(item, path, partial(check, path=path))
        written.append(done)
        exports[str(path)] = info
        progress.advance(1, f"checked {path.name}")
    return exports


def build_and_export(
    spec: TubeSpec,
    outputs,
    step_schema: str = "AP214",
    report_path: Path | None = None,
    written: list[Path] | None = None,
    mesh_tolerance: float | None = None,
    mesh_angle: float | None = None,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Build ``spec``'s solid (the wall with [wall], else the capped tube; the named assembly
    with [stiffeners] or [panels]), write each of ``outputs``, read each back, and return the
    report (also written to ``report_path`` if given).

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
    if spec.branches:  # a junction: its own build, assembly and read-back
        from tubecad.spec.junction import build_and_export_junction

        return build_and_export_junction(spec, outputs, step_schema, report_path, written, progress)
    built = build_spec(spec, progress)
    export_build(built, outputs, step_schema, written, deflection, angular, progress)
    if report_path is not None:
        written.append(write_text(report_path, to_json(built.report)))
    return built.report
