"""The principal curvatures and directions of a host surface at any points, from its exact
first and second derivatives (issue 44; docs/MATH.md section 15).

With the first fundamental form I = [[E, F], [F, G]] (E = X_u.X_u, F = X_u.X_v, G = X_v.X_v)
and the second II = [[L, M], [M, N]] (L = X_uu.n, M = X_uv.n, N = X_vv.n, n the unit normal
X_u x X_v / |X_u x X_v|), the shape operator is I^-1 II. With I = R^T R (R upper triangular:
R = [[sqrt E, F / sqrt E], [0, sqrt(EG - F^2) / sqrt E]], the tangent plane's orthonormal frame
e1 = X_u / |X_u|, e2 = n x e1), S = R^-T II R^-1 is symmetric: the shape operator in that frame.
Its eigenvalues are the principal curvatures k1 >= k2, its eigenvectors w the principal
directions' components in (e1, e2), and the parameter directions (du, dv) = R^-1 w. Written in
closed form for a 2 x 2 symmetric matrix: with h = (S11 + S22) / 2 (mean curvature) and the
trace-free part (a, b) = ((S11 - S22) / 2, S12), k = h +- sqrt(a^2 + b^2) and the k1 direction
at the angle phi = atan2(b, a) / 2 from e1. The point is an umbilic where a = b = 0: the
*umbilic measure* sqrt(a^2 + b^2) = (k1 - k2) / 2 (:mod:`~tubecad.nets.umbilics`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tubecad.nets.host import HostSurface, SurfaceJet

FloatArray = np.ndarray


@dataclass(frozen=True)
class PrincipalField:
    """At each point: ``k1`` >= ``k2`` (the principal curvatures, sign by the normal ``n``),
    the trace-free shape operator ``a``, ``b`` (in the frame ``e1``, ``e2``), the 3-D unit
    principal directions ``d1`` (of k1) and ``d2``, and the parameter directions ``uv1``,
    ``uv2`` ((du, dv) per unit 3-D length along d1 and d2); ``area``: |X_u x X_v| (0 where
    the parameterisation degenerates, a sphere's pole)."""

    k1: FloatArray
    k2: FloatArray
    a: FloatArray
    b: FloatArray
    n: FloatArray
    e1: FloatArray
    e2: FloatArray
    d1: FloatArray
    d2: FloatArray
    uv1: FloatArray
    uv2: FloatArray
    area: FloatArray

    @property
    def umbilic_measure(self) -> FloatArray:
        """(k1 - k2) / 2 = sqrt(a^2 + b^2): zero at an umbilic."""
        return np.hypot(self.a, self.b)


def principal_field(host: HostSurface, u: FloatArray, v: FloatArray) -> PrincipalField:
    """The principal field of ``host`` at the points (u, v) (module docstring).

    Args:
        host: the surface.
        u: the first parameters (any shape; flattened).
        v: the second parameters.

    Returns:
        The field at each point.
    """
    return field_of(host.jet(u, v))


def field_of(jet: SurfaceJet) -> PrincipalField:
    """The principal field from a surface's jet (module docstring)."""

    def dot(p: FloatArray, q: FloatArray) -> FloatArray:
        return np.einsum("nk,nk->n", p, q)

    cross = np.cross(jet.Xu, jet.Xv)
    area = np.linalg.norm(cross, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        n = cross / area[:, None]
        E, F = dot(jet.Xu, jet.Xu), dot(jet.Xu, jet.Xv)
        L, M, N = dot(jet.Xuu, n), dot(jet.Xuv, n), dot(jet.Xvv, n)
        r11 = np.sqrt(E)
        r12 = F / r11
        r22 = area / r11  # sqrt(EG - F^2) / sqrt(E)
        # S = R^-T II R^-1 with R^-1 = [[1 / r11, -r12 / (r11 r22)], [0, 1 / r22]]
        i11, i12, i22 = 1.0 / r11, -r12 / (r11 * r22), 1.0 / r22
        s11 = L * i11 * i11
        s12 = i11 * (L * i12 + M * i22)
        s22 = i12 * (L * i12 + M * i22) + i22 * (M * i12 + N * i22)
        h, a, b = 0.5 * (s11 + s22), 0.5 * (s11 - s22), s12
        root = np.hypot(a, b)
        phi = 0.5 * np.arctan2(b, a)
        c, s = np.cos(phi), np.sin(phi)
        e1 = jet.Xu / r11[:, None]
        e2 = np.cross(n, e1)
        d1 = c[:, None] * e1 + s[:, None] * e2
        d2 = -s[:, None] * e1 + c[:, None] * e2
        # (du, dv) = R^-1 w for w = (c, s) and (-s, c): unit 3-D length
        uv1 = np.stack([i11 * c + i12 * s, i22 * s], axis=-1)
        uv2 = np.stack([-i11 * s + i12 * c, i22 * c], axis=-1)
    return PrincipalField(h + root, h - root, a, b, n, e1, e2, d1, d2, uv1, uv2, area)


class PointField:
    """The principal directions at one point at a time, in plain floats (the tracer's inner
    loop: OCCT's ``D2`` and the module's closed form, some 20 us a point where the arrays'
    :func:`principal_field` costs 0.3 ms for one)."""

    def __init__(self, host: HostSurface) -> None:
        from OCP.gp import gp_Pnt, gp_Vec

        self.d2 = host.surface.D2
        self.p, self.du, self.dv = gp_Pnt(), gp_Vec(), gp_Vec()
        self.duu, self.dvv, self.duv = gp_Vec(), gp_Vec(), gp_Vec()

    def at(
        self, u: float, v: float, family: int
    ) -> tuple[float, float, float, float, float, float, float, float, float] | None:
        """(du, dv, d_x, d_y, d_z, |X_u|, |X_v|, (k1 - k2) / 2, max(|k1|, |k2|)) of
        ``family``'s direction at (u, v): its parameter direction of unit 3-D length, its 3-D
        unit vector, the derivatives' lengths, the umbilic measure and the larger principal
        curvature's size; None where the parameterisation degenerates."""
        self.d2(u, v, self.p, self.du, self.dv, self.duu, self.dvv, self.duv)
        xu = (self.du.X(), self.du.Y(), self.du.Z())
        xv = (self.dv.X(), self.dv.Y(), self.dv.Z())
        nx = xu[1] * xv[2] - xu[2] * xv[1]
        ny = xu[2] * xv[0] - xu[0] * xv[2]
        nz = xu[0] * xv[1] - xu[1] * xv[0]
        area = math.sqrt(nx * nx + ny * ny + nz * nz)
        E = xu[0] * xu[0] + xu[1] * xu[1] + xu[2] * xu[2]
        if not (area > 0.0 and E > 0.0):
            return None
        nx, ny, nz = nx / area, ny / area, nz / area
        F = xu[0] * xv[0] + xu[1] * xv[1] + xu[2] * xv[2]
        G = xv[0] * xv[0] + xv[1] * xv[1] + xv[2] * xv[2]
        L = self.duu.X() * nx + self.duu.Y() * ny + self.duu.Z() * nz
        M = self.duv.X() * nx + self.duv.Y() * ny + self.duv.Z() * nz
        N = self.dvv.X() * nx + self.dvv.Y() * ny + self.dvv.Z() * nz
        r11 = math.sqrt(E)
        r12, r22 = F / r11, area / r11
        i11, i12, i22 = 1.0 / r11, -r12 / (r11 * r22), 1.0 / r22
        s11 = L * i11 * i11
        s12 = i11 * (L * i12 + M * i22)
        s22 = i12 * (L * i12 + M * i22) + i22 * (M * i12 + N * i22)
        a, b = 0.5 * (s11 - s22), s12
        phi = 0.5 * math.atan2(b, a)
        c, s = math.cos(phi), math.sin(phi)
        if family == 2:
            c, s = -s, c
        e1 = (xu[0] / r11, xu[1] / r11, xu[2] / r11)
        e2 = (ny * e1[2] - nz * e1[1], nz * e1[0] - nx * e1[2], nx * e1[1] - ny * e1[0])
        return (
            i11 * c + i12 * s,
            i22 * s,
            c * e1[0] + s * e2[0],
            c * e1[1] + s * e2[1],
            c * e1[2] + s * e2[2],
            r11,
            math.sqrt(G),
            math.hypot(a, b),
            abs(0.5 * (s11 + s22)) + math.hypot(a, b),
        )
