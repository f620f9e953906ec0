"""numpy -> OCCT array conversions (OCCT arrays are 1-based)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from OCP.gp import gp_Pnt

from tubecad.occ_compat import Array1OfInteger, Array1OfReal, Array2OfPnt, Array2OfReal


def reals(values: Sequence[float] | np.ndarray) -> Array1OfReal:
    out = Array1OfReal(1, len(values))
    for i, v in enumerate(np.asarray(values, dtype=float).tolist()):  # Python floats: no numpy scalar per item
        out.SetValue(i + 1, v)
    return out


def integers(values: Sequence[int] | np.ndarray) -> Array1OfInteger:
    out = Array1OfInteger(1, len(values))
    for i, v in enumerate(np.asarray(values).tolist()):
        out.SetValue(i + 1, int(v))
    return out


def points_2d(points: np.ndarray) -> Array2OfPnt:
    """(n, m, 3) -> Array2OfPnt(1..n, 1..m)."""
    n, m, _ = points.shape
    out = Array2OfPnt(1, n, 1, m)
    for i, row in enumerate(np.asarray(points, dtype=float).tolist(), start=1):
        for j, (x, y, z) in enumerate(row, start=1):
            out.SetValue(i, j, gp_Pnt(x, y, z))
    return out


def reals_2d(values: np.ndarray) -> Array2OfReal:
    n, m = values.shape
    out = Array2OfReal(1, n, 1, m)
    for i, row in enumerate(np.asarray(values, dtype=float).tolist(), start=1):
        for j, v in enumerate(row, start=1):
            out.SetValue(i, j, v)
    return out


def knots_and_multiplicities(full_knots: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A full (repeated) knot vector -> distinct knots and their multiplicities.

    Knots within a few units of round-off of each other (relative to the vector's
    magnitude) are one knot, kept at its first value exactly: rounding to a fixed number
    of decimals would move the end knots of a span far from 0 (s ~ 1e7) off the span.
    """
    t = np.asarray(full_knots, dtype=float)
    close = 8 * np.finfo(float).eps * max(1.0, float(np.abs(t).max()))
    new = np.concatenate([[True], np.diff(t) > close])
    starts = np.flatnonzero(new)
    return t[starts], np.diff(np.append(starts, len(t)))
