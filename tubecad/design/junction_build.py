"""A :class:`~tubecad.design.junction.JunctionDesign` built: the main wall with every branch's
wall joined on (:func:`tubecad.junctions.build_branched_wall`), the pads and stiffeners, the
named assembly its files are written from and what was measured (issue 25).

The assembly holds the solid ``wall``, each pad and stiffener, and ``junction_edges``: a
compound per named edge set (``saddle_outer``, ``saddle_inner``, ``main_ring_03``,
``branch_stringer_05_inner``, ...), so the names read back from STEP. The report holds each
saddle's fit and its edges in the solid, measured, and with ``reinforcement`` each
opening's area-replacement figures (:func:`tubecad.junctions.area_replacement`: a
geometric aid, not a code certification)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tubecad.core.errors import ParameterError
from tubecad.core.progress import Progress
from tubecad.design.stages import stage

if TYPE_CHECKING:
    import build123d as bd

    from tubecad.design.junction import JunctionDesign
    from tubecad.export.registry import Exportable, OutputFormat
    from tubecad.junctions import BranchWall, JunctionWall
    from tubecad.stiffeners.pad import Pad
    from tubecad.surface.protocol import CurvatureLineSurface


@dataclass
class JunctionResult:
    """A junction built (:class:`~tubecad.design.result.BuildResult`): the
    :class:`~tubecad.junctions.JunctionWall` ``junction``, the branches' ``walls``, the
    ``pads`` by branch index, the ``stiffeners``, the ``shape`` its files are written from
    (the named assembly) and the ``report``."""

    design: JunctionDesign
    junction: JunctionWall
    walls: list[BranchWall]
    pads: dict[int, Pad] = field(default_factory=dict)
    stiffeners: list = field(default_factory=list)
    shape: Any = None
    report: dict[str, Any] = field(default_factory=dict)

    kind = "junction_wall"

    @property
    def length_unit(self) -> str:
        return self.design.length_unit

    @property
    def surfaces(self) -> list:
        """The exact surfaces: the main tube's, then each branch's."""
        return [self.design.main.surface, *(b.surface for b in self.design.branches)]

    @property
    def pad_names(self) -> dict[int, str]:
        """Each pad's name by branch index (``pad``; ``pad_0``, ``pad_1``... with several branches)."""
        from tubecad.stiffeners.pad import pad_name

        return {k: pad_name(k, len(self.walls)) for k in self.pads}

    @property
    def solids(self) -> list[tuple[str, Any]]:
        """(name, OCCT solid): the junction wall first, then each stiffener and each pad."""
        out = [("wall", self.junction.shape.wrapped)]
        out += [(st.name, st.solid.wrapped) for st in self.stiffeners]
        out += [(self.pad_names[k], pad.solid.wrapped) for k, pad in self.pads.items()]
        return out

    @property
    def named_edges(self) -> dict[str, list[Any]]:
        """The junction wall's named edges (``saddle_outer``, ``main_ring_03``,
        ``branch_stringer_05_inner``...) as OCCT edges of its solid."""
        return {name: [e.wrapped for e in edges] for name, edges in sorted(self.junction.edges.items())}

    @property
    def mesh_radius(self) -> float:
        """The smallest radius of the walls' surfaces (mesh tolerances are checked against it)."""
        radii = []
        for surface, wall in [(self.design.main.surface, self.design.main.wall), *self._branch_walls()]:
            assert wall is not None  # a junction's main has a wall (JunctionDesign)
            radii.append(surface.radius_law.min_radius + wall.offsets()[0])
        return min(radii)

    def _branch_walls(self) -> list[tuple[Any, Any]]:
        return [(b.surface, b.wall) for b in self.design.branches]

    def lines(self) -> list:
        """A junction's curvature lines are its named edges (no polylines are written of them)."""
        return []

    def exportable(self, step_schema: str, deflection: float, angular: float) -> Exportable:
        """What every output of this junction is written from: the named assembly."""
        from tubecad.export.registry import Exportable

        return Exportable(
            self.shape,
            None,
            step_schema,
            mesh_deflection=deflection,
            mesh_angular=angular,
            length_unit=self.length_unit,
        )

    def written_reference(self) -> Any:
        """The assembly written, with the volume measured on its solids at build time."""
        from tubecad.export.readback import WrittenShape

        junction = self.report["junction"]
        total = junction["volume"] + sum(p["volume"] for p in junction.get("pads", {}).values())
        total += sum(p["volume"] for p in junction.get("stiffeners", {}).values())
        return WrittenShape(self.shape, {"volume": total})

    def check_file(
        self, tmp: Path, fmt: OutputFormat, target: Path, reference: Any, deflection: float, angular: float
    ) -> dict[str, Any]:
        """Read a just-written file back: a CAD file as one wall solid, its pads and
        stiffeners, their volume and area those written, a STEP file's edge names all there; a
        mesh's triangles; a picture's pixels. Raises if not, so it is never moved into place."""
        from tubecad.export.cad import step_names
        from tubecad.export.readback import FileAccuracyError, mesh_report, readback_report

        if fmt.kind == "picture":
            from matplotlib.image import imread

            height, width = imread(tmp, format="png").shape[:2]
            return {"bytes": tmp.stat().st_size, "picture": f"PNG {width} x {height}"}
        if fmt.kind == "mesh":
            return mesh_report(tmp, fmt.name, None, deflection, target, None, self.length_unit, angular)
        info = readback_report(tmp, reference, None, target, None, self.length_unit)
        if info["solids"] != 1 + len(self.pads) + len(self.stiffeners):
            raise FileAccuracyError(
                f"{target.name}: reads back as {info['solids']} solids, not the junction's, its {len(self.pads)} pads "
                f"and {len(self.stiffeners)} stiffeners"
            )
        if fmt.name == "step":
            names = {name for _, name in step_names(tmp)}
            missing = sorted((set(self.junction.edges) | set(self.pad_names.values())) - names)
            if missing:
                raise FileAccuracyError(f"{target.name}: the edge names {', '.join(missing[:4])} did not read back")
            info["edge_names"] = len(self.junction.edges)
        return info


def branch_walls(design: JunctionDesign) -> list[BranchWall]:
    """The design's branches as :class:`~tubecad.junctions.BranchWall` s."""
    from tubecad.junctions import BranchWall

    return [BranchWall(b.surface, b.wall.thickness, b.wall.side, b.layout) for b in design.branches]


def junction_wall(design: JunctionDesign, walls: list[BranchWall] | None = None) -> JunctionWall:
    """The junction wall of ``design`` (``walls``: its :func:`branch_walls` if made already)."""
    from tubecad.junctions import build_branched_wall

    main = design.main
    assert main.wall is not None  # a junction joins walls
    with stage("branches"):
        return build_branched_wall(
            main.surface,
            main.wall.thickness,
            walls if walls is not None else branch_walls(design),
            main_side=main.wall.side,
            main_layout=main.layout,
            tolerance=main.tolerance,
        )


def junction_pads(design: JunctionDesign, junction: JunctionWall, walls: list[BranchWall]) -> dict[int, Pad]:
    """The reinforcement pads of the branches that have one, by branch index: each on the
    main wall's outer surface round the branch's outer saddle."""
    from tubecad.junctions import saddle_name
    from tubecad.stiffeners.pad import reinforcement_pad

    main = design.main
    assert main.wall is not None
    main_out = main.wall.offsets()[1]
    pads = {}
    for k, (branch, wall) in enumerate(zip(design.branches, walls)):
        if branch.pad is None:
            continue
        with stage("pads", k):
            pads[k] = reinforcement_pad(
                main.surface.offset(main_out),
                wall.surface.offset(wall.offsets()[1]),
                junction.saddles[saddle_name("saddle_outer", k, len(walls))].saddle,
                branch.pad.thickness,
                branch.pad.width,
                main.tolerance,
            )
    _check_pads_apart(main.surface.offset(main_out), junction, pads, len(walls))
    return pads


def _check_pads_apart(outer: CurvatureLineSurface, junction: JunctionWall, pads: dict[int, Pad], n: int) -> None:
    """Refuse a pad that reaches another branch's opening or pad on the main's outer surface
    ``outer`` (both unrolled: :mod:`tubecad.junctions.placement`), naming its width and the
    clearance it would need."""
    from tubecad.junctions import saddle_name
    from tubecad.junctions.placement import region_clearance, unrolled_opening, unrolled_patch

    openings = {
        m: unrolled_opening(outer, junction.saddles[saddle_name("saddle_outer", m, n)].saddle) for m in range(n)
    }
    patches = {k: unrolled_patch(outer, pad.s_range, pad.angles_deg) for k, pad in pads.items()}
    for k, patch in patches.items():
        others = [(f"the opening of branch {m}", region) for m, region in openings.items() if m != k]
        others += [(f"the pad of branch {m}", region) for m, region in patches.items() if m > k]
        for what, region in others:
            if region_clearance(outer, patch, region) <= 0.0:
                overlap = patch.intersection(region).area
                with stage("pads", k):
                    raise ParameterError(
                        f"pad.width: the pad of branch {k} (width {pads[k].width:g}) reaches {what} on the main "
                        f"tube (they overlap over {overlap:.4g} square units): a narrower pad, or the branches apart",
                        key="pad.width",
                    )


def junction_stiffeners(
    design: JunctionDesign, walls: list[BranchWall], junction: JunctionWall | None = None
) -> list[Any]:
    """The main design's stiffeners on the main wall, each stopped at every branch's opening
    (on the surface it stands on: the outer saddle outside, the bore's inside) or at its
    pad's edge (a pad outside), and each stiffened branch's own (its stringers from its
    saddle, its rings beyond it); [] without stiffeners (:mod:`tubecad.stiffeners.junction`).
    ``junction``: the built wall, whose saddles start Newton (no new march round a branch)."""
    from tubecad.junctions import saddle_name
    from tubecad.junctions.saddle import saddle_curve
    from tubecad.stiffeners.junction import Keepout, branch_stiffeners, main_stiffeners
    from tubecad.stiffeners.pad import pad_bounds

    main, chosen = design.main, design.main.stiffeners
    if chosen is None:
        return []
    assert main.wall is not None
    layout, outside = main.layout, chosen.side == "outside"
    main_base = main.surface.offset(main.wall.offsets()[1 if outside else 0])
    keepouts, saddles = [], []
    for k, (branch, wall) in enumerate(zip(design.branches, walls)):
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
    with stage("stiffeners"):
        out = main_stiffeners(
            main_base,
            [(i, layout.s_rings[i]) for i in chosen.rings],
            [(j, layout.stringers_deg[j]) for j in chosen.stringers],
            chosen.profile,
            chosen.side,
            keepouts,
            main.tolerance,
        )
    for k, (branch, (branch_base, saddle)) in enumerate(zip(design.branches, saddles)):
        if not branch.stiffened:
            continue
        net = branch.layout
        start = chosen.profile.height if branch.stiffener_start is None else branch.stiffener_start
        with stage("stiffeners", k):
            out += branch_stiffeners(
                branch_base,
                saddle,
                [(i, net.s_rings[i]) for i in branch.stiffener_rings],
                [(j, net.stringers_deg[j]) for j in branch.stiffener_stringers],
                chosen.profile,
                chosen.side,
                start,
                "branch" if len(walls) == 1 else f"branch{k}",
                main.tolerance,
            )
    return out


def junction_assembly(
    junction: JunctionWall, pads: dict[int, Pad] | None = None, branches: int = 1, stiffeners: list[Any] | None = None
) -> bd.Compound:
    """``wall`` (the junction solid), each stiffener (``ring_03``, ``stringer_05_a``,
    ``branch_ring_02``...), each pad (``pad``, ``pad_1``...) and ``junction_edges``: a
    compound per edge name."""
    import build123d as bd

    from tubecad.stiffeners.pad import pad_name

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
    design: JunctionDesign, junction: JunctionWall, walls: list[BranchWall], pads: dict[int, Pad] | None = None
) -> dict[str, Any]:
    """What was measured on the junction: the solid (valid, counts, volume), per saddle its
    fitted edge (poles, distance from the exact saddle) and its edges in the solid (how many,
    their largest distance from the exact saddle, their length over the saddle's), each
    pad, and per branch the area-replacement figures when the design asks for them."""
    from tubecad.brep.properties import count, is_valid, volume
    from tubecad.stiffeners.pad import pad_name

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
    if pads:
        from tubecad.shop.panel_development import develop_panel

        report["pads"] = {}
        for k, pad in pads.items():
            name = pad_name(k, len(walls))
            development = develop_panel(pad.surface, pad.s_range, pad.angles_deg, name)
            report["pads"][name] = {
                "valid": is_valid(pad.solid.wrapped),
                "volume": volume(pad.solid.wrapped),
                "thickness": pad.thickness,
                "s_range": list(pad.s_range),
                "angles_deg": list(pad.angles_deg),
                "development_max_strain": development.max_strain,
            }
    if design.reinforcement is not None:
        report["reinforcement"] = reinforcement(design, junction, walls, *design.reinforcement, pads)
    return report


def reinforcement(
    design: JunctionDesign,
    junction: JunctionWall,
    walls: list[BranchWall],
    pressure: float,
    stress: float,
    pads: dict[int, Pad] | None = None,
) -> list[dict[str, Any]]:
    """Each branch's area-replacement figures from its bore saddle (constant radii only: the
    rule takes one inside radius per shell)."""
    from tubecad.junctions import area_replacement, saddle_name

    main = design.main
    assert main.wall is not None
    out = []
    main_in = main.wall.offsets()[0]
    for k, wall in enumerate(walls):
        if not (main.surface.constant_radius and wall.surface.constant_radius):
            out.append({"branch": k, "skipped": "a radius law: the rule takes one inside radius per shell"})
            continue
        with stage("branches", k):
            figures = area_replacement(
                junction.saddles[saddle_name("saddle_inner", k, len(walls))].saddle,
                shell_radius=main.surface.radius_law.constant_value + main_in,
                shell_thickness=main.wall.thickness,
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


def build_junction(design: JunctionDesign, progress: Progress | None = None) -> JunctionResult:
    """Build ``design``: the junction wall, its pads and stiffeners, the named assembly, and
    measure them (the main tube's exact measures, the junction's report). Nothing is written.

    Raises:
        ParameterError, RegularityError, FitError: tagged with the stage that failed
            (:func:`tubecad.design.stages.stage`); a stiffener that is not a valid solid
            (stage ``stiffeners``).
    """
    from tubecad.brep.properties import is_valid, volume
    from tubecad.design.report import tube_report

    progress = progress if progress is not None else Progress(enabled=False)
    progress.step("building the junction", 1)
    walls = branch_walls(design)
    junction = junction_wall(design, walls)
    pads = junction_pads(design, junction, walls)
    stiffeners = junction_stiffeners(design, walls, junction)
    progress.advance(1, "junction")
    main = design.main
    report = tube_report(main.surface, *main.report_grid, length_unit=main.length_unit)
    report["junction"] = measured = junction_report(design, junction, walls, pads)
    if stiffeners:
        measured["stiffeners"] = {
            st.name: {"valid": is_valid(st.solid.wrapped), "volume": volume(st.solid.wrapped)} for st in stiffeners
        }
        invalid = [st.name for st in stiffeners if not measured["stiffeners"][st.name]["valid"]]
        if invalid:
            with stage("stiffeners"):
                raise ParameterError(f"{', '.join(invalid)}: not a valid solid", key="stiffeners")
    # what a batch's summary reads of any build (tubecad.batch.jobs)
    report["brep"] = {key: measured[key] for key in ("valid", "faces", "edges", "volume")}
    report["brep"]["kind"] = "junction_wall"
    shape = junction_assembly(junction, pads, len(walls), stiffeners)
    return JunctionResult(design, junction, walls, pads, stiffeners, shape, report)
