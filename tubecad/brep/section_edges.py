"""Edges where two faces meet, as OCCT's booleans leave them, made again on the two faces'
own surfaces to round-off (issue 25).

A boolean's section edge is an approximation: its 3D curve and its two pcurves agree only
within the edge's tolerance (1e-7 .. 5e-6 on a junction's saddle). In memory the edge carries
that tolerance and every check passes; a STEP file keeps no edge tolerance, the reader gives
the edge 1e-7, and FreeCAD's pre-boolean check (BOPAlgo_ArgumentAnalyzer, CurveOnSurfaceMode)
then finds the curve off its surfaces. Here such an edge is replaced by one whose curve and
pcurves are interpolants of the exact intersection of the two surfaces S1(u1, v1) = S2(u2, v2):

- the parameter tau is whichever of u1, v1, u2, v2 runs strictly monotonically along the edge
  (round a branch, its stringer angle): the intersection is then a smooth function of tau (as
  smooth as the surfaces), so interpolants converge at their full order; fixing tau leaves
  three equations S1 - S2 = 0 in three unknowns, solved by Newton's method with the surfaces'
  first derivatives (J = [dS1/du1, dS1/dv1, -dS2/du2, -dS2/dv2] less tau's column);
- the end points: Newton on S1 - S2 = 0 and (S1 - V).T = 0, the intersection point in the plane
  through the vertex V normal to the old edge: the vertices stay as they are;
- the 3D curve and both pcurves are degree-5 interpolants at 2^k + 1 values of tau (The NURBS
  Book, section 9.2.1), one parameterisation for all three (same parameter by construction);
  k grows until, at the midpoints, the curve is within ``target`` of the exact intersection
  and of both surfaces along its pcurves.

An edge is replaced only where the new one is measured within a tenth of the old tolerance;
otherwise (no monotonic parameter, a corner in the intersection, tangent surfaces) the old
edge stays and is reported.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepTools import BRepTools_ReShape
from OCP.Geom import Geom_BSplineSurface
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Edge, TopoDS_Shape
from scipy.interpolate import BSpline, make_interp_spline

from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.fitting.nurbs import SurfaceArrays, occ_curve_2d, occ_curve_3d
from tubecad.occ_compat import IndexedDataMapOfShapeListOfShape, as_edge, as_face, downcast, shapes_in

#: the interpolants' degree
DEGREE = 5
#: the fewest and the most intervals of tau along one edge
FIRST_INTERVALS, MOST_INTERVALS = 16, 512
#: samples of the old edge that pick the parameter tau and start Newton
TABLE = 65
#: Newton steps at most; it stops when the step is below round-off of the parameters
NEWTON_STEPS = 30
#: Newton's point is the intersection where the two surfaces' points are this close (relative)
ROUND_OFF = 1e-11


@dataclass
class SectionEdgeReport:
    """What :func:`refine_section_edges` did: per replaced edge its old tolerance and the new
    edge's measured deviation; the edges left as they were, with the reason."""

    replaced: list[tuple[float, float]] = field(default_factory=list)
    kept: list[str] = field(default_factory=list)

    @property
    def largest_deviation(self) -> float:
        return max((new for _, new in self.replaced), default=0.0)


def refine_section_edges(
    shape: TopoDS_Shape, *, above: float = EDGE_TOLERANCE, target: float = 1e-9
) -> tuple[TopoDS_Shape, BRepTools_ReShape, SectionEdgeReport]:
    """``shape`` with every edge whose tolerance exceeds ``above`` and which joins two faces on
    different surfaces made again on those surfaces (see the module's text), the re-shaper
    (``.Value(old_edge)`` gives an edge's replacement) and a report."""
    faces_of = IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, faces_of)
    reshape, report = BRepTools_ReShape(), SectionEdgeReport()
    surfaces = _Surfaces()
    for i in range(1, faces_of.Extent() + 1):
        edge = as_edge(faces_of.FindKey(i))
        old = BRep_Tool.Tolerance_s(edge)
        if old <= above or BRep_Tool.Degenerated_s(edge):
            continue
        faces: list[TopoDS_Shape] = []
        for face in shapes_in(faces_of.FindFromIndex(i)):
            if not any(face.IsSame(f) for f in faces):
                faces.append(face)
        if len(faces) != 2:
            report.kept.append(f"an edge on {len(faces)} faces")
            continue
        face_1, face_2 = as_face(faces[0]), as_face(faces[1])
        pair = _Pair(surfaces.of(face_1), surfaces.of(face_2))
        made = _remade(as_edge(edge.Oriented(TopAbs_FORWARD)), face_1, face_2, pair, target)
        if isinstance(made, str):
            report.kept.append(made)
            continue
        new, deviation = made
        if deviation > old / 10:
            report.kept.append(f"the intersection holds only {deviation:.1e} against the edge's {old:.1e}")
            continue
        reshape.Replace(edge.Oriented(TopAbs_FORWARD), new)
        report.replaced.append((old, deviation))
    if not report.replaced:
        return shape, reshape, report
    return reshape.Apply(shape), reshape, report


# --- one edge ----------------------------------------------------------------------------------


class _Surface:
    """A face's surface evaluated at many (u, v) at once with its first derivatives: a
    B-spline one from its own poles, weights and knots
    (:meth:`tubecad.fitting.nurbs.SurfaceArrays.points_d1`), any other through OCCT point by
    point."""

    def __init__(self, face) -> None:
        self.occt = BRep_Tool.Surface_s(face)
        bspline = self.occt.DynamicType().Name() == "Geom_BSplineSurface"
        self.spline = SurfaceArrays.from_occ(downcast(self.occt, Geom_BSplineSurface)) if bspline else None

    def d1(self, uv: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(S, S_u, S_v) at the rows of ``uv``, each (rows, 3)."""
        if self.spline is not None:
            # Newton may step off a rational patch (a weight of 0 there): inf or nan, which the
            # caller takes as no convergence, not a warning to the user
            with np.errstate(divide="ignore", invalid="ignore"):
                return self.spline.points_d1(uv)
        out = np.empty((3, len(uv), 3))
        p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
        for m, (u, v) in enumerate(uv.tolist()):
            self.occt.D1(u, v, p, du, dv)
            out[0, m], out[1, m], out[2, m] = p.Coord(), du.Coord(), dv.Coord()
        return out[0], out[1], out[2]


class _Surfaces:
    """Each face's :class:`_Surface`, read once (a face bounds several section edges)."""

    def __init__(self) -> None:
        self._made: list[tuple[TopoDS_Shape, _Surface]] = []

    def of(self, face) -> _Surface:
        for known, surface in self._made:
            if known.IsSame(face):
                return surface
        self._made.append((face, _Surface(face)))
        return self._made[-1][1]


class _Pair:
    """The two surfaces S1(u1, v1), S2(u2, v2) of an edge's faces."""

    def __init__(self, surface_1: _Surface, surface_2: _Surface) -> None:
        self.surface_1, self.surface_2 = surface_1, surface_2

    def evaluate(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """At each row x = (u1, v1, u2, v2): S1, S2 and the Jacobian [dS1/du1, dS1/dv1, -dS2/du2,
        -dS2/dv2] of S1 - S2 (rows, 3, 4)."""
        p1, a1, b1 = self.surface_1.d1(x[:, :2])
        p2, a2, b2 = self.surface_2.d1(x[:, 2:])
        return p1, p2, np.stack([a1, b1, -a2, -b2], axis=2)

    def solve(self, x: np.ndarray, fixed: int | None = None, planes: tuple | None = None) -> np.ndarray | None:
        """Newton's method from each row of ``x`` for S1 = S2, with x[:, fixed] kept, or with S1
        in the plane (points, unit normals) ``planes``; None unless every row reaches it."""
        x = np.array(x, dtype=float)
        scale = max(1.0, float(np.abs(x).max()))
        keep = [k for k in range(4) if k != fixed]
        for _ in range(NEWTON_STEPS):
            p1, p2, jac = self.evaluate(x)
            f = p1 - p2
            if planes is not None:
                point, normal = planes
                f = np.concatenate([f, np.einsum("ij,ij->i", p1 - point, normal)[:, None]], axis=1)
                row = np.einsum("ij,ijk->ik", normal, jac[:, :, :2])
                jac = np.concatenate([jac, np.pad(row, ((0, 0), (0, 2)))[:, None, :]], axis=1)
                step = np.linalg.solve(jac, -f[..., None])[..., 0]
            else:
                step = np.zeros_like(x)
                step[:, keep] = np.linalg.solve(jac[:, :, keep], -f[..., None])[..., 0]
            x += step
            if np.abs(step).max() <= 4 * np.finfo(float).eps * scale:
                break
        p1, p2, _ = self.evaluate(x)
        gap = np.linalg.norm(p1 - p2, axis=1)
        ok = np.isfinite(gap).all() and (gap <= ROUND_OFF * np.maximum(1.0, np.abs(p1).max(axis=1))).all()
        return x if ok else None


def _table(edge: TopoDS_Edge, face_1, face_2) -> tuple[np.ndarray, np.ndarray]:
    """The old edge sampled: the four surface parameters (its pcurves), its points."""
    first, last = BRep_Tool.Range_s(edge)
    c1 = BRep_Tool.CurveOnSurface_s(edge, face_1, 0.0, 0.0)
    c2 = BRep_Tool.CurveOnSurface_s(edge, face_2, 0.0, 0.0)
    curve = BRep_Tool.Curve_s(edge, 0.0, 0.0)
    t = np.linspace(first, last, TABLE).tolist()
    params = np.array([c1.Value(x).Coord() + c2.Value(x).Coord() for x in t])
    points = np.array([curve.Value(x).Coord() for x in t])
    return params, points


def _monotone(params: np.ndarray) -> tuple[int, float] | None:
    """The surface parameter that runs most evenly and strictly monotonically along the edge,
    and its direction (+1, -1); None if none does."""
    best: tuple[float, int, float] | None = None
    for k in range(4):
        step = np.diff(params[:, k])
        if np.all(step > 0) or np.all(step < 0):
            evenness = float(np.abs(step).min() / np.abs(step).max())
            if best is None or evenness > best[0]:
                best = (evenness, k, float(np.sign(step[0])))
    return None if best is None else (best[1], best[2])


def _remade(edge: TopoDS_Edge, face_1, face_2, pair: _Pair, target: float) -> tuple[TopoDS_Edge, float] | str:
    params, points = _table(edge, face_1, face_2)
    chosen = _monotone(params)
    if chosen is None:
        return "no surface parameter runs monotonically along the edge"
    k, sign = chosen
    vertices = [TopExp.FirstVertex_s(edge), TopExp.LastVertex_s(edge)]
    at = np.array([BRep_Tool.Pnt_s(v).Coord() for v in vertices])
    normal = np.array([points[1] - points[0], points[-1] - points[-2]])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    ends = pair.solve(params[[0, -1]], planes=(at, normal))
    if ends is None:
        return "Newton did not reach the intersection at an end"
    reached = 0.5 * np.add(*pair.evaluate(ends)[:2])
    if any(np.linalg.norm(reached[j] - at[j]) > BRep_Tool.Tolerance_s(vertices[j]) for j in (0, 1)):
        # where the surfaces touch (an equal tee's crotch) the intersection near the vertex is
        # ill-conditioned: Newton's end may leave the vertex's tolerance, which would break the solid
        return "the intersection's end is off its vertex (the surfaces touch there)"
    low, high = sign * ends[:, k]  # the new edge's parameter: sigma = sign * x[k]
    if not high > low:
        return "the ends' parameters are not in order"
    order = np.argsort(sign * params[:, k])
    known_sigma, known = sign * params[order, k], params[order]  # where Newton starts from
    intervals = FIRST_INTERVALS
    sigma = np.linspace(low, high, 2 * intervals + 1)
    exact = np.empty((len(sigma), 4))
    exact[[0, -1]] = ends
    while True:
        new = slice(1, -1) if intervals == FIRST_INTERVALS else slice(1, None, 2)
        guess = np.column_stack([np.interp(sigma[new], known_sigma, known[:, j]) for j in range(4)])
        guess[:, k] = sign * sigma[new]
        found = pair.solve(guess, fixed=k)
        if found is None:
            return "Newton did not reach the intersection"
        exact[new] = found
        p1, p2, _ = pair.evaluate(exact)
        at_points = 0.5 * (p1 + p2)
        curve = make_interp_spline(sigma[::2], at_points[::2], k=DEGREE)
        pcurve_1 = make_interp_spline(sigma[::2], exact[::2, :2], k=DEGREE)
        pcurve_2 = make_interp_spline(sigma[::2], exact[::2, 2:], k=DEGREE)
        mid = sigma[1::2]
        on_curve = curve(mid)
        q1, q2, _ = pair.evaluate(np.concatenate([pcurve_1(mid), pcurve_2(mid)], axis=1))
        deviation = max(
            float(np.linalg.norm(on_curve - at_points[1::2], axis=1).max()),
            float(np.linalg.norm(q1 - on_curve, axis=1).max()),
            float(np.linalg.norm(q2 - on_curve, axis=1).max()),
        )
        if deviation <= target or intervals >= MOST_INTERVALS:
            break
        # twice the intervals: the samples so far are the new nodes, Newton adds the midpoints
        intervals *= 2
        known_sigma, known = sigma, exact
        sigma = np.linspace(low, high, 2 * intervals + 1)
        exact = np.empty((len(sigma), 4))
        exact[::2] = known
    return section_edge(edge, face_1, face_2, curve, pcurve_1, pcurve_2, deviation), deviation


def section_edge(
    old: TopoDS_Edge, face_1, face_2, curve: BSpline, pcurve_1: BSpline, pcurve_2: BSpline, deviation: float
) -> TopoDS_Edge:
    """An edge between two faces made of ``curve`` (3D) and its pcurves on ``face_1`` and
    ``face_2`` (scipy B-splines of one parameter), with ``old``'s vertices and a tolerance of twice
    ``deviation`` (at least EDGE_TOLERANCE): what replaces ``old``.

    Args:
        old: the edge replaced (its vertices are kept).
        face_1: one face it bounds.
        face_2: the other.
        curve: the 3D curve.
        pcurve_1: its pcurve on ``face_1``.
        pcurve_2: its pcurve on ``face_2``.
        deviation: the largest distance measured between the three.

    Returns:
        The edge.
    """
    tolerance = max(EDGE_TOLERANCE, 2.0 * deviation)
    first, last = float(curve.t[0]), float(curve.t[-1])
    builder, edge = BRep_Builder(), TopoDS_Edge()
    builder.MakeEdge(edge, occ_curve_3d(curve), tolerance)
    builder.Add(edge, TopExp.FirstVertex_s(old).Oriented(TopAbs_FORWARD))
    builder.Add(edge, TopExp.LastVertex_s(old).Oriented(TopAbs_REVERSED))
    builder.Range(edge, first, last)
    for face, pcurve in ((face_1, pcurve_1), (face_2, pcurve_2)):
        builder.UpdateEdge(edge, occ_curve_2d(pcurve), face, tolerance)
        builder.Range(edge, face, first, last)
    builder.SameParameter(edge, True)
    builder.SameRange(edge, True)
    return edge
