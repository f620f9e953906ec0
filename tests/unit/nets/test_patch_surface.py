"""A refitted cell read as S(u, s) (tubecad.nets.patch_surface): its values and first and
second derivatives, on a grid of points and at scattered ones, are OCCT's own ``D2`` of the
same B-spline surface."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture(scope="module")
def surface():
    from OCP.Geom import Geom_BSplineSurface

    from tubecad.fitting.occ_arrays import integers, points_2d, reals

    rng = np.random.default_rng(7)
    u_knots, v_knots = [0.0, 40.0, 55.0, 100.0], [0.0, 30.0, 80.0]
    poles = np.empty((8, 7, 3))  # degree 5: poles = the knots' multiplicities less 6
    for i in range(poles.shape[0]):
        for j in range(poles.shape[1]):
            poles[i, j] = (100 * i / 7, 80 * j / 6, 0.0)
    poles[..., 2] = rng.normal(0.0, 5.0, poles.shape[:2])
    return Geom_BSplineSurface(
        points_2d(poles), reals(u_knots), reals(v_knots), integers([6, 1, 1, 6]), integers([6, 1, 6]), 5, 5
    )


def _occ(surface, u: float, s: float) -> np.ndarray:
    from OCP.gp import gp_Pnt, gp_Vec

    p, du, dv, duu, dvv, duv = gp_Pnt(), gp_Vec(), gp_Vec(), gp_Vec(), gp_Vec(), gp_Vec()
    surface.D2(u, s, p, du, dv, duu, dvv, duv)
    return np.array([p.Coord(), du.Coord(), dv.Coord(), duu.Coord(), duv.Coord(), dvv.Coord()])


@pytest.mark.parametrize("layout", ["grid", "scattered"])
def test_the_derivatives_are_occts(surface, layout):
    from tubecad.nets.patch_surface import PatchSurface

    patch = PatchSurface(surface)
    assert patch.u_range == (0.0, 100.0) and patch.span == (0.0, 80.0)
    assert patch.u_breaks().tolist() == [40.0, 55.0] and patch.s_breaks().tolist() == [30.0]
    rng = np.random.default_rng(3)
    if layout == "grid":
        u, s = np.linspace(0.0, 100.0, 13)[:, None], np.array([0.0, 12.5, 30.0, 61.0, 80.0])
    else:
        u, s = rng.uniform(0.0, 100.0, 40), rng.uniform(0.0, 80.0, 40)
    d = patch.derivatives(u, s)
    uu, ss = np.broadcast_arrays(u, s)
    mine = np.stack([d.S, d.S_u, d.S_s, d.S_uu, d.S_us, d.S_ss], axis=-2)
    for index in np.ndindex(uu.shape):
        occ = _occ(surface, float(uu[index]), float(ss[index]))
        scale = np.abs(occ).max(axis=1, keepdims=True)
        assert np.abs(mine[index] - occ).max() <= 1e-12 * scale.max()
