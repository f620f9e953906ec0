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

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError, RegularityError
from tubecad.core.validation import bounded_length, flag
from tubecad.curves.axis import Axis
from tubecad.surface.forms import FundamentalForms, SurfaceDerivatives
from tubecad.surface.regularity import RegularityReport, check_regularity

FloatArray = np.ndarray


class CurvatureLineTube:
    """A tube of radius ``radius`` about ``axis`` over the axis' span, in curvature-line
    coordinates: u is the angle around the circle (period 2 pi), s the axis arc length.

    A tube that is not regular (rho k >= 1 somewhere, or an axis that comes back within
    2 rho of itself) raises :class:`RegularityError` unless ``allow_irregular=True``;
    the measured facts are kept in :attr:`regularity` either way.
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

    # --- evaluation -------------------------------------------------------------------
    def phi(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """phi = u - Int sigma ds: the angle from the principal normal n (paper eq. 6; slope curves)."""
        return np.asarray(u, dtype=float) - self.axis.twist(s)

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
