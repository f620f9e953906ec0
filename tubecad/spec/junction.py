"""A spec with [[branches]]: the junction wall, its named assembly and its report (issue 25).

``tubecad build`` on such a spec makes the main [wall] with every branch's wall joined to it
(:func:`tubecad.junctions.build_branched_wall`) and writes it as a named assembly: the solid
``wall`` and ``junction_edges``, one compound per named edge set (``saddle_outer``,
``saddle_inner``, ``main_ring_03``, ``branch_stringer_05_inner``, ...), so the names read back
from STEP. The report holds each saddle's fit and its edges in the solid, measured, and,
with [analysis] pressure and allowable_stress, each opening's area-replacement figures
(:func:`tubecad.junctions.area_replacement`: a geometric aid, not a code certification).
"""

from __future__ import annotations

from functools import partial
from pathlib import Path
from typing import Any

import build123d as bd

from tubecad.brep.properties import count, is_valid, volume
from tubecad.core.errors import ParameterError, RegularityError, SpecError, TubecadError
from tubecad.core.progress import Progress
from tubecad.fitting import FitError
from tubecad.junctions import BranchWall, JunctionWall, area_replacement, build_branched_wall, saddle_name
from tubecad.spec.parse import TubeSpec
from tubecad.stiffeners.pad import Pad, pad_name


def branch_walls(spec: TubeSpec) -> list[BranchWall]:
    """The spec's [[branches]] as :class:`~tubecad.junctions.BranchWall` (parse_spec checked them)."""
    assert spec.wall is not None  # parse_spec refuses [[branches]] without [wall]
    main_stringers = len(spec.layout.net(spec.tube).stringers_deg)
    out = []
    for branch in spec.branches:
        surface = branch.surface(spec.tube)
        wall = branch.wall or spec.wall
        out.append(BranchWall(surface, wall.thickness, wall.side, branch.net(surface, main_stringers)))
    return out


def build_junction(spec: TubeSpec, walls: list[BranchWall] | None = None) -> JunctionWall:
    """The junction wall of ``spec`` (its [wall] and [[branches]], ``walls`` their
    :func:`branch_walls` if made already); a SpecError naming the key (``branches``,
    ``branches.radius``, ``fit.tolerance``) where it cannot be built."""
    assert spec.wall is not None
    try:
        return build_branched_wall(
            spec.tube,
            spec.wall.thickness,
            walls if walls is not None else branch_walls(spec),
            main_side=spec.wall.side,
            main_layout=spec.layout.net(spec.tube),
            tolerance=spec.fit.tolerance,
        )
    except FitError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}", key="fit.tolerance") from None
    except (ParameterError, RegularityError) as exc:
        key = exc.key if exc.key and (exc.key.startswith("branches") or exc.key.startswith("fit")) else "branches"
        raise SpecError(f"{spec.source}: [[branches]] {exc}", key=key) from None
    except TubecadError as exc:
        raise SpecError(f"{spec.source}: [[branches]] {exc}", key="branches") from None


def build_pads(spec: TubeSpec, junction: JunctionWall, walls: list[BranchWall]) -> dict[int, Pad]:
    """The reinforcement pads of the branches that ask for one (``pad`` in their table), by
    branch index: each on the main wall's outer surface round the branch's outer saddle
    (``walls``: the branches' :func:`branch_walls`)."""
    from tubecad.stiffeners.pad import reinforcement_pad

    assert spec.wall is not None
    pads = {}
    main_out = spec.wall.offsets()[1]
    for k, (branch, wall) in enumerate(zip(spec.branches, walls)):
        if branch.pad is None:
            continue
        try:
            pads[k] = reinforcement_pad(
                spec.tube.offset(main_out),
                wall.surface.offset(wall.offsets()[1]),
                junction.saddles[saddle_name("saddle_outer", k, len(walls))].saddle,
                branch.pad.thickness,
                branch.pad.width,
                spec.fit.tolerance,
            )
        except ParameterError as exc:
            raise SpecError(f"{spec.source}: [[branches]] #{k + 1} {exc}", key=exc.key or "branches.pad") from None
    return pads


def build_junction_stiffeners(
    spec: TubeSpec, walls: list[BranchWall], junction: JunctionWall | None = None
) -> list[Any]:
    """The main [stiffeners] on the main wall, each stopped at every branch's opening (on the
    surface it stands on: the outer saddle outside, the bore's inside) or at its pad's edge
    (a pad outside), and each branch's own ``stiffeners`` (its stringers from its saddle, its
    rings ``start`` beyond it); [] without [stiffeners] (:mod:`tubecad.stiffeners.junction`).
    ``junction``: the built wall, whose saddles start Newton (no new march round a branch)."""
    from tubecad.junctions.saddle import saddle_curve
    from tubecad.stiffeners.junction import Keepout, branch_stiffeners, main_stiffeners
    from tubecad.stiffeners.pad import pad_bounds

    if spec.stiffeners is None:
        return []
    assert spec.wall is not None
    layout = spec.layout.net(spec.tube)
    chosen = spec.stiffeners.select(layout, spec.source, spec.length_unit)
    outside = chosen.side == "outside"
    main_base = spec.tube.offset(spec.wall.offsets()[1 if outside else 0])
    keepouts, saddles = [], []
    for k, (branch, wall) in enumerate(zip(spec.branches, walls)):
        branch_base = wall.surface.offset(wall.offsets()[1 if outside else 0])
        known = saddle_name("saddle_outer" if outside else "saddle_inner", k, len(walls))
        near = junction.saddles[known].saddle if junction is not None else None
        saddle = saddle_curve(main_base, branch_base, near=near)
        saddles.append((branch_base, saddle))
        if outside and branch.pad is not None:
            s_range, angles = pad_bounds(main_base, saddle, branch.pad.width)
            keepouts.append(Keepout(s_range=s_range, angles_deg=angles))
        else:
            keepouts.append(Keepout(saddle=saddle))
    try:
        out = main_stiffeners(
            main_base,
            [(i, layout.s_rings[i]) for i in chosen.rings],
            [(j, layout.stringers_deg[j]) for j in chosen.stringers],
            chosen.profile,
            chosen.side,
            keepouts,
            spec.fit.tolerance,
        )
        for k, (branch, wall, (branch_base, saddle)) in enumerate(zip(spec.branches, walls, saddles)):
            if branch.stiffeners is None:
                continue
            assert wall.layout is not None
            net = wall.layout
            start = chosen.profile.height if branch.stiffeners.start is None else branch.stiffeners.start
            prefix = "branch" if len(walls) == 1 else f"branch{k}"
            out += branch_stiffeners(
                branch_base,
                saddle,
                [(i, net.s_rings[i]) for i in branch.stiffeners.indices("rings", len(net.s_rings))],
                [(j, net.stringers_deg[j]) for j in branch.stiffeners.indices("stringers", len(net.stringers_deg))],
                chosen.profile,
                chosen.side,
                start,
                prefix,
                spec.fit.tolerance,
            )
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [stiffeners] {exc}", key=exc.key or "stiffeners") from None
    return out


def junction_assembly(
    junction: JunctionWall, pads: dict[int, Pad] | None = None, branches: int = 1, stiffeners: list[Any] | None = None
) -> bd.Compound:
    """``wall`` (the junction solid), each pad (``pad``, ``pad_1``...), each stiffener
    (``ring_03``, ``stringer_05_a``, ``branch_ring_02``...) and ``junction_edges``: a
    compound per edge name."""
    wall = bd.Solid(junction.shape.wrapped)
    wall.label = "wall"
    plates = []
    for stiffener in stiffeners or []:  # as on a stiffened wall: the wall, then its stiffeners
        solid = bd.Solid(stiffener.solid.wrapped)
        solid.label = stiffener.name
        plates.append(solid)
    for k, pad in (pads or {}).items():
        plate = bd.Solid(pad.solid.wrapped)
        plate.label = pad_name(k, branches)
        plates.append(plate)
    groups = []
    for name in sorted(junction.edges):
        group = bd.Compound(children=[bd.Edge(e.wrapped) for e in junction.edges[name]])
        group.label = name
        groups.append(group)
    edges = bd.Compound(children=groups)
    edges.label = "junction_edges"
    return bd.Compound(label="tubecad", children=[wall, *plates, edges])


def junction_report(
    spec: TubeSpec, junction: JunctionWall, walls: list[BranchWall], pads: dict[int, Pad] | None = None
) -> dict[str, Any]:
    """What was measured on the junction: the solid (valid, counts, volume), per saddle its
    fitted edge (poles, distance from the exact saddle) and its edges in the solid (how many,
    their largest distance from the exact saddle, their length over the saddle's), and per
    branch the area-replacement figures when [analysis] gives pressure and allowable_stress."""
    shape = junction.shape.wrapped
    report: dict[str, Any] = {
        "valid": is_valid(shape),
        "solids": count(shape, "solid"),
        "faces": count(shape, "face"),
        "edges": count(shape, "edge"),
        "volume": volume(shape),
        "named_edge_sets": sorted(junction.edges),
        "saddles": {
            name: {
                "poles": saddle.poles,
                "fit_deviation": saddle.deviation,
                "edges_in_solid": len(junction.edges.get(name, [])),
                "edges_deviation": junction.deviation[name],
                "coverage": junction.coverage[name],
            }
            for name, saddle in junction.saddles.items()
        },
    }
    pads = pads or {}
    if pads:
        from tubecad.shop.panel_development import develop_panel

        report["pads"] = {}
        for k, pad in pads.items():
            development = develop_panel(pad.surface, pad.s_range, pad.angles_deg, pad_name(k, len(spec.branches)))
            report["pads"][pad_name(k, len(spec.branches))] = {
                "valid": is_valid(pad.solid.wrapped),
                "volume": volume(pad.solid.wrapped),
                "thickness": pad.thickness,
                "s_range": list(pad.s_range),
                "angles_deg": list(pad.angles_deg),
                "development_max_strain": development.max_strain,
            }
    analysis = spec.analysis
    if analysis is not None and analysis.pressure and analysis.allowable_stress:
        report["reinforcement"] = reinforcement(
            spec, junction, walls, analysis.pressure, analysis.allowable_stress, pads
        )
    return report


def reinforcement(
    spec: TubeSpec,
    junction: JunctionWall,
    walls: list[BranchWall],
    pressure: float,
    stress: float,
    pads: dict[int, Pad] | None = None,
) -> list[dict[str, Any]]:
    """Each branch's area-replacement figures from its bore saddle (constant radii only: the
    rule takes one inside radius per shell)."""
    assert spec.wall is not None
    out = []
    main_in = spec.wall.offsets()[0]
    for k, wall in enumerate(walls):
        if not (spec.tube.constant_radius and wall.surface.constant_radius):
            out.append({"branch": k, "skipped": "a radius law: the rule takes one inside radius per shell"})
            continue
        figures = area_replacement(
            junction.saddles[saddle_name("saddle_inner", k, len(walls))].saddle,
            shell_radius=spec.tube.radius_law.constant_value + main_in,
            shell_thickness=spec.wall.thickness,
            nozzle_radius=wall.surface.radius_law.constant_value + wall.offsets()[0],
            nozzle_thickness=wall.thickness,
            pressure=pressure,
            stress=stress,
            pad_diameter=pads[k].diameter if pads and k in pads else 0.0,
            pad_thickness=pads[k].thickness if pads and k in pads else 0.0,
            key="branches",
        )
        out.append({"branch": k, **figures.as_dict()})
    return out


def build_and_export_junction(
    spec: TubeSpec,
    outputs: list[Path],
    step_schema: str = "AP214",
    report_path: Path | None = None,
    written: list[Path] | None = None,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """:func:`tubecad.spec.build.build_and_export` for a spec with [[branches]]: the junction
    wall as a named assembly in each CAD output (STEP, IGES, BREP), each read back before it
    is moved into place (one valid solid, its volume and area those written; a STEP file's
    edge names all there), a PNG output the solid rendered with its edges, and the report.
    Meshes, SVG pictures and polylines of a junction are refused before anything is built
    (not made yet)."""
    from tubecad.core.atomic import write_text
    from tubecad.export.cad import step_names
    from tubecad.export.readback import FileAccuracyError, WrittenShape, readback_report
    from tubecad.export.registry import Exportable, output_format, write_output
    from tubecad.spec.preflight import check_build_outputs
    from tubecad.spec.report import to_json, tube_report

    written = [] if written is None else written
    progress = progress if progress is not None else Progress(enabled=False)
    check_build_outputs(spec, outputs, report_path)  # made by build_and_export too: a script may call this alone
    unit = spec.length_unit
    progress.step("building the junction", 1)
    walls = branch_walls(spec)
    junction = build_junction(spec, walls)
    pads = build_pads(spec, junction, walls)
    stiffeners = build_junction_stiffeners(spec, walls, junction)
    progress.advance(1, "junction")
    report = tube_report(spec.tube, 64, 501, length_unit=unit)
    report["junction"] = junction_report(spec, junction, walls, pads)
    if stiffeners:
        report["junction"]["stiffeners"] = {
            st.name: {"valid": is_valid(st.solid.wrapped), "volume": volume(st.solid.wrapped)} for st in stiffeners
        }
        invalid = [st.name for st in stiffeners if not report["junction"]["stiffeners"][st.name]["valid"]]
        if invalid:
            raise SpecError(f"{spec.source}: [stiffeners] {', '.join(invalid)}: not a valid solid", key="stiffeners")
    # what a batch's summary reads of any build (tubecad.batch.jobs)
    report["brep"] = {key: report["junction"][key] for key in ("valid", "faces", "edges", "volume")}
    report["brep"]["kind"] = "junction_wall"
    shape = junction_assembly(junction, pads, len(spec.branches), stiffeners)
    pad_volume = sum(p["volume"] for p in report["junction"].get("pads", {}).values())
    pad_volume += sum(p["volume"] for p in report["junction"].get("stiffeners", {}).values())
    reference = WrittenShape(shape, {"volume": report["junction"]["volume"] + pad_volume})
    item = Exportable(shape, None, step_schema, length_unit=unit)
    exports = report["exports"] = {}

    def check(tmp: Path, fmt: Any, target: Path) -> dict[str, Any]:
        if fmt.name == "png":
            from matplotlib.image import imread

            height, width = imread(tmp, format="png").shape[:2]
            return {"bytes": tmp.stat().st_size, "picture": f"PNG {width} x {height}"}
        info = readback_report(tmp, reference, None, target, None, unit)
        if info["solids"] != 1 + len(pads) + len(stiffeners):
            raise FileAccuracyError(
                f"{target.name}: reads back as {info['solids']} solids, not the junction's, its {len(pads)} pads "
                f"and {len(stiffeners)} stiffeners"
            )
        if fmt.name == "step":
            names = {name for _, name in step_names(tmp)}
            missing = sorted(set(junction.edges) - names | {pad_name(k, len(spec.branches)) for k in pads} - names)
            if missing:
                raise FileAccuracyError(f"{target.name}: the edge names {', '.join(missing[:4])} did not read back")
            info["edge_names"] = len(junction.edges)
        return info

    progress.step("writing and reading back files", len(outputs))
    for path in outputs:
        if output_format(path).name == "png":
            solids = bd.Compound(
                [junction.shape, *(pad.solid for pad in pads.values()), *(st.solid for st in stiffeners)]
            )
            done, info = path, render_junction(solids, path, spec.source, check)
        else:
            done, info = write_output(item, path, partial(check, target=path))
        written.append(done)
        exports[str(path)] = info
        progress.advance(1, f"checked {path.name}")
    if report_path is not None:
        written.append(write_text(report_path, to_json(report)))
    return report


def render_junction(solids: bd.Shape, path: Path, title: str, check: Any) -> dict[str, Any]:
    """The junction's solids (the wall, its pads) shaded with their edges (the nets, the saddles) into the PNG
    ``path``, atomically; ``check(tmp, fmt, path)`` reads it back before it is kept."""
    from tubecad.core.atomic import atomic_path
    from tubecad.export.registry import output_format
    from tubecad.export.render import render_shape_png

    with atomic_path(path) as tmp:
        render_shape_png(solids, tmp, title=Path(title).name)
        return check(tmp, output_format(path), path)
