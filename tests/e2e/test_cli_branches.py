"""[[branches]] in a spec (issue 25), from the command line: the commands that cannot make a
junction yet refuse it with exit code 2 and no file; shop writes a tee's templates, bevels
and webs, and a nozzle's opening on a conical main on a panel's development; a batch and a
curved branch build valid junctions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner
from shared.branches import BRANCH, MAIN, spec_text

from tubecad.cli.app import cli


@pytest.mark.parametrize(
    ("command", "says"),
    [
        (["build", "{spec}", "-o", "{out}/x.svg"], "output 'x.svg': a junction is written as cad, mesh, png files"),
        (["build", "{spec}", "-o", "{out}/x.csv"], "output 'x.csv': a junction is written as cad, mesh, png files"),
    ],
)
def test_what_a_junction_cannot_be_yet_is_refused_with_exit_2_and_no_file(tmp_path, command, says):
    spec = tmp_path / "tee.toml"
    spec.write_text(spec_text())
    out = tmp_path / "out"
    out.mkdir()
    result = CliRunner().invoke(cli, [a.format(spec=spec, out=out) for a in command])
    assert result.exit_code == 2, result.output
    assert says in result.output and "Traceback" not in result.output
    assert list(out.iterdir()) == []


@pytest.mark.slow
def test_shop_on_a_tee_writes_the_templates_and_bevels_of_the_closed_forms(tmp_path):
    """Main y^2 + z^2 = 52^2 (outer), branch x'^2 + y^2 = 32^2 (outer: the main's wall 4 on
    r 30): the cutting template, read back by ezdxf, is y = sqrt(52^2 - 32^2 sin^2(x / 32)) on
    the branch's strip; the bevel file's dihedral angle is arccos(32 sin^2 u / 52); the opening's
    template is one closed line of the bore's saddle (28 on 48) whose area shapely measures
    against the quadrature int R 2 sqrt(r^2 - R^2 cos^2 chi) dchi."""
    import csv

    import ezdxf
    from scipy.integrate import quad
    from shapely.geometry import Polygon

    spec = tmp_path / "tee.toml"
    spec.write_text(spec_text(BRANCH + "pad = { thickness = 6.0, width = 20.0 }\n"))
    result = CliRunner().invoke(cli, ["shop", str(spec), "-o", str(tmp_path / "shop")])
    assert result.exit_code == 0, result.output
    folder = tmp_path / "shop" / "branches"
    saddle = [e for e in ezdxf.readfile(folder / "branch_0_template.dxf").modelspace() if e.dxf.layer == "saddle"]
    points = np.array([p[:2] for p in saddle[0].get_points()])
    x, y = points.T
    # measured 1e-12 (the saddle's Newton points)
    assert np.abs(y - np.sqrt(52.0**2 - 32.0**2 * np.sin(x / 32.0) ** 2)).max() < 1e-9
    rows = list(csv.DictReader((folder / "branch_0_bevel.csv").open()))
    u = np.radians([float(r["u_deg"]) for r in rows])
    angles = np.array([float(r["dihedral_deg"]) for r in rows])
    assert np.abs(angles - np.degrees(np.arccos(32.0 * np.sin(u) ** 2 / 52.0))).max() < 1e-9
    hole = [e for e in ezdxf.readfile(folder / "branch_0_hole.dxf").modelspace() if e.dxf.layer == "saddle"]
    assert len(hole) == 1 and hole[0].closed
    polygon = Polygon([p[:2] for p in hole[0].get_points()])
    exact, _ = quad(
        lambda chi: 48.0 * 2 * np.sqrt(max(28.0**2 - 48.0**2 * np.cos(chi) ** 2, 0.0)),
        np.arccos(28.0 / 48.0),
        np.pi - np.arccos(28.0 / 48.0),
        epsabs=1e-10,
        limit=200,
    )
    # the pad's development: the rectangle R (u_b - u_a) x (s_b - s_a) of its rings and stringers,
    # 20 beyond the saddle (x = 150 +- 32, angle 90 deg +- asin(32 / 52)), the branch's line inside
    pad = {e.dxf.layer: e for e in ezdxf.readfile(folder / "branch_0_pad_development.dxf").modelspace()}
    outline = Polygon([p[:2] for p in pad["OUTLINE"].get_points()])
    width_u = 2 * (np.arcsin(32.0 / 52.0) + 20.0 / 52.0)
    assert outline.area == pytest.approx(52.0 * width_u * (2 * 32.0 + 40.0), rel=1e-9)
    assert outline.contains(Polygon([p[:2] for p in pad["MARKING"].get_points()]))
    # the developed hole as a polygon of 720 sides: measured 1.3e-5 relative (the chords' loss)
    assert polygon.is_valid and abs(polygon.area / exact - 1) < 3e-5, polygon.area / exact - 1


@pytest.mark.slow
def test_shop_on_a_stiffened_tee_nests_the_webs_stopped_at_the_opening(tmp_path):
    """[stiffeners] on the tee: the ring frame through the branch's axis (ring 3, x = 150) is
    cut at the opening, so its web is the sector of the arc it keeps, 2 pi - (pi - 2 acos(32 /
    52)) of the annulus 52 .. 62; the stringer on the branch's side stops on the saddle, its
    two pieces' webs rectangles 150 - 32 and 400 - 182 long. The webs' plate, read back by
    ezdxf and measured by shapely, holds every piece at the area the index gives it."""
    import json

    import ezdxf
    from shapely.geometry import Polygon

    spec = tmp_path / "tee.toml"
    stiffeners = '[stiffeners]\nrings = [1, 3]\nstringers = [0, 2]\nprofile = "flat"\nheight = 10.0\nthickness = 2.0\n'
    spec.write_text(spec_text(BRANCH + "around = 90.0\n") + "[layout]\nrings = 9\nstringers = 8\n" + stiffeners)
    result = CliRunner().invoke(cli, ["shop", str(spec), "-o", str(tmp_path / "shop")])
    assert result.exit_code == 0, result.output
    index = json.loads((tmp_path / "shop" / "index.json").read_text())
    pieces = {p["name"]: p for p in index["webs"]["pieces"]}
    assert set(pieces) == {"ring_01", "ring_03", "stringer_00", "stringer_02_a", "stringer_02_b"}
    a, b = pieces["ring_03"]["span"]
    kept = 2 * math.pi - (math.pi - 2 * math.acos(32.0 / 52.0))
    assert math.radians(b - a) == pytest.approx(kept, rel=1e-7)
    assert pieces["ring_03"]["area"] == pytest.approx(0.5 * kept * (62.0**2 - 52.0**2), rel=1e-7)
    assert pieces["ring_01"]["area"] == pytest.approx(math.pi * (62.0**2 - 52.0**2), rel=1e-12)
    assert pieces["stringer_02_a"]["area"] == pytest.approx(10.0 * (150.0 - 32.0), rel=1e-7)
    assert pieces["stringer_02_b"]["area"] == pytest.approx(10.0 * (400.0 - 182.0), rel=1e-7)
    assert pieces["stringer_00"]["area"] == pytest.approx(10.0 * 400.0, rel=1e-9)
    (plate,) = (tmp_path / "shop" / "webs").glob("webs_plate_*.dxf")
    parts = [e for e in ezdxf.readfile(plate).modelspace() if e.dxf.layer == "PARTS"]
    circles = sorted(math.pi * e.dxf.radius**2 for e in parts if e.dxftype() == "CIRCLE")
    outlines = [Polygon(_bulged_points(e)) for e in parts if e.dxftype() == "LWPOLYLINE"]
    assert circles == pytest.approx([math.pi * 52.0**2, math.pi * 62.0**2], rel=1e-12)  # ring_01's annulus
    drawn = sorted([circles[1] - circles[0], *(o.area for o in outlines)])
    # the arcs as chords of 1/4000 of a turn: measured 4.1e-7 below the exact area (the sector)
    assert drawn == pytest.approx(sorted(p["area"] for p in pieces.values()), rel=1e-6)


def _bulged_points(polyline) -> list[tuple[float, float]]:
    """A closed LWPOLYLINE's outline with each bulge's exact arc (ezdxf.math.bulge_to_arc)
    sampled at least every 1/4000 of a turn (ezdxf's own paths make cubic Beziers of the arcs,
    4e-3 off a 142 deg arc of radius 62)."""
    from ezdxf.math import bulge_to_arc

    vertices = list(polyline.get_points("xyb"))
    out = []
    for (x, y, bulge), (x2, y2, _) in zip(vertices, vertices[1:] + vertices[:1]):
        out.append((x, y))
        if bulge:
            centre, start, end, radius = bulge_to_arc((x, y), (x2, y2), bulge)
            sweep = (end - start) % (2 * math.pi)
            steps = max(2, math.ceil(4000 * sweep / (2 * math.pi)))
            angles = start + sweep * np.arange(1, steps) / steps
            if bulge < 0:  # clockwise: from the start point the other way round
                angles = end - sweep * np.arange(1, steps) / steps
            out += [(centre.x + radius * math.cos(a), centre.y + radius * math.sin(a)) for a in angles]
    return out


@pytest.mark.slow
def test_a_batch_of_a_branched_spec_builds_its_junctions(tmp_path):
    """`tubecad build SPEC -d DIR --sweep ...` runs each job through the junction's build."""
    import json

    spec = tmp_path / "tee.toml"
    spec.write_text(spec_text())
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-d", str(tmp_path / "out"), "--sweep", "wall.thickness=4.0", "-j", "1"]
    )
    assert result.exit_code == 0, result.output
    jobs = json.loads((tmp_path / "out" / "batch.json").read_text())["jobs"]
    assert [job["status"] for job in jobs] == ["ok"] and "junction_wall" in result.output
    report = json.loads(next((tmp_path / "out").glob("*.report.json")).read_text())
    assert report["junction"]["valid"] and report["junction"]["solids"] == 1


@pytest.mark.slow
def test_a_curved_branch_builds_a_valid_junction(tmp_path):
    spec = tmp_path / "bent.toml"
    spec.write_text(spec_text(BRANCH + 'axis = { k = "1/200" }\n'))
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-o", str(tmp_path / "bent.step"), "--report", str(tmp_path / "r.json")]
    )
    assert result.exit_code == 0, result.output
    import json

    junction = json.loads((tmp_path / "r.json").read_text())["junction"]
    assert junction["valid"] and junction["solids"] == 1
    for saddle in junction["saddles"].values():
        assert saddle["edges_deviation"] < 1e-6 and abs(saddle["coverage"] - 1) < 1e-8


@pytest.mark.slow
def test_a_near_equal_spec_tee_builds_as_the_python_api_does(tmp_path):
    """Issue 43: r = 49 on R = 50 with 4 mm walls (r / R = 0.98, refused by the old spec rule
    r + t_b/2 < R - t/2): one valid junction written to STEP and read back, its saddles on
    the exact ones (the report's edges' distance from the Newton-solved saddle)."""
    import json

    spec = tmp_path / "tee.toml"
    spec.write_text(spec_text(BRANCH.replace("radius = 30.0", "radius = 49.0")))
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-o", str(tmp_path / "tee.step"), "--report", str(tmp_path / "r.json")]
    )
    assert result.exit_code == 0, result.output
    junction = json.loads((tmp_path / "r.json").read_text())["junction"]
    assert junction["valid"] and junction["solids"] == 1
    for name in ("saddle_outer", "saddle_inner"):
        assert junction["saddles"][name]["edges_deviation"] < 1e-8  # measured 1e-10


@pytest.mark.slow
def test_shop_on_a_nozzle_on_a_cone_develops_the_opening_on_a_panel(tmp_path):
    """The main a cone (spheres of radius 55 - 0.05 s about the x axis, wall 4: the bore's
    surface the cone of 53 - 0.05 s, apex at x = 1060, half-angle a with sin a = 0.05), the
    branch r 20 up z at x = 150: the opening's template is the bore's saddle (on the cone and
    on the cylinder (x - 150)^2 + y^2 = 18^2) developed on the panel of the cone round it,
    one closed polyline that ezdxf reads back, whose vertices' pairwise distances are those
    of the cone's exact development (rho, theta sin a) of the saddle's points (rigid-motion
    blind), inside the panel's outline; the index says it is a panel's, strain 0."""
    import json

    import ezdxf
    from scipy.spatial.distance import pdist
    from shapely.geometry import Polygon

    from tubecad.junctions import saddle_curve
    from tubecad.spec.design import design_of
    from tubecad.spec.parse import load_spec

    spec = tmp_path / "cone.toml"
    main = MAIN.replace("radius = 50.0", 'radius = "55 - 0.05 * s"')
    spec.write_text(spec_text(BRANCH.replace("radius = 30.0", "radius = 20.0"), main))
    result = CliRunner().invoke(cli, ["shop", str(spec), "-o", str(tmp_path / "shop")])
    assert result.exit_code == 0, result.output
    assert "the opening's template (on the main's panel" in result.output
    entry = json.loads((tmp_path / "shop" / "index.json").read_text())["branches"][0]
    assert entry["hole"]["developed"] == "panel" and entry["hole"]["strain"] < 1e-14  # measured 9.0e-16
    assert "branches/branch_0_hole.dxf" in entry["files"]
    space = ezdxf.readfile(tmp_path / "shop" / "branches" / "branch_0_hole.dxf").modelspace()
    (line,) = space.query('LWPOLYLINE[layer=="saddle"]')
    (outline,) = space.query('LWPOLYLINE[layer=="outline"]')
    assert line.closed and outline.closed
    drawn = np.array([p[:2] for p in line.get_points()])

    design = design_of(load_spec(spec))  # the bore's saddle on the exact surfaces, as the shop solves it
    (inside, _), (bore, _) = design.main.wall.offsets(), design.branches[0].wall.offsets()
    saddle = saddle_curve(
        design.main.surface.offset(inside), design.branches[0].surface.offset(bore), len(drawn) + 1
    ).points[:-1]
    x, y, z = saddle.T
    slant = np.linalg.norm(saddle - [1060.0, 0.0, 0.0], axis=1)
    # on both surfaces: measured 8.5e-14 and 1.3e-13
    assert np.abs(np.hypot(x - 150.0, y) - 18.0).max() < 1e-12 and np.abs(0.05 * slant - np.hypot(y, z)).max() < 1e-12
    theta = 0.05 * np.unwrap(np.arctan2(z, y))
    exact = np.column_stack([slant * np.cos(theta), slant * np.sin(theta)])
    got, want = pdist(drawn), pdist(exact)
    assert np.abs(got - want).max() < 2e-13 * want.max()  # measured 1.4e-14
    assert Polygon([p[:2] for p in outline.get_points()]).contains(Polygon(drawn))
