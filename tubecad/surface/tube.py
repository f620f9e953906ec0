"""The tubular surface referred to its lines of curvature (paper eq. 7, docs/MATH.md sections 2, 7).

    S(u, s) = c(s) + rho (cos u r1(s) + sin u r2(s))

where (t, r1, r2) is the axis' rotation-minimising frame (for a slope curve this is
c + rho (cos phi n + sin phi bn) with phi = u - psi sin b). With the normal development
k1, k2 of the axis and kappa_u = k1 cos u + k2 sin u (= k cos phi), the circles s = const
and their orthogonal trajectories u = const are both lines of curvature: E = rho^2, F = 0,
G = (1 - rho kappa_u)^2, L = -rho, M = 0, N = kappa_u (1 - rho kappa_u).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Never, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError, RegularityError
from tubecad.core.validation import bounded_length, flag
from tubecad.curves.axis import Axis
from tubecad.curves.radius_law import RadiusLaw
from tubecad.curves.radius_law import radius_law as radius_law_of
from tubecad.surface.forms import FundamentalForms, SurfaceDerivatives
from tubecad.surface.regularity import RegularityReport, check_regularity

FloatArray = np.ndarray
T = TypeVar("T")


class CurvatureLineTube:
    """A tube of radius ``radius`` about ``axis`` over the axis' span, in curvature-line
    coordinates: u is the angle around the circle (period 2 pi), s the axis arc length.

    A tube that is not regular (rho k >= 1 somewhere, or an axis that comes back within
    2 rho of itself) raises :class:`RegularityError` unless ``allow_irregular=True``;
    the measured facts are kept in :attr:`regularity` either way.

    Args:
        axis: the tube's axis, any :class:`~tubecad.curves.axis.Axis` (a slope curve, a
            natural, parametric, points, edge or route axis); the tube covers its span.
        radius: the tube radius rho, model units, > 0.
        allow_irregular: build the tube even where it is not regular (default False: a
            :class:`RegularityError` instead).

    Raises:
        ParameterError: ``axis`` not an Axis, or ``radius`` not a positive length.
        RegularityError: rho k >= 1 somewhere, or the axis comes back within 2 rho of
            itself, unless ``allow_irregular``.
    """

    def __init__(self, axis: Axis, radius: float, *, allow_irregular: bool = False) -> None:
        if not isinstance(axis, Axis):
            raise ParameterError(
                f"axis must be a tubecad Axis (a SlopeCurve or another kind), got {type(axis).__name__}"
            )
        self.axis = axis
        self.radius = bounded_length("radius", radius, 0.0)
        allow_irregular = flag("allow_irregular", allow_irregular)
        problem = axis.tube_radius_problem(self.radius)
        if problem is not None and not allow_irregular:
            raise RegularityError(f"{problem} (pass allow_irregular=True to build it anyway)")
        self.regularity: RegularityReport = check_regularity(axis, self.radius)
        if not self.regularity.ok and not allow_irregular:
            raise RegularityError(self.regularity.message())

    # --- exact measures (docs/MATH.md section 4) -------------------------------------------
    @property
    def span(self) -> tuple[float, float]:
        return self.axis.span

    @property
    def length(self) -> float:
        """L, the axis length over the span."""
        return self.axis.length

    @property
    def area_exact(self) -> float:
        """2 pi rho L (Pappus-Guldin for tubes)."""
        return 2.0 * math.pi * self.radius * self.length

    @property
    def volume_exact(self) -> float:
        """pi rho^2 L, enclosed with planar end discs in the normal planes."""
        return math.pi * self.radius**2 * self.length

    def offset(self, distance: float, *, allow_irregular: bool = False) -> CurvatureLineTube:
        """The normal offset by ``distance`` (outward > 0): the tube of radius rho + distance
        on the same axis, with the same curvature-line net (docs/MATH.md section 4)."""
        return CurvatureLineTube(self.axis, self.radius + distance, allow_irregular=allow_irregular)

    def restricted(self, span: tuple[float, float]) -> CurvatureLineTube:
        """The same tube over a sub-span of the axis (a stiffener's); the restricted axis keeps
        its frame, so a stringer keeps its angle u."""
        return CurvatureLineTube(self.axis.restricted(span), self.radius, allow_irregular=True)

    # --- the canal surface's members in the tube's closed form (r = rho: r' = 0, q = 1, Mb = I) ---
    @property
    def radius_law(self) -> RadiusLaw:
        """The constant law r(s) = rho (its r', r'', r''' are 0 exactly)."""
        law = self.__dict__.get("_radius_law")
        if law is None:
            law = self.__dict__["_radius_law"] = radius_law_of(self.radius, self.axis.span)
        return law

    @property
    def constant_radius(self) -> bool:
        """Always True: the tube's fast path (closed forms, the 9-component frame fit)."""
        return True

    def fast_path(self) -> CurvatureLineTube:
        """The tube itself (it is the fast path)."""
        return self

    def dispatch(self, tube: Callable[[CurvatureLineTube], T], canal: Callable[[Never], object]) -> T:  # noqa: ARG002 - the protocol's signature
        """``tube(self)``: a tube takes the tube's function (the protocol's double dispatch;
        ``canal``, the canal surface's function, is never called here)."""
        return tube(self)

    def inside(self, s: ArrayLike) -> FloatArray:
        """``s`` as a float array, checked to lie in the span (:meth:`Axis.inside`)."""
        return self.axis.inside(s)

    def s_breaks(self) -> FloatArray:
        """The span's ends and the axis' joints inside it, sorted (where k1, k2 may jump)."""
        s0, s1 = self.span
        joints = [s for s, _ in self.axis.joints if s0 < s < s1]
        return np.unique(np.concatenate([[s0, s1], joints]))

    def circle(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The ring at ``s``: (centre c, radius rho, plane normal t): r' = 0 makes the canal
        surface's c - r r' t the axis point and r q the radius rho."""
        s = np.asarray(s, dtype=float)
        t = self.axis.rotation_minimising_frame(s)[0]
        return self.axis.position(s), np.full(s.shape, self.radius), t

    def moebius_matrix(self, s: ArrayLike) -> FloatArray:
        """Mb(s) = I, shape s.shape + (2, 2): r' = 0, so the stringers keep their angle."""
        s = np.asarray(s, dtype=float)
        return np.broadcast_to(np.eye(2), s.shape + (2, 2)).copy()

    def stringer_angle(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """chi(u, s) = u: a tube's stringers are the lines u = const (broadcast with ``s``)."""
        return np.asarray(u, dtype=float) + np.zeros(np.shape(s))

    def closing_angle(self, u: ArrayLike) -> FloatArray:
        """On a closed axis u + h (h the axis' holonomy: r1(s1) = cos h r1(s0) + sin h r2(s0)):
        where the stringer that leaves the closing ring at ``u`` comes back to it."""
        if not self.axis.closed:
            raise ParameterError("closing_angle: the axis is not a closed loop")
        return np.asarray(u, dtype=float) + self.axis.holonomy

    # --- evaluation -------------------------------------------------------------------
    def phi(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """phi = u - Int sigma ds: the angle from the principal normal n (paper eq. 6; slope curves)."""
        twist = getattr(self.axis, "twist", None)  # Int sigma ds: a slope curve's
        if twist is None:
            raise ParameterError(f"phi: only a slope curve has the twist Int sigma ds, not a {self.axis.family} axis")
        return np.asarray(u, dtype=float) - twist(s)

    def normal_curvature(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """kappa_u = k1 cos u + k2 sin u (= k cos phi): the axis curvature seen along the
        stringer at u, so that |S_s| = 1 - rho kappa_u."""
        u = np.asarray(u, dtype=float)
        k1, k2 = self.axis.normal_development(s)
        return k1 * np.cos(u) + k2 * np.sin(u)

    def points(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """S(u, s) for ``u`` and ``s`` broadcast together; shape broadcast(u, s) + (3,).

        Pass ``u[:, None]`` and ``s[None, :]`` for a grid: the axis is then evaluated once
        per s and the circle once per u.
        """
        u = np.asarray(u, dtype=float)
        s = np.asarray(s, dtype=float)
        c = self.axis.position(s)
        _, r1, r2 = self.axis.rotation_minimising_frame(s)
        rc = (self.radius * np.cos(u))[..., None]
        rs = (self.radius * np.sin(u))[..., None]
        out = rc * r1
        out += rs * r2
        out += c
        return out

    def grid(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """S on the grid u x s: shape (len(u), len(s), 3)."""
        return self.points(np.asarray(u, dtype=float)[:, None], np.asarray(s, dtype=float)[None, :])

    def normal(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """Outward unit normal cos phi n + sin phi bn."""
        u, s = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(s, dtype=float))
        _, r1, r2 = self.axis.rotation_minimising_frame(s)
        return np.cos(u)[..., None] * r1 + np.sin(u)[..., None] * r2

    def derivatives(self, u: ArrayLike, s: ArrayLike) -> SurfaceDerivatives:
        """S and its partial derivatives up to second order, from the Bishop equations
        r1' = -k1 t, r2' = -k2 t, t' = k1 r1 + k2 r2 (docs/MATH.md section 7):

            S_u = rho e_u,  S_s = (1 - rho kappa_u) t,  S_uu = -rho e,  S_us = -rho kappa_u,u t,
            S_ss = -rho kappa_u' t + (1 - rho kappa_u) (k1 r1 + k2 r2)

        with e = cos u r1 + sin u r2, e_u = -sin u r1 + cos u r2, kappa_u = k1 cos u + k2 sin u.
        """
        u, s = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(s, dtype=float))
        a = self.axis.at(s)
        dk1, dk2 = self.axis.normal_development_derivative(s)
        rho = self.radius
        cu, su = np.cos(u), np.sin(u)
        kappa = (a.k1 * cu + a.k2 * su)[..., None]
        kappa_u = (a.k2 * cu - a.k1 * su)[..., None]
        kappa_s = (dk1 * cu + dk2 * su)[..., None]
        cu, su = cu[..., None], su[..., None]
        ring = cu * a.r1 + su * a.r2  # outward radial unit vector
        speed = 1.0 - rho * kappa
        return SurfaceDerivatives(
            S=a.position + rho * ring,
            S_u=rho * (-su * a.r1 + cu * a.r2),
            S_s=speed * a.t,
            S_uu=-rho * ring,
            S_us=-rho * kappa_u * a.t,
            S_ss=-rho * kappa_s * a.t + speed * a.curvature_vector,
        )

    def fundamental_forms(self, u: ArrayLike, s: ArrayLike) -> FundamentalForms:
        """E, F, G, L, M, N at (u, s), computed from the derivative vectors."""
        return FundamentalForms.from_derivatives(self.derivatives(u, s))

    def __repr__(self) -> str:
        return f"CurvatureLineTube({self.axis!r}, radius={self.radius!r})"
