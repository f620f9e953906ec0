"""A face the user already has, from the command line (issue 44): the [host] samples build,
shop and mesh; their files read back with every line and web named; bad [host] input is
refused in one line naming the key, exit code 2, no file.

Independent checks: the dome's lines are its parallels and meridians (every point of a k1
line at one height, of a k2 line at one polar angle: the closed forms of a surface of
revolution); a web's solid has the volume of its development times its thickness (the web is
developable, its sides symmetric: Steiner's formula with K = 0)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import ROOT

from tubecad.cli.app import cli

HOST = ROOT / "samples"


def _spec(tmp_path, name: str, edits=()) -> str:
    text = (HOST / name).read_text().replace('step = "', f'step = "{ROOT / "samples"}/')
    for old, new in edits:
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize(
    ("edits", "key", "says"),
    [
        ((("k1_lines = 6", "k1_lines = 6\nk1_spacing = 100.0"),), "host.k1_lines", "not both"),
        ((("k1_lines = 6", "k1_lines = 0"),), "host.k1_lines", "1..200"),
        ((("step = ", "face = 3\nstep = "),), "host.face", "[0, 0]"),
        ((("[host]", '[host]\nface = "keel"'),), "host.face", "no face named 'keel'"),
        ((("dome.step", "nothing.step"),), "host.step", "no file"),
        ((("k1 = [1, 3, 5]", "k1 = [1, 9]"),), "stiffeners.k1", "[0, 5]"),
        ((("k1 = [1, 3, 5]", "rings = [1]"),), "stiffeners.rings", "k1 and k2"),
        ((("[wall]", "[layout]\nrings = 3\n\n[wall]"),), "layout", "is not for a [host] spec"),
        ((("k1_lines = 6", "k1_lines = 6\nseed = [0.0, 0.0, 0.0]"),), "host.seed", "seed must be a point on the face"),
    ],
)
def test_bad_host_input_is_refused_in_one_line_naming_the_key(tmp_path, edits, key, says):
    spec = _spec(tmp_path, "dome.toml", edits)
    result = CliRunner().invoke(cli, ["build", spec, "-o", str(tmp_path / "x.step")])
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and says in lines[0], lines
    assert key.split(".")[-1] in lines[0]
    assert not (tmp_path / "x.step").exists()


@pytest.mark.slow
def test_the_dome_builds_with_its_parallels_meridians_and_webs(tmp_path):
    spec = _spec(tmp_path, "dome.toml")
    out = tmp_path / "dome.step"
    result = CliRunner().invoke(cli, ["build", spec, "-o", str(out), "--report", str(tmp_path / "r.json")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["brep"]["valid"] and report["host"]["umbilics"] == []
    assert report["net"]["angle"] < 1e-8  # the edges follow the principal directions
    for web in report["stiffeners"].values():  # a developable web: volume = developed area x thickness
        assert web["volume"] == pytest.approx(8.0 * web["developed_area"], rel=1e-8)
    assert report["exports"][str(out)]["names"] == 6 + 8 + 3
    # the wall as a user reads it passes OCCT's whole pre-boolean check (its offset edges were
    # 1e-5 off and read back InvalidCurveOnSurface 420 times: tubecad.brep.offset_edges)
    import build123d as bd

    from tubecad.brep.analyzer import analyzer_findings

    wall = next(child for child in bd.import_step(out).children if child.label == "wall")
    assert analyzer_findings(wall.wrapped, prefilter=False) == {}


@pytest.mark.slow
def test_the_dome_shop_marks_parallels_and_meridians(tmp_path):
    spec = _spec(tmp_path, "dome.toml")
    result = CliRunner().invoke(cli, ["shop", spec, "-o", str(tmp_path / "shop")])
    assert result.exit_code == 0, result.output
    index = json.loads((tmp_path / "shop" / "index.json").read_text())
    assert index["webs"]["nesting"]["valid"]
    rows = np.genfromtxt(
        tmp_path / "shop" / "marking" / "net_lines.csv", delimiter=",", dtype=None, names=True, encoding="utf-8"
    )
    for name in sorted(set(rows["line"])):
        at = rows[rows["line"] == name]
        if name.startswith("k1_"):  # a parallel: one height, one distance from the axis (the CSV's 9 digits)
            assert np.ptp(at["z"]) < 1e-6 and np.ptp(np.hypot(at["x"], at["y"])) < 2e-6
        else:  # a meridian: one polar angle
            angle = np.unwrap(np.arctan2(at["y"], at["x"]))
            assert np.ptp(angle) < 1e-8
    # a pin-jig table per panel (7 rings of 8), its pins on the dome's outer surface (the wall
    # and the webs inside: the face itself), each listed in the index and printed
    panels = index["panels"]
    assert len(panels) == 7 * 8 and f"panels: {len(panels)} pin-jig tables" in result.output
    table = tmp_path / "shop" / "panels" / f"{panels[0]['name']}_pin_jig.csv"
    pins = np.genfromtxt(table, delimiter=",", names=True, skip_header=2)  # after the units and the lines
    assert len(pins) == panels[0]["pins"] and pins["height"].min() >= 0.0
    a, b = 500.0, 250.0
    assert np.abs((pins["px"] ** 2 + pins["py"] ** 2) / a**2 + pins["pz"] ** 2 / b**2 - 1).max() < 1e-12


@pytest.mark.slow
@pytest.mark.requires("gmsh")
def test_the_dome_meshes_with_its_webs_as_beams(tmp_path):
    spec = _spec(tmp_path, "dome.toml")
    result = CliRunner().invoke(cli, ["mesh", spec, "-o", str(tmp_path / "dome.inp"), "-o", str(tmp_path / "dome.msh")])
    assert result.exit_code == 0, result.output
    import meshio

    mesh = meshio.read(tmp_path / "dome.msh")
    r, z = np.hypot(mesh.points[:, 0], mesh.points[:, 1]), mesh.points[:, 2]
    assert np.abs((r / 500.0) ** 2 + (z / 250.0) ** 2 - 1.0).max() < 1e-9  # on the elliptical head
    assert "3 beam blocks" in result.output


@pytest.mark.slow
def test_the_dome_reports_and_develops_its_ring_webs_as_the_closed_form_cones(tmp_path):
    """`tubecad report` and `tubecad flat` on a [host] spec. The dome is the 2:1 ellipse
    x^2 / a^2 + z^2 / c^2 = 1 (a = 500, c = 250) turned about z; a parallel of radius r (its
    length 2 pi r in the report) has the outward normal's radial part
    n_r = (r / a^2) / |(r / a^2, z / c^2)|. A web standing on the normal inside the 8 mm wall
    develops to an annulus sector whose arcs are the circles it stands on: base
    2 pi (r - 8 n_r), top 2 pi (r - (8 + 60) n_r)."""
    spec = _spec(tmp_path, "dome.toml")
    shown = CliRunner().invoke(cli, ["report", spec])
    assert shown.exit_code == 0, shown.output
    report = json.loads(shown.output)
    assert report["brep"]["valid"] and report["host"]["umbilics"] == [] and report["host"]["umbilic_parts"] == []
    assert sorted(report["stiffeners"]) == ["stiffener_k1_01", "stiffener_k1_03", "stiffener_k1_05"]
    made = CliRunner().invoke(cli, ["flat", spec, "-o", str(tmp_path / "flat")])
    assert made.exit_code == 0, made.output
    flat = json.loads((tmp_path / "flat" / "flat.json").read_text())
    webs = {web["name"]: web for web in flat["webs"]}
    assert sorted(webs) == ["k1_01", "k1_03", "k1_05"]
    a, c = 500.0, 250.0
    for name, web in webs.items():
        r = report["net"]["lines"][name]["length"] / (2 * np.pi)
        z = c * np.sqrt(1 - (r / a) ** 2)
        n_r = (r / a**2) / np.hypot(r / a**2, z / c**2)
        assert web["base_length"] == pytest.approx(2 * np.pi * (r - 8.0 * n_r), rel=1e-13)  # measured 3e-15
        assert web["top_length"] == pytest.approx(2 * np.pi * (r - 68.0 * n_r), rel=1e-13)  # measured 2.7e-14
        assert not web["crosses_itself"]
    assert (tmp_path / "flat" / "webs.dxf").is_file() and (tmp_path / "flat" / "k1_03.svg").is_file()


@pytest.mark.slow
def test_the_dome_with_curvature_patches_builds_and_develops_its_panels(tmp_path):
    """`[host] patches = "curvature"`: the 2 x 4 inner cells of a 3 + 4 net on their
    curvature-line patches in the wall read back from STEP (valid, every patch a B-spline whose
    isolines meet the target), and the shop develops each as a panel (panel_NN_development.dxf):
    its flat area more than its surface's (K > 0 on the dome: Jacobi), its ring edges arcs."""
    import ezdxf

    edits = (("k1_lines = 6", "k1_lines = 3"), ("k2_lines = 8", 'k2_lines = 4\npatches = "curvature"'))
    edits += (("k1 = [1, 3, 5]", "k1 = [1]"),)
    spec = _spec(tmp_path, "dome.toml", edits)
    out = tmp_path / "dome.step"
    built = CliRunner().invoke(cli, ["build", spec, "-o", str(out), "--report", str(tmp_path / "r.json")])
    assert built.exit_code == 0, built.output
    report = json.loads((tmp_path / "r.json").read_text())
    assert len(report["patches"]["refitted"]) == 2 * 4 and report["brep"]["valid"]
    assert report["patches"]["angle"] < 1e-6 and "8 cells refitted" in built.output
    shop = CliRunner().invoke(cli, ["shop", spec, "-o", str(tmp_path / "shop")])
    assert shop.exit_code == 0, shop.output
    index = json.loads((tmp_path / "shop" / "index.json").read_text())
    assert len(index["developments"]) == 2 * 4
    for dev in index["developments"]:
        assert dev["flat_area"] > dev["surface_area"] and dev["max_strain"] > 0  # a quarter of the dome a panel
        drawing = ezdxf.readfile(tmp_path / "shop" / "panels" / f"{dev['name']}_development.dxf")
        (outline,) = drawing.modelspace().query("LWPOLYLINE[layer=='OUTLINE']")
        assert outline.closed and len(outline) > 4


def test_a_tube_spec_refuses_a_nets_line_choice(tmp_path):
    text = (
        (ROOT / "samples" / "helix_stiffened.toml").read_text().replace("[stiffeners]\n", "[stiffeners]\nk1 = [0]\n", 1)
    )
    spec = tmp_path / "tube.toml"
    spec.write_text(text)
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(tmp_path / "x.step")])
    assert result.exit_code == 2
    assert (
        "[stiffeners] k1 chooses a [host] net's lines" in result.output and len(result.output.strip().splitlines()) == 1
    )
