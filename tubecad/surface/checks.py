"""Measured checks of a tube against the exact facts of docs/MATH.md sections 3-4.

These do not trust any formula of the tube: they measure the net's orthogonality and
conjugacy from the derivative vectors, integrate the area numerically, and find each
point's closest axis point by Newton's method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tubecad.surface.protocol import CurvatureLineSurface
from tubecad.surface.tube import CurvatureLineTube


@dataclass(frozen=True)
class NetErrors:
    """Largest |F|/sqrt(EG) and conjugacy error (see FundamentalForms) on a u x s grid."""

    max_orthogonality_error: float
    max_M_error: float
    nu: int
    ns: int


def net_errors(tube: CurvatureLineSurface, nu: int = 256, ns: int = 2001, chunk: int = 256) -> NetErrors:
    """Measure the curvature-line net on ``nu`` x ``ns`` points (s in chunks to bound memory)."""
    u = np.linspace(0.0, 2.0 * math.pi, nu, endpoint=False)[:, None]
    s_all = np.linspace(*tube.span, ns)
    orth = conj = 0.0
    for start in range(0, ns, chunk):
        forms = tube.fundamental_forms(u, s_all[None, start : start + chunk])
        orth = max(orth, float(forms.orthogonality_error.max()))
        conj = max(conj, float(forms.conjugacy_error.max()))
    return NetErrors(orth, conj, nu, ns)


def area_by_quadrature(tube: CurvatureLineTube, nu: int = 64, panels: int = 64, order: int = 16) -> float:
    """Int Int |S_u x S_s| du ds: Gauss-Legendre panels in s, the periodic trapezoid rule in u
    (spectrally accurate for a periodic integrand)."""
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(*tube.span, panels + 1)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    s = (mid[:, None] + half[:, None] * x).ravel()
    ws = (half[:, None] * w).ravel()
    u = np.linspace(0.0, 2.0 * math.pi, nu, endpoint=False)
    d = tube.derivatives(u[:, None], s[None, :])
    jac = np.linalg.norm(np.cross(d.S_u, d.S_s), axis=-1)
    return float((jac * ws).sum() * (2.0 * math.pi / nu))


#: Newton's steps below this fraction of the span are round-off: the iteration stops there
CONVERGED = 1e-15


def distance_to_axis(
    axis, points: np.ndarray, s_guess: np.ndarray | None = None, iters: int = 12
) -> tuple[np.ndarray, np.ndarray]:
    """(distance, s*) from each point to its closest axis point, near ``s_guess`` or, if it is
    None, near the closest of 4001 axis samples.

    Newton on f(x) = (P - c(x)).t(x), f' = -1 + k (P - c(x)).n(x), kept inside the span;
    round a closed axis it runs on across the closing (s taken mod the length), so a point
    near the closing ring finds its closest point on either side.
    """
    p = np.asarray(points, dtype=float)
    lo, hi = axis.span

    def inside(x: np.ndarray) -> np.ndarray:
        return lo + np.mod(x - lo, hi - lo) if axis.closed else np.clip(x, lo, hi)

    if s_guess is None:
        from scipy.spatial import cKDTree

        samples = np.linspace(lo, hi, 4001)
        s_guess = samples[cKDTree(axis.position(samples)).query(p)[1]]
    flat_p = p.reshape(-1, 3)
    flat_x = (inside(np.asarray(s_guess, dtype=float)) * np.ones(p.shape[:-1])).ravel().copy()
    active = np.arange(len(flat_x))  # the points still moving: a converged one is left where it is
    for _ in range(iters):
        a = axis.at(flat_x[active])
        r = flat_p[active] - a.position
        f = np.einsum("...i,...i", r, a.t)
        fp = -1.0 + np.einsum("...i,...i", r, a.curvature_vector)
        step = f / fp
        flat_x[active] = inside(flat_x[active] - step)
        active = active[np.abs(step) > CONVERGED * (hi - lo)]
        if not len(active):
            break
    x = flat_x.reshape(p.shape[:-1])
    return np.linalg.norm(p - axis.position(x), axis=-1), x


def envelope_distance(
    surface, points: np.ndarray, s_guess: np.ndarray | None = None, iters: int = 12
) -> tuple[np.ndarray, np.ndarray]:
    """(e, s*): how far each point lies outside the canal surface ``surface`` (a CanalSurface,
    the envelope of the spheres of radius r(s) about c(s)), e = min_s |P - c(s)| - r(s), and
    the s* where the minimum is (near the surface: the sphere the point's normal comes from).

    Newton on g(s) = |P - c| - r: g' = -(P - c).t / D - r', g'' = (1 - (P - c).k) / D -
    ((P - c).t)^2 / D^3 - r'' (D = |P - c|, k the curvature vector), from the best sample of
    g (not the closest axis point: a large sphere's points may lie nearer another part of the
    axis) or ``s_guess``. The samples are at most a quarter of the smallest radius apart (at
    least 2001), so the best one lies in the minimum's basin, and no Newton step goes further
    than one sample spacing; round a closed axis s runs on across the closing (mod the
    length), on an open one it is kept inside the span.
    """
    p = np.asarray(points, dtype=float)
    axis, law = surface.axis, surface.radius_law
    lo, hi = axis.span
    coarse = np.linspace(lo, hi, 2001)
    r_min = float(np.min(law.r(coarse)))
    n = int(min(max(2001, math.ceil(4.0 * (hi - lo) / r_min) + 1), 200_001))
    spacing = (hi - lo) / (n - 1)

    def inside(x: np.ndarray) -> np.ndarray:
        return lo + np.mod(x - lo, hi - lo) if axis.closed else np.clip(x, lo, hi)

    if s_guess is None:
        samples = np.linspace(lo, hi, n)
        centres, radii = axis.position(samples), law.r(samples)
        flat = p.reshape(-1, 3)
        best = np.empty(len(flat), dtype=int)
        rows_per_block = max(1, 2_000_000 // n)  # about 50 MB of differences at a time
        for rows in np.array_split(np.arange(len(flat)), max(1, math.ceil(len(flat) / rows_per_block))):
            g = np.linalg.norm(flat[rows, None, :] - centres[None, :, :], axis=-1) - radii[None, :]
            best[rows] = np.argmin(g, axis=1)
        s_guess = samples[best].reshape(p.shape[:-1])
    flat_p = p.reshape(-1, 3)
    flat_x = (inside(np.asarray(s_guess, dtype=float)) * np.ones(p.shape[:-1])).ravel().copy()
    active = np.arange(len(flat_x))  # the points still moving
    for _ in range(iters):
        xa = flat_x[active]
        a = axis.at(xa)
        r = flat_p[active] - a.position
        d = np.linalg.norm(r, axis=-1)
        along = np.einsum("...i,...i", r, a.t)
        slope = -along / d - law.dr(xa)
        bend = (1.0 - np.einsum("...i,...i", r, a.curvature_vector)) / d - along**2 / d**3 - law.ddr(xa)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.clip(np.where(bend > 0.0, slope / bend, 0.0), -spacing, spacing)
        flat_x[active] = inside(xa - step)
        active = active[np.abs(step) > CONVERGED * (hi - lo)]
        if not len(active):
            break
    x = flat_x.reshape(p.shape[:-1])
    return np.linalg.norm(p - axis.position(x), axis=-1) - law.r(x), x


def axis_distance_errors(tube: CurvatureLineTube, u: np.ndarray, s: np.ndarray) -> tuple[float, float]:
    """For points S(u, s): max |distance to the closest axis point - rho| and max |s* - s|,
    s* the closest axis point's arc length, found from s + rho/2 (so converging back to s
    is a real finding)."""
    u, s = np.broadcast_arrays(np.asarray(u, float), np.asarray(s, float))
    dist, x = distance_to_axis(tube.axis, tube.points(u, s), s + 0.5 * tube.radius)
    return float(np.abs(dist - tube.radius).max()), float(np.abs(x - s).max())
