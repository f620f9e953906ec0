"""An OCCT B-spline surface as numpy arrays, evaluated on a whole grid at once; a scipy
B-spline curve as OCCT's (:func:`occ_curve`).

:class:`SurfaceArrays` holds what defines a ``Geom_BSplineSurface`` (poles P_ij, weights
w_ij, the flat knot vectors and the degrees p, q; The NURBS Book, section 4.4) and
evaluates the surface and its first derivatives on a grid of (u, v) as a tensor product,
one direction at a time, with scipy's B-splines (de Boor's algorithm; NURBS Book A2.2, A3.6):

    A(u, v) = sum_ij N_i,p(u) N_j,q(v) w_ij P_ij,   w(u, v) = sum_ij N_i,p(u) N_j,q(v) w_ij,
    S = A / w,   S_u = (A_u - w_u S) / w,   S_v = (A_v - w_v S) / w   (NURBS Book eq. 4.8).

It replaces a Python loop of ``Geom_Surface.D1`` calls where thousands of samples are taken
(the fit's measure, the read-back's): the surface measured is still the OCCT one, its own
poles, weights and knots; tests/unit/fitting/test_nurbs_arrays.py holds the two to 1e-12 of each other.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.gp import gp_Pnt, gp_Pnt2d
from scipy.interpolate import BSpline, NdBSpline

from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, reals
from tubecad.occ_compat import Array1OfPnt, Array1OfPnt2d, copy_of

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class SurfaceArrays:
    """Poles (n_u, n_v, 3), weights (n_u, n_v), flat knots and degrees of a non-periodic
    B-spline surface (a periodic one is stored unperiodic: the same surface)."""

    poles: FloatArray
    weights: FloatArray
    u_knots: FloatArray
    v_knots: FloatArray
    u_degree: int
    v_degree: int

    @classmethod
    def from_occ(cls, surface: Geom_BSplineSurface) -> SurfaceArrays:
        """The arrays of an OCCT surface (1-based poles, distinct knots with multiplicities)."""
        if surface.IsUPeriodic() or surface.IsVPeriodic():
            surface = copy_of(surface)
            if surface.IsUPeriodic():
                surface.SetUNotPeriodic()
            if surface.IsVPeriodic():
                surface.SetVNotPeriodic()
        n_u, n_v = surface.NbUPoles(), surface.NbVPoles()
        poles = np.array(
            [[surface.Pole(i, j).Coord() for j in range(1, n_v + 1)] for i in range(1, n_u + 1)], dtype=float
        )
        weights = np.array([[surface.Weight(i, j) for j in range(1, n_v + 1)] for i in range(1, n_u + 1)], dtype=float)
        u_knots = np.repeat(
            [surface.UKnot(i) for i in range(1, surface.NbUKnots() + 1)],
            [surface.UMultiplicity(i) for i in range(1, surface.NbUKnots() + 1)],
        )
        v_knots = np.repeat(
            [surface.VKnot(i) for i in range(1, surface.NbVKnots() + 1)],
            [surface.VMultiplicity(i) for i in range(1, surface.NbVKnots() + 1)],
        )
        return cls(poles, weights, u_knots, v_knots, surface.UDegree(), surface.VDegree())

    def points_d1(self, uv: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(S, S_u, S_v) at each row (u, v) of ``uv`` (scattered points, not a grid), each of
        shape (rows, 3): the homogeneous tensor product as scipy's NdBSpline, then eq. 4.8."""
        spline = self._tensor_product
        a, a_u, a_v = (spline(uv, nu=order) for order in ((0, 0), (1, 0), (0, 1)))
        w = a[:, 3:]
        s = a[:, :3] / w
        return s, (a_u[:, :3] - a_u[:, 3:] * s) / w, (a_v[:, :3] - a_v[:, 3:] * s) / w

    @cached_property
    def _tensor_product(self) -> NdBSpline:
        """The homogeneous surface (w P, w) as one scipy NdBSpline, made once (Newton calls
        :meth:`points_d1` many times on one surface)."""
        homogeneous = np.concatenate([self.poles * self.weights[..., None], self.weights[..., None]], axis=-1)
        return NdBSpline((self.u_knots, self.v_knots), homogeneous, (self.u_degree, self.v_degree))

    def grid_d1(self, us: FloatArray, vs: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(S, S_u, S_v) at every (us[i], vs[j]), each of shape (len(us), len(vs), 3)."""
        n_u, n_v, _ = self.poles.shape
        homogeneous = np.concatenate([self.poles * self.weights[..., None], self.weights[..., None]], axis=-1)
        along_u = BSpline(self.u_knots, homogeneous.reshape(n_u, -1), self.u_degree, extrapolate=False)
        rows = [along_u(us, nu).reshape(len(us), n_v, 4) for nu in (0, 1)]  # A, A_u at the us, per v pole

        def along_v(c: FloatArray, nu: int) -> FloatArray:  # (len(us), n_v, 4) -> (len(us), len(vs), 4)
            return BSpline(self.v_knots, np.moveaxis(c, 1, 0), self.v_degree, extrapolate=False)(vs, nu).swapaxes(0, 1)

        a, a_u, a_v = along_v(rows[0], 0), along_v(rows[1], 0), along_v(rows[0], 1)
        w = a[..., 3:]
        s = a[..., :3] / w
        return s, (a_u[..., :3] - a_u[..., 3:] * s) / w, (a_v[..., :3] - a_v[..., 3:] * s) / w


def span_grid(knots: FloatArray, lo: float, hi: float, per_span: int) -> FloatArray:
    """Parameters that cover every knot span of ``knots`` inside [lo, hi]: each distinct knot
    there, both ends, and ``per_span - 1`` equally spaced points inside each span.

    Where an isoline's error peaks, at a face's boundary (a ring or a stringer), at a knot or
    inside a span, such a grid has a sample: sampling only inside the spans misses the first two.

    Args:
        knots: a knot vector (repeats allowed).
        lo: the first parameter wanted (a face's or surface's bound).
        hi: the last parameter wanted.
        per_span: samples per span (at least 1).

    Returns:
        The increasing parameters.
    """
    inside = np.unique(np.clip(np.asarray(knots, dtype=float), lo, hi))
    ends = np.unique(np.concatenate([[lo], inside, [hi]]))
    steps = np.arange(per_span) / per_span
    return np.concatenate([(a + steps * (b - a)) for a, b in zip(ends[:-1], ends[1:])] + [[hi]])


def occ_curve(spline: BSpline) -> Geom_BSplineCurve | Geom2d_BSplineCurve:
    """A scipy B-spline of points (coefficients (n, 3) or (n, 2)) as OCCT's 3D or 2D
    B-spline curve of the same degree, knots and poles (non-rational): :func:`occ_curve_3d`
    or :func:`occ_curve_2d`, which a caller that knows the dimension calls itself."""
    return occ_curve_3d(spline) if np.shape(spline.c)[1] == 3 else occ_curve_2d(spline)


def occ_curve_3d(spline: BSpline) -> Geom_BSplineCurve:
    """A scipy B-spline of 3D points (coefficients (n, 3)) as OCCT's Geom_BSplineCurve."""
    poles = _poles(spline, 3)
    array = Array1OfPnt(1, len(poles))
    for i, pole in enumerate(poles.tolist()):
        array.SetValue(i + 1, gp_Pnt(*pole))
    knots, multiplicities = knots_and_multiplicities(spline.t)
    return Geom_BSplineCurve(array, reals(knots), integers(multiplicities), int(spline.k))


def occ_curve_2d(spline: BSpline) -> Geom2d_BSplineCurve:
    """A scipy B-spline of plane points (coefficients (n, 2)) as OCCT's Geom2d_BSplineCurve
    (a pcurve)."""
    poles = _poles(spline, 2)
    array = Array1OfPnt2d(1, len(poles))
    for i, pole in enumerate(poles.tolist()):
        array.SetValue(i + 1, gp_Pnt2d(*pole))
    knots, multiplicities = knots_and_multiplicities(spline.t)
    return Geom2d_BSplineCurve(array, reals(knots), integers(multiplicities), int(spline.k))


def _poles(spline: BSpline, dimension: int) -> FloatArray:
    """The spline's coefficients as (n, ``dimension``) floats; a ValueError otherwise."""
    poles = np.asarray(spline.c, dtype=float)
    if poles.ndim != 2 or poles.shape[1] != dimension:
        raise ValueError(f"a B-spline of {dimension}D points has coefficients (n, {dimension}), got {poles.shape}")
    return poles
