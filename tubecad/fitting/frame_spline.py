"""The s direction: one B-spline of the 9-vector F(s) = (c(s), r1(s), r2(s)).

c is the axis, (r1, r2) its rotation-minimising normals (MATH.md section 6). F is
interpolated at the Greville abscissae of a clamped knot vector of degree p, and spans
are halved until, sampled densely on every span, both
    |c_fit - c| + R sqrt(|r1_fit - r1|^2 + |r2_fit - r2|^2) <= tolerance / 2      (position)
    (|c'_fit - c'| + R sqrt(|r1'_fit - r1'|^2 + |r2'_fit - r2'|^2)) / (1 - R |k|) <= orthogonality / 2
hold, R the largest radius that will be built on the fit. The first bounds the distance of
every surface point to the exact tube, the second the |cos| of the angle between the
isolines (MATH.md section 3: |S_s| >= 1 - rho |k|). The exact derivatives are
c' = t, r1' = -k cos(w) t, r2' = -k sin(w) t, w = Int sigma ds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline, make_interp_spline

from ..curves.slope_curve import SlopeCurve
from ..errors import ParameterError, TubecadError

SAMPLES_PER_SPAN = 24
#: refinements without halving the error after which a failed fit is said to have stalled
STALLED_ROUNDS = 3


class FitError(TubecadError, ValueError):
    """The requested tolerance could not be reached."""


@dataclass(frozen=True)
class FrameSpline:
    """F(s) = (c, r1, r2) as a scipy BSpline, with the bounds it was measured to meet."""

    spline: BSpline
    position_bound: float
    orthogonality_bound: float
    radius_bound: float

    @property
    def degree(self) -> int:
        return int(self.spline.k)

    @property
    def poles(self) -> int:
        return len(self.spline.c)

    @property
    def spans(self) -> int:
        return len(np.unique(self.spline.t)) - 1


def exact_frame(axis: SlopeCurve, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """F(s) and F'(s), each (len(s), 9)."""
    t, r1, r2 = axis.rotation_minimising_frame(s)
    w = axis.twist(s)
    k = axis.curvature(s)
    F = np.hstack([axis.position(s), r1, r2])
    dF = np.hstack([t, -(k * np.cos(w))[:, None] * t, -(k * np.sin(w))[:, None] * t])
    return F, dF


def fit_frame(
    axis: SlopeCurve,
    radius_bound: float,
    tolerance: float = 1e-8,
    orthogonality: float = 1e-9,
    degree: int = 7,
    max_spans: int = 4096,
) -> FrameSpline:
    """Fit F adaptively until the measured bounds meet ``tolerance`` and ``orthogonality``."""
    if isinstance(degree, bool) or not (isinstance(degree, int) and 3 <= degree <= 9):
        raise ParameterError(f"degree must be a whole number in [3, 9], got {degree!r}")
    tolerance = check_tolerance("tolerance", tolerance)
    orthogonality = check_tolerance("orthogonality", orthogonality)
    breaks = _initial_breaks(axis, 8)
    best = (math.inf, math.inf)
    worst: list[float] = []  # per refinement: the largest error in units of its target
    while True:
        spline = _interpolate(axis, breaks, degree)
        pos, orth = _span_errors(axis, spline, breaks, radius_bound)
        best = (min(best[0], float(pos.max())), min(best[1], float(orth.max())))
        bad = (pos > 0.5 * tolerance) | (orth > 0.5 * orthogonality)
        if not bad.any():
            return FrameSpline(spline, float(pos.max()), float(orth.max()), radius_bound)
        worst.append(max(pos.max() / (0.5 * tolerance), orth.max() / (0.5 * orthogonality)))
        if len(breaks) - 1 + bad.sum() > max_spans:
            stalled = len(worst) > STALLED_ROUNDS and min(worst[-STALLED_ROUNDS:]) > 0.5 * worst[-STALLED_ROUNDS - 1]
            why = ("the error stopped decreasing under refinement: double precision limits what is reachable, "
                   "try a looser tolerance") if stalled else (
                   "the error was still decreasing: try a looser tolerance or split the span")  # fmt: skip
            raise FitError(
                f"fit tolerance {tolerance:g} / orthogonality {orthogonality:g} not reached with {max_spans} "
                f"spans of degree {degree} (the frame spline must meet half of each, {0.5 * tolerance:g} / "
                f"{0.5 * orthogonality:g}); the best reached was {best[0]:.3g} / {best[1]:.3g} ({why})"
            )
        mids = 0.5 * (breaks[:-1] + breaks[1:])[bad]
        breaks = np.sort(np.concatenate([breaks, mids]))


def check_tolerance(name: str, value: object) -> float:
    """A fit tolerance in (0, 1) model units, or a ParameterError naming ``name``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)) or not (
        math.isfinite(value) and 0 < value < 1
    ):
        raise ParameterError(f"fit {name} must be in (0, 1) model units, got {value!r:.80}")
    return float(value)


def _initial_breaks(axis: SlopeCurve, spans: int) -> np.ndarray:
    """Equidistribute Int (|k| / cos b + 1 / L) ds: the total curvature, plus length."""
    s = np.linspace(*axis.span, 2001)
    density = np.abs(axis.curvature(s)) / math.cos(axis.beta) + 1.0 / axis.length
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(s))])
    breaks = np.interp(np.linspace(0, cumulative[-1], spans + 1), cumulative, s)
    breaks[0], breaks[-1] = axis.span
    return breaks


def _interpolate(axis: SlopeCurve, breaks: np.ndarray, p: int) -> BSpline:
    knots = np.concatenate([[breaks[0]] * p, breaks, [breaks[-1]] * p])
    n = len(knots) - p - 1
    greville = np.array([knots[i + 1 : i + p + 1].mean() for i in range(n)])
    greville = np.clip(greville, breaks[0], breaks[-1])  # a mean of equal knots can round past them
    F, _ = exact_frame(axis, greville)
    return make_interp_spline(greville, F, k=p, t=knots)


def _span_errors(axis: SlopeCurve, spline: BSpline, breaks: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
    m = len(breaks) - 1
    frac = np.linspace(0.0, 1.0, SAMPLES_PER_SPAN)
    s = (breaks[:-1, None] + np.diff(breaks)[:, None] * frac).ravel()
    F, dF = exact_frame(axis, s)

    def bound(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        d = a - b
        return np.linalg.norm(d[:, :3], axis=1) + radius * np.linalg.norm(d[:, 3:], axis=1)

    pos = bound(spline(s), F)
    orth = bound(spline.derivative()(s), dF) / (1.0 - radius * np.abs(axis.curvature(s)))
    return pos.reshape(m, -1).max(axis=1), orth.reshape(m, -1).max(axis=1)
