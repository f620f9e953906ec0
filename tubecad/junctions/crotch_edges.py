"""An equal tee's saddle as edges: its two curves from crotch point to crotch point
(:mod:`~tubecad.junctions.crotch`), each an exact ellipse arc where it is a conic, else a
fitted B-spline, sharing the two crotch vertices (issue 43).

Two equal straight tubes whose axes meet cross in two plane ellipses (the planes bisecting
the axes; Monge: both tubes envelop one sphere), each with an axis along the line through
the crotch points. So a curve is taken as an ellipse where its samples lie in a plane within
CONIC of the model's size: centre C the crotch points' midpoint, semi-axis a = half their
distance along x, the other b = |y| / sqrt(1 - x^2 / a^2) at the sample farthest from the
chord (x, y its plane coordinates), and kept only if every sample (the midpoints between the
fitted nodes too) lies within CONIC of that ellipse (OCCT's projection on it). Where the tubes
curve, the curve is the degree-5 B-spline interpolating it at even steps of u_B (The NURBS
Book, section 9.2.1, not-a-knot ends), measured at the midpoints between its nodes, its nodes
doubled until that is within the fit tolerance, as for a smooth saddle.
"""

from __future__ import annotations

import math

import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeVertex
from OCP.Geom import Geom_BSplineCurve, Geom_Curve, Geom_Ellipse, Geom_TrimmedCurve
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.gp import gp_Ax2, gp_Dir, gp_Elips, gp_Pnt
from OCP.TopoDS import TopoDS_Edge, TopoDS_Vertex
from scipy.interpolate import make_interp_spline

from tubecad.core.errors import ParameterError
from tubecad.fitting.occ_arrays import integers, reals
from tubecad.junctions.saddle import SaddleCurve, saddle_curve
from tubecad.occ_compat import Array1OfPnt
from tubecad.surface.protocol import CurvatureLineSurface

#: a curve is an ellipse where all its samples lie within this times the model's size of one
#: (round-off of Newton's points: ~1e-15 of it)
CONIC = 1e-11
#: the interpolant's degree where a curve is no conic
DEGREE = 5
#: the most intervals on each curve
MOST_INTERVALS = 2048


def fit_crotched(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    exact: SaddleCurve,
    tolerance: float,
    *,
    key: str = "branches",
) -> tuple[tuple[Geom_Curve, ...], tuple[TopoDS_Edge, ...], SaddleCurve, float]:
    """The two curves of an equal tee's saddle ``exact`` (it has corners) as edges.

    Args:
        main: the main surface the saddle lies on.
        branch: the branch surface.
        exact: the saddle sampled (:func:`~tubecad.junctions.saddle.saddle_curve`; its
            corners the crotch points).
        tolerance: the largest distance allowed between an edge and the exact saddle.
        key: the key a refusal names.

    Returns:
        (the two curves, their edges sharing the crotch vertices, the exact saddle at the
        fitted nodes, the largest distance of the curves from the exact saddle measured at the
        samples between the nodes).

    Raises:
        ParameterError: (``fit.tolerance``) where MOST_INTERVALS do not hold the tolerance.
    """
    scale = float(np.abs(exact.points).max())
    vertices = [
        BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex() for p in exact.points[list(exact.corners[:2])]
    ]
    while True:
        m = exact.corners[1]  # the samples' intervals on each curve (even: nodes and midpoints)
        if m % 2:
            exact = saddle_curve(main, branch, 4 * m + 1, key=key, near=exact)
            continue
        curves, deviation = [], 0.0
        for a, b in zip(exact.corners[:-1], exact.corners[1:]):
            curve, off = _conic(exact.points[a : b + 1], scale) or _spline(exact, a, b)
            curves.append(curve)
            deviation = max(deviation, off)
        if deviation <= tolerance:
            break
        if m >= MOST_INTERVALS:
            raise ParameterError(
                f"fit.tolerance: the saddle's curves hold only {deviation:.1e} with {m // 2} intervals each "
                f"(tolerance {tolerance:.1e})",
                key="fit.tolerance",
            )
        wanted = m * max(2.0, (deviation / tolerance) ** (1.0 / (DEGREE + 1)))
        exact = saddle_curve(
            main, branch, 2 * min(MOST_INTERVALS, 2 ** math.ceil(math.log2(wanted))) + 1, key=key, near=exact
        )
    nodes = np.arange(0, len(exact), 2)
    knots = SaddleCurve(
        exact.branch_u[nodes],
        exact.branch_s[nodes],
        exact.main_u[nodes],
        exact.main_s[nodes],
        exact.points[nodes],
        exact.residual,
        tuple(c // 2 for c in exact.corners),
    )
    return tuple(curves), tuple(_edge(c, vertices) for c in curves), knots, deviation


def _conic(points: np.ndarray, scale: float) -> tuple[Geom_Curve, float] | None:
    """The ellipse arc through ``points`` (a curve from crotch point to crotch point, its ends
    on an axis of the ellipse) and its largest distance from them, or None where they are not
    one within CONIC x ``scale`` (module docstring)."""
    first, last = points[0], points[-1]
    centre = 0.5 * (first + last)
    a = 0.5 * float(np.linalg.norm(last - first))
    x_dir = (last - first) / (2.0 * a)
    rel = points - centre
    normal = np.linalg.svd(rel - rel.mean(axis=0))[2][2]
    limit = CONIC * scale
    if np.abs(rel @ normal).max() > limit:
        return None
    y_dir = np.cross(normal, x_dir)
    x, y = rel @ x_dir, rel @ y_dir
    far = int(np.argmax(np.abs(y)))
    if abs(x[far]) >= a:
        return None
    if y[far] < 0:  # y towards the curve's bulge
        y_dir, y = -y_dir, -y
    b = float(y[far] / math.sqrt(1.0 - (x[far] / a) ** 2))
    if b >= a:  # the major axis across the chord: the arc runs -pi/2 .. pi/2
        axes = gp_Ax2(gp_Pnt(*centre), gp_Dir(*np.cross(y_dir, x_dir)), gp_Dir(*y_dir))
        ellipse, ends = Geom_Ellipse(gp_Elips(axes, b, a)), (-0.5 * math.pi, 0.5 * math.pi)
    else:  # the major axis along the chord: the arc runs 0 .. pi
        axes = gp_Ax2(gp_Pnt(*centre), gp_Dir(*np.cross(x_dir, y_dir)), gp_Dir(*x_dir))
        ellipse, ends = Geom_Ellipse(gp_Elips(axes, a, b)), (0.0, math.pi)
    arc = Geom_TrimmedCurve(ellipse, *ends)
    projector = GeomAPI_ProjectPointOnCurve()
    projector.Init(arc, arc.FirstParameter(), arc.LastParameter())
    off = 0.0
    for p in points:
        projector.Perform(gp_Pnt(*map(float, p)))
        if projector.NbPoints() == 0:
            return None
        off = max(off, projector.LowerDistance())
    return (arc, off) if off <= limit else None


def _spline(exact: SaddleCurve, a: int, b: int) -> tuple[Geom_Curve, float]:
    """The degree-5 B-spline (parameter u_B) through the even samples a, a + 2, ..., b of
    ``exact`` and its largest distance from the odd ones between them."""
    u, points = exact.branch_u[a : b + 1], exact.points[a : b + 1]
    spline = make_interp_spline(u[::2], points[::2], k=DEGREE)
    knots, mults = np.unique(spline.t, return_counts=True)
    poles = Array1OfPnt(1, len(spline.c))
    for i, c in enumerate(spline.c):
        poles.SetValue(i + 1, gp_Pnt(*map(float, c)))
    curve = Geom_BSplineCurve(poles, reals(knots), integers(mults), spline.k, False)
    fitted = np.array([curve.Value(float(t)).Coord() for t in u[1::2]])
    return curve, float(np.linalg.norm(fitted - points[1::2], axis=1).max())


def _edge(curve: Geom_Curve, vertices: list[TopoDS_Vertex]) -> TopoDS_Edge:
    """``curve``'s edge between the crotch vertices (each end on the vertex nearer to it)."""
    from OCP.BRep import BRep_Tool

    first, last = curve.FirstParameter(), curve.LastParameter()
    start = np.array(curve.Value(first).Coord())
    near = [float(np.linalg.norm(np.array(BRep_Tool.Pnt_s(v).Coord()) - start)) for v in vertices]
    v1, v2 = (vertices[0], vertices[1]) if near[0] <= near[1] else (vertices[1], vertices[0])
    return BRepBuilderAPI_MakeEdge(curve, v1, v2, first, last).Edge()
