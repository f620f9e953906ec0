"""A branch wall on a main wall as one solid, its saddles named edges (issue 25).

With A_o, A_i the main's outer and inner tubes as capped solids (the main wall lies between
them), B_o, B_i the branch's, the junction's wall is

    W = (A_o u B_o) - (A_i u B_i),

made of two OCCT booleans: the fuses O = A_o u B_o and I = A_i u B_i each meet along one saddle
(``saddle_outer``: B_o's surface leaving A_o's; ``saddle_inner``: the bore B_i leaving A_i).
No face of one argument lies on a curved face of another: that is what makes booleans slow
and fragile (a wall fused with a wall and then bored would put the bore's tool on the wall's
own inner face: 18 s against 3 s measured). The cut O - I is not made by a boolean: no
curved faces of O and I cross (the tubes of one axis are concentric), so W is bounded by
O's faces, I's faces turned inside out, and at each open end the annulus between O's and
I's coplanar end discs (:func:`_between`: O's disc with I's boundary as its hole, every
edge shared). OCCT's cut intersected every pair of concentric faces whose boxes overlap
(2-4 s on the samples; the tee's wall 5.3 s -> 2.1 s without it, measured); it remains the
fallback where the discs do not pair up or the wall is not valid. The branch starts inside
the main bore (where :func:`~tubecad.junctions.saddle.saddle_curve` requires it) so its
start discs vanish in the fuse.

Every ring and stringer of the four tubes stays an edge of W where it lies on W, split where
it crosses an opening: the faces round the opening are the net's faces cut by the saddle.
The fuses' history (BRepAlgoAPI's Modified / IsDeleted) follows each net edge into W,
where its pieces are labelled ``main_ring_03``, ``main_stringer_05``, ``branch_ring_01``
(``..._inner`` on the inner surfaces; a face edge u = const that is no stringer, where the faces
are split at the circle's C0 knot, ``main_seam_00``). The saddle edges in W are OCCT's intersection curves made again on the fitted faces'
surfaces (:func:`~tubecad.brep.section_edges.refine_section_edges`: OCCT's are 2e-7 .. 5e-6
off their faces, which a STEP file cannot carry), not the fitted
:class:`~tubecad.junctions.edges.SaddleEdge` (which lies on the exact surfaces, within the fit
tolerance of the faces): each edge of W whose points all lie on the fitted saddle (within the
edge tolerance) is labelled with the saddle's name, and the largest distance of their points
from the exact saddle, the intersection of the exact surfaces (each point's foot on it by
Newton, :func:`~tubecad.junctions.saddle.saddle_distance`), is measured and reported.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Protocol

import build123d as bd
import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepAlgoAPI import BRepAlgoAPI_BooleanOperation, BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
from OCP.BRepTools import BRepTools_ReShape
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.GeomAbs import GeomAbs_BSplineCurve
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_FORWARD
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Shape

from tubecad.brep.layout import NetLayout
from tubecad.brep.operations import built
from tubecad.brep.properties import is_valid, sub_shapes
from tubecad.brep.section_edges import refine_section_edges
from tubecad.brep.solids import build_tube_solid
from tubecad.brep.wall import wall_offsets
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, EDGE_TOLERANCE
from tubecad.junctions.blend import BLEND_RINGS, BLEND_STRINGERS, RollingBall, rolling_ball
from tubecad.junctions.edges import SaddleEdge, wall_saddles
from tubecad.junctions.saddle import SaddleCurve
from tubecad.junctions.touching import exact_saddle_edges, touching_union
from tubecad.occ_compat import as_edge, as_face, as_wire, box_corners, shapes_in
from tubecad.surface.protocol import CurvatureLineSurface

#: points sampled on each edge of W to tell whether it lies on a saddle
EDGE_SAMPLES = 17
#: an edge is on a saddle where its points are within this many times its own tolerance (or the
#: fit tolerance) of it
ON_SADDLE = 10.0
#: points per knot span at which a saddle edge of W is measured against the exact saddle
PROBES_PER_SPAN = 8
#: the relative tolerance of the saddle edges' lengths (OCCT's default, 1e-6 of an ellipse arc, would
#: show as a gap in the coverage)
LENGTH_TOLERANCE = 1e-12
#: an edge of W lies on a blend's contact curve where its points are within this of it (the
#: contact edges are made again on the curve: round-off)
CONTACT = 1e-7


@dataclass
class JunctionWall:
    """The junction's wall ``shape`` (one valid solid), its named edges: the saddles
    (``edges['saddle_outer']``, ``edges['saddle_inner']``) and the pieces of each ring and
    stringer of both tubes (``edges['main_ring_03']``, ``edges['branch_stringer_05_inner']``),
    labelled build123d Edges of the shape; the fitted exact saddles ``saddles`` and, per saddle, the largest distance of
    the shape's saddle edges from the exact saddle (``deviation``) and their length over the
    exact saddle's (``coverage``, 1 when the edges make the whole closed curve)."""

    shape: bd.Solid
    edges: dict[str, list[bd.Edge]]
    saddles: dict[str, SaddleEdge]
    deviation: dict[str, float]
    coverage: dict[str, float]
    #: the crotch blends by branch index (:mod:`~tubecad.junctions.blend`): where one joins a
    #: branch, its outer saddle is no edge of the shape; the blend's contact curves are
    #: (``blend_main``, ``blend_branch``), and its rings (``blend_ring_03``)
    blends: dict[int, RollingBall] = field(default_factory=dict)

    @property
    def blended(self) -> set[str]:
        """The outer saddles a blend took the place of (no edges of the shape)."""
        return _blended_saddles(self.blends, len(self.saddles) // 2)  # two saddles a branch

    def outer_boundary(self, k: int, branches: int) -> SaddleCurve:
        """Where branch ``k`` (of ``branches``) leaves the main's outer surface: its blend's
        spine (whose main and branch parameters are the contact curves') where it has one,
        else its outer saddle.

        Args:
            k: the branch's index.
            branches: how many branches the junction has.

        Returns:
            The curve, sampled in both surfaces' parameters.
        """
        if k in self.blends:
            return self.blends[k].spine
        return self.saddles[saddle_name("saddle_outer", k, branches)].saddle

    @property
    def saddle_outer(self) -> list[bd.Edge]:
        return self.edges["saddle_outer"]

    @property
    def saddle_inner(self) -> list[bd.Edge]:
        return self.edges["saddle_inner"]


@dataclass(frozen=True)
class BranchWall:
    """A branch for :func:`build_branched_wall`: its surface, its wall and its net, and the
    radius of a crotch ``blend`` along its outer saddle (None: none)."""

    surface: CurvatureLineSurface
    thickness: float
    side: str = "centered"
    layout: NetLayout | None = None
    blend: float | None = None

    def offsets(self) -> tuple[float, float]:
        """(d_in, d_out): the branch wall's surfaces as offsets of its surface."""
        return wall_offsets(self.thickness, self.side)


def _blended_saddles(blends: dict[int, RollingBall], branches: int) -> set[str]:
    """The names of the outer saddles of the ``blends``' branches (of ``branches``)."""
    return {saddle_name("saddle_outer", k, branches) for k in blends}


def saddle_name(base: str, k: int, branches: int) -> str:
    """The name of branch ``k``'s saddle ``base`` (saddle_outer, saddle_inner) among
    ``branches``: the base alone with one branch, ``base_k`` with several."""
    return base if branches == 1 else f"{base}_{k}"


def build_junction_wall(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    main_thickness: float,
    branch_thickness: float,
    *,
    main_side: str = "centered",
    branch_side: str = "centered",
    main_layout: NetLayout | None = None,
    branch_layout: NetLayout | None = None,
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    key: str = "branches",
) -> JunctionWall:
    """The wall of ``branch`` (thickness, side) joined to the wall of ``main`` as one solid
    whose edges are both tubes' rings and stringers (``main_layout``, ``branch_layout``:
    default NetLayout.equal) and the two saddles, named. Refused naming ``key`` where the
    branch does not start inside the main bore and leave through its wall, where the
    surfaces are tangent on a saddle, or where OCCT's booleans give no single valid solid."""
    return build_branched_wall(
        main,
        main_thickness,
        [BranchWall(branch, branch_thickness, branch_side, branch_layout)],
        main_side=main_side,
        main_layout=main_layout,
        tolerance=tolerance,
        key=key,
    )


def build_branched_wall(
    main: CurvatureLineSurface,
    main_thickness: float,
    branches: list[BranchWall],
    *,
    main_side: str = "centered",
    main_layout: NetLayout | None = None,
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    key: str = "branches",
) -> JunctionWall:
    """:func:`build_junction_wall` with any number of branches, each with its own wall and
    net: W = (A_o u B1_o u B2_o ...) - (A_i u B1_i u B2_i ...). With one branch its edges are
    named ``branch_ring_01``, ``saddle_outer``...; with several ``branch1_ring_01``,
    ``saddle_outer_1``... (numbered from 0). Branches must not meet each other."""
    if not branches:
        raise ParameterError(f"{key}: at least one branch is needed", key=key)
    main_in, main_out = wall_offsets(main_thickness, main_side)
    main_layout = main_layout or NetLayout.equal(main)
    # name -> (its edges, True where they are on the outside's tubes (A_o, B_o), False the bore's)
    net: dict[str, tuple[list[TopoDS_Edge], bool]] = {}

    def solid(
        surface: CurvatureLineSurface, offset: float, rings: list[float], stringers: list[float], name: str, side: str
    ) -> TopoDS_Shape:
        """The capped tube of ``surface`` offset by ``offset``, its net edges registered."""
        tube = surface.offset(offset) if offset else surface
        built = build_tube_solid(tube, NetLayout.explicit(tube, rings, stringers), tolerance)
        patches, outside = built.patches[0], side == ""
        for i, ring in enumerate(patches.rings):
            net.setdefault(f"{name}_ring_{i:02d}{side}", ([], outside))[0].extend(ring)
        for j, stringer in enumerate(patches.stringers):
            net.setdefault(f"{name}_stringer_{j:02d}{side}", ([], outside))[0].extend(stringer)
        for k, seam in enumerate(patches.seams):  # a face split at the circle's C0 knot: no stringer
            net.setdefault(f"{name}_seam_{k:02d}{side}", ([], outside))[0].extend(seam)
        return built.shape.wrapped

    saddles: list[SaddleEdge] = []
    outers: list[tuple[TopoDS_Shape, _Joint | None]] = []
    inners: list[tuple[TopoDS_Shape, _Joint | None]] = []
    blends: dict[int, RollingBall] = {}
    for k, branch in enumerate(branches):
        tag = "" if len(branches) == 1 else str(k)
        outer, inner = wall_saddles(
            main,
            branch.surface,
            main_thickness,
            branch.thickness,
            main_side=main_side,
            branch_side=branch.side,
            tolerance=tolerance,
            key=key,
        )
        saddles += [replace(e, name=saddle_name(e.name, k, len(branches))) for e in (outer, inner)]
        b_in, b_out = branch.offsets()
        layout = branch.layout or NetLayout.equal(branch.surface)
        rings, stringers = list(layout.s_rings), list(layout.stringers_deg)
        for offset, side, edge, joined in ((b_out, "", outer, outers), (b_in, "_inner", inner, inners)):
            tube = solid(branch.surface, offset, rings, stringers, f"branch{tag}", side)
            # an equal tee's saddle (two curves through the crotch points): joined on it (touching.py)
            touches: _Joint | None = (
                _Touching(branch.surface.offset(offset), list(edge.edges)) if edge.saddle.corners else None
            )
            if side == "" and branch.blend is not None:  # a crotch blend along the outer saddle (blend.py)
                if edge.saddle.corners:
                    raise ParameterError(
                        f"{key}.blend.radius: a blend on an equal tee (the surfaces touch) is not made yet",
                        key=f"{key}.blend.radius",
                    )
                ball = rolling_ball(
                    main.offset(main_out), branch.surface.offset(offset), branch.blend, tolerance, key=f"{key}.blend"
                )
                blends[k] = ball
                net_of_ball = NetLayout.equal(ball.surface, BLEND_RINGS, BLEND_STRINGERS)
                ball_solid = solid(
                    ball.surface, 0.0, list(net_of_ball.s_rings), list(net_of_ball.stringers_deg), f"blend{tag}", ""
                )
                touches = _Blended(ball, ball_solid)
            joined.append((tube, touches))
    _check_openings_apart(main.offset(main_out), [e.saddle for e in saddles[::2]], key)
    rings, stringers = list(main_layout.s_rings), list(main_layout.stringers_deg)
    a_o = solid(main, main_out, rings, stringers, "main", "")
    a_i = solid(main, main_in, rings, stringers, "main", "_inner")
    outside, history_o = _union(a_o, main.offset(main_out), outers, key)
    bore, history_i = _union(a_i, main.offset(main_in), inners, key)
    between = _between(outside, bore)
    if between is not None:  # no boolean: the faces of both unions and the annular ends
        cut, history_w = between, _unchanged
        result, remade, _ = refine_section_edges(cut)
        if not is_valid(result):
            between = None
    if between is None:
        cut, history_w = _boolean(BRepAlgoAPI_Cut(), outside, [bore], key)
        result, remade, _ = refine_section_edges(cut)
    crotch_curves = [c for e in saddles if e.saddle.corners for c in e.curves]
    crotch_curves += [c for ball in blends.values() for c in ball.contacts]
    if crotch_curves:  # the equal tee's saddle edges on the exact saddle (touching.py)
        result, remade_on_saddle, _ = exact_saddle_edges(result, crotch_curves)
        history_r: BRepTools_ReShape | _Chained = _Chained(remade, remade_on_saddle)
    else:
        history_r = remade
    solids = bd.Shape.cast(result).solids()
    if len(solids) != 1 or (between is None and not is_valid(solids[0].wrapped)):
        raise TubecadError(
            f"{key}: OCCT's booleans gave {len(solids)} solids{'' if len(solids) != 1 else ', not valid'} "
            "for the branches on the main wall (do two branches meet, or one end outside the main wall?)",
            key=key,
        )
    shape = solids[0]
    edges = shape.edges()
    # each piece in W of a net edge -> its name; OCP's hash of a shape is its TShape's and
    # location's (either orientation), its == the Python object's, so IsSame decides
    labels: dict[int, list[tuple[TopoDS_Shape, str]]] = {}
    for name, (net_edges, in_outside) in net.items():
        first = history_o if in_outside else history_i
        for piece in history_w(*first(*net_edges)):
            piece = history_r.Value(piece)
            labels.setdefault(hash(piece), []).append((piece, name))
    named: dict[str, list[bd.Edge]] = {}
    for edge in edges:
        label = next((n for piece, n in labels.get(hash(edge.wrapped), []) if piece.IsSame(edge.wrapped)), None)
        if label is not None:
            edge.label = label
            named.setdefault(label, []).append(edge)
    blended = _blended_saddles(blends, len(branches))
    on_saddles, deviation, coverage = _name_saddle_edges(
        [e for e in edges if not e.label], [e for e in saddles if e.name not in blended]
    )
    for name in blended:  # the blend took the outer saddle's place: none of its edges is in W
        deviation[name], coverage[name] = 0.0, 0.0
    on_contacts = _name_contact_edges([e for e in edges if not e.label], blends, len(branches))
    return JunctionWall(
        shape, {**on_saddles, **on_contacts, **named}, {e.name: e for e in saddles}, deviation, coverage, blends
    )


class _Joint(Protocol):
    """How a branch's solid is joined to the main's without OCCT's fuse (touching.py, blend.py)."""

    def join(
        self, base: TopoDS_Shape, base_surface: CurvatureLineSurface, tube: TopoDS_Shape, key: str
    ) -> tuple[TopoDS_Shape, Callable[..., list[TopoDS_Shape]]]: ...


@dataclass(frozen=True)
class _Touching:
    """A branch surface that touches the main's at its start (an equal tee) and the exact
    saddle's edges it is joined along."""

    surface: CurvatureLineSurface
    saddle: list[TopoDS_Edge]

    def join(
        self, base: TopoDS_Shape, base_surface: CurvatureLineSurface, tube: TopoDS_Shape, key: str
    ) -> tuple[TopoDS_Shape, Callable[..., list[TopoDS_Shape]]]:
        return touching_union(base, base_surface, tube, self.surface, self.saddle, key)


@dataclass(frozen=True)
class _Blended:
    """A branch joined on through a crotch blend: the rolling ball and its tube's solid."""

    ball: RollingBall
    solid: TopoDS_Shape

    def join(
        self, base: TopoDS_Shape, base_surface: CurvatureLineSurface, tube: TopoDS_Shape, key: str
    ) -> tuple[TopoDS_Shape, Callable[..., list[TopoDS_Shape]]]:
        return self.ball.join(base, base_surface, tube, self.solid, key)


def _union(
    base: TopoDS_Shape,
    base_surface: CurvatureLineSurface,
    branches: list[tuple[TopoDS_Shape, _Joint | None]],
    key: str,
) -> tuple[TopoDS_Shape, Callable[..., list[TopoDS_Shape]]]:
    """``base`` united with the branches' solids, and the history (input edges -> their pieces):
    OCCT's fuse for the branches that cross the main surface, then each that touches it (along
    its exact saddle, :func:`~tubecad.junctions.touching.touching_union`) or has a blend
    (:meth:`~tubecad.junctions.blend.RollingBall.join`) joined by its own joint."""
    crossing = [tube for tube, joint in branches if joint is None]
    shape, history = _boolean(BRepAlgoAPI_Fuse(), base, crossing, key) if crossing else (base, _unchanged)
    for tube, joint in branches:
        if joint is not None:
            shape, more = joint.join(shape, base_surface, tube, key)
            history = _then(history, more)
    return shape, history


def _then(
    first: Callable[..., list[TopoDS_Shape]], second: Callable[..., list[TopoDS_Shape]]
) -> Callable[..., list[TopoDS_Shape]]:
    return lambda *edges: second(*first(*edges))


class _Chained:
    """Two re-shapers one after the other: ``.Value(edge)`` of the second of the first's."""

    def __init__(self, first: BRepTools_ReShape | _Chained, second: BRepTools_ReShape) -> None:
        self.first, self.second = first, second

    def Value(self, shape: TopoDS_Shape) -> TopoDS_Shape:  # OCCT's name
        return self.second.Value(self.first.Value(shape))


def _boolean(operation: BRepAlgoAPI_BooleanOperation, argument: TopoDS_Shape, tools: list[TopoDS_Shape], key: str):
    """``argument`` fused with or cut by ``tools`` (OCCT's booleans, in parallel), and the
    history: a function from input edges to the list of their pieces in the result (the
    edge itself where the operation left it as it was, none where it deleted it)."""
    built(operation, [argument], tools, parallel=True)
    if not operation.IsDone():
        raise TubecadError(f"{key}: OCCT's boolean of the branches and the main tube failed", key=key)

    def pieces(*edges: TopoDS_Shape) -> list[TopoDS_Shape]:
        out: list[TopoDS_Shape] = []
        for edge in edges:
            if operation.IsDeleted(edge):
                continue
            modified = shapes_in(operation.Modified(edge))
            out.extend(modified if modified else [edge])
        return out

    return operation.Shape(), pieces


def _unchanged(*edges: TopoDS_Shape) -> list[TopoDS_Shape]:
    return list(edges)


def _between(outside: TopoDS_Shape, bore: TopoDS_Shape) -> TopoDS_Shape | None:
    """W = ``outside`` - ``bore`` made of faces, no boolean: ``outside``'s faces but its end
    discs, ``bore``'s reversed (they face into the bore) but its end discs, and at each end the
    annulus between the coplanar outer and bore discs (the outer disc's boundary, the bore
    disc's as its hole, shared edges). None where the discs do not pair up (a branch through
    an end disc, a canal's cone-shaped end): then, as where the wall is not valid, OCCT's cut
    is used."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane

    from tubecad.brep.assembled import closed_solid

    def split(shape: TopoDS_Shape) -> tuple[list[TopoDS_Face], list[TopoDS_Face]]:
        faces: list[TopoDS_Face] = []
        discs: list[TopoDS_Face] = []
        for face in map(as_face, sub_shapes(shape, TopAbs_FACE)):
            (discs if BRepAdaptor_Surface(face).GetType() == GeomAbs_Plane else faces).append(face)
        return faces, discs

    if len(bd.Shape.cast(outside).solids()) != 1 or len(bd.Shape.cast(bore).solids()) != 1:
        return None
    out_faces, out_discs = split(outside)
    in_faces, in_discs = split(bore)
    if len(out_discs) != len(in_discs):
        return None
    annuli, left = [], list(in_discs)
    for disc in out_discs:
        plane = BRepAdaptor_Surface(disc).Plane()
        normal, origin = np.array(plane.Axis().Direction().Coord()), np.array(plane.Location().Coord())
        centre = _centre(disc)
        coplanar = [
            d
            for d in left
            if abs(abs(np.dot(normal, BRepAdaptor_Surface(d).Plane().Axis().Direction().Coord())) - 1.0) < 1e-12
            and abs(np.dot(_centre(d) - origin, normal)) < EDGE_TOLERANCE
        ]
        if not coplanar:
            return None
        inner = min(coplanar, key=lambda d: float(np.linalg.norm(_centre(d) - centre)))
        left.remove(inner)
        annuli.append(_annulus(disc, inner))
    return closed_solid(out_faces + annuli + [as_face(f.Reversed()) for f in in_faces])


def _centre(face: TopoDS_Face) -> np.ndarray:
    low, high = box_corners(face) or ((0.0,) * 3, (0.0,) * 3)
    return 0.5 * (np.array(low) + np.array(high))


def _annulus(outer: TopoDS_Face, inner: TopoDS_Face) -> TopoDS_Face:
    """The planar face of ``outer`` (as it is oriented) with ``inner``'s boundary as its hole:
    the hole's wire runs clockwise about ``outer``'s plane normal (the other way round from
    ``inner``'s own wire where the two planes' normals agree)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepLib import BRepLib
    from OCP.BRepTools import BRepTools

    forward = as_face(outer.Oriented(TopAbs_FORWARD))
    hole = BRepTools.OuterWire_s(as_face(inner.Oriented(TopAbs_FORWARD)))
    same = np.dot(
        BRepAdaptor_Surface(forward).Plane().Axis().Direction().Coord(),
        BRepAdaptor_Surface(inner).Plane().Axis().Direction().Coord(),
    )
    if same > 0:
        hole = as_wire(hole.Reversed())
    builder, face = BRep_Builder(), TopoDS_Face()
    builder.MakeFace(face, BRep_Tool.Surface_s(forward), BRep_Tool.Tolerance_s(forward))
    for wire in (BRepTools.OuterWire_s(forward), hole):
        for edge in sub_shapes(wire, TopAbs_EDGE):
            BRepLib.BuildPCurveForEdgeOnPlane_s(as_edge(edge), face)
        builder.Add(face, wire)
    return as_face(face.Oriented(outer.Orientation()))


def _name_saddle_edges(
    edges: list[bd.Edge], saddles: list[SaddleEdge]
) -> tuple[dict[str, list[bd.Edge]], dict[str, float], dict[str, float]]:
    """Label those of ``edges`` that lie on each saddle (within the limit of the fitted saddle
    edges); their largest distance from the exact saddle, the intersection of the exact
    surfaces (:meth:`SaddleEdge.exact_distance`), and their total length over the saddle's."""
    named: dict[str, list[bd.Edge]] = {s.name: [] for s in saddles}
    found: dict[str, list[BRepAdaptor_Curve]] = {s.name: [] for s in saddles}
    length = {s.name: 0.0 for s in saddles}
    projectors: dict[str, list[GeomAPI_ProjectPointOnCurve]] = {}
    for saddle in saddles:
        projectors[saddle.name] = []
        for piece in saddle.curves:
            projector = GeomAPI_ProjectPointOnCurve()
            projector.Init(piece, piece.FirstParameter(), piece.LastParameter())
            projectors[saddle.name].append(projector)
    for edge in edges:
        curve = BRepAdaptor_Curve(edge.wrapped)
        t = np.linspace(curve.FirstParameter(), curve.LastParameter(), EDGE_SAMPLES)
        order = np.argsort(np.abs(np.arange(EDGE_SAMPLES) - EDGE_SAMPLES // 2), kind="stable")  # middle first
        points = [curve.Value(float(t[i])) for i in order]
        for saddle in saddles:
            # the faces' intersection lies within about the fit tolerance of the exact saddle
            limit = ON_SADDLE * max(BRep_Tool.Tolerance_s(edge.wrapped), EDGE_TOLERANCE, saddle.tolerance)
            if _near(projectors[saddle.name], points, limit):
                edge.label = saddle.name
                named[saddle.name].append(edge)
                found[saddle.name].append(curve)
                length[saddle.name] += GCPnts_AbscissaPoint.Length_s(curve, LENGTH_TOLERANCE)
                break
    deviation = {s.name: _exact_deviation(s, found[s.name]) for s in saddles}
    coverage = {
        s.name: length[s.name]
        / sum(GCPnts_AbscissaPoint.Length_s(BRepAdaptor_Curve(e), LENGTH_TOLERANCE) for e in s.edges)
        for s in saddles
    }
    return named, deviation, coverage


def _name_contact_edges(
    edges: list[bd.Edge], blends: dict[int, RollingBall], branches: int
) -> dict[str, list[bd.Edge]]:
    """Label those of ``edges`` that lie on a blend's contact curves (within CONTACT of them):
    ``blend_main`` and ``blend_branch`` (``..._k`` with several branches)."""
    named: dict[str, list[bd.Edge]] = {}
    for k, ball in blends.items():
        tag = "" if branches == 1 else f"_{k}"
        for name, curve in zip((f"blend_main{tag}", f"blend_branch{tag}"), ball.contacts):
            projector = GeomAPI_ProjectPointOnCurve()
            projector.Init(curve, curve.FirstParameter(), curve.LastParameter())
            named[name] = []
            for edge in edges:
                adaptor = BRepAdaptor_Curve(edge.wrapped)
                t = np.linspace(adaptor.FirstParameter(), adaptor.LastParameter(), EDGE_SAMPLES)
                if not edge.label and _near([projector], [adaptor.Value(float(x)) for x in t], CONTACT):
                    edge.label = name
                    named[name].append(edge)
    return named


def _near(projectors: list[GeomAPI_ProjectPointOnCurve], points: list[gp_Pnt], limit: float) -> bool:
    """Whether every one of ``points`` lies within ``limit`` of one of the projectors' curves
    (False as soon as one does not: most edges, at the first point)."""
    for point in points:
        closest = math.inf
        for projector in projectors:
            projector.Perform(point)
            if projector.NbPoints():
                closest = min(closest, projector.LowerDistance())
        if closest > limit:
            return False
    return True


def _probes(curve: BRepAdaptor_Curve) -> np.ndarray:
    """Where an edge of W on a saddle is measured: evenly, PROBES_PER_SPAN points to its
    shortest knot span (a B-spline interpolant is exact at its nodes and farthest off between
    them, which samples at the nodes alone would hide; its end spans, without interior knots,
    hold nodes too), or to each of EDGE_SAMPLES - 1 even steps on another curve."""
    first, last = curve.FirstParameter(), curve.LastParameter()
    spans = EDGE_SAMPLES - 1
    if curve.GetType() == GeomAbs_BSplineCurve:
        spline = curve.BSpline()
        knots = np.unique(np.clip([spline.Knot(i) for i in range(1, spline.NbKnots() + 1)], first, last))
        if len(knots) > 1:
            spans = max(spans, math.ceil((last - first) / float(np.diff(knots).min())))
    return np.linspace(first, last, PROBES_PER_SPAN * spans + 1)


def _exact_deviation(saddle: SaddleEdge, found: list[BRepAdaptor_Curve]) -> float:
    """The largest distance of the edges ``found`` on ``saddle`` from the exact saddle, at
    their probes (0 without any); each probe's foot looked for first at u_B of the exact
    saddle's sample nearest to it."""
    if not found:
        return 0.0
    from scipy.spatial import cKDTree

    points = np.array([curve.Value(float(t)).Coord() for curve in found for t in _probes(curve)])
    _, nearest = cKDTree(saddle.saddle.points).query(points)
    return float(saddle.exact_distance(points, saddle.saddle.branch_u[nearest]).max())


def _check_openings_apart(outer: CurvatureLineSurface, saddles: list[SaddleCurve], key: str) -> None:
    """Refuse two branches whose openings in the main's outer surface ``outer`` meet (their
    outer saddles, :func:`~tubecad.junctions.placement.opening_clearance`): the branches would
    cut into each other, which the union would silently make one odd opening of."""
    from tubecad.junctions.placement import region_clearance, unrolled_opening

    regions = [unrolled_opening(outer, saddle) for saddle in saddles]
    for k in range(len(saddles)):
        for m in range(k + 1, len(saddles)):
            if region_clearance(outer, regions[k], regions[m]) <= 0.0:
                overlap = regions[k].intersection(regions[m]).area
                raise ParameterError(
                    f"{key}: the openings of branches {k} and {m} meet in the main tube's outer surface "
                    f"(they overlap over {overlap:.4g} square units): move them apart (at, around) or make them "
                    "smaller",
                    key=key,
                )
