"""Slope-curve families with closed-form integrals (docs/MATH.md section 1).

Each family gives k(s) and the antiderivatives Int k ds, Int cos psi ds, Int sin psi ds
in closed form, so the axis, its frame and the tube are evaluated exactly (to round-off).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import fresnel

from tubecad.core.errors import ParameterError
from tubecad.core.validation import bounded_length, finite_number, number_in_range
from tubecad.curves.slope_curve import FloatArray, SlopeCurve


class LogSpiral(SlopeCurve):
    """k = a / s (s > 0): the paper's axis, whose horizontal projection is a logarithmic spiral.

    psi = a ln s / cos b and, with cb = cos b (paper eq. 9),
    x0 = s cb^2 / (a^2 + cb^2) (cb cos psi + a sin psi),
    y0 = s cb^2 / (a^2 + cb^2) (cb sin psi - a cos psi).
    The spiral's pole (s -> 0) is at the origin.

    Args:
        a: the constant of k = a / s, dimensionless, > 0 (a larger ``a`` winds the spiral
            tighter).
        beta_deg: the elevation angle in degrees, in (-90, 90) (see :class:`SlopeCurve`).
        span: the arc lengths (s0, s1), model units, increasing, with s0 > 0.

    Raises:
        ParameterError: a parameter out of range, naming it.
    """

    family = "log_spiral"
    s_lower_bound = 0.0

    def __init__(self, a: float, beta_deg: float, span: tuple[float, float]) -> None:
        self.a = number_in_range("a", a, 0.0)
        super().__init__(beta_deg, span)

    def curvature(self, s: ArrayLike) -> FloatArray:
        return self.a / np.asarray(s, dtype=float)

    def curvature_derivative(self, s: ArrayLike) -> FloatArray:
        return -self.a / np.asarray(s, dtype=float) ** 2

    def turning(self, s: ArrayLike) -> FloatArray:
        return self.a * np.log(np.asarray(s, dtype=float))

    def plan_integrals(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        # Int cos(c ln s) ds = s (cos + c sin) / (1 + c^2), c = a / cos b.
        s = np.asarray(s, dtype=float)
        c = self.a / self._cos_b
        psi = c * np.log(s)
        scale = s / (1.0 + c * c)
        cp, sp = np.cos(psi), np.sin(psi)
        return scale * (cp + c * sp), scale * (sp - c * cp)

    def parameters(self) -> dict[str, Any]:
        return {"a": self.a}


class Helix(SlopeCurve):
    """k = const: a circular helix (beta = 0: a circle, the tube is a torus; k = 0: a line).

    psi = k s / cos b; the helix lies on a cylinder of radius cos^2 b / k with pitch
    2 pi sin b cos b / k.

    Args:
        k: the constant curvature, 1 / model units, signed (k < 0 turns clockwise in plan):
            0 for a straight line, else at least ``MIN_CURVATURE`` (1e-9) in magnitude.
            :meth:`from_radius_pitch` makes the helix from its cylinder radius and pitch.
        beta_deg: the elevation angle in degrees, in (-90, 90) (see :class:`SlopeCurve`).
        span: the arc lengths (s0, s1), model units, increasing.

    Raises:
        ParameterError: a parameter out of range, naming it.
    """

    family = "helix"

    #: the smallest nonzero |k|: the helix is placed about the z axis, so its coordinates are
    #: ~ cos^2 b / |k|, and beyond 1e9 model units double precision cannot place it to 1e-7
    MIN_CURVATURE = 1e-9

    def __init__(self, k: float, beta_deg: float, span: tuple[float, float]) -> None:
        self.k = finite_number("k", k)
        if 0.0 < abs(self.k) < self.MIN_CURVATURE:
            raise ParameterError(
                f"k must be 0 (a straight axis) or at least {self.MIN_CURVATURE:g} in magnitude "
                f"(the helix lies on a cylinder of radius cos^2(beta) / |k| about the z axis), "
                f"got {self.k:g}"
            )
        super().__init__(beta_deg, span)

    @classmethod
    def from_radius_pitch(cls, radius: float, pitch: float, span: tuple[float, float]) -> Helix:
        """The helix on a cylinder of ``radius`` rising ``pitch`` per turn (pitch may be 0)."""
        radius = bounded_length("radius", radius, 0.0)
        pitch = bounded_length("pitch", pitch)
        beta = math.atan2(pitch, 2.0 * math.pi * radius)
        return cls(math.cos(beta) ** 2 / radius, math.degrees(beta), span)

    @property
    def cylinder_radius(self) -> float:
        return math.inf if self.k == 0 else self._cos_b**2 / abs(self.k)

    @property
    def pitch(self) -> float:
        return math.inf if self.k == 0 else 2.0 * math.pi * self._sin_b * self._cos_b / abs(self.k)

    def curvature(self, s: ArrayLike) -> FloatArray:
        return np.full(np.shape(s), self.k)

    def curvature_derivative(self, s: ArrayLike) -> FloatArray:
        return np.zeros(np.shape(s))

    def turning(self, s: ArrayLike) -> FloatArray:
        return self.k * np.asarray(s, dtype=float)

    def plan_integrals(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        s = np.asarray(s, dtype=float)
        if self.k == 0.0:
            return s.copy(), np.zeros_like(s)
        w = self.k / self._cos_b
        return np.sin(w * s) / w, -np.cos(w * s) / w

    def parameters(self) -> dict[str, Any]:
        return {"k": self.k}


class Clothoid(SlopeCurve):
    """k = s / A^2: the Euler spiral (clothoid), curvature growing linearly with length.

    psi = s^2 / (2 A^2 cos b). With lam = A sqrt(pi cos b) and the Fresnel integrals
    C, S (scipy.special.fresnel): Int cos psi ds = lam C(s / lam), Int sin psi ds = lam S(s / lam).
    s may be negative (the other branch, curving the other way).

    Args:
        A: the clothoid parameter, a length in model units, > 0: the radius of curvature
            R = 1 / k at arc length s satisfies R s = A^2.
        beta_deg: the elevation angle in degrees, in (-90, 90) (see :class:`SlopeCurve`).
        span: the arc lengths (s0, s1), model units, increasing; negative s is allowed.

    Raises:
        ParameterError: a parameter out of range, naming it.
    """

    family = "clothoid"

    def __init__(self, A: float, beta_deg: float, span: tuple[float, float]) -> None:
        self.A = bounded_length("A", A, 0.0)
        super().__init__(beta_deg, span)

    def curvature(self, s: ArrayLike) -> FloatArray:
        return np.asarray(s, dtype=float) / self.A**2

    def curvature_derivative(self, s: ArrayLike) -> FloatArray:
        return np.full(np.shape(s), 1.0 / self.A**2)

    def turning(self, s: ArrayLike) -> FloatArray:
        return np.asarray(s, dtype=float) ** 2 / (2.0 * self.A**2)

    def plan_integrals(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        lam = self.A * math.sqrt(math.pi * self._cos_b)
        fs, fc = fresnel(np.asarray(s, dtype=float) / lam)
        return lam * fc, lam * fs

    def parameters(self) -> dict[str, Any]:
        return {"A": self.A}


class CircleInvolute(SlopeCurve):
    """k = 1 / sqrt(2 a s) (s > 0): the involute of a circle of radius a.

    psi = c sqrt(s) with c = sqrt(2 / a) / cos b, and with w = sqrt(s):
    Int cos psi ds = 2 (w sin(c w) / c + cos(c w) / c^2),
    Int sin psi ds = 2 (-w cos(c w) / c + sin(c w) / c^2).

    Args:
        a: the radius of the involute's base circle, model units, > 0.
        beta_deg: the elevation angle in degrees, in (-90, 90) (see :class:`SlopeCurve`).
        span: the arc lengths (s0, s1), model units, increasing, with s0 > 0.

    Raises:
        ParameterError: a parameter out of range, naming it.
    """

    family = "involute"
    s_lower_bound = 0.0

    def __init__(self, a: float, beta_deg: float, span: tuple[float, float]) -> None:
        self.a = bounded_length("a", a, 0.0)
        super().__init__(beta_deg, span)

    def curvature(self, s: ArrayLike) -> FloatArray:
        return 1.0 / np.sqrt(2.0 * self.a * np.asarray(s, dtype=float))

    def curvature_derivative(self, s: ArrayLike) -> FloatArray:
        s = np.asarray(s, dtype=float)
        return -0.5 / (s * np.sqrt(2.0 * self.a * s))

    def turning(self, s: ArrayLike) -> FloatArray:
        return np.sqrt(2.0 * np.asarray(s, dtype=float) / self.a)

    def plan_integrals(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        c = math.sqrt(2.0 / self.a) / self._cos_b
        w = np.sqrt(np.asarray(s, dtype=float))
        cw, sw = np.cos(c * w), np.sin(c * w)
        return 2.0 * (w * sw / c + cw / c**2), 2.0 * (-w * cw / c + sw / c**2)

    def parameters(self) -> dict[str, Any]:
        return {"a": self.a}
