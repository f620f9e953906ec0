"""The fitted frame F(s) = (c(s), r1(s), r2(s)) as a B-spline (docs/MATH.md section 6): its
container, the exact frame it is measured against, and the orthogonality measure

    max over radii r and angles u of |cos(S_u, S_s)|,  S = C + r (cos u R1 + sin u R2),

shared by the smooth fit (:mod:`.frame_spline`) and a route's exact rational frame
(:mod:`.route_frame`)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline

from tubecad.core.errors import TubecadError
from tubecad.curves.axis import Axis, AxisFrame

#: angles around the tube at which the fitted surface's orthogonality is measured
ORTHOGONALITY_ANGLES = 16


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

    A route's exact frame (:mod:`tubecad.fitting.route_frame`) is rational: ``spline`` then holds its
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
    return frame_values(axis.at(s))


def frame_values(a: AxisFrame) -> tuple[np.ndarray, np.ndarray]:
    """F = (c, r1, r2) and F' = (t, -k1 t, -k2 t) (the Bishop equations) of an evaluated axis."""
    F = np.hstack([a.position, a.r1, a.r2])
    dF = np.hstack([a.t, -a.k1[:, None] * a.t, -a.k2[:, None] * a.t])
    return F, dF


def measured_cos(fit: np.ndarray, dfit: np.ndarray, radii: Sequence[float]) -> np.ndarray:
    """max over radii and angles of |cos(S_u, S_s)| of S = C + r (cos u R1 + sin u R2), per sample.

    With S_u = -sin u R1 + cos u R2 and S_s = C' + r (cos u R1' + sin u R2'), the dot products
    S_u . S_s, |S_u|^2 and |S_s|^2 are trigonometric polynomials in u whose coefficients are the
    15 dot products of R1, R2, C', R1', R2' (taken once per sample, not per angle)."""
    u = np.linspace(0.0, 2 * math.pi, ORTHOGONALITY_ANGLES, endpoint=False)
    c, s = np.cos(u)[None, :], np.sin(u)[None, :]
    cc, ss, cs = c * c, s * s, c * s
    R1, R2, dC, dR1, dR2 = fit[:, 3:6], fit[:, 6:], dfit[:, :3], dfit[:, 3:6], dfit[:, 6:]

    def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.einsum("ij,ij->i", a, b)[:, None]

    r1_c, r2_c = dot(R1, dC), dot(R2, dC)
    r1_r1p, r1_r2p, r2_r1p, r2_r2p = dot(R1, dR1), dot(R1, dR2), dot(R2, dR1), dot(R2, dR2)
    su_norm2 = ss * dot(R1, R1) + cc * dot(R2, R2) - 2.0 * cs * dot(R1, R2)  # |S_u|^2, the same at every radius
    c_c, c_r1p, c_r2p = dot(dC, dC), dot(dC, dR1), dot(dC, dR2)
    r1p_r1p, r2p_r2p, r1p_r2p = dot(dR1, dR1), dot(dR2, dR2), dot(dR1, dR2)
    worst = np.zeros(len(fit))
    for r in radii:
        along = -s * r1_c + c * r2_c + r * (-cs * r1_r1p - ss * r1_r2p + cc * r2_r1p + cs * r2_r2p)
        ss_norm2 = c_c + 2.0 * r * (c * c_r1p + s * c_r2p) + r * r * (cc * r1p_r1p + ss * r2p_r2p + 2.0 * cs * r1p_r2p)
        cos = np.abs(along) / np.sqrt(su_norm2 * ss_norm2)
        worst = np.maximum(worst, cos.max(axis=1))
    return worst
