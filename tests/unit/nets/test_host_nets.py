"""Principal field, umbilics and lines of curvature on a host surface (issue 44), against
closed forms: the triaxial ellipsoid's confocal quadrics (tests/shared/ellipsoid.py), a
torus' meridians and parallels, the monkey saddle's star, a sphere's and a plane's umbilic
regions. None of the expected values comes from tubecad."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shared.ellipsoid import confocal, curvature_directions, nurbs_ellipsoid, umbilics

from tubecad.core.errors import ParameterError
from tubecad.nets import HostSurface, find_umbilics, principal_field, trace_line

A, B, C = 30.0, 20.0, 10.0


@pytest.fixture(scope="module")
def ellipsoid() -> HostSurface:
    return HostSurface.of_surface(nurbs_ellipsoid(A, B, C))


def _angle(d: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The angle between lines (either sense), accurate near 0."""
    return np.arctan2(np.linalg.norm(np.cross(d, t), axis=1), np.abs(np.einsum("nk,nk->n", d, t)))


def test_the_principal_directions_are_the_confocal_quadrics_tangents(ellipsoid):
    rng = np.random.default_rng(44)
    u, v = rng.uniform(0.0, 2 * math.pi, 4000), rng.uniform(-1.45, 1.45, 4000)
    field = principal_field(ellipsoid, u, v)
    points = ellipsoid.jet(u, v).X
    t1, t2 = curvature_directions(points, A, B, C)
    error = np.minimum(_angle(field.d1, t1), _angle(field.d1, t2))
    assert error.max() < 1e-10  # measured 1.7e-11 rad (the closed form's own round-off near the umbilics)
    assert np.abs(_angle(field.d1, field.d2) - math.pi / 2).max() < 1e-14
    # K = 1 / (a^2 b^2 c^2 (x^2/a^4 + y^2/b^4 + z^2/c^4)^2)
    K = 1.0 / ((A * B * C) ** 2 * ((points**2) / np.array([A**4, B**4, C**4])).sum(axis=1) ** 2)
    assert np.abs(field.k1 * field.k2 / K - 1.0).max() < 1e-12  # measured 1.1e-14


def test_the_four_umbilics_are_found_two_on_the_seam_all_lemons(ellipsoid):
    found = find_umbilics(ellipsoid)
    assert not found.region and len(found.points) == 4
    exact = umbilics(A, B, C)
    for umbilic in found.points:
        assert np.linalg.norm(exact - umbilic.point, axis=1).min() < 1e-13 * A  # measured 3.6e-16 a
        assert (umbilic.index, umbilic.separatrices, umbilic.type) == (0.5, 1, "lemon")
    assert found.index_sum == 2.0  # Poincare-Hopf: the sphere's Euler characteristic
    on_seam = [p for p in found.points if min(p.u, 2 * math.pi - p.u) < 1e-9]
    assert len(on_seam) == 2 and all(p.point[0] > 0 for p in on_seam)


def _distance_to_line(points: np.ndarray, which: int, value: float) -> np.ndarray:
    """Each point's distance on the ellipsoid from the line l_which = value: |l - value| over
    the length of l's gradient in the tangent plane (l implicit in sum x_i^2 / (A_i - l) = 1)."""
    lam = confocal(points, A, B, C)[which]
    squares = np.array([A * A, B * B, C * C])
    denominator = squares[None, :] - lam[:, None]
    grad = -(2 * points / denominator) / ((points**2) / denominator**2).sum(axis=1, keepdims=True)
    n = points / squares
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    tangential = grad - np.einsum("nk,nk->n", grad, n)[:, None] * n
    return np.abs(lam - value) / np.linalg.norm(tangential, axis=1)


@pytest.mark.parametrize("family", [1, 2])
@pytest.mark.parametrize("seed", [(1.0, 0.3), (2.0, -0.9), (0.3, 1.2), (3.0, 0.1)])
def test_a_traced_line_stays_on_its_confocal_quadric_and_closes(ellipsoid, family, seed):
    stops = np.array([p.point for p in find_umbilics(ellipsoid).points])
    line = trace_line(ellipsoid, seed, family, stops=stops, reach=1e-3)
    assert line.closed
    first = ellipsoid.jet(np.array([seed[0]]), np.array([seed[1]])).X
    l_seed = np.array(confocal(first, A, B, C))[:, 0]
    # the family's constant quadric: the one whose value does not change along the line
    spread = [np.ptp(lam) for lam in confocal(line.points, A, B, C)]
    which = int(np.argmin(spread))
    distance = _distance_to_line(line.points, which, l_seed[which])
    assert distance.max() < 1e-9 * A  # measured 1.9e-10 a at worst (tolerance 1e-10 a step)
    assert line.error < 1e-9 * A  # the largest step error or the closing gap: measured 1.2e-10 a
    assert np.linalg.norm(line.points[-1] - line.points[0]) < 1e-9 * A


def test_on_a_torus_the_lines_are_meridians_and_parallels():
    from OCP.Geom import Geom_ToroidalSurface
    from OCP.gp import gp_Ax3

    torus = HostSurface.of_surface(Geom_ToroidalSurface(gp_Ax3(), 40.0, 10.0))
    for family in (1, 2):
        line = trace_line(torus, (1.0, 0.7), family)
        assert line.closed
        spread_u, spread_v = np.ptp(line.uv[:, 0]), np.ptp(line.uv[:, 1])
        assert min(spread_u, spread_v) < 1e-10  # one parameter constant: a meridian or a parallel
        assert max(spread_u, spread_v) == pytest.approx(2 * math.pi, abs=1e-6)


def _monkey_saddle():
    """z = x^3 - 3 x y^2 over [-1, 1]^2 as the bicubic Bezier patch of (x, y) = (2 s - 1, 2 t - 1):
    its poles solve the Bernstein interpolation at s, t = 0, 1/3, 2/3, 1 (exact: z is in the
    bicubics' span)."""
    from math import comb

    from OCP.Geom import Geom_BezierSurface

    from tubecad.fitting.occ_arrays import points_2d

    nodes = np.linspace(0.0, 1.0, 4)
    bernstein = np.array([[comb(3, k) * x**k * (1 - x) ** (3 - k) for k in range(4)] for x in nodes])
    x, y = np.meshgrid(2 * nodes - 1, 2 * nodes - 1, indexing="ij")
    values = np.stack([x, y, x**3 - 3 * x * y**2], axis=-1)
    inverse = np.linalg.inv(bernstein)
    return HostSurface.of_surface(Geom_BezierSurface(points_2d(np.einsum("ki,ijc,lj->klc", inverse, values, inverse))))


def test_an_open_line_stops_on_the_faces_boundary_both_ways():
    host = _monkey_saddle()
    for family in (1, 2):
        line = trace_line(host, (0.7, 0.4), family)
        assert line.stopped == ("boundary", "boundary")
        for end in (line.uv[0], line.uv[-1]):
            assert min(abs(end[0]), abs(end[0] - 1), abs(end[1]), abs(end[1] - 1)) < 1e-12
        assert np.all((line.uv >= -1e-12) & (line.uv <= 1 + 1e-12))


def test_the_monkey_saddle_has_one_star_umbilic():
    """z = x^3 - 3 x y^2 = Re (x + i y)^3: its second form's trace-free part is 6 (x - i y)
    near 0, winding once backwards: index -1/2, the three lines y = 0, y = +-sqrt(3) x its
    separatrices (a star). The polynomial is exactly a bicubic Bezier patch."""
    host = _monkey_saddle()
    found = find_umbilics(host)
    assert len(found.points) == 1
    (star,) = found.points
    assert np.linalg.norm(star.point) < 1e-12
    assert (star.index, star.separatrices, star.type) == (-0.5, 3, "star")


def test_a_sphere_and_a_plane_are_umbilic_regions_and_a_seed_there_is_refused():
    from OCP.Geom import Geom_Plane, Geom_SphericalSurface
    from OCP.gp import gp_Ax3

    sphere = HostSurface.of_surface(Geom_SphericalSurface(gp_Ax3(), 5.0))
    assert find_umbilics(sphere).region
    plane = HostSurface.of_surface(Geom_Plane(gp_Ax3()), (0.0, 1.0, 0.0, 1.0))
    assert find_umbilics(plane).region
    with pytest.raises(ParameterError, match="umbilic") as info:
        trace_line(plane, (0.5, 0.5), 1)
    assert info.value.key == "seed"


@pytest.mark.parametrize("family", [1, 2])
@pytest.mark.parametrize("seed", [(1.0, 0.3), (2.0, -0.9), (0.3, 1.2), (3.0, 0.1)])
def test_a_line_as_an_edge_follows_the_closed_form_directions(ellipsoid, family, seed):
    """The edge's 3-D curve, sampled densely (not at its nodes), lies on the ellipsoid and its
    tangent is the confocal quadrics' line direction there; its pcurve's points are the 3-D
    curve's; OCCT finds the edge valid. (0.3, 1.2) in family 1 passes 4e-3 rad from two
    umbilics, where the direction field turns fastest: the worst case."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepCheck import BRepCheck_Analyzer

    from tubecad.nets.edges import line_edge

    line = trace_line(ellipsoid, seed, family)
    edge = line_edge(ellipsoid, line)
    curve = BRepAdaptor_Curve(edge.edge)
    ts = np.linspace(curve.FirstParameter(), curve.LastParameter(), 4001)
    points = np.array([[p.X(), p.Y(), p.Z()] for p in map(curve.Value, ts)])
    tangents = np.array([[d.X(), d.Y(), d.Z()] for d in (curve.DN(t, 1) for t in ts)])
    t1, t2 = curvature_directions(points, A, B, C)
    angle = np.minimum(_angle(tangents, t1), _angle(tangents, t2))
    assert angle.max() < 2e-8  # measured 9.5e-9 rad near the umbilics, 1e-9 elsewhere
    assert np.abs((points**2 / np.array([A * A, B * B, C * C])).sum(axis=1) - 1.0).max() < 1e-10  # 1.3e-11
    assert edge.gap < 1e-9 * A and edge.angle < 2e-8
    assert BRepCheck_Analyzer(edge.edge).IsValid()


def test_a_build123d_face_is_read_as_its_surface_and_a_non_face_is_refused():
    """A build123d torus' face: its exact toroidal surface over its parameter box (one whole
    turn each way), no umbilics, its lines closed round either period."""
    import build123d as bd

    face = bd.Solid.make_torus(40.0, 10.0).faces()[0]
    host = HostSurface.of_face(face)
    assert host.closed == (True, True)
    assert not find_umbilics(host).points and not find_umbilics(host).region
    line = trace_line(host, (0.5, 0.5), 2)
    assert line.closed
    with pytest.raises(ParameterError, match="face must be") as info:
        HostSurface.of_face(face.edges()[0])
    assert info.value.key == "face"


@pytest.fixture(scope="module")
def net(ellipsoid):
    from tubecad.nets.net import curvature_net

    return curvature_net(ellipsoid, 3, 3, seed=(1.0, 0.3))


def test_the_net_splits_the_face_into_a_valid_shell_of_the_same_area(net):
    """3 + 3 lines on the whole ellipsoid: edges k1_00 .. k2_02, each closed on its confocal
    quadric; the face split by them is valid and its patches' areas add up to the ellipsoid's
    (the face before the split, measured the same way)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import faces_area, sub_shapes
    from tubecad.occ_compat import as_face

    assert sorted(net.edges) == [f"k{f}_{i:02d}" for f in (1, 2) for i in range(3)]
    assert BRepCheck_Analyzer(net.patches).IsValid()
    patches = [as_face(f) for f in sub_shapes(net.patches, TopAbs_FACE)]
    assert len(patches) > 9
    u0, u1, v0, v1 = net.host.bounds
    whole = faces_area([BRepBuilderAPI_MakeFace(net.host.surface, u0, u1, v0, v1, 1e-7).Face()])
    assert faces_area(patches) == pytest.approx(whole, rel=1e-6)  # measured 4.7e-7 (OCCT's area integration)
    for name, line in net.lines.items():
        spread = min(np.ptp(lam) for lam in confocal(line.points, A, B, C))
        assert spread < 1e-7, name  # l along the line (l ~ 100 .. 900): measured 3.6e-9


def test_the_nets_edges_follow_the_principal_directions(net):
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    worst = 0.0
    for edge in net.edges.values():
        curve = BRepAdaptor_Curve(edge.edge)
        ts = np.linspace(curve.FirstParameter(), curve.LastParameter(), 2001)
        points = np.array([[p.X(), p.Y(), p.Z()] for p in map(curve.Value, ts)])
        tangents = np.array([[d.X(), d.Y(), d.Z()] for d in (curve.DN(t, 1) for t in ts)])
        t1, t2 = curvature_directions(points, A, B, C)
        worst = max(worst, float(np.minimum(_angle(tangents, t1), _angle(tangents, t2)).max()))
    assert worst < 2e-8  # measured 5.2e-9 rad (the edges' own measure, at their pcurves' points: 2.4e-8)


def test_a_net_is_refused_on_an_umbilic_region_and_for_a_bad_count():
    from OCP.Geom import Geom_Plane
    from OCP.gp import gp_Ax3

    from tubecad.nets.net import curvature_net

    plane = HostSurface.of_surface(Geom_Plane(gp_Ax3()), (0.0, 1.0, 0.0, 1.0))
    with pytest.raises(ParameterError, match="umbilic region") as info:
        curvature_net(plane, 2, 2)
    assert info.value.key == "face"
    with pytest.raises(ParameterError, match="k1_lines must be") as info:
        curvature_net(plane, 0, 2)
    assert info.value.key == "k1_lines"


def test_a_torus_face_net_is_its_parallels_and_meridians_in_eight_patches():
    """A build123d torus face (R = 40, r = 10) seeded at its centre (pi, pi): 3 parallels (at
    v = pi, 5 pi / 3, pi / 3) and 2 meridians (u = pi, and u = 0: the face's own seam, not split
    again). With the face's seams the parallels cut the torus into 4 rings and the meridians
    each ring in 2: 8 patches, their area the torus' 4 pi^2 R r."""
    import build123d as bd
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import faces_area, sub_shapes
    from tubecad.nets.net import curvature_net
    from tubecad.occ_compat import as_face

    face = bd.Solid.make_torus(40.0, 10.0).faces()[0]
    net = curvature_net(face, 3, 2)
    assert net.on_face_edges == {"k2_01"}
    patches = [as_face(f) for f in sub_shapes(net.patches, TopAbs_FACE)]
    assert len(patches) == 8 and BRepCheck_Analyzer(net.patches).IsValid()
    assert faces_area(patches) == pytest.approx(4 * math.pi**2 * 40.0 * 10.0, rel=1e-12)
    for name, line in net.lines.items():
        constant = line.uv[:, 1] if name.startswith("k1") else line.uv[:, 0]
        assert np.ptp(constant) < 1e-10, name
    assert net.angle < 1e-10  # measured 2.5e-11 rad


def test_the_nets_report_lists_the_umbilics_typed_and_each_line(net):
    """The ellipsoid's report: its four lemons at the closed-form points, as named vertices
    too, and every line with its figures (JSON as written)."""
    import json

    from OCP.BRep import BRep_Tool

    report = json.loads(json.dumps(net.report()))
    assert not report["umbilic_region"] and [u["type"] for u in report["umbilics"]] == ["lemon"] * 4
    exact = umbilics(A, B, C)
    for entry in report["umbilics"]:
        assert np.linalg.norm(exact - np.array(entry["point"]), axis=1).min() < 1e-13 * A
        vertex = BRep_Tool.Pnt_s(net.vertices[entry["name"]])
        assert np.allclose([vertex.X(), vertex.Y(), vertex.Z()], entry["point"], rtol=0, atol=1e-12)
    assert set(report["lines"]) == set(net.edges)
    assert all(line["length"] > 0 and line["angle"] == net.edges[n].angle for n, line in report["lines"].items())
    assert report["angle"] == net.angle


def test_on_a_trimmed_face_the_lines_stop_on_its_own_boundary():
    """A torus cut by a tilted box: its toroidal face's boundary is plane sections, not
    parameter lines. The lines (still parallels and meridians) stop on that boundary, not on
    the parameter box's; the net splits the trimmed face into patches of its area."""
    import build123d as bd
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import faces_area, sub_shapes
    from tubecad.nets.net import curvature_net
    from tubecad.occ_compat import as_face

    part = bd.Solid.make_torus(40.0, 10.0) - bd.Box(200, 200, 200).rotate(bd.Axis.X, 25).translate((0, 0, 103))
    face = max(part.faces(), key=lambda f: f.area)
    host = HostSurface.of_face(face)
    for family in (1, 2):
        line = trace_line(host, (1.0, 3.5), family)
        assert line.stopped == ("boundary", "boundary")
        assert min(np.ptp(line.uv[:, 0]), np.ptp(line.uv[:, 1])) < 1e-10  # a parallel or a meridian
        for end in (line.points[0], line.points[-1]):
            vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*(float(c) for c in end))).Vertex()
            gap = min(BRepExtrema_DistShapeShape(vertex, e.wrapped).Value() for e in face.edges())
            assert gap < 1e-7  # measured 2.3e-8 (the boolean's edges' own tolerance is 1e-7)
    net = curvature_net(face, 2, 2, seed=(1.0, 3.5))
    assert BRepCheck_Analyzer(net.patches).IsValid()
    patches = [as_face(f) for f in sub_shapes(net.patches, TopAbs_FACE)]
    # measured the same way before and after (OCCT's adaptive integration: 2.4e-10 apart; a
    # fixed-order rule, build123d's face.area, is 0.1 % off on this trimmed face)
    assert len(patches) > 4 and faces_area(patches) == pytest.approx(faces_area([face.wrapped]), rel=1e-9)
