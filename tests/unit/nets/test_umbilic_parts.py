"""Umbilic parts (issue 44): a hull-like bicubic patch with a flat bottom and a dome of
revolution with a flat crown. Each part is found as one region, not as points, and the net's
lines stop on its border; outside it they follow OCCT's own principal directions (the hull)
and are the closed form's meridians and parallels (the dome).

The patch: cubic both ways, clamped knots (0, 1/3, 2/3, 1), its first four rows of poles in
the plane z = 0 (a flat bottom): on the knot span v in [0, 1/3], which only those rows
shape, the surface is that plane exactly (k1 = k2 = 0), and nowhere else (the fifth row
rises)."""

from __future__ import annotations

import math

import numpy as np
import pytest

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


def _occ_angle(net, surface) -> float:
    """The largest angle between a net's edges and OCCT's principal directions
    (``GeomLProp_SLProps``, not tubecad's field) at 60 points an edge."""
    from OCP.GeomLProp import GeomLProp_SLProps
    from OCP.gp import gp_Dir

    worst = 0.0
    for edge in net.edges.values():
        for t in np.linspace(edge.curve.FirstParameter(), edge.curve.LastParameter(), 62)[1:-1]:
            uv = edge.pcurve.Value(float(t))
            props = GeomLProp_SLProps(surface, uv.X(), uv.Y(), 2, 1e-9)
            d1, d2 = gp_Dir(), gp_Dir()
            props.CurvatureDirections(d1, d2)
            tangent = np.array(edge.curve.DN(float(t), 1).Coord())
            worst = max(
                worst,
                min(
                    math.atan2(np.linalg.norm(np.cross(tangent, d.Coord())), abs(tangent @ np.array(d.Coord())))
                    for d in (d1, d2)
                ),
            )
    return worst


def _area(face) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(face, props)
    return props.Mass()


def test_the_flat_bottom_is_found_as_one_flat_part_of_its_area():
    from OCP.BRep import BRep_Tool
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace

    from tubecad.nets import HostSurface, find_umbilics

    face = _face("flat")
    host = HostSurface.of_face(face)
    umbilics = find_umbilics(host)
    assert not umbilics.region and umbilics.points == [] and len(umbilics.parts) == 1
    (part,) = umbilics.parts
    assert part.type == "flat" and np.abs(part.points[:, 2]).max() < 1e-9  # on the plane z = 0
    # the whole span v <= 1/3 is flat: its area (OCCT's, of the face cut there) to a grid strip
    span = BRepBuilderAPI_MakeFace(BRep_Tool.Surface_s(face), 0.0, 1.0, 0.0, 1 / 3, 1e-7).Face()
    strip = _area(face) / 96  # one row of the search grid's 96 cells (about: they are not even)
    assert abs(part.area - _area(span)) < 2 * strip
    assert umbilics.part_level > 0.0


def test_a_net_on_the_flat_bottom_stops_on_its_border_and_follows_the_principal_directions():
    from OCP.BRep import BRep_Tool
    from OCP.BRepCheck import BRepCheck_Analyzer

    from tubecad.nets import curvature_net

    face = _face("flat")
    net = curvature_net(face, 5, 5)
    assert BRepCheck_Analyzer(net.patches).IsValid()
    ends = [
        line.uv[0 if way == 0 else -1]
        for line in net.lines.values()
        for way, stop in ((1, line.stopped[0]), (0, line.stopped[1]))
        if stop == "umbilic_part"
    ]
    # the lines running down into the bottom: each stops on its border v = 1/3 (past it by the
    # width where (k1 - k2) / 2 < 1e-6 max|k|: measured 5e-7)
    assert len(ends) == 5
    assert all(1 / 3 <= v < 1 / 3 + 1e-6 for _, v in ends)
    assert _occ_angle(net, BRep_Tool.Surface_s(face)) < 1e-9  # measured 3.1e-11
    (part,) = net.report()["umbilic_parts"]
    assert part["type"] == "flat" and part["box"][1][2] < 1e-9


def _flat_crown_dome():
    """A dome of revolution whose cubic meridian's first span is straight and level: a flat
    crown of radius R0 (the meridian's point at its first knot), then a curved shoulder whose
    meridian curvature stays above the parallels' (no umbilic circle)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_BSplineCurve, Geom_SurfaceOfRevolution
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt

    from tubecad.occ_compat import Array1OfInteger, Array1OfPnt, Array1OfReal

    profile = [(0.0, 500.0), (400 / 3, 500.0), (800 / 3, 500.0), (400.0, 500.0), (750.0, 460.0), (1000.0, 300.0)]
    poles = Array1OfPnt(1, 6)
    for i, (x, z) in enumerate(profile, 1):
        poles.SetValue(i, gp_Pnt(x, 0.0, z))
    knots, mults = Array1OfReal(1, 4), Array1OfInteger(1, 4)
    for n, (value, mult) in enumerate(zip((0.0, 1 / 3, 2 / 3, 1.0), (4, 1, 1, 4)), 1):
        knots.SetValue(n, value)
        mults.SetValue(n, mult)
    meridian = Geom_BSplineCurve(poles, knots, mults, 3)
    crown = meridian.Value(1 / 3).X()
    surface = Geom_SurfaceOfRevolution(meridian, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)))
    return BRepBuilderAPI_MakeFace(surface, 1e-7).Face(), crown


def test_on_a_dome_with_a_flat_crown_the_meridians_stop_on_the_crown_and_the_parallels_are_circles():
    from OCP.BRep import BRep_Tool

    from tubecad.nets import curvature_net

    face, crown = _flat_crown_dome()
    net = curvature_net(face, 6, 6)
    assert net.umbilics.points == [] and len(net.umbilics.parts) == 1
    (part,) = net.umbilics.parts
    assert part.type == "flat" and np.abs(part.points[:, 2] - 500.0).max() < 1e-9
    assert np.linalg.norm(part.centre[:2]) < crown / 48  # on the axis, to the grid's step
    assert abs(part.area - math.pi * crown**2) < 0.05 * math.pi * crown**2
    meridians = [line for line in net.lines.values() if not line.closed]
    parallels = [line for line in net.lines.values() if line.closed]
    assert len(meridians) == 6 and len(parallels) == 6
    for line in meridians:
        p = line.points
        r = np.hypot(p[:, 0], p[:, 1])
        # in the plane through the axis and its first point
        normal = np.cross([0.0, 0.0, 1.0], p[0] / np.linalg.norm(p[0]))
        assert np.abs(p @ normal).max() < 1e-9
        # from the rim to the crown's border, past it by where (k1 - k2) / 2 < 1e-6 max|k|
        assert "umbilic_part" in line.stopped and "boundary" in line.stopped
        assert crown <= r.min() < crown + 3e-4  # measured 1.6e-4
        assert r.max() == pytest.approx(1000.0, abs=1e-9)
    assert _occ_angle(net, BRep_Tool.Surface_s(face)) < 2e-9  # measured 6.2e-10
    for line in parallels:
        r = np.hypot(line.points[:, 0], line.points[:, 1])
        assert np.ptp(r) < 1e-9 and np.ptp(line.points[:, 2]) < 1e-9 and r.min() > crown


def test_a_web_on_a_nearly_straight_line_by_the_flat_bottom_develops():
    """The lines along the patch (family 2) are nearly straight (normal curvature 9e-7 / mm,
    the face's largest 2.6e-3): a web on one develops, its base as long as the line (OCCT's
    length of its 3-D curve) and its area h L - h^2 / 2 Int k_n ds, k_n = X'' . n from the
    edge's 3-D curve and OCCT's surface normal (Gauss-Legendre on each of the curve's knot
    spans)."""
    from OCP.GCPnts import GCPnts_AbscissaPoint
    from OCP.GeomAdaptor import GeomAdaptor_Curve
    from OCP.GeomLProp import GeomLProp_SLProps
    from OCP.gp import gp_Pnt, gp_Vec

    from tubecad.nets import curvature_net
    from tubecad.stiffeners.net_webs import web_pattern

    face = _face("flat")
    net = curvature_net(face, 6, 5)
    edge, line = net.edges["k2_00"], net.lines["k2_00"]
    height = 150.0
    pattern = web_pattern(net.host, "k2_00", line, edge, height, "outside")
    length = GCPnts_AbscissaPoint.Length_s(GeomAdaptor_Curve(edge.curve))
    assert pattern.base_length == pytest.approx(length, rel=1e-12)
    x, w = np.polynomial.legendre.leggauss(12)
    knots = [edge.curve.Knot(i) for i in range(1, edge.curve.NbKnots() + 1)]
    turn = 0.0
    for a, b in zip(knots[:-1], knots[1:]):
        for t, weight in zip(0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w):
            p, d1, d2 = gp_Pnt(), gp_Vec(), gp_Vec()
            edge.curve.D2(float(t), p, d1, d2)
            uv = edge.pcurve.Value(float(t))
            normal = np.array(GeomLProp_SLProps(net.host.surface, uv.X(), uv.Y(), 2, 1e-9).Normal().Coord())
            speed = np.linalg.norm(d1.Coord())
            turn += weight * float(np.dot(d2.Coord(), normal)) / speed  # k_n |X'| dt
    assert abs(turn) > 1e-3  # not straight: the area's turn term is 28 mm^2 of 6e5
    assert pattern.area == pytest.approx(height * length - height**2 / 2 * turn, rel=1e-12)
