"""Slope curves from any curvature function k(s), integrated numerically.

The three quadratures of docs/MATH.md section 1 (Int k ds, Int cos psi ds, Int sin psi ds)
are done with adaptive piecewise Chebyshev series (:mod:`.chebyshev`) over the span,
reaching ~1e-14 relative accuracy: the tests compare this path with every closed-form
family. Integration starts at the span's start with psi(s0) = ``psi0_deg`` and
c(s0) = ``origin``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError
from tubecad.core.validation import coordinates, finite_number
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.curves.expression import compile_expression
from tubecad.curves.slope_curve import FloatArray, SlopeCurve


class CustomCurvature(SlopeCurve):
    """A slope curve whose curvature is any smooth ``k``: a vectorised callable or a string
    expression in ``s`` (parsed safely, see :mod:`.expression`).

    Args:
        k: the curvature k(s), 1 / model units, signed: a string expression in ``s`` (e.g.
            ``"0.004 + 0.003 * sin(2 * pi * s / 500)"``) or a vectorised callable taking an
            array of s and returning an array shaped like it (or a scalar).
        beta_deg: the elevation angle in degrees, in (-90, 90) (see :class:`SlopeCurve`).
        span: the arc lengths (s0, s1), model units, increasing; the integration starts at s0.
        psi0_deg: the plan direction angle psi at s0, degrees (default 0: along +x).
        origin: the axis point c(s0) as [x, y, z], model units (default the origin).

    Raises:
        ExpressionError: ``k`` is a string that is not a safe arithmetic expression in s.
        ParameterError: a parameter out of range, ``k`` not callable or not returning real
            numbers, or a plan that turns too often to integrate to round-off.
    """

    family = "custom"

    def __init__(
        self,
        k: Callable[[np.ndarray], np.ndarray] | str,
        beta_deg: float,
        span: tuple[float, float],
        *,
        psi0_deg: float = 0.0,
        origin: Sequence[float] = (0.0, 0.0, 0.0),
    ) -> None:
        super().__init__(beta_deg, span)
        self.expression = k if isinstance(k, str) else None
        func = compile_expression(k, "k") if isinstance(k, str) else k
        if not callable(func):
            raise ParameterError(f"k must be a callable k(s) or an expression string, got {k!r}")
        self._k = func
        self.psi0_deg = finite_number("psi0_deg", psi0_deg)
        self.origin = coordinates("origin", origin)

        s0, s1 = self.span
        k_series = PiecewiseChebyshev.fit(self._k_values, s0, s1, name="k(s)")
        self._dk = k_series.derivative()
        psi0 = math.radians(self.psi0_deg)
        self._turning = k_series.antiderivative(psi0 * self._cos_b)
        x0, y0 = self.origin[0] / self._cos_b, self.origin[1] / self._cos_b
        psi = self.psi(np.linspace(s0, s1, 20001))
        # cos and sin of psi are only known to ~eps |psi|: asking for more would halve panels
        # on round-off noise without end once the plan has turned a few dozen times
        tol = max(1e-15, 8.0 * np.finfo(float).eps * float(np.abs(psi).max()))
        try:
            self._x = PiecewiseChebyshev.fit(
                lambda s: np.cos(self.psi(s)), s0, s1, name="cos psi", tol=tol
            ).antiderivative(x0)
            self._y = PiecewiseChebyshev.fit(
                lambda s: np.sin(self.psi(s)), s0, s1, name="sin psi", tol=tol
            ).antiderivative(y0)
        except ParameterError:  # k itself was resolved: the plan turns too often
            turns = float(np.abs(np.diff(psi)).sum()) / (2.0 * math.pi)
            raise ParameterError(
                f"the plan of the axis turns {turns:.4g} times over the span (psi = Int k ds / cos(beta_deg)): "
                "too often to integrate to round-off; lower |beta_deg|, the curvature k or the span"
            ) from None
        self._z_offset = self.origin[2] - s0 * self._sin_b

    def _k_values(self, s: np.ndarray) -> np.ndarray:
        if self.expression is not None:
            return np.asarray(self._k(s), dtype=float) * np.ones_like(s)
        try:  # a user's callable: whatever goes wrong in it is a ParameterError naming k
            value = np.asarray(self._k(s))
        except Exception as exc:
            raise ParameterError(f"k(s) raised {type(exc).__name__}: {exc}"[:300]) from exc
        if value.dtype.kind not in "iuf":
            raise ParameterError(
                f"k(s) must return real numbers (an array shaped like s, or a scalar), "
                f"got {value.dtype} values {value.ravel()[:3]!r:.80}"
            )
        try:
            return value.astype(float) * np.ones_like(s)
        except ValueError:
            raise ParameterError(
                f"k(s) must return an array shaped like s {np.shape(s)} or a scalar, got shape {value.shape}"
            ) from None

    def inside(self, s: ArrayLike) -> FloatArray:
        s = np.asarray(s, dtype=float)
        s0, s1 = self.span
        slack = 1e-9 * (s1 - s0)
        if s.size and (s.min() < s0 - slack or s.max() > s1 + slack):
            raise ParameterError(
                f"s must lie in the span [{s0:g}, {s1:g}] of a custom curve, got [{s.min():g}, {s.max():g}]"
            )
        return s

    def curvature(self, s: ArrayLike) -> FloatArray:
        s = self._inside(s)
        with np.errstate(all="ignore"):
            return self._k_values(s)

    def curvature_derivative(self, s: ArrayLike) -> FloatArray:
        return self._dk(self._inside(s))

    def turning(self, s: ArrayLike) -> FloatArray:
        return self._turning(self._inside(s))

    def plan_integrals(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        s = self._inside(s)
        return self._x(s), self._y(s)

    def position(self, s: ArrayLike) -> FloatArray:
        p = super().position(s)
        p[..., 2] += self._z_offset
        return p

    def parameters(self) -> dict[str, Any]:
        return {"k": self.expression if self.expression is not None else repr(self._k)}
