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
from tubecad.brep.wall import WallSide
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.parts.axis_input import AxisLike, RadiusLike, as_axis
from tubecad.parts.engine import edge_map_of, layout_of


class _Shared:
    """What the part was built from, shared, not copied, by the part's copies (OCCT objects
    do not deep-copy): the JunctionWall and the named edges' indices in its edge map."""

    def __init__(self, junction: Any, named: dict[str, list[int]], tubes: list, pads: list) -> None:
        self.junction, self.named = junction, named
        self.tubes, self.pads = tubes, pads  # the shell model's (tubecad.fem.junction)

    def __deepcopy__(self, memo: dict) -> _Shared:
        return self


@dataclass(frozen=True)
class Branch:
    """A branch of ``radius`` (a number or a radius law along it) and ``length``, straight or
    curving by its natural equations ``k`` and ``tau`` (expressions in its arc length s), leaving the main axis at arc length ``at``, ``angle`` degrees from its tangent, on the
    side ``around`` degrees round it from its first stringer, ``offset`` sideways (a hillside
    nozzle); its wall ``thickness`` (None: the main's) placed ``side``; ``rings`` and
    ``stringers`` its net (counts, or arc lengths and angles; None: the main's stringers);
    with ``pad_thickness`` and ``pad_width`` a reinforcement pad round it
    (:func:`tubecad.stiffeners.pad.reinforcement_pad`), its own solid ``pad``."""

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


@dataclass
class JunctionPart:
    """What :func:`build_junction_part` made: the junction wall, the main tube and its net,
    the branches' walls and each pad (name, :class:`~tubecad.stiffeners.pad.Pad`)."""

    junction: Any
    main: Any
    main_layout: Any
    walls: list
    pads: list[tuple[str, Any]]


def build_junction_part(
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
) -> JunctionPart:
    """The junction of :class:`CurvatureJunction` (its arguments), for the build123d object
    and the CadQuery plugin alike: the main tube about ``axis``, each :class:`Branch` placed
    on it (:func:`tubecad.junctions.branch_surface`) with its wall and net, the walls joined
    (:func:`tubecad.junctions.build_branched_wall`) and each branch's pad
    (:func:`tubecad.stiffeners.pad.reinforcement_pad`: ``pad``, ``pad_k`` with several)."""
    from tubecad.brep.wall import wall_offsets
    from tubecad.junctions import BranchWall, branch_surface, build_branched_wall, saddle_name
    from tubecad.stiffeners.pad import pad_name, reinforcement_pad
    from tubecad.surface.canal import tube_or_canal

    main = tube_or_canal(as_axis(axis, bend_radius=bend_radius, normal=normal, closed=closed), radius)
    main_layout = layout_of(main, rings, stringers)
    walls = []
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
        walls.append(
            BranchWall(
                surface,
                thickness if branch.thickness is None else branch.thickness,
                branch.side,
                layout_of(surface, branch.rings, branch_stringers),
            )
        )
    junction = build_branched_wall(main, thickness, walls, main_side=side, main_layout=main_layout, tolerance=tolerance)
    pads = []
    main_out = wall_offsets(thickness, side)[1]
    for k, (branch, wall) in enumerate(zip(branches, walls)):
        if branch.pad_thickness is None and branch.pad_width is None:
            continue
        saddle = junction.saddles[saddle_name("saddle_outer", k, len(branches))].saddle
        pad = reinforcement_pad(
            main.offset(main_out),
            wall.surface.offset(wall.offsets()[1]),
            saddle,
            branch.pad_thickness if branch.pad_thickness is not None else float("nan"),
            branch.pad_width if branch.pad_width is not None else float("nan"),
            tolerance,
            key="pad",
        )
        pads.append((pad_name(k, len(branches)), pad))
    return JunctionPart(junction, main, main_layout, walls, pads)


class CurvatureJunction(bd.BasePartObject):
    """The wall of ``thickness`` round the tube of ``radius`` about ``axis`` (any axis
    :class:`~tubecad.parts.build123d_parts.CurvatureWall` takes) with every branch of
    ``branches`` (:class:`Branch`) joined on: one solid, W = (A_o u B_o) - (A_i u B_i).
    ``named_edges`` gives its named edges (``main_ring_03``, ``branch_stringer_05_inner``,
    ``saddle_outer``, ...; with several branches ``branch1_...`` and ``saddle_outer_1``) for
    every placed copy; ``saddle_outer`` and ``saddle_inner`` the saddles (one branch), and
    ``junction`` what was built and measured (:class:`~tubecad.junctions.JunctionWall`).
    The other arguments are ``CurvatureWall``'s."""

    _applies_to = [bd.BuildPart._tag]

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
        from tubecad.fem.junction import PadRegion, mid_surface_tubes

        junction, pads = built.junction, built.pads
        edge_map = edge_map_of(junction.shape.wrapped)
        named = {name: [edge_map.FindIndex(e.wrapped) for e in edges] for name, edges in junction.edges.items()}
        regions = [PadRegion(name, pad.s_range, pad.angles_deg, pad.thickness) for name, pad in pads]
        tubes = mid_surface_tubes(built.main, thickness, built.main_layout, built.walls, side=side)
        self._tubecad = _Shared(junction, named, tubes, regions)
        self._tolerance = tolerance
        wall = bd.Solid(junction.shape.wrapped)
        wall.label = "wall"
        self._pad_names = [name for name, _ in pads]
        pad_solids = []
        for name, pad in pads:
            solid = bd.Solid(pad.solid.wrapped)
            solid.label = name
            pad_solids.append(solid)
        part = bd.Part(bd.Compound([wall, *pad_solids]).wrapped) if pads else wall
        super().__init__(part=part, rotation=rotation, align=align, mode=mode)

    def shell_model(self, size: float | None = None, element: str = "S8R") -> Any:
        """The junction's shell model for a finite-element analysis
        (:func:`tubecad.fem.junction.junction_shell_mesh`: the walls' mid-surfaces joined on
        their saddle, meshed by gmsh, node sets ``saddle``, ``pad`` (``pad_0``... with several
        branches), ``main_start``, ``main_end``, ``branch_end``), elements of about ``size`` (default 2 pi r / 32 of
        the smallest tube), in the junction's own coordinates (as built, before ``rotation``,
        ``align`` and any placement). Solve it with :func:`tubecad.fem.analysis.solve` and
        :func:`tubecad.fem.junction_analysis.junction_step` (``tubes``: :attr:`shell_tubes`)."""
        from tubecad.fem.junction import junction_shell_mesh
        from tubecad.fem.settings import MeshSettings

        tubes, pads = self._tubecad.tubes, self._tubecad.pads
        settings = MeshSettings(element=element, size_along=size)
        return junction_shell_mesh(tubes[0], tubes[1:], pads=pads, settings=settings, tolerance=self._tolerance)

    @property
    def shell_tubes(self) -> list[Any]:
        """The shell model's tubes (:class:`tubecad.fem.junction.JunctionTube`: the main first)."""
        return list(self._tubecad.tubes)

    @property
    def pads(self) -> bd.ShapeList[bd.Solid]:
        """The pads of every placed copy, labelled ``pad`` (``pad_0``, ... with several branches)."""
        per_copy = 1 + len(self._pad_names)
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
        for copy in list(self.solids())[:: 1 + len(self._pad_names)]:  # each copy's wall, its pads after it
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
