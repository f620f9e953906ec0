"""A junction design (:class:`JunctionDesign`: a main wall with branches) and its build: the main wall with every branch's
wall joined on (:func:`tubecad.junctions.build_branched_wall`), the pads and stiffeners, the
named assembly its files are written from and what was measured (issue 25).

The assembly holds the solid ``wall``, each pad and stiffener, and ``junction_edges``: a
compound per named edge set (``saddle_outer``, ``saddle_inner``, ``main_ring_03``,
``branch_stringer_05_inner``, ...), so the names read back from STEP. The report holds each
saddle's fit and its edges in the solid, measured, and with ``reinforcement`` each
opening's area-replacement figures (:func:`tubecad.junctions.area_replacement`: a
geometric aid, not a code certification)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

from tubecad.core.errors import ParameterError
from tubecad.core.progress import Progress
from tubecad.design.junction_parts import branch_walls, junction_pads, junction_stiffeners, junction_wall
from tubecad.design.model import BranchDesign, StiffenerChoice
from tubecad.design.stages import stage
from tubecad.design.wall import WallDesign

if TYPE_CHECKING:
    import build123d as bd

    from tubecad.design.result import BuildResult
    from tubecad.design.shell import ShellModel
    from tubecad.design.shop import ShopPackage
    from tubecad.export.registry import Exportable, OutputFormat
    from tubecad.fem.settings import MeshSettings
    from tubecad.junctions import BranchWall, JunctionWall
    from tubecad.shop.fabrication import Fabrication
    from tubecad.stiffeners.pad import Pad


@dataclass(frozen=True)
class JunctionDesign:
    """A main wall (``main``: its surface, net, wall and stiffeners; panels are not split
    round openings) with every branch of ``branches`` joined on: one solid, W = (A_o u B_o) -
    (A_i u B_i); ``reinforcement`` = (pressure, allowable stress) asks for each opening's
    area-replacement figures in the report.

    Args:
        main: the main wall's design (its ``wall`` required; ``panels`` are not split round openings).
        branches: the branches joined on (:class:`~tubecad.design.model.BranchDesign`).
        reinforcement: (pressure, allowable stress) for each opening's area-replacement
            figures in the report, or None.
    """

    main: WallDesign
    branches: tuple[BranchDesign, ...]
    reinforcement: tuple[float, float] | None = None

    #: what it is written as: CAD files, meshes and a PNG picture (no SVG projection, no polylines yet)
    WRITTEN_AS: ClassVar[frozenset[str]] = frozenset({"cad", "mesh", "png"})
    WHAT: ClassVar[str] = "a junction"
    #: a junction's shop package always has its branches' templates
    SHOP_NEEDS_PARTS: ClassVar[bool] = False

    @property
    def length_unit(self) -> str:
        """The main design's length unit."""
        return self.main.length_unit

    @property
    def stiffeners(self) -> StiffenerChoice | None:
        """The main wall's stiffeners (each branch says whether it has its own)."""
        return self.main.stiffeners

    def build(self, progress: Progress | None = None) -> BuildResult:
        """The junction solid, its pads and stiffeners, named and measured
        (:func:`build_junction`)."""
        return build_junction(self, progress)

    def shell_model(self, settings: MeshSettings) -> ShellModel:
        """The junction meshed for analysis with ``settings``
        (:func:`tubecad.design.shell.junction_shell_model`)."""
        from tubecad.design.junction_shell import junction_shell_model

        return junction_shell_model(self.main, self.branches, settings)

    def shop(self, fab: Fabrication, progress: Callable[[str], None] | None = None) -> ShopPackage:
        """The junction's shop package with the fabrication settings ``fab``
        (:func:`tubecad.design.junction_shop.junction_shop`)."""
        from tubecad.design.junction_shop import junction_shop

        return junction_shop(self.main, self.branches, fab, progress)

    @classmethod
    def analysis_ends(cls, given: str | None, default: str) -> str:
        """The pressure step's end condition (:func:`tubecad.design.shell.junction_ends`)."""
        from tubecad.design.shell import junction_ends

        return junction_ends(given, default)


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
        from tubecad.export.readback import FileAccuracyError, mesh_report, picture_pixels, readback_report

        if fmt.kind == "picture":
            return picture_pixels(tmp, fmt.name)
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
        if not junction.edges[name]:  # a blended branch's outer saddle: no edge of the wall
            continue
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
                "curves": saddle.kind,
                "fit_deviation": saddle.deviation,
                "edges_in_solid": len(junction.edges.get(name, [])),
                "edges_deviation": junction.deviation[name],
                "coverage": junction.coverage[name],
            }
            for name, saddle in junction.saddles.items()
            if name not in junction.blended
        },
    }
    if junction.blends:
        n = len(design.branches)
        report["blends"] = {
            ("blend" if n == 1 else f"blend_{k}"): {
                "radius": ball.radius,
                "contact_deviation": ball.deviation,
                "edges_in_solid": {
                    name: len(junction.edges.get(name, []))
                    for name in (("blend_main", "blend_branch") if n == 1 else (f"blend_main_{k}", f"blend_branch_{k}"))
                },
            }
            for k, ball in junction.blends.items()
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
    walls = branch_walls(design.branches)
    junction = junction_wall(design.main, design.branches, walls)
    pads = junction_pads(design.main, design.branches, junction, walls)
    stiffeners = junction_stiffeners(design.main, design.branches, walls, junction)
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
