"""The exact frame of a route (lines and circular bends) as a rational quadratic B-spline.

On a line F(s) = (c, r1, r2) is linear in s; on a bend of radius R every component is an
affine function of (cos phi, sin phi), phi = (s - s_a) / R (:mod:`tubecad.curves.route`):

    c = O + R (X e1 + Y e2),   v(phi) = v_b + (v.e1)(X e1 + Y e2) + (v.e2)(-Y e1 + X e2)

with (X, Y) = (cos phi, sin phi). A rational quadratic B-spline represents (X, Y) exactly,
and an affine map of a rational curve is the same map applied to its poles, weights
unchanged; so F is exact with poles F(X_i, Y_i) and the arc's weights. The s direction is
split at every break (the span ends, the rings, the line-bend joints: double knots, C0) and
each piece between breaks of angle theta into n = ceil(theta / 90 deg) C1 sub-arcs with the
weights of :mod:`.circle` (docs/MATH.md section 6, "The ring circles"):

    J_i = cos^2(theta / 4) / cos^2(i a / 2 - theta / 4),   m_i = cos(a / 2) sqrt(J_i J_{i+1}),   a = theta / n

knot spans proportional to m_i and summing to the piece's arc length, so the NURBS
parameter v equals the arc length s at every break (faces are cut there) and is a smooth
monotone function of it in between (:func:`RouteFrame.arc_length`, closed form as
:meth:`CircleSpline.theta_of_u`). A line is one Bezier piece with weights 1 (v = s).
The tensor product with the rational circle in u then gives the tube exactly: cylinder
and torus pieces (section 6: poles C_j + rho (X_i R1_j + Y_i R2_j), weights w_i v_j).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline

from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, DEFAULT_ORTHOGONALITY
from tubecad.curves.axis import Axis
from tubecad.curves.route import Piece
from tubecad.fitting.frame import FitError, FrameSpline, exact_frame, measured_cos

#: the longest sub-arc in s (90 deg: neighbouring weights stay within a factor 2)
MAX_SUB_ARC = math.pi / 2
SAMPLES_PER_SPAN = 24


@dataclass(frozen=True)
class _Segment:
    """One rational quadratic Bezier of the frame: v in [v0, v0 + dv], weights (w0, m, w1);
    on a bend it runs over the angles [phi0, phi0 + alpha] of ``piece``."""

    v0: float
    dv: float
    piece: Piece
    phi0: float
    alpha: float
    w0: float
    m: float
    w1: float


class RouteFrame:
    """The parameter map of a route's rational frame: v <-> s, per Bezier segment."""

    def __init__(self, segments: list[_Segment]) -> None:
        self.segments = segments
        self._v0 = np.array([g.v0 for g in segments])
        self._s0 = np.array(
            [g.piece.s0 + g.phi0 * (g.piece.radius if g.piece.kind == "bend" else 1.0) for g in segments]
        )

    def arc_length(self, v: np.ndarray | float) -> np.ndarray:
        """s(v): s = v on a line; on a sub-arc, with tau = (v - v0) / dv and r = sqrt(w1 / w0),
        sigma = r tau / (r tau + 1 - tau), phi = phi0 + a/2 + 2 atan(tan(a/4) (2 sigma - 1))."""
        v = np.asarray(v, dtype=float)
        idx = np.clip(np.searchsorted(self._v0, v, side="right") - 1, 0, len(self.segments) - 1)
        out = np.empty_like(v)
        for k in np.unique(idx):
            g, sel = self.segments[k], idx == k
            tau = np.clip((v[sel] - g.v0) / g.dv, 0.0, 1.0)
            if g.piece.kind == "line":
                out[sel] = self._s0[k] + tau * g.dv
                continue
            r = math.sqrt(g.w1 / g.w0)
            sigma = r * tau / (r * tau + (1.0 - tau))
            phi = g.phi0 + g.alpha / 2 + 2 * np.arctan(math.tan(g.alpha / 4) * (2 * sigma - 1))
            out[sel] = g.piece.s0 + g.piece.radius * phi
        return out

    def parameter(self, s: np.ndarray | float) -> np.ndarray:
        """v(s), the inverse of :meth:`arc_length`."""
        s = np.asarray(s, dtype=float)
        idx = np.clip(np.searchsorted(self._s0, s, side="right") - 1, 0, len(self.segments) - 1)
        out = np.empty_like(s)
        for k in np.unique(idx):
            g, sel = self.segments[k], idx == k
            if g.piece.kind == "line":
                out[sel] = g.v0 + np.clip(s[sel] - self._s0[k], 0.0, g.dv)
                continue
            phi = np.clip((s[sel] - g.piece.s0) / g.piece.radius - g.phi0, 0.0, g.alpha)
            sigma = 0.5 * (1.0 + np.tan((phi - g.alpha / 2) / 2) / math.tan(g.alpha / 4))
            r = math.sqrt(g.w1 / g.w0)
            out[sel] = g.v0 + g.dv * sigma / (sigma + r * (1.0 - sigma))
        return out


def route_breaks(axis: Axis, rings: Sequence[float]) -> np.ndarray:
    """The span ends, the rings inside it and the joints, increasing and distinct."""
    s0, s1 = axis.span
    inner = [float(r) for r in rings if s0 < r < s1] + [s for s, _ in axis.joints]
    merged = np.unique(np.concatenate([[s0, s1], inner]))
    keep = np.concatenate([[True], np.diff(merged) > 1e-12 * (s1 - s0)])
    merged = merged[keep]
    merged[-1] = s1
    return merged


def _affine(piece: Piece):
    """The map (X, Y) -> F = (c, r1, r2) of a bend (pole by pole; see the module)."""
    e1, e2 = piece.e1, piece.direction
    assert e1 is not None  # a bend has its e1

    def frame_vector(v: np.ndarray, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        a, b = float(v @ e1), float(v @ e2)
        return (
            (v - a * e1 - b * e2) + a * (X[:, None] * e1 + Y[:, None] * e2) + b * (-Y[:, None] * e1 + X[:, None] * e2)
        )

    def apply(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        c = piece.centre + piece.radius * (X[:, None] * e1 + Y[:, None] * e2)
        return np.hstack([c, frame_vector(piece.r1, X, Y), frame_vector(piece.r2, X, Y)])

    return apply


def route_frame(
    axis: Axis,
    radius_bound: float,
    rings: Sequence[float] = (),
    radii: Sequence[float] = (),
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    orthogonality: float = DEFAULT_ORTHOGONALITY,
) -> FrameSpline:
    """The exact rational quadratic frame of ``axis`` (an axis with :attr:`~Axis.pieces`, a
    route: each piece by :meth:`~Axis.piece_at`) with breaks at ``rings`` and the joints;
    its deviation from the exact frame and the orthogonality of the surfaces of ``radii``
    built on it are measured (round-off) and checked against the targets."""
    breaks = route_breaks(axis, rings)
    knots: list[float] = [breaks[0]] * 3
    poles: list[np.ndarray] = []
    weights: list[float] = []
    segments: list[_Segment] = []
    for a, b in zip(breaks[:-1], breaks[1:]):
        piece = axis.piece_at(0.5 * (a + b))
        first = not poles
        if piece.kind == "line":
            F, _ = exact_frame(axis, np.array([a, 0.5 * (a + b), b]))
            new_poles, new_weights, spans = F, [1.0, 1.0, 1.0], [b - a]
            segments.append(_Segment(a, b - a, piece, (a - piece.s0), b - a, 1.0, 1.0, 1.0))
        else:
            R = piece.radius
            theta = (b - a) / R
            phi_a = (a - piece.s0) / R
            n = max(1, math.ceil(theta / MAX_SUB_ARC - 1e-12))
            alpha = theta / n
            J = math.cos(theta / 4) ** 2 / np.cos(np.arange(n + 1) * alpha / 2 - theta / 4) ** 2
            J[0] = J[-1] = 1.0
            m = math.cos(alpha / 2) * np.sqrt(J[:-1] * J[1:])
            spans = list((b - a) * m / m.sum())
            mids = phi_a + (np.arange(n) + 0.5) * alpha
            X = np.concatenate([[math.cos(phi_a)], np.cos(mids) / math.cos(alpha / 2), [math.cos(phi_a + theta)]])
            Y = np.concatenate([[math.sin(phi_a)], np.sin(mids) / math.cos(alpha / 2), [math.sin(phi_a + theta)]])
            new_poles, new_weights = _affine(piece)(X, Y), [1.0, *m, 1.0]
            v = a
            for i in range(n):
                segments.append(_Segment(v, spans[i], piece, phi_a + i * alpha, alpha, J[i], m[i], J[i + 1]))
                v += spans[i]
        new_poles = np.asarray(new_poles)
        poles.extend(new_poles if first else new_poles[1:])  # the break's pole is shared
        weights.extend(new_weights if first else new_weights[1:])
        knots.extend(list(a + np.cumsum(spans)[:-1]) + [b, b])
    knots.append(breaks[-1])
    t, P, w = np.array(knots), np.array(poles), np.array(weights)
    spline = BSpline(t, P, 2)
    params = RouteFrame(segments)
    radii = tuple(float(r) for r in radii) or (float(radius_bound),)
    pos, orth = _measure(axis, t, P, w, params, radius_bound, radii)
    if pos > 0.5 * tolerance or orth > 0.5 * orthogonality:
        raise FitError(
            f"the exact route frame measured {pos:.3g} / {orth:.3g} from the exact tube (targets "
            f"{0.5 * tolerance:g} / {0.5 * orthogonality:g}): round-off on a route this large"
        )
    return FrameSpline(
        spline, pos, orth, radius_bound, weights=w, arc_length=params.arc_length, parameter=params.parameter
    )


def rational_values(t: np.ndarray, P: np.ndarray, w: np.ndarray, v: np.ndarray, nu: int = 0) -> np.ndarray:
    """F(v) = H(v) / W(v) (nu = 0) or F'(v) = (H' - F W') / W (nu = 1), H = sum N_j w_j P_j."""
    H, W = BSpline(t, P * w[:, None], 2), BSpline(t, w, 2)
    F = H(v) / W(v)[:, None]
    if nu == 0:
        return F
    return (H.derivative()(v) - F * W.derivative()(v)[:, None]) / W(v)[:, None]


def _measure(
    axis: Axis,
    t: np.ndarray,
    P: np.ndarray,
    w: np.ndarray,
    params: RouteFrame,
    radius: float,
    radii: Sequence[float],
) -> tuple[float, float]:
    """The position bound |C - c| + R |(R1, R2) - (r1, r2)| at s(v), and the largest |cos|
    between the isolines of the surfaces of ``radii`` on the frame, sampled on every span of
    the knots ``t`` (the breaks among them)."""
    spans = np.unique(t)
    frac = np.linspace(0.0, 1.0, SAMPLES_PER_SPAN)
    v = spans[:-1, None] + np.diff(spans)[:, None] * frac
    v[:, -1] = np.nextafter(spans[1:], spans[:-1])  # each span's own end (a knot gives the next span's derivative)
    v = v.ravel()
    F, dF = rational_values(t, P, w, v), rational_values(t, P, w, v, 1)
    exact, _ = exact_frame(axis, np.clip(params.arc_length(v), *axis.span))
    d = F - exact
    pos = np.linalg.norm(d[:, :3], axis=1) + radius * np.linalg.norm(d[:, 3:], axis=1)
    return float(pos.max()), float(measured_cos(F, dF, radii).max())
