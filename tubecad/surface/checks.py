"""Measured checks of a tube against the exact facts of MATH.md sections 3-4.

These do not trust any formula of the tube: they measure the net's orthogonality and
conjugacy from the derivative vectors, integrate the area numerically, and find each
point's closest axis point by Newton's method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .tube import CurvatureLineTube


@dataclass(frozen=True)
class NetErrors:
    """Largest |F|/sqrt(EG) and conjugacy error (see FundamentalForms) on a u x s grid."""

    max_orthogonality_error: float
    max_M_error: float
    nu: int
    ns: int


def net_errors(tube: CurvatureLineTube, nu: int = 256, ns: int = 2001, chunk: int = 256) -> NetErrors:
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


def axis_distance_errors(tube: CurvatureLineTube, u: np.ndarray, s: np.ndarray, iters: int = 8) -> tuple[float, float]:
    """For points S(u, s): max |distance to the closest axis point - rho| and
    max |s* - s|, s* the closest axis point's arc length.

    Newton on f(x) = (P - c(x)).t(x), f' = -1 + k (P - c(x)).n(x), started away from s
    (at s + rho/2) so that converging back to s is a real finding.
    """
    u, s = np.broadcast_arrays(np.asarray(u, float), np.asarray(s, float))
    p = tube.points(u, s)
    lo, hi = tube.span
    x = np.clip(s + 0.5 * tube.radius, lo, hi)
    for _ in range(iters):
        a = tube.axis.evaluate(x)
        r = p - a.position
        f = np.einsum("...i,...i", r, a.t)
        fp = -1.0 + a.k * np.einsum("...i,...i", r, a.n)
        x = np.clip(x - f / fp, lo, hi)
    dist = np.linalg.norm(p - tube.axis.position(x), axis=-1)
    return float(np.abs(dist - tube.radius).max()), float(np.abs(x - s).max())
