"""Measure an OCCT tube surface against the exact tube by dense sampling.

The OCCT surface itself is evaluated (its poles, weights and knots, on the whole grid at once:
:class:`tubecad.fitting.nurbs.SurfaceArrays`), never the fitter's residual:
- deviation: max |S_occ(u, s) - S_exact(theta(u), s)| (parameter-matched, so an upper
  bound of the distance to the exact tube);
- orthogonality: max |cos| of the angle between dS/du and dS/ds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tubecad.fitting.exact_section import TubeSurface
from tubecad.fitting.nurbs import SurfaceArrays, span_grid


@dataclass(frozen=True)
class SurfaceMeasure:
    max_deviation: float
    max_orthogonality_error: float
    samples: int


#: samples per knot span, both ways, on top of the off-knot grid: the knots and the surface's
#: bounds are sampled too, where the isolines' |cos| peaks (a face's ring and stringer edges)
PER_SPAN = 6


def measure_surface(ts: TubeSurface, nu: int = 48, ns: int = 1500) -> SurfaceMeasure:
    """Sample ``nu`` x ``ns`` points off the knots over the whole surface, and every knot span
    (:func:`~tubecad.fitting.nurbs.span_grid`: knots and bounds included) ``PER_SPAN`` ways."""
    surf = ts.surface
    u0, u1, s0, s1 = surf.Bounds()
    arrays = SurfaceArrays.from_occ(surf)
    us = u0 + (np.arange(nu) + 0.37) * (u1 - u0) / nu
    ss = np.linspace(s0, s1, ns)
    ss[1:-1] += 0.29 * (ss[1] - ss[0])  # off the sample lattice of the fit, inside the span
    us = np.union1d(us, span_grid(arrays.u_knots, u0, u1, PER_SPAN))
    ss = np.union1d(ss, span_grid(arrays.v_knots, s0, s1, PER_SPAN))
    pts, du, ds = arrays.grid_d1(us, ss)
    exact = ts.tube.points(ts.theta_at(us)[:, None], ts.s_at(ss)[None, :])
    deviation = np.linalg.norm(pts - exact, axis=-1).max()
    cos = np.abs(np.einsum("ijk,ijk->ij", du, ds)) / np.linalg.norm(du, axis=-1) / np.linalg.norm(ds, axis=-1)
    return SurfaceMeasure(float(deviation), float(cos.max()), len(us) * len(ss))
