"""Radius laws in the spec (issue 12), from the command line: `[tube] radius` as an expression in
s or a table makes a canal surface; `tubecad report` measures it; bad laws are refused in one
line.

Independent facts: on a straight axis the canal surface is the surface of revolution of
the profile (z, rho) = (s - r r', r q), q = sqrt(1 - r'^2), whose area 2 pi Int rho dl and
enclosed volume pi Int rho^2 dz are integrated here with scipy's quad from r(s) alone.
"""

import json
import math

import pytest
from click.testing import CliRunner
from scipy.integrate import quad
from shared.canal_spec import NOZZLE

from tubecad.cli.app import cli


def nozzle_law(s: float) -> tuple[float, float, float]:
    """r, r', r'' of the smooth step 40 -> 15 over [0, 200], by hand."""
    x = s / 200
    return 40 - 25 * x * x * (3 - 2 * x), -25 * 6 * x * (1 - x) / 200, -25 * 6 * (1 - 2 * x) / 200**2


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.mark.slow
def test_report_of_a_nozzle_is_the_surface_of_revolution_of_its_profile(tmp_path):
    spec = tmp_path / "nozzle.toml"
    spec.write_text(NOZZLE)
    result = run("report", spec)
    assert result.exit_code == 0, result.output
    report = json.loads(result.output)

    def profile_speed(s: float) -> tuple[float, float, float]:  # rho, d rho/ds, dz/ds
        r, dr, ddr = nozzle_law(s)
        q = math.sqrt(1 - dr * dr)
        return r * q, dr * q - r * dr * ddr / q, 1 - dr * dr - r * ddr

    area = quad(
        lambda s: 2 * math.pi * profile_speed(s)[0] * math.hypot(*profile_speed(s)[1:]), 0, 200, epsabs=0, epsrel=1e-13
    )[0]
    # the solid between the end discs: the discs of the profile swept along z
    volume = quad(lambda s: math.pi * profile_speed(s)[0] ** 2 * profile_speed(s)[2], 0, 200, epsabs=0, epsrel=1e-13)[0]
    assert report["surface"] == "canal" and report["regular"] is True
    assert report["area_numeric"] == pytest.approx(area, rel=1e-12)
    assert report["volume_numeric"] == pytest.approx(volume, rel=1e-12)
    law = report["parameters"]["tube"]["radius"]
    assert law["min"] == pytest.approx(15.0, rel=1e-12) and law["max"] == pytest.approx(40.0, rel=1e-12)
    assert law["max_abs_slope"] == pytest.approx(25 * 6 * 0.25 / 200, rel=1e-12) and law[
        "s_at_max_abs_slope"
    ] == pytest.approx(100)
    assert report["max_orthogonality_error"] < 1e-12 and report["max_M_error"] < 1e-12


@pytest.mark.slow
def test_a_table_law_on_a_helix_has_a_curvature_line_net(tmp_path):
    spec = tmp_path / "helix.toml"
    spec.write_text(
        '[axis]\ncurve = "helix"\nk = 0.02\nbeta_deg = 20.0\ns = [0.0, 300.0]\n'
        "[tube]\nradius = [[0, 8], [100, 10], [200, 7], [300, 9]]\n"
    )
    result = run("report", spec)
    assert result.exit_code == 0, result.output
    report = json.loads(result.output)
    law = report["parameters"]["tube"]["radius"]
    assert law["kind"] == "table" and "cubic spline" in law["interpolation"]
    assert report["max_orthogonality_error"] < 1e-10 and report["max_M_error"] < 1e-10
    assert report["area_relative_error"] < 1e-10 and report["volume_relative_error"] < 1e-10


@pytest.mark.parametrize(
    "tube, extra, says",
    [
        ("radius = [[0, 40], [100, 20], [50, 45]]", "", "[tube] radius: s = 50 (row 2) follows s = 100 (row 1)"),
        ("radius = [[0, 40], [100, 20], [100, 45]]", "", "[tube] radius: s = 100 (row 2) appears twice"),
        ('radius = "10 + 1.5 * s"', "", "[tube] radius: |r'| reaches 1.5 at s = 0"),
        ('radius = "20 - 0.2 * s"', "", "[tube] radius: r reaches -20 at s = 200"),
        ('radius = "10 + log(s - 100)"', "", "[tube] radius"),
        (
            'radius = "40 - 0.1 * s"',
            "[wall]\nthickness = 41\n",
            "[wall] thickness 41 (side = 'centered') is too thick for the smallest radius 20 at s = 200",
        ),
        (
            'radius = "40 - 0.1 * s"',
            '[wall]\nthickness = 2\n[stiffeners]\nstringers = [0]\nheight = 25\nthickness = 1\nside = "inside"\n',
            "[stiffeners] height: a stringer reaches in to r -26, and the radius law's r is 20 at s = 200",
        ),
        (
            'radius = "40 - 0.1 * s"',
            '[wall]\nthickness = 2\n[stiffeners]\nrings = [3]\nheight = 39\nthickness = 1\nside = "inside"\n',
            "[stiffeners] height: the ring at s = 60 reaches in to r -40, and the radius law's r is 33.95",
        ),
        (
            "radius = [40]",
            "",
            "[tube] radius must be a number, an expression in s or a table of two or more [s, r] rows",
        ),
    ],
)
def test_bad_radius_laws_are_refused_in_one_line(tmp_path, tube, extra, says):
    spec = tmp_path / "bad.toml"
    spec.write_text('[axis]\ncurve = "natural"\nk = "0"\ntau = "0"\ns = [0.0, 200.0]\n[tube]\n' + tube + "\n" + extra)
    for command in (("report", spec), ("build", spec, "-o", tmp_path / "x.step")):
        result = run(*command)
        message = result.output.strip()
        assert result.exit_code == 2 and "\n" not in message and says in message, message
        assert not (tmp_path / "x.step").exists()


DUPIN = """
[axis]
curve = "parametric"
x = "100 * cos(t)"
y = "80 * sin(t)"
z = "0"
t = [0.0, 6.283185307179586]

[tube]
radius = "80 - 0.6 * x"
"""


def test_a_radius_expression_may_use_the_axis_point(tmp_path):
    """The ring Dupin cyclide: spheres on the ellipse x^2/100^2 + y^2/80^2 = 1 with radius
    mu - (c/a) x, c = 60, mu = 80: r is given through the axis point's x."""
    import numpy as np

    from tubecad.spec.parse import load_spec

    spec = tmp_path / "dupin.toml"
    spec.write_text(DUPIN)
    surface = load_spec(spec).tube
    s = np.linspace(*surface.span, 97)
    assert np.abs(surface.radius_law.r(s) - (80 - 0.6 * surface.axis.position(s)[:, 0])).max() < 1e-11
    assert surface.axis.closed and surface.regularity.ok
    bad = tmp_path / "bad.toml"
    bad.write_text(DUPIN.replace("0.6 * x", "0.6 * w"))
    result = run("report", bad)
    assert (
        result.exit_code == 2
        and "[tube] radius: unknown name 'w'; the names allowed are s, x, y, z, pi, e" in result.output
    )


@pytest.mark.slow
def test_a_canal_wall_splits_into_named_panels_from_the_cli(tmp_path):
    from tubecad.export.cad import step_names

    spec = tmp_path / "nozzle.toml"
    spec.write_text(
        NOZZLE + "[layout]\nrings = 5\nstringers = 4\n[wall]\nthickness = 2.0\n"
        "[panels]\nseams = [0, 2]\nrings = [0, 2, 4]\n"
    )
    out, report = tmp_path / "panels.step", tmp_path / "r.json"
    result = run("build", spec, "-o", out, "--report", report)
    assert result.exit_code == 0, result.output
    data = json.loads(report.read_text())
    panels = [p["name"] for p in data["panels"]]
    assert panels == ["panel_r0_s0", "panel_r0_s1", "panel_r1_s0", "panel_r1_s1"]
    assert set(panels) <= {name for _, name in step_names(out)}
    # the panels fill the wall: their volumes add up to its volume
    assert sum(p["volume"] for p in data["panels"]) == pytest.approx(data["brep"]["volume"], rel=1e-10)
