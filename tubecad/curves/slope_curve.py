"""Slope curves: spatial axes of constant elevation angle given by a natural equation.

docs/MATH.md section 1 (paper eq. 2, 5, 8). A slope curve is fixed by its curvature k(s) as a
function of its own arc length s and a constant elevation angle beta (|beta| < 90 deg):

    psi(s) = (1 / cos b) Int k ds
    x0 = cos b Int cos psi ds,   y0 = cos b Int sin psi ds,   z0 = s sin b

    t  = ( cos b cos psi,  cos b sin psi, sin b)
    n  = (-sin psi,        cos psi,       0    )
    bn = (-sin b cos psi, -sin b sin psi, cos b)

with torsion sigma = k tan b (Lancret). A concrete family only supplies k(s), dk/ds and
the antiderivatives Int k ds, Int cos psi ds, Int sin psi ds; everything else is here.
As an :class:`~tubecad.curves.axis.Axis` its rotation-minimising frame is the Frenet frame
turned back by w = Int sigma ds = psi sin b, so its normal development is
k1 = k cos w, k2 = k sin w (docs/MATH.md section 7).
The curvature k is signed: k < 0 turns the horizontal projection clockwise, and the
frame (t, n, bn) above stays continuous through k = 0.
"""

from __future__ import annotations

import math
from abc import abstractmethod
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.validation import number_in_range, span_pair
from tubecad.curves.axis import Axis, FloatArray


@dataclass(frozen=True)
class AxisSample:
    """The axis and its Frenet frame at an array of arc lengths (vectors have shape (..., 3))."""

    s: FloatArray
    position: FloatArray
    t: FloatArray
    n: FloatArray
    bn: FloatArray
    psi: FloatArray
    k: FloatArray
    torsion: FloatArray


class SlopeCurve(Axis):
    """A slope curve of elevation angle ``beta_deg`` over the arc-length ``span``.

    Subclasses implement the natural equation of one family. All evaluation methods take
    arrays of s (any shape) and are vectorised.

    Args:
        beta_deg: the constant elevation angle beta of the tangent above the xy plane, in
            degrees, in the open interval (-90, 90); 0 gives a plane curve, a negative angle
            a descending one.
        span: the arc lengths (s0, s1) the axis covers, in model units, increasing, both
            finite and above the family's ``s_lower_bound`` (s > 0 for the log spiral and the
            involute).

    Raises:
        ParameterError: ``beta_deg`` or ``span`` out of range, naming the parameter.
    """

    #: name used in spec files (``[axis] curve = ...``)
    family: str
    #: the open lower bound of arc lengths where the family is defined
    s_lower_bound: ClassVar[float] = -math.inf

    def __init__(self, beta_deg: float, span: tuple[float, float]) -> None:
        self.beta_deg = number_in_range("beta_deg", beta_deg, -90.0, 90.0)
        self.beta = math.radians(self.beta_deg)
        self.span = span_pair("span", span, self.s_lower_bound)
        self._cos_b = math.cos(self.beta)
        self._sin_b = math.sin(self.beta)

    # --- what a family provides -------------------------------------------------------
    @abstractmethod
    def curvature(self, s: ArrayLike) -> FloatArray:
        """k(s), the curvature of the axis (signed, see module docstring)."""

    @abstractmethod
    def curvature_derivative(self, s: ArrayLike) -> FloatArray:
        """dk/ds."""

    @abstractmethod
    def turning(self, s: ArrayLike) -> FloatArray:
        """Int k ds: an antiderivative of the curvature (so psi = turning / cos b)."""

    @abstractmethod
    def plan_integrals(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(Int cos psi ds, Int sin psi ds): antiderivatives that give x0, y0 (eq. 2)."""

    @abstractmethod
    def parameters(self) -> dict[str, Any]:
        """The family's own parameters, as spec keys and values."""

    # --- derived quantities -----------------------------------------------------------
    def psi(self, s: ArrayLike) -> FloatArray:
        """psi(s) = (1 / cos b) Int k ds: direction angle of the horizontal projection (eq. 8)."""
        return self.turning(s) / self._cos_b

    def torsion(self, s: ArrayLike) -> FloatArray:
        """sigma = k tan b (Lancret's theorem for a slope curve)."""
        return self.curvature(s) * math.tan(self.beta)

    def twist(self, s: ArrayLike) -> FloatArray:
        """Int sigma ds = psi sin b: the angle the Frenet frame turns about t (docs/MATH.md section 2)."""
        return self.psi(s) * self._sin_b

    def position(self, s: ArrayLike) -> FloatArray:
        """c(s) = (cos b Int cos psi, cos b Int sin psi, s sin b), shape (..., 3) (eq. 2)."""
        s = np.asarray(s, dtype=float)
        x, y = self.plan_integrals(s)
        return np.stack([self._cos_b * x, self._cos_b * y, self._sin_b * s], axis=-1)

    def frame(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Frenet frame (t, n, bn) of the slope curve (eq. 5 simplified), each (..., 3)."""
        return self._frame_from_psi(self.psi(s))

    def rotation_minimising_frame(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(t, r1, r2): the Frenet frame turned back by the twist, r1 = cos w n - sin w bn,
        r2 = sin w n + cos w bn with w = Int sigma ds. Its normals do not spin about t."""
        psi = self.psi(s)
        t, n, bn = self._frame_from_psi(psi)
        w = (psi * self._sin_b)[..., None]
        cw, sw = np.cos(w), np.sin(w)
        return t, cw * n - sw * bn, sw * n + cw * bn

    def normal_development(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(k1, k2) = k (cos w, sin w), w = psi sin b: since n = cos w r1 + sin w r2."""
        k, w = self.curvature(s), self.twist(s)
        return k * np.cos(w), k * np.sin(w)

    def normal_development_derivative(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(k1', k2') = k' (cos w, sin w) + k sigma (-sin w, cos w), as w' = sigma."""
        k, dk, w = self.curvature(s), self.curvature_derivative(s), self.twist(s)
        spin = k * k * math.tan(self.beta)
        cw, sw = np.cos(w), np.sin(w)
        return dk * cw - spin * sw, dk * sw + spin * cw

    def frame_rate(self, s: ArrayLike) -> FloatArray:
        """sqrt(k^2 + sigma^2) = |k| / cos b: the Darboux vector's length."""
        return np.abs(self.curvature(s)) / self._cos_b

    def evaluate(self, s: ArrayLike) -> AxisSample:
        """Position, Frenet frame, psi, k and torsion at arc lengths ``s``."""
        s = np.asarray(s, dtype=float)
        psi = self.psi(s)
        t, n, bn = self._frame_from_psi(psi)
        k = self.curvature(s)
        return AxisSample(s, self.position(s), t, n, bn, psi, k, k * math.tan(self.beta))

    def describe(self) -> dict[str, Any]:
        """Spec-style description: ``curve``, the family's parameters, ``beta_deg``, ``s``."""
        return {"curve": self.family, **self.parameters(), "beta_deg": self.beta_deg, "s": list(self.span)}

    def __repr__(self) -> str:
        params = ", ".join(f"{k}={v!r}" for k, v in self.parameters().items())
        return f"{type(self).__name__}({params}, beta_deg={self.beta_deg!r}, span={self.span!r})"

    def _frame_from_psi(self, psi: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        cb, sb = self._cos_b, self._sin_b
        cp, sp = np.cos(psi), np.sin(psi)
        zero, one = np.zeros_like(psi), np.ones_like(psi)
        t = np.stack([cb * cp, cb * sp, sb * one], axis=-1)
        n = np.stack([-sp, cp, zero], axis=-1)
        bn = np.stack([-sb * cp, -sb * sp, cb * one], axis=-1)
        return t, n, bn
