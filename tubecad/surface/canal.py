"""Canal surfaces referred to their lines of curvature (docs/MATH.md section 8).

The envelope of the spheres of radius r(s) centred on the axis c(s), |r'| < 1, is, with
q = sqrt(1 - r'^2), the axis' rotation-minimising frame (t, r1, r2) and e = cos chi r1 +
sin chi r2, ebar = -sin chi r1 + cos chi r2,

    X(chi, s) = c + r ( -r' t + q e )                       (outward normal n = -r' t + q e)

The characteristic circles s = const are one family of curvature lines; the other, the
stringers, are their orthogonal trajectories chi(s):

    d chi / ds = (r' / q) kbar,      kbar = k2 cos chi - k1 sin chi

With w = tan(chi / 2) this is a Riccati equation, so chi(s) is a Moebius image of chi0 = chi(s0).
Written on the half-angle vector (sin(chi/2), cos(chi/2)) it is the linear system

    (a, b)' = [[-beta/2, alpha], [alpha, beta/2]] (a, b),   alpha = r' k2 / 2q,  beta = r' k1 / q

solved once for the 2 x 2 fundamental matrix Mb(s) (Mb(s0) = I) by spectral collocation
(:mod:`..curves.bishop`). Then (a, b) = Mb (sin(chi0/2), cos(chi0/2)) and, with no pole,

    cos chi = (b^2 - a^2) / (a^2 + b^2),   sin chi = 2 a b / (a^2 + b^2)

The surface is parameterised by (chi0, s): chi0 is the stringer's angle at the span's start.
Its derivatives are exact derivatives of the evaluated net (Mb's series differentiated term
by term), so F = M = 0 measured on them tests the net, not a formula. Along a stringer
X_s + X_chi chi' = sqrt(G) m, m = q t + r' e, with

    sqrt(G) = q - r r'' / q - r (k1 cos chi + k2 sin chi)

which is smallest where k1 cos chi + k2 sin chi = k: the surface does not fold iff
fold(s) = r (k q + r'') / q^2 < 1 on the whole span (r' = 0: rho k < 1, the tube's condition).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError, RegularityError
from tubecad.core.validation import flag
from tubecad.curves.axis import Axis
from tubecad.curves.bishop import solve_linear_ode
from tubecad.curves.radius_law import RadiusLaw, RadiusValue, refined_extreme
from tubecad.curves.radius_law import radius_law as radius_law_of
from tubecad.surface.forms import FundamentalForms, SurfaceDerivatives
from tubecad.surface.tube import CurvatureLineTube

FloatArray = np.ndarray
T = TypeVar("T")
MAX_FOLD_SAMPLES = 40_000
#: :attr:`CanalSurface.area_exact` stops doubling its panels when two estimates agree to this (relative)
AREA_CONVERGED = 1e-14
#: ... or at this many Gauss-Legendre panels over the span (their first number: AREA_PANELS); the
#: points round the circles double with them up to MOST_AREA_CHI (8 are exact on a regular surface)
AREA_PANELS, MOST_AREA_PANELS, MOST_AREA_CHI = 16, 2048, 64


@dataclass(frozen=True)
class CanalRegularity:
    """What was measured: the largest |r'| (< 1 by the law's own check) and where; the fold
    ratio r (k q + r'') / q^2 (must stay < 1), its largest value, where, and the runs of s
    where it is >= 1; the smallest stringer speed sqrt(G) = q (1 - fold) over the surface and
    where; and the global self-approach check of a tube of the largest radius (conservative)."""

    max_slope: float
    s_at_max_slope: float
    max_fold: float
    s_at_max_fold: float
    min_speed: float
    s_at_min_speed: float
    folded_intervals: list[tuple[float, float]] = field(default_factory=list)
    #: (s of a surface point, s of a sphere it lies inside, how deep) where the surface
    #: passes inside itself, or None
    entry: tuple[float, float, float] | None = None

    @property
    def locally_regular(self) -> bool:
        return self.max_slope < 1.0 and self.max_fold < 1.0

    @property
    def self_intersecting(self) -> bool:
        return self.entry is not None

    @property
    def ok(self) -> bool:
        return self.locally_regular and not self.self_intersecting

    def message(self) -> str:
        """Why the canal surface is refused, in one line naming the key and where."""
        parts = []
        if not self.locally_regular:
            where = ", ".join(f"[{a:.6g}, {b:.6g}]" for a, b in self.folded_intervals)
            parts.append(
                f"r (k q + r'') / q^2 reaches {self.max_fold:.6g} at s = {self.s_at_max_fold:.6g}; it must "
                f"stay below 1 (the surface folds: the stringers stop for s in {where})"
            )
        if self.entry is not None:
            s1, s2, depth = self.entry
            parts.append(
                f"the surface self-intersects: at s = {s1:.6g} it passes {depth:.3g} inside the sphere of "
                f"the surface at s = {s2:.6g}"
            )
        return (
            "radius: canal surface is not regular: "
            + "; ".join(parts)
            + " (pass allow_irregular=True to build it anyway)"
        )

    def describe(self) -> dict[str, Any]:
        return {
            "max_abs_slope": self.max_slope,
            "s_at_max_abs_slope": self.s_at_max_slope,
            "max_fold": self.max_fold,
            "s_at_max_fold": self.s_at_max_fold,
            "min_stringer_speed": self.min_speed,
            "s_at_min_stringer_speed": self.s_at_min_speed,
            "ok": self.ok,
        }


@dataclass(frozen=True)
class _Angles:
    """cos chi, sin chi along stringers and chi's derivatives in (chi0, s)."""

    cos: FloatArray
    sin: FloatArray
    u: FloatArray | None = None
    s: FloatArray | None = None
    uu: FloatArray | None = None
    us: FloatArray | None = None
    ss: FloatArray | None = None

    def rates(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
        """(chi_u, chi_s, chi_uu, chi_us, chi_ss), which an ``order`` 2 evaluation gives."""
        u, s, uu, us, ss = self.u, self.s, self.uu, self.us, self.ss
        assert u is not None and s is not None and uu is not None and us is not None and ss is not None
        return u, s, uu, us, ss


class CanalSurface:
    """The canal surface about ``axis`` with the radius law ``radius_law`` (a
    :class:`~tubecad.curves.radius_law.RadiusLaw` or anything :func:`radius_law` takes), in
    curvature-line coordinates (chi0, s): chi0 (period 2 pi) names the stringer by its angle
    from r1 at the span's start, s is the axis arc length.

    A surface that folds (r (k q + r'') / q^2 >= 1 somewhere) or whose axis comes back so
    close that a tube of the largest radius self-intersects raises :class:`RegularityError`
    unless ``allow_irregular=True``; the measured facts are in :attr:`regularity` either way.

    Args:
        axis: the surface's axis, any :class:`~tubecad.curves.axis.Axis`; the surface covers
            its span.
        radius_law: the sphere radius r(s), model units: a
            :class:`~tubecad.curves.radius_law.RadiusLaw` on the axis' span, or anything
            :func:`~tubecad.curves.radius_law.radius_law` takes (a number, an expression in
            s and x, y, z, a callable, a table [[s, r], ...]); r > 0 and |r'| < 1, and on a
            closed axis a law that closes (r and r' equal at both ends).
        allow_irregular: build the surface even where it is not regular (default False: a
            :class:`RegularityError` instead).
        _known: internal, for the surface's own offsets and pieces (its solved net and
            regularity, reused); callers leave it None.

    Raises:
        ParameterError: ``axis`` not an Axis, or a bad radius law (see :func:`radius_law`).
        RegularityError: the surface folds or self-intersects, unless ``allow_irregular``.
    """

    def __init__(
        self,
        axis: Axis,
        radius_law: RadiusLaw | RadiusValue,
        *,
        allow_irregular: bool = False,
        _known: tuple[Any, CanalRegularity] | None = None,
    ) -> None:
        if not isinstance(axis, Axis):
            raise ParameterError(
                f"axis must be a tubecad Axis (a SlopeCurve or another kind), got {type(axis).__name__}"
            )
        self.axis = axis
        self.radius_law = radius_law_of(radius_law, axis.span, axis=axis)
        if axis.closed:  # the circle at s1 must be the circle at s0
            self.radius_law.check_closes()
        allow_irregular = flag("allow_irregular", allow_irregular)
        self._offsets: dict[float, CanalSurface] = {}
        if _known is not None:  # (Moebius solution, regularity) of this very surface, from a sibling (offset, piece)
            self._moebius, self.regularity = _known
        else:
            self._moebius = None if self.radius_law.constant else self._solve_moebius()
            self.regularity = self._check_regularity()
        if not self.regularity.ok and not allow_irregular:
            raise RegularityError(self.regularity.message())

    # --- the net -----------------------------------------------------------------------
    def _solve_moebius(self) -> tuple[Any, Any, Any]:
        """Mb(s), Mb'(s), Mb''(s): the half-angle system's fundamental matrix and its derivatives."""
        law, axis = self.radius_law, self.axis

        def matrix(s: np.ndarray) -> np.ndarray:
            dr = law.dr(s)
            k1, k2 = axis.normal_development(s)
            q = np.sqrt(1.0 - dr * dr)
            alpha, half_beta = 0.5 * dr * k2 / q, 0.5 * dr * k1 / q
            return np.stack([np.stack([-half_beta, alpha], -1), np.stack([alpha, half_beta], -1)], -2)

        m = solve_linear_ode(matrix, self.s_breaks(), np.eye(2), name="radius: the stringers' equation")
        dm = m.derivative()
        return m, dm, dm.derivative()

    def _angles(self, chi0: FloatArray, s: FloatArray, order: int = 0) -> _Angles:
        """cos, sin of chi(chi0, s) and (for ``order`` 2) chi_u, chi_s, chi_uu, chi_us, chi_ss,
        from (a, b) = Mb v, v = (sin h, cos h), h = chi0 / 2, chi = 2 atan2(a, b)."""
        if self._moebius is None:  # r' = 0: chi = chi0
            zero = np.zeros(np.broadcast_shapes(np.shape(chi0), np.shape(s)))
            return _Angles(np.cos(chi0) + zero, np.sin(chi0) + zero, 1.0 + zero, zero, zero, zero, zero)
        h = 0.5 * chi0
        sh, ch = np.sin(h), np.cos(h)
        mats = [m(s) for m in (self._moebius if order else self._moebius[:1])]

        def apply(mat: FloatArray, x: FloatArray, y: FloatArray) -> tuple[FloatArray, FloatArray]:
            return mat[..., 0, 0] * x + mat[..., 0, 1] * y, mat[..., 1, 0] * x + mat[..., 1, 1] * y

        a, b = apply(mats[0], sh, ch)
        rr = a * a + b * b
        cos, sin = (b * b - a * a) / rr, 2.0 * a * b / rr
        if not order:
            return _Angles(cos, sin)
        da, db = apply(mats[1], sh, ch)
        dda, ddb = apply(mats[2], sh, ch)
        wa, wb = apply(mats[0], ch, -sh)  # Mb w, w = dv/dh
        dwa, dwb = apply(mats[1], ch, -sh)
        cross = b * da - a * db  # chi_s = 2 cross / rr
        dot = a * da + b * db  # (rr)' = 2 dot
        n1 = b * wa - a * wb  # chi_u = n1 / rr (= det Mb / rr)
        dn1 = db * wa + b * dwa - da * wb - a * dwb
        chi_s = 2.0 * cross / rr
        chi_ss = 2.0 * ((b * dda - a * ddb) / rr - 2.0 * cross * dot / rr**2)
        chi_u = n1 / rr
        chi_uu = -n1 * (a * wa + b * wb) / rr**2
        chi_us = dn1 / rr - 2.0 * n1 * dot / rr**2
        return _Angles(cos, sin, chi_u, chi_s, chi_uu, chi_us, chi_ss)

    def moebius_matrix(self, s: ArrayLike) -> FloatArray:
        """Mb(s), shape s.shape + (2, 2): the half-angle system's fundamental matrix, which maps
        (sin(chi0/2), cos(chi0/2)) to a multiple of (sin(chi/2), cos(chi/2)) (the identity for
        a constant law)."""
        s = np.asarray(s, dtype=float)
        if self._moebius is None:
            return np.broadcast_to(np.eye(2), s.shape + (2, 2)).copy()
        return self._moebius[0](s)

    def stringer_angle(self, chi0: ArrayLike, s: ArrayLike) -> FloatArray:
        """chi(s) on the stringer that starts at angle ``chi0``: chi0 plus twice the turn of the
        half-angle vector (a turn in (-pi, pi]), so continuous while |chi - chi0| < 2 pi."""
        chi0, s = np.asarray(chi0, dtype=float), self._inside(s)
        if self._moebius is None:
            return chi0 + np.zeros(np.shape(s))
        h = 0.5 * chi0
        sh, ch = np.sin(h), np.cos(h)
        m = self._moebius[0](s)
        a, b = m[..., 0, 0] * sh + m[..., 0, 1] * ch, m[..., 1, 0] * sh + m[..., 1, 1] * ch
        return chi0 + 2.0 * np.arctan2(a * ch - b * sh, b * ch + a * sh)

    def closing_angle(self, chi0: ArrayLike) -> FloatArray:
        """On a closed axis, where the stringer that leaves the closing circle at angle
        ``chi0`` (from r1 at the span's start) comes back to it: the absolute angle (from
        r1(s0) too) phi = chi(chi0, s1) + h, h the axis' holonomy, since r1(s1) = cos h r1(s0)
        + sin h r2(s0) and the circle at s1 is the circle at s0. A constant law gives chi0 + h.
        phi is a Moebius map of the circle (increasing: the stringers' ends keep their order)."""
        if not self.axis.closed:
            raise ParameterError("closing_angle: the axis is not a closed loop")
        chi0 = np.asarray(chi0, dtype=float)
        return self.stringer_angle(chi0, np.full(np.shape(chi0), self.span[1])) + self.axis.holonomy

    # --- measures and the circles -------------------------------------------------------
    @property
    def span(self) -> tuple[float, float]:
        return self.axis.span

    @property
    def length(self) -> float:
        """L, the axis length over the span."""
        return self.axis.length

    def inside(self, s: ArrayLike) -> FloatArray:
        """``s`` as a float array, checked to lie in the span (:meth:`Axis.inside`)."""
        return self.axis.inside(s)

    _inside = inside

    def s_breaks(self) -> FloatArray:
        """The span's ends, the law's breaks (a table's knots) and the axis' joints, sorted:
        where the surface is only C^k (r''' or k1, k2 may jump there)."""
        s0, s1 = self.span
        joints = [s for s, _ in self.axis.joints if s0 < s < s1]
        return np.unique(np.concatenate([[s0, s1], self.radius_law.breaks, joints]))

    _breaks = s_breaks  # the former private name

    @property
    def constant_radius(self) -> bool:
        """Whether the law is constant (r' = 0: chi = chi0, Mb = I, the tube's closed forms
        apply; :meth:`fast_path` gives that tube)."""
        return self.radius_law.constant

    def fast_path(self) -> CanalSurface | CurvatureLineTube:
        """A constant law's surface as the :class:`CurvatureLineTube` of that radius (the
        same points, the same operations in the same order; its regularity was checked
        here), any other law the canal surface itself."""
        if self.radius_law.constant:
            return self._as_tube()
        return self

    def dispatch(self, tube: Callable[[CurvatureLineTube], T], canal: Callable[[CanalSurface], T]) -> T:
        """The protocol's double dispatch: ``canal(self)`` on a varying law; a constant law
        takes the tube's function with the tube of that radius (:meth:`fast_path`)."""
        if self.radius_law.constant:
            return tube(self._as_tube())
        return canal(self)

    def _as_tube(self) -> CurvatureLineTube:
        """A constant law's surface as the tube of that radius (its regularity checked here)."""
        return CurvatureLineTube(self.axis, self.radius_law.constant_value, allow_irregular=True)

    def circle(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The characteristic circle at ``s``: (centre c - r r' t, radius r q, plane normal t)."""
        s = self._inside(s)
        law = self.radius_law
        r, dr = law.r(s), law.dr(s)
        t = self.axis.rotation_minimising_frame(s)[0]
        return self.axis.position(s) - (r * dr)[..., None] * t, r * np.sqrt(1.0 - dr * dr), t

    def offset(self, distance: float, *, allow_irregular: bool = False) -> CanalSurface:
        """The normal offset by ``distance`` (outward > 0): the canal surface of r + distance,
        with the same characteristic circles' planes and the same stringers chi(chi0, s)
        (so the same Moebius solution; its regularity is its own, checked once per distance)."""
        distance = float(distance)
        if distance not in self._offsets:
            law = self.radius_law.shifted(distance)
            out = CanalSurface(self.axis, law, allow_irregular=True, _known=(self._moebius, self.regularity))
            out.regularity = out._check_regularity()
            self._offsets[distance] = out
        out = self._offsets[distance]
        if not out.regularity.ok and not allow_irregular:
            raise RegularityError(out.regularity.message())
        return out

    def restricted(self, span: tuple[float, float]) -> CanalSurface:
        """The same surface over a sub-span of the axis (a stiffener's), its stringers named
        by their angle chi0 at the sub-span's start (:meth:`stringer_angle` of this surface
        there converts)."""
        axis, law = self.axis.restricted(span), self.radius_law.restricted(span)
        if axis.span == self.span:
            return self
        piece = CanalSurface(
            axis, law, allow_irregular=True, _known=(None, self.regularity)
        )  # a piece of a regular surface is regular
        piece._moebius = None if law.constant else piece._solve_moebius()
        return piece

    # --- evaluation -------------------------------------------------------------------
    def points(self, chi0: ArrayLike, s: ArrayLike) -> FloatArray:
        """X(chi(chi0, s), s) for ``chi0`` and ``s`` broadcast together; shape broadcast + (3,).

        Pass ``chi0[:, None]`` and ``s[None, :]`` for a grid. A constant law gives exactly
        :meth:`CurvatureLineTube.points` (the same operations in the same order)."""
        chi0 = np.asarray(chi0, dtype=float)
        s = self._inside(s)
        law = self.radius_law
        c = self.axis.position(s)
        t, r1, r2 = self.axis.rotation_minimising_frame(s)
        ang = self._angles(chi0, s)
        if law.constant:
            rc, rs = (law.value * ang.cos)[..., None], (law.value * ang.sin)[..., None]
        else:
            r, dr = law.r(s), law.dr(s)
            rq = r * np.sqrt(1.0 - dr * dr)
            rc, rs = (rq * ang.cos)[..., None], (rq * ang.sin)[..., None]
        out = rc * r1
        out += rs * r2
        if not law.constant:
            out += (-law.r(s) * law.dr(s))[..., None] * t
        out += c
        return out

    def grid(self, chi0: ArrayLike, s: ArrayLike) -> FloatArray:
        """X on the grid chi0 x s: shape (len(chi0), len(s), 3)."""
        return self.points(np.asarray(chi0, dtype=float)[:, None], np.asarray(s, dtype=float)[None, :])

    def normal(self, chi0: ArrayLike, s: ArrayLike) -> FloatArray:
        """Outward unit normal -r' t + q e (the sphere's)."""
        chi0, s = np.broadcast_arrays(np.asarray(chi0, dtype=float), self._inside(s))
        t, r1, r2 = self.axis.rotation_minimising_frame(s)
        ang = self._angles(chi0, s)
        dr = self.radius_law.dr(s)
        e = ang.cos[..., None] * r1 + ang.sin[..., None] * r2
        return (-dr)[..., None] * t + np.sqrt(1.0 - dr * dr)[..., None] * e

    def _sphere_derivatives(
        self, cos: FloatArray, sin: FloatArray, s: FloatArray, second: bool = True
    ) -> dict[str, FloatArray]:
        """X and its partial derivatives in (chi, s) with chi held fixed (docs/MATH.md section 8).

        With g = -r r', h = r q, kappa = k1 cos + k2 sin, kbar = k2 cos - k1 sin:
            X = c + g t + h e,  X_chi = h ebar,  X_chichi = -h e,  X_chis = h' ebar - h kbar t,
            X_s = A t + B e + C ebar,   A = 1 + g' - h kappa,  B = h' + g kappa,  C = g kbar,
            X_ss = (A' - B kappa - C kbar) t + (A kappa + B') e + (A kbar + C') ebar.
        """
        law, a = self.radius_law, self.axis.at(s)
        r, dr, ddr = law.r(s), law.dr(s), law.ddr(s)
        q = np.sqrt(1.0 - dr * dr)
        dq = -dr * ddr / q
        g, dg = -r * dr, -(dr * dr + r * ddr)
        h, dh = r * q, dr * q + r * dq
        kappa, kbar = a.k1 * cos + a.k2 * sin, a.k2 * cos - a.k1 * sin
        A, B, C = 1.0 + dg - h * kappa, dh + g * kappa, g * kbar
        cos_, sin_ = cos[..., None], sin[..., None]
        e, ebar = cos_ * a.r1 + sin_ * a.r2, -sin_ * a.r1 + cos_ * a.r2

        def v(x: FloatArray) -> FloatArray:
            return x[..., None]

        first = {
            "X": a.position + v(g) * a.t + v(h) * e,
            "X_chi": v(h) * ebar,
            "X_s": v(A) * a.t + v(B) * e + v(C) * ebar,
        }
        if not second:
            return first
        dk1, dk2 = self.axis.normal_development_derivative(s)
        dddr = law.dddr(s)
        ddq = -(ddr * ddr + dr * dddr) / q - (dr * ddr) ** 2 / q**3
        ddg, ddh = -(3.0 * dr * ddr + r * dddr), ddr * q + 2.0 * dr * dq + r * ddq
        dkappa, dkbar = dk1 * cos + dk2 * sin, dk2 * cos - dk1 * sin
        dA, dB, dC = ddg - dh * kappa - h * dkappa, ddh + dg * kappa + g * dkappa, dg * kbar + g * dkbar
        return {
            **first,
            "X_chichi": -v(h) * e,
            "X_chis": v(dh) * ebar - v(h * kbar) * a.t,
            "X_ss": v(dA - B * kappa - C * kbar) * a.t + v(A * kappa + dB) * e + v(A * kbar + dC) * ebar,
        }

    def derivatives(self, chi0: ArrayLike, s: ArrayLike) -> SurfaceDerivatives:
        """Y(chi0, s) = X(chi(chi0, s), s) and its partial derivatives up to second order
        (S_u means d/d chi0), by the chain rule:

            Y_u = X_chi chi_u,   Y_s = X_s + X_chi chi_s,   Y_uu = X_chichi chi_u^2 + X_chi chi_uu,
            Y_us = X_chichi chi_u chi_s + X_chis chi_u + X_chi chi_us,
            Y_ss = X_ss + 2 X_chis chi_s + X_chichi chi_s^2 + X_chi chi_ss.
        """
        chi0, s = np.broadcast_arrays(np.asarray(chi0, dtype=float), self._inside(s))
        ang = self._angles(chi0, s, order=2)
        x = self._sphere_derivatives(ang.cos, ang.sin, s)
        c_u, c_s, c_uu, c_us, c_ss = ang.rates()

        def v(y: FloatArray) -> FloatArray:
            return y[..., None]

        return SurfaceDerivatives(
            S=x["X"],
            S_u=x["X_chi"] * v(c_u),
            S_s=x["X_s"] + x["X_chi"] * v(c_s),
            S_uu=x["X_chichi"] * v(c_u**2) + x["X_chi"] * v(c_uu),
            S_us=x["X_chichi"] * v(c_u * c_s) + x["X_chis"] * v(c_u) + x["X_chi"] * v(c_us),
            S_ss=x["X_ss"] + 2.0 * x["X_chis"] * v(c_s) + x["X_chichi"] * v(c_s**2) + x["X_chi"] * v(c_ss),
        )

    def tangents(self, chi0: ArrayLike, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(Y, Y_u, Y_s) of :meth:`derivatives` only: for Newton steps on the surface."""
        chi0, s = np.broadcast_arrays(np.asarray(chi0, dtype=float), self._inside(s))
        ang = self._angles(chi0, s, order=2)
        x = self._sphere_derivatives(ang.cos, ang.sin, s, second=False)
        c_u, c_s, *_ = ang.rates()
        return x["X"], x["X_chi"] * c_u[..., None], x["X_s"] + x["X_chi"] * c_s[..., None]

    def fundamental_forms(self, chi0: ArrayLike, s: ArrayLike) -> FundamentalForms:
        """E, F, G, L, M, N at (chi0, s), computed from the derivative vectors."""
        return FundamentalForms.from_derivatives(self.derivatives(chi0, s))

    # --- regularity ------------------------------------------------------------------------
    def fold_ratio(self, s: ArrayLike) -> FloatArray:
        """r (k q + r'') / q^2 with k = sqrt(k1^2 + k2^2): sqrt(G) = q (1 - fold) on the
        stringer where the axis bends most; the surface is regular where it is < 1."""
        s = self._inside(s)
        law = self.radius_law
        r, dr, ddr = law.r(s), law.dr(s), law.ddr(s)
        q2 = 1.0 - dr * dr
        return r * (np.hypot(*self.axis.normal_development(s)) * np.sqrt(q2) + ddr) / q2

    def _check_regularity(self) -> CanalRegularity:
        law, (s0, s1) = self.radius_law, self.span
        n = int(min(MAX_FOLD_SAMPLES, max(2001, math.ceil(8 * self.length / law.min_radius) + 1)))
        s = np.union1d(np.linspace(s0, s1, n), law.breaks)
        s_fold, fold = refined_extreme(self.fold_ratio, s, largest=True, name="radius: the fold ratio")

        def speed(x: np.ndarray) -> np.ndarray:
            return np.sqrt(1.0 - law.dr(x) ** 2) * (1.0 - self.fold_ratio(x))

        s_speed, min_speed = refined_extreme(speed, s, largest=False, name="radius: the stringer speed")
        intervals = _runs(lambda x: float(self.fold_ratio(np.array(x))) - 1.0, s, self.fold_ratio(s) >= 1.0)
        # a folded surface is refused anyway; one no longer than its smallest radius (a ring
        # frame's piece) whose axis turns by less than a radian cannot come back into its spheres
        short = (
            self.length <= law.min_radius
            and self.length * float(np.hypot(*self.axis.normal_development(s)).max()) < 1.0
        )
        entry = self._sphere_entry() if not intervals and not short else None
        return CanalRegularity(law.max_slope, law.s_at_max_slope, fold, s_fold, min_speed, s_speed, intervals, entry)

    def _sphere_entry(self) -> tuple[float, float, float] | None:
        """Where the surface passes inside one of its own spheres: a regular canal surface is
        the boundary of the union of its spheres, so no point X(chi, s) lies strictly inside
        the sphere at any other s' (near s' = s it touches them from outside, to second
        order); a point inside one (deeper than round-off) is a self-intersection. Points
        every r_min / 8 along and 32 around (a penetration much shallower than that
        spacing can be missed), tested against the spheres at the same samples, a chunk of
        rings at a time. Returns the deepest found: (s of the point, s' of the sphere, depth)."""
        from scipy.spatial import cKDTree

        law, (s0, s1) = self.radius_law, self.span
        count = int(min(MAX_FOLD_SAMPLES, max(257, math.ceil(8 * self.length / law.min_radius) + 1)))
        s = np.linspace(s0, s1, count)
        centres, radii = self.axis.position(s), law.r(s)
        tree = cKDTree(centres)
        chi = np.linspace(0.0, 2.0 * math.pi, 32, endpoint=False)
        apart = 0.5 * (s[1] - s[0])
        best: tuple[float, float, float] | None = None
        for rows in np.array_split(np.arange(count), max(1, math.ceil(count / 128))):
            points = self.points(chi[None, :], s[rows][:, None]).reshape(-1, 3)
            at = np.repeat(s[rows], len(chi))
            near = cKDTree(points).sparse_distance_matrix(tree, law.max_radius, output_type="ndarray")
            i, j, d = near["i"], near["j"], near["v"]
            depth = radii[j] - d
            inside = (depth > 1e-9 * radii[j]) & (np.abs(at[i] - s[j]) > apart)
            if inside.any():
                k = int(np.argmax(np.where(inside, depth, -np.inf)))
                if best is None or depth[k] > best[2]:
                    best = (float(at[i[k]]), float(s[j[k]]), float(depth[k]))
        return best

    # --- measures ----------------------------------------------------------------------------
    def _quadrature(self, n_chi: int, panels: int, order: int) -> tuple[FloatArray, FloatArray, FloatArray, float]:
        """(chi, s, weights (s), d chi): Gauss-Legendre panels in s (starting at the law's and
        the axis' breaks), the periodic trapezoid rule in chi."""
        breaks = self.s_breaks()
        edges = np.concatenate(
            [
                np.linspace(a, b, max(1, math.ceil(panels * (b - a) / self.length)) + 1)[:-1]
                for a, b in itertools.pairwise(breaks)
            ]
            + [breaks[-1:]]
        )
        x, w = np.polynomial.legendre.leggauss(order)
        mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
        chi = np.linspace(0.0, 2.0 * math.pi, n_chi, endpoint=False)
        return chi, (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel(), 2.0 * math.pi / n_chi

    def measures(self, n_chi: int = 32, panels: int = 64, order: int = 16) -> tuple[float, float]:
        """(area, volume) by quadrature in the (chi, s) coordinates (chi uniform: the integrands
        are trigonometric polynomials of low degree in chi, so the trapezoid rule is exact).

        area = Int Int |X_chi x X_s| dchi ds; volume of the solid bounded by the surface and the
        discs of the first and last characteristic circles, by the divergence theorem:
        V = 1/3 (Int Int (X - p) . (X_chi x X_s) dchi ds + pi R1^2 (C1 - p) . t1), p = C0 the
        first circle's centre (so its disc, normal -t0, adds nothing) and R1, C1, t1 the last's."""
        chi, s, ws, dchi = self._quadrature(n_chi, panels, order)
        x = self._sphere_derivatives(np.cos(chi)[:, None], np.sin(chi)[:, None], s[None, :])
        cross = np.cross(x["X_chi"], x["X_s"])  # = h sqrt(G) n, outward where the surface is regular
        c, radius, t = self.circle(np.array(self.span))
        area = float((np.linalg.norm(cross, axis=-1) * ws).sum() * dchi)
        flux = float((np.einsum("...i,...i", x["X"] - c[0], cross) * ws).sum() * dchi)
        volume = (flux + math.pi * float(radius[1]) ** 2 * float((c[1] - c[0]) @ t[1])) / 3.0
        return area, volume

    @property
    def area(self) -> float:
        """The surface's area between the first and last characteristic circles (quadrature)."""
        return self.measures()[0]

    @property
    def area_exact(self) -> float:
        """The exact surface's area over the span, A = Int Int sqrt(E G - F^2) du ds (F = 0),
        taken in (chi, s) as Int Int |X_chi x X_s| dchi ds (the same surface, chi = chi(u, s)
        a change of variable; docs/MATH.md section 8): Gauss-Legendre panels between the
        breaks doubled with the periodic trapezoid rule in chi (exact for |X_chi x X_s| =
        r q |sqrt(G)|, linear in cos chi, sin chi) until two estimates agree to
        AREA_CONVERGED. Computed once.

        Returns:
            The area, to about 1e-14 relative on a regular surface.
        """
        area = self.__dict__.get("_area_exact")
        if area is None:
            n_chi, panels = 8, AREA_PANELS
            area = self._area_by_quadrature(n_chi, panels)
            while panels < MOST_AREA_PANELS:
                n_chi, panels, coarse = min(2 * n_chi, MOST_AREA_CHI), 2 * panels, area
                area = self._area_by_quadrature(n_chi, panels)
                if abs(area - coarse) <= AREA_CONVERGED * abs(area):
                    break
            self.__dict__["_area_exact"] = area
        return area

    def _area_by_quadrature(self, n_chi: int, panels: int, order: int = 16) -> float:
        """Int Int |X_chi x X_s| dchi ds on ``n_chi`` x (about ``panels`` x ``order``) points
        (:meth:`_quadrature`), a chunk of panels at a time."""
        chi, s, ws, dchi = self._quadrature(n_chi, panels, order)
        cos, sin = np.cos(chi)[:, None], np.sin(chi)[:, None]
        total = 0.0
        for rows in np.array_split(np.arange(len(s)), max(1, len(s) // 4096)):
            x = self._sphere_derivatives(cos, sin, s[None, rows], second=False)
            total += float((np.linalg.norm(np.cross(x["X_chi"], x["X_s"]), axis=-1) * ws[rows]).sum())
        return total * dchi

    def swept_measures(self, panels: int = 64, order: int = 16) -> tuple[float, float]:
        """(area, volume) from one-dimensional integrals, independent of the surface's
        parameterisation: A = 2 pi Int r (q^2 - r r'') ds (the stringer speed averaged round
        the circle) and V = pi Int (r q)^2 (q^2 - r r'') ds (the characteristic discs, whose
        centres advance by q^2 - r r'' per unit s along t); Gauss-Legendre panels in s."""
        _, s, ws, _ = self._quadrature(1, panels, order)
        law = self.radius_law
        r, dr, ddr = law.r(s), law.dr(s), law.ddr(s)
        advance = 1.0 - dr**2 - r * ddr
        return (
            float((2 * math.pi * r * advance * ws).sum()),
            float((math.pi * r**2 * (1.0 - dr**2) * advance * ws).sum()),
        )

    @property
    def volume(self) -> float:
        """The volume enclosed with the discs of the first and last characteristic circles."""
        return self.measures()[1]

    def describe(self) -> dict[str, Any]:
        return {"radius": self.radius_law.describe(), "regularity": self.regularity.describe()}

    def __repr__(self) -> str:
        return f"CanalSurface({self.axis!r}, {self.radius_law!r})"


def _runs(excess: Any, s: np.ndarray, bad: np.ndarray) -> list[tuple[float, float]]:
    """Maximal runs of samples where ``bad``, their ends refined by root finding on ``excess``."""
    if not bad.any():
        return []
    from scipy.optimize import brentq  # at first use: a surface that never folds loads no scipy.optimize

    runs = []
    edges = np.flatnonzero(np.diff(bad.astype(np.int8)))
    starts = ([0] if bad[0] else []) + [e + 1 for e in edges if not bad[e]]
    ends = [e for e in edges if bad[e]] + ([len(s) - 1] if bad[-1] else [])
    for a, b in zip(starts, ends):
        left = s[a] if a == 0 else brentq(excess, s[a - 1], s[a])
        right = s[b] if b == len(s) - 1 else brentq(excess, s[b], s[b + 1])
        runs.append((float(left), float(right)))
    return runs


def tube_or_canal(
    axis: Axis, radius: RadiusLaw | RadiusValue, allow_irregular: bool = False
) -> CurvatureLineTube | CanalSurface:
    """A constant radius (a number) gives today's :class:`CurvatureLineTube`; any other law
    (an expression, a callable, a table) the :class:`CanalSurface`.

    Args:
        axis: the surface's axis, any :class:`~tubecad.curves.axis.Axis`.
        radius: the radius, model units: a number, or anything
            :func:`~tubecad.curves.radius_law.radius_law` takes (with x, y, z of the axis
            point in an expression), or a :class:`~tubecad.curves.radius_law.RadiusLaw`.
        allow_irregular: build the surface even where it is not regular (default False).

    Returns:
        The :class:`CurvatureLineTube` for a constant law, else the :class:`CanalSurface`.

    Raises:
        ParameterError: a bad radius or radius law.
        RegularityError: the surface is not regular, unless ``allow_irregular``.
    """
    law = radius_law_of(radius, axis.span, axis=axis)
    if law.constant:
        return CurvatureLineTube(axis, law.constant_value, allow_irregular=allow_irregular)
    return CanalSurface(axis, law, allow_irregular=allow_irregular)
