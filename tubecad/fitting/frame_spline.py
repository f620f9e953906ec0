"""The s direction: one B-spline of the 9-vector F(s) = (c(s), r1(s), r2(s)).

c is the axis, (r1, r2) its rotation-minimising normals (docs/MATH.md section 6). F is
interpolated at the Greville abscissae of a clamped knot vector of degree p whose breaks
include the ring frames (so every face boundary s = s_i is a knot, never a sliver of a
span away from one), each of multiplicity p (so one abscissa is the ring itself and the
fitted section there is the exact one to round-off: its isoline is the ring's exact circle
at any tolerance, which a STEP file's 1e-7 edges need; F is then only C0 at the rings,
where the faces end anyway, and each face's Segment()-ed surface has the poles it had), and spans are halved until, sampled densely on every span, both
    |c_fit - c| + R sqrt(|r1_fit - r1|^2 + |r2_fit - r2|^2) <= tolerance / 2      (position)
    |cos(S_u, S_s)| of the fitted surface, at every radius built, <= orthogonality / 2
hold, R the largest radius that will be built on the fit. The first bounds the distance of
every surface point to the exact tube. The second is measured on the surface
S = C + r (cos u R1 + sin u R2) of the fitted frame at ORTHOGONALITY_ANGLES angles; where
the cheaper bound
    (|c'_fit - c'| + R sqrt(|r1'_fit - r1'|^2 + |r2'_fit - r2'|^2)) / (1 - R |k|)
(docs/MATH.md section 3: |S_s| >= 1 - rho |k|) already meets the target the measurement is
skipped. The exact derivatives are c' = t, r1' = -k1 t, r2' = -k2 t (the Bishop
equations, docs/MATH.md section 7; for a slope curve k1 = k cos w, k2 = k sin w).
Halving leaves many spans far inside the targets (an error falls 2^(p+1) = 256 times a
halving); once every span meets them, the breaks are redistributed by each span's measured
error (de Boor's knot placement) and the fit on fewer spans is kept if it meets them too.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from scipy.interpolate import BSpline, make_interp_spline

from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, DEFAULT_ORTHOGONALITY, check_tolerance
from tubecad.curves.axis import Axis
from tubecad.fitting.frame import (
    ORTHOGONALITY_ANGLES,
    FitError,
    FrameSpline,
    SplineSize,
    exact_frame,
    frame_values,
    measured_cos,
)
from tubecad.fitting.route_frame import route_frame

__all__ = ["FitError", "FrameSpline", "SplineSize", "exact_frame", "fit_frame", "refine_spline", "ORTHOGONALITY_ANGLES"]

SAMPLES_PER_SPAN = 24
#: an initial break closer than this fraction of its span to a ring is moved onto the ring
SNAP_FRACTION = 0.25
#: refinements without halving the error after which a failed fit is said to have stalled
STALLED_ROUNDS = 3


def fit_frame(
    axis: Axis,
    radius_bound: float,
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    orthogonality: float = DEFAULT_ORTHOGONALITY,
    degree: int = 7,
    max_spans: int = 4096,
    rings: Sequence[float] = (),
    radii: Sequence[float] = (),
) -> FrameSpline:
    """Fit F adaptively until the measured bounds meet ``tolerance`` and ``orthogonality``.

    ``rings`` (arc lengths inside the span) become knots; ``radii`` are the tube radii that
    will be built on the fit (default: ``radius_bound``), each measured for orthogonality.
    """
    if isinstance(degree, bool) or not (isinstance(degree, int) and 3 <= degree <= 9):
        raise ParameterError(f"degree must be a whole number in [3, 9], got {degree!r}")
    tolerance = check_tolerance("tolerance", tolerance)
    orthogonality = check_tolerance("orthogonality", orthogonality)
    if axis.pieces is not None:  # lines and bends: the exact rational frame, nothing to fit
        return route_frame(axis, radius_bound, rings, radii, tolerance, orthogonality)
    joints = _joint_multiplicities(axis, degree)
    breaks = _with_rings(_initial_breaks(axis, 8), np.concatenate([np.asarray(rings, dtype=float), list(joints)]))
    radii = tuple(float(r) for r in radii) or (float(radius_bound),)
    samples = SpanSamples(lambda s: _frame_and_curvature(axis, s))
    spline, pos, orth = refine_spline(
        lambda s: exact_frame(axis, s)[0],
        breaks,
        degree,
        joints,
        lambda spline, breaks: _span_errors(
            samples, spline, breaks, radius_bound, radii, 0.5 * orthogonality, 0.5 * tolerance
        ),
        tolerance,
        orthogonality,
        max_spans,
        "the frame spline",
        rings=rings,
    )
    return FrameSpline(spline, pos, orth, radius_bound)


def refine_spline(
    values: Callable[[np.ndarray], np.ndarray],
    breaks: np.ndarray,
    degree: int,
    joints: dict[float, int],
    span_errors: Callable[[BSpline, np.ndarray], tuple[np.ndarray, np.ndarray]],
    tolerance: float,
    orthogonality: float,
    max_spans: int = 4096,
    what: str = "the spline",
    rings: Sequence[float] = (),
) -> tuple[BSpline, float, float]:
    """Interpolate the vector function ``values`` (s -> (len(s), m)) at the Greville
    abscissae of the clamped knot vector of ``degree`` on ``breaks`` (inner breaks in
    ``joints`` repeated to their multiplicity), and halve every span where
    ``span_errors(spline, breaks)`` (per span: a position error and an orthogonality error)
    exceeds half of ``tolerance`` / ``orthogonality``, until none does, then try the breaks
    redistributed to fewer spans (:func:`redistributed_breaks`), kept if that fit meets the targets too. Each of ``rings``
    (breaks) is a knot of multiplicity ``degree``: one abscissa is the ring itself, so the
    spline is exact there: (spline, largest
    position error, largest orthogonality error). A FitError (naming ``what``) when more than
    ``max_spans`` spans would be needed."""
    best = (math.inf, math.inf)
    worst: list[float] = []  # per refinement: the largest error in units of its target
    while True:
        spline = _interpolate(values, breaks, degree, joints, rings)
        pos, orth = span_errors(spline, breaks)
        best = (min(best[0], float(pos.max())), min(best[1], float(orth.max())))
        bad = (pos > 0.5 * tolerance) | (orth > 0.5 * orthogonality)
        if not bad.any():
            fixed = {float(x) for x in rings} | set(joints)
            fewer = redistributed_breaks(breaks, pos, orth, degree, tolerance, orthogonality, fixed)
            if len(fewer) <= REDISTRIBUTE_GAIN * len(breaks):  # worth a round on new samples
                trial = _interpolate(values, fewer, degree, joints, rings)
                pos_r, orth_r = span_errors(trial, fewer)
                if not ((pos_r > 0.5 * tolerance) | (orth_r > 0.5 * orthogonality)).any():
                    return trial, float(pos_r.max()), float(orth_r.max())
            return spline, float(pos.max()), float(orth.max())
        worst.append(max(pos.max() / (0.5 * tolerance), orth.max() / (0.5 * orthogonality)))
        if len(breaks) - 1 + bad.sum() > max_spans:
            stalled = len(worst) > STALLED_ROUNDS and min(worst[-STALLED_ROUNDS:]) > 0.5 * worst[-STALLED_ROUNDS - 1]
            why = (
                (
                    "the error stopped decreasing under refinement: double precision limits what is reachable, "
                    "try a looser tolerance"
                )
                if stalled
                else ("the error was still decreasing: try a looser tolerance or split the span")
            )
            raise FitError(
                f"fit tolerance {tolerance:g} / orthogonality {orthogonality:g} not reached with {max_spans} "
                f"spans of degree {degree} ({what} must meet half of each, {0.5 * tolerance:g} / "
                f"{0.5 * orthogonality:g}); the best reached was {best[0]:.3g} / {best[1]:.3g} ({why})"
            )
        mids = 0.5 * (breaks[:-1] + breaks[1:])[bad]
        breaks = np.sort(np.concatenate([breaks, mids]))


#: the error each span of a redistributed fit is aimed at, as a fraction of the target: the
#: measured rate is an estimate (tried at 0.8 and 1.0: several redistributions then missed)
REDISTRIBUTE_AIM = 0.5
#: the redistributed fit is tried only if it has at most this fraction of the breaks (it costs
#: a round on new samples). Measured misses, where it is tried and the halved fit kept: the
#: canal samples at 1e-8 (the nozzle 16 -> 11 spans, the tapered helix 64 -> 55), a round lost
REDISTRIBUTE_GAIN = 0.95


def redistributed_breaks(
    breaks: np.ndarray,
    pos: np.ndarray,
    orth: np.ndarray,
    degree: int,
    tolerance: float,
    orthogonality: float,
    fixed: set[float],
) -> np.ndarray:
    """Breaks on which every span is expected to meet REDISTRIBUTE_AIM of half the targets,
    from the errors ``pos``, ``orth`` measured on the spans of ``breaks``. De Boor's knot
    placement (A Practical Guide to Splines, 1978, ch. XII: the breaks equidistribute
    |f^(p+1)|^(1/(p+1))), that derivative taken from each span's measured error
    e ~ h^(p+1) |f^(p+1)| (an orthogonality error ~ h^p): a span whose error is r times the
    aim holds r^(1/(p+1)) spans of the new breaks. The ``fixed`` breaks (rings, joints) stay
    (each stretch between two of them is redistributed on its own), and a stretch is left as
    it is unless it loses a span."""
    p = degree
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.maximum(pos / (0.5 * tolerance), (orth / (0.5 * orthogonality)) ** ((p + 1) / p))
    density = (np.maximum(ratio, 1e-300) / REDISTRIBUTE_AIM) ** (1.0 / (p + 1))  # spans per span
    if not np.isfinite(density).all():
        return breaks
    new: list[float] = [float(breaks[0])]
    start = 0
    for i in range(1, len(breaks)):
        if float(breaks[i]) not in fixed and i < len(breaks) - 1:
            continue
        spans = max(1, math.ceil(float(density[start:i].sum())))
        if spans < i - start:
            cumulative = np.concatenate([[0.0], np.cumsum(density[start:i])])
            marks = np.linspace(0.0, cumulative[-1], spans + 1)[1:-1]
            new += np.interp(marks, cumulative, breaks[start : i + 1]).tolist()
        else:
            new += breaks[start + 1 : i].tolist()
        new.append(float(breaks[i]))
        start = i
    return np.array(new)


def _initial_breaks(axis: Axis, spans: int) -> np.ndarray:
    """Equidistribute Int (frame rate + 1 / L) ds: the frame's total turning, plus length
    (for a slope curve the rate is |k| / cos b = sqrt(k^2 + sigma^2))."""
    s = np.linspace(*axis.span, 2001)
    density = axis.frame_rate(s) + 1.0 / axis.length
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(s))])
    breaks = np.interp(np.linspace(0, cumulative[-1], spans + 1), cumulative, s)
    breaks[0], breaks[-1] = axis.span
    return breaks


def _with_rings(breaks: np.ndarray, rings: np.ndarray) -> np.ndarray:
    """``breaks`` with the rings added; a break within SNAP_FRACTION of its span of a ring
    is dropped (the ring takes its place), so no sliver spans appear."""
    s0, s1 = breaks[0], breaks[-1]
    rings = rings[(rings > s0) & (rings < s1)]
    if rings.size == 0:
        return breaks
    spacing = np.min(np.diff(breaks))
    inner = breaks[1:-1]
    near = np.min(np.abs(inner[:, None] - rings[None, :]), axis=1) < SNAP_FRACTION * spacing if inner.size else []
    merged = np.unique(np.concatenate([[s0], inner[~np.asarray(near, dtype=bool)], rings, [s1]]))
    keep = np.concatenate([[True], np.diff(merged) > 1e-12 * (s1 - s0)])
    return merged[keep]


def _joint_multiplicities(axis: Axis, degree: int) -> dict[float, int]:
    """Inner joint s -> knot multiplicity degree - continuity: there the frame F = (c, r1, r2)
    is only C^continuity (a spline axis' knot, a route's line-bend joint), and the fit must
    be allowed the same, or it would refine towards the joint without end."""
    s0, s1 = axis.span
    return {float(s): degree - int(c) for s, c in axis.joints if s0 < s < s1 and 0 <= c < degree}


def _interpolate(
    values: Callable[[np.ndarray], np.ndarray],
    breaks: np.ndarray,
    p: int,
    joints: dict[float, int],
    rings: Sequence[float] = (),
) -> BSpline:
    exact = {float(x) for x in rings}
    inner = [b for b in breaks[1:-1] for _ in range(p if float(b) in exact else joints.get(float(b), 1))]
    knots = np.concatenate([[breaks[0]] * (p + 1), inner, [breaks[-1]] * (p + 1)])
    n = len(knots) - p - 1
    greville = np.lib.stride_tricks.sliding_window_view(knots[1:], p)[:n].mean(axis=1)  # of knots i + 1 .. i + p
    greville = np.clip(greville, breaks[0], breaks[-1])  # a mean of equal knots can round past them
    for x in exact:  # p equal knots: their mean is the ring, up to the rounding of the mean
        greville[np.argmin(np.abs(greville - x))] = x
    return make_interp_spline(greville, values(greville), k=p, t=knots)


class SpanSamples:
    """``exact`` (s -> a tuple of arrays, one row per s) at SAMPLES_PER_SPAN points
    s = a + (b - a) j / (SAMPLES_PER_SPAN - 1) of every span [a, b] (the last one b less one
    ulp: the span's own end, its derivatives' left limits) of a refinement, each span
    evaluated once: a span kept from one round to the next keeps its samples, and a round
    evaluates ``exact`` (in one call) only on the spans it halved."""

    def __init__(self, exact: Callable[[np.ndarray], tuple[np.ndarray, ...]]) -> None:
        self.exact = exact
        self._spans: dict[tuple[float, float], tuple[np.ndarray, ...]] = {}

    def __call__(self, breaks: np.ndarray) -> tuple[np.ndarray, ...]:
        """(s, *exact(s)) on all spans of ``breaks``, span after span (rows spans * samples)."""
        spans = list(zip(breaks[:-1].tolist(), breaks[1:].tolist()))
        new = [span for span in dict.fromkeys(spans) if span not in self._spans]
        if new:
            lo, hi = np.array(new).T
            s = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, SAMPLES_PER_SPAN)
            # each span's last sample a step inside it: a spline (and the exact frame at a
            # joint) evaluated at a break gives the next span's derivative, and at a ring (a
            # knot of multiplicity p) the two differ: the span's own end was never measured
            s[:, -1] = np.nextafter(hi, lo)
            s = s.ravel()
            values = (s, *self.exact(s))
            for i, span in enumerate(new):
                rows = slice(i * SAMPLES_PER_SPAN, (i + 1) * SAMPLES_PER_SPAN)
                self._spans[span] = tuple(v[rows] for v in values)
        return tuple(np.concatenate(column) for column in zip(*(self._spans[span] for span in spans)))


def _frame_and_curvature(axis: Axis, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """F, F' (:func:`exact_frame`) and |k| = sqrt(k1^2 + k2^2), from one evaluation of the axis."""
    a = axis.at(s)
    return (*frame_values(a), np.hypot(a.k1, a.k2))


def _span_errors(
    samples: SpanSamples,
    spline: BSpline,
    breaks: np.ndarray,
    radius: float,
    radii: Sequence[float],
    target: float,
    position_target: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Per span: the position bound and the orthogonality (the bound, or where it exceeds
    ``target``, the largest |cos| measured on the fitted surface at every radius). A span whose
    position bound already exceeds ``position_target`` is halved whatever its orthogonality:
    it keeps the orthogonality bound, unmeasured (an upper bound)."""
    m = len(breaks) - 1
    s, F, dF, k = samples(breaks)

    def bound(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        d = a - b
        return np.linalg.norm(d[:, :3], axis=1) + radius * np.linalg.norm(d[:, 3:], axis=1)

    fit, dfit = spline(s), spline.derivative()(s)
    pos = bound(fit, F)
    with np.errstate(divide="ignore"):
        orth = bound(dfit, dF) / np.maximum(1.0 - radius * k, 0.0)
    orth = orth.reshape(m, -1).max(axis=1)
    pos = pos.reshape(m, -1).max(axis=1)
    over = np.flatnonzero((orth > target) & (pos <= position_target))
    if over.size:
        rows = (over[:, None] * SAMPLES_PER_SPAN + np.arange(SAMPLES_PER_SPAN)).ravel()
        orth[over] = measured_cos(fit[rows], dfit[rows], radii).reshape(over.size, -1).max(axis=1)
    return pos, orth
