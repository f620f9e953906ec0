"""tubecad.fitting.nurbs: an OCCT B-spline surface evaluated from its own arrays on a grid,
against OCCT's evaluator (Geom_Surface.D1) and against closed forms (a torus, exactly)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from OCP.Geom import Geom_BSplineSurface, Geom_ToroidalSurface
from OCP.GeomConvert import GeomConvert
from OCP.gp import gp_Ax3, gp_Pnt, gp_Vec

from tubecad.fitting.nurbs import SurfaceArrays

R, r = 50.0, 12.0


def torus() -> Geom_BSplineSurface:
    """The torus (R, r) as OCCT converts it: rational, periodic in both directions."""
    convert = getattr(GeomConvert, "SurfaceToBSplineSurface_s", None) or GeomConvert.SurfaceToBSplineSurface
    return convert(Geom_ToroidalSurface(gp_Ax3(), R, r))


def occ_d1(surface, us, vs):
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    out = np.empty((3, len(us), len(vs), 3))
    for i, u in enumerate(us):
        for j, v in enumerate(vs):
            surface.D1(u, v, p, du, dv)
            out[:, i, j] = p.Coord(), du.Coord(), dv.Coord()
    return out


def test_a_rational_periodic_torus_is_the_torus_and_agrees_with_occt():
    surface = torus()
    assert surface.IsURational() and surface.IsUPeriodic() and surface.IsVPeriodic()
    u0, u1, v0, v1 = surface.Bounds()
    rng = np.random.default_rng(7)
    us, vs = np.sort(rng.uniform(u0, u1, 23)), np.sort(rng.uniform(v0, v1, 29))
    us[0], vs[-1] = u0, v1  # the ends of the domain too
    s, s_u, s_v = SurfaceArrays.from_occ(surface).grid_d1(us, vs)
    # on the torus: distance r from the core circle (the B-spline parameters are not the angles)
    core = np.hypot(s[..., 0], s[..., 1]) - R
    assert np.abs(np.hypot(core, s[..., 2]) - r).max() < 1e-12 * R
    # u runs along the parallels: S_u horizontal and normal to the radius (x, y, 0)
    assert np.abs(s_u[..., 2]).max() < 1e-12 * np.abs(s_u).max()
    assert np.abs(np.einsum("ijk,ijk->ij", s_u[..., :2], s[..., :2])).max() < 1e-12 * R * np.abs(s_u).max()
    occ = occ_d1(surface, us, vs)
    for ours, theirs in zip((s, s_u, s_v), occ):
        assert np.abs(ours - theirs).max() < 1e-12 * R


def test_a_non_rational_surface_with_inner_knots_agrees_with_occt():
    """A degree (3, 2) polynomial patch with repeated inner knots (C0 and C1 joints)."""
    from tubecad.fitting.occ_arrays import integers, points_2d, reals

    rng = np.random.default_rng(3)
    nu, nv = 7, 5  # u: knots 0 1 2 3 (mult 4 1 2 4: 11 = 7 + 3 + 1), v: 0 1.5 4 (mult 3 2 3: 8 = 5 + 2 + 1)
    poles = rng.normal(size=(nu, nv, 3)) * 10.0
    surface = Geom_BSplineSurface(
        points_2d(poles),
        reals([0.0, 1.0, 2.0, 3.0]),
        reals([0.0, 1.5, 4.0]),
        integers([4, 1, 2, 4]),
        integers([3, 2, 3]),
        3,
        2,
    )
    us, vs = np.linspace(0.0, 3.0, 31), np.linspace(0.0, 4.0, 17)
    ours = SurfaceArrays.from_occ(surface).grid_d1(us, vs)
    occ = occ_d1(surface, us, vs)
    for a, b in zip(ours, occ):
        assert np.abs(a - b).max() < 1e-12 * np.abs(b).max()
    # the corners are the corner poles (clamped knots)
    assert np.allclose(ours[0][[0, -1]][:, [0, -1]], poles[[0, -1]][:, [0, -1]], rtol=0, atol=1e-12)


@pytest.mark.parametrize("angle", [math.pi / 2, math.pi])
def test_a_trimmed_arc_direction_keeps_its_exact_circle(angle):
    """A torus piece converted over [0, angle] in u: rational, not periodic; every point at
    distance r from the core circle."""
    from OCP.Geom import Geom_RectangularTrimmedSurface

    convert = getattr(GeomConvert, "SurfaceToBSplineSurface_s", None) or GeomConvert.SurfaceToBSplineSurface
    piece = convert(Geom_RectangularTrimmedSurface(Geom_ToroidalSurface(gp_Ax3(), R, r), 0.0, angle, 0.0, 2 * math.pi))
    u0, u1, v0, v1 = piece.Bounds()
    s, _, _ = SurfaceArrays.from_occ(piece).grid_d1(np.linspace(u0, u1, 41), np.linspace(v0, v1, 43))
    core = np.hypot(s[..., 0], s[..., 1]) - R
    assert np.abs(np.hypot(core, s[..., 2]) - r).max() < 1e-12 * R
