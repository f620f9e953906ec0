"""A branch joined to the main where their surfaces touch: the equal tee (issue 43).

Where a branch surface touches the main surface at its start (r = R on the outer or the bore
surface, :mod:`~tubecad.junctions.crotch`), OCCT's boolean intersects two faces that are
tangent at the crotch points: its result is valid in memory, but its section edges near the
crotch lie up to 4e-5 off the exact saddle (each point within 1e-7 of both faces may lie
sqrt(1e-7 r) off their crossing), with vertices 2e-6 off the crotch points, and a STEP file
read back fails the pre-boolean check there. So the union is made without intersecting the
faces:

1. both solids' faces are split by the exact saddle's edges (the two ellipse arcs or fitted
   curves through the crotch points, :mod:`~tubecad.junctions.crotch_edges`), which lie on
   both faces within the fit tolerance (OCCT's splitter: edge-on-face interference only);
2. each piece is kept or dropped by where a point inside it lies (OCCT's ``PointInFace``)
   against the other exact surface: a main piece inside the branch (in its span, nearer its
   axis than its radius) is the opening, a branch piece inside the main (its start and its
   start cap) is dropped;
3. the pieces kept are sewn (the two solids' copies of each saddle edge become one) into the
   union's closed shell;
4. the saddle edges are made again on the exact saddle (:func:`exact_saddle_edges`): the 3D
   curve is the saddle's own (an ellipse arc stays an ellipse arc), the pcurves the exact
   points projected on each face's surface (well-conditioned: one surface at a time), so a
   STEP file's 1e-7 holds them.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from OCP.BOPTools import BOPTools_AlgoTools3D
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepAlgoAPI import BRepAlgoAPI_Splitter
from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
from OCP.BRepTools import BRepTools, BRepTools_ReShape
from OCP.Geom import Geom_Curve, Geom_TrimmedCurve
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve, GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt, gp_Pnt2d
from OCP.IntTools import IntTools_Context
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Shape
from scipy.interpolate import make_interp_spline

from tubecad.brep.assembled import closed_solid
from tubecad.brep.operations import built
from tubecad.brep.properties import sub_shapes
from tubecad.core.errors import TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.fitting.nurbs import occ_curve_2d
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.occ_compat import IndexedDataMapOfShapeListOfShape, as_edge, as_face, shapes_in
from tubecad.surface.protocol import CurvatureLineSurface

#: the sewing's tolerance: the two copies of a saddle edge are the same curve, split at
#: vertices within the edges' 1e-7
SEWING = 1e-6
#: an edge of the union lies on a saddle where its points are within this of the saddle's curves
ON_SADDLE = 1e-6
#: points of the exact saddle along a remade edge (pcurves interpolated at every other one,
#: measured at the others)
REMADE_SAMPLES = 65
#: the pcurves' degree
DEGREE = 5

Pieces = Callable[..., list[TopoDS_Shape]]


def touching_union(
    base: TopoDS_Shape,
    base_surface: CurvatureLineSurface,
    branch: TopoDS_Shape,
    branch_surface: CurvatureLineSurface,
    saddle: list[TopoDS_Edge],
    key: str,
) -> tuple[TopoDS_Shape, Pieces]:
    """``base`` (the main tube's capped solid, or its union with other branches) united with
    the capped ``branch`` that touches it at the crotch, along the exact ``saddle`` edges
    (module docstring), and the history: a function from input edges to their pieces in the
    union (where they were split; deleted ones give none).

    Args:
        base: the main's solid (its surface ``base_surface`` where the branch stands).
        base_surface: the main's exact surface of that solid.
        branch: the branch's capped solid.
        branch_surface: its exact surface.
        saddle: the exact saddle's edges (on both surfaces), sharing the crotch vertices.
        key: the key a failure names.

    Returns:
        (the union's solid, the history).

    Raises:
        TubecadError: where the split pieces do not sew into one closed shell.
    """
    return split_and_sewn(
        [
            (base, saddle, lambda p: not _inside(branch_surface, p, strict_span=True)),
            (branch, saddle, lambda p: not _inside(base_surface, p, strict_span=False)),
        ],
        key,
    )


def split_and_sewn(
    parts: list[tuple[TopoDS_Shape, list[TopoDS_Edge], Callable[[np.ndarray], bool]]], key: str
) -> tuple[TopoDS_Shape, Pieces]:
    """The solid bounded by the pieces of several solids' faces: each solid's faces split by
    its edges (lying on them), the pieces whose inner point (OCCT's ``PointInFace``) the
    solid's test keeps, sewn (copies of an edge in two solids become one) into one closed
    shell; and the history (input edges -> their pieces).

    Args:
        parts: per solid: the solid, the edges its faces are split by, and the test of a
            piece's inner point (True: kept).
        key: the key a failure names.

    Returns:
        (the solid, the history).

    Raises:
        TubecadError: where the pieces kept do not sew into one closed shell.
    """
    context = IntTools_Context()
    kept: list[TopoDS_Face] = []
    splits = []
    for shape, edges, keep in parts:
        splitter = _split(shape, edges, key)
        splits.append(splitter)
        for face in map(as_face, sub_shapes(splitter.Shape(), TopAbs_FACE)):
            if keep(_point_in(face, context)):
                kept.append(face)
    sewing = BRepBuilderAPI_Sewing(SEWING)
    for face in kept:
        sewing.Add(face)
    sewing.Perform()
    faces = [as_face(f) for f in sub_shapes(sewing.SewedShape(), TopAbs_FACE)]
    if sewing.NbFreeEdges() or sewing.NbMultipleEdges() or len(faces) != len(kept):
        raise TubecadError(
            f"{key}: the branch's faces joined on the main's did not close: {sewing.NbFreeEdges()} free "
            f"and {sewing.NbMultipleEdges()} multiple edges after sewing them",
            key=key,
        )

    def pieces(*edges: TopoDS_Shape) -> list[TopoDS_Shape]:
        out: list[TopoDS_Shape] = []
        for edge in edges:
            for splitter in splits:
                if splitter.IsDeleted(edge):
                    continue
                modified = shapes_in(splitter.Modified(edge))
                for piece in modified or [edge]:
                    out.append(sewing.ModifiedSubShape(piece) if sewing.IsModifiedSubShape(piece) else piece)
        return out

    return closed_solid(faces), pieces


def _split(shape: TopoDS_Shape, edges: list[TopoDS_Edge], key: str) -> BRepAlgoAPI_Splitter:
    """``shape``'s faces split by ``edges`` lying on them (OCCT's General Fuse splitter)."""
    splitter = built(BRepAlgoAPI_Splitter(), [shape], edges)
    if not splitter.IsDone():
        raise TubecadError(f"{key}: OCCT could not split the faces by the equal tee's saddle", key=key)
    return splitter


def _point_in(face: TopoDS_Face, context: IntTools_Context) -> np.ndarray:
    """A point inside ``face`` (OCCT's ``BOPTools_AlgoTools3D::PointInFace``)."""
    point, uv = gp_Pnt(), gp_Pnt2d()
    BOPTools_AlgoTools3D.PointInFace_s(face, point, uv, context)
    return np.array(point.Coord())


def _inside(surface: CurvatureLineSurface, point: np.ndarray, *, strict_span: bool) -> bool:
    """Whether ``point`` lies inside ``surface`` (nearer its axis than its radius, at a ring of
    its span; ``strict_span``: not at an end ring, where a point beyond the end is clamped)."""
    at = surface_coordinates(surface, point[None, :])
    s0, s1 = surface.span
    s = float(at.s[0])
    within = s0 < s < s1 if strict_span else s0 <= s <= s1
    return bool(within and at.gap[0] < 0.0)


def exact_saddle_edges(shape: TopoDS_Shape, curves: list[Geom_Curve]) -> tuple[TopoDS_Shape, BRepTools_ReShape, float]:
    """``shape`` with its edges along an equal tee's saddle ``curves`` made again on them.

    Each edge whose points lie within ON_SADDLE of one of the ``curves`` and which bounds two
    faces gets that curve between its vertices' feet as its 3D curve (an ellipse arc stays one)
    and, as pcurves, REMADE_SAMPLES of its points projected on each face's surface,
    interpolated (degree 5) in the curve's parameter; the largest distance between the curve
    and a face along its pcurve, at the samples between the nodes, is measured.

    Args:
        shape: the union (or the wall) with the saddle's edges.
        curves: the exact saddle's curves (:class:`~tubecad.junctions.edges.SaddleEdge`).

    Returns:
        (the shape, the re-shaper (``.Value(old_edge)``), the largest distance measured).
    """
    reshape, largest = BRepTools_ReShape(), 0.0
    faces_of = IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, faces_of)
    projectors = []
    for curve in curves:
        projector = GeomAPI_ProjectPointOnCurve()
        projector.Init(curve, curve.FirstParameter(), curve.LastParameter())
        projectors.append((curve, projector))
    for i in range(1, faces_of.Extent() + 1):
        edge = as_edge(faces_of.FindKey(i).Oriented(TopAbs_FORWARD))
        if BRep_Tool.Degenerated_s(edge):
            continue
        faces: list[TopoDS_Face] = []
        for face in shapes_in(faces_of.FindFromIndex(i)):
            if not any(face.IsSame(f) for f in faces):
                faces.append(as_face(face))
        on = _on_curve(edge, projectors)
        if len(faces) != 2 or on is None:
            continue
        remade = _remade(edge, faces, *on)
        if remade is None:
            continue
        new, deviation = remade
        reshape.Replace(edge, new)
        largest = max(largest, deviation)
    return reshape.Apply(shape), reshape, largest


def _on_curve(
    edge: TopoDS_Edge, projectors: list[tuple[Geom_Curve, GeomAPI_ProjectPointOnCurve]]
) -> tuple[Geom_Curve, GeomAPI_ProjectPointOnCurve] | None:
    """The saddle curve ``edge`` lies on (9 of its points within ON_SADDLE), or None."""
    adaptor = BRepAdaptor_Curve(edge)
    probes = [adaptor.Value(float(t)) for t in np.linspace(adaptor.FirstParameter(), adaptor.LastParameter(), 9)]
    for curve, projector in projectors:
        if all(_foot(curve, projector, p)[1] <= ON_SADDLE for p in probes):
            return curve, projector
    return None


def _foot(curve: Geom_Curve, projector: GeomAPI_ProjectPointOnCurve, point: gp_Pnt) -> tuple[float, float]:
    """The parameter (in ``curve``'s range) and the distance of ``point``'s nearest point on
    ``curve``: OCCT's extrema, or an end of the curve where that is nearer (the extrema of a
    trimmed ellipse miss a point at its end: 104 off, measured)."""
    candidates = [(curve.FirstParameter(), point.Distance(curve.Value(curve.FirstParameter())))]
    candidates.append((curve.LastParameter(), point.Distance(curve.Value(curve.LastParameter()))))
    projector.Perform(point)
    for k in range(1, projector.NbPoints() + 1):
        candidates.append((_in_range(curve, projector.Parameter(k)), projector.Distance(k)))
    return min(candidates, key=lambda c: c[1])


def _remade(
    edge: TopoDS_Edge, faces: list[TopoDS_Face], curve: Geom_Curve, projector: GeomAPI_ProjectPointOnCurve
) -> tuple[TopoDS_Shape, float] | None:
    """The edge on ``curve`` between ``edge``'s vertices, with pcurves on both ``faces``, oriented
    as ``edge``; and its measured deviation. None where a projection fails."""
    first, last = TopExp.FirstVertex_s(edge), TopExp.LastVertex_s(edge)
    feet = [_foot(curve, projector, BRep_Tool.Pnt_s(vertex))[0] for vertex in (first, last)]
    if curve.IsPeriodic():  # a closed curve: the edge may run across its seam
        adaptor = BRepAdaptor_Curve(edge)
        middle = _foot(curve, projector, adaptor.Value(0.5 * (adaptor.FirstParameter() + adaptor.LastParameter())))[0]
        feet = _through(feet[0], feet[1], middle, curve.Period())
    flipped = feet[0] > feet[1]
    (t0, t1), (v0, v1) = (feet[::-1], (last, first)) if flipped else (feet, (first, last))
    t = np.linspace(t0, t1, REMADE_SAMPLES)
    points = np.array([curve.Value(float(x)).Coord() for x in t])
    pcurves, deviation = [], 0.0
    for face in faces:
        uv = _projected(face, points)
        if uv is None:
            return None
        pcurve = make_interp_spline(t[::2], uv[::2], k=DEGREE)
        surface = BRep_Tool.Surface_s(face)
        on_face = np.array([surface.Value(float(a), float(b)).Coord() for a, b in pcurve(t[1::2])])
        deviation = max(deviation, float(np.linalg.norm(on_face - points[1::2], axis=1).max()))
        deviation = max(
            deviation,
            float(
                np.linalg.norm(
                    np.array([surface.Value(*map(float, p)).Coord() for p in uv[::2]]) - points[::2], axis=1
                ).max()
            ),
        )
        pcurves.append(pcurve)
    tolerance = max(EDGE_TOLERANCE, 2.0 * deviation)
    builder, new = BRep_Builder(), TopoDS_Edge()
    builder.MakeEdge(new, Geom_TrimmedCurve(curve, float(t0), float(t1)), tolerance)
    builder.Add(new, v0.Oriented(TopAbs_FORWARD))
    builder.Add(new, v1.Oriented(TopAbs_REVERSED))
    builder.Range(new, float(t0), float(t1))
    for face, pcurve in zip(faces, pcurves):
        builder.UpdateEdge(new, occ_curve_2d(pcurve), face, tolerance)
        builder.Range(new, face, float(t0), float(t1))
    for vertex, at in ((v0, points[0]), (v1, points[-1])):
        gap = float(np.linalg.norm(np.array(BRep_Tool.Pnt_s(vertex).Coord()) - at))
        if gap > BRep_Tool.Tolerance_s(vertex):
            builder.UpdateVertex(vertex, 1.01 * gap)
    builder.SameParameter(new, True)
    builder.SameRange(new, True)
    return (new.Reversed() if flipped else new), deviation


def _through(t0: float, t1: float, middle: float, period: float) -> list[float]:
    """The ends t0, t1 (t1 moved by a period if need be) of the arc of a periodic curve that
    holds ``middle`` (a point of the edge between them), shorter than a period."""
    for shift in (0.0, period, -period):
        a, b = sorted((t0, t1 + shift))
        if b - a < period and any(a <= middle + k * period <= b for k in (-1, 0, 1)):
            return [t0, t1 + shift]
    return [t0, t1]


def _in_range(curve: Geom_Curve, t: float) -> float:
    """``t`` moved by whole periods into ``curve``'s range (a trimmed ellipse's parameter is
    periodic: a foot at the arc's end may come back a period away from it)."""
    first, last = curve.FirstParameter(), curve.LastParameter()
    basis = curve.BasisCurve() if isinstance(curve, Geom_TrimmedCurve) else curve
    if not basis.IsPeriodic():
        return t
    period = basis.Period()
    candidates = t + period * np.arange(-2, 3)
    slack = 1e-9 * period
    within = candidates[(candidates >= first - slack) & (candidates <= last + slack)]
    chosen = (
        within[0] if within.size else candidates[np.argmin(np.minimum(abs(candidates - first), abs(candidates - last)))]
    )
    return float(min(max(chosen, first), last))


def _projected(face: TopoDS_Face, points: np.ndarray) -> np.ndarray | None:
    """(u, v) of ``points`` projected on ``face``'s surface within its bounds, or None."""
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    projector = GeomAPI_ProjectPointOnSurf()
    projector.Init(surface, u0, u1, v0, v1)
    uv = []
    for p in points:
        projector.Perform(gp_Pnt(*map(float, p)))
        if not projector.NbPoints():
            return None
        uv.append(projector.LowerDistanceParameters())
    return np.array(uv)
