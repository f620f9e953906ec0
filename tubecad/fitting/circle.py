"""The unit circle as a periodic rational quadratic B-spline whose C0 knots are the stringers.

OCCT calls a B-spline C0 wherever a knot's multiplicity equals the degree, and its
pre-boolean check (BOPAlgo_ArgumentAnalyzer) reports every face that spans such a knot.
The classic circle (four 90 deg arcs, double knots) puts one every quarter turn. Here the
double knots sit only at chosen *breaks* (the stringers, which are face boundaries), and
each arc of angle theta < 2 pi between two breaks is a C1 chain of n = ceil(theta / 90 deg)
sub-arcs of angle a = theta / n joined by simple knots (docs/MATH.md section 6):

    end weights    J_i = cos^2(theta / 4) / cos^2(i a / 2 - theta / 4),   i = 0..n (J_0 = J_n = 1)
    middle weights m_i = cos(a / 2) sqrt(J_i J_{i+1})                       (the circle's shape factor)
    knot spans     proportional to m_i, summing to theta

The homogeneous curve is C1 at an interior knot exactly when J_i is the harmonic mean of
m_{i-1}, m_i with spans in the ratio m_{i-1} : m_i; with m_i as above this is the
recurrence Y_{i-1} + Y_{i+1} = 2 cos(a / 2) Y_i for Y = 1 / sqrt(J), solved by the cosine.
Y stays positive only while theta < 2 pi, so a closed C1 quadratic circle does not exist:
an arc longer than 330 deg (a single break, or two close ones) is split at its middle,
which leaves one C0 knot inside that face.

The parameter u is the angle at every break (u = theta there, so stringer cuts are exact)
and a smooth monotone function of it in between; :meth:`CircleSpline.theta_of_u` and
:meth:`CircleSpline.u_of_theta` convert in closed form.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

TWO_PI = 2 * math.pi
#: the longest sub-arc of a chain (90 deg: neighbouring weights stay within a factor 2)
MAX_SUB_ARC = math.pi / 2
#: the longest C1 arc: the end-to-middle weight ratio 1 / cos^2(theta / 4) grows without
#: bound as theta nears 2 pi (58 at 330 deg); a longer arc is split at its middle (C0 there)
MAX_ARC = math.radians(330.0)


@dataclass(frozen=True)
class _Arc:
    """Sub-arc of angle ``alpha`` starting at angle ``start`` and parameter ``u0``: the
    rational Bezier with weights (w0, m, w1) over u in [u0, u0 + du]."""

    start: float
    alpha: float
    u0: float
    du: float
    w0: float
    m: float
    w1: float


@dataclass(frozen=True)
class CircleSpline:
    """The unit circle, C0 only at ``breaks`` (radians in [0, 2 pi), increasing, first 0)."""

    breaks: tuple[float, ...]
    x: np.ndarray = field(repr=False)  # pole coordinates, weights: one period
    y: np.ndarray = field(repr=False)
    weights: np.ndarray = field(repr=False)
    knots: np.ndarray = field(repr=False)  # distinct knots over [0, 2 pi] and their multiplicities
    multiplicities: np.ndarray = field(repr=False)
    arcs: tuple[_Arc, ...] = field(repr=False)

    @classmethod
    def with_breaks(
        cls, breaks: np.ndarray | list[float] | tuple[float, ...], max_sub_arc: float = MAX_SUB_ARC
    ) -> CircleSpline:
        """The circle with double knots at the angles ``breaks`` (radians, relative to the
        first, which becomes angle and parameter 0), its C1 sub-arcs at most ``max_sub_arc``
        (a canal surface's Moebius map needs shorter ones, :mod:`.canal_section`)."""
        b = np.unique(np.mod(np.asarray(breaks, dtype=float) - float(np.asarray(breaks).flat[0]), TWO_PI))
        ends = np.append(b, TWO_PI)
        long = np.diff(ends) > MAX_ARC  # (a single break always: no closed C1 circle exists)
        b = np.sort(np.concatenate([b, 0.5 * (ends[:-1] + ends[1:])[long]]))
        ends = np.append(b, TWO_PI)
        x, y, w, knots, mults, arcs = [], [], [], [], [], []
        for start, stop in zip(ends[:-1], ends[1:]):
            theta = stop - start
            n = max(1, math.ceil(theta / max_sub_arc - 1e-12))
            a = theta / n
            J = math.cos(theta / 4) ** 2 / np.cos(np.arange(n + 1) * a / 2 - theta / 4) ** 2
            J[0] = J[-1] = 1.0
            m = math.cos(a / 2) * np.sqrt(J[:-1] * J[1:])
            spans = theta * m / m.sum()
            u = start + np.concatenate([[0.0], np.cumsum(spans)])
            u[-1] = stop
            x.append(math.cos(start))
            y.append(math.sin(start))
            w.append(1.0)
            knots.append(start)
            mults.append(2)
            for i in range(n):
                mid = start + (i + 0.5) * a
                x.append(math.cos(mid) / math.cos(a / 2))
                y.append(math.sin(mid) / math.cos(a / 2))
                w.append(m[i])
                if i > 0:
                    knots.append(u[i])
                    mults.append(1)
                arcs.append(_Arc(start + i * a, a, u[i], u[i + 1] - u[i], J[i], m[i], J[i + 1]))
        knots.append(TWO_PI)
        mults.append(2)
        return cls(
            tuple(map(float, b)), np.array(x), np.array(y), np.array(w), np.array(knots), np.array(mults), tuple(arcs)
        )

    @classmethod
    def for_stringers(
        cls, angles: np.ndarray | list[float] | tuple[float, ...], max_sub_arc: float = MAX_SUB_ARC
    ) -> CircleSpline:
        """The circle with the fewest poles whose C0 knots are stringers (face boundaries):
        breaks at the first angle and at the one nearest the opposite side, so each arc is
        at most about 180 deg + the stringer spacing (6 poles for evenly spaced stringers)."""
        rel = np.mod(np.asarray(angles, dtype=float) - float(np.asarray(angles).flat[0]), TWO_PI)
        opposite = rel[np.argmin(np.abs(rel - math.pi))]
        return cls.with_breaks([0.0] if opposite == 0.0 else [0.0, float(opposite)], max_sub_arc)

    @classmethod
    def quarters(cls) -> CircleSpline:
        """The classic circle: four 90 deg arcs, double knots at 0, 90, 180, 270 deg."""
        return cls.with_breaks(np.arange(4) * math.pi / 2)

    def _arc_index(self, u: np.ndarray) -> np.ndarray:
        starts = np.array([a.u0 for a in self.arcs])
        return np.clip(np.searchsorted(starts, u, side="right") - 1, 0, len(self.arcs) - 1)

    def theta_of_u(self, u: np.ndarray | float) -> np.ndarray:
        """Angle (radians) at parameter u: the rational Bezier of the sub-arc evaluated in
        closed form, tan((phi - a/2) / 2) = tan(a / 4) (2 sigma - 1), with sigma the
        standard-form parameter: sigma / (1 - sigma) = (tau / (1 - tau)) sqrt(w1 / w0)."""
        u = np.asarray(u, dtype=float)
        turns = np.floor(u / TWO_PI)
        local = u - turns * TWO_PI
        idx = self._arc_index(local)
        out = np.empty_like(local)
        for k in np.unique(idx):
            arc, sel = self.arcs[k], idx == k
            tau = np.clip((local[sel] - arc.u0) / arc.du, 0.0, 1.0)
            r = math.sqrt(arc.w1 / arc.w0)
            sigma = r * tau / (r * tau + (1.0 - tau))
            out[sel] = arc.start + arc.alpha / 2 + 2 * np.arctan(math.tan(arc.alpha / 4) * (2 * sigma - 1))
        return out + turns * TWO_PI

    def u_of_theta(self, theta: np.ndarray | float) -> np.ndarray:
        """Parameter u at angle theta (radians), the inverse of :meth:`theta_of_u`."""
        theta = np.asarray(theta, dtype=float)
        turns = np.floor(theta / TWO_PI)
        local = theta - turns * TWO_PI
        starts = np.array([a.start for a in self.arcs])
        idx = np.clip(np.searchsorted(starts, local, side="right") - 1, 0, len(self.arcs) - 1)
        out = np.empty_like(local)
        for k in np.unique(idx):
            arc, sel = self.arcs[k], idx == k
            phi = np.clip(local[sel] - arc.start, 0.0, arc.alpha)
            sigma = 0.5 * (1.0 + np.tan((phi - arc.alpha / 2) / 2) / math.tan(arc.alpha / 4))
            r = math.sqrt(arc.w1 / arc.w0)
            tau = sigma / (sigma + r * (1.0 - sigma))
            out[sel] = arc.u0 + arc.du * tau
        return out + turns * TWO_PI
