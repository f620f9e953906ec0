"""First and second fundamental forms of a parametric surface, from its derivatives.

Nothing here assumes the tube: E, F, G, L, M, N are dot products of the derivative
vectors and of the unit normal S_u x S_s / |S_u x S_s|, so a wrong parameterisation shows
up as F != 0 or M != 0 (docs/MATH.md section 3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

FloatArray = np.ndarray


@dataclass(frozen=True)
class SurfaceDerivatives:
    """S and its first and second partial derivatives in (u, s), each of shape (..., 3)."""

    S: FloatArray
    S_u: FloatArray
    S_s: FloatArray
    S_uu: FloatArray
    S_us: FloatArray
    S_ss: FloatArray

    @property
    def normal(self) -> FloatArray:
        """Unit normal S_u x S_s / |S_u x S_s| (outward for the tube)."""
        cross = np.cross(self.S_u, self.S_s)
        return cross / np.linalg.norm(cross, axis=-1, keepdims=True)


@dataclass(frozen=True)
class FundamentalForms:
    """Coefficients of I = E du^2 + 2F du ds + G ds^2 and II = L du^2 + 2M du ds + N ds^2."""

    E: FloatArray
    F: FloatArray
    G: FloatArray
    L: FloatArray
    M: FloatArray
    N: FloatArray

    @classmethod
    def from_derivatives(cls, d: SurfaceDerivatives) -> FundamentalForms:
        nrm = d.normal

        def dot(a: FloatArray, b: FloatArray) -> FloatArray:
            return np.einsum("...i,...i->...", a, b)

        return cls(
            dot(d.S_u, d.S_u),
            dot(d.S_u, d.S_s),
            dot(d.S_s, d.S_s),
            dot(d.S_uu, nrm),
            dot(d.S_us, nrm),
            dot(d.S_ss, nrm),
        )

    @property
    def orthogonality_error(self) -> FloatArray:
        """|F| / sqrt(E G): |cos| of the angle between the u- and s-isolines."""
        return np.abs(self.F) / np.sqrt(self.E * self.G)

    @property
    def conjugacy_error(self) -> FloatArray:
        """|M| / sqrt(E G), relative to the shape operator's size sqrt((L/E)^2 + (N/G)^2).

        The off-diagonal of the shape operator in the orthonormal isoline frame over its
        norm: dimensionless, and zero exactly when the isolines are conjugate. (The
        textbook |M| / sqrt(L N) is undefined where N = 0, which every tube has.)
        """
        scale = np.sqrt((self.L / self.E) ** 2 + (self.N / self.G) ** 2)
        return np.abs(self.M) / np.sqrt(self.E * self.G) / scale

    def principal_curvatures(self) -> tuple[FloatArray, FloatArray]:
        """(kappa_1, kappa_2) from the mean and Gaussian curvature, kappa_1 >= kappa_2.

        With F = M = 0 these are L/E and N/G: -1/rho along the circles and
        k cos phi / (1 - rho k cos phi) along the u-lines (outward normal).
        """
        det_i = self.E * self.G - self.F**2
        gauss = (self.L * self.N - self.M**2) / det_i
        mean = (self.E * self.N - 2 * self.F * self.M + self.G * self.L) / (2 * det_i)
        root = np.sqrt(np.maximum(mean**2 - gauss, 0.0))
        return mean + root, mean - root

    @property
    def gaussian_curvature(self) -> FloatArray:
        return (self.L * self.N - self.M**2) / (self.E * self.G - self.F**2)
