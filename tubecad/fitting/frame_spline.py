"""The s direction: one B-spline of the 9-vector F(s) = (c(s), r1(s), r2(s)).

c is the axis, (r1, r2) its rotation-minimising normals (docs/MATH.md section 6). F is
interpolated at the Greville abscissae of a clamped knot vector of degree p whose breaks
include the ring frames (so every face boundary s = s_i is a knot, never a sliver of a
span away from one), and spans are halved until, sampled densely on every span, both
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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np
from scipy.interpolate import BSpline, make_interp_spline

from ..curves.axis import Axis
from ..errors import ParameterError, TubecadError
from .tolerance import check_tolerance

SAMPLES_PER_SPAN = 24
#: angles around the tube at which the fitted surface's orthogonality is measured
ORTHOGONALITY_ANGLES = 16
#: an initial break closer than this fraction of its span to a ring is moved onto the ring
SNAP_FRACTION = 0.25
#: refinements without halving the error after which a failed fit is said to have stalled
STALLED_ROUNDS = 3


class FitError(TubecadError, ValueError):
    """The requested tolerance could not be reached."""


class SplineSize:
    """The size of a fit's ``spline`` (a scipy BSpline), as a build reports it."""

    spline: BSpline

    @property
    def degree(self) -> int:
        return int(self.spline.k)

    @property
    def poles(self) -> int:
        return len(self.spline.c)

    @property
    def spans(self) -> int:
        return len(np.unique(self.spline.t)) - 1


@dataclass(frozen=True)
class FrameSpline(SplineSize):
    """F(s) = (c, r1, r2) as a scipy BSpline, with the bounds it was measured to meet.

    A route's exact frame (:mod:`.route_frame`) is rational: ``spline`` then holds its
    poles and knots, ``weights`` the pole weights, and its parameter v equals the arc
    length s only at the breaks (``arc_length`` maps v -> s, ``parameter`` s -> v)."""

    spline: BSpline
    position_bound: float
    orthogonality_bound: float
    radius_bound: float
    weights: np.ndarray | None = None
    arc_length: Callable[[np.ndarray], np.ndarray] | None = None
    parameter: Callable[[np.ndarray], np.ndarray] | None = None

    @property
    def rational(self) -> bool:
        return self.weights is not None

    def values(self, v: np.ndarray | float) -> np.ndarray:
        """F at parameters ``v`` (weights applied), shape v.shape + (9,)."""
        if self.weights is None:
            return self.spline(v)
        H = BSpline(self.spline.t, self.spline.c * self.weights[:, None], self.spline.k)
        W = BSpline(self.spline.t, self.weights, self.spline.k)
        return H(v) / np.asarray(W(v))[..., None]


def exact_frame(axis: Axis, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """F(s) and F'(s), each (len(s), 9)."""
    a = axis.at(s)
    F = np.hstack([a.position, a.r1, a.r2])
    dF = np.hstack([a.t, -a.k1[:, None] * a.t, -a.k2[:, None] * a.t])
    return F, dF


def fit_frame(
    axis: Axis,
    radius_bound: float,
    tolerance: float = 1e-8,
    orthogonality: float = 1e-9,
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
    from ..curves.route import RouteAxis

    if isinstance(axis, RouteAxis):  # lines and bends: the exact rational frame, nothing to fit
        from .route_frame import route_frame

        return route_frame(axis, radius_bound, rings, radii, tolerance, orthogonality)
    joints = _joint_multiplicities(axis, degree)
    breaks = _with_rings(_initial_breaks(axis, 8), np.concatenate([np.asarray(rings, dtype=float), list(joints)]))
    radii = tuple(float(r) for r in radii) or (float(radius_bound),)
    spline, pos, orth = refine_spline(
        lambda s: exact_frame(axis, s)[0], breaks, degree, joints,
        lambda spline, breaks: _span_errors(axis, spline, breaks, radius_bound, radii, 0.5 * orthogonality),
        tolerance, orthogonality, max_spans, "the frame spline",
    )  # fmt: skip
    return FrameSpline(spline, pos, orth, radius_bound)


def refine_spline(values: Callable[[np.ndarray], np.ndarray], breaks: np.ndarray, degree: int,
                  joints: dict[float, int], span_errors: Callable[[BSpline, np.ndarray], tuple[np.ndarray, np.ndarray]],
                  tolerance: float, orthogonality: float, max_spans: int = 4096, what: str = "the spline",
                  ) -> tuple[BSpline, float, float]:  # fmt: skip
    """Interpolate the vector function ``values`` (s -> (len(s), m)) at the Greville
    abscissae of the clamped knot vector of ``degree`` on ``breaks`` (inner breaks in
    ``joints`` repeated to their multiplicity), and halve every span where
    ``span_errors(spline, breaks)`` (per span: a position error and an orthogonality error)
    exceeds half of ``tolerance`` / ``orthogonality``, until none does: (spline, largest
    position error, largest orthogonality error). A FitError (naming ``what``) when more than
    ``max_spans`` spans would be needed."""
    best = (math.inf, math.inf)
    worst: list[float] = []  # per refinement: the largest error in units of its target
    while True:
        spline = _interpolate(values, breaks, degree, joints)
        pos, orth = span_errors(spline, breaks)
        best = (min(best[0], float(pos.max())), min(best[1], float(orth.max())))
        bad = (pos > 0.5 * tolerance) | (orth > 0.5 * orthogonality)
        if not bad.any():
            return spline, float(pos.max()), float(orth.max())
        worst.append(max(pos.max() / (0.5 * tolerance), orth.max() / (0.5 * orthogonality)))
        if len(breaks) - 1 + bad.sum() > max_spans:
            stalled = len(worst) > STALLED_ROUNDS and min(worst[-STALLED_ROUNDS:]) > 0.5 * worst[-STALLED_ROUNDS - 1]
            why = ("the error stopped decreasing under refinement: double precision limits what is reachable, "
                   "try a looser tolerance") if stalled else (
                   "the error was still decreasing: try a looser tolerance or split the span")  # fmt: skip
            raise FitError(
                f"fit tolerance {tolerance:g} / orthogonality {orthogonality:g} not reached with {max_spans} "
                f"spans of degree {degree} ({what} must meet half of each, {0.5 * tolerance:g} / "
                f"{0.5 * orthogonality:g}); the best reached was {best[0]:.3g} / {best[1]:.3g} ({why})"
            )
        mids = 0.5 * (breaks[:-1] + breaks[1:])[bad]
        breaks = np.sort(np.concatenate([breaks, mids]))


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


def _interpolate(values: Callable[[np.ndarray], np.ndarray], breaks: np.ndarray, p: int,
                 joints: dict[float, int]) -> BSpline:  # fmt: skip
    inner = [b for b in breaks[1:-1] for _ in range(joints.get(float(b), 1))]
    knots = np.concatenate([[breaks[0]] * (p + 1), inner, [breaks[-1]] * (p + 1)])
    n = len(knots) - p - 1
    greville = np.array([knots[i + 1 : i + p + 1].mean() for i in range(n)])
    greville = np.clip(greville, breaks[0], breaks[-1])  # a mean of equal knots can round past them
    return make_interp_spline(greville, values(greville), k=p, t=knots)


def _span_errors(axis: Axis, spline: BSpline, breaks: np.ndarray, radius: float, radii: Sequence[float],
                 target: float) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Per span: the position bound and the orthogonality (the bound, or where it exceeds
    ``target``, the largest |cos| measured on the fitted surface at every radius)."""
    m = len(breaks) - 1
    frac = np.linspace(0.0, 1.0, SAMPLES_PER_SPAN)
    s = (breaks[:-1, None] + np.diff(breaks)[:, None] * frac).ravel()
    F, dF = exact_frame(axis, s)

    def bound(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        d = a - b
        return np.linalg.norm(d[:, :3], axis=1) + radius * np.linalg.norm(d[:, 3:], axis=1)

    fit, dfit = spline(s), spline.derivative()(s)
    pos = bound(fit, F)
    with np.errstate(divide="ignore"):
        orth = bound(dfit, dF) / np.maximum(1.0 - radius * np.abs(axis.curvature(s)), 0.0)
    orth = orth.reshape(m, -1).max(axis=1)
    over = np.flatnonzero(orth > target)
    if over.size:
        rows = np.concatenate([np.arange(i * SAMPLES_PER_SPAN, (i + 1) * SAMPLES_PER_SPAN) for i in over])
        orth[over] = _measured_cos(fit[rows], dfit[rows], radii).reshape(over.size, -1).max(axis=1)
    return pos.reshape(m, -1).max(axis=1), orth


def _measured_cos(fit: np.ndarray, dfit: np.ndarray, radii: Sequence[float]) -> np.ndarray:
    """max over radii and angles of |cos(S_u, S_s)| of S = C + r (cos u R1 + sin u R2), per sample."""
    u = np.linspace(0.0, 2 * math.pi, ORTHOGONALITY_ANGLES, endpoint=False)
    cu, su = np.cos(u)[None, :, None], np.sin(u)[None, :, None]
    R1, R2, dC, dR1, dR2 = fit[:, None, 3:6], fit[:, None, 6:], dfit[:, None, :3], dfit[:, None, 3:6], dfit[:, None, 6:]
    worst = np.zeros(len(fit))
    for r in radii:
        S_u = -su * R1 + cu * R2
        S_s = dC + r * (cu * dR1 + su * dR2)
        cos = np.abs(np.einsum("ijk,ijk->ij", S_u, S_s)) / (np.linalg.norm(S_u, axis=2) * np.linalg.norm(S_s, axis=2))
        worst = np.maximum(worst, cos.max(axis=1))
    return worst
