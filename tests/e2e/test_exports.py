"""STEP, IGES and BREP files written atomically and read back (issue 3)."""

import json
import math
import os

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import PAPER_SPEC, ROOT, sample_build_outputs

from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.cli.app import cli
from tubecad.export.cad import import_shape
from tubecad.export.registry import export_shape
from tubecad.spec.paper import paper_tube

SAMPLES = ROOT / "samples"


@pytest.fixture(scope="module")
def wall():
    tube = paper_tube()
    return build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 6, 4)).shape


@pytest.mark.parametrize(
    "name, volume_rel", [("w.step", 1e-9), ("w242.step", 1e-9), ("w.iges", 1e-9), ("w.brep", 1e-12)]
)
def test_round_trip_keeps_a_valid_identical_solid(tmp_path, wall, name, volume_rel):
    path = export_shape(wall, tmp_path / name, "AP242" if "242" in name else "AP214")
    back = import_shape(path)
    assert props.is_valid(back) and props.count(back, "solid") == 1 and props.free_edges(back) == 0
    for kind in ("face", "edge", "vertex"):
        assert props.count(back, kind) == props.count(wall, kind)
    assert props.volume(back) == pytest.approx(props.volume(wall), rel=volume_rel)
    assert props.area(back) == pytest.approx(props.area(wall), rel=volume_rel)
    assert props.volume(back) == pytest.approx(math.pi * (16**2 - 14**2) * 1000.0, rel=4e-11)  # measured 3.1e-12
    if name.endswith(".step"):
        text = path.read_text(errors="replace")
        assert ("AUTOMOTIVE_DESIGN" in text) == ("242" not in name) and "SI_UNIT(.MILLI.,.METRE.)" in text
    assert [p.name for p in tmp_path.iterdir()] == [name]  # no temporary file left behind


def test_unknown_extension_and_missing_folder(tmp_path, wall):
    from tubecad import ParameterError

    with pytest.raises(
        ParameterError, match="unknown extension '.obj'; use one of .step, .stp, .iges, .igs, .brep, .stl"
    ):
        export_shape(wall, tmp_path / "w.obj")
    with pytest.raises(ParameterError, match="does not exist"):
        export_shape(wall, tmp_path / "nope" / "w.step")


def test_failed_write_leaves_no_file(tmp_path, wall, monkeypatch):
    import tubecad.export.cad as cad

    def boom(*args):
        raise KeyboardInterrupt  # an interrupted build

    monkeypatch.setattr(cad, "write_step", boom)
    target = tmp_path / "w.step"
    target.write_text("previous good file")
    with pytest.raises(KeyboardInterrupt):
        export_shape(wall, target)
    assert target.read_text() == "previous good file" and len(list(tmp_path.iterdir())) == 1


def test_interrupt_as_the_temporary_is_created_leaves_no_file(tmp_path, monkeypatch):
    """Ctrl-C lands after the temporary file exists but before its name is returned (the
    window that left a ``.part`` file in CI, then inside ``mkstemp``): the file is removed.
    The KeyboardInterrupt is raised where Python's SIGINT handler would raise it, not sent as
    a signal: whether a raised signal is handled at once depends on what earlier tests in
    the worker left in the process (it once reached the test's body in a full run)."""
    from tubecad.core.atomic import atomic_path

    real_open = os.open

    def open_interrupted(*args, **kwargs):
        real_open(*args, **kwargs)  # the file now exists
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "open", open_interrupted)
    with pytest.raises(KeyboardInterrupt):
        with atomic_path(tmp_path / "w.step"):
            pytest.fail("the interrupt must end the write before it starts")
    monkeypatch.undo()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_paper_command_writes_a_valid_wall_step_and_iges(paper_run):
    result = paper_run  # `tubecad paper -o DIR --nu 64 --ns 501`, the suite's one paper run (conftest)
    tmp_path = result.folder
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "report.json").read_text())
    brep = report["brep"]
    assert brep["kind"] == "wall" and brep["valid"] and brep["free_edges"] == 0
    assert brep["faces"] == 2 * 10 * 8 + 2 and brep["volume_relative_error"] < 1e-6
    assert brep["fit"]["max_deviation"] < 1e-8 and brep["fit"]["max_orthogonality_error"] < 1e-9
    assert all(s["pole_count"] <= 2000 and s["area_relative_error"] < 1e-6 for s in brep["surfaces"])
    step = import_shape(tmp_path / "paper.step")
    assert props.is_valid(step) and props.count(step, "face") == brep["faces"]
    assert props.volume(step) == pytest.approx(math.pi * (16**2 - 14**2) * 1000, rel=7e-12)  # measured 6.4e-13
    iges = import_shape(tmp_path / "paper.iges")
    assert props.count(iges, "face") == brep["faces"] and props.is_valid(iges)
    for name in ("paper.step", "paper.iges"):
        assert report["exports"][name]["valid"] and report["exports"][name]["volume_relative_error"] < 1e-6
    png = (tmp_path / "paper_step.png").read_bytes()
    assert png.startswith(b"\x89PNG") and len(png) > 50_000
    # issue 4: the named assembly, the polylines and the stiffener list
    import build123d as bd

    names = [c.label for c in bd.import_step(tmp_path / "paper_stiffened.step").children]
    assert names == ["wall"] + [f"ring_{i:02d}" for i in range(1, 10)] + [f"stringer_{j:02d}" for j in (0, 4)] + [
        "curvature_lines"
    ]
    stiff = report["stiffeners"]
    assert len(stiff["stiffeners"]) == 11 and all(s["valid"] for s in stiff["stiffeners"])
    ring = stiff["stiffeners"][0]
    assert ring["volume"] == pytest.approx(math.pi * (14**2 - 11**2) * 1.0, rel=3e-12)  # measured 2.3e-13
    assert ring["mass_kg"] == pytest.approx(ring["volume"] * 7.85e-6)
    assert len(stiff["lines"]) == 2 * (11 + 8)
    assert (tmp_path / "paper_lines.csv").read_text().startswith("line,kind,index,surface_radius,s,theta_deg,x,y,z")
    assert (tmp_path / "paper_stiffened.png").read_bytes().startswith(b"\x89PNG")


@pytest.mark.slow
@pytest.mark.parametrize("name", ["dupin_cyclide", "saddle_canal_closed", "tapered_bend"])
def test_canal_samples_report_areas_against_their_exact_surfaces(sample_build, name):
    """issue 41: each wall surface's faces are measured against the area of the exact canal
    surface they are fitted to, r + d for d = +-thickness / 2 (2 pi r L of the mean radius was
    0.22 off on the cyclide, 1.2e-3 and 4.7e-4 on the others), here the closed form
    A = 2 pi Int (r + d) (1 - r'^2 - (r + d) r'') ds (docs/MATH.md section 8) by scipy's quad."""
    import tomllib

    from scipy.integrate import quad

    from tubecad.spec.parse import load_spec

    result = sample_build(name)
    assert result.exit_code == 0, result.output
    surfaces = result.report()["brep"]["surfaces"]
    canal = load_spec(SAMPLES / f"{name}.toml").tube
    law, breaks = canal.radius_law, canal.s_breaks()
    thickness = tomllib.loads((SAMPLES / f"{name}.toml").read_text())["wall"]["thickness"]
    for surface, d in zip(surfaces, (0.5 * thickness, -0.5 * thickness)):

        def density(s: float, d: float = d) -> float:
            r, dr, ddr = (float(f(np.array([s]))[0]) for f in (law.r, law.dr, law.ddr))
            return 2.0 * math.pi * (r + d) * (1.0 - dr * dr - (r + d) * ddr)

        exact = sum(quad(density, a, b, epsabs=0.0, epsrel=1e-13, limit=200)[0] for a, b in zip(breaks, breaks[1:]))
        assert surface["area_exact"] == pytest.approx(exact, rel=1e-11)
        # measured 5.8e-14 (cyclide), 2.3e-12 (saddle loop), 7.5e-15 (bend): the fit's level
        assert surface["area_relative_error"] < 1e-8


@pytest.mark.slow
@pytest.mark.parametrize("spec", sorted(SAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_build_command_for_every_family(sample_build, spec):
    """`tubecad build` of every sample (a wall added where it has none: conftest.WALL_SECTIONS)
    to STEP and IGES (the closed trefoil to BREP), each read back: the suite's one build of each
    sample (conftest.sample_build), which other tests of a sample share."""
    result = sample_build(spec.stem)
    folder, second = result.folder, sample_build_outputs(spec.stem)[1]
    assert result.exit_code == 0, result.output
    report = result.report()
    if "junction" in report:  # [[branches]]: the junction wall, its saddles named edges
        junction = report["junction"]
        assert junction["valid"] and junction["solids"] == 1
        for saddle in junction["saddles"].values():
            # measured 7e-8 .. 2.1e-7 (OCCT's section curves) and coverage 1 to 2e-10
            assert saddle["edges_deviation"] < 1e-6 and abs(saddle["coverage"] - 1) < 1e-8
        for name in ("a.step", second):
            back = report["exports"][str(folder / name)]
            parts = len(junction.get("pads", {})) + len(junction.get("stiffeners", {}))  # each its own solid
            assert back["valid"] and back["solids"] == 1 + parts and back["volume_relative_error"] < 1e-9
        assert all(st["valid"] for st in junction.get("stiffeners", {}).values())
        for pad in junction.get("pads", {}).values():  # the tee's pad, on the route's straight first leg
            assert pad["valid"] and pad["development_max_strain"] < 1e-12
        assert report["exports"][str(folder / "a.step")]["edge_names"] == len(junction["named_edge_sets"])
        return
    if "net" in report:  # [host]: a face's net, its wall and webs, every line, web and umbilic named in the STEP
        # the edges' angle to the principal directions: measured 3e-11 on the dome, 6.4e-10 on the hull, 6.3e-10
        # on the ellipsoid's 6 + 4 lines (a k2 line passing near its NURBS poles reaches 5e-6: issue 44 is open)
        assert report["brep"]["valid"] and report["net"]["angle"] < 1e-8
        names = report["net"]["k1_lines"] + report["net"]["k2_lines"] + len(report["host"]["umbilics"])
        names += len(report.get("stiffeners", {}))
        for name in ("a.step", second):
            back = report["exports"][str(folder / name)]
            assert back["valid"] and back["area_relative_error"] < 1e-9
            assert back.get("volume_relative_error", 0.0) < 1e-7  # measured 1.5e-8 (the hull panel's IGES)
        assert report["exports"][str(folder / "a.step")]["names"] == names
        return
    assert report["brep"]["valid"] and report["brep"]["volume_relative_error"] < 1e-6
    assert report["brep"]["fit"]["max_deviation"] < 1e-8
    assert report["brep"]["fit"]["max_orthogonality_error"] < 1e-9
    for name in ("a.step", second):
        back = report["exports"][str(folder / name)]
        assert back["valid"] and back["volume_relative_error"] < 1e-6
        if "stiffeners" in report:  # the assembly: the wall's faces and the stiffeners'
            wall = len(report.get("panels") or []) or 1  # the wall, or its panels
            assert back["faces"] > report["brep"]["faces"] and back["solids"] == wall + len(
                report["stiffeners"]["stiffeners"]
            )
        else:
            assert back["faces"] == report["brep"]["faces"]


@pytest.mark.parametrize(
    "extra, says",
    [
        ("[layout]\nrings = 3\ns_rings = [300.0]\n", "[layout] give either rings or s_rings"),
        ("[layout]\nrings = 1\n", "[layout] rings must be a whole number >= 2"),
        ("[layout]\nrings = 2.5\n", "[layout] rings must be a whole number"),
        ("[layout]\nu_stringers_deg = []\n", "[layout] u_stringers_deg must be a non-empty list"),
        ('[wall]\nthickness = 2.0\nside = "middle"\n', "[wall] side must be one of"),
        ("[wall]\nthickness = 40.0\n", "[wall] thickness must be < 30"),
        ("[wall]\nthickness = 3.0\n", "[wall] the wall's outer surface is not regular"),
        ('[wall]\nside = "inside"\n', "[wall] thickness is missing"),
        ("[fit]\ntolerance = 2.0\n", "[fit] fit tolerance must be in (0, 1)"),
        ("[fit]\ntolerance = 1e-17\n", "[fit] fit tolerance"),
    ],
)
def test_build_spec_errors_exit_2_and_write_nothing(tmp_path, extra, says):
    path = tmp_path / "spec.toml"
    path.write_text(PAPER_SPEC + "\n" + extra)
    out = tmp_path / "x.step"
    result = CliRunner().invoke(cli, ["build", str(path), "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert says in result.output and "Traceback" not in result.output
    assert not out.exists()


def test_build_refuses_unknown_extension_before_building(tmp_path):
    result = CliRunner().invoke(cli, ["build", str(SAMPLES / "paper_log_spiral.toml"), "-o", str(tmp_path / "x.obj")])
    assert result.exit_code == 2 and "unknown extension" in result.output
    assert os.listdir(tmp_path) == []


@pytest.mark.slow
def test_a_lateral_s_saddles_read_back_from_step_by_name_on_both_cylinders(sample_build):
    """samples/lateral.toml (main y^2 + z^2 = R^2 along x, branch at 45 deg from (150, 0, 0)
    along (cos 45, 0, sin 45)): the STEP file's ``junction_edges`` holds ``saddle_outer`` and
    ``saddle_inner`` by name, each edge on both cylinders of its radii (outer 52 / 31.5, bore
    48 / 28.5), and the wall is one valid solid."""
    import build123d as bd

    from tubecad.brep.properties import is_valid

    result = sample_build("lateral")
    assert result.exit_code == 0, result.output
    parts = {c.label: c for c in bd.import_step(result.folder / "a.step").children}
    assert set(parts) == {"wall", "junction_edges"} and is_valid(parts["wall"].wrapped)
    named = {c.label: c for c in parts["junction_edges"].children}
    direction = np.array([math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4)])
    for name, big, small in (("saddle_outer", 52.0, 31.5), ("saddle_inner", 48.0, 28.5)):
        points = np.array([tuple(e.position_at(t)) for e in named[name].edges() for t in np.linspace(0, 1, 11)])
        from_main = np.hypot(points[:, 1], points[:, 2])
        along = (points - [150.0, 0.0, 0.0]) @ direction
        from_branch = np.linalg.norm(points - [150.0, 0.0, 0.0] - along[:, None] * direction, axis=1)
        # measured 2e-7 (OCCT's intersection curves; 13 digits in the file)
        assert np.abs(from_main - big).max() < 1e-6 and np.abs(from_branch - small).max() < 1e-6, name
    assert {"main_ring_00", "branch_stringer_07_inner"} <= set(named)
