"""The triaxial ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 as an exact NURBS surface, and its
lines of curvature in closed form (issue 44): the intersections with its confocal quadrics.

Through a point of the ellipsoid pass two confocal quadrics
x^2/(A - l) + y^2/(B - l) + z^2/(C - l) = 1 (A, B, C = a^2, b^2, c^2), with l1 in (C, B) (a
hyperboloid of one sheet) and l2 in (B, A) (of two sheets): the roots of
l^2 + (x^2 + y^2 + z^2 - A - B - C) l + AB + AC + BC - x^2 (B + C) - y^2 (A + C) - z^2 (A + B) = 0
(the cubic of the three quadrics through the point divided by its root 0, the ellipsoid). By
Dupin's theorem the lines of curvature are the curves l1 = const and l2 = const; a line of
l1 = const runs along n_E x n_l1, n_l = (x / (A - l), y / (B - l), z / (C - l)). The four
umbilics: x = +-a sqrt((A - B)/(A - C)), y = 0, z = +-c sqrt((B - C)/(A - C)).

The NURBS: OCCT's unit sphere converted (GeomConvert: rational biquadratic, periodic in u,
its seam the half-plane y = 0, x > 0) with its poles scaled by (a, b, c), an exact affine
image; two umbilics (x > 0) lie on the seam."""

from __future__ import annotations

import numpy as np


def nurbs_ellipsoid(a: float, b: float, c: float):
    from OCP.Geom import Geom_SphericalSurface
    from OCP.GeomConvert import GeomConvert
    from OCP.gp import gp_Ax3, gp_Pnt

    surface = GeomConvert.SurfaceToBSplineSurface_s(Geom_SphericalSurface(gp_Ax3(), 1.0))
    for i in range(1, surface.NbUPoles() + 1):
        for j in range(1, surface.NbVPoles() + 1):
            p = surface.Pole(i, j)
            surface.SetPole(i, j, gp_Pnt(a * p.X(), b * p.Y(), c * p.Z()), surface.Weight(i, j))
    return surface


def confocal(points: np.ndarray, a: float, b: float, c: float) -> tuple[np.ndarray, np.ndarray]:
    """(l1, l2) of each point (n, 3) on the ellipsoid (module docstring)."""
    A, B, C = a * a, b * b, c * c
    x2, y2, z2 = (points**2).T
    p = x2 + y2 + z2 - A - B - C
    q = A * B + A * C + B * C - x2 * (B + C) - y2 * (A + C) - z2 * (A + B)
    root = np.sqrt(np.maximum(p * p / 4 - q, 0.0))
    return -p / 2 - root, -p / 2 + root


def curvature_directions(points: np.ndarray, a: float, b: float, c: float) -> tuple[np.ndarray, np.ndarray]:
    """The unit tangents of the lines l1 = const and l2 = const through each point."""
    A, B, C = a * a, b * b, c * c
    normal = points / np.array([A, B, C])
    out = []
    for lam in confocal(points, a, b, c):
        other = points / np.stack([A - lam, B - lam, C - lam], axis=-1)
        t = np.cross(normal, other)
        out.append(t / np.linalg.norm(t, axis=1, keepdims=True))
    return out[0], out[1]


def umbilics(a: float, b: float, c: float) -> np.ndarray:
    A, B, C = a * a, b * b, c * c
    x, z = a * np.sqrt((A - B) / (A - C)), c * np.sqrt((B - C) / (A - C))
    return np.array([[sx * x, 0.0, sz * z] for sx in (1, -1) for sz in (1, -1)])
