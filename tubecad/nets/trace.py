"""Lines of curvature traced on a host surface (issue 44; docs/MATH.md section 15).

A line of curvature of family k (1: along the k1 direction, 2: along k2) through a seed is
the solution of the ODE in the parameters

    d(u, v) / dsigma = uv_k(u, v),

uv_k the parameter direction of unit 3-D length along the principal direction d_k
(:mod:`~tubecad.nets.principal`), sigma the arc length. The field is a line field (d_k and
-d_k are one direction), so each step takes the sign that continues the step before: every
stage of a step is turned to agree with the direction at its start. The integrator is
Dormand & Prince's 5(4) pair (J. Comput. Appl. Math. 6 (1980) 19-26) with its embedded error
estimate, measured in 3-D (the parameter error times |X_u|, |X_v|) and kept below
``tolerance`` per step, the step size adapted as usual (safety 0.9, factors 0.2 .. 5).

The line stops:

- at the face's boundary (a direction that is not closed round a period): the last step
  shortened by bisection until it ends on the boundary (to 1e-12 of the box);
- near an umbilic (one of ``stops``, within ``reach``), where the field is singular;
- on the border of an umbilic part (a hull's flat side, a spherical cap: where the umbilic
  measure (k1 - k2) / 2 is at most ``flat``, the directions are not defined): a step with a
  stage there is halved until its length is FLOOR of the face's size, so the line ends on the
  border to that length (``"umbilic_part"``);
- near a pole of the parameterisation (a side of the parameter box collapsed to a point, a
  NURBS sphere's), within ``reach`` or POLE_REACH of the face's size: the line is regular
  there, but an edge through it would need its pcurve to run along the collapsed side while
  its 3-D curve stays put (two edges);
- on closing: crossing the plane through the seed normal to the seed's direction, moving the
  same way, within CLOSE_SHARE of the face's size of the seed (after a tenth of its size): the
  last step cut on the plane by bisection on its length, the gap left counted in the error;
- after ``max_length`` (a guard, reported).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.nets.host import HostSurface, crossed_breaks
from tubecad.nets.principal import PointField, principal_field

FloatArray = np.ndarray
Family = Literal[1, 2]
Stop = Literal["boundary", "umbilic", "umbilic_part", "pole", "closed", "length"]

# Dormand-Prince 5(4): nodes, stages, 5th- and 4th-order weights
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = [
    [],
    [1 / 5],
    [3 / 40, 9 / 40],
    [44 / 45, -56 / 15, 32 / 9],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
]
_B5 = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0])
_B4 = np.array([5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40])
#: the error estimate's weights, b5 - b4 (plain floats: the step's loop)
_E = (_B5 - _B4).tolist()
#: the most a step may turn (its length times the line's curvature in space, or the larger
#: principal curvature's size where that is more): the edge's quintic pieces then follow the
#: line to about 1e-9 rad (docs/MATH.md section 15). The line's own curvature counts, not only
#: the surface's: a parallel near the crown of a flat dome (k ~ 1e-3, the circle's 7e-3) would
#: otherwise turn 0.3 rad a step, its edge 2e-7 rad off
TURN = 0.05
#: a node on a break line is put this share of the box past it (the field's other side)
NUDGE = 1e-12
#: closing: the line crosses its seed's plane within this share of the face's size of the seed
CLOSE_SHARE = 1e-6
#: a line stops at least this share of the face's size from a pole of the parameterisation
#: (``reach`` from it where that is more): round one its pcurve swings through pi in u over a
#: 3-D length of a few times its distance, in pieces of TURN of that
POLE_REACH = 1e-4
#: the shortest piece between two nodes, as a share of the face's size: a node that would
#: follow the last one closer than this (a step landing a hair short of a break line, of the
#: seed's plane, of the boundary) takes the last one's place, and a seed this near a break line
#: (along the line) is put on it. Far above the round-off at which the edge's knots (the arc
#: lengths, up to 200 sizes) would merge (8 eps x 200 = 3.6e-13), far below the edges' tolerance.
SNAP = 1e-11
#: the shortest piece a plain step's node leaves before the next node (a step landing short of
#: a break line, of the seed's plane, of the boundary), as a share of the face's size: a closer
#: node takes its place, the piece before reaching it; a plain step that short after a break
#: node leaves no node (the next piece starts at the break). On a piece of length h the edge's
#: tangent holds round-off of its end data over h (positions to 1e-13 of a 4 m panel: 6e-9 rad
#: on a 1.7e-4 mm piece before the hull sample's knot line; a 5.1e-4 mm piece after one left
#: its neighbours' knot C0, OCCT's knot removal amplifying round-off by their lengths' ratio),
#: so none is left shorter than this (4 um on that panel), a share of a step the tolerance
#: allows, its piece's turn unchanged.
SHORTEST = 1e-6
#: a line stops on an umbilic part's border when a step into it this share of the face's size
#: long still reaches it (the border found to this length)
FLOOR = 1e-10


@dataclass(frozen=True)
class CurvatureLine:
    """A traced line of curvature of ``family`` from its seed: its parameters ``uv`` (m, 2;
    u unwrapped across a periodic seam), its ``points`` (m, 3), the arc length ``sigma`` at
    each, why it ``stopped`` (at each end: forward, backward), and the largest local error
    estimate of its steps, ``error`` (3-D length)."""

    family: Family
    uv: FloatArray
    points: FloatArray
    sigma: FloatArray
    stopped: tuple[Stop, Stop]
    error: float
    #: per node, the parameter offsets at which the pieces ending and starting there read the
    #: field ((m, 2) each): zero, but at a node on a break line of the surface (one is put on
    #: each crossing) each piece reads it a hair inside its own side
    ending: FloatArray | None = None
    starting: FloatArray | None = None

    @property
    def closed(self) -> bool:
        """Whether the line closed on itself (a loop)."""
        return self.stopped[0] == "closed"

    def offsets(self) -> tuple[FloatArray, FloatArray]:
        """(``ending``, ``starting``), zeros where not given."""
        zero = np.zeros_like(self.uv)
        return (zero if self.ending is None else self.ending, zero if self.starting is None else self.starting)


def trace_line(
    host: HostSurface,
    seed: tuple[float, float],
    family: Family,
    *,
    tolerance: float = 1e-10,
    stops: FloatArray | None = None,
    reach: float = 0.0,
    max_length: float | None = None,
    flat: float = 0.0,
) -> CurvatureLine:
    """The line of curvature of ``family`` through the parameters ``seed`` (module docstring),
    traced both ways until it stops (or once round, where it closes).

    Args:
        host: the surface.
        seed: (u, v) inside its box.
        family: 1 (along the k1 direction) or 2 (along k2).
        tolerance: the local error per step (3-D length).
        stops: umbilics' points (n, 3) the line stops near, or None.
        reach: how near (3-D length); to a pole of the parameterisation too (at least
            POLE_REACH of the face's size).
        max_length: the longest a line may run each way (default 100 x the face's size).
        flat: the umbilic measure (k1 - k2) / 2 (1 / length) at or below which a point lies in
            an umbilic part (:attr:`~tubecad.nets.umbilics.Umbilics.part_level`): the line
            stops on its border; 0, none.

    Returns:
        The line.

    Raises:
        ParameterError: (``family``) not 1 or 2; (``seed``) outside the box, at an umbilic or
            in an umbilic part.
    """
    if family not in (1, 2):
        raise ParameterError(f"family must be 1 or 2, got {family!r:.20}", key="family")
    u, v = (float(x) for x in seed)
    if not host.inside(np.array([u]), np.array([v]))[0]:
        raise ParameterError(f"seed {seed} lies outside the face's parameter box {host.bounds}", key="seed")
    start = principal_field(host, np.array([u]), np.array([v]))
    if not start.umbilic_measure[0] > flat:
        where = "an umbilic" if flat == 0.0 else "in an umbilic part (flat or spherical)"
        raise ParameterError(f"seed {seed} is {where}: every direction there is principal", key="seed")
    size = host.size
    limit = max_length if max_length is not None else 100.0 * size
    direction = (start.uv1 if family == 1 else start.uv2)[0]
    x0 = _snapped(host, np.array([u, v]), direction, SNAP * size)
    ahead = _Tracer(host, family, tolerance, stops, reach, limit, size, flat)
    forward = ahead.run(x0, +1.0)
    if forward.stop == "closed":
        uv, sigma, errors = forward.uv, forward.sigma, forward.error
        ending, starting = forward.across, -forward.across
        stopped: tuple[Stop, Stop] = ("closed", "closed")
    else:
        backward = ahead.run(x0, -1.0)
        uv = np.concatenate([backward.uv[:0:-1], forward.uv])
        sigma = np.concatenate([-backward.sigma[:0:-1], forward.sigma])
        sigma = sigma - sigma[0]
        errors = max(forward.error, backward.error)
        stopped = (forward.stop, backward.stop)
        # a run's piece arriving at a break node reads ``across`` off it, the one leaving the
        # opposite; the backward run, read forwards, swaps arriving and leaving
        ending = np.concatenate([-backward.across[:0:-1], forward.across])
        starting = np.concatenate([backward.across[:0:-1], -forward.across])
    wu, wv = host.wrapped(uv[:, 0], uv[:, 1])
    return CurvatureLine(family, uv, host.points(wu, wv), sigma, stopped, errors, ending, starting)


def _turn(a: FloatArray, b: FloatArray) -> float:
    """The angle between the vectors a and b (2-D or 3-D; accurate near 0): atan2(|a x b|, a.b),
    in Python floats (numpy's cross of two 3-vectors costs 50 us, this 2)."""
    if len(a) == 2:
        (a0, a1), (b0, b1) = a.tolist(), b.tolist()
        return math.atan2(abs(a0 * b1 - a1 * b0), a0 * b0 + a1 * b1)
    (a0, a1, a2), (b0, b1, b2) = a.tolist(), b.tolist()
    c0, c1, c2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0
    return math.atan2(math.sqrt(c0 * c0 + c1 * c1 + c2 * c2), a0 * b0 + a1 * b1 + a2 * b2)


def _poles(host: HostSurface, size: float) -> FloatArray:
    """The poles of the parameterisation: the points to which a side of the parameter box
    collapses (a NURBS sphere's v = +-pi/2, |X_u x X_v| = 0 along it), (n, 3). A line through
    one stops ``reach`` from it like at an umbilic (its pcurve would have to run along the
    collapsed side, where the 3-D curve does not move: two edges, not one)."""
    u0, u1, v0, v1 = host.bounds
    cu, cv = host.closed
    t = np.linspace(0.0, 1.0, 9)
    sides = []
    if not cv:
        sides += [(u0 + (u1 - u0) * t, np.full(9, v0)), (u0 + (u1 - u0) * t, np.full(9, v1))]
    if not cu:
        sides += [(np.full(9, u0), v0 + (v1 - v0) * t), (np.full(9, u1), v0 + (v1 - v0) * t)]
    out = []
    for u, v in sides:
        points = host.points(u, v)
        if float(np.ptp(points, axis=0).max()) <= 1e-9 * size:
            out.append(points.mean(axis=0))
    return np.array(out).reshape(-1, 3)


def _breaks_of(host: HostSurface, k: int) -> tuple[FloatArray, float | None]:
    """The break values of coordinate ``k`` (the periodic seam's with them where the face is
    closed that way) and the period they repeat with (None)."""
    values = host.breaks[k]
    period = host.periods[k] if host.closed[k] else None
    if period is not None:
        values = np.append(values, host.bounds[2 * k])
    return values, period


def _nearest_break(host: HostSurface, k: int, value: float) -> float | None:
    """The break value of coordinate ``k`` nearest ``value`` (unwrapped as ``value`` is)."""
    values, period = _breaks_of(host, k)
    if not values.size:
        return None
    if period is not None:
        values = values + period * np.round((value - values) / period)
    return float(values[np.argmin(np.abs(values - value))])


def _snapped(host: HostSurface, x: FloatArray, direction: FloatArray, reach: float) -> FloatArray:
    """The seed ``x`` put on a break line it lies within ``reach`` of along the line's
    parameter ``direction`` (per unit length): its node is then a break node (the field read
    on each side), not a node a hair from one, whose piece to the break would be as short."""
    x = x.copy()
    for k in (0, 1):
        value = _nearest_break(host, k, float(x[k]))
        if value is not None and abs(value - x[k]) < reach * abs(direction[k]):
            x[k] = value
    return x


@dataclass
class _Run:
    uv: FloatArray
    sigma: FloatArray
    stop: Stop
    error: float
    across: FloatArray  # (m, 2): from a node just past a break back across it, else 0


class _Tracer:
    """One way of a line: the integrator and its stopping rules (module docstring)."""

    def __init__(self, host, family, tolerance, stops, reach, limit, size, flat=0.0) -> None:
        self.host, self.family, self.tolerance = host, family, tolerance
        self.flat = flat
        self.in_part = False  # the last field read was inside an umbilic part
        self.stops = np.zeros((0, 3)) if stops is None else np.asarray(stops, dtype=float).reshape(-1, 3)
        self.reach, self.limit, self.size = reach, limit, size
        self.field = PointField(host)
        self.curvature = 0.0
        self._last: tuple[float, float, tuple[float, ...] | None, bool] | None = None
        self.poles = _poles(host, size)
        self.pole_reach = max(reach, POLE_REACH * size)

    def direction(self, x: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray] | None:
        """(uv direction, 3-D direction, |X_u| and |X_v|) of the family at the point x; None
        at a degenerate point. Keeps the larger principal curvature's size (``curvature``)."""
        at = self._field_at(float(x[0]), float(x[1]))
        if at is None:
            return None
        return np.array(at[:2]), np.array(at[2:5]), np.array(at[5:7])

    def point(self, x: FloatArray) -> FloatArray:
        u, v = self.host.wrapped(x[:1], x[1:])
        return self.host.points(u, v)[0]

    def run(self, x0: FloatArray, sign: float) -> _Run:
        first = self.direction(x0)
        assert first is not None  # the seed is checked
        uv0, d0, lengths = first
        reference = sign * d0  # the way this run goes, in 3-D
        seed_point = self.point(x0)
        # a seed on a break line the line crosses is a break node: the field read on the side
        # this run goes to (across: the side behind, read by a piece arriving there)
        bias: FloatArray | None = None  # on a break line: the field is read on the side ahead
        start = np.zeros(2)
        for k in (0, 1):
            if _nearest_break(self.host, k, float(x0[k])) == x0[k] and abs(uv0[k]) * lengths[k] > 1e-6:
                bias = np.zeros(2) if bias is None else bias
                bias[k] = np.sign(sign * uv0[k]) * NUDGE * self._width(k)
                start[k] = -bias[k]
        xs, sigmas, across = [x0.copy()], [0.0], [start]

        def done(stop: Stop, error: float) -> _Run:
            return _Run(np.array(xs), np.array(sigmas), stop, error, np.array(across))

        def node(at: FloatArray, length: float, off: FloatArray) -> None:
            """A node at the arc length ``length``: in the last one's place where that one is
            less than SHORTEST of the face's size behind and a plain step's end (not the seed, not
            on a break line); else after it (a piece that short from the seed or a break node
            stays: the seed is put on a break line that near, :func:`_snapped`)."""
            if length - sigmas[-1] < SHORTEST * self.size and len(xs) > 1 and not np.any(across[-1]):
                xs[-1], sigmas[-1], across[-1] = at.copy(), length, off
            else:
                xs.append(at.copy())
                sigmas.append(length)
                across.append(off)

        x, sigma, h, worst = x0.copy(), 0.0, 1e-3 * self.size, 0.0
        while True:
            step = self._step(x, h, reference, bias)
            if step is None and self.in_part and h > FLOOR * self.size:
                h *= 0.5  # a stage inside an umbilic part: closer to its border
                continue
            if step is None:  # an umbilic's neighbourhood (or part): the field is singular
                return done("umbilic_part" if self.in_part else "umbilic", worst)
            new, error, direction, _, bent = step
            if error > self.tolerance:
                h *= max(0.2, 0.9 * (self.tolerance / error) ** 0.2)
                continue
            # the step's turn in space and in the parameters (a pcurve swinging round a pole)
            bending = max(_turn(reference, direction), bent)
            if bending > 2 * TURN and h > 1e3 * SNAP * self.size:
                h *= max(0.1, TURN / bending)
                continue
            inside = self.host.inside(new[:1], new[1:])[0]
            if not inside:
                new, taken = self._to_boundary(x, h, reference, bias)
                node(new, sigma + taken, np.zeros(2))
                return done("boundary", max(worst, error))
            p_new = self.point(new)
            crossed = crossed_breaks(self.host, x, new)
            if sigma + h > 0.1 * self.size and self._crosses_seed(x, p_new, seed_point, d0 * sign, h):
                # back at the seed (checked before a break the step crosses too: the seed may
                # lie between the two, or on the break, a node of its own)
                closing = self._closing(x, h, new, reference, seed_point, d0 * sign, bias)
                if closing is not None:
                    end, taken, gap = closing
                    if not crossed or taken <= self._to_break(x, h, reference, bias, *crossed[0])[1] + SNAP * self.size:
                        # the loop's gap is its error; its last node is its first (the start's
                        # side behind read by the last piece where the seed is on a break)
                        node(end, sigma + taken, across[0].copy())
                        return done("closed", max(worst, error, gap))
            if crossed:  # a node on the break; the field read on the side ahead from there
                k, value = crossed[0]
                at, taken, ahead = self._to_break(x, h, reference, bias, k, value)
                sigma += taken
                node(at, sigma, -ahead)
                x, bias = at, ahead
                worst = max(worst, error)
                continue
            worst = max(worst, error)
            bias = None
            x, sigma = new, sigma + h
            if not (np.any(across[-1]) and sigma - sigmas[-1] < SHORTEST * self.size):
                node(x, sigma, np.zeros(2))  # (a step that short after a break node leaves none:
                # its piece would be too short to join the next one C2 in round-off)
            bending /= h  # the line's curvature in space (normal and geodesic) or its pcurve's
            reference = direction
            if len(self.stops) and np.linalg.norm(self.stops - p_new, axis=1).min() < self.reach:
                return done("umbilic", worst)
            if len(self.poles) and np.linalg.norm(self.poles - p_new, axis=1).min() < self.pole_reach:
                return done("pole", worst)
            if sigma >= self.limit:
                return done("length", worst)
            h *= min(5.0, 0.9 * (self.tolerance / max(error, 1e-300)) ** 0.2)
            # the edge's Hermite pieces follow the line to 1e-9 rad where a step turns by at
            # most TURN, in space and in the parameters (a line integrated exactly in the
            # parameters, a torus' circle, would otherwise stride the whole face; a line past
            # a pole of the parameterisation, a NURBS sphere's, swings round it in u)
            h = min(h, 0.05 * self.size, TURN / max(self.curvature, bending, 1e-300))

    def _width(self, k: int) -> float:
        u0, u1, v0, v1 = self.host.bounds
        return (u1 - u0) if k == 0 else (v1 - v0)

    def _step(self, x: FloatArray, h: float, reference: FloatArray, bias: FloatArray | None = None):
        """One Dormand-Prince step of length h: (new x, error, 3-D direction at the end,
        metric), every stage's direction turned to agree with ``reference`` and evaluated
        ``bias`` off (a node on a break line: the field of the side ahead); None where the
        field vanishes (an umbilic).

        In Python floats (numpy's small-array calls cost more than the arithmetic here), the
        field at the point of the last stage kept: it is the next step's first stage where the
        step is taken (Dormand-Prince's "first same as last"), and a step tried again shorter
        starts from the same point."""
        x0, x1 = float(x[0]), float(x[1])
        b0, b1 = (0.0, 0.0) if bias is None else (float(bias[0]), float(bias[1]))
        r0, r1, r2 = (float(c) for c in reference)
        ku: list[float] = []
        kv: list[float] = []
        metric, end = (0.0, 0.0), (0.0, 0.0, 0.0)
        for i, row in enumerate(_A):
            su = sv = 0.0
            for a, ka, kb in zip(row, ku, kv):
                su += a * ka
                sv += a * kb
            pu, pv = x0 + h * su, x1 + h * sv
            at = self._field_at(pu + b0, pv + b1)
            if at is None or not (math.isfinite(at[0]) and math.isfinite(at[1])):
                return None
            flip = -1.0 if at[2] * r0 + at[3] * r1 + at[4] * r2 < 0 else 1.0
            ku.append(flip * at[0])
            kv.append(flip * at[1])
            if i == 0:
                metric = (at[5], at[6])
            if i == 6:
                end = (flip * at[2], flip * at[3], flip * at[4])
        new = np.array([pu, pv])  # the last stage's point: x + h sum(b5_j k_j) (its row is _B5)
        eu = ev = 0.0
        for e, ka, kb in zip(_E, ku, kv):
            eu += e * ka
            ev += e * kb
        eu, ev = h * eu, h * ev
        error = abs(eu) * metric[0] + abs(ev) * metric[1]
        turn = math.atan2(abs(ku[0] * kv[6] - kv[0] * ku[6]), ku[0] * ku[6] + kv[0] * kv[6])
        return new, error, np.array(end), np.array(metric), turn

    def _field_at(self, u: float, v: float) -> tuple[float, ...] | None:
        """The field's data at (u, v) (:meth:`PointField.at`, wrapped into the box), the last
        point's kept; None at a degenerate point and inside an umbilic part (``in_part`` then
        set); sets ``curvature``."""
        if self._last is not None and self._last[0] == u and self._last[1] == v:
            at, self.in_part = self._last[2], self._last[3]
        else:
            wu, wv = self.host.wrapped_point(u, v)
            at = self.field.at(wu, wv, self.family)
            self.in_part = self.flat > 0.0 and at is not None and at[7] <= self.flat
            if self.in_part:
                at = None
            self._last = (u, v, at, self.in_part)
        if at is not None:
            self.curvature = at[8]
        return at

    def _to_break(
        self, x: FloatArray, h: float, reference: FloatArray, bias: FloatArray | None, k: int, value: float
    ) -> tuple[FloatArray, float, FloatArray]:
        """The step from x cut where coordinate ``k`` reaches the break ``value`` (bisection on
        its length, the node then set on it exactly); (the node, the length taken, the offset
        NUDGE of the box ahead across the break, where the field is read from there on)."""
        full = self._step(x, h, reference, bias)
        sign = 1.0 if full is not None and full[0][k] > x[k] else -1.0
        lo, hi, end = 0.0, h, x
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            step = self._step(x, mid, reference, bias)
            if step is None:
                break
            if sign * (step[0][k] - value) < 0.0:
                lo = mid
            else:
                hi, end = mid, step[0]
            if hi - lo < 1e-15 * self.size:
                break
        u0, u1, v0, v1 = self.host.bounds
        at = end.copy()
        at[k] = value
        ahead = np.zeros(2)
        ahead[k] = sign * NUDGE * ((u1 - u0) if k == 0 else (v1 - v0))
        return at, hi, ahead

    def _to_boundary(
        self, x: FloatArray, h: float, reference: FloatArray, bias: FloatArray | None = None
    ) -> tuple[FloatArray, float]:
        """The step from x cut where it meets the box's boundary (bisection on its length)."""
        lo, hi = 0.0, h
        best = x
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            step = self._step(x, mid, reference, bias)
            if step is None:
                break
            if self.host.inside(step[0][:1], step[0][1:])[0]:
                lo, best = mid, step[0]
            else:
                hi = mid
            if hi - lo < 1e-12 * self.size:
                break
        u0, u1, v0, v1 = self.host.bounds
        clipped = np.array([min(max(best[0], u0), u1), min(max(best[1], v0), v1)])
        cu, cv = self.host.closed
        return np.array([best[0] if cu else clipped[0], best[1] if cv else clipped[1]]), lo

    def _crosses_seed(self, x: FloatArray, end: FloatArray, seed: FloatArray, way: FloatArray, h: float) -> bool:
        """Whether the step from x to the point ``end`` crosses the seed's plane (normal
        ``way``) next to the seed: the cheap test before :meth:`_closing` cuts the step."""
        da, db = float((self.point(x) - seed) @ way), float((end - seed) @ way)
        return da < 0.0 <= db and float(np.linalg.norm(end - seed)) <= h + CLOSE_SHARE * self.size

    def _closing(
        self,
        x: FloatArray,
        h: float,
        new: FloatArray,
        reference: FloatArray,
        seed: FloatArray,
        way: FloatArray,
        bias: FloatArray | None = None,
    ):
        """The step of length h from x to ``new``, which crosses the seed's plane (normal
        ``way``) next to the seed (:meth:`_crosses_seed`), cut on that plane by bisection on its
        length: (the point's parameters, the length taken, its gap from the seed); None where
        the gap is over CLOSE_SHARE of the face's size (the line does not close there)."""
        lo, hi, end = 0.0, h, new
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            cut = self._step(x, mid, reference, bias)
            if cut is None:
                return None
            if float((self.point(cut[0]) - seed) @ way) < 0.0:
                lo = mid
            else:
                hi, end = mid, cut[0]
            if hi - lo < 1e-14 * self.size:
                break
        gap = float(np.linalg.norm(self.point(end) - seed))
        return (end, hi, gap) if gap <= CLOSE_SHARE * self.size else None
