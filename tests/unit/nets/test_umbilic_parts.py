"""A hull-like bicubic patch with a flat region (issue 44): its umbilic part found as a part,
not as points, and a net on it refused in one line naming the face (tracing round such a part
is not made yet), where the same patch with its bottom bent builds.

The patch: cubic both ways, clamped knots (0, 1/3, 2/3, 1), its first four rows of poles in
the plane z = 0 (a flat bottom): on the knot span v in [0, 1/3], which only those rows
shape, the surface is that plane exactly (k1 = k2 = 0), and nowhere else (the fifth row
rises)."""

from __future__ import annotations

import numpy as np
import pytest

from tubecad.core.errors import ParameterError

SECTIONS = {
    "flat": [(0, 0), (300, 0), (600, 0), (900, 0), (1300, 250), (1500, 900)],
    "bent": [(0, 0), (300, 10), (600, 40), (900, 90), (1300, 300), (1500, 900)],
}


def _face(kind: str):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    from tubecad.occ_compat import Array1OfInteger, Array1OfReal, Array2OfPnt

    poles = Array2OfPnt(1, 6, 1, 6)
    for i, x in enumerate((0.0, 800.0, 1600.0, 2400.0, 3200.0, 4000.0)):
        for j, (y, z) in enumerate(SECTIONS[kind]):
            poles.SetValue(i + 1, j + 1, gp_Pnt(x, y * (1 - 0.1 * (i / 5) ** 2), z))

    def knots():
        values, mults = Array1OfReal(1, 4), Array1OfInteger(1, 4)
        for n, (value, mult) in enumerate(zip((0.0, 1 / 3, 2 / 3, 1.0), (4, 1, 1, 4)), 1):
            values.SetValue(n, value)
            mults.SetValue(n, mult)
        return values, mults

    (uk, um), (vk, vm) = knots(), knots()
    return BRepBuilderAPI_MakeFace(Geom_BSplineSurface(poles, uk, vk, um, vm, 3, 3), 1e-7).Face()


def test_the_flat_bottom_is_found_as_one_umbilic_part_in_its_plane():
    from tubecad.nets import HostSurface, find_umbilics

    host = HostSurface.of_face(_face("flat"))
    umbilics = find_umbilics(host)
    assert not umbilics.region and umbilics.points == [] and len(umbilics.parts) == 1
    (part,) = umbilics.parts
    assert np.abs(part[:, 2]).max() < 1e-9  # every node of the part on the plane z = 0
    # the whole span v <= 1/3 is flat: the part holds all the search grid's nodes there
    flat_share = len(part) / 98**2  # the grid's nodes (96 cells, the box's ends included)
    assert flat_share == pytest.approx(1 / 3, abs=0.02)


def test_a_net_on_it_is_refused_naming_the_face_and_the_bent_one_builds():
    from tubecad.nets import curvature_net

    with pytest.raises(ParameterError, match="a part of it is umbilic") as refused:
        curvature_net(_face("flat"), 3, 3)
    assert refused.value.key == "face" and "\n" not in str(refused.value)
    net = curvature_net(_face("bent"), 3, 3)
    assert net.umbilics.parts == () and net.angle < 1e-8  # measured 8.4e-9 with 5 + 5 lines
