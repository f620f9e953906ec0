"""The equal tee's saddle (issue 43) against closed forms that do not come from tubecad: two
equal cylinders whose axes meet cross in two plane ellipses, in the planes bisecting the axes
(Monge: both envelop one sphere), and touch at the crotch points, where those planes meet the
cylinders' common sphere. Perpendicular: main y^2 + z^2 = R^2 along x, branch x^2 + y^2 = R^2
up z; the saddle lies in x = +-z and the crotch points are (0, +-R, 0)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.TopExp import TopExp

from tubecad import NaturalAxis
from tubecad.junctions import fit_saddle, saddle_curve
from tubecad.junctions.crotch import crotch
from tubecad.surface.canal import tube_or_canal

R = 50.0


def line(origin, tangent, normal, length, radius, k="0"):
    return tube_or_canal(NaturalAxis(k, "0", (0.0, length), origin=origin, tangent=tangent, normal=normal), radius)


MAIN = line((-100.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 200.0, R)
BRANCH = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, R)


def test_the_saddle_is_two_half_ellipses_in_the_bisecting_planes_through_the_crotch():
    saddle = saddle_curve(MAIN, BRANCH, 129)
    p = saddle.points
    # measured 2.3e-13 R and 1.1e-13 R (Newton's round-off): issue 43 asks 1e-9 r
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R).max() < 1e-12 * R
    assert np.abs(np.hypot(p[:, 0], p[:, 1]) - R).max() < 1e-12 * R
    assert np.minimum(np.abs(p[:, 0] - p[:, 2]), np.abs(p[:, 0] + p[:, 2])).max() < 1e-12 * R  # measured 6.4e-13
    assert (p[:, 2] >= -1e-12).all()
    assert saddle.corners == (0, 64, 128)
    corners = p[list(saddle.corners)]
    assert np.abs(corners - [[0, R, 0], [0, -R, 0], [0, R, 0]]).max() < 1e-12 * R  # measured 2.3e-14
    # from u_B = pi/2 (y = R) round to 3 pi/2 (y = -R) through x = -R: the half-ellipse in
    # x = -z (x < 0); the other in x = z (x > 0)
    first, second = p[1:64], p[65:128]
    assert np.abs(first[:, 0] + first[:, 2]).max() < 1e-12 * R and (first[:, 0] < 0).all()
    assert np.abs(second[:, 0] - second[:, 2]).max() < 1e-12 * R and (second[:, 0] > 0).all()
    # extent: the opening reaches from x = -R to R along the main axis (s = 100 -+ R)
    assert saddle.extent(saddle.main_s) == pytest.approx((100.0 - R, 100.0 + R), abs=1e-9)


def test_the_crotch_is_where_the_rings_meet_on_the_common_sphere():
    touch = crotch(MAIN, BRANCH, 300.0)
    assert touch is not None
    assert np.abs(touch.points - [[0, R, 0], [0, -R, 0]]).max() < 1e-12 * R
    assert touch.branch_u == pytest.approx([math.pi / 2, 3 * math.pi / 2], abs=1e-13)
    assert touch.main_s == pytest.approx([100.0, 100.0], abs=1e-12)
    # a near-equal branch (r / R = 0.999) or one offset sideways does not touch
    assert crotch(MAIN, line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, 0.999 * R), 300.0) is None
    assert crotch(MAIN, line((0.0, 0.1, 0.0), (0, 0, 1), (1, 0, 0), 120.0, R), 300.0) is None


def test_the_fitted_saddle_is_two_exact_ellipse_arcs_sharing_the_crotch_vertices():
    edge = fit_saddle(MAIN, BRANCH)
    assert edge.conic and len(edge.curves) == 2 and edge.poles == 0
    assert edge.deviation < 1e-12 * R  # measured 1.3e-13: the ellipse is the closed form
    for curve in edge.curves:
        t = np.linspace(curve.FirstParameter(), curve.LastParameter(), 201)
        p = np.array([curve.Value(float(x)).Coord() for x in t])
        assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R).max() < 1e-12 * R
        assert np.abs(np.hypot(p[:, 0], p[:, 1]) - R).max() < 1e-12 * R
        assert np.minimum(np.abs(p[:, 0] - p[:, 2]), np.abs(p[:, 0] + p[:, 2])).max() < 1e-12 * R
        # semi-axes R (across, through the crotch points) and R sqrt(2) (in the bisecting plane)
        assert curve.BasisCurve().MajorRadius() == pytest.approx(R * math.sqrt(2), rel=1e-13)
        assert curve.BasisCurve().MinorRadius() == pytest.approx(R, rel=1e-13)
    first, second = edge.edges
    assert all(BRepCheck_Analyzer(e).IsValid() for e in edge.edges)
    shared = {
        TopExp.FirstVertex_s(first).IsSame(v) or TopExp.LastVertex_s(first).IsSame(v)
        for v in (TopExp.FirstVertex_s(second), TopExp.LastVertex_s(second))
    }
    assert shared == {True}
    ends = sorted(tuple(np.round(BRep_Tool.Pnt_s(TopExp.FirstVertex_s(e)).Coord(), 9)) for e in edge.edges)
    assert np.allclose(ends, [[0, -R, 0], [0, R, 0]], atol=1e-12)
    assert edge.to_build123d().is_closed


def test_an_oblique_equal_branch_meets_in_the_planes_bisecting_the_axes():
    """Branch at 60 deg, d = (cos a, 0, sin a): the saddle lies in the planes through the axes'
    crossing normal to t - d and t + d (t = (1, 0, 0)), both ellipse arcs."""
    a = math.radians(60.0)
    d = np.array([math.cos(a), 0.0, math.sin(a)])
    branch = line((0.0, 0.0, 0.0), tuple(d), (0, 1, 0), 150.0, R)
    saddle = saddle_curve(MAIN, branch, 97)
    p = saddle.points
    planes = np.abs(np.stack([p @ (np.array([1.0, 0, 0]) - d), p @ (np.array([1.0, 0, 0]) + d)], axis=1))
    assert planes.min(axis=1).max() < 1e-11 * R
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R).max() < 1e-12 * R
    edge = fit_saddle(MAIN, branch)
    assert edge.conic
    # the main cut by the planes normal to t - d and t + d: semi-axes R / sin(a/2), R / cos(a/2)
    majors = sorted(c.BasisCurve().MajorRadius() for c in edge.curves)
    assert majors == pytest.approx(sorted([R / math.sin(a / 2), R / math.cos(a / 2)]), rel=1e-12)
    assert all(c.BasisCurve().MinorRadius() == pytest.approx(R, rel=1e-12) for c in edge.curves)


def test_a_curved_equal_branch_has_fitted_curves_through_the_crotch():
    """A branch bending at curvature 1/250 from the start: no conic; each of its two curves is a
    B-spline within the tolerance of the exact saddle, its points on both exact surfaces."""
    branch = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, R, k="0.004")
    edge = fit_saddle(MAIN, branch, 1e-8)
    assert not edge.conic and len(edge.curves) == 2
    assert edge.deviation <= 1e-8  # measured 2.1e-10
    p = edge.saddle.points
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R).max() < 1e-12 * R
    assert np.abs(p[list(edge.saddle.corners)] - [[0, R, 0], [0, -R, 0], [0, R, 0]]).max() < 1e-12 * R
    # the fitted curves against the exact saddle between their nodes, away from the crotch
    u = np.linspace(edge.saddle.branch_u[0] + 0.1, edge.saddle.branch_u[edge.saddle.corners[1]] - 0.1, 23)
    points = np.array([edge.curves[0].Value(float(x)).Coord() for x in u])
    assert edge.exact_distance(points, u).max() < 1e-8
