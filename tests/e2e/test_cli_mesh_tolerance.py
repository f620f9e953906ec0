"""`tubecad build --mesh-tolerance/--mesh-angle`: meshes to a tolerance, checked as read back
(tubecad.export.meshing, tubecad.export.tessellate)."""

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import ROOT

from tubecad.cli.app import cli

SAMPLES = ROOT / "samples"
#: a short helical wall, radii 11.5 and 12.5
WALL = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 300.0]

[tube]
radius = 12.0

[layout]
rings = 3
stringers = 3

[wall]
thickness = 1.0
"""
MESHES = ("stl", "3mf", "gltf", "glb")


def run(*args, **kwargs):
    return CliRunner().invoke(cli, [str(a) for a in args], **kwargs)


@pytest.fixture(scope="module")
def wall_spec(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("spec") / "wall.toml"
    path.write_text(WALL)
    return path


def mesh_report(spec: Path, out: Path, *options) -> dict:
    result = run("build", spec, "-o", out, "--report", out.with_suffix(".json"), "-q", *options)
    assert result.exit_code == 0, result.output
    return json.loads(out.with_suffix(".json").read_text())["exports"][str(out)]


@pytest.fixture(scope="module")
def two_tolerances(wall_spec, tmp_path_factory):
    folder = tmp_path_factory.mktemp("meshes")
    return {t: mesh_report(wall_spec, folder / f"w{t}.stl", "--mesh-tolerance", t) for t in (0.05, 0.01)}


@pytest.mark.slow
def test_a_finer_tolerance_gives_more_triangles_closer_to_the_tube(two_tolerances):
    coarse, fine = two_tolerances[0.05], two_tolerances[0.01]
    assert fine["triangles"] > 2 * coarse["triangles"]
    assert fine["max_triangle_deviation"] < coarse["max_triangle_deviation"] / 2
    for tolerance, info in two_tolerances.items():
        assert info["deflection"] == tolerance and info["angular_deflection_deg"] == pytest.approx(np.degrees(0.1))
        # within the tolerance (plus the 32-bit rounding of the vertices), and not needlessly finer
        assert 0.5 * tolerance < info["max_triangle_deviation"] <= tolerance + info["max_vertex_deviation"]
        assert info["max_vertex_deviation"] < 1e-4


@pytest.mark.slow
def test_every_mesh_format_holds_the_same_triangles_within_the_tolerance(wall_spec, tmp_path):
    from tubecad.export.mesh import read_mesh_triangles
    from tubecad.export.tessellate import mesh_deviation
    from tubecad.spec.parse import load_spec

    outs = [tmp_path / f"w.{ext}" for ext in MESHES]
    result = run(
        "build",
        wall_spec,
        *[a for o in outs for a in ("-o", o)],
        "--mesh-tolerance",
        "0.02",
        "--mesh-angle",
        "10",
        "--report",
        tmp_path / "r.json",
        "-q",
    )
    assert result.exit_code == 0, result.output
    exports = json.loads((tmp_path / "r.json").read_text())["exports"]
    counts = {exports[str(o)]["triangles"] for o in outs}
    assert len(counts) == 1, exports  # the writers keep the one triangulation
    axis = load_spec(wall_spec).tube.axis
    for out in outs:
        info = exports[str(out)]
        assert info["deflection"] == 0.02 and info["angular_deflection_deg"] == pytest.approx(10.0)
        assert info["max_triangle_deviation"] <= 0.02 + info["max_vertex_deviation"]
        vertices, triangles = read_mesh_triangles(out, "gltf" if out.suffix == ".glb" else out.suffix[1:])
        assert len(triangles) == info["triangles"]
        assert mesh_deviation(axis, [12.5, 11.5], vertices, triangles)[1] == pytest.approx(
            info["max_triangle_deviation"]
        )
        assert f"{out}: " in result.output and "tolerance 0.02 and 10 deg" in result.output


@pytest.mark.slow
def test_the_mesh_is_closed_and_faces_outward(wall_spec, tmp_path):
    """Each edge of the STL is shared by two triangles, and the signed volume is the wall's."""
    from tubecad.export.mesh import read_mesh_triangles

    out = tmp_path / "w.stl"
    assert run("build", wall_spec, "-o", out, "-q").exit_code == 0
    vertices, triangles = read_mesh_triangles(out, "stl")
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses) == {2}
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    assert volume == pytest.approx(np.pi * (12.5**2 - 11.5**2) * 300.0, rel=2e-3)


@pytest.mark.parametrize(
    "options, says",
    [
        (("--mesh-tolerance", "0"), "--mesh-tolerance must be in [0.00115, 11.5]"),
        (("--mesh-tolerance", "-1"), "--mesh-tolerance must be in [0.00115, 11.5]"),
        (("--mesh-tolerance", "1e-5"), "1e-05"),
        (("--mesh-tolerance", "nan"), "--mesh-tolerance must be in"),
        (("--mesh-tolerance", "100"), "the smallest tube radius 11.5"),
        (("--mesh-angle", "0.5"), "--mesh-angle must be in [1, 45] degrees, got 0.5"),
        (("--mesh-angle", "90"), "--mesh-angle must be in [1, 45] degrees, got 90"),
    ],
)
def test_out_of_range_tolerances_exit_2_with_one_line_and_write_nothing(wall_spec, tmp_path, options, says):
    result = run("build", wall_spec, "-o", tmp_path / "w.stl", "-o", tmp_path / "w.step", *options)
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("Error: ") and says in lines[0], result.output
    assert list(tmp_path.iterdir()) == []


def test_mesh_options_without_a_mesh_output_are_refused(wall_spec, tmp_path):
    result = run("build", wall_spec, "-o", tmp_path / "w.step", "--mesh-tolerance", "0.1")
    assert result.exit_code == 2 and "apply to mesh outputs (.stl, .3mf, .gltf, .glb)" in result.output
    result = run("build", wall_spec, "-d", tmp_path / "b", "--mesh-angle", "10")  # batch, default -f step
    assert result.exit_code == 2 and "--mesh-tolerance and --mesh-angle apply to mesh outputs" in result.output
    assert list(tmp_path.iterdir()) == []


def test_help_says_which_formats_the_tolerances_apply_to():
    text = " ".join(run("build", "--help").output.split())
    assert "--mesh-tolerance LENGTH Mesh outputs only (.stl, .3mf, .gltf, .glb)" in text
    assert "--mesh-angle DEGREES Mesh outputs only" in text and "-q, --quiet" in text


@pytest.mark.slow
def test_batch_jobs_mesh_to_the_tolerance(wall_spec, tmp_path):
    out = tmp_path / "out"
    result = run("build", wall_spec, "-d", out, "-f", "stl", "--mesh-tolerance", "0.05", "-j", "1")
    assert result.exit_code == 0, result.output
    info = json.loads((out / "wall.report.json").read_text())["exports"][str(out / "wall.stl")]
    assert info["deflection"] == 0.05 and info["max_triangle_deviation"] <= 0.05 + info["max_vertex_deviation"]
    result = run("build", wall_spec, "-d", tmp_path / "bad", "-f", "stl", "--mesh-tolerance", "50", "-j", "1")
    assert result.exit_code == 2 and "--mesh-tolerance must be in [0.00115, 11.5]" in result.output
    assert sorted(p.name for p in (tmp_path / "bad").iterdir()) == ["batch.json"]
