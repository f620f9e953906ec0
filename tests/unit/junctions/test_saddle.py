"""The saddle curve of a branch on a main surface (issue 25) against closed forms: unequal
perpendicular cylinders, an oblique and an offset (hillside) branch, a branch on a torus, a
conical (canal) branch; and the refusals (tangent surfaces, a branch that never leaves)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import NaturalAxis, ParameterError
from tubecad.junctions import saddle_curve
from tubecad.junctions.saddle import saddle_distance
from tubecad.surface.canal import tube_or_canal

R, r = 50.0, 20.0
#: Newton stops at |X_A - X_B| <= 1e-13 x the size (~150 here); measured 8e-14 on the closed forms
ROUND_OFF = 5e-13


def line(origin, tangent, normal, length, radius):
    """A straight tube (k = tau = 0) of ``radius`` from ``origin`` along ``tangent``; its r1 = ``normal``."""
    return tube_or_canal(NaturalAxis("0", "0", (0.0, length), origin=origin, tangent=tangent, normal=normal), radius)


MAIN = line((-100.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 200.0, R)  # y^2 + z^2 = R^2


def test_perpendicular_cylinders_meet_on_the_closed_form_saddle():
    """Branch x^2 + y^2 = r^2 up z: the point at u is (r cos u, r sin u, sqrt(R^2 - r^2 sin^2 u)),
    so s_B = z, s_A = x + 100 and the main's angle from its r1 = y is atan2(z, y)."""
    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    c = saddle_curve(MAIN, branch, 129)
    u = c.branch_u
    z = np.sqrt(R**2 - r**2 * np.sin(u) ** 2)
    assert np.abs(c.branch_s - z).max() < ROUND_OFF
    assert np.abs(c.main_s - (r * np.cos(u) + 100.0)).max() < ROUND_OFF
    chi = np.arctan2(z, r * np.sin(u))
    assert np.abs(np.angle(np.exp(1j * (c.main_u - chi)))).max() < ROUND_OFF / R
    assert np.abs(c.points - np.column_stack([r * np.cos(u), r * np.sin(u), z])).max() < ROUND_OFF
    assert c.residual < ROUND_OFF and u[0] == 0.0 and u[-1] == pytest.approx(2 * math.pi)


def test_an_oblique_branch_meets_where_the_quadratic_says():
    """Branch along d = (cos a, 0, sin a): P = s d + r (cos u (0,1,0) + sin u (-sin a, 0, cos a)),
    on the main where (s sin a + r sin u cos a)^2 = R^2 - r^2 cos^2 u."""
    a = math.radians(60.0)
    branch = line((0.0, 0.0, 0.0), (math.cos(a), 0, math.sin(a)), (0, 1, 0), 120.0, r)
    c = saddle_curve(MAIN, branch, 97)
    u = c.branch_u
    s = (np.sqrt(R**2 - r**2 * np.cos(u) ** 2) - r * np.sin(u) * math.cos(a)) / math.sin(a)
    assert np.abs(c.branch_s - s).max() < ROUND_OFF


def test_a_hillside_branch_offset_sideways():
    """Branch up z, its axis e = 22 off the main's: z = sqrt(R^2 - (e + r sin u)^2)."""
    e = 22.0
    branch = line((0.0, e, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    c = saddle_curve(MAIN, branch, 97)
    z = np.sqrt(R**2 - (e + r * np.sin(c.branch_u)) ** 2)
    assert np.abs(c.branch_s - z).max() < ROUND_OFF


def test_saddle_distance_is_a_points_offset_across_the_closed_form_saddle():
    """issue 41: P = C(u) + delta m, m a unit vector normal to C'(u), has its foot at u on the
    perpendicular cylinders' saddle C(u) = (r cos u, r sin u, w), w = sqrt(R^2 - r^2 sin^2 u),
    C'(u) = (-r sin u, r cos u, -r^2 sin 2u / 2w), so it lies delta from the saddle; found
    from a first guess of u_B 0.02 off and the saddle at 33 samples."""
    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    u = np.linspace(0.1, 6.2, 23)
    w = np.sqrt(R**2 - r**2 * np.sin(u) ** 2)
    tangent = np.column_stack([-r * np.sin(u), r * np.cos(u), -(r**2) * np.sin(2 * u) / (2 * w)])
    across = np.cross(tangent, [0.0, 0.0, 1.0])
    across /= np.linalg.norm(across, axis=1, keepdims=True)
    other = np.cross(tangent / np.linalg.norm(tangent, axis=1, keepdims=True), across)
    turn = 0.7 * np.arange(len(u))
    delta = np.logspace(-10, -4, len(u))
    points = np.column_stack([r * np.cos(u), r * np.sin(u), w])
    points += delta[:, None] * (np.cos(turn)[:, None] * across + np.sin(turn)[:, None] * other)
    distance = saddle_distance(MAIN, branch, points, u + 0.02, saddle_curve(MAIN, branch, 33))
    assert np.abs(distance - delta).max() < ROUND_OFF  # measured 8.6e-14


def test_a_branch_on_a_torus_lies_on_both_surfaces():
    """Main: the torus (sqrt(x^2 + y^2) - 150)^2 + z^2 = 40^2 (axis a half circle of radius 150);
    branch: r = 15 up z from the axis point at 45 deg. Every point on both, by their equations."""
    bend = 150.0
    main = tube_or_canal(
        NaturalAxis(f"1/{bend}", "0", (0.0, math.pi * bend), origin=(bend, 0, 0), tangent=(0, 1, 0), normal=(-1, 0, 0)),
        40.0,
    )
    foot = bend * np.array([math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0])
    branch = line(tuple(foot), (0, 0, 1), (1, 0, 0), 100.0, 15.0)
    c = saddle_curve(main, branch, 97)
    x, y, z = c.points.T
    assert np.abs(np.hypot(np.hypot(x, y) - bend, z) - 40.0).max() < ROUND_OFF
    assert np.abs(np.hypot(x - foot[0], y - foot[1]) - 15.0).max() < ROUND_OFF
    assert (z > 0).all() and abs(np.mean(c.main_s) - math.pi * bend / 4) < 15.0


def test_a_conical_branch_a_canal_surface():
    """Branch radius law r(s) = 20 - 0.1 s up z: the cone whose points at height z lie
    rho = (20 + b s) sqrt(1 - b^2) from its axis, s = (z + 20 b) / (1 - b^2), b = -0.1
    (the characteristic circles' centres sit r r' ahead of c(s))."""
    b = -0.1
    branch = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 100.0), origin=(0, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), "20 - 0.1 * s"
    )
    c = saddle_curve(MAIN, branch, 97)
    x, y, z = c.points.T
    s = (z + 20.0 * b) / (1.0 - b * b)
    assert np.abs(np.hypot(x, y) - (20.0 + b * s) * math.sqrt(1.0 - b * b)).max() < ROUND_OFF
    assert np.abs(np.hypot(y, z) - R).max() < ROUND_OFF


def test_a_branch_grazing_the_main_tube_is_refused_naming_the_radius():
    """A hillside branch whose side touches the main tube (offset + r = R) is tangent to it at
    one point of the saddle, not at its start: refused naming the radius."""
    branch = line((0.0, R - r, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    with pytest.raises(ParameterError, match="tangent|grazes") as info:
        saddle_curve(MAIN, branch)
    assert info.value.key.startswith("branches") and "\n" not in str(info.value)


def test_a_branch_that_never_leaves_the_main_tube_is_refused():
    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 30.0, r)  # ends at z = 30 < 41.2
    with pytest.raises(ParameterError, match="never leaves") as info:
        saddle_curve(MAIN, branch)
    assert info.value.key == "branches"


@pytest.mark.parametrize("tolerance", [1e-6, 1e-8, 1e-10])
def test_the_saddle_edge_lies_on_both_cylinders_within_the_tolerance(tolerance):
    """The fitted edge sampled by OCCT's own evaluator 5,000 times round the branch: each point
    within ``tolerance`` of both cylinders (their equations, not the saddle's samples); one
    periodic, closed, valid, at least C2 edge named ``saddle_outer``; each halving of the
    knot spacing gains the h^6 of a quintic (64x: at most 2 doublings per factor 100)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.GeomAbs import GeomAbs_C2

    from tubecad.junctions import fit_saddle

    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    saddle = fit_saddle(MAIN, branch, tolerance)
    curve = BRepAdaptor_Curve(saddle.edge)
    t = np.linspace(curve.FirstParameter(), curve.LastParameter(), 5001)
    p = np.array([curve.Value(float(x)).Coord() for x in t])
    assert np.abs(np.hypot(p[:, 0], p[:, 1]) - r).max() <= tolerance
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R).max() <= tolerance
    assert saddle.name == "saddle_outer" and saddle.deviation <= tolerance
    assert saddle.curve.IsPeriodic() and saddle.curve.IsClosed() and saddle.curve.Continuity().value >= GeomAbs_C2.value
    assert BRepCheck_Analyzer(saddle.edge).IsValid()
    # measured: 64 poles at 1e-6, 128 at 1e-8, 256 at 1e-10
    assert saddle.poles <= {1e-6: 64, 1e-8: 128, 1e-10: 256}[tolerance]


def test_a_periodic_bspline_through_samples_reproduces_them():
    """periodic_bspline's OCCT curve passes through its samples and is the scipy interpolant
    between them (a trigonometric curve, period 2 pi)."""
    from scipy.interpolate import make_interp_spline

    from tubecad.junctions import periodic_bspline

    u = np.linspace(0.0, 2 * np.pi, 17)
    p = np.column_stack([np.cos(u) + 0.3 * np.cos(3 * u), np.sin(2 * u), np.sin(u)])
    p[-1] = p[0]
    curve = periodic_bspline(u, p)
    at = lambda x: np.array([curve.Value(float(v)).Coord() for v in x])
    assert np.abs(at(u) - p).max() < 1e-14
    x = np.linspace(0.0, 2 * np.pi, 101)
    assert np.abs(at(x) - make_interp_spline(u, p, k=5, bc_type="periodic")(x)).max() < 1e-14


def test_a_branch_wall_on_a_main_wall_has_an_outer_and_an_inner_saddle():
    """Main wall 4 thick centred on R = 50 (48..52), branch wall 2 thick outside r = 20 (20..22):
    saddle_outer on the cylinders of 22 and 52, saddle_inner on those of 20 and 48."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    from tubecad.junctions import wall_saddles

    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    outer, inner = wall_saddles(MAIN, branch, 4.0, 2.0, branch_side="outside", tolerance=1e-8)
    for saddle, (rb, rm) in ((outer, (22.0, 52.0)), (inner, (20.0, 48.0))):
        curve = BRepAdaptor_Curve(saddle.edge)
        t = np.linspace(curve.FirstParameter(), curve.LastParameter(), 2001)
        p = np.array([curve.Value(float(x)).Coord() for x in t])
        assert np.abs(np.hypot(p[:, 0], p[:, 1]) - rb).max() <= 1e-8
        assert np.abs(np.hypot(p[:, 1], p[:, 2]) - rm).max() <= 1e-8
    assert (outer.name, inner.name) == ("saddle_outer", "saddle_inner")
    # as build123d edges: labelled, closed, the same OCCT edge; the outer saddle is the longer
    edges = [saddle.to_build123d() for saddle in (outer, inner)]
    assert [e.label for e in edges] == ["saddle_outer", "saddle_inner"]
    assert all(e.is_closed and e.wrapped.IsSame(s.edge) for e, s in zip(edges, (outer, inner)))
    assert edges[0].length > edges[1].length


def test_the_saddle_edge_lies_on_both_fitted_tubes():
    """The edge against the tubes' own fitted B-rep faces (OCCT's distance from each of 60
    points of the edge to each tube's faces): within the saddle's deviation plus the faces'
    fit tolerance, 1e-8 + 1e-8, of both."""
    import build123d as bd
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt

    from tubecad.brep import NetLayout, build_tube_solid
    from tubecad.junctions import fit_saddle

    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    saddle = fit_saddle(MAIN, branch, 1e-8)
    # each tube's curved faces only (a point inside a solid is 0 from it), as one compound
    tubes = []
    for surface in (MAIN, branch):
        solid = build_tube_solid(surface, NetLayout.equal(surface, 3, 4), 1e-8).shape
        tubes.append(bd.Compound([f for f in solid.faces() if f.geom_type == bd.GeomType.BSPLINE]).wrapped)
    curve = BRepAdaptor_Curve(saddle.edge)
    for t in np.linspace(curve.FirstParameter(), curve.LastParameter(), 60, endpoint=False):
        vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*curve.Value(float(t)).Coord())).Vertex()
        for faces in tubes:
            distance = BRepExtrema_DistShapeShape(vertex, faces)
            # the guarantee is 2e-8; measured 8.4e-11 (both fits far inside their tolerance)
            assert distance.IsDone() and distance.Value() <= 1e-9


def test_the_extent_of_a_sampled_saddle_is_refined_between_its_samples():
    """The perpendicular cylinders' saddle sampled at 26 points (u_B = 2 pi j / 25, so pi, pi / 2
    and 3 pi / 2 fall between samples): along the main it spans s_A = 100 -+ r, round it the
    angles atan2(z, +-r) at z = sqrt(R^2 - r^2). The samples miss the near end by 0.16 and the
    angles by 8.6e-4 rad; refined (the trigonometric interpolant), by 6e-14 and 5e-11."""
    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)
    c = saddle_curve(MAIN, branch, 26)
    z = math.sqrt(R**2 - r**2)
    exact_u = (math.atan2(z, r), math.atan2(z, -r))
    assert c.main_s.min() > 100.0 - r + 0.1 and c.main_u.min() > exact_u[0] + 5e-4
    s_lo, s_hi = c.extent(c.main_s)
    u_lo, u_hi = c.extent(c.main_u)
    assert type(s_lo) is float and type(u_hi) is float  # (report.json takes them)
    assert abs(s_lo - (100.0 - r)) < 1e-12 and abs(s_hi - (100.0 + r)) < 1e-12
    assert abs(u_lo - exact_u[0]) < 1e-10 and abs(u_hi - exact_u[1]) < 1e-10
