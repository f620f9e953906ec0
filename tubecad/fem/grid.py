"""Where the mesh's nodes lie in the curvature-line coordinates (angle, s): the layout's
rings and stringers, refined between them to the ``[mesh]`` sizes.

Element edges along s are measured on the surface, L = max over the angles of
Int sqrt(G) ds between two rings (Gauss-Legendre, 8 points per bay, 36 angles); edges
round the rings as max |S_u| times the angle between two stringers. Quadratic elements
add the parameter midpoints (mid-side nodes), so every node is a point of the exact
surface. On a closed axis the closing ring is the first ring: its nodes are those of ring 0
carried by the closing map (the holonomy angle on a tube, a Moebius map on a canal surface).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tubecad.core.errors import ParameterError

#: quadratures of the edge lengths
_GAUSS = 8
_ANGLE_SAMPLES = 36
#: the widest angle one element may span round a ring (8 elements round a tube at least)
MAX_ELEMENT_ANGLE = math.pi / 4
#: how closely the closing map must carry the mesh's angles onto each other (radians)
CLOSING_MATCH = 1e-9


@dataclass(frozen=True)
class ParameterGrid:
    """Lattice of node parameters: ``s`` (rows) and ``angles`` (columns, radians,
    increasing from the first stringer, period 2 pi); ``order`` 1 or 2 (every second row
    and column then a mid-side station). ``ring_rows[i]``: the row of layout ring i;
    ``stringer_columns[j]``: the column of layout stringer j. ``closing[c]``: on a closed
    axis, the column at s0 that column c reaches at the span's end (None when open)."""

    s: np.ndarray
    angles: np.ndarray
    order: int
    ring_rows: tuple[int, ...]
    stringer_columns: tuple[int, ...]
    closing: np.ndarray | None

    @property
    def shell_count(self) -> int:
        return ((len(self.s) - 1) // self.order) * (len(self.angles) // self.order)


def bay_lengths(surface, s_rings: np.ndarray) -> np.ndarray:
    """Per bay between consecutive rings: the longest stringer length over it (module docstring)."""
    x, w = np.polynomial.legendre.leggauss(_GAUSS)
    a, b = s_rings[:-1], s_rings[1:]
    s = (0.5 * (a + b)[:, None] + 0.5 * (b - a)[:, None] * x).ravel()
    u = np.linspace(0.0, 2 * math.pi, _ANGLE_SAMPLES, endpoint=False)
    speed = np.linalg.norm(surface.derivatives(u[:, None], s[None, :]).S_s, axis=-1)
    per_bay = (speed.reshape(len(u), len(a), _GAUSS) * w).sum(axis=-1) * 0.5 * (b - a)
    return per_bay.max(axis=0)


def gap_lengths(surface, angles: np.ndarray, s_rings: np.ndarray) -> np.ndarray:
    """Per gap between consecutive stringers (cyclic): the longest ring arc over it."""
    gaps = np.diff(np.concatenate([angles, [angles[0] + 2 * math.pi]]))
    s = np.linspace(s_rings[0], s_rings[-1], 65)
    u = (angles[:, None] + gaps[:, None] * np.linspace(0.0, 1.0, 5)).ravel()
    speed = np.linalg.norm(surface.derivatives(u[:, None], s[None, :]).S_u, axis=-1).max(axis=1)
    return speed.reshape(len(angles), 5).max(axis=1) * gaps


def _refined(stations: np.ndarray, counts: np.ndarray, order: int, cyclic: bool = False) -> np.ndarray:
    """``stations`` with each interval cut into ``counts`` equal parts, times ``order``."""
    ends = np.concatenate([stations, [stations[0] + 2 * math.pi]]) if cyclic else stations
    parts = [np.linspace(a, b, order * n, endpoint=False) for a, b, n in zip(ends[:-1], ends[1:], counts)]
    out = np.concatenate(parts)
    return out if cyclic else np.concatenate([out, ends[-1:]])


def _counts(surface, s_rings, stringers_deg, size_along: float, size_around: float):
    s_rings = np.asarray(s_rings, dtype=float)
    angles = np.sort(np.radians(np.asarray(stringers_deg, dtype=float)) % (2 * math.pi))
    along = np.maximum(1, np.ceil(bay_lengths(surface, s_rings) / size_along - 1e-9)).astype(int)
    gaps = np.diff(np.concatenate([angles, [angles[0] + 2 * math.pi]]))
    around = np.maximum(
        np.ceil(gap_lengths(surface, angles, s_rings) / size_around - 1e-9), np.ceil(gaps / MAX_ELEMENT_ANGLE - 1e-9)
    ).astype(int)
    return s_rings, angles, along, around


def element_counts(surface, s_rings, stringers_deg, size_along: float, size_around: float) -> tuple[int, int]:
    """(elements along s, elements round the rings) that :func:`parameter_grid` will make:
    cheap (no node is made), so that an element cap is checked first."""
    _, _, along, around = _counts(surface, s_rings, stringers_deg, size_along, size_around)
    return int(along.sum()), int(around.sum())


def parameter_grid(
    surface, s_rings, stringers_deg, order: int, size_along: float, size_around: float, closing=None
) -> ParameterGrid:
    """The node lattice of ``surface`` (a CurvatureLineTube or CanalSurface) for the layout's
    rings ``s_rings`` and stringers ``stringers_deg``. ``closing(angles)``: on a closed axis,
    where the stringers at these angles reach the closing ring (in s0's angles)."""
    s_rings, angles, along, around = _counts(surface, s_rings, stringers_deg, size_along, size_around)
    s = _refined(s_rings, along, order)
    cols = _refined(angles, around, order, cyclic=True)
    ring_rows = tuple(int(r) for r in order * np.concatenate([[0], np.cumsum(along)]))
    first = np.concatenate([[0], np.cumsum(around)[:-1]]) * order
    stringer_columns = tuple(
        int(first[np.searchsorted(angles, a)])
        for a in np.radians(np.asarray(stringers_deg, dtype=float)) % (2 * math.pi)
    )
    closing_cols = None
    if closing is not None:
        reached = np.asarray(closing(cols), dtype=float)
        diff = (reached[:, None] - cols[None, :] + math.pi) % (2 * math.pi) - math.pi
        closing_cols = np.argmin(np.abs(diff), axis=1)
        miss = np.abs(diff[np.arange(len(cols)), closing_cols]).max()
        if miss > CLOSING_MATCH or len(set(closing_cols.tolist())) != len(cols):
            shift = math.degrees(float(((reached[0] - cols[0] + math.pi) % (2 * math.pi)) - math.pi))
            raise ParameterError(
                f"the closed axis' stringers come back to the closing ring turned by {shift:.6g} deg "
                "(its holonomy), which does not carry the mesh's angles onto each other, so its "
                "elements cannot close up; give the stringers equal spacing that divides the holonomy, "
                "or mesh an open span"
            )
    return ParameterGrid(s, cols, order, ring_rows, stringer_columns, closing_cols)


def lattice_ids(grid: ParameterGrid) -> np.ndarray:
    """(rows, columns) array of node numbers, -1 where no node is (the centre of a quadratic
    element); on a closed axis the last row holds ring 0's nodes carried by the closing map."""
    rows, cols, p = len(grid.s), len(grid.angles), grid.order
    keep = np.ones((rows, cols), dtype=bool)
    if p == 2:
        keep[1::2, 1::2] = False
    if grid.closing is not None:
        keep[-1] = False
    ids = np.full((rows, cols), -1, dtype=np.int64)
    ids[keep] = np.arange(int(keep.sum()))
    if grid.closing is not None:
        ids[-1] = ids[0][grid.closing]
    return ids
