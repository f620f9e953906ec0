"""The build123d object ``CurvatureJunction``: a main wall with branch walls joined on, one solid.

A part object as ``CurvatureWall`` is (builder and algebra mode, ``rotation``, ``align``,
``Locations``), over :func:`tubecad.junctions.build_branched_wall`. Each ``Branch`` says where
a straight branch leaves the main axis (:func:`tubecad.junctions.branch_surface`) and its
tube, wall and net. The part's named edges (both tubes' rings and stringers, the saddles
``saddle_outer`` and ``saddle_inner``) are kept as indices into the solid's edge map, so
every placed copy finds them::

    from build123d import Edge
    from tubecad import Branch, CurvatureJunction

    tee = CurvatureJunction(Edge.make_line((0, 0, 0), (300, 0, 0)), radius=50, thickness=4,
                            branches=[Branch(at=150, length=120, radius=30, thickness=3)])
    tee.saddle_outer  # the saddle's edges, labelled "saddle_outer"
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import build123d as bd

from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS
from tubecad.brep.wall import WallSide, as_wall_side
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.design.junction import JunctionDesign
from tubecad.design.model import BranchDesign, PadChoice, WallChoice
from tubecad.design.wall import WallDesign
from tubecad.parts.axis_input import AxisLike, RadiusLike, as_axis
from tubecad.parts.engine import edge_map_of, layout_of
from tubecad.parts.named_part import NamedSolidsPart


@dataclass(frozen=True)
class Branch:
    """A branch of ``radius`` (a number or a radius law along it) and ``length``, straight or
    curving by its natural equations ``k`` and ``tau`` (expressions in its arc length s), leaving the main axis at arc length ``at``, ``angle`` degrees from its tangent, on the
    side ``around`` degrees round it from its first stringer, ``offset`` sideways (a hillside
    nozzle); its wall ``thickness`` (None: the main's) placed ``side``; ``rings`` and
    ``stringers`` its net (counts, or arc lengths and angles; None: the main's stringers);
    with ``pad_thickness`` and ``pad_width`` a reinforcement pad round it
    (:func:`tubecad.stiffeners.pad.reinforcement_pad`), its own solid ``pad``.

    Args:
        at: the arc length on the main axis where the branch's axis leaves it.
        length: the branch's length along its own axis.
        radius: the branch tube's radius, or a radius law along it.
        thickness: its wall's thickness (None: the main's).
        angle: degrees between the branch and the main axis' tangent (90: perpendicular).
        around: degrees round the main axis from its first stringer, the side it leaves on.
        offset: sideways offset of the branch's axis from the main axis (a hillside nozzle).
        side: where its wall stands: ``centered``, ``inside`` or ``outside`` its surface.
        rings: its ring frames: a count or arc lengths.
        stringers: its stringers: a count or angles (None: as many as the main's).
        pad_thickness: a reinforcement pad's thickness (with ``pad_width``).
        pad_width: how far the pad reaches beyond the saddle (with ``pad_thickness``).
        k: the branch axis' curvature k(s), an expression in its arc length s ("0": straight).
        tau: its torsion tau(s), likewise.
        blend_radius: a crotch blend along its outer saddle: the rolling ball's radius
            (:mod:`tubecad.junctions.blend`; None: no blend).
    """

    at: float
    length: float
    radius: RadiusLike
    thickness: float | None = None
    angle: float = 90.0
    around: float = 90.0
    offset: float = 0.0
    side: WallSide = "centered"
    rings: int | Sequence[float] = 3
    stringers: int | Sequence[float] | None = None
    pad_thickness: float | None = None
    pad_width: float | None = None
    k: str = "0"
    tau: str = "0"
    blend_radius: float | None = None


@dataclass
class JunctionPart:
    """What :func:`build_junction_part` made: the ``design`` (as a spec's), the junction wall,
    the branches' walls and their pads by branch index (:class:`~tubecad.stiffeners.pad.Pad`)."""

    design: JunctionDesign
    junction: Any
    walls: list
    pads_by_branch: dict[int, Any]

    @property
    def pads(self) -> list[tuple[str, Any]]:
        """Each pad with its name (``pad``; ``pad_0``, ... with several branches)."""
        from tubecad.stiffeners.pad import pad_name

        return [(pad_name(k, len(self.walls)), pad) for k, pad in sorted(self.pads_by_branch.items())]

    @property
    def main(self) -> Any:
        """The main tube's exact surface."""
        return self.design.main.surface

    @property
    def main_layout(self) -> Any:
        """The main tube's net."""
        return self.design.main.layout


def junction_part_design(
    axis: AxisLike,
    radius: RadiusLike,
    thickness: float,
    branches: Sequence[Branch],
    *,
    side: WallSide = "centered",
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
    bend_radius: float | Sequence[float] | None = None,
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
) -> JunctionDesign:
    """The :class:`~tubecad.design.junction.JunctionDesign` of :class:`CurvatureJunction`'s
    arguments (the one a spec with [[branches]] makes): the main wall about ``axis``, each
    :class:`Branch` placed on it (:func:`tubecad.junctions.branch_surface`) with its wall,
    net and pad."""
    from tubecad.junctions import branch_surface
    from tubecad.surface.canal import tube_or_canal

    main = tube_or_canal(as_axis(axis, bend_radius=bend_radius, normal=normal, closed=closed), radius)
    main_layout = layout_of(main, rings, stringers)
    designs = []
    for branch in branches:
        surface = branch_surface(
            main,
            branch.at,
            branch.length,
            branch.radius,
            angle=branch.angle,
            around=branch.around,
            offset=branch.offset,
            k=branch.k,
            tau=branch.tau,
        )
        branch_stringers = branch.stringers if branch.stringers is not None else len(main_layout.stringers_deg)
        pad = None
        if branch.pad_thickness is not None or branch.pad_width is not None:  # the missing one refused by name
            nan = float("nan")
            pad = PadChoice(
                branch.pad_thickness if branch.pad_thickness is not None else nan,
                branch.pad_width if branch.pad_width is not None else nan,
            )
        wall = WallChoice(thickness if branch.thickness is None else branch.thickness, as_wall_side(branch.side))
        net = layout_of(surface, branch.rings, branch_stringers)
        designs.append(BranchDesign(surface, wall, net, pad, blend=branch.blend_radius))
    main_design = WallDesign(main, main_layout, tolerance, WallChoice(thickness, as_wall_side(side)))
    return JunctionDesign(main_design, tuple(designs))


def build_junction_part(
    axis: AxisLike,
    radius: RadiusLike,
    thickness: float,
    branches: Sequence[Branch],
    **options: Any,
) -> JunctionPart:
    """The junction of :class:`CurvatureJunction` (its arguments; ``options`` the keyword
    ones of :func:`junction_part_design`), for the build123d object and the CadQuery plugin
    alike: its design built as a spec's is (:mod:`tubecad.design.junction_parts`), the
    walls joined (:func:`tubecad.junctions.build_branched_wall`) and each branch's pad
    (:func:`tubecad.stiffeners.pad.reinforcement_pad`: ``pad``, ``pad_k`` with several)."""
    from tubecad.design.junction_parts import branch_walls, junction_pads, junction_wall

    design = junction_part_design(axis, radius, thickness, branches, **options)
    walls = branch_walls(design.branches)
    junction = junction_wall(design.main, design.branches, walls)
    return JunctionPart(design, junction, walls, junction_pads(design.main, design.branches, junction, walls))


class _JunctionEngine:
    """What the junction part was built from, shared (not copied) by its copies: its design,
    the :class:`~tubecad.junctions.JunctionWall`, the branches' walls and pads, and every
    named edge set as indices into the wall solid's edge map (``named``; the main tube's
    rings and stringers also as ``net``, as a wall part's)."""

    def __init__(self, built: JunctionPart) -> None:
        from tubecad.parts.engine import NetEdges, edge_map_of

        self.design, self.junction, self.walls = built.design, built.junction, built.walls
        self.pads = built.pads_by_branch
        edge_map = edge_map_of(built.junction.shape.wrapped)
        self.named = {
            name: [edge_map.FindIndex(e.wrapped) for e in edges] for name, edges in built.junction.edges.items()
        }
        self.surface, self.layout = self.design.main.surface, self.design.main.layout

        def lines(kind: str, suffix: str) -> dict[str, list[int]]:
            head = f"main_{kind}_"
            return {
                name.removeprefix("main_").removesuffix(suffix): found
                for name, found in sorted(self.named.items())
                if name.startswith(head) and name.endswith(suffix) and (suffix or not name.endswith("_inner"))
            }

        self.net = NetEdges(
            lines("ring", ""), lines("stringer", ""), lines("ring", "_inner"), lines("stringer", "_inner")
        )

    def __deepcopy__(self, memo: dict) -> _JunctionEngine:
        return self

    def report(self) -> dict[str, Any]:
        """The junction's measures (:func:`tubecad.design.junction.junction_report`):
        validity, counts, volume, each saddle's fit and edges, each pad."""
        from tubecad.design.junction import junction_report

        return junction_report(self.design, self.junction, self.walls, self.pads)


class CurvatureJunction(NamedSolidsPart):
    """The wall of ``thickness`` round the tube of ``radius`` about ``axis`` (any axis
    :class:`~tubecad.parts.build123d_parts.CurvatureWall` takes) with every branch of
    ``branches`` (:class:`Branch`) joined on: one solid, W = (A_o u B_o) - (A_i u B_i), and
    each branch's pad. A part as the others are: ``rings`` and ``stringers`` (the main
    tube's outer lines, a line cut by an opening as one wire each side of it; ``inner_rings``,
    ``inner_stringers``), ``surface`` (the main's exact surface), ``report``; ``saddles``
    the saddles' edges by name; ``named_edges`` every named edge set (``main_ring_03``,
    ``branch_stringer_05_inner``, ``saddle_outer``, ...; with several branches
    ``branch1_...`` and ``saddle_outer_1``) for every placed copy; ``junction`` what was
    built and measured (:class:`~tubecad.junctions.JunctionWall`); ``design`` the
    :class:`~tubecad.design.junction.JunctionDesign` (a spec with [[branches]] makes the
    same). The other arguments are ``CurvatureWall``'s.

    Args:
        axis: the main tube's axis (anything ``CurvatureWall`` takes).
        radius: the main tube's radius, or a radius law.
        thickness: the main wall's thickness (model units, > 0).
        branches: the :class:`Branch` es joined on.
        side: where the main wall stands: ``centered``, ``inside`` or ``outside`` its surface.
        rings: the main tube's ring frames: a count or arc lengths.
        stringers: the main tube's stringers: a count or angles in degrees.
        tolerance: the fit's tolerance, in model units.
        bend_radius: for a main axis given as points: the bends' radius (a pipe route).
        normal: for a main axis given as points or an edge: the first stringer's direction.
        closed: for a main axis given as points or an edge: whether it closes on itself.
        rotation: as for build123d's ``Box``.
        align: as for build123d's ``Box``; None keeps the part where its axis is.
        mode: as for build123d's ``Box``.
    """

    _tubecad: _JunctionEngine

    def __init__(
        self,
        axis: AxisLike,
        radius: RadiusLike,
        thickness: float,
        branches: Sequence[Branch],
        *,
        side: WallSide = "centered",
        rings: int | Sequence[float] = DEFAULT_RINGS,
        stringers: int | Sequence[float] = DEFAULT_STRINGERS,
        tolerance: float = DEFAULT_TOLERANCE,
        bend_radius: float | Sequence[float] | None = None,
        normal: Sequence[float] | None = None,
        closed: bool | None = None,
        rotation: bd.RotationLike = (0, 0, 0),
        align: bd.Align | tuple[bd.Align, bd.Align, bd.Align] | None = None,
        mode: bd.Mode = bd.Mode.ADD,
    ) -> None:
        built = build_junction_part(
            axis,
            radius,
            thickness,
            branches,
            side=side,
            rings=rings,
            stringers=stringers,
            tolerance=tolerance,
            bend_radius=bend_radius,
            normal=normal,
            closed=closed,
        )
        self._pad_names = [name for name, _ in built.pads]
        self._solid_names = ("wall", *self._pad_names)
        # the solids are labelled as the part's children (NamedSolidsPart), the part by its class
        wall = bd.Solid(built.junction.shape.wrapped)
        pad_solids = [bd.Solid(pad.solid.wrapped) for _, pad in built.pads]
        part = bd.Part(bd.Compound([wall, *pad_solids]).wrapped) if pad_solids else wall
        super().__init__(_JunctionEngine(built), part, rotation, align, mode)
        #: the inputs, kept as given (the axis as the Axis it became)
        self.axis = built.design.main.surface.axis
        self.radius, self.thickness, self.side, self.tolerance = radius, thickness, side, tolerance
        self.branches = tuple(branches)

    def _line_wires(self, edges: list[bd.Edge]) -> list[bd.Wire]:
        """A line's edges as wires: one per run of edges joined end to end (a line an opening
        cuts is two)."""
        return list(bd.Wire.combine(edges))

    @property
    def inner_rings(self) -> bd.ShapeList[bd.Wire]:
        """The main tube's ring frames on its inner surface (``ring_00``, ...)."""
        return self._wires(self._net.inner_rings)

    @property
    def inner_stringers(self) -> bd.ShapeList[bd.Wire]:
        """The main tube's stringers on its inner surface (``stringer_00``, ...)."""
        return self._wires(self._net.inner_stringers)

    def _named_lines(self) -> list[bd.Shape]:
        """Every named edge set (both tubes' nets, the saddles) as a labelled compound of its edges."""
        return [bd.Compound(label=name, children=list(edges)) for name, edges in self.named_edges.items()]

    @property
    def design(self) -> JunctionDesign:
        """What the part is: the main wall and the branches (as a spec's [[branches]])."""
        return self._tubecad.design

    @property
    def saddles(self) -> dict[str, bd.ShapeList[bd.Edge]]:
        """The saddles' edges by name (``saddle_outer``, ``saddle_inner``; with several
        branches ``saddle_outer_0``, ...), on every placed copy."""
        return {name: edges for name, edges in self.named_edges.items() if name.startswith("saddle_")}

    def shell_model(self, size: float | None = None, element: str = "S8R") -> Any:
        """The junction's shell model for a finite-element analysis
        (:func:`tubecad.fem.junction.junction_shell_mesh`: the walls' mid-surfaces joined on
        their saddle, meshed by gmsh, node sets ``saddle``, ``pad`` (``pad_0``... with several
        branches), ``main_start``, ``main_end``, ``branch_end``), elements of about ``size`` (default 2 pi r / 32 of
        the smallest tube), in the junction's own coordinates (as built, before ``rotation``,
        ``align`` and any placement). Solve it with :func:`tubecad.fem.analysis.solve` and
        :func:`tubecad.fem.junction_analysis.junction_step` (``tubes``: :attr:`shell_tubes`)."""
        from tubecad.fem.settings import MeshSettings

        return self.design.shell_model(MeshSettings(element=element, size_along=size)).mesh

    @property
    def shell_tubes(self) -> list[Any]:
        """The shell model's tubes (:class:`tubecad.fem.junction.JunctionTube`: the main first)."""
        from tubecad.design.junction_shell import junction_tubes

        return junction_tubes(self.design.main, self.design.branches)[0]

    @property
    def pads(self) -> bd.ShapeList[bd.Solid]:
        """The pads of every placed copy, labelled ``pad`` (``pad_0``, ... with several branches)."""
        per_copy = self._solids_per_copy
        solids = list(self.solids())
        out = []
        for start in range(0, len(solids), per_copy):
            for name, solid in zip(self._pad_names, solids[start + 1 : start + per_copy]):
                solid.label = name
                out.append(solid)
        return bd.ShapeList(out)

    @property
    def junction(self) -> Any:
        """The :class:`~tubecad.junctions.JunctionWall` built (unplaced): saddles, deviations."""
        return self._tubecad.junction

    @property
    def named_edges(self) -> dict[str, bd.ShapeList[bd.Edge]]:
        """Each name's edges on every placed copy of the part, labelled with the name."""
        from tubecad.occ_compat import as_edge

        named = self._tubecad.named
        out: dict[str, list[bd.Edge]] = {name: [] for name in sorted(named)}
        for copy in self._copies():  # each copy's wall (its pads after it)
            edge_map = edge_map_of(copy.wrapped)
            for name in out:
                for index in named[name]:
                    edge = bd.Edge(as_edge(edge_map.FindKey(index)))
                    edge.label = name
                    out[name].append(edge)
        return {name: bd.ShapeList(edges) for name, edges in out.items()}

    @property
    def saddle_outer(self) -> bd.ShapeList[bd.Edge]:
        """Where the branch's outer surface leaves the main's (one branch; else ``saddle_outer_0``...)."""
        return self.named_edges["saddle_outer"]

    @property
    def saddle_inner(self) -> bd.ShapeList[bd.Edge]:
        """Where the branch's bore leaves the main's (one branch; else ``saddle_inner_0``...)."""
        return self.named_edges["saddle_inner"]
