"""Closed axes (issue 11 item 3): a closed spline, a closed route, a torus knot; detected when
the ends and their tangents agree, or demanded with ``closed = true``.

The facts checked come from closed forms computed here, not from the code: the length of a
circle, the holonomy of a closed curve's rotation-minimising frame as minus its total
torsion mod 2 pi (quadrature of the Frenet torsion from exact derivatives), and a closed
route's holonomy by parallel transport through its bends with Rodrigues rotations.
"""

import math

import numpy as np
import pytest
from conftest import ROOT
from scipy.integrate import quad

from tubecad.core.errors import ParameterError
from tubecad.curves.natural import NaturalAxis
from tubecad.curves.parametric import ParametricAxis
from tubecad.curves.points import points_axis
from tubecad.curves.route import RouteAxis
from tubecad.spec.parse import load_spec

SAMPLES = ROOT / "samples"
TWO_PI = 2 * math.pi


def wrapped(angle: float) -> float:
    """``angle`` mod 2 pi, in [-pi, pi)."""
    return (angle + math.pi) % TWO_PI - math.pi


def symbolic_curve(x, y, z):
    """The curve (x, y, z)(t) of sympy expressions as a vectorised callable, and its first
    three derivatives as exact (lambdified) callables of a scalar t."""
    sp = pytest.importorskip("sympy")
    t = sp.Symbol("t")
    X = sp.Matrix([e(t, sp) for e in (x, y, z)])
    components = [sp.lambdify(t, e, "numpy") for e in X]
    derivatives = [sp.lambdify(t, X.diff(t, n), "numpy") for n in (1, 2, 3)]

    def curve(tt: np.ndarray) -> np.ndarray:
        return np.stack([np.broadcast_to(np.asarray(f(tt), dtype=float), np.shape(tt)) for f in components], -1)

    def d(tt: float) -> list[np.ndarray]:
        return [np.asarray(g(tt), dtype=float).ravel() for g in derivatives]

    return curve, d


def total_torsion(d, t0: float, t1: float) -> float:
    """Int tau ds = Int (x' x x'') . x''' / |x' x x''|^2 |x'| dt, by adaptive quadrature."""

    def integrand(t: float) -> float:
        d1, d2, d3 = d(t)
        c = np.cross(d1, d2)
        return float(c @ d3 / (c @ c) * np.linalg.norm(d1))

    value, error = quad(integrand, t0, t1, limit=500, epsabs=1e-13, epsrel=1e-13)
    assert error < 1e-11
    return value


def trefoil(t, sp):
    return sp.sin(t) + 2 * sp.sin(2 * t), sp.cos(t) - 2 * sp.cos(2 * t), -sp.sin(3 * t)


TREFOIL = (lambda t, sp: trefoil(t, sp)[0], lambda t, sp: trefoil(t, sp)[1], lambda t, sp: trefoil(t, sp)[2])
TORUS_KNOT_2_3 = (
    lambda t, sp: (3 + sp.cos(3 * t)) * sp.cos(2 * t),
    lambda t, sp: (3 + sp.cos(3 * t)) * sp.sin(2 * t),
    lambda t, sp: sp.sin(3 * t),
)


# ---------------------------------------------------------------------------------------------
# parametric and natural axes


def test_a_circle_is_detected_closed_with_no_holonomy():
    R = 7.5
    axis = ParametricAxis(lambda t: np.stack([R * np.cos(t), R * np.sin(t), 0 * t], -1), (0.0, TWO_PI))
    assert axis.closed
    assert axis.length == pytest.approx(TWO_PI * R, rel=1e-13)
    assert abs(axis.holonomy) < 1e-12  # a planar curve's rotation-minimising frame closes
    assert axis.describe()["closed"] is True
    half = ParametricAxis(lambda t: np.stack([R * np.cos(t), R * np.sin(t), 0 * t], -1), (0.0, math.pi))
    assert not half.closed and half.holonomy == 0.0 and "closed" not in half.describe()
    # a piece of a loop is open
    assert not axis.restricted((0.0, 0.5 * axis.length)).closed


def test_a_natural_circle_is_closed():
    axis = NaturalAxis("0.5", "0", (0.0, 4 * math.pi))
    assert axis.closed and abs(axis.holonomy) < 1e-12 and axis.describe()["closed"] is True
    assert not NaturalAxis("0.5", "0", (0.0, 4 * math.pi), closed=False).closed


@pytest.mark.parametrize("curve", [TREFOIL, TORUS_KNOT_2_3], ids=["trefoil", "torus_knot_2_3"])
def test_the_holonomy_of_a_knot_is_minus_its_total_torsion(curve):
    """r1 = cos w n - sin w b with w = Int tau ds solves r1' = -k1 t; the Frenet frame of a
    closed curve with k > 0 closes, so r1(L) = cos(-W) r1(0) + sin(-W) r2(0), W the total torsion."""
    x, d = symbolic_curve(*curve)
    axis = ParametricAxis(x, (0.0, TWO_PI))
    assert axis.closed and axis.describe()["closed"] is True
    assert axis.curvature(np.linspace(*axis.span, 2001)).min() > 0.03  # the torsion exists throughout
    W = total_torsion(d, 0.0, TWO_PI)
    assert abs(wrapped(axis.holonomy + W)) < 1e-9  # measured ~8e-12
    assert abs(axis.holonomy) > 0.1  # not a trivial 0
    # the frame's closing angle is the holonomy, whatever the start normal
    turned = ParametricAxis(x, (0.0, TWO_PI), normal=(0.3, -1.0, 0.2))
    assert abs(wrapped(turned.holonomy - axis.holonomy)) < 1e-10


@pytest.mark.slow
def test_the_trefoil_knot_is_closed_and_closed_true_accepts_it():
    x, _ = symbolic_curve(*TREFOIL)
    assert ParametricAxis(x, (0.0, TWO_PI)).closed
    assert ParametricAxis(x, (0.0, TWO_PI), closed=True).closed
    assert not ParametricAxis(x, (0.0, TWO_PI), closed=False).closed
    assert not ParametricAxis(x, (0.0, 5.5)).closed


def test_closed_true_on_an_open_arc_says_how_far_apart_the_ends_are():
    with pytest.raises(ParameterError, match=r"^closed = true, but the axis' ends are 2 apart"):
        ParametricAxis(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), (0.0, math.pi), closed=True)


def test_closed_true_on_ends_meeting_at_a_corner_says_the_tangents_differ():
    """x = sin t, y = sin t cos t, t in [0, pi]: a teardrop whose ends meet at the origin with
    tangents (1, 1) and (-1, 1), 90 deg apart."""

    def teardrop(t):
        return np.stack([np.sin(t), np.sin(t) * np.cos(t), 0 * t], -1)

    assert not ParametricAxis(teardrop, (0.0, math.pi)).closed  # detected: not a loop
    with pytest.raises(
        ParameterError,
        match=r"^closed = true, but the tangents at the axis' ends differ by 90 deg: "
        r"the closing rings would not lie in one plane",
    ):
        ParametricAxis(teardrop, (0.0, math.pi), closed=True)


def test_closed_must_be_a_boolean():
    with pytest.raises(ParameterError, match="closed must be true or false"):
        ParametricAxis(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), (0.0, TWO_PI), closed="yes")
    with pytest.raises(ParameterError, match="closed must be true or false"):
        points_axis(LOOP, closed=1)
    with pytest.raises(ParameterError, match="closed must be true or false"):
        RouteAxis(SQUARE, 2.0, closed="no")


# ---------------------------------------------------------------------------------------------
# points


def loop_points(n: int = 7) -> np.ndarray:
    a = np.linspace(0.0, TWO_PI, n, endpoint=False)
    return np.stack(
        [(40 + 8 * np.cos(3 * a)) * np.cos(a), (40 + 8 * np.cos(3 * a)) * np.sin(a), 12 * np.sin(2 * a)], -1
    )


LOOP = loop_points()


def test_a_closed_polygon_of_points_gives_a_periodic_spline():
    axis = points_axis(np.vstack([LOOP, LOOP[:1]]))
    assert axis.closed
    assert axis.describe()["interpolation"] == "periodic cubic spline (C2, closed), centripetal parameterisation"
    assert axis.describe()["closed"] is True
    ends = axis.at(np.array(axis.span))
    assert np.abs(ends.position[1] - ends.position[0]).max() < 1e-12 * axis.length
    assert np.abs(ends.t[1] - ends.t[0]).max() < 1e-12
    # C2 all round: the curvature vector t' agrees too (a not-a-knot spline's would not)
    assert (
        np.abs(ends.curvature_vector[1] - ends.curvature_vector[0]).max() < 1e-9 * np.abs(ends.curvature_vector).max()
    )
    assert axis.curvature(np.array(axis.span)) == pytest.approx(axis.curvature(np.array(axis.span[::-1])), rel=1e-9)
    # it passes through every point: the first at s = 0, the others at the knots (its joints, C1 frame)
    knots = np.array([0.0] + [s for s, continuity in axis.joints if continuity == 1])
    assert len(knots) == len(LOOP)
    assert np.abs(axis.position(knots) - LOOP).max() < 1e-12 * axis.length
    # and stays near the polygon between them (no loop or overshoot)
    s = np.linspace(*axis.span, 2001)
    assert np.linalg.norm(axis.position(s), axis=1).max() < 1.1 * np.linalg.norm(LOOP, axis=1).max()


def test_closed_true_without_repeating_the_first_point_gives_the_same_axis():
    repeated, appended = points_axis(np.vstack([LOOP, LOOP[:1]])), points_axis(LOOP, closed=True)
    assert appended.closed and appended.length == pytest.approx(repeated.length, rel=1e-14)
    s = np.linspace(*repeated.span, 101)
    assert np.abs(appended.position(s) - repeated.position(s)).max() < 1e-12 * repeated.length
    assert appended.holonomy == pytest.approx(repeated.holonomy, abs=1e-12)


def test_open_points_and_closed_false_keep_the_not_a_knot_spline():
    assert not points_axis(LOOP).closed
    kept = points_axis(np.vstack([LOOP, LOOP[:1]]), closed=False)
    assert not kept.closed and kept.describe()["interpolation"].endswith("not-a-knot ends")
    ends = kept.at(np.array(kept.span))
    assert np.linalg.norm(ends.position[1] - ends.position[0]) < 1e-12 * kept.length  # the ends meet, with a kink
    assert np.linalg.norm(ends.t[1] - ends.t[0]) > 1e-3


def test_a_loop_of_points_needs_three_distinct_points():
    with pytest.raises(ParameterError, match="a closed loop of points needs 3 or more distinct points, got 2"):
        points_axis([[0, 0, 0], [1, 0, 0], [0, 0, 0]])


# ---------------------------------------------------------------------------------------------
# routes

SIDE, BEND = 100.0, 15.0
SQUARE = [[0, 0, 0], [SIDE, 0, 0], [SIDE, SIDE, 0], [0, SIDE, 0]]


def test_a_closed_square_route():
    axis = RouteAxis(SQUARE + [SQUARE[0]], BEND)
    assert axis.closed
    assert axis.length == pytest.approx(4 * (SIDE - 2 * BEND) + TWO_PI * BEND, rel=1e-14)
    assert axis.holonomy == 0.0 or abs(axis.holonomy) < 1e-14
    assert [p.kind for p in axis.pieces] == ["line", "bend"] * 4
    assert [p.vertex for p in axis.pieces if p.kind == "bend"] == [1, 2, 3, 0]
    # it starts and ends where the bend at points[0] ends, on the leg points[0]-points[1]
    ends = axis.at(np.array(axis.span))
    assert np.abs(ends.position - [BEND, 0, 0]).max() < 1e-12 * SIDE
    assert np.abs(ends.t - [1, 0, 0]).max() < 1e-14
    assert axis.describe()["closed"] is True and axis.describe()["bend_radius"] == [BEND] * 4
    assert np.array_equal(axis.points, np.array(SQUARE + [SQUARE[0]], dtype=float))  # as given
    # closed = true closes it without the repeated point
    same = RouteAxis(SQUARE, BEND, closed=True)
    assert same.closed and same.length == pytest.approx(axis.length, rel=1e-15)
    # closed = false keeps an open route (its ends meet at points[0] with a corner)
    kept = RouteAxis(SQUARE + [SQUARE[0]], BEND, closed=False)
    assert not kept.closed and kept.length == pytest.approx(4 * SIDE - 3 * (2 - math.pi / 2) * BEND, rel=1e-14)


def rodrigues(v: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    k = axis / np.linalg.norm(axis)
    return v * math.cos(angle) + np.cross(k, v) * math.sin(angle) + k * (k @ v) * (1 - math.cos(angle))


def transported_holonomy(points: np.ndarray) -> float:
    """A normal of the leg points[0]-points[1] carried round the loop: on a line it stays,
    on a bend it turns with the tangent, by the turning angle about the binormal d_in x d_out."""
    n = len(points)
    d = [(points[(i + 1) % n] - points[i]) / np.linalg.norm(points[(i + 1) % n] - points[i]) for i in range(n)]
    v0 = np.cross(d[0], [0.3, 0.5, 0.8])
    v0 /= np.linalg.norm(v0)
    v = v0
    for i in list(range(1, n)) + [0]:  # the bends in the order the route meets them
        d_in, d_out = d[i - 1], d[i]
        v = rodrigues(v, np.cross(d_in, d_out), math.acos(np.clip(d_in @ d_out, -1, 1)))
    return math.atan2(v @ np.cross(d[0], v0), v @ v0)


def test_a_closed_skew_route_comes_back_turned_by_its_parallel_transport():
    points = np.array([[0, 0, 0], [400, 0, 0], [400, 300, 0], [400, 300, 250], [0, 300, 250]], dtype=float)
    axis = RouteAxis(points, [60, 60, 80, 60, 50], closed=True)
    assert axis.closed
    expected = transported_holonomy(points)
    assert abs(expected) > 0.1
    assert abs(wrapped(axis.holonomy - expected)) < 1e-12
    ends = axis.at(np.array(axis.span))
    assert np.abs(ends.position[1] - ends.position[0]).max() < 1e-12 * axis.length
    assert np.abs(ends.t[1] - ends.t[0]).max() < 1e-13
    # r1 comes back turned by the holonomy about t
    a = axis.holonomy
    assert np.abs(ends.r1[1] - (math.cos(a) * ends.r1[0] + math.sin(a) * ends.r2[0])).max() < 1e-13


def test_the_fitting_takes_a_closed_route_frame_exactly():
    from tubecad.fitting.route_frame import route_frame

    axis = RouteAxis(
        np.array([[0, 0, 0], [400, 0, 0], [400, 300, 0], [400, 300, 250], [0, 300, 250]]), 60.0, closed=True
    )
    frame = route_frame(axis, 20.0, rings=np.linspace(*axis.span, 7), radii=(18.0, 20.0))
    assert frame.position_bound < 1e-9 and frame.orthogonality_bound < 1e-12


def test_closed_route_errors_name_the_users_points():
    with pytest.raises(ParameterError, match=r"^a closed route needs 3 or more distinct points, got 2$"):
        RouteAxis([[0, 0, 0], [100, 0, 0]], 5.0, closed=True)
    with pytest.raises(ParameterError, match=r"^a closed route needs 3 or more distinct points, got 2$"):
        RouteAxis([[0, 0, 0], [100, 0, 0], [0, 0, 0]], 5.0)
    with pytest.raises(
        ParameterError,
        match=r"^bend_radius must be one number or 4 \(one per vertex of the loop "
        r"points\[0\]\.\.points\[3\]\), got 3$",
    ):
        RouteAxis(SQUARE + [SQUARE[0]], [5.0, 5.0, 5.0])
    with pytest.raises(ParameterError, match=r"^bend_radius at points\[0\] must be a finite number > 0"):
        RouteAxis(SQUARE, [-1.0, 5.0, 5.0, 5.0], closed=True)
    # points[0] on the line points[3]-points[1]: no bend there
    with pytest.raises(
        ParameterError,
        match=r"^points\[0\] \[0, 0, 0\] makes no bend: points\[3\], points\[0\] and "
        r"points\[1\] are collinear",
    ):
        RouteAxis([[0, 0, 0], [100, 0, 0], [100, 100, 0], [-100, 0, 0]], 5.0, closed=True)
    # the closing leg points[3]-points[0] cannot hold the bends at both its ends
    with pytest.raises(
        ParameterError,
        match=r"^bend_radius 90 at points\[0\] \[0, 0, 0\] does not fit: the leg "
        r"points\[3\]-points\[0\] is 100 long but its bends need 20 \(the bend at "
        r"points\[3\]\) \+ 90 \(the bend at points\[0\]\)",
    ):
        RouteAxis(SQUARE, [90, 5, 5, 20], closed=True)
    # a bend not above the tube radius, named by the user's vertex
    assert (
        RouteAxis(SQUARE, [4, 6, 6, 6], closed=True)
        .tube_radius_problem(5.0)
        .startswith("tube is not regular: the bend at points[0] [0, 0, 0] has bend_radius 4")
    )


def test_open_route_messages_are_unchanged():
    with pytest.raises(
        ParameterError,
        match=r"^bend_radius must be one number or 2 \(one per inner vertex "
        r"points\[1\]\.\.points\[2\]\), got 3$",
    ):
        RouteAxis(SQUARE, [5.0, 5.0, 5.0])
    assert not RouteAxis(SQUARE, 5.0).closed and "closed" not in RouteAxis(SQUARE, 5.0).describe()


# ---------------------------------------------------------------------------------------------
# CAD edges


def test_a_periodic_spline_edge_and_a_closed_wire_are_closed():
    bd = pytest.importorskip("build123d")
    from tubecad.curves.edge import edge_axis

    spline = edge_axis(bd.Spline((0, 0, 0), (60, 25, 10), (120, 10, 45), (80, -30, 40), (20, -20, 5), periodic=True))
    assert spline.closed and spline.describe()["closed"] is True
    r = 5.0  # a stadium: two lines and two half circles, G1 where they meet
    wire = bd.Wire(
        [
            bd.Line((0, 0), (20, 0)),
            bd.CenterArc((20, r), r, 270, 180),
            bd.Line((20, 2 * r), (0, 2 * r)),
            bd.CenterArc((0, r), r, 90, 180),
        ]
    )
    stadium = edge_axis(wire)
    assert stadium.closed and stadium.length == pytest.approx(40 + TWO_PI * r, rel=1e-12)
    assert abs(stadium.holonomy) < 1e-12
    with pytest.raises(ParameterError, match="closed = true, but the axis' ends are"):
        edge_axis(bd.Edge.make_circle(10, start_angle=0, end_angle=90), closed=True)


# ---------------------------------------------------------------------------------------------
# spec files


def test_the_closed_samples_are_closed():
    knot = load_spec(SAMPLES / "trefoil_closed.toml").axis
    assert knot.closed and knot.describe()["closed"] is True
    route = load_spec(SAMPLES / "route_closed.toml").axis
    assert route.closed and route.describe()["closed"] is True and len(route.bend_radii) == 5
