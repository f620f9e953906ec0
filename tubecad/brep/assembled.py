"""Solids assembled from faces that share their edges (BRep_Builder, no sewing, no boolean).

Every edge is made once, from one 3D curve that *is* an isoline of the faces it bounds,
and gets on each of those faces the straight pcurve u = const or s = const with the same
parameter (an exact circle, parameterised by angle, comes with its own pcurve); on a plane
its pcurve is the curve's projection (exact for a planar curve). Edges are therefore
same-parameter by construction and nothing has to be sewn.

:func:`strip_solid` builds the solid swept by a cross-section whose boundary is a cycle of
strips: strip k is ``surface_k`` over u in [u0_k, u1_k] (u0 > u1 runs it backwards) and the
common s range [s0, s1]; strip k ends (u = u1_k) where strip k + 1 starts (u = u0_{k+1}).
Its faces are the strips and two planar caps at s0 and s1. Orientation: with the cycle
counter-clockwise about the s direction, the outward normal of a strip is the traversal
direction x S_s, so its face is the natural one (S_u x S_s) exactly when u0 < u1.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRepLib import BRepLib
from OCP.Geom import Geom_BSplineSurface, Geom_Curve, Geom_Plane
from OCP.Geom2d import Geom2d_Curve, Geom2d_Line
from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Shell, TopoDS_Solid, TopoDS_Vertex, TopoDS_Wire

from tubecad.core.errors import TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.occ_compat import as_face, copy_of

#: edge, vertex and face tolerance: Precision::Confusion(); the geometry is far tighter
TOLERANCE = EDGE_TOLERANCE


def vertex(point: gp_Pnt, tolerance: float = TOLERANCE) -> TopoDS_Vertex:
    out = TopoDS_Vertex()
    BRep_Builder().MakeVertex(out, point, tolerance)
    return out


def edge(curve: Geom_Curve, v0: TopoDS_Vertex, v1: TopoDS_Vertex, t0: float, t1: float) -> TopoDS_Edge:
    """The edge of ``curve`` on [t0, t1] from v0 to v1."""
    maker = BRepBuilderAPI_MakeEdge(curve, v0, v1, t0, t1)
    if not maker.IsDone():
        raise TubecadError(f"OCCT could not make an edge on [{t0:g}, {t1:g}] (error {maker.Error()})")
    return maker.Edge()


def iso_pcurve(u: float | None = None, s: float | None = None) -> Geom2d_Line:
    """The parameter-plane line u = const (parameter s) or s = const (parameter u)."""
    if u is not None:
        return Geom2d_Line(gp_Pnt2d(u, 0.0), gp_Dir2d(0.0, 1.0))
    if s is None:
        raise TypeError("iso_pcurve: u or s")
    return Geom2d_Line(gp_Pnt2d(0.0, s), gp_Dir2d(1.0, 0.0))


def patch_face(
    surface: Geom_BSplineSurface,
    u0: float,
    u1: float,
    s0: float,
    s1: float,
    bottom: TopoDS_Edge,
    right: TopoDS_Edge,
    top: TopoDS_Edge,
    left: TopoDS_Edge,
    reverse: bool = False,
    ring_pcurves: tuple[Geom2d_Curve, Geom2d_Curve] | None = None,
    ring_tolerance: float = TOLERANCE,
) -> TopoDS_Face:
    """The face [u0, u1] x [s0, s1] (u0 < u1, s0 < s1) of ``surface`` bounded by its isolines:
    ``bottom``/``top`` at s0/s1 (parameter u), ``left``/``right`` at u0/u1 (parameter s).
    Edges whose 3D curve has another parameter (an exact circle, by angle) come with their
    ``ring_pcurves`` (bottom, top) in that parameter and the ``ring_tolerance`` they meet.
    The face lies on a Segment()-ed copy of the surface (fewer poles for everything after);
    its normal is S_u x S_s, or the opposite with ``reverse``."""
    builder = BRep_Builder()
    piece = copy_of(surface)
    piece.Segment(u0, u1, s0, s1)
    face = TopoDS_Face()
    builder.MakeFace(face, piece, TOLERANCE)
    if ring_pcurves is None:
        builder.UpdateEdge(bottom, iso_pcurve(s=s0), face, TOLERANCE)
        builder.UpdateEdge(top, iso_pcurve(s=s1), face, TOLERANCE)
    else:
        builder.UpdateEdge(bottom, ring_pcurves[0], face, ring_tolerance)
        builder.UpdateEdge(top, ring_pcurves[1], face, ring_tolerance)
    builder.UpdateEdge(left, iso_pcurve(u=u0), face, TOLERANCE)
    builder.UpdateEdge(right, iso_pcurve(u=u1), face, TOLERANCE)
    wire = TopoDS_Wire()
    builder.MakeWire(wire)  # counter-clockwise in (u, s)
    for e, orientation in (
        (bottom, TopAbs_FORWARD),
        (right, TopAbs_FORWARD),
        (top, TopAbs_REVERSED),
        (left, TopAbs_REVERSED),
    ):
        builder.Add(wire, e.Oriented(orientation))
    wire.Closed(True)
    builder.Add(face, wire)
    return as_face(face.Reversed()) if reverse else face


def plane_face(
    origin: np.ndarray, normal: np.ndarray, x_dir: np.ndarray, loops: Sequence[Sequence[tuple[TopoDS_Edge, bool]]]
) -> TopoDS_Face:
    """A planar face through ``origin`` with unit ``normal``, bounded by ``loops``: each a
    list of (edge, forward) in traversal order, the first counter-clockwise about the
    normal, the others (holes) clockwise."""
    builder = BRep_Builder()
    plane = Geom_Plane(gp_Ax3(gp_Pnt(*map(float, origin)), gp_Dir(*map(float, normal)), gp_Dir(*map(float, x_dir))))
    face = TopoDS_Face()
    builder.MakeFace(face, plane, TOLERANCE)
    for loop in loops:
        wire = TopoDS_Wire()
        builder.MakeWire(wire)
        for e, forward in loop:
            builder.Add(wire, e.Oriented(TopAbs_FORWARD if forward else TopAbs_REVERSED))
            BRepLib.BuildPCurveForEdgeOnPlane_s(e, face)
        wire.Closed(True)
        builder.Add(face, wire)
    return face


def c0_knots(surface: Geom_BSplineSurface, direction: str = "u") -> list[float]:
    """The u-knots (or v-knots) where ``surface`` is only C0 (multiplicity >= its degree in
    that direction): a face should end there (OCCT's pre-boolean check reports a face or
    edge across one)."""
    knot: Callable[[int], float]
    multiplicity: Callable[[int], int]
    if direction == "u":
        degree, count, knot, multiplicity = surface.UDegree(), surface.NbUKnots(), surface.UKnot, surface.UMultiplicity
    else:
        degree, count, knot, multiplicity = surface.VDegree(), surface.NbVKnots(), surface.VKnot, surface.VMultiplicity
    return [knot(i) for i in range(1, count + 1) if multiplicity(i) >= degree]


def shell_of(faces: Sequence[TopoDS_Face], closed: bool) -> TopoDS_Shell:
    """One shell of ``faces`` that share their edges (nothing is sewn)."""
    builder = BRep_Builder()
    shell = TopoDS_Shell()
    builder.MakeShell(shell)
    for face in faces:
        builder.Add(shell, face)
    shell.Closed(closed)
    return shell


def closed_solid(*shells: Sequence[TopoDS_Face]) -> TopoDS_Solid:
    """The solid bounded by closed shells of faces (oriented outward of the solid by the
    caller): one shell, or an outer shell and the shells of its cavities."""
    builder = BRep_Builder()
    solid = TopoDS_Solid()
    builder.MakeSolid(solid)
    for faces in shells:
        builder.Add(solid, shell_of(faces, closed=True))
    return solid


@dataclass(frozen=True)
class Strip:
    """One side of a swept cross-section: ``surface`` from u = u0 to u = u1 (either way)."""

    surface: Geom_BSplineSurface
    u0: float
    u1: float


@dataclass(frozen=True)
class CapPlane:
    """The plane of a cap: a point, the unit normal pointing along +s, an in-plane direction."""

    origin: np.ndarray
    normal: np.ndarray
    x_dir: np.ndarray


def strip_solid(
    strips: Sequence[Strip],
    s0: float,
    s1: float,
    caps: tuple[CapPlane, CapPlane],
    counter_clockwise: bool,
    cuts: Sequence[float] = (),
) -> tuple[TopoDS_Solid, list[TopoDS_Face]]:
    """The solid between s0 and s1 bounded by ``strips`` (a closed cycle, see the module) and
    planar caps in ``caps`` (at s0, s1); ``counter_clockwise``: the cycle runs counter-
    clockwise about +S_s. Each strip is cut into faces at the arc lengths ``cuts`` (where
    its surface is only C0 along s: a face must not run across). Returns the solid and its
    strip faces (strip by strip, each from s0 to s1)."""
    bands = [s0, *sorted(c for c in cuts if s0 < c < s1), s1]
    faces, crosses = _strip_faces(strips, bands, counter_clockwise, closed=False)
    n = len(strips)
    cap_faces = []
    for end, cap in enumerate(caps):
        outward = end == 1  # +s at s1, -s at s0
        along = counter_clockwise == outward  # traverse the cycle in order: counter-clockwise about the normal
        order = range(n) if along else range(n - 1, -1, -1)
        loop = [(crosses[k][0 if end == 0 else -1], (strips[k].u0 < strips[k].u1) == along) for k in order]
        normal = cap.normal if outward else -cap.normal
        cap_faces.append(plane_face(cap.origin, normal, cap.x_dir, [loop]))
    return closed_solid(faces + cap_faces), faces


def closed_strip_solid(
    strips: Sequence[Strip], s0: float, s1: float, counter_clockwise: bool, cuts: Sequence[float] = ()
) -> tuple[TopoDS_Solid, list[TopoDS_Face]]:
    """Like :func:`strip_solid` round a closed axis whose frame comes back unturned: the
    cross-section at s1 is the one at s0, so there are no caps; the edges at s0 close the
    strips at s1 too. A strip with no cut is cut at s_mid as well (no face meets itself
    along an edge). Returns the solid and its strip faces."""
    inner = sorted(c for c in cuts if s0 < c < s1) or [0.5 * (s0 + s1)]
    faces, _ = _strip_faces(strips, [s0, *inner, s1], counter_clockwise, closed=True)
    return closed_solid(faces), faces


def _strip_faces(
    strips: Sequence[Strip], bands: list[float], counter_clockwise: bool, closed: bool
) -> tuple[list[TopoDS_Face], list[list[TopoDS_Edge]]]:
    """The faces of every strip between consecutive arc lengths ``bands`` with shared edges,
    and crosses[k][c]: strip k's edge at bands[c] along +u (``closed``: the edges at
    bands[0] serve at bands[-1] as well)."""
    n = len(strips)
    rows = len(bands) - 1 if closed else len(bands)  # cross-sections with edges of their own
    at = [c % rows for c in range(len(bands))]  # the cross-section used at bands[c]
    corners = [[vertex(st.surface.Value(st.u0, s)) for s in bands[:rows]] for st in strips]
    # each long edge on its own band's piece of the surface: its curve then has no C0 knot
    # (e.g. a route's joint) outside the edge, which OCCT's continuity check would report
    longs = [
        [
            edge(
                _band(st, bands[b], bands[b + 1]).UIso(st.u0),
                corners[k][at[b]],
                corners[k][at[b + 1]],
                bands[b],
                bands[b + 1],
            )
            for b in range(len(bands) - 1)
        ]
        for k, st in enumerate(strips)
    ]
    faces, crosses = [], []
    for k, st in enumerate(strips):
        nxt = (k + 1) % n
        forward = st.u0 < st.u1
        lo, hi = (st.u0, st.u1) if forward else (st.u1, st.u0)
        own = []
        for c in range(rows):
            start, end = (corners[k][c], corners[nxt][c]) if forward else (corners[nxt][c], corners[k][c])
            own.append(edge(st.surface.VIso(bands[c]), start, end, lo, hi))
        crosses.append([own[at[c]] for c in range(len(bands))])
    for k, st in enumerate(strips):
        nxt = (k + 1) % n
        forward = st.u0 < st.u1
        lo, hi = (st.u0, st.u1) if forward else (st.u1, st.u0)
        for b in range(len(bands) - 1):
            left, right = (longs[k][b], longs[nxt][b]) if forward else (longs[nxt][b], longs[k][b])
            faces.append(
                patch_face(
                    st.surface,
                    lo,
                    hi,
                    bands[b],
                    bands[b + 1],
                    crosses[k][b],
                    right,
                    crosses[k][b + 1],
                    left,
                    reverse=forward != counter_clockwise,
                )
            )
    return faces, crosses


def _band(strip: Strip, s0: float, s1: float) -> Geom_BSplineSurface:
    """The strip's surface over s in [s0, s1] only (the whole surface when that is all of it)."""
    _, _, v0, v1 = strip.surface.Bounds()
    if s0 <= v0 and s1 >= v1:
        return strip.surface
    piece = copy_of(strip.surface)
    u0, u1, _, _ = strip.surface.Bounds()
    piece.Segment(u0, u1, s0, s1)
    return piece
