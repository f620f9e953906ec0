"""The tubular surface referred to its lines of curvature (paper eq. 7, docs/MATH.md section 2).

    phi = u - Int sigma ds            (for a slope curve Int sigma ds = psi sin b)
    S(u, s) = c(s) + rho (cos phi n(s) + sin phi bn(s))
            = c(s) + rho (cos u r1(s) + sin u r2(s))

where (t, r1, r2) is the rotation-minimising frame. The circles s = const and their
orthogonal trajectories u = const are both lines of curvature: E = rho^2, F = 0,
G = (1 - rho k cos phi)^2, L = -rho, M = 0, N = k cos phi (1 - rho k cos phi).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..curves.slope_curve import SlopeCurve
from ..errors import ParameterError, RegularityError
from ..validation import bounded_length, flag
from .forms import FundamentalForms, SurfaceDerivatives
from .regularity import RegularityReport, check_regularity

FloatArray = np.ndarray


class CurvatureLineTube:
    """A tube of radius ``radius`` about ``axis`` over the axis' span, in curvature-line
    coordinates: u is the angle around the circle (period 2 pi), s the axis arc length.

    A tube that is not regular (rho k >= 1 somewhere, or an axis that comes back within
    2 rho of itself) raises :class:`RegularityError` unless ``allow_irregular=True``;
    the measured facts are kept in :attr:`regularity` either way.
    """

    def __init__(self, axis: SlopeCurve, radius: float, *, allow_irregular: bool = False) -> None:
        if not isinstance(axis, SlopeCurve):
            raise ParameterError(f"axis must be a tubecad SlopeCurve, got {type(axis).__name__}")
        self.axis = axis
        self.radius = bounded_length("radius", radius, 0.0)
        allow_irregular = flag("allow_irregular", allow_irregular)
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

    def offset(self, distance: float, *, allow_irregular: bool = False) -> "CurvatureLineTube":
        """The normal offset by ``distance`` (outward > 0): the tube of radius rho + distance
        on the same axis, with the same curvature-line net (docs/MATH.md section 4)."""
        return CurvatureLineTube(self.axis, self.radius + distance, allow_irregular=allow_irregular)

    # --- evaluation -------------------------------------------------------------------
    def phi(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """phi = u - Int sigma ds: the angle from the principal normal n (paper eq. 6)."""
        return np.asarray(u, dtype=float) - self.axis.twist(s)

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
        """S and its partial derivatives up to second order, from the Frenet-Serret formulas
        n' = -k t + sigma bn, bn' = -sigma n and phi_s = -sigma (paper eq. 11, corrected)."""
        u, s = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(s, dtype=float))
        a = self.axis.evaluate(s)
        rho = self.radius
        k, sig = a.k[..., None], a.torsion[..., None]
        dk = self.axis.curvature_derivative(s)[..., None]
        dsig = dk * math.tan(self.axis.beta)
        phi = (u - self.axis.twist(s))[..., None]
        cp, sp = np.cos(phi), np.sin(phi)
        phi_s, phi_ss = -sig, -dsig

        t, n, bn = a.t, a.n, a.bn
        dn = -k * t + sig * bn
        dbn = -sig * n
        ddn = -dk * t - (k * k + sig * sig) * n + dsig * bn
        ddbn = sig * k * t - dsig * n - sig * sig * bn

        ring = cp * n + sp * bn  # outward radial unit vector
        ring_u = -sp * n + cp * bn
        ring_s = cp * dn + sp * dbn + phi_s * ring_u
        ring_u_s = -sp * dn + cp * dbn - phi_s * ring
        ring_ss = phi_s * (-sp * dn + cp * dbn) + cp * ddn + sp * ddbn + phi_ss * ring_u + phi_s * ring_u_s

        return SurfaceDerivatives(
            S=a.position + rho * ring,
            S_u=rho * ring_u,
            S_s=t + rho * ring_s,
            S_uu=-rho * ring,
            S_us=rho * ring_u_s,
            S_ss=k * n + rho * ring_ss,
        )

    def fundamental_forms(self, u: ArrayLike, s: ArrayLike) -> FundamentalForms:
        """E, F, G, L, M, N at (u, s), computed from the derivative vectors."""
        return FundamentalForms.from_derivatives(self.derivatives(u, s))

    def __repr__(self) -> str:
        return f"CurvatureLineTube({self.axis!r}, radius={self.radius!r})"
