"""The route axis (issue 11): lines and circular bends, each piece of the tube an exact
cylinder or torus piece (rational in both directions), every line-bend joint a ring edge.

Tolerances are from measurements (build123d 0.12 / OCCT 7.9): faces' deviation from the
exact tube ~7e-14 and isoline |cos| ~2e-13 (dense sampling), wall volume ~3e-13 relative,
F = M = 0 on the exact grid ~1e-16. The sample built and read back, and bad routes refused,
from the command line: tests/e2e/test_cli_route.py."""

import math

import numpy as np
import pytest
from conftest import ROOT

from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep.measure import measure_tube_faces
from tubecad.brep.properties import ANALYZER_MODES, analyzer_findings, is_valid, volume
from tubecad.core.errors import ParameterError
from tubecad.curves.route import RouteAxis
from tubecad.fitting import fit_frame
from tubecad.fitting.frame_spline import exact_frame
from tubecad.surface import CurvatureLineTube

SAMPLES = ROOT / "samples"
#: bends in three planes: xy, then the plane of y and z, then the plane of z and (1, 1, 0)
POINTS = [[0, 0, 0], [300, 0, 0], [300, 250, 0], [300, 250, 200], [450, 400, 200]]
RADII = [60, 60, 80]


@pytest.fixture(scope="module")
def route() -> RouteAxis:
    return RouteAxis(POINTS, RADII)


@pytest.fixture(scope="module")
def wall(route):
    tube = CurvatureLineTube(route, 20.0)
    return tube, build_wall_solid(tube, 2.0, side="inside", layout=NetLayout.equal(tube, 7, 8))


def test_pieces_and_joints(route):
    kinds = [p.kind for p in route.pieces]
    assert kinds == ["line", "bend", "line", "bend", "line", "bend", "line"]
    # bend at vertex 1 turns 90 deg with R = 60: tangent length 60, the first line 300 - 60 long
    assert route.pieces[0].s1 == pytest.approx(240.0, abs=1e-12)
    assert route.pieces[1].s1 - route.pieces[1].s0 == pytest.approx(60 * math.pi / 2, abs=1e-12)
    assert [s for s, _ in route.joints] == [p.s0 for p in route.pieces[1:]]
    assert {c for _, c in route.joints} == {0}
    # the route passes through the tangent points and ends at the last point
    assert np.allclose(
        route.position(np.array([0.0, 240.0, route.span[1]])), [[0, 0, 0], [240, 0, 0], POINTS[-1]], atol=1e-12
    )


def test_frame_is_the_closed_form_rmf(route):
    """Away from the joints: c' = t, r1' = -k1 t, r2' = -k2 t (central differences), the
    frame orthonormal, and at the joints the frame continuous (stringers continue)."""
    h = 1e-4
    for piece in route.pieces:
        s = np.linspace(piece.s0 + 10 * h, piece.s1 - 10 * h, 50)
        t, r1, r2 = route.rotation_minimising_frame(s)
        k1, k2 = route.normal_development(s)
        diff = lambda f: (f(s + h) - f(s - h)) / (2 * h)
        assert np.abs(diff(route.position) - t).max() < 1e-7
        assert np.abs(diff(lambda x: route.rotation_minimising_frame(x)[1]) + k1[:, None] * t).max() < 1e-7
        assert np.abs(diff(lambda x: route.rotation_minimising_frame(x)[2]) + k2[:, None] * t).max() < 1e-7
        gram = np.einsum("nij,nkj->nik", np.stack([t, r1, r2], axis=1), np.stack([t, r1, r2], axis=1))
        assert np.abs(gram - np.eye(3)).max() < 1e-15 * 10
        if piece.kind == "bend":
            assert np.hypot(k1, k2) == pytest.approx(1 / piece.radius, rel=1e-14)
        else:
            assert not k1.any() and not k2.any()
    for s, _ in route.joints:
        before, after = (np.stack(route.rotation_minimising_frame(np.array([x]))) for x in (s - 1e-9, s + 1e-9))
        assert np.abs(after - before).max() < 1e-10  # C0 frame: the RMF does not jump


def test_a_bend_is_a_torus_piece_and_a_line_a_cylinder(route):
    rho = 20.0
    tube = CurvatureLineTube(route, rho)
    u = np.linspace(0, 2 * math.pi, 37)
    for piece in route.pieces:
        s = np.linspace(piece.s0, piece.s1, 41)
        X = tube.grid(u, s).reshape(-1, 3)
        if piece.kind == "bend":
            b = np.cross(piece.e1, piece.direction)
            rel = X - piece.centre
            z = rel @ b
            in_plane = np.linalg.norm(rel - z[:, None] * b, axis=1)
            residual = (in_plane - piece.radius) ** 2 + z**2 - rho**2  # the torus equation
            assert np.abs(residual).max() < 1e-10 * rho**2
        else:
            rel = X - piece.start
            radial = rel - (rel @ piece.direction)[:, None] * piece.direction
            assert np.abs(np.linalg.norm(radial, axis=1) - rho).max() < 1e-12 * rho


def test_fundamental_forms_on_the_exact_grid(route):
    tube = CurvatureLineTube(route, 20.0)
    u = np.linspace(0, 2 * math.pi, 48)[:, None]
    s = np.linspace(*route.span, 4001)[None]  # straight runs, bends and joints
    f = tube.fundamental_forms(u, s)
    assert np.abs(f.F).max() < 1e-10 and np.abs(f.M).max() < 1e-10
    assert f.orthogonality_error.max() < 1e-10


def test_the_frame_is_exact_and_rational(route):
    """The route's frame is no fit: a rational quadratic with v = s at every break."""
    rings = np.linspace(*route.span, 7)
    frame = fit_frame(route, 20.0, rings=rings)
    assert frame.rational and frame.degree == 2
    assert frame.position_bound < 1e-12 and frame.orthogonality_bound < 1e-12
    breaks = np.unique(np.concatenate([rings, [s for s, _ in route.joints]]))
    assert np.abs(frame.arc_length(breaks) - breaks).max() < 1e-12
    v = np.linspace(*route.span, 5001)
    F, _ = exact_frame(route, frame.arc_length(v))
    assert np.abs(frame.values(v) - F).max() < 1e-12 * 1000
    assert np.abs(frame.parameter(frame.arc_length(v)) - v).max() < 1e-9


def test_joints_are_ring_edges_and_layout_rings_are_added(wall, route):
    tube, build = wall
    joints = [s for s, _ in route.joints]
    equal = np.linspace(*route.span, 7)
    assert np.allclose(build.layout.s_rings, np.unique(np.concatenate([equal, joints])), atol=1e-12)
    for s in joints:
        i = int(np.argmin(np.abs(np.array(build.layout.s_rings) - s)))
        centre = route.position(np.array([s]))[0]
        for surface, radius in ((0, 20.0), (1, 18.0)):
            for edge in build.ring_wires(surface)[i].edges():
                assert edge.geom_type.name == "CIRCLE" and edge.radius == pytest.approx(radius, abs=1e-12)
                assert np.allclose(tuple(edge.arc_center), centre, atol=1e-9)


def test_stringers_continue_across_joints(wall, route):
    """The stringer edges meet at each joint with the same tangent (the RMF is continuous)."""
    _, build = wall
    for wire in build.stringer_wires(0):
        edges = wire.edges()
        for a, b in zip(edges[:-1], edges[1:]):
            assert (a @ 1) == pytest.approx(b @ 0, abs=1e-9)
            ta, tb = np.array(tuple(a % 1)), np.array(tuple(b % 0))
            assert np.linalg.norm(np.cross(ta, tb)) < 1e-9


@pytest.mark.slow
def test_wall_faces_are_exact_valid_and_fit_for_booleans(wall, route):
    tube, build = wall
    m = measure_tube_faces(build.shape, route, build.radii, samples=20000)
    assert m.faces == 2 * 12 * 8 and m.skipped == 0
    assert m.max_deviation < 1e-12 and m.max_orthogonality < 1e-11
    assert is_valid(build.shape)
    assert analyzer_findings(build.shape) == {}
    assert analyzer_findings(build.shape, ANALYZER_MODES[:3]) == {}
    exact = math.pi * (20.0**2 - 18.0**2) * route.length
    assert abs(volume(build.shape) - exact) < 1e-11 * exact


def test_bend_radius_per_vertex_and_a_straight_route():
    straight = RouteAxis([[0, 0, 0], [0, 0, 100]], 5.0)
    assert straight.joints == () and straight.length == pytest.approx(100.0)
    with pytest.raises(ParameterError, match=r"bend_radius must be one number or 3 \(one per inner vertex"):
        RouteAxis(POINTS, [60, 60])


TUBE = "[tube]\nradius = 5.0\n"


def test_points_from_a_csv_file(tmp_path):
    from tubecad.spec.parse import load_spec

    (tmp_path / "route.csv").write_text("x,y,z\n" + "\n".join(",".join(map(str, p)) for p in POINTS) + "\n")
    spec = tmp_path / "s.toml"
    spec.write_text('[axis]\ncurve = "route"\nfile = "route.csv"\nbend_radius = [60, 60, 80]\n' + TUBE)
    axis = load_spec(spec).axis
    assert isinstance(axis, RouteAxis) and axis.length == pytest.approx(RouteAxis(POINTS, RADII).length, abs=1e-12)


@pytest.mark.slow
def test_stiffeners_across_the_joints_are_fit_for_booleans(wall, route):
    """A stringer runs across every line-bend joint, where the frame is only C0: its faces
    end there (and its edges' curves with them), so OCCT's pre-boolean check finds nothing."""
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.profiles import Profile

    _, build = wall
    profile = Profile("T", 8.0, 1.0, 5.0, 1.0)
    stiffeners = build_stiffeners(build, [3], [0, 3], profile, "outside")
    joints = sum(1 for _, continuity in route.joints if continuity == 0)
    for st in stiffeners:
        assert is_valid(st.solid) and analyzer_findings(st.solid) == {}, st.name
    stringer = stiffeners[1]
    sides = len(profile.outline())  # the outline's sides and the base under the web
    assert len(stringer.solid.faces()) == sides * (joints + 1) + 2  # each side cut at every joint; 2 caps


def test_a_stringers_length_on_a_route_is_exact(wall, route):
    """Int sqrt(G) ds along u = th: per piece (1 - rho (k1 cos th + k2 sin th)) x its length,
    k1, k2 constant on a bend and 0 on a line (the quadrature must not run across a joint)."""
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.profiles import Profile

    tube, build = wall
    [stringer] = build_stiffeners(build, [], [1], Profile("flat", 4.0, 1.0), "outside")
    th = math.radians(build.layout.stringers_deg[1])
    exact = 0.0
    for piece in route.pieces:
        k1, k2 = route.normal_development(np.array([0.5 * (piece.s0 + piece.s1)]))
        exact += (piece.s1 - piece.s0) * (1.0 - 20.0 * (k1[0] * math.cos(th) + k2[0] * math.sin(th)))
    assert stringer.length() == pytest.approx(exact, rel=1e-13)


def test_a_ring_on_a_joint_is_fit_for_booleans(wall, route):
    """A ring frame centred on a line-bend joint straddles it: its tube faces end at the
    joint, so OCCT's pre-boolean check (FreeCAD's) finds no C0 face or edge."""
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.profiles import Profile

    _, build = wall
    on_joint = [i for i, s in enumerate(build.layout.s_rings) if any(abs(s - j) < 1e-9 for j, _ in route.joints)]
    assert on_joint
    [ring] = build_stiffeners(build, on_joint[:1], [], Profile("T", 8.0, 1.0, 5.0, 1.0), "outside")
    assert is_valid(ring.solid) and analyzer_findings(ring.solid) == {}
    R, h, tw, bf, tf = 20.0, 8.0, 1.0, 5.0, 1.0  # web R..R+h-tf wide tw, flange R+h-tf..R+h wide bf
    exact = math.pi * (((R + h - tf) ** 2 - R**2) * tw + ((R + h) ** 2 - (R + h - tf) ** 2) * bf)
    assert volume(ring.solid) == pytest.approx(exact, rel=1e-9)


def test_panels_across_joints_are_fit_for_booleans(wall, route):
    """Panels between rings 0 and the last (every joint inside them): faces end at the joints."""
    from tubecad.stiffeners.panels import split_into_panels

    tube, build = wall
    panels = split_into_panels(build, [0, 4], [0, len(build.layout.s_rings) - 1])
    assert len(panels) == 2
    for panel in panels:
        assert is_valid(panel.solid) and analyzer_findings(panel.solid, ANALYZER_MODES[2:]) == {}, panel.name
    total = sum(volume(p.solid) for p in panels)
    assert total == pytest.approx(math.pi * (20.0**2 - 18.0**2) * route.length, rel=1e-9)
    # each panel's outer area: half the outer tube's, 2 pi R L / 2 (the stringers at 0 and 180 deg halve it
    # only on average: the bends' inner and outer halves differ), so their sum is the whole
    assert sum(p.outer_area for p in panels) == pytest.approx(2 * math.pi * 20.0 * route.length, rel=1e-9)


def test_a_straight_bay_of_a_route_is_meshed_as_straight(wall, route):
    """A line's ring bay needs one row of triangles along s whatever the bends beside it
    (the bend's curvature at the joint must not refine it)."""
    from tubecad.export.tessellate import grid_arcs

    tube, build = wall
    rings = build.layout.s_rings
    lines = [(p.s0, p.s1) for p in route.pieces if p.kind == "line"]
    rows = grid_arcs(route, rings, 20.0, 0.02, math.radians(5.0))
    for (a, b), bay in zip(zip(rings[:-1], rings[1:]), rows):
        if any(lo - 1e-9 <= a and b <= hi + 1e-9 for lo, hi in lines):
            assert len(bay) == 2, (a, b)
