"""From a checked spec to B-rep: layout, wall and fit sections (README, "Spec files"),
and :func:`build_and_export`, the body of ``tubecad build`` for one spec."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tubecad.brep import TubeBuild, build_tube_solid, build_wall_solid
from tubecad.core.errors import ParameterError, RegularityError, SpecError
from tubecad.core.progress import Progress, ProgressCallback
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.fitting import FitError
from tubecad.spec.layout import layout_from_section
from tubecad.spec.parse import TubeSpec
from tubecad.stiffeners.profiles import Profile
from tubecad.surface import CanalSurface, CurvatureLineTube


def build_from_spec(spec: TubeSpec, progress: ProgressCallback | None = None) -> TubeBuild:
    """The wall solid if the spec has [wall], else the capped tube solid; ``progress(step,
    done, total)`` is called as it is built."""
    tube = spec.tube
    try:
        layout = layout_from_section(tube, spec.sections.get("layout", {}))
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [layout] {exc}") from None
    tolerance = spec.sections.get("fit", {}).get("tolerance", DEFAULT_TOLERANCE)
    wall = spec.sections.get("wall")
    try:
        if wall is None:
            return build_tube_solid(tube, layout, tolerance, progress)
        return build_wall_solid(tube, wall["thickness"], wall.get("side", "centered"), layout, tolerance, progress)
    except FitError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}") from None
    except RegularityError as exc:
        raise SpecError(f"{spec.source}: [wall] the wall's outer surface is not regular: {exc}") from None
    except ParameterError as exc:
        section = "[fit]" if "tolerance" in str(exc) else "[wall]"
        raise SpecError(f"{spec.source}: {section} {exc}") from None


@dataclass(frozen=True)
class StiffenerSelection:
    """What a [stiffeners] section asks for, checked against the built layout."""

    rings: list[int]
    stringers: list[int]
    profile: Profile
    side: str
    fuse: bool
    density: float

    def base(self, build: TubeBuild) -> CurvatureLineTube | CanalSurface:
        """The wall surface the stiffeners stand on: outer (outside) or inner (inside)."""
        from tubecad.stiffeners.assembly import stiffener_base

        return stiffener_base(build, self.side)


def stiffener_selection(spec: TubeSpec, build: TubeBuild) -> StiffenerSelection | None:
    """The checked [stiffeners] section, or None if the spec has none."""
    from tubecad.core.units import steel_density
    from tubecad.stiffeners.profiles import SIDES

    section = spec.sections.get("stiffeners")
    if section is None:
        return None

    def chosen(key: str, count: int) -> list[int]:
        value = section.get(key, [])
        indices = list(range(count)) if value == "all" else value
        bad = [i for i in indices if not 0 <= i < count]
        if bad:
            raise SpecError(f"{spec.source}: [stiffeners] {key} must be indices in [0, {count - 1}], got {bad}")
        return indices

    try:
        profile = Profile(
            section.get("profile", "flat"),
            section["height"],
            section["thickness"],
            section.get("flange_width", 0.0),
            section.get("flange_thickness", 0.0),
        )
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [stiffeners] {exc}") from None
    side = section.get("side", "outside")
    if side not in SIDES:
        raise SpecError(f"{spec.source}: [stiffeners] side must be one of {', '.join(SIDES)}, got {side!r}")
    density = section.get("density", steel_density(spec.length_unit))  # kg per cubic [units] length
    if not density > 0:
        raise SpecError(f"{spec.source}: [stiffeners] density must be > 0, got {density}")
    from tubecad.stiffeners.assembly import distinct_rings

    rings = distinct_rings(build, chosen("rings", len(build.layout.s_rings)))
    return StiffenerSelection(
        rings, chosen("stringers", len(build.layout.stringers_deg)), profile, side, section.get("fuse", False), density
    )


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
        raise SpecError(f"{spec.source}: [stiffeners] {exc}") from None


def panels_from_spec(spec: TubeSpec, build: TubeBuild) -> list:
    """The [panels] section's panels of the wall ([] without the section)."""
    from tubecad.stiffeners.panels import split_into_panels

    section = spec.sections.get("panels")
    if section is None:
        return []
    n_s, n_r = len(build.layout.stringers_deg), len(build.layout.s_rings)
    seams = list(range(n_s)) if section["seams"] == "all" else section["seams"]
    rings = section.get("rings", "all")
    try:
        return split_into_panels(build, seams, None if rings == "all" else rings)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [panels] {exc} (the layout has {n_s} stringers and {n_r} rings)") from None


def split_outputs(outputs) -> tuple[list[Path], list[Path]]:
    """Shape outputs (CAD and mesh formats) and polyline outputs (.csv, .json), by the one
    table of formats (tubecad.export.registry); a ParameterError listing every allowed
    extension for any other, before anything is built."""
    from tubecad.export.registry import output_format

    paths = [Path(p) for p in outputs]
    kinds = {p: output_format(p).kind for p in paths}
    return [p for p in paths if kinds[p] != "polylines"], [p for p in paths if kinds[p] == "polylines"]


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


#: how the command line names the mesh tolerances (in messages)
MESH_OPTIONS = ("--mesh-tolerance", "--mesh-angle")


def mesh_tolerance_for(
    spec: TubeSpec, linear: float | None = None, angle_deg: float | None = None
) -> tuple[float, float]:
    """(linear deflection, angular deflection in radians) of the spec's mesh outputs, checked
    before anything is built (tubecad.export.meshing: the defaults, and the ranges relative
    to the spec's smallest tube radius); a SpecError names the option and the range."""
    from tubecad.brep.wall import wall_offsets
    from tubecad.export.meshing import checked_tolerance

    tube, wall = spec.tube, spec.sections.get("wall")
    radius = tube.radius if isinstance(tube, CurvatureLineTube) else tube.radius_law.min_radius  # a canal surface's law
    if wall is not None:
        try:
            radius += wall_offsets(wall["thickness"], wall.get("side", "centered"))[0]
        except (ParameterError, KeyError):
            pass  # the build says what is wrong with [wall]
    try:
        return checked_tolerance(linear, angle_deg, radius, MESH_OPTIONS)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}") from None


def check_mesh_options(outputs, mesh_tolerance: float | None, mesh_angle: float | None) -> None:
    """--mesh-tolerance and --mesh-angle only with a mesh output among ``outputs`` (paths or
    names with an extension): a ParameterError otherwise."""
    from tubecad.export.registry import EXTENSIONS

    if mesh_tolerance is None and mesh_angle is None or any(Path(p).suffix.lower() not in EXTENSIONS for p in outputs):
        return  # an unknown extension is refused by split_outputs, listing them all
    if not any(getattr(EXTENSIONS.get(Path(p).suffix.lower()), "kind", "") == "mesh" for p in outputs):
        meshes = ", ".join(ext for ext, fmt in EXTENSIONS.items() if fmt.kind == "mesh")
        raise ParameterError(f"{' and '.join(MESH_OPTIONS)} apply to mesh outputs ({meshes}); none is asked for")


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
    ``wall_solids``: for an assembly, how many of its first solids are the wall;
    ``length_unit``: the model's unit, which the file is read back into."""
    from tubecad.export.readback import mesh_report, readback_report

    if fmt.kind == "cad":
        return readback_report(tmp, shape, build, target, wall_solids, length_unit)
    if fmt.kind == "mesh":
        return mesh_report(tmp, fmt.name, build, deflection, target, wall_solids, length_unit, angular)
    return {"bytes": tmp.stat().st_size, "lines": len(wall_lines(build))}


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
    """
    from tubecad.brep.properties import volume
    from tubecad.core.atomic import check_writable, write_text
    from tubecad.core.units import steel_density
    from tubecad.export.registry import Exportable, write_output
    from tubecad.spec.report import build_report, stiffener_report, to_json, tube_report
    from tubecad.stiffeners import net_lines
    from tubecad.stiffeners.assembly import named_assembly

    written = [] if written is None else written
    progress = progress if progress is not None else Progress(enabled=False)
    unit = spec.length_unit  # [units] length: the model's unit, stated in every file and the report
    outputs = [Path(p) for p in outputs]
    split_outputs(outputs)  # an unknown extension is refused, listing them all, before anything is built
    for path in (*outputs, *([report_path] if report_path is not None else [])):
        check_writable(path)  # a bad output is refused before anything is built or written
    deflection, angular = mesh_tolerance_for(spec, mesh_tolerance, mesh_angle)
    kind = "wall" if "wall" in spec.sections else "tube"
    progress.step(f"building the {kind}", 4 if kind == "wall" else 3)
    result = build_from_spec(spec, progress.update)
    report = tube_report(spec.tube, 64, 501, length_unit=unit)
    report["brep"] = build_report(result, spec.tube)
    if "stiffeners" in spec.sections:
        progress.step("building stiffeners")
    stiffeners, selection = stiffeners_from_spec(spec, result, progress.update)
    if "panels" in spec.sections:
        progress.step("splitting the wall into panels")
    panels = panels_from_spec(spec, result)
    shape = result.shape
    named = bool(stiffeners or panels)
    if named:
        progress.step("assembling" + (" (fusing the stiffeners into the wall)" if selection and selection.fuse else ""))
        lines = net_lines(result.surfaces[0], result.layout)
        shape = named_assembly(result, stiffeners, lines, fuse=bool(selection and selection.fuse), panels=panels)
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
    report["exports"] = {}
    wall_solids = (len(panels) or 1) if named else None  # the assembly's first solids: the wall, or its panels
    item = Exportable(
        shape,
        lambda: wall_lines(result),
        step_schema,
        mesh_deflection=deflection,
        length_unit=unit,
        mesh_angular=angular,
        build=result,
    )

    def check(tmp, fmt, path):
        progress.advance(1, f"wrote {path.name}")
        return check_output(tmp, fmt, path, shape, result, wall_solids, deflection, unit, angular)

    progress.step("writing and reading back files", 2 * len(outputs))
    for path in outputs:  # STEP of an assembly keeps its names: wall, ring_03, line_ring_03, ...
        done, info = write_output(item, path, lambda tmp, fmt, path=path: check(tmp, fmt, path))
        written.append(done)
        report["exports"][str(path)] = info
        progress.advance(1, f"checked {path.name}")
    if report_path is not None:
        written.append(write_text(report_path, to_json(report)))
    return report
