"""Closed tubes (issue 11 item 3): no caps, the rotation-minimising frame comes back turned by
the holonomy, the stringers meet the closing ring shifted by it, and the shell, solid and
wall are valid closed B-reps with shared edges.

Independent facts: a circle's tube is the torus (sqrt(x^2 + y^2) - R)^2 + z^2 = rho^2 with
volume 2 pi^2 R rho^2 (Pappus); a tube's volume is pi rho^2 L whatever its axis, closed or
not; a trefoil's holonomy is minus its total torsion mod 2 pi (quadrature of the Frenet
torsion of the closed-form curve, not the code's frame).
"""

import math

import build123d as bd
import numpy as np
import pytest
from OCP.TopAbs import TopAbs_SHELL
from OCP.TopExp import TopExp_Explorer
from scipy.integrate import quad

from tubecad.brep import NetLayout, build_tube_shell, build_tube_solid, build_wall_solid
from tubecad.brep import properties as props
from tubecad.curves.parametric import ParametricAxis
from tubecad.curves.route import RouteAxis
from tubecad.errors import ParameterError
from tubecad.stiffeners.assembly import build_stiffeners
from tubecad.stiffeners.profiles import Profile
from tubecad.surface import CurvatureLineTube

TWO_PI = 2 * math.pi
#: every check of OCCT's pre-boolean analyzer but the self-intersection one (tens of seconds
#: on these walls; the faces are cut at the closing ring, which the other checks cover)
CHECKS = tuple(mode for mode in props.ANALYZER_MODES if mode != "SelfInterMode")
R_TORUS, RHO_TORUS = 10.0, 1.0


def circle(t: np.ndarray) -> np.ndarray:
    return np.stack([R_TORUS * np.cos(t), R_TORUS * np.sin(t), 0.0 * t], axis=-1)


def trefoil(t: np.ndarray) -> np.ndarray:
    return np.stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)], axis=-1)


def trefoil_derivatives(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x', x'', x''' of the trefoil, by hand."""
    d1 = np.array([math.cos(t) + 4 * math.cos(2 * t), -math.sin(t) + 4 * math.sin(2 * t), -3 * math.cos(3 * t)])
    d2 = np.array([-math.sin(t) - 8 * math.sin(2 * t), -math.cos(t) + 8 * math.cos(2 * t), 9 * math.sin(3 * t)])
    d3 = np.array([-math.cos(t) - 16 * math.cos(2 * t), math.sin(t) - 16 * math.sin(2 * t), 27 * math.cos(3 * t)])
    return d1, d2, d3


def shells(shape) -> int:
    explorer, n = TopExp_Explorer(props.topods(shape), TopAbs_SHELL), 0
    while explorer.More():
        n += 1
        explorer.Next()
    return n


@pytest.fixture(scope="module")
def torus_tube() -> CurvatureLineTube:
    axis = ParametricAxis(circle, (0.0, TWO_PI))
    assert axis.closed and abs(axis.holonomy) < 1e-12  # a planar loop: the frame closes
    return CurvatureLineTube(axis, RHO_TORUS)


@pytest.fixture(scope="module")
def trefoil_tube() -> CurvatureLineTube:
    return CurvatureLineTube(ParametricAxis(trefoil, (0.0, TWO_PI)), 0.3)


@pytest.mark.parametrize("stringers", [1, 4])
def test_the_closed_tube_of_a_circle_is_the_torus(torus_tube, stringers):
    build = build_tube_solid(torus_tube, NetLayout.equal(torus_tube, 5, stringers))
    shape = build.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.count(shape, "face") == 4 * stringers  # no caps; the closing ring joins the last band to the first
    assert props.count(shape, "vertex") == 4 * stringers  # holonomy 0: every stringer ends where it started
    assert props.volume(shape) == pytest.approx(2 * math.pi**2 * R_TORUS * RHO_TORUS**2, rel=1e-10)
    for face in shape.faces():  # every point of every face on the torus
        for u in np.linspace(0.05, 0.95, 5):
            for v in np.linspace(0.0, 1.0, 5):
                x, y, z = face.position_at(u, v)
                assert abs((math.hypot(x, y) - R_TORUS) ** 2 + z**2 - RHO_TORUS**2) < 2e-8 * RHO_TORUS


def test_a_closed_tube_shell_is_closed(trefoil_tube):
    shell = build_tube_shell(trefoil_tube, NetLayout.equal(trefoil_tube, 5, 3)).shape
    assert props.is_valid(shell) and props.free_edges(shell) == 0 and shell.wrapped.Closed()


def test_the_trefoil_wall_is_a_valid_solid_with_a_cavity(trefoil_tube):
    rings, stringers = 9, 4
    build = build_wall_solid(trefoil_tube, 0.06, "centered", NetLayout.equal(trefoil_tube, rings, stringers))
    shape = build.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.analyzer_findings(shape, CHECKS) == {}
    assert shells(shape) == 2 and props.count(shape, "face") == 2 * (rings - 1) * stringers
    length = trefoil_tube.length
    assert props.volume(shape) == pytest.approx(math.pi * (0.33**2 - 0.27**2) * length, rel=1e-9)


def test_the_stringers_meet_the_closing_ring_turned_by_minus_the_total_torsion(trefoil_tube):
    """Stringer j leaves the closing ring at angle th_j (from r1(0)) and comes back to it at
    th_j + h: its end vertex is the exact tube point S(th_j, L) and lies on the ring circle at
    s = 0 at that angle, with h = -Int tau ds mod 2 pi from the closed-form trefoil."""
    axis = trefoil_tube.axis
    total, _ = quad(lambda t: (lambda d: float(np.cross(d[0], d[1]) @ d[2] / np.sum(np.cross(d[0], d[1]) ** 2)
                                             * np.linalg.norm(d[0])))(trefoil_derivatives(t)),
                    0.0, TWO_PI, limit=400, epsabs=1e-13, epsrel=1e-13)  # fmt: skip
    holonomy = math.remainder(-total, TWO_PI)
    assert abs(math.remainder(axis.holonomy - holonomy, TWO_PI)) < 1e-9
    layout = NetLayout.equal(trefoil_tube, 5, 4)
    build = build_tube_solid(trefoil_tube, layout)
    L = axis.span[1]
    start = axis.at(np.array([0.0]))
    c0, r1, r2 = start.position[0], start.r1[0], start.r2[0]
    for wire, theta_deg in zip(build.stringer_wires(), layout.stringers_deg):
        end = np.array(tuple(wire.edges()[-1].position_at(1.0)))
        exact = trefoil_tube.points(np.array(math.radians(theta_deg)), np.array(L))
        assert np.linalg.norm(end - exact) < 1e-8
        turned = math.radians(theta_deg) + holonomy
        on_ring = c0 + 0.3 * (math.cos(turned) * r1 + math.sin(turned) * r2)
        assert np.linalg.norm(end - on_ring) < 1e-8
    # the closing ring is cut at both the starts and the (shifted) ends: 8 arcs, shared by 8 faces
    assert props.count(build.shape, "vertex") == (5 - 2) * 4 + 8


def test_a_closed_tube_needs_a_ring_besides_the_closing_one(torus_tube):
    with pytest.raises(ParameterError, match="rings must be >= 3"):
        build_tube_solid(torus_tube, NetLayout.equal(torus_tube, 2, 4))


def test_stiffeners_on_a_closed_wall(trefoil_tube):
    """Rings (the closing ring one solid, not two halves) and stringers that end on the closing
    ring at their shifted angle: each a valid solid fit for booleans."""
    layout = NetLayout.equal(trefoil_tube, 5, 4)
    wall = build_wall_solid(trefoil_tube, 0.04, "centered", layout)
    profile = Profile("T", 0.15, 0.02, 0.08, 0.015)
    stiffeners = build_stiffeners(wall, [0, 2, 4], [0, 1, 2, 3], profile, "outside")
    assert [st.name for st in stiffeners] == ["ring_00", "ring_02", "stringer_00", "stringer_01", "stringer_02",
                                              "stringer_03"]  # ring 4 is ring 0  # fmt: skip
    for st in stiffeners:
        assert props.is_valid(st.solid) and props.analyzer_findings(st.solid, CHECKS) == {}, st.name
    closing, middle = (props.volume(st.solid) for st in stiffeners[:2])
    assert closing == pytest.approx(middle, rel=1e-9)  # the two halves make one whole ring


def closed_square_route(side: float = 40.0, bend: float = 5.0) -> RouteAxis:
    return RouteAxis([[0, 0, 0], [side, 0, 0], [side, side, 0], [0, side, 0], [0, 0, 0]], bend)


def test_stringers_on_a_planar_loop_close_on_themselves():
    """A planar closed route: holonomy 0, so a stringer comes back onto its own start and is
    one ring-like solid without caps, whose volume is its section's area times the path of
    its centroid (Pappus)."""
    axis = closed_square_route()
    assert axis.closed and abs(axis.holonomy) < 1e-12
    tube = CurvatureLineTube(axis, 2.0)
    wall = build_wall_solid(tube, 0.2, "centered", NetLayout.equal(tube, 5, 8))  # 8: GProp is exact on 45 deg arcs
    assert props.is_valid(wall.shape) and props.analyzer_findings(wall.shape, CHECKS) == {}
    assert props.volume(wall.shape) == pytest.approx(math.pi * (2.1**2 - 1.9**2) * axis.length, rel=1e-10)
    profile = Profile("flat", 0.8, 0.2)
    [stringer] = build_stiffeners(wall, [], [1], profile, "outside")
    assert props.is_valid(stringer.solid) and props.analyzer_findings(stringer.solid) == {}
    planar = [f for f in stringer.solid.faces() if f.geom_type == "PLANE" or str(f.geom_type).endswith("PLANE")]
    assert planar == [] and props.free_edges(stringer.solid) == 0
    # Pappus, bend by bend: a section of area A whose centroid lies c_n inward of the axis
    # sweeps A (R_b - c_n) phi_b round each bend and A l along each line, so on a convex
    # planar loop (sum phi_b = 2 pi) V = A (L - 2 pi c_n). The section is cut mid-leg, where
    # the axis is (20, 0, 0), its tangent +x and the inward normal +y.
    [section] = stringer.solid.intersect(bd.Face.make_rect(40, 40, bd.Plane(origin=(20, 0, 0), z_dir=(1, 0, 0)))).faces()
    area, centroid = section.area, section.center()
    assert abs(centroid.X - 20) < 1e-9
    assert props.volume(stringer.solid) == pytest.approx(area * (axis.length - TWO_PI * centroid.Y), rel=1e-9)


def test_a_stringer_that_would_touch_its_own_start_is_refused():
    """A closed loop slightly out of plane: the frame comes back turned by a small holonomy,
    less than the stringer's width seen from the axis, so its end would overlap its start."""
    axis = RouteAxis([[0, 0, 0], [40, 0, 0], [40, 40, 1.0], [0, 40, 3.0], [0, 0, 0]], 5.0)
    turn = abs(math.degrees(axis.holonomy))
    assert 1e-3 < turn < 1
    tube = CurvatureLineTube(axis, 2.0)
    wall = build_wall_solid(tube, 0.2, "centered", NetLayout.equal(tube, 5, 4))
    with pytest.raises(ParameterError, match=r"stringer_01 would touch its own start .* holonomy"):
        build_stiffeners(wall, [], [1], Profile("T", 0.8, 0.2, 0.6, 0.1), "outside")


SMALL_CLOSED_SPEC = """
[axis]
curve = "parametric"
x = "sin(t) + 2 * sin(2 * t)"
y = "cos(t) - 2 * cos(2 * t)"
z = "-sin(3 * t)"
t = [0.0, 6.283185307179586]

[tube]
radius = 0.3

[layout]
rings = 5
stringers = 4

[wall]
thickness = 0.04

[stiffeners]
rings = "all"
stringers = [0, 2]
profile = "flat"
height = 0.1
thickness = 0.02
"""


def test_build_a_closed_wall_with_stiffeners_to_step_and_a_closed_mesh(tmp_path):
    """`tubecad build`: the named STEP reads back valid (wall, one closing ring, the others,
    stringers), the report gives the holonomy, and the wall's STL (BRepMesh) is closed: each
    edge shared by two triangles, its signed volume the wall's."""
    import json

    from click.testing import CliRunner

    from tubecad.export.cad import import_shape
    from tubecad.export.mesh import read_mesh_triangles
    from tubecad.interfaces.cli import cli

    spec = tmp_path / "closed.toml"
    spec.write_text(SMALL_CLOSED_SPEC)
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(tmp_path / "c.step"), "--report",
                                      str(tmp_path / "r.json"), "-q"])  # fmt: skip
    assert result.exit_code == 0, result.output
    plain = tmp_path / "plain.toml"  # the wall alone: the stiffeners' meshes touch it
    plain.write_text(SMALL_CLOSED_SPEC.split("[stiffeners]")[0])
    result = CliRunner().invoke(cli, ["build", str(plain), "-o", str(tmp_path / "c.stl"), "--mesh-tolerance", "0.003", "-q"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["closed"] is True and report["holonomy_deg"] == pytest.approx(-127.485438056, abs=1e-6)
    assert report["brep"]["valid"] and report["brep"]["free_edges"] == 0
    shape = import_shape(tmp_path / "c.step")
    assert props.is_valid(shape) and props.count(shape, "solid") == 1 + 4 + 2  # wall, rings 0-3, 2 stringers
    vertices, triangles = read_mesh_triangles(tmp_path / "c.stl", "stl")
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses) == {2}
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    length = report["length"]
    assert volume == pytest.approx(math.pi * (0.32**2 - 0.28**2) * length, rel=5e-3)  # measured -3.1e-3: chords inside


def test_a_closing_with_a_kink_is_refused(tmp_path):
    """Ends that meet at a corner (the teardrop x = sin t, y = sin t cos t, whose tangents at
    t = 0 and pi differ): closed = true is refused in one line naming the key, no file."""
    from conftest import assert_build_refused

    text = ('[axis]\ncurve = "parametric"\nx = "10 * sin(t)"\ny = "10 * sin(t) * cos(t)"\nz = "0"\n'
            't = [0.0, 3.141592653589793]\nclosed = true\n[tube]\nradius = 0.5\n')  # fmt: skip
    assert_build_refused(tmp_path, text, "[axis] closed = true, but the tangents at the axis' ends differ by")


def test_a_periodic_build123d_spline_gives_a_closed_wall():
    """A closed spline Edge of a build123d model: its wall is closed, valid, of volume
    pi (R^2 - r^2) L."""
    from tubecad.curves.edge import edge_axis

    points = [(0, 0, 0), (30, 5, 4), (40, 30, -3), (10, 40, 6), (-10, 20, 0)]
    axis = edge_axis(bd.Spline(*points, periodic=True))
    assert axis.closed
    tube = CurvatureLineTube(axis, 2.0)
    wall = build_wall_solid(tube, 0.4, "centered", NetLayout.equal(tube, 5, 8))
    assert props.is_valid(wall.shape) and props.free_edges(wall.shape) == 0
    assert props.analyzer_findings(wall.shape, CHECKS) == {}
    assert props.volume(wall.shape) == pytest.approx(math.pi * (2.2**2 - 1.8**2) * axis.length, rel=1e-9)
