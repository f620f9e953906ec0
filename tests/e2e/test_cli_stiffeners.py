"""Stiffeners on curvature lines (issue 4) from the command line: `tubecad build` and
`tubecad flat` with a [stiffeners] section, its errors in one line, panels and polylines."""

import json
import math

import build123d as bd
import numpy as np
import pytest
from conftest import SMALL_STIFFENED_WALL

from tubecad import ParameterError
from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.spec.paper import paper_tube

STIFFENED = (
    SMALL_STIFFENED_WALL
    + """profile = "flat"
height = 3.0
thickness = 1.0
side = "inside"
"""
)


@pytest.mark.slow
def test_build_and_flat_commands_with_stiffeners(tmp_path):
    from click.testing import CliRunner
    from conftest import PAPER_SPEC

    from tubecad.cli.app import cli

    spec = tmp_path / "s.toml"
    spec.write_text(PAPER_SPEC + STIFFENED)
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-o", str(tmp_path / "a.step"), "--report", str(tmp_path / "r.json")]
    )
    assert result.exit_code == 0, result.output
    names = [c.label for c in bd.import_step(tmp_path / "a.step").children]
    assert names == ["wall", "ring_01", "ring_02", "stringer_00", "stringer_02", "curvature_lines"]
    report = json.loads((tmp_path / "r.json").read_text())["stiffeners"]
    assert [s["name"] for s in report["stiffeners"]] == names[1:5] and report["total_stiffener_mass_kg"] > 0
    result = CliRunner().invoke(cli, ["flat", str(spec), "-o", str(tmp_path / "flat")])
    assert result.exit_code == 0, result.output
    webs = json.loads((tmp_path / "flat" / "flat.json").read_text())["webs"]
    assert [w["name"] for w in webs] == ["ring_01", "ring_02", "stringer_00", "stringer_02"]
    assert webs[0]["area"] == pytest.approx(math.pi * (14**2 - 11**2))
    assert (tmp_path / "flat" / "webs.dxf").exists() and (tmp_path / "flat" / "stringer_02.svg").exists()
    assert "crosses itself" not in result.output  # these webs do not: no warning (the paper's do: tests/e2e)


@pytest.mark.parametrize(
    "edit, says",
    [
        (
            lambda t: t.replace("rings = [1, 2]", "rings = [1, 9]"),
            "[stiffeners] rings must be indices in [0, 3], got [9]",
        ),
        (
            lambda t: t.replace("rings = [1, 2]", 'rings = "some"'),
            '[stiffeners] rings must be a list of whole-number indices or "all"',
        ),
        (lambda t: t.replace('profile = "flat"', 'profile = "I"'), "[stiffeners] profile must be one of flat, T, L"),
        (lambda t: t.replace('side = "inside"', 'side = "under"'), "[stiffeners] side must be one of outside, inside"),
        (lambda t: t.replace("height = 3.0\n", ""), "[stiffeners] height is missing"),
        (
            lambda t: t.replace('profile = "flat"', 'profile = "T"'),
            "[stiffeners] flange_thickness must be in (0, 3), got 0",
        ),
        (lambda t: t.replace("height = 3.0", "height = 30.0"), "[stiffeners] height must be < R"),
    ],
)
def test_stiffener_spec_errors(tmp_path, edit, says):
    from click.testing import CliRunner
    from conftest import PAPER_SPEC

    from tubecad.cli.app import cli

    spec = tmp_path / "s.toml"
    spec.write_text(PAPER_SPEC + edit(STIFFENED))
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(tmp_path / "a.step")])
    assert result.exit_code == 2 and says in result.output, result.output
    assert not (tmp_path / "a.step").exists()


def test_flat_needs_a_stiffeners_section(tmp_path):
    from click.testing import CliRunner
    from conftest import PAPER_SPEC

    from tubecad.cli.app import cli

    spec = tmp_path / "s.toml"
    spec.write_text(PAPER_SPEC)
    result = CliRunner().invoke(cli, ["flat", str(spec), "-o", str(tmp_path / "f")])
    assert result.exit_code == 2 and "has no [stiffeners] section" in result.output


@pytest.mark.slow
def test_panels_fit_together_into_the_wall_with_exact_areas(tmp_path):
    from click.testing import CliRunner
    from conftest import PAPER_SPEC

    from tubecad.cli.app import cli
    from tubecad.stiffeners.panels import split_into_panels

    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 5, 8))
    panels = split_into_panels(build, [5, 0, 3], [0, 2, 4])
    assert [p.name for p in panels] == [f"panel_r{i}_s{j}" for i in range(2) for j in range(3)]
    assert all(props.is_valid(p.solid) and props.free_edges(p.solid) == 0 for p in panels)
    assert sum(props.volume(p.solid) for p in panels) == pytest.approx(props.volume(build.shape), rel=1e-9)
    x, w = np.polynomial.legendre.leggauss(24)
    for p in panels:  # outer area = r Int Int (1 - r k cos(theta - Int sigma)) ds dtheta
        (s0, s1), (a, b) = p.s_range, np.radians(p.angles_deg)
        s = 0.5 * (s0 + s1) + 0.5 * (s1 - s0) * x[:, None]
        th = 0.5 * (a + b) + 0.5 * (b - a) * x[None, :]
        g = 1 - 16.0 * tube.axis.curvature(s) * np.cos(th - tube.axis.twist(s))
        exact = 16.0 * float((g * w[:, None] * w[None, :]).sum()) * 0.25 * (s1 - s0) * (b - a)
        assert p.outer_area == pytest.approx(exact, rel=1e-6)
        assert p.mass(7.85e-6) == pytest.approx(props.volume(p.solid) * 7.85e-6)
    spec = tmp_path / "p.toml"
    spec.write_text(
        PAPER_SPEC + "\n[layout]\nrings = 3\nstringers = 4\n\n[wall]\nthickness = 2.0\n\n[panels]\nseams = [0, 2]\n"
    )
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-o", str(tmp_path / "p.step"), "--report", str(tmp_path / "r.json")]
    )
    assert result.exit_code == 0, result.output
    wall = bd.import_step(tmp_path / "p.step").children[0]
    assert wall.label == "wall" and [c.label for c in wall.children] == [
        "panel_r0_s0",
        "panel_r0_s1",
        "panel_r1_s0",
        "panel_r1_s1",
    ]
    assert len(json.loads((tmp_path / "r.json").read_text())["panels"]) == 4
    with pytest.raises(ParameterError, match="seams must be one or more stringer indices"):
        split_into_panels(build, [8])


@pytest.mark.slow
def test_build_writes_polylines_by_extension(tmp_path):
    from click.testing import CliRunner
    from conftest import PAPER_SPEC

    from tubecad.cli.app import cli

    spec = tmp_path / "s.toml"
    spec.write_text(PAPER_SPEC + "\n[layout]\nrings = 3\nstringers = 2\n\n[wall]\nthickness = 2.0\n")
    result = CliRunner().invoke(
        cli, ["build", str(spec), "-o", str(tmp_path / "n.csv"), "-o", str(tmp_path / "n.json")]
    )
    assert result.exit_code == 0, result.output
    data = json.loads((tmp_path / "n.json").read_text())
    assert [ln["name"] for ln in data["lines"]][:5] == [
        "line_ring_00",
        "line_ring_01",
        "line_ring_02",
        "line_stringer_00",
        "line_stringer_01",
    ]
    assert {ln["surface_radius"] for ln in data["lines"]} == {16.0, 14.0}
    rows = (tmp_path / "n.csv").read_text().splitlines()
    assert rows[0].startswith("line,kind,index") and len(rows) == 1 + 200 * 10
