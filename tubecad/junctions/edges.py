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
from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Pnt
from OCP.TopoDS import TopoDS_Edge
from scipy.interpolate import make_interp_spline

from tubecad.brep.wall import wall_offsets
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, check_tolerance
from tubecad.fitting.occ_arrays import integers, reals
from tubecad.junctions.saddle import SaddleCurve, saddle_curve, saddle_distance
from tubecad.occ_compat import Array1OfPnt
from tubecad.surface.protocol import CurvatureLineSurface

#: the interpolant's degree (odd: scipy's periodic knots are then the samples themselves)
DEGREE = 5
#: the first and the largest number of intervals round the branch
FIRST_INTERVALS, MOST_INTERVALS = 32, 4096


@dataclass(frozen=True)
class SaddleEdge:
    """A saddle curve as an OCCT edge: ``name`` (``saddle_outer``, ``saddle_inner``), the
    periodic B-spline ``curve`` (parameter u_B), its ``edge``, the exact ``saddle`` at its
    knots, the largest distance ``deviation`` from the exact saddle measured at the
    midpoints between them, and the exact surfaces ``main`` and ``branch`` that meet on it."""

    name: str
    curve: Geom_BSplineCurve
    edge: TopoDS_Edge
    saddle: SaddleCurve
    deviation: float
    tolerance: float
    main: CurvatureLineSurface
    branch: CurvatureLineSurface

    @property
    def poles(self) -> int:
        return self.curve.NbPoles()

    def exact_distance(self, points: np.ndarray, u_b: np.ndarray) -> np.ndarray:
        """How far ``points`` (n, 3) lie from the exact saddle, the intersection of the exact
        surfaces (:func:`~tubecad.junctions.saddle.saddle_distance`), not from this fitted edge.

        Args:
            points: the points, near the saddle.
            u_b: (n,) their parameters on :attr:`curve` (u_B: where their feet are looked for first).

        Returns:
            (n,) distances.
        """
        return saddle_distance(self.main, self.branch, points, u_b, self.saddle)

    def to_build123d(self) -> bd.Edge:
        """The edge as a build123d Edge labelled with its name (``saddle_outer``...)."""
        edge = bd.Edge(self.edge)
        edge.label = self.name
        return edge


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
    while True:
        exact = saddle_curve(main, branch, 2 * intervals + 1, key=key, near=exact)
        nodes = exact.points[::2].copy()
        nodes[-1] = nodes[0]
        curve = periodic_bspline(exact.branch_u[::2], nodes)
        mids = exact.branch_u[1::2]
        fitted = np.array([curve.Value(float(u)).Coord() for u in mids])
        deviation = float(np.linalg.norm(fitted - exact.points[1::2], axis=1).max())
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
    return SaddleEdge(name, curve, edge, knots, deviation, tolerance, main, branch)


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
