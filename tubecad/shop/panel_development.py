"""Panel development (issue 13): a doubly curved wall panel laid flat, and its strain.

A panel lies between the rings s_a < s_b and the stringers u_a < u_b of a wall surface
S(u, s) whose net is the curvature-line net (F = M = 0). Its Gaussian curvature K is not
zero in general, so no development is free of strain (Gauss; docs/MATH.md section 9). This
one keeps the middle stringer u_m = (u_a + u_b) / 2 and every ring isometric:

- the middle stringer develops to the plane curve gamma(s) of speed sqrt(G(u_m, s)) turning by
  alpha'(s) = kg sqrt(G) = S_ss . (N x S_s) / G at (u_m, s), N = S_u x S_s / |S_u x S_s|;
- the ring s develops from gamma(s), square to gamma'(s), as the plane curve of speed sqrt(E)
  turning by theta_u = kg sqrt(E) = S_uu . (N x S_u) / E (0 on a tube: its rings are geodesics):

      P(u, s) = gamma(s) + Rot(alpha(s) - pi/2) Q(u, s),
      Q(u, s) = Int_{u_m}^u sqrt(E) (cos theta, sin theta) du',   theta = Int_{u_m}^u theta_u du'.

The plane is seen from the outward side (N towards the viewer): (P_u, P_s) is right-handed,
the outline runs counter-clockwise and signed curvatures are geodesic curvatures. The
middle stringer starts at the origin with its chord along +y. Derivatives of P, with
beta = alpha - pi/2 + theta and J the quarter turn:

      P_u = sqrt(E) (cos beta, sin beta),   P_s = gamma' + alpha' J Rot Q + Rot Q_s,
      Q_s = Int_{u_m}^u [(sqrt E)_s (cos theta, sin theta) + sqrt(E) theta_s (-sin theta, cos theta)] du'.

theta_s needs no third derivative: on an orthogonal net Liouville's formulas give the turns
kappa_s = (sqrt G)_u / sqrt(E) of the stringers (per unit s) and theta_u = -(sqrt E)_s / sqrt(G)
of the rings (per unit u), and Gauss's equation reads K sqrt(EG) = d_s theta_u - d_u kappa_s, so

      theta_s(u, s) = kappa_s(u, s) - kappa_s(u_m, s) + Int_{u_m}^u K sqrt(EG) du'.

All integrals are adaptive Chebyshev series (:mod:`tubecad.curves.chebyshev`), ~1e-14.

Strain: with a = [P_u P_s]^T [P_u P_s] and the first fundamental form g = [[E, F], [F, G]], the
principal stretches are lambda = sqrt(eig(g^-1 a)) (computed as eig(L^-1 a L^-T), g = L L^T)
and the principal strains lambda - 1 (> 0 where the development is longer than the surface).

On the tube of radius R (docs/MATH.md section 7; kappa = k1 cos u + k2 sin u) this is in
closed form: sqrt(E) = R, theta = 0, alpha' = k1 sin u_m - k2 cos u_m, and with T = gamma' /
|gamma'|, nu = T turned by -90 deg, delta = u - u_m,

      P = gamma(s) + R delta nu(s),   P_u = R nu,   P_s = (1 - R kappa(u_m) + R delta alpha') T,
      lambda_u = 1,   lambda_s = (1 - R kappa(u_m) + R delta alpha') / (1 - R kappa(u)),

so to second order in the distance d = R delta from the middle stringer the strain is
lambda_s - 1 = K d^2 / 2, K = -kappa / (R (1 - R kappa)) (Jacobi: along the rings, geodesics, the
stringers' spacing falls behind its linear growth in the plane by the factor 1 - K d^2 / 2), so
|strain| ~ |K| d^2 / 2, stretched where K > 0 and shortened where K < 0.
On a canal surface theta_u = -r' chi_u: the rings develop to circular arcs (radius r q / |r'|,
the slant of their normal cone), and a cone develops without strain.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, overload

import numpy as np

from tubecad.core.atomic import save_figure
from tubecad.core.dxf import Drawing
from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.core.units import length_unit as length_unit_of
from tubecad.core.validation import span_pair
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.surface import CurvatureLineSurface, is_surface
from tubecad.surface.forms import SurfaceDerivatives

FloatArray = np.ndarray
WallSurface = CurvatureLineSurface  # a tube or a canal surface
#: most grid samples along either direction
MAX_SAMPLES = 4097
#: the relative tolerance of a refitted net cell's fits (:func:`develop_cell`)
CELL_TOLERANCE = 1e-13
#: the development DXF's layers, name -> DXF colour index
PANEL_LAYERS = {"OUTLINE": 7, "MARKING": 1, "TEXT": 3, "STRAIN": 5}


def _dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.einsum("...i,...i->...", a, b)


def _rotate(v: FloatArray, angle: FloatArray) -> FloatArray:
    """Rot(angle) v for plane vectors v (..., 2) and angles broadcast with v[..., 0]."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def _turns(d: SurfaceDerivatives) -> tuple[FloatArray, FloatArray]:
    """(theta_u, kappa_s): the rings' turn per unit u, S_uu . (N x S_u) / E, and the
    stringers' per unit s, S_ss . (N x S_s) / G (geodesic curvature times speed)."""
    n = d.normal
    return (
        _dot(d.S_uu, np.cross(n, d.S_u)) / _dot(d.S_u, d.S_u),
        _dot(d.S_ss, np.cross(n, d.S_s)) / _dot(d.S_s, d.S_s),
    )


def _gauss_density(d: SurfaceDerivatives) -> FloatArray:
    """K sqrt(EG - F^2) = (LN - M^2) / sqrt(EG - F^2)."""
    n = d.normal
    E, F, G = _dot(d.S_u, d.S_u), _dot(d.S_u, d.S_s), _dot(d.S_s, d.S_s)
    L, M, N = _dot(d.S_uu, n), _dot(d.S_us, n), _dot(d.S_ss, n)
    return (L * N - M * M) / np.sqrt(E * G - F * F)


def _columns(series: PiecewiseChebyshev, x: FloatArray, column: FloatArray) -> FloatArray:
    """series(x[i])[column[i]] for each i (Clenshaw on each point's own column): shape
    (n, *value_shape[1:])."""
    i = np.clip(np.searchsorted(series.breaks, x, side="right") - 1, 0, len(series.coeffs) - 1)
    lo, hi = series.breaks[i], series.breaks[i + 1]
    c = series.coeffs[i, :, column]  # (n, degree + 1, *rest)
    z = ((2.0 * x - lo - hi) / (hi - lo)).reshape((-1,) + (1,) * (c.ndim - 2))
    b1 = np.zeros(c.shape[:1] + c.shape[2:])
    b2 = np.zeros_like(b1)
    for j in range(c.shape[1] - 1, 0, -1):
        b1, b2 = c[:, j] + 2.0 * z * b1 - b2, b1
    return c[:, 0] + z * b1 - b2


class _Primitive:
    """F(x) = Int_{x0}^x f dx' on [lo, hi]: the antiderivative of the adaptive Chebyshev series
    of f + floor, less floor (x - x0). The floor gives the fit an absolute scale: an f that is
    zero but for round-off (a cylinder's ring turn) would otherwise be resolved to its noise."""

    def __init__(
        self,
        f: Callable[[FloatArray], FloatArray],
        lo: float,
        hi: float,
        x0: float,
        floor: float,
        name: str,
        breaks: FloatArray | None = None,
        tol: float = 1e-15,
    ) -> None:
        fit = PiecewiseChebyshev.fit(lambda x: f(x) + floor, lo, hi, name=name, breaks=breaks, tol=tol)
        self.series = fit.antiderivative()
        self.floor, self.x0 = floor, x0
        self.start = self.series(np.array(x0))

    def __call__(self, x: FloatArray) -> FloatArray:
        x = np.asarray(x, dtype=float)
        extra = (1,) * len(self.series.value_shape)
        return self.series(x) - self.start - (self.floor * (x - self.x0)).reshape(x.shape + extra)

    def columns(self, x: FloatArray, column: FloatArray) -> FloatArray:
        extra = (1,) * (len(self.series.value_shape) - 1)
        return (
            _columns(self.series, x, column)
            - self.start[column]
            - (self.floor * (x - self.x0)).reshape(x.shape + extra)
        )


@dataclass(frozen=True)
class _Rings:
    """The developed rings at K arc lengths: theta, Q and (for the derivatives) Q_s, each a
    primitive in u from u_m with K columns."""

    theta: _Primitive
    q: _Primitive
    q_s: _Primitive | None


class PanelConstruction:
    """The development map P(u, s) of one panel (module docstring); u in radians."""

    def __init__(
        self,
        base: WallSurface,
        u_range: tuple[float, float],
        s_range: tuple[float, float],
        u_breaks: FloatArray | None = None,
        length_scale: float | None = None,
        tol: float = 1e-15,
    ) -> None:
        self.tol = tol  # the fits' relative tolerance: a tube's analytic derivatives hold 1e-15
        self.base = base
        self.u_a, self.u_b = u_range
        self.u_m = 0.5 * (self.u_a + self.u_b)
        self.s_a, self.s_b = s_range
        self.breaks = _s_breaks(base, s_range)
        # the fits across the rings start panels at these u (a B-spline cell's knots, where it is
        # C^(p-1) only), the middle stringer's u among them
        inner = [] if u_breaks is None else [u for u in np.asarray(u_breaks, dtype=float) if self.u_a < u < self.u_b]
        self.u_breaks = np.unique(np.concatenate([[self.u_a, self.u_b], inner]))
        # the fits' absolute scale: a tube's radius (sqrt(E) per radian), or given (a net's cell,
        # whose u is a length: its size)
        mid = base.derivatives(self.u_m, 0.5 * (self.s_a + self.s_b))
        self.length_scale = float(np.linalg.norm(mid.S_u)) if length_scale is None else float(length_scale)
        turn = lambda s: _turns(base.derivatives(self.u_m, s))[1]  # noqa: E731
        self.alpha = _Primitive(
            turn,
            self.s_a,
            self.s_b,
            self.s_a,
            1.0 / self.length_scale,
            "the middle stringer's geodesic curvature",
            self.breaks,
            tol=self.tol,
        )
        trial = self._gamma(0.5 * math.pi)
        chord = trial(np.array(self.s_b))
        self.alpha0 = math.pi - math.atan2(float(chord[1]), float(chord[0]))  # chord along +y
        self.gamma = self._gamma(self.alpha0)

    def _gamma(self, alpha0: float) -> _Primitive:
        """gamma(s) = Int_{s_a}^s sqrt(G(u_m, s)) (cos alpha, sin alpha) ds, alpha = alpha0 + Int alpha'."""

        def velocity(s: FloatArray) -> FloatArray:
            speed = np.linalg.norm(self.base.derivatives(self.u_m, s).S_s, axis=-1)
            a = alpha0 + self.alpha(s)
            return speed[..., None] * np.stack([np.cos(a), np.sin(a)], axis=-1)

        return _Primitive(
            velocity, self.s_a, self.s_b, self.s_a, 0.0, "the middle stringer's development", self.breaks, tol=self.tol
        )

    def rings(self, s: FloatArray, derivatives: bool = False) -> _Rings:
        """The developed rings at the arc lengths ``s`` (shape (K,))."""
        base, s = self.base, np.asarray(s, dtype=float)
        lo, hi, um = self.u_a, self.u_b, self.u_m

        def at(u: FloatArray) -> SurfaceDerivatives:
            return base.derivatives(u[..., None], s)

        breaks = self.u_breaks
        theta = _Primitive(
            lambda u: _turns(at(u))[0], lo, hi, um, 1.0, "the rings' geodesic curvature", breaks, tol=self.tol
        )

        def velocity(u: FloatArray) -> FloatArray:
            speed, th = np.linalg.norm(at(u).S_u, axis=-1), theta(u)
            return speed[..., None] * np.stack([np.cos(th), np.sin(th)], axis=-1)

        q = _Primitive(velocity, lo, hi, um, 0.0, "the rings' development", breaks, tol=self.tol)
        if not derivatives:
            return _Rings(theta, q, None)
        gauss = _Primitive(
            lambda u: _gauss_density(at(u)),
            lo,
            hi,
            um,
            1.0 / self.length_scale,
            "the Gaussian curvature across the rings",
            breaks,
            tol=self.tol,
        )
        kappa_m = _turns(base.derivatives(um, s))[1]

        def d_velocity(u: FloatArray) -> FloatArray:
            d = at(u)
            speed = np.linalg.norm(d.S_u, axis=-1)
            speed_s = _dot(d.S_u, d.S_us) / speed  # (sqrt E)_s
            theta_s = _turns(d)[1] - kappa_m + gauss(u)
            th = theta(u)
            c, sn = np.cos(th), np.sin(th)
            return np.stack([speed_s * c - speed * theta_s * sn, speed_s * sn + speed * theta_s * c], axis=-1)

        return _Rings(
            theta, q, _Primitive(d_velocity, lo, hi, um, 1.0, "the rings' development, d/ds", breaks, tol=self.tol)
        )

    @overload
    def evaluate(self, u: FloatArray, s: FloatArray, derivatives: Literal[False] = False) -> FloatArray: ...

    @overload
    def evaluate(
        self, u: FloatArray, s: FloatArray, derivatives: Literal[True]
    ) -> tuple[FloatArray, FloatArray, FloatArray]: ...

    def evaluate(
        self, u: FloatArray, s: FloatArray, derivatives: bool = False
    ) -> FloatArray | tuple[FloatArray, FloatArray, FloatArray]:
        """P at the points (u[i], s[i]) (flat arrays, radians), shape (n, 2); with
        ``derivatives`` (P, P_u, P_s)."""
        u, s = np.asarray(u, dtype=float).ravel(), np.asarray(s, dtype=float).ravel()
        s_unique, column = np.unique(s, return_inverse=True)
        rings = self.rings(s_unique, derivatives)
        alpha = self.alpha0 + self.alpha(s)
        q = rings.q.columns(u, column)
        p = self.gamma(s) + _rotate(q, alpha - 0.5 * math.pi)
        if not derivatives:
            return p
        d, dm = self.base.derivatives(u, s), self.base.derivatives(self.u_m, s)
        beta = alpha - 0.5 * math.pi + rings.theta.columns(u, column)
        p_u = np.linalg.norm(d.S_u, axis=-1)[:, None] * np.stack([np.cos(beta), np.sin(beta)], axis=-1)
        gamma_s = np.linalg.norm(dm.S_s, axis=-1)[:, None] * np.stack([np.cos(alpha), np.sin(alpha)], axis=-1)
        assert rings.q_s is not None  # (made with the derivatives)
        q_s = rings.q_s.columns(u, column)
        p_s = gamma_s + _turns(dm)[1][:, None] * _rotate(q, alpha) + _rotate(q_s, alpha - 0.5 * math.pi)
        return p, p_u, p_s

    def surface_area(self) -> float:
        """Int Int sqrt(EG - F^2) du ds over the patch (nested adaptive Chebyshev quadrature)."""
        base, lo, hi = self.base, self.u_a, self.u_b

        def across(s: FloatArray) -> FloatArray:
            flat = s.ravel()

            def density(u: FloatArray) -> FloatArray:
                d = base.derivatives(u[..., None], flat)
                E, F, G = _dot(d.S_u, d.S_u), _dot(d.S_u, d.S_s), _dot(d.S_s, d.S_s)
                return np.sqrt(E * G - F * F)

            return _Primitive(density, lo, hi, lo, 0.0, "the panel's area density", self.u_breaks, tol=self.tol)(
                np.array(hi)
            ).reshape(s.shape)

        total = _Primitive(across, self.s_a, self.s_b, self.s_a, 0.0, "the panel's area", self.breaks, tol=self.tol)
        return float(total(np.array(self.s_b)))

    def flat_area(self) -> float:
        """The area the developed outline encloses, by Green's theorem A = 1/2 closed-Int P x dP
        along its four edges (the limit of the outline's shoelace formula)."""
        floor = self.length_scale**2

        def cross(a: FloatArray, b: FloatArray) -> FloatArray:
            return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]

        def ring_edges(u: FloatArray) -> FloatArray:  # (P x P_u) at s_a and at s_b
            uu = np.repeat(u.ravel(), 2)
            ss = np.tile([self.s_a, self.s_b], u.size)
            p, p_u, _ = self.evaluate(uu, ss, derivatives=True)
            return cross(p, p_u).reshape(u.shape + (2,))

        def seam_edges(s: FloatArray) -> FloatArray:  # (P x P_s) at u_a and at u_b
            ss = np.repeat(s.ravel(), 2)
            uu = np.tile([self.u_a, self.u_b], s.size)
            p, _, p_s = self.evaluate(uu, ss, derivatives=True)
            return cross(p, p_s).reshape(s.shape + (2,))

        rings = _Primitive(
            ring_edges, self.u_a, self.u_b, self.u_a, floor, "the outline's rings", self.u_breaks, tol=self.tol
        )(np.array(self.u_b))
        seams = _Primitive(
            seam_edges, self.s_a, self.s_b, self.s_a, floor, "the outline's seams", self.breaks, tol=self.tol
        )(np.array(self.s_b))
        return 0.5 * float(rings[0] - rings[1] + seams[1] - seams[0])


def _s_breaks(base: WallSurface, s_range: tuple[float, float]) -> FloatArray:
    """s_a, s_b and the axis' joints (and a radius table's knots) between them."""
    s_a, s_b = s_range
    inner = list(np.asarray(base.s_breaks(), dtype=float))  # the joints (and a radius table's knots)
    inner = [s for s in inner if s_a + 1e-12 * (s_b - s_a) < s < s_b - 1e-12 * (s_b - s_a)]
    return np.unique(np.concatenate([[s_a, s_b], inner]))


def principal_strains(
    E: FloatArray, F: FloatArray, G: FloatArray, a11: FloatArray, a12: FloatArray, a22: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """(lambda_1 - 1, lambda_2 - 1), lambda_1 >= lambda_2 the square roots of the eigenvalues of
    g^-1 a, g = [[E, F], [F, G]], a = [[a11, a12], [a12, a22]]: C = L^-1 a L^-T with g = L L^T
    (Cholesky), mu = mean(C) +- hypot((C11 - C22) / 2, C12), strain = (mu - 1) / (sqrt(mu) + 1),
    which keeps small strains accurate to round-off (no discriminant cancellation)."""
    l11 = np.sqrt(E)
    l21 = F / l11
    l22 = np.sqrt(G - l21 * l21)
    m21, m22 = -l21 / (l11 * l22), 1.0 / l22  # second row of L^-1 (the first is (1 / l11, 0))
    c11 = a11 / E
    c12 = (a11 * m21 + a12 * m22) / l11
    c22 = a11 * m21 * m21 + 2.0 * a12 * m21 * m22 + a22 * m22 * m22
    mean_excess = 0.5 * ((c11 - 1.0) + (c22 - 1.0))
    radius = np.hypot(0.5 * (c11 - c22), c12)
    out = []
    for excess in (mean_excess + radius, mean_excess - radius):
        out.append(excess / (np.sqrt(1.0 + excess) + 1.0))
    return out[0], out[1]


@dataclass(frozen=True)
class PanelDevelopment:
    """A panel's development (module docstring): the grid of developed points, the strain at
    each node and its largest value, the 3-D and flat areas. Angles in degrees (on a canal
    surface they are chi0, the stringers' angles at the span's start)."""

    name: str
    angles_deg: np.ndarray  # (n_u,) grid angles from u_a to u_b
    s: np.ndarray  # (n_s,) grid s from s_a to s_b
    grid: np.ndarray  # (n_u, n_s, 2) developed positions
    strain: np.ndarray  # (n_u, n_s) largest |principal strain| at each node
    max_strain: float
    max_strain_at: tuple[float, float]  # (u_deg, s)
    max_strain_point: np.ndarray  # (3,) on the surface
    surface_area: float  # of the 3-D patch, Int Int sqrt(EG - F^2) du ds
    flat_area: float  # enclosed by the developed outline (Green's theorem on its exact edges)
    construction: PanelConstruction = field(repr=False, compare=False)
    #: the construction's u per unit of the grid's u (``angles_deg``): pi / 180 on a tube (the
    #: grid in degrees, the construction in radians), 1 on a net's cell (both its arc length)
    u_per_unit: float = math.pi / 180.0
    #: the grid's u unit in the texts ("deg"; "" on a net's cell: a length)
    u_unit: str = "deg"

    @property
    def angle_range(self) -> tuple[float, float]:
        return float(self.angles_deg[0]), float(self.angles_deg[-1])

    @property
    def s_range(self) -> tuple[float, float]:
        return float(self.s[0]), float(self.s[-1])

    def outline(self) -> np.ndarray:
        """The closed outline (m, 2) through the grid's boundary nodes, counter-clockwise: ring
        s_a (u_a -> u_b), seam u_b (s_a -> s_b), ring s_b back, seam u_a back; the first point
        is not repeated."""
        g = self.grid
        return np.concatenate([g[:, 0], g[-1, 1:], g[-2::-1, -1], g[0, -2:0:-1]])

    def _checked(self, u_deg: Any, s: Any) -> tuple[FloatArray, FloatArray]:
        u, s = np.broadcast_arrays(np.asarray(u_deg, dtype=float), np.asarray(s, dtype=float))
        for key, x, (lo, hi) in (("u_deg", u, self.angle_range), ("s", s, self.s_range)):
            slack = 1e-9 * (hi - lo)
            if x.size and not (np.all(np.isfinite(x)) and x.min() >= lo - slack and x.max() <= hi + slack):
                raise ParameterError(
                    f"{key} must lie in the panel's range [{lo:g}, {hi:g}], got [{np.nanmin(x):g}, {np.nanmax(x):g}]"
                )
        return u, s

    def map(self, u_deg: Any, s: Any) -> np.ndarray:
        """Developed positions of (u_deg, s) inside the panel, broadcast: shape (..., 2). The
        construction itself is evaluated (no interpolation of the grid)."""
        u, s = self._checked(u_deg, s)
        return self.construction.evaluate(u * self.u_per_unit, s).reshape(u.shape + (2,))

    def tangents(self, u_deg: Any, s: Any) -> tuple[np.ndarray, np.ndarray]:
        """(P_u, P_s), the developed map's derivatives per radian (per unit u on a net's cell)
        and per unit s, shape (..., 2)."""
        u, s = self._checked(u_deg, s)
        _, p_u, p_s = self.construction.evaluate(u * self.u_per_unit, s, derivatives=True)
        return p_u.reshape(u.shape + (2,)), p_s.reshape(u.shape + (2,))

    def ring_line(self, s: float, points: int = 65) -> np.ndarray:
        """The developed ring s = const across the panel (a marking line), (points, 2)."""
        return self.map(np.linspace(*self.angle_range, _count("points", points)), s)

    def stringer_line(self, u_deg: float, points: int = 129) -> np.ndarray:
        """The developed stringer u = const along the panel, (points, 2)."""
        return self.map(u_deg, np.linspace(*self.s_range, _count("points", points)))


def _count(key: str, value: Any, low: int = 2) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= MAX_SAMPLES:
        raise ParameterError(f"{key} must be an integer in [{low}, {MAX_SAMPLES}], got {value!r:.40}")
    return int(value)


def _samples(samples: Any) -> tuple[int, int]:
    """A development grid's (n_u, n_s), each checked (:func:`_count`)."""
    try:
        n_u, n_s = samples
    except (TypeError, ValueError):
        raise ParameterError(f"samples must be a pair (n_u, n_s), got {samples!r:.60}") from None
    return _count("samples n_u", n_u), _count("samples n_s", n_s)


def _panel_name(name: Any) -> str:
    if not isinstance(name, str) or not name or any(c in name for c in "/\\\0"):
        raise ParameterError(f"name must be a non-empty string without path separators, got {name!r:.60}")
    return name


def check_panel(base: Any, s_range: Any, angles_deg: Any) -> tuple[tuple[float, float], tuple[float, float]]:
    """The panel's (s_a, s_b) within the surface's span and (u_a, u_b) in degrees with
    0 < u_b - u_a <= 360; a ParameterError naming the key otherwise."""
    if not is_surface(base):
        raise ParameterError(f"base must be a CurvatureLineTube or a CanalSurface, got {type(base).__name__}")
    s_a, s_b = span_pair("s_range", s_range)
    lo, hi = base.span
    slack = 1e-9 * (hi - lo)
    if s_a < lo - slack or s_b > hi + slack:
        raise ParameterError(
            f"s_range must lie within the span [{lo:g}, {hi:g}] of the surface, got [{s_a:g}, {s_b:g}]"
        )
    u_a, u_b = span_pair("angles_deg", angles_deg)
    if u_b - u_a > 360.0 + 1e-9:
        raise ParameterError(f"angles_deg must span at most 360 deg, got [{u_a:g}, {u_b:g}]")
    return (max(s_a, lo), min(s_b, hi)), (u_a, u_b)


def develop_panel(
    base: WallSurface,
    s_range: tuple[float, float],
    angles_deg: tuple[float, float],
    name: str = "panel",
    samples: tuple[int, int] = (33, 65),
) -> PanelDevelopment:
    """Develop the panel of ``base`` (the wall surface) between the rings ``s_range`` and the
    stringers ``angles_deg`` (degrees, counter-clockwise, u_b may exceed 360) on a grid of
    ``samples`` = (n_u, n_s) nodes; the strain is measured at every node."""
    (s_a, s_b), (u_a, u_b) = check_panel(base, s_range, angles_deg)
    name = _panel_name(name)
    n_u, n_s = _samples(samples)
    construction = PanelConstruction(base, (math.radians(u_a), math.radians(u_b)), (s_a, s_b))
    return _developed(construction, np.linspace(u_a, u_b, n_u), np.linspace(s_a, s_b, n_s), name)


def develop_cell(
    base: Any,
    u_range: tuple[float, float],
    s_range: tuple[float, float],
    name: str = "panel",
    samples: tuple[int, int] = (33, 33),
) -> PanelDevelopment:
    """Develop a net's cell refitted in curvature-line coordinates (``base``: its
    :class:`~tubecad.nets.patch_surface.PatchSurface`, u along the k1 lines and s along the k2
    lines, both arc lengths of its sides) over ``u_range`` x ``s_range`` on a grid of
    ``samples`` nodes, as a tube's panel (module docstring: the middle k2 line and every k1
    line isometric); the strain measured at every node.

    Args:
        base: the cell's surface: ``derivatives(u, s)``, ``points(u, s)``, ``s_breaks()`` and
            ``u_breaks()`` (its knots).
        u_range: the span of u developed (along the k1 lines).
        s_range: the span of s developed (along the k2 lines).
        name: the panel's name (the files').
        samples: the grid's nodes (along u, along s), 2 .. MAX_SAMPLES each.

    Returns:
        The development: the grid's developed points, the strain at each, the areas.

    Raises:
        ParameterError: (``name``, ``samples``, ``u_range``, ``s_range``) out of range.
    """
    name = _panel_name(name)
    n_u, n_s = _samples(samples)
    (u_a, u_b), (s_a, s_b) = span_pair("u_range", u_range), span_pair("s_range", s_range)
    size = max(u_b - u_a, s_b - s_a)
    # a B-spline's derivatives hold round-off of its poles over a knot span (about 1e-14 of
    # them): its fits are resolved to CELL_TOLERANCE, not the tube's 1e-15
    construction = PanelConstruction(base, (u_a, u_b), (s_a, s_b), base.u_breaks(), size, CELL_TOLERANCE)
    return _developed(construction, np.linspace(u_a, u_b, n_u), np.linspace(s_a, s_b, n_s), name, 1.0, "")


def _developed(
    construction: PanelConstruction,
    u: FloatArray,
    s: FloatArray,
    name: str,
    u_per_unit: float = math.pi / 180.0,
    u_unit: str = "deg",
) -> PanelDevelopment:
    """The development on the grid ``u`` x ``s`` (u in the grid's units, ``u_per_unit`` of
    the construction's each) and the strain at every node."""
    base = construction.base
    n_u, n_s = len(u), len(s)
    uu, ss = np.repeat(u * u_per_unit, n_s), np.tile(s, n_u)
    p, p_u, p_s = construction.evaluate(uu, ss, derivatives=True)
    d = base.derivatives(uu, ss)
    first, second = principal_strains(
        _dot(d.S_u, d.S_u), _dot(d.S_u, d.S_s), _dot(d.S_s, d.S_s), _dot(p_u, p_u), _dot(p_u, p_s), _dot(p_s, p_s)
    )
    strain = np.maximum(np.abs(first), np.abs(second)).reshape(n_u, n_s)
    top = float(strain.max())
    # ties (a torus' strain does not depend on s): the first node in (u, s) order within round-off of the largest
    i, j = np.unravel_index(int(np.argmax(strain >= top * (1.0 - 1e-12))), strain.shape)
    return PanelDevelopment(
        name,
        u,
        s,
        p.reshape(n_u, n_s, 2),
        strain,
        top,
        (float(u[i]), float(s[j])),
        base.points(float(u[i] * u_per_unit), s[j]),
        construction.surface_area(),
        construction.flat_area(),
        construction,
        u_per_unit,
        u_unit,
    )


def _polyline_points(key: str, points: Any) -> np.ndarray:
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
        raise ParameterError(f"{key} must be an (n, 2) array of finite points, n >= 2, got shape {pts.shape}")
    return pts


def _strain_text(dev: PanelDevelopment) -> str:
    u, s = dev.max_strain_at
    return f"max strain {dev.max_strain:.3e} at u = {u:.6g}{' ' + dev.u_unit if dev.u_unit else ''}, s = {s:.6g}"


def write_panel_dxf(
    developments: list[PanelDevelopment],
    marking: dict[str, list[tuple[str, np.ndarray]]],
    folder: str | Path,
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> list[Path]:
    """One DXF per panel, ``NAME_development.dxf`` in ``folder``, 1:1 in ``length_unit``
    ($INSUNITS): layers OUTLINE (the closed outline), MARKING (one open polyline per marking
    line, ``marking[name]`` = [(line name, (n, 2) developed points)]), TEXT (the panel's and
    each marking line's name) and STRAIN (the largest strain and where). Written atomically."""
    length_unit_of(length_unit)  # an unknown unit fails before any file is written
    paths = []
    for dev in developments:
        outline = dev.outline()
        height = 0.02 * float(np.ptp(outline, axis=0).max())
        drawing = Drawing(length_unit, PANEL_LAYERS)
        drawing.polyline(outline, "OUTLINE")
        drawing.text(dev.name, outline.mean(axis=0), height, "TEXT")
        for line_name, points in marking.get(dev.name, []):
            pts = _polyline_points(f"marking[{dev.name!r}] line {line_name!r}", points)
            drawing.polyline(pts, "MARKING", closed=False)
            drawing.text(str(line_name), pts[len(pts) // 2], 0.6 * height, "TEXT")
        low = outline.min(axis=0)
        drawing.text(_strain_text(dev), (float(low[0]), float(low[1]) - 2.0 * height), 0.6 * height, "STRAIN")
        paths.append(drawing.save(Path(folder) / f"{dev.name}_development.dxf"))
    return paths


def write_panel_picture(
    development: PanelDevelopment,
    marking_lines: list[tuple[str, np.ndarray]],
    folder: str | Path,
    formats: tuple[str, ...] = ("png", "svg"),
) -> list[Path]:
    """``NAME_development.png`` and ``.svg`` (``formats``): the outline, the marking lines and the strain as a
    colour map, equal aspect, the largest strain and where in the title."""
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone

    dev = development
    fig = Figure(figsize=(8, 8))
    ax = fig.subplots()
    mesh = ax.pcolormesh(
        dev.grid[..., 0], dev.grid[..., 1], dev.strain, shading="gouraud", cmap="viridis", rasterized=True
    )  # a gouraud mesh as SVG vectors takes seconds to draw
    fig.colorbar(mesh, ax=ax, shrink=0.8, label="|principal strain|")
    closed = np.vstack([dev.outline(), dev.outline()[:1]])
    ax.plot(closed[:, 0], closed[:, 1], color="#10203a", linewidth=1.0)
    for line_name, points in marking_lines:
        pts = _polyline_points(f"marking line {line_name!r}", points)
        ax.plot(pts[:, 0], pts[:, 1], color="#c0392b", linewidth=0.8, linestyle="--")
        ax.annotate(str(line_name), tuple(pts[len(pts) // 2]), fontsize=7, color="#c0392b")
    ax.set_aspect("equal")
    ax.set_title(f"{dev.name}: development, {_strain_text(dev)}", fontsize=9)
    return save_figure(fig, folder, f"{dev.name}_development", formats, dpi=110)
