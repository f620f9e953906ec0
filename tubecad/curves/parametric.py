"""Axes given as parametric curves x(t) (docs/MATH.md section 7): expressions, splines
through points, CAD edges.

x(t) is resolved as a piecewise Chebyshev series (panels start at ``breaks``, e.g. a
spline's knots), so x', x'' are exact derivatives of the series. Then

    s(t) = Int |x'| dt,        T = x' / |x'|,        T_t = (x'' - T (T . x'')) / |x'|
    dr1/dt = -(r1 . T_t) T     (the Bishop equation in t; r2 = T x r1)

the last solved by spectral collocation (:mod:`.bishop`), which passes through inflections
(T_t = 0) and straight stretches with no jump: nothing divides by the curvature. The axis
is then re-read in arc length: t(s) by Newton on s(t), k1 = T_t . r1 / |x'|,
k2 = T_t . r2 / |x'|, and (c, T, r1, k1, k2) resolved once more as one Chebyshev series
in s (t(s) solved once per node for all of them; each part to its own tolerance: c to
1e-15 of its size, the unit frame to its round-off floor, the curvatures to 1e-13 of
theirs), so that evaluating the axis costs one series evaluation, not a Newton solve.
Every fit evaluates a panel's nodes on that panel's series of x (and of r1): at a break
the neighbouring panel's agrees only to its accuracy, a jump the fit would refine without
end. A zero speed |x'| = 0 anywhere (a cusp, a stop) is refused.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError
from tubecad.core.validation import span_pair
from tubecad.curves.axis import Axis, AxisFrame, FloatArray, closing
from tubecad.curves.bishop import solve_linear_ode
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.curves.expression import compile_expression
from tubecad.curves.natural import unit_vector

if TYPE_CHECKING:
    from scipy.interpolate import CubicHermiteSpline

#: the smallest speed |x'| accepted, relative to the largest on the curve
MIN_RELATIVE_SPEED = 1e-6
#: Newton steps for t(s) at most (each one series evaluation; from the inverse table's guess two reach round-off)
NEWTON_STEPS = 8

CurveFunction = Callable[[np.ndarray], np.ndarray]


def expression_curve(x: str, y: str, z: str) -> CurveFunction:
    """x(t), y(t), z(t) from three expressions in t, as one vectorised curve.

    Args:
        x: the expression of x(t) in ``t`` (parsed safely, see :mod:`.expression`), e.g.
            ``"100 * cos(t)"``; model units.
        y: the expression of y(t).
        z: the expression of z(t).

    Returns:
        The callable t -> points of shape t.shape + (3,), to give :class:`ParametricAxis`.

    Raises:
        ExpressionError: an expression that is not a safe arithmetic expression in t,
            naming x, y or z.
    """
    parts = [compile_expression(text, name, variable="t") for text, name in ((x, "x"), (y, "y"), (z, "z"))]

    def curve(t: np.ndarray) -> np.ndarray:
        return np.stack([np.asarray(f(t), dtype=float) * np.ones_like(t) for f in parts], axis=-1)

    return curve


class ParametricAxis(Axis):
    """The curve ``curve(t)`` (a vectorised callable t -> (..., 3)) for t in ``t_span``,
    in arc length s from 0 at t_span[0]. ``breaks``: where the series' panels start (where
    the curve is less smooth); ``joints``: (t, continuity of the frame) at such breaks (see
    :attr:`Axis.joints`). ``normal``: the initial r1 (made orthogonal to the tangent;
    default the principal normal, or any normal where the curve starts straight).
    ``closed``: a closed loop (None: detected when the ends and their tangents agree; True:
    demanded; False: kept open, see :func:`~.axis.closing`).

    Args:
        curve: the vectorised curve x(t): takes an array of t, returns points of shape
            t.shape + (3,) in model units (e.g. :func:`expression_curve`'s); its speed
            |dx/dt| must not vanish on ``t_span``.
        t_span: the parameter interval (t0, t1), increasing; s = 0 at t0.
        breaks: parameters where the curve is less smooth (a spline's knots), where the
            series' panels start; None (default): none.
        joints: (t, continuity) pairs at such breaks: the frame there is only C^continuity
            (0 or 1); those outside (t0, t1) are ignored. Default: none.
        normal: the initial r1 at t0, made orthogonal to the tangent; None (default): the
            principal normal, or the coordinate axis least along the tangent where the curve
            starts straight.
        description: the axis as :meth:`describe` reports it; its ``"curve"`` key becomes
            the axis' ``family``. None (default): ``{"curve": "parametric", "t": t_span}``.
        name: what the curve is called in error messages (default ``"the curve x(t)"``).
        closed: None (default) to detect a closed loop, True to demand one, False to keep
            the axis open.

    Raises:
        ParameterError: ``curve`` not callable or not returning real points of the right
            shape, a degenerate curve (zero speed), a ``normal`` parallel to the tangent, or
            ``closed=True`` on a curve whose ends do not meet tangentially.
    """

    family = "parametric"

    def __init__(
        self,
        curve: CurveFunction,
        t_span: tuple[float, float],
        *,
        breaks: ArrayLike | None = None,
        joints: Sequence[tuple[float, int]] = (),
        normal: Sequence[float] | None = None,
        description: dict[str, Any] | None = None,
        name: str = "the curve x(t)",
        closed: bool | None = None,
    ) -> None:
        self.t_span = span_pair("t", t_span)
        t0, t1 = self.t_span
        if not callable(curve):
            raise ParameterError(f"curve must be a callable x(t) returning points (..., 3), got {curve!r:.80}")
        self._x = PiecewiseChebyshev.fit(
            lambda t: _points(curve, t, name),
            t0,
            t1,
            name=name,
            breaks=None if breaks is None else np.asarray(breaks, dtype=float),
        )
        self._dx = self._x.derivative()
        self._jet = PiecewiseChebyshev.stack([self._x, self._dx, self._dx.derivative()])  # (x, x', x'')
        self._check_speed(name)
        speed = PiecewiseChebyshev.fit(
            lambda t: np.linalg.norm(self._dx.rows(t), axis=-1),
            t0,
            t1,
            name=f"the speed of {name}",
            breaks=self._x.breaks,
        )
        self._s = speed.antiderivative(0.0)
        self._arc = PiecewiseChebyshev.stack([self._s, speed])  # (s, ds/dt)
        self.span = (0.0, float(self._s(np.array(t1))))
        self._guess = self._inverse_table()
        r1_start = self._start_normal(normal)

        def bishop(t: np.ndarray) -> np.ndarray:  # dr1/dt = -(T_t . r1) T = A r1, A = -T T_t^T
            T, T_t, _ = self._tangent_and_rate(t, rows=True)  # t: (panels, nodes), each row one panel
            return -T[..., :, None] * T_t[..., None, :]

        # from the speed's panels (x's, halved where the speed needed it): fewer collocations refused and halved
        self._r1 = solve_linear_ode(bishop, self._s.breaks, r1_start, name=f"the frame of {name}")
        s_breaks = self._s(self._r1.breaks)
        s_breaks[0], s_breaks[-1] = self.span
        self._axis_s = PiecewiseChebyshev.fit(
            self._in_arc_length,
            *self.span,
            breaks=s_breaks,
            parts=((3, 1e-15), (6, self._frame_floor(t0, t1)), (2, 1e-13)),
            name=f"{name} in arc length",
        )
        self._c_s, self._frame_s = self._axis_s.part(0, 3), self._axis_s.part(3, 9)
        self._development_s = self._axis_s.part(9, 11)
        self._development_rate_s = self._development_s.derivative()
        self._joints = tuple((float(self._s(np.array(t))), int(c)) for t, c in joints if t0 < t < t1)
        self._description = description or {"curve": self.family, "t": list(self.t_span)}
        self.family = self._description["curve"]  # points and edge axes are parametric curves too
        self._closed = closing(self, closed)

    # --- in t ---------------------------------------------------------------------------
    def _speed(self, t: np.ndarray) -> np.ndarray:
        return np.linalg.norm(self._dx(t), axis=-1)

    def _tangent_and_rate(self, t: np.ndarray, rows: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """T, dT/dt = (x'' - T (T . x'')) / |x'| and the speed |x'|; ``rows``: t (..., n) holds
        panels' nodes, each row evaluated on one panel (:meth:`PiecewiseChebyshev.rows`)."""
        jet = self._jet.rows(t) if rows else self._jet(t)
        return _tangent_and_rate(jet[..., 1, :], jet[..., 2, :])

    def _frame_floor(self, t0: float, t1: float) -> float:
        """The frame's tolerance in s: 1e-15, or the round-off it carries where that is more.
        s is known to an ulp, ~1.1e-16 L, and T turns at the rate k, so T(s) is known only to
        ~1.1e-16 L k: a long axis of tight bends (k L ~ 1e3) cannot be resolved to 1e-15."""
        _, T_t, speed = self._tangent_and_rate(np.linspace(t0, t1, 4097))
        k = float((np.linalg.norm(T_t, axis=-1) / speed[..., 0]).max())
        return max(1e-15, 4 * np.finfo(float).eps * self.span[1] * k)

    def _in_arc_length(self, s: np.ndarray) -> np.ndarray:
        """The 11 values (c, T, r1, k1, k2) at the nodes s (panels, nodes) of a fit in s, at
        t = t(s): c = x(t), T = x' / |x'|, r1 the Bishop solution made a unit normal, and
        k1 = dT/ds . r1, k2 = dT/ds . r2 with dT/ds = T_t / |x'|, r2 = T x r1."""
        t = self.parameter(s)
        jet = self._jet.rows(t)
        T, T_t, speed = _tangent_and_rate(jet[..., 1, :], jet[..., 2, :])
        r1 = _unit_normal(T, self._r1.rows(t))
        dT_ds = T_t / speed
        k1 = np.sum(dT_ds * r1, axis=-1, keepdims=True)
        k2 = np.sum(dT_ds * np.cross(T, r1), axis=-1, keepdims=True)
        return np.concatenate([jet[..., 0, :], T, r1, k1, k2], axis=-1)

    def _inverse_table(self) -> CubicHermiteSpline:
        """t(s) interpolated from 64 samples per panel of x: the cubic Hermite interpolant
        through (s(t_i), t_i) with slopes dt/ds = 1 / |x'(t_i)|, Newton's first guess."""
        from scipy.interpolate import CubicHermiteSpline  # not loaded with tubecad

        table_t = np.linspace(*self.t_span, 64 * len(self._x.breaks))
        arc = self._arc(table_t)
        return CubicHermiteSpline(arc[:, 0], table_t, 1.0 / arc[:, 1])

    def parameter(self, s: ArrayLike) -> FloatArray:
        """t(s): Newton on s(t) - s = 0 (s(t) is increasing) from the inverse table's guess,
        t <- t - (s(t) - s) / |x'(t)|, until every residual is at round-off, 8 eps L (two
        steps from the guess), or after NEWTON_STEPS."""
        s = self._inside(s)
        t0, t1 = self.t_span
        t = np.clip(self._guess(s), t0, t1)
        floor = 8 * np.finfo(float).eps * self.span[1]
        for _ in range(NEWTON_STEPS):
            arc = self._arc(t)
            residual = arc[..., 0] - s
            if not np.abs(residual).max(initial=0.0) > floor:
                break
            t = np.clip(t - residual / arc[..., 1], t0, t1)
        return t

    def _check_speed(self, name: str) -> None:
        """Refuse a speed |dx/dt| below MIN_RELATIVE_SPEED of its largest: sampled, then the
        smallest sample refined (a cusp between samples is found, not stepped over)."""
        from scipy.optimize import minimize_scalar

        t = np.linspace(*self.t_span, 64 * len(self._x.breaks) + 1)
        speed = self._speed(t)
        i = int(np.argmin(speed))
        lo, hi = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
        best = minimize_scalar(
            lambda x: float(self._speed(np.array(x))),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-12 * (t[-1] - t[0])},
        )
        t_min, v_min = (float(best.x), float(best.fun)) if best.fun < speed[i] else (float(t[i]), float(speed[i]))
        if not v_min > MIN_RELATIVE_SPEED * speed.max():
            raise ParameterError(
                f"{name} is degenerate: its speed |dx/dt| is {v_min:.3g} at t = {t_min:.6g} "
                f"(at most {speed.max():.3g} elsewhere); a tube needs a regular curve, |dx/dt| > 0"
            )

    def _start_normal(self, normal: Sequence[float] | None) -> np.ndarray:
        t0 = np.array([self.t_span[0]])
        T, T_t, _ = (v[0] for v in self._tangent_and_rate(t0))
        if normal is not None:
            n = unit_vector("normal", normal)
        elif np.linalg.norm(T_t) > 1e-9 * self._speed(t0)[0] / max(self.span[1], 1e-300):
            n = T_t / np.linalg.norm(T_t)  # its length k |x'| scales as 1 / size: only its direction counts
        else:  # starts straight: the coordinate axis least along T
            n = np.eye(3)[int(np.argmin(np.abs(T)))]
        n = n - float(n @ T) * T
        if np.linalg.norm(n) < 1e-6:
            raise ParameterError("normal must not be parallel to the curve's tangent at its start")
        return n / np.linalg.norm(n)

    # --- the Axis protocol, in s -------------------------------------------------------
    def position(self, s: ArrayLike) -> FloatArray:
        return self._c_s(self._inside(s))

    def rotation_minimising_frame(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        return _frame(self._frame_s(self._inside(s)))

    def at(self, s: ArrayLike) -> AxisFrame:
        """As :meth:`Axis.at`, from one evaluation of the stacked series (c, T, r1, k1, k2)."""
        s = np.asarray(s, dtype=float)
        values = self._axis_s(self._inside(s))
        T, r1, r2 = _frame(values[..., 3:9])
        return AxisFrame(s, values[..., :3], T, r1, r2, values[..., 9], values[..., 10])

    def normal_development(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        k = self._development_s(self._inside(s))
        return k[..., 0], k[..., 1]

    def normal_development_derivative(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        dk = self._development_rate_s(self._inside(s))
        return dk[..., 0], dk[..., 1]

    @property
    def joints(self) -> tuple[tuple[float, int], ...]:
        return self._joints

    def describe(self) -> dict[str, Any]:
        return {**self._description, "s": list(self.span), **({"closed": True} if self.closed else {})}

    def __repr__(self) -> str:
        return f"ParametricAxis({self._description!r}, length={self.length:.6g})"


def _points(curve: CurveFunction, t: np.ndarray, name: str) -> np.ndarray:
    try:
        out = np.asarray(curve(t), dtype=float)
    except (TypeError, ValueError) as exc:
        raise ParameterError(f"{name} must return real points: {exc}"[:300]) from None
    if out.shape != t.shape + (3,):
        raise ParameterError(
            f"{name} must return points of shape {t.shape + (3,)} for t of shape {t.shape}, got {out.shape}"
        )
    return out


def _tangent_and_rate(d1: np.ndarray, d2: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """From x' and x'': T = x' / |x'|, dT/dt = (x'' - T (T . x'')) / |x'| and |x'| (..., 1)."""
    speed = np.linalg.norm(d1, axis=-1, keepdims=True)
    T = d1 / speed
    return T, (d2 - T * np.sum(T * d2, axis=-1, keepdims=True)) / speed, speed


def _unit_normal(T: np.ndarray, r1: np.ndarray) -> np.ndarray:
    """r1 - T (T . r1), normalised (~1e-15 from r1 already; keeps the frame exact)."""
    r1 = r1 - T * np.sum(T * r1, axis=-1, keepdims=True)
    return r1 / np.linalg.norm(r1, axis=-1, keepdims=True)


def _frame(f: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(T, r1, r2) from the fitted values f = (T, r1) (..., 6): T normalised, r1 made a unit
    normal to it, r2 = T x r1."""
    T = f[..., :3] / np.linalg.norm(f[..., :3], axis=-1, keepdims=True)
    r1 = _unit_normal(T, f[..., 3:])
    return T, r1, np.cross(T, r1)
