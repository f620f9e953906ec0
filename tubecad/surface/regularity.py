"""Regularity of a tube (docs/MATH.md section 5).

Locally the tube is regular only where rho |k(s)| < 1 (else G = 0 somewhere on the
circle and the surface folds). Globally it self-intersects where the axis comes back
within 2 rho of itself so far that a point of the surface lies strictly inside the tube
around another part of the axis, more than pi rho away along it. Closeness of the axis
alone is not enough: a 0.9-turn torus brings its two ends close across the gap with no
overlap at all, so the surface itself is tested. (Within pi rho of arc a curve with
rho |k| < 1 cannot bring its points closer than 2 rho, by Schur's comparison theorem.)

Surface points are sampled every rho / 8 along the axis and 32 around it, and each
candidate is refined by Newton's method; a penetration shallower than about
rho / 500 can be missed. On a closed axis "along it" is the shorter way round the loop.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import cKDTree

from tubecad.curves.axis import Axis

MAX_SAMPLES = 40_000
#: the closest return of the axis is reported when it is within this many radii
REPORT_RETURNS_WITHIN = 3.0
MAX_CANDIDATES = 20_000
#: axis sample pairs within REPORT_RETURNS_WITHIN radii kept in memory: an axis that coils
#: onto itself (a long helix of tiny pitch, a circle run many times round) is sampled more
#: coarsely instead, so the check stays within ~100 MB and a few seconds
MAX_PAIRS = 500_000
#: points per side of the grids refining the closest return (_refine_closest)
REFINE_GRID = 33
#: axis samples whose circles are tested for entry at once (bounds the candidate matrix)
ENTRY_CHUNK = 128


@dataclass(frozen=True)
class RegularityReport:
    """What was measured: the largest rho |k|, where rho |k| >= 1, and the axis' closest
    return to itself (None when no two far-apart axis points are within 2 rho)."""

    radius: float
    max_rho_k: float
    s_at_max_rho_k: float
    folded_intervals: list[tuple[float, float]] = field(default_factory=list)
    closest_approach: float | None = None
    closest_pair: tuple[float, float] | None = None
    crossing_pair: tuple[float, float] | None = None

    @property
    def locally_regular(self) -> bool:
        return self.max_rho_k < 1.0

    @property
    def self_intersecting(self) -> bool:
        return self.crossing_pair is not None

    @property
    def ok(self) -> bool:
        return self.locally_regular and not self.self_intersecting

    def message(self) -> str:
        """Why the tube is refused, with the s values where it happens."""
        lines = []
        if not self.locally_regular:
            where = ", ".join(f"[{a:.6g}, {b:.6g}]" for a, b in self.folded_intervals)
            lines.append(
                f"rho*k reaches {self.max_rho_k:.6g} at s = {self.s_at_max_rho_k:.6g}; it must stay below 1 "
                f"(radius {self.radius:g} is larger than the axis' radius of curvature for s in {where})"
            )
        if self.self_intersecting:
            s1, s2 = self.closest_pair  # type: ignore[misc]
            c1, c2 = self.crossing_pair  # type: ignore[misc]
            lines.append(
                f"the axis comes back within {self.closest_approach:.6g} of itself (closest between s = {s1:.6g} "
                f"and s = {s2:.6g}; a tube of radius {self.radius:g} needs 2*rho = {2 * self.radius:g}) and the "
                f"tube self-intersects: the circle at s = {c1:.6g} enters the tube around s = {c2:.6g}"
            )
        return "tube is not regular: " + "; ".join(lines) + " (pass allow_irregular=True to build it anyway)"


def check_regularity(axis: Axis, radius: float) -> RegularityReport:
    """Measure local and global regularity of the tube of ``radius`` about ``axis``."""
    s0, s1 = axis.span
    n = int(min(MAX_SAMPLES, max(2001, math.ceil(8 * axis.length / radius) + 1)))
    s = np.linspace(s0, s1, n)
    rho_k = radius * np.abs(axis.curvature(s))
    i = int(np.argmax(rho_k))
    s_max, max_rho_k = _refine_max(axis, radius, s, i)
    folded = _folded_intervals(axis, radius, s, rho_k >= 1.0)
    approach, pair, crossing = _closest_return(axis, radius, s)
    return RegularityReport(radius, max_rho_k, s_max, folded, approach, pair, crossing)


def _refine_max(axis: Axis, radius: float, s: np.ndarray, i: int) -> tuple[float, float]:
    lo, hi = s[max(i - 1, 0)], s[min(i + 1, len(s) - 1)]
    best = (float(s[i]), float(radius * abs(axis.curvature(s[i]))))
    if 0 < i < len(s) - 1:
        from scipy.optimize import minimize_scalar  # at first use: a spec's check loads no scipy.optimize (0.1 s)

        res = minimize_scalar(lambda x: -radius * abs(float(axis.curvature(x))), bounds=(lo, hi), method="bounded")
        if -res.fun > best[1]:
            best = (float(res.x), float(-res.fun))
    return best


def _folded_intervals(axis: Axis, radius: float, s: np.ndarray, bad: np.ndarray) -> list[tuple[float, float]]:
    """Maximal runs of s where rho |k| >= 1, with their ends refined by root finding."""
    if not bad.any():
        return []
    from scipy.optimize import brentq  # at first use: a tube that never folds loads no scipy.optimize

    def excess(x: float) -> float:
        return radius * abs(float(axis.curvature(x))) - 1.0

    runs = []
    edges = np.flatnonzero(np.diff(bad.astype(np.int8)))
    starts = ([0] if bad[0] else []) + [e + 1 for e in edges if not bad[e]]
    ends = [e for e in edges if bad[e]] + ([len(s) - 1] if bad[-1] else [])
    for a, b in zip(starts, ends):
        left = s[a] if a == 0 else brentq(excess, s[a - 1], s[a])
        right = s[b] if b == len(s) - 1 else brentq(excess, s[b], s[b + 1])
        runs.append((float(left), float(right)))
    return runs


def _closest_return(
    axis: Axis, radius: float, s: np.ndarray
) -> tuple[float | None, tuple[float, float] | None, tuple[float, float] | None]:
    """Closest distance (if under 3 rho) between axis points more than pi*rho apart along the
    axis, where, and a (circle s, axis s) pair where the surface enters the tube elsewhere."""
    if s[-1] - s[0] <= math.pi * radius:
        return None, None, None
    step = min(radius / 8.0, (s[-1] - s[0]) / 64.0)
    m = int(min(MAX_SAMPLES, math.ceil((s[-1] - s[0]) / step) + 1))
    ss = np.linspace(s[0], s[-1], m)
    pts = axis.position(ss)
    tree = cKDTree(pts)
    # the pairs estimated from a subsample's neighbours (a dual-tree count of all of them
    # costs 0.3 s on a 40,000-sample coil), scaled to all samples
    every = max(1, len(ss) // 2048) if len(ss) > 4096 else 1
    near = int(cKDTree(pts[::every]).count_neighbors(tree, REPORT_RETURNS_WITHIN * radius))
    count = (near * len(ss) // len(pts[::every]) - len(ss)) // 2
    if count > MAX_PAIRS:  # the axis is packed onto itself: pairs grow as samples^2
        ss = np.linspace(s[0], s[-1], max(64, int(len(ss) * math.sqrt(MAX_PAIRS / count))))
        pts = axis.position(ss)
        tree = cKDTree(pts)
    pairs = tree.query_pairs(REPORT_RETURNS_WITHIN * radius, output_type="ndarray")
    if len(pairs):
        pairs = pairs[_apart(axis, ss[pairs[:, 0]], ss[pairs[:, 1]]) >= math.pi * radius]
    if len(pairs) == 0:
        return None, None, None
    dist = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    i, j = pairs[int(np.argmin(dist))]
    approach, pair = _refine_closest(axis, ss, i, j, float(np.min(dist)))
    close = pairs[dist < 2.0 * radius]
    if len(close) == 0:
        return approach, pair, None
    return approach, pair, _surface_entry(axis, radius, ss, pts, tree, np.unique(close.ravel()))


def _surface_entry(
    axis: Axis, radius: float, ss: np.ndarray, pts: np.ndarray, tree: cKDTree, near: np.ndarray
) -> tuple[float, float] | None:
    """The deepest point where a circle of the tube (at an axis sample in ``near``) lies
    inside the tube around a far part of the axis (or on it, to round-off: a circle run
    round twice), as (s of the circle, s on the axis).

    The samples are taken ENTRY_CHUNK at a time; once an entry is found and more than
    MAX_CANDIDATES candidates were refined, the search stops (a densely coiled axis)."""
    best: tuple[float, float, float] | None = None  # (depth, s of the circle, s on the axis)
    refined = 0
    for chunk in np.array_split(near, max(1, math.ceil(len(near) / ENTRY_CHUNK))):
        found, count = _deepest_entry(axis, radius, ss, pts, tree, chunk)
        refined += count
        if found is not None and (best is None or found[0] > best[0]):
            best = found
        if best is not None and refined > MAX_CANDIDATES:
            break
    return None if best is None else (best[1], best[2])


def _deepest_entry(
    axis: Axis, radius: float, ss: np.ndarray, pts: np.ndarray, tree: cKDTree, near: np.ndarray
) -> tuple[tuple[float, float, float] | None, int]:
    h = ss[1] - ss[0]
    _, r1, r2 = axis.rotation_minimising_frame(ss[near])
    u = np.linspace(0.0, 2.0 * math.pi, 32, endpoint=False)
    surf = pts[near][:, None, :] + radius * (
        np.cos(u)[None, :, None] * r1[:, None] + np.sin(u)[None, :, None] * r2[:, None]
    )
    circle_s = np.repeat(ss[near], len(u))
    surf = surf.reshape(-1, 3)
    cand = cKDTree(surf).sparse_distance_matrix(tree, radius + h, output_type="ndarray")
    far = _apart(axis, ss[cand["j"]], circle_s[cand["i"]]) >= math.pi * radius
    cand = cand[far]
    if len(cand) == 0:
        return None, 0
    if len(cand) > MAX_CANDIDATES:  # the deepest entry is among the closest candidates
        cand = cand[np.argpartition(cand["v"], MAX_CANDIDATES)[:MAX_CANDIDATES]]
    p_idx, q_idx = cand["i"], cand["j"]
    x, target = ss[q_idx].astype(float), surf[p_idx]
    lo, hi = ss[0], ss[-1]
    for _ in range(5):  # Newton: the closest axis point near each candidate sample (from within 2 h: quadratic)
        a = axis.at(x)
        r = target - a.position
        f = np.einsum("ij,ij->i", r, a.t)
        fp = -1.0 + np.einsum("ij,ij->i", r, a.curvature_vector)
        with np.errstate(divide="ignore", invalid="ignore"):  # fp = 0 at a centre of curvature
            step = np.where(fp != 0.0, f / fp, 0.0)
        x = np.clip(x - step, np.maximum(lo, ss[q_idx] - 2 * h), np.minimum(hi, ss[q_idx] + 2 * h))
    a = axis.at(x)
    depth = radius - np.linalg.norm(target - a.position, axis=1)
    in_disc = np.abs(np.einsum("ij,ij->i", target - a.position, a.t)) < 1e-7 * radius  # not beyond an end cap
    # depth ~ 0 (to round-off) away from the ends is a surface lying on another part of
    # itself (a circle run round more than once): refused too; a ring closed end to end is not
    c_s = circle_s[p_idx]
    interior = (np.minimum(c_s - lo, hi - c_s) > h) & (np.minimum(x - lo, hi - x) > h) | axis.closed
    touching = (np.abs(depth) <= 1e-9 * radius) & interior
    inside = ((depth > 1e-9 * radius) | touching) & in_disc & (_apart(axis, x, c_s) >= math.pi * radius)
    if not inside.any():
        return None, len(cand)
    k = np.flatnonzero(inside)[np.argmax(depth[inside])]
    return (float(depth[k]), float(circle_s[p_idx[k]]), float(x[k])), len(cand)


def _apart(axis: Axis, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """How far apart arc lengths a and b lie along the axis: |a - b|, or the shorter way
    round a closed loop, min(|a - b|, L - |a - b|)."""
    d = np.abs(a - b)
    return np.minimum(d, axis.length - d) if axis.closed else d


def _refine_closest(axis: Axis, ss: np.ndarray, i: int, j: int, sampled: float) -> tuple[float, tuple[float, float]]:
    """The closest pair of axis points in the cells round samples i and j: the distance on a
    REFINE_GRID x REFINE_GRID grid over (s_i +- h) x (s_j +- h), then on the same grid over
    the two steps round its best pair. Near its minimum the distance is quadratic in the
    parameters, so the grid's step (h / 256 at the second level) leaves an error of order
    (h / 256)^2 |c''|. (A grid, not scipy's L-BFGS: the spec check then loads no
    scipy.optimize, 0.1 s of every refusal.)"""
    h, lo, hi = ss[1] - ss[0], ss[0], ss[-1]
    boxes = [(max(lo, ss[i] - h), min(hi, ss[i] + h)), (max(lo, ss[j] - h), min(hi, ss[j] + h))]
    best = (sampled**2, float(ss[i]), float(ss[j]))
    for _ in range(2):
        a = np.linspace(*boxes[0], REFINE_GRID)
        b = np.linspace(*boxes[1], REFINE_GRID)
        gap = np.sum((axis.position(a)[:, None, :] - axis.position(b)[None, :, :]) ** 2, axis=-1)
        k, m = np.unravel_index(int(np.argmin(gap)), gap.shape)
        if gap[k, m] <= best[0]:
            best = (float(gap[k, m]), float(a[k]), float(b[m]))
        step_a, step_b = a[1] - a[0], b[1] - b[0]
        boxes = [
            (max(lo, a[k] - 2 * step_a), min(hi, a[k] + 2 * step_a)),
            (max(lo, b[m] - 2 * step_b), min(hi, b[m] + 2 * step_b)),
        ]
    x, y = sorted(best[1:])
    return math.sqrt(best[0]), (x, y)
