"""Where points lie on a curvature-line surface: their ring, their stringer angle and their
gap from the surface (docs/MATH.md section 13), for points found by another program (a
mesher's nodes on the junction's faces).

A point P lies in the plane of the ring at s when

    h(s) = (P - c(s)) . n(s) = 0,        c, n the ring's centre and plane normal,

solved for every point at once by bracketing (the sign change of h on a table of s nearest
to P, then regula falsi with the Illinois modification, Dowell & Jarratt, BIT 11 (1971)
168-174, which converges superlinearly and never leaves its bracket). Round that ring P
has the angle chi = atan2((P - c) . r2, (P - c) . r1) from the axis' r1, the stringer
u = Mb(s)^-1 chi (the identity on a tube), and the gap |P - c| - r (> 0 outside).
A point in no ring's plane (beyond the ends) gets the nearer end's ring, clamped; on a closed
axis a point in the closing ring's plane (h changes sign between the table's last ring and
its first, one ring to round-off) gets s = s_0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tubecad.surface.protocol import CurvatureLineSurface

FloatArray = np.ndarray

#: rings in the table that brackets each point's ring
TABLE = 1025
#: the table's rings nearest to a point whose intervals are searched first
NEAREST = 6
#: points searched over the whole table at once (bounds the memory: BLOCK x TABLE x 3)
BLOCK = 256
#: |h| below this times the span's size is a root (h is a length; round-off is ~1e-16 of it)
ROOT = 1e-15
#: regula falsi steps (each at least halves the bracket's worse side with Illinois' rule)
STEPS = 60


@dataclass(frozen=True)
class SurfaceCoordinates:
    """Per point: the stringer angle ``u`` (radians), the ring ``s`` and the ``gap``
    |P - c(s)| - r(s), P's distance from the surface along the ring's radius."""

    u: FloatArray
    s: FloatArray
    gap: FloatArray


def surface_coordinates(surface: CurvatureLineSurface, points: FloatArray) -> SurfaceCoordinates:
    """(u, s, gap) of ``points`` (n, 3) on ``surface`` (module docstring)."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    s0, s1 = surface.span
    table = np.unique(np.concatenate([np.linspace(s0, s1, TABLE), surface.s_breaks()]))

    def h(s: FloatArray, p: FloatArray) -> FloatArray:
        centre, _, normal = surface.circle(s)
        return np.einsum("...k,...k->...", p - centre, normal)

    centres, _, normals = surface.circle(table)
    lo, hi, f_lo, f_hi, bracketed = _brackets(table, centres, normals, points)
    size = max(abs(s0), abs(s1), s1 - s0)
    at_root = _at_closing(surface.axis.closed, centres, normals, points, surface.circle(lo)[0], bracketed)
    bracketed |= at_root
    root = np.where(at_root, s0, lo)
    moved = np.zeros(len(points), dtype=int)  # +1: lo moved last step, -1: hi did
    for _ in range(STEPS):
        active = np.flatnonzero(bracketed & ~at_root & (hi - lo > 4 * np.finfo(float).eps * size))
        if not active.size:
            break
        a_lo, a_hi, fa_lo, fa_hi = lo[active], hi[active], f_lo[active], f_hi[active]
        denom = np.where(fa_hi != fa_lo, fa_lo - fa_hi, 1.0)
        mid = np.clip(a_lo + fa_lo * (a_hi - a_lo) / denom, a_lo, a_hi)
        f_mid = h(mid, points[active])
        done = np.abs(f_mid) <= ROOT * size
        at_root[active[done]], root[active[done]] = True, mid[done]
        left = np.signbit(f_mid) == np.signbit(fa_lo)  # the root is in [mid, hi]: lo moves
        last = moved[active]
        # Illinois: an end kept twice running has its value halved, so that it moves too
        f_hi[active] = np.where(left & (last == 1), 0.5 * fa_hi, np.where(left, fa_hi, f_mid))
        f_lo[active] = np.where(~left & (last == -1), 0.5 * fa_lo, np.where(left, f_mid, fa_lo))
        lo[active], hi[active] = np.where(left, mid, a_lo), np.where(left, a_hi, mid)
        moved[active] = np.where(left, 1, -1)
    s = np.where(at_root, root, np.where(np.abs(f_lo) <= np.abs(f_hi), lo, hi))
    if not bracketed.all():  # beyond an end: the nearer end's ring
        ends = np.array([s0, s1])
        nearest = ends[np.argmin(np.linalg.norm(points[:, None, :] - surface.circle(ends)[0][None], axis=-1), axis=1)]
        s = np.where(bracketed, s, nearest)
    centre, radius, _ = surface.circle(s)
    _, r1, r2 = surface.axis.rotation_minimising_frame(s)
    e = points - centre
    chi = np.arctan2(np.einsum("pk,pk->p", e, r2), np.einsum("pk,pk->p", e, r1))
    half = np.stack([np.sin(chi / 2), np.cos(chi / 2)], axis=-1)
    back = np.linalg.solve(surface.moebius_matrix(s), half[..., None])[..., 0]
    u = 2.0 * np.arctan2(back[..., 0], back[..., 1])
    return SurfaceCoordinates(u, s, np.linalg.norm(e, axis=-1) - radius)


def _at_closing(
    closed: bool, centre: FloatArray, normal: FloatArray, points: FloatArray, found: FloatArray, bracketed: FloatArray
) -> FloatArray:
    """Which points lie in the closing ring's plane of a ``closed`` axis (table rings
    ``centre``, ``normal``): h changes sign between the table's last ring and its first (one
    ring, to the axis' round-off, so no table interval brackets a point there, and on a
    torus the opposite ring's plane, y = 0 too, would take it), and the closing ring's centre
    is nearer than that of the bracket ``found`` (centres; where ``bracketed``)."""
    if not closed:
        return np.zeros(len(points), dtype=bool)
    first = np.einsum("pk,k->p", points - centre[0], normal[0])
    last = np.einsum("pk,k->p", points - centre[-1], normal[-1])
    nearer = np.linalg.norm(points - centre[0], axis=-1) < np.linalg.norm(points - found, axis=-1)
    return (np.signbit(first) != np.signbit(last)) & (~bracketed | nearer)


def _brackets(
    table: FloatArray, centre: FloatArray, normal: FloatArray, points: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Per point the table interval [lo, hi] where h changes sign nearest to the point (the
    ring planes through a point near its foot on the axis: the table's nearest centres), with
    h at its ends and whether one was found; points beyond the table's nearest centres'
    intervals are searched over the whole table, in blocks."""
    from scipy.spatial import cKDTree

    last = len(table) - 2
    _, near = cKDTree(centre).query(points, k=min(NEAREST, len(table)))
    starts = np.clip(np.concatenate([near - 1, near], axis=1), 0, last)  # intervals [j, j + 1]
    found = _nearest_change(starts, centre, normal, points)
    missing = np.flatnonzero(found < 0)
    for a in range(0, len(missing), BLOCK):
        rows = missing[a : a + BLOCK]
        every = np.broadcast_to(np.arange(last + 1), (len(rows), last + 1))
        found[rows] = _nearest_change(every, centre, normal, points[rows])
    bracketed = found >= 0
    j = np.where(bracketed, found, 0)
    h = lambda k: np.einsum("pk,pk->p", points - centre[k], normal[k])  # noqa: E731
    return table[j], table[j + 1], h(j), h(j + 1), bracketed


def _nearest_change(starts: FloatArray, centre: FloatArray, normal: FloatArray, points: FloatArray) -> FloatArray:
    """Per point (row of ``starts``: candidate intervals [j, j + 1]) the candidate where h
    changes sign whose start is nearest to the point, -1 where none does."""
    p = points[:, None, :]
    h0 = np.einsum("pck,pck->pc", p - centre[starts], normal[starts])
    h1 = np.einsum("pck,pck->pc", p - centre[starts + 1], normal[starts + 1])
    distance = np.linalg.norm(p - centre[starts], axis=-1)
    score = np.where(np.signbit(h0) != np.signbit(h1), distance, np.inf)
    best = np.argmin(score, axis=1)
    rows = np.arange(len(points))
    return np.where(np.isfinite(score[rows, best]), starts[rows, best], -1)
