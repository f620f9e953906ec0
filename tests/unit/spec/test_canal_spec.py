"""Radius laws in the spec (issue 12): a constant `[tube] radius` is the tube of today. The
laws as expressions and tables, measured by `tubecad report` against the surface of revolution
of their profile, and refused in one line when bad, are in tests/e2e/test_cli_canal_spec.py.
"""

from shared.canal_spec import NOZZLE


def test_a_constant_radius_is_the_tube_of_today(tmp_path):
    from tubecad.spec.parse import load_spec
    from tubecad.surface import CurvatureLineTube

    spec = tmp_path / "tube.toml"
    spec.write_text(NOZZLE.replace('radius = "40 - 25 * (s / 200)**2 * (3 - 2 * s / 200)"', "radius = 12.5"))
    assert type(load_spec(spec).tube) is CurvatureLineTube
