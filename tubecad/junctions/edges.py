"""The saddle curve fitted into the B-spline edge the junction's faces share.

The saddle is smooth and periodic in the branch's stringer angle u_B, so it is interpolated
at N evenly spaced u_B by a periodic B-spline of degree 5 (knots at the samples, C^4 round
the whole turn: no seam for OCCT's continuity check to find; The NURBS Book, section 9.2.1,
global interpolation, with scipy's periodic solver), and measured against the exact saddle
(Newton's points, :mod:`~tubecad.junctions.saddle`) at the N midpoints. N starts at 32 (or
at the N another saddle of the junction needed) and, until the largest distance is within the
fit tolerance, goes up to the power of two the error's rate asks for: a degree-5
interpolant's error falls as h^6, so N (d / tolerance)^(1/6), rounded up, at least 2 N.

The edge lies within that distance of both exact surfaces, and so within it plus the faces'
own fit tolerance of both fitted faces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.Geom import Geom_BSplineCurve, Geom_Curve, Geom_TrimmedCurve
from OCP.gp import gp_Pnt
from OCP.TopoDS import TopoDS_Edge
from scipy.interpolate import make_interp_spline

from tubecad.brep.wall import wall_offsets
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, check_tolerance
from tubecad.fitting.occ_arrays import integers, reals
from tubecad.junctions.crotch_edges import fit_crotched
from tubecad.junctions.saddle import SaddleCurve, saddle_curve, saddle_distance
from tubecad.occ_compat import Array1OfPnt
from tubecad.surface.protocol import CurvatureLineSurface

#: the interpolant's degree (odd: scipy's periodic knots are then the samples themselves)
DEGREE = 5
#: the first and the largest number of intervals round the branch
FIRST_INTERVALS, MOST_INTERVALS = 32, 4096


@dataclass(frozen=True)
class SaddleEdge:
    """A saddle curve as OCCT edges: ``name`` (``saddle_outer``, ``saddle_inner``), its
    ``curves`` and their ``edges``, the exact ``saddle`` at the knots, the largest distance
    ``deviation`` from the exact saddle measured at the midpoints between them, and the exact
    surfaces ``main`` and ``branch`` that meet on it.

    A smooth saddle is one periodic B-spline (parameter u_B); an equal tee's is two curves from
    crotch point to crotch point (:mod:`~tubecad.junctions.crotch`), edges sharing the crotch
    vertices: ellipse arcs where they are conics (two equal straight tubes), else B-splines
    (parameter u_B) fitted as the periodic one is."""

    name: str
    curves: tuple[Geom_Curve, ...]
    edges: tuple[TopoDS_Edge, ...]
    saddle: SaddleCurve
    deviation: float
    tolerance: float
    main: CurvatureLineSurface
    branch: CurvatureLineSurface

    @property
    def curve(self) -> Geom_Curve:
        """The saddle's curve: a smooth saddle's only one; an equal tee's first (see :attr:`curves`)."""
        return self.curves[0]

    @property
    def edge(self) -> TopoDS_Edge:
        """The saddle's edge: a smooth saddle's only one; an equal tee's first (see :attr:`edges`)."""
        return self.edges[0]

    @property
    def poles(self) -> int:
        """The B-spline poles of its curves (an ellipse arc has none)."""
        return sum(c.NbPoles() for c in self.curves if isinstance(c, Geom_BSplineCurve))

    @property
    def kind(self) -> str:
        """What its curves are: ``periodic B-spline`` (a smooth saddle), ``2 ellipse arcs`` or
        ``2 B-splines`` (an equal tee's, through the crotch points)."""
        if len(self.curves) == 1:
            return "periodic B-spline"
        return f"{len(self.curves)} {'ellipse arcs' if self.conic else 'B-splines'}"

    @property
    def conic(self) -> bool:
        """Whether its curves are exact ellipse arcs (an equal tee of straight tubes)."""
        return all(isinstance(c, Geom_TrimmedCurve) for c in self.curves)

    def exact_distance(self, points: np.ndarray, u_b: np.ndarray) -> np.ndarray:
        """How far ``points`` (n, 3) lie from the exact saddle, the intersection of the exact
        surfaces (:func:`~tubecad.junctions.saddle.saddle_distance`), not from this fitted edge.

        Args:
            points: the points, near the saddle.
            u_b: (n,) their parameters on :attr:`curve` (u_B: where their feet are looked for first).

        Returns:
            (n,) distances.
        """
        distance = saddle_distance(self.main, self.branch, points, u_b, self.saddle)
        near_crotch = np.isnan(distance)
        if near_crotch.any():  # an equal tee's crotch: see saddle_distance
            distance[near_crotch] = self._crotch_distance(points[near_crotch])
        return distance

    def _crotch_distance(self, points: np.ndarray) -> np.ndarray:
        """Near an equal tee's crotch, where Newton's feet are ill-conditioned: each point's
        distance from this saddle's curves plus their measured :attr:`deviation` from the exact
        saddle (an upper bound of the distance from it; the ellipse arcs of two straight tubes
        are its closed form, 1e-13 off Newton's points)."""
        from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve

        out = np.full(len(points), np.inf)
        for curve in self.curves:
            projector = GeomAPI_ProjectPointOnCurve()
            projector.Init(curve, curve.FirstParameter(), curve.LastParameter())
            for i, p in enumerate(points):
                projector.Perform(gp_Pnt(*map(float, p)))
                if projector.NbPoints():
                    out[i] = min(out[i], projector.LowerDistance())
        return out + self.deviation

    def to_build123d(self) -> bd.Edge | bd.Wire:
        """The saddle as a build123d Edge (an equal tee's: a Wire of its two edges) labelled with
        its name (``saddle_outer``...)."""
        shape: bd.Edge | bd.Wire = (
            bd.Edge(self.edges[0]) if len(self.edges) == 1 else bd.Wire(list(map(bd.Edge, self.edges)))
        )
        shape.label = self.name
        return shape


def periodic_bspline(u: np.ndarray, points: np.ndarray, degree: int = DEGREE) -> Geom_BSplineCurve:
    """The periodic B-spline of ``degree`` through ``points`` at ``u`` (the last point the
    first, at u[0] + period): knots at u, each of multiplicity 1. scipy's periodic
    interpolant's first len(u) - 1 coefficients are OCCT's periodic poles (same knots)."""
    spline = make_interp_spline(u, points, k=degree, bc_type="periodic")
    n = len(u) - 1
    poles = Array1OfPnt(1, n)
    for i in range(n):
        poles.SetValue(i + 1, gp_Pnt(*map(float, spline.c[i])))
    return Geom_BSplineCurve(poles, reals(u), integers([1] * len(u)), degree, True)


def fit_periodic(u: np.ndarray, points: np.ndarray) -> tuple[Geom_BSplineCurve, float]:
    """The periodic B-spline through the even samples of a closed curve (``points`` at ``u``,
    an odd number over one turn, the last the first again) and its largest distance from the
    odd ones, the midpoints between its nodes.

    Args:
        u: the samples' parameters, increasing over one period.
        points: (len(u), 3) the curve's points there.

    Returns:
        (the curve, the measured deviation).
    """
    nodes = points[::2].copy()
    nodes[-1] = nodes[0]
    curve = periodic_bspline(u[::2], nodes)
    fitted = np.array([curve.Value(float(v)).Coord() for v in u[1::2]])
    return curve, float(np.linalg.norm(fitted - points[1::2], axis=1).max())


def fit_saddle(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    *,
    name: str = "saddle_outer",
    key: str = "branches",
    near: SaddleCurve | None = None,
    intervals: int = FIRST_INTERVALS,
) -> SaddleEdge:
    """The saddle where ``branch`` leaves ``main`` as a periodic B-spline edge within
    ``tolerance`` of the exact saddle (measured at the midpoints between its knots). ``near``:
    a saddle close to it (the other wall face's), whose points start Newton instead of a march;
    ``intervals``: the first number of intervals tried (the other saddle's)."""
    tolerance = check_tolerance("tolerance", tolerance)
    exact = near
    if near is None or near.corners:  # an equal tee's saddle is two curves (crotch.py)
        exact = saddle_curve(main, branch, 2 * intervals + 1, key=key, near=near)
        if exact.corners:
            curves, edges, knots, deviation = fit_crotched(main, branch, exact, tolerance, key=key)
            return SaddleEdge(name, curves, edges, knots, deviation, tolerance, main, branch)
    while True:
        exact = saddle_curve(main, branch, 2 * intervals + 1, key=key, near=exact)
        curve, deviation = fit_periodic(exact.branch_u, exact.points)
        if deviation <= tolerance:
            break
        if intervals >= MOST_INTERVALS:
            raise ParameterError(
                f"fit.tolerance: the saddle curve holds only {deviation:.1e} with {intervals} poles "
                f"round the branch (tolerance {tolerance:.1e})",
                key="fit.tolerance",
            )
        wanted = intervals * max(2.0, (deviation / tolerance) ** (1.0 / (DEGREE + 1)))
        intervals = min(MOST_INTERVALS, 2 ** math.ceil(math.log2(wanted)))
    knots = SaddleCurve(
        exact.branch_u[::2],
        exact.branch_s[::2],
        exact.main_u[::2],
        exact.main_s[::2],
        exact.points[::2],
        exact.residual,
    )
    edge = BRepBuilderAPI_MakeEdge(curve).Edge()
    return SaddleEdge(name, (curve,), (edge,), knots, deviation, tolerance, main, branch)


def wall_saddles(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    main_thickness: float,
    branch_thickness: float,
    *,
    main_side: str = "centered",
    branch_side: str = "centered",
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    key: str = "branches",
) -> tuple[SaddleEdge, SaddleEdge]:
    """The two saddles of a branch wall on a main wall: ``saddle_outer``, where the branch's
    outer surface leaves the main's outer surface (the joint's outer skin), and
    ``saddle_inner``, where the branch's bore leaves the main's inner surface (the bore's
    opening). Each wall lies ``side`` of its surface (centered, inside, outside: the
    offsets of :func:`tubecad.brep.wall.wall_offsets`); both edges within ``tolerance``."""
    main_in, main_out = wall_offsets(main_thickness, main_side)
    branch_in, branch_out = wall_offsets(branch_thickness, branch_side)
    outer = fit_saddle(main.offset(main_out), branch.offset(branch_out), tolerance, name="saddle_outer", key=key)
    inner_main, inner_branch = main.offset(main_in), branch.offset(branch_in)
    try:  # the bore's saddle lies a wall's thickness from the outer one: Newton from its points
        inner = fit_saddle(
            inner_main, inner_branch, tolerance, name="saddle_inner", key=key, near=outer.saddle, intervals=outer.poles
        )
    except ParameterError:  # too far for Newton (or refused): march round the branch anew
        inner = fit_saddle(inner_main, inner_branch, tolerance, name="saddle_inner", key=key)
    return outer, inner
