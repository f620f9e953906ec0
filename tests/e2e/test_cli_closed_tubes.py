"""Closed tubes (issue 11 item 3) from the command line: `tubecad build` of a closed trefoil
wall with stiffeners to a named STEP and a closed STL mesh on the curvature-line grid; a
closing with a kink refused in one line.

Independent facts: a tube's volume is pi rho^2 L whatever its axis, closed or not; the
mesh's triangles are counted from the step rules alone.
"""

import math

import pytest
from shared.closed_tubes import TWO_PI, closed_mesh, grid_counts, on_closing_ring, trefoil

from tubecad.brep import NetLayout
from tubecad.brep import properties as props
from tubecad.curves.parametric import ParametricAxis
from tubecad.surface import CurvatureLineTube

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
rings = 4
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


@pytest.mark.slow
def test_build_a_closed_wall_with_stiffeners_to_step_and_a_closed_mesh(tmp_path):
    """`tubecad build`: the named STEP reads back valid (wall, one closing ring, the others,
    stringers) and the report gives the holonomy. The wall's STL, closed and holding its
    volume, is the next test's (test_a_closed_wall_meshes_on_its_grid_closed_at_the_default_tolerance)."""
    import json

    from click.testing import CliRunner

    from tubecad.cli.app import cli
    from tubecad.export.cad import import_shape

    spec = tmp_path / "closed.toml"
    spec.write_text(SMALL_CLOSED_SPEC)
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-o", str(tmp_path / "c.step"), "--report", str(tmp_path / "r.json"), "-q"]
    )
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["closed"] is True and report["holonomy_deg"] == pytest.approx(-127.485438056, abs=1e-6)
    assert report["brep"]["valid"] and report["brep"]["free_edges"] == 0
    shape = import_shape(tmp_path / "c.step")
    assert props.is_valid(shape) and props.count(shape, "solid") == 1 + 4 + 2  # wall, rings 0-3, 2 stringers


def test_a_closing_with_a_kink_is_refused(tmp_path):
    """Ends that meet at a corner (the teardrop x = sin t, y = sin t cos t, whose tangents at
    t = 0 and pi differ): closed = true is refused in one line naming the key, no file."""
    from conftest import assert_build_refused

    text = (
        '[axis]\ncurve = "parametric"\nx = "10 * sin(t)"\ny = "10 * sin(t) * cos(t)"\nz = "0"\n'
        "t = [0.0, 3.141592653589793]\nclosed = true\n[tube]\nradius = 0.5\n"
    )
    assert_build_refused(tmp_path, text, "[axis] closed = true, but the tangents at the axis' ends differ by")


# --- closed meshes on the curvature-line grid (tubecad.export.tessellate) ------------------


@pytest.mark.slow
def test_a_closed_wall_meshes_on_its_grid_closed_at_the_default_tolerance(tmp_path):
    """`tubecad build -o x.stl` of the small closed trefoil wall at the default tolerance: the
    STL is closed (each edge shared by two triangles), its signed volume short of
    pi (R^2 - r^2) L by the chords (at least the ring polygon's deficit), and it has the open
    grid's triangles (2 per cell, from the step rules) plus one per extra node on the closing
    ring, which holds the columns and the columns turned by the holonomy, on both tubes."""
    import json

    from click.testing import CliRunner

    from tubecad.cli.app import cli
    from tubecad.export.mesh import read_mesh_triangles

    spec = tmp_path / "plain.toml"
    spec.write_text(SMALL_CLOSED_SPEC.split("[stiffeners]")[0])
    out = tmp_path / "x.stl"
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(out), "--report", str(tmp_path / "r.json"), "-q"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "r.json").read_text())
    mesh = report["exports"][str(out)]
    tolerance = 1e-3 * 0.28  # the default: 1e-3 of the smallest radius
    assert mesh["deflection"] == pytest.approx(tolerance) and mesh["max_triangle_deviation"] <= tolerance
    vertices, triangles = read_mesh_triangles(out, "stl")
    uses, volume = closed_mesh(vertices, triangles)
    assert uses == {2}
    axis = ParametricAxis(trefoil, (0.0, TWO_PI))
    assert axis.length == pytest.approx(report["length"], rel=1e-9)
    columns, rows, deficit = grid_counts(axis, NetLayout.equal(CurvatureLineTube(axis, 0.3), 5, 4), 0.32, tolerance)
    short = 1.0 - volume / (math.pi * (0.32**2 - 0.28**2) * axis.length)
    assert deficit < short < 6.5e-4  # measured 5.71e-4; the ring polygons alone 4.89e-4
    assert on_closing_ring(axis, vertices, 0.5) == 2 * 2 * columns  # h = -127.5 deg: no column turned onto another
    expected = 2 * (2 * columns * rows) + 2 * (2 * columns)  # two tubes; a fan triangle per extra ring node, twice
    assert len(triangles) == pytest.approx(expected, rel=0.01)
    assert len(triangles) < 0.5e6  # BRepMesh made 1.06 M here
