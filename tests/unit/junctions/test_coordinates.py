"""Where points lie on a surface (tubecad.junctions.coordinates) against closed forms."""

from __future__ import annotations

import math

import numpy as np

from tubecad.curves.parametric import ParametricAxis
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.surface.canal import tube_or_canal


def test_points_in_the_closing_ring_plane_of_a_torus():
    """On a torus (a tube about the circle x^2 + y^2 = R^2) the closing ring's plane y = 0
    also holds the opposite ring: points on the closing ring must get s = 0 (or L) and their
    own angle, not the opposite ring's. The closing ring's h is round-off there, so the
    bracket at the table's ends could miss it (a crotch blend's seam node once got the
    opposite ring's normal, and CalculiX a negative Jacobian)."""
    R, r = 40.0, 7.75
    axis = ParametricAxis(
        lambda t: np.stack([R * np.cos(t), R * np.sin(t), 0.0 * t], axis=-1), (0.0, 2 * math.pi), closed=True
    )
    torus = tube_or_canal(axis, r)
    L = axis.length
    phi = np.linspace(0.0, 2 * math.pi, 25)[:-1]
    for y in (0.0, 1e-15, -1e-15):  # on the plane and round-off either side of it
        points = np.column_stack([R + r * np.cos(phi), np.full_like(phi, y), r * np.sin(phi)])
        at = surface_coordinates(torus, points)
        ring = np.minimum(np.abs(at.s), np.abs(L - at.s))
        assert ring.max() < 1e-9 * R
        assert np.abs(at.gap).max() < 1e-12 * R
        normal = torus.normal(at.u, at.s)
        exact = np.column_stack([np.cos(phi), 0 * phi, np.sin(phi)])  # away from the circle
        assert np.abs(normal - exact).max() < 1e-12
