"""What a spec's build writes besides its solids, as library code a script calls: the flat
patterns of its stiffener webs (``tubecad flat``, a tube's or a face's net's), the report of
a face's net (``tubecad report`` on a [host] spec), a picture of a STEP file as read back,
and the one-line summary of a written file that ``tubecad build`` prints."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.spec.parse import AnySpec, TubeSpec

if TYPE_CHECKING:
    from tubecad.spec.host import HostSpec


def output_folder(folder: str | Path) -> Path:
    """``folder``, created if needed; a ParameterError (key ``output``) if it cannot be."""
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError(f"cannot create output folder {str(folder)!r}: {exc.strerror}", key="output") from None
    return folder


def flat_from_spec(spec: AnySpec, output: str | Path) -> list[Path]:
    """``tubecad flat``: the flat patterns of the webs of ``spec``'s [stiffeners] into
    ``output``: webs.dxf, NAME.svg/.png per web and flat.json (lengths in the spec's [units]
    length). A tube's webs are built on its wall, a face's net's on its lines (each web plate
    up to its flange, as the shop cuts it). Returns the files written."""
    from tubecad.spec.preflight import check_flat

    check_flat(spec, output)
    return spec.dispatch(lambda tube: _tube_flat(tube, output), lambda host: _net_flat(host, output))


def _tube_flat(spec: TubeSpec, output: str | Path) -> list[Path]:
    from tubecad.spec.build import build_from_spec, stiffener_selection
    from tubecad.stiffeners.flat import ring_web_flat_pattern, stringer_flat_pattern

    result = build_from_spec(spec)
    chosen = stiffener_selection(spec, result)
    assert chosen is not None  # the spec has [stiffeners]
    base, height, side = chosen.base(result), chosen.profile.web_height, chosen.side
    layout = result.layout
    folder = output_folder(output)
    patterns = [ring_web_flat_pattern(base, layout.s_rings[i], height, side, f"ring_{i:02d}") for i in chosen.rings]
    patterns += [
        stringer_flat_pattern(base, layout.stringers_deg[j], height, side, f"stringer_{j:02d}")
        for j in chosen.stringers
    ]
    return write_patterns(patterns, folder, spec.length_unit)


def _net_flat(spec: HostSpec, output: str | Path) -> list[Path]:
    from tubecad.spec.design import net_design, spec_errors

    design = net_design(spec)
    with spec_errors(spec):
        webs = design.built_webs()
    return write_patterns([web.pattern for web in webs], output_folder(output), spec.length_unit)


def net_report_from_spec(spec: HostSpec) -> dict[str, Any]:
    """``tubecad report`` on a [host] spec: the net built (its [wall] and [stiffeners] with
    it) and its report, as ``tubecad build --report`` writes it (without the files' part).

    Args:
        spec: the checked [host] spec.

    Returns:
        The report (plain JSON values).

    Raises:
        SpecError: a build error, naming the section and key.
    """
    from tubecad.spec.design import net_design, spec_errors

    design = net_design(spec)
    with spec_errors(spec):
        return design.build_net().report


def write_flat_patterns(stiffeners, folder: Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> list[Path]:
    """The flat patterns of built ``stiffeners`` (each on its own base surface) into
    ``folder`` (created): webs.dxf, NAME.svg/.png per web and flat.json (issue 4)."""
    from tubecad.stiffeners.flat import ring_web_flat_pattern, stringer_flat_pattern

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    patterns = [
        ring_web_flat_pattern(st.base, st.value, st.profile.web_height, st.side, st.name)
        if st.kind == "ring"
        else stringer_flat_pattern(st.base, st.value, st.profile.web_height, st.side, st.name)
        for st in stiffeners
    ]
    return write_patterns(patterns, folder, length_unit)


def write_patterns(patterns, folder: Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> list[Path]:
    """webs.dxf (all), NAME.svg and NAME.png per web, flat.json with the measures; lengths
    in ``length_unit`` (the spec's [units] length, stated in the DXF and flat.json)."""
    from shapely.geometry import Polygon

    from tubecad.core.atomic import write_text
    from tubecad.spec.report import to_json
    from tubecad.stiffeners.flat import write_dxf, write_picture

    folder = Path(folder)
    written = [write_dxf(patterns, folder / "webs.dxf", length_unit=length_unit)]
    for pattern in patterns:
        written += write_picture(pattern, folder)
    webs: list[dict[str, Any]] = [
        {
            "name": p.name,
            "kind": p.kind,
            "area": p.area,
            "base_length": p.base_length,
            "top_length": p.top_length,
            "crosses_itself": not Polygon(p.outline).is_valid,
        }
        for p in patterns
    ]
    summary = {
        "units": {"length": length_unit},
        "webs": webs,
        "note": "a web that crosses itself cannot be cut as drawn: `tubecad shop` splits it into cuttable "
        "pieces at butt joints and nests them on plates",
        "warnings": [
            f"{web['name']}: its flat pattern crosses itself and cannot be cut as drawn "
            "(`tubecad shop` splits it into cuttable pieces at butt joints)"
            for web in webs
            if web["crosses_itself"]
        ],
    }
    written.append(write_text(folder / "flat.json", to_json(summary)))
    return written


def written_warnings(paths) -> list[str]:
    """The warnings the written measures hold (each flat.json's self-crossing webs), for the
    terminal: nothing a file records as a warning goes unsaid."""
    import json

    found: list[str] = []
    for path in map(Path, paths):
        if path.name == "flat.json":
            found += json.loads(path.read_text(encoding="utf-8")).get("warnings", [])
    return found


def render_step_picture(step: Path, png: Path) -> Path:
    """Render the STEP file as read back (tessellated faces, B-rep edges on top)."""
    from tubecad.export.cad import import_shape
    from tubecad.export.render import render_shape_png

    return render_shape_png(import_shape(step), png, title=f"{step.name} as read back: faces and B-rep edges")


def export_summary(info: dict[str, Any]) -> str:
    """One line on a written file, from what was measured on it as read back."""
    if "lines" in info:
        return f"{info['bytes']} bytes, {info['lines']} curvature lines as polylines"
    if "picture" in info and "rings" not in info:  # a junction's picture: the solid with its edges
        return f"{info['bytes']} bytes, {info['picture']}: the solid with its named edges"
    if "picture" in info:
        return (
            f"{info['bytes']} bytes, {info['picture']}: projections with {info['rings']} ring frames "
            f"and {info['stringers']} stringers"
        )
    if "triangles" in info:
        checked = (
            f", within {info['max_triangle_deviation']:.1e} of the tube (vertices {info['max_vertex_deviation']:.1e})"
            if "max_triangle_deviation" in info
            else ""
        )
        asked = (
            f", tolerance {info['deflection']:.3g} and {info['angular_deflection_deg']:.3g} deg"
            if info.get("deflection") is not None and info.get("angular_deflection_deg") is not None
            else ""
        )
        return f"{info['bytes']} bytes, mesh for visual use: {info['triangles']} triangles{checked}{asked}"
    measured = (
        f", file deviation {info['max_deviation']:.2e}, orthogonality {info['max_orthogonality_error']:.2e}"
        if "max_deviation" in info
        else ""
    )
    return f"{info['bytes']} bytes, read back valid={info['valid']}, faces={info['faces']}{measured}"


def build_summary(report: dict[str, Any]) -> list[str]:
    """The lines ``tubecad build`` prints for one spec: the B-rep (or the junction: its solid,
    each saddle, each opening's area replacement), then each file written."""
    if "junction" in report:
        return junction_summary(report["junction"]) + [
            f"{path}: {export_summary(info)}" for path, info in report["exports"].items()
        ]
    if "net" in report:
        return net_summary(report) + [f"{path}: {export_summary(info)}" for path, info in report["exports"].items()]
    brep = report["brep"]
    lines = [
        f"{brep['kind']}: {brep['faces']} faces, {brep['edges']} edges, valid={brep['valid']}, "
        f"fit deviation {brep['fit']['max_deviation']:.2e}, orthogonality {brep['fit']['max_orthogonality_error']:.2e}"
    ]
    return lines + [f"{path}: {export_summary(info)}" for path, info in report["exports"].items()]


def net_summary(report: dict[str, Any]) -> list[str]:
    """A face's net: its lines and their largest angle to the principal directions, its
    patches, its umbilics by type, its webs."""
    net, brep, host = report["net"], report["brep"], report["host"]
    kinds: dict[str, int] = {}
    for point in host["umbilics"]:
        kinds[point["type"]] = kinds.get(point["type"], 0) + 1
    umbilics = ", ".join(f"{n} {kind}" for kind, n in sorted(kinds.items())) or "none"
    for part in host.get("umbilic_parts", ()):
        umbilics += f"; a {part['type']} umbilic part of {part['area']:.4g} (the lines stop on its border)"
    lines = [
        f"{brep['kind']}: {net['k1_lines']} + {net['k2_lines']} lines of curvature, within {net['angle']:.1e} rad of the "
        f"principal directions; {brep['patches']} patches, valid={brep['valid']}; umbilics: {umbilics}"
    ]
    if "patches" in report:
        refit = report["patches"]
        lines.append(
            f"patches: {len(refit['refitted'])} cells refitted in curvature-line coordinates (within "
            f"{refit['distance']:.1e} of the face, isolines within {refit['angle']:.1e} rad of the principal "
            f"directions), {len(refit['kept'])} kept on the face"
        )
    if "stiffeners" in report:
        lines.append(f"stiffeners: {len(report['stiffeners'])} webs on the lines, each developing flat without strain")
    return lines


def junction_summary(junction: dict[str, Any]) -> list[str]:
    """The junction's lines: the solid, each saddle (its edges in the solid, how far from
    the exact saddle), each opening's area replacement with its disclaimer."""
    lines = [
        f"junction wall: {junction['faces']} faces, {junction['edges']} edges, valid={junction['valid']}, "
        f"{len(junction['named_edge_sets'])} named edge sets"
    ]
    for name, saddle in junction["saddles"].items():
        lines.append(
            f"{name}: {saddle['edges_in_solid']} edges in the solid, {saddle['edges_deviation']:.1e} from the exact "
            f"saddle (fitted: {saddle.get('curves', 'periodic B-spline')}, {saddle['poles']} poles, "
            f"{saddle['fit_deviation']:.1e})"
        )
    for name, blend in junction.get("blends", {}).items():
        edges = ", ".join(f"{count} {edge}" for edge, count in blend["edges_in_solid"].items())
        lines.append(
            f"{name}: radius {blend['radius']:g}, its edges in the solid {edges} (the contact curves, fitted to "
            f"{blend['contact_deviation']:.1e})"
        )
    for name, pad in junction.get("pads", {}).items():
        lines.append(
            f"{name}: thickness {pad['thickness']:g}, volume {pad['volume']:.6g}, valid={pad['valid']}, "
            f"development strain {pad['development_max_strain']:.2g}"
        )
    stiffeners = junction.get("stiffeners", {})
    if stiffeners:
        stopped = sorted({name.rsplit("_", 1)[0] for name in stiffeners if name[-2:] in ("_a", "_b", "_c")})
        lines.append(
            f"stiffeners: {len(stiffeners)} solids, valid={all(v['valid'] for v in stiffeners.values())}; "
            f"stringers in pieces at an opening or pad: {', '.join(stopped) if stopped else 'none'}"
        )
    for row in junction.get("reinforcement", []):
        if "skipped" in row:
            lines.append(f"branch {row['branch']}: area replacement skipped ({row['skipped']})")
            continue
        verdict = "adequate" if row["adequate"] else "NOT adequate"
        lines.append(
            f"branch {row['branch']}: area replacement A = {row['required']:.4g}, available {row['available']:.4g} "
            f"(shell {row['shell']:.4g}, nozzle {row['nozzle']:.4g}, pad {row['pad']:.4g}): {verdict} - {row['note']}"
        )
    return lines
