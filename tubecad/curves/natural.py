"""Axes from their natural equations: curvature k(s) and torsion tau(s) (docs/MATH.md section 7).

With w = Int tau ds the rotation-minimising frame is the Frenet frame turned back by w, so
the normal development is k1 = k cos w, k2 = k sin w, and the Bishop equations

    t' = k1 r1 + k2 r2,   r1' = -k1 t,   r2' = -k2 t,   c' = t

are a linear system with known coefficients. It is solved by spectral collocation
(:mod:`.bishop`) from the initial Frenet frame (``tangent``, ``normal``; r1 = n, r2 = b at
s0) and c = origin + Int t ds by the Chebyshev series' antiderivative: ~1e-13 relative.
A slope curve is the case tau = k tan(beta) (Lancret); a circular helix has k, tau constant.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError
from tubecad.core.validation import coordinates, span_pair
from tubecad.curves.axis import Axis, FloatArray, closing
from tubecad.curves.bishop import solve_linear_ode
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.curves.expression import compile_expression

Function = Callable[[np.ndarray], np.ndarray]


def unit_vector(name: str, value: object) -> np.ndarray:
    """Three finite coordinates of a non-zero vector, normalised; ParameterError naming ``name``."""
    v = np.array(coordinates(name, value))
    norm = float(np.linalg.norm(v))
    if norm == 0.0:
        raise ParameterError(f"{name} must not be the zero vector")
    return v / norm


def initial_frame(tangent: object, normal: object) -> np.ndarray:
    """(t, n, b) at the start: ``normal`` made orthogonal to ``tangent`` (Gram-Schmidt)."""
    t = unit_vector("tangent", tangent)
    n = unit_vector("normal", normal)
    n = n - float(n @ t) * t
    if np.linalg.norm(n) < 1e-6:
        raise ParameterError("normal must not be parallel to tangent (they fix the initial frame)")
    n /= np.linalg.norm(n)
    return np.array([t, n, np.cross(t, n)])


def series(func: Function | str, label: str, span: tuple[float, float]) -> tuple[PiecewiseChebyshev, str | None]:
    """A callable or an expression in s, resolved as a Chebyshev series on the span."""
    text = func if isinstance(func, str) else None
    f = compile_expression(func, label) if isinstance(func, str) else func
    if not callable(f):
        raise ParameterError(f"{label} must be a callable {label}(s) or an expression string in s, got {func!r:.80}")

    def values(s: np.ndarray) -> np.ndarray:
        try:
            out = np.asarray(f(s), dtype=float)
        except (TypeError, ValueError) as exc:
            raise ParameterError(f"{label}(s) must return real numbers: {exc}"[:300]) from None
        return out * np.ones_like(s)

    return PiecewiseChebyshev.fit(values, *span, name=f"{label}(s)"), text


class NaturalAxis(Axis):
    """The curve with curvature ``k`` and torsion ``tau`` (callables of s or expressions in
    s) over ``span``, starting at ``origin`` with Frenet frame (``tangent``, ``normal``).
    ``closed``: a closed loop (None: detected when the ends and their tangents agree; True:
    demanded; False: kept open, see :func:`~.axis.closing`).

    Args:
        k: the curvature k(s), 1 / model units: a string expression in ``s`` or a
            vectorised callable of an array of s (k < 0 bends the curve towards -normal).
        tau: the torsion tau(s), 1 / model units, signed: an expression in ``s`` or a
            vectorised callable (0 everywhere: a plane curve).
        span: the arc lengths (s0, s1), model units, increasing.
        origin: the start point c(s0) as [x, y, z], model units (default the origin).
        tangent: the unit tangent's direction at s0 (normalised; default +x).
        normal: the principal normal's direction at s0, made orthogonal to ``tangent``
            (Gram-Schmidt; default +y); it must not be parallel to ``tangent``.
        closed: None (default) to detect a closed loop, True to demand one (refused if the
            ends or their tangents differ), False to keep the axis open.

    Raises:
        ExpressionError: ``k`` or ``tau`` is a string that is not a safe expression in s.
        ParameterError: a parameter out of range, a zero or parallel ``tangent`` and
            ``normal``, or ``closed=True`` on an axis whose ends do not meet tangentially.
    """

    family = "natural"

    def __init__(
        self,
        k: Function | str,
        tau: Function | str,
        span: tuple[float, float],
        *,
        origin: Sequence[float] = (0.0, 0.0, 0.0),
        tangent: Sequence[float] = (1.0, 0.0, 0.0),
        normal: Sequence[float] = (0.0, 1.0, 0.0),
        closed: bool | None = None,
    ) -> None:
        self.span = span_pair("span", span)
        self._k, self.k_text = series(k, "k", self.span)
        self._tau, self.tau_text = series(tau, "tau", self.span)
        self.origin = coordinates("origin", origin)
        frame0 = initial_frame(tangent, normal)
        self.tangent, self.normal = tuple(frame0[0]), tuple(frame0[1])
        self._dk = self._k.derivative()
        self._w = self._tau.antiderivative(0.0)

        def bishop(s: np.ndarray) -> np.ndarray:  # d/ds (t, r1, r2) = A (t, r1, r2)
            k1, k2 = self.normal_development(s)
            A = np.zeros(s.shape + (3, 3))
            A[..., 0, 1], A[..., 0, 2], A[..., 1, 0], A[..., 2, 0] = k1, k2, -k1, -k2
            return A

        breaks = np.union1d(self._k.breaks, self._tau.breaks)
        self._frame = solve_linear_ode(bishop, breaks, frame0, name="the natural equations' frame")
        self._position = PiecewiseChebyshev(self._frame.breaks, self._frame.coeffs[:, :, 0, :]).antiderivative(
            np.array(self.origin)
        )
        self._closed = closing(self, closed)

    def position(self, s: ArrayLike) -> FloatArray:
        return self._position(self._inside(s))

    def rotation_minimising_frame(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        f = self._frame(self._inside(s))
        t = f[..., 0, :] / np.linalg.norm(f[..., 0, :], axis=-1, keepdims=True)
        return t, f[..., 1, :], f[..., 2, :]

    def normal_development(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        s = self._inside(s)
        k, w = self._k(s), self._w(s)
        return k * np.cos(w), k * np.sin(w)

    def normal_development_derivative(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(k1', k2') = k' (cos w, sin w) + k tau (-sin w, cos w)."""
        s = self._inside(s)
        k, dk, w, tau = self._k(s), self._dk(s), self._w(s), self._tau(s)
        cw, sw = np.cos(w), np.sin(w)
        return dk * cw - k * tau * sw, dk * sw + k * tau * cw

    def frame_rate(self, s: ArrayLike) -> FloatArray:
        """sqrt(k^2 + tau^2): the Darboux vector's length."""
        s = self._inside(s)
        return np.hypot(self._k(s), self._tau(s))

    def torsion(self, s: ArrayLike) -> FloatArray:
        return self._tau(self._inside(s))

    def describe(self) -> dict[str, Any]:
        return {
            "curve": self.family,
            "k": self.k_text or repr(self._k),
            "tau": self.tau_text or repr(self._tau),
            "s": list(self.span),
            "origin": list(self.origin),
            "tangent": list(self.tangent),
            "normal": list(self.normal),
            **({"closed": True} if self.closed else {}),
        }

    def __repr__(self) -> str:
        return f"NaturalAxis(k={self.k_text!r}, tau={self.tau_text!r}, span={self.span!r})"
