"""A net's cell refitted in curvature-line coordinates, read as a wall surface S(u, s): the
derivatives a panel's development takes (:func:`tubecad.shop.panel_development.develop_cell`)
of its B-spline (:mod:`tubecad.nets.patches`: u along the k1 lines, s along the k2 lines, both
the arc lengths of the cell's sides).

They are evaluated on whole arrays from the surface's own poles and knots:
S_(a,b)(u_i, s_i) = sum_jk N_j^(a)(u_i) P_jk M_k^(b)(s_i), the basis functions' values and
derivatives N^(a), M^(b) at all the points at once (scipy's ``BSpline`` with the identity as
its coefficients), the sum over j a matrix product (de Boor, *A Practical Guide to Splines*,
chapter XVII). A development evaluates a cell at some 10^5 points: OCCT's ``D2``, a point a
call, took 7 s a cell.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from OCP.Geom import Geom_BSplineSurface
from scipy.interpolate import BSpline

from tubecad.surface.forms import SurfaceDerivatives

FloatArray = np.ndarray


@dataclass(frozen=True)
class PatchSurface:
    """The B-spline ``surface`` of a refitted cell (non-rational) as S(u, s) (module docstring)."""

    surface: Geom_BSplineSurface

    @property
    def u_range(self) -> tuple[float, float]:
        """The cell's u span: 0 to the length of its side along k1."""
        u0, u1, _, _ = self.surface.Bounds()
        return float(u0), float(u1)

    @property
    def span(self) -> tuple[float, float]:
        """The cell's s span: 0 to the length of its side along k2."""
        _, _, v0, v1 = self.surface.Bounds()
        return float(v0), float(v1)

    def s_breaks(self) -> FloatArray:
        """The surface's interior knots along s (the development's Chebyshev panels start there)."""
        return np.array([self.surface.VKnot(i) for i in range(2, self.surface.NbVKnots())], dtype=float)

    def u_breaks(self) -> FloatArray:
        """The surface's interior knots along u."""
        return np.array([self.surface.UKnot(i) for i in range(2, self.surface.NbUKnots())], dtype=float)

    @cached_property
    def _bases(self) -> tuple[BSpline, BSpline, FloatArray]:
        """(the u basis and the s basis: scipy splines whose coefficients are the identity, so
        a call gives every basis function; the poles, (n_u, n_s, 3))."""
        surface = self.surface

        def basis(count: int, value, multiplicity, degree: int, poles: int) -> BSpline:
            knots = np.repeat([value(i) for i in range(1, count + 1)], [multiplicity(i) for i in range(1, count + 1)])
            return BSpline(knots, np.eye(poles), degree)

        n_u, n_v = surface.NbUPoles(), surface.NbVPoles()
        along_u = basis(surface.NbUKnots(), surface.UKnot, surface.UMultiplicity, surface.UDegree(), n_u)
        along_s = basis(surface.NbVKnots(), surface.VKnot, surface.VMultiplicity, surface.VDegree(), n_v)
        poles = np.array([[surface.Pole(i, j).Coord() for j in range(1, n_v + 1)] for i in range(1, n_u + 1)])
        return along_u, along_s, poles

    def derivatives(self, u: FloatArray, s: FloatArray) -> SurfaceDerivatives:
        """S and its first and second derivatives at (u, s), broadcast, each (..., 3). The
        bases are evaluated at the distinct u's and s's only; where the points are a grid of
        them (a development's rings: every u of a fit at every ring's s), the sums are matrix
        products over the whole grid, then read at the points."""
        uu, ss = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(s, dtype=float))
        along_u, along_s, poles = self._bases
        n_u, n_v = poles.shape[:2]
        us, at_u = np.unique(uu.ravel(), return_inverse=True)
        vs, at_s = np.unique(ss.ravel(), return_inverse=True)
        # the sum over the u poles first: (distinct u's, n_v, 3) for each order of the u derivative
        partial = [(along_u(us, nu=a) @ poles.reshape(n_u, -1)).reshape(len(us), n_v, 3) for a in range(3)]
        across = [along_s(vs, nu=b) for b in range(3)]
        shape = uu.shape + (3,)
        grid = len(us) * len(vs) <= 2 * uu.size

        def value(a: int, b: int) -> FloatArray:
            if grid:  # (distinct s's, distinct u's x 3), read at the points
                table = (across[b] @ partial[a].transpose(1, 0, 2).reshape(n_v, -1)).reshape(len(vs), len(us), 3)
                return table[at_s, at_u].reshape(shape)
            return np.einsum("nkc,nk->nc", partial[a][at_u], across[b][at_s]).reshape(shape)

        return SurfaceDerivatives(value(0, 0), value(1, 0), value(0, 1), value(2, 0), value(1, 1), value(0, 2))

    def points(self, u: FloatArray, s: FloatArray) -> FloatArray:
        """S(u, s), broadcast, (..., 3)."""
        return self.derivatives(u, s).S
