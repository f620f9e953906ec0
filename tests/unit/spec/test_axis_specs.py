"""The new axis kinds from spec files (issue 11): natural, parametric, points, edge. Each
has a sample; bad keys are refused from the command line in tests/e2e/test_cli_spec_axes.py."""

import pytest
from conftest import ROOT

from tubecad.spec.parse import load_spec

SAMPLES = ROOT / "samples"
KINDS = {"natural": "natural.toml", "parametric": "trefoil.toml", "points": "points.toml", "edge": "edge.toml"}


@pytest.mark.slow
def test_each_kind_has_its_sample():
    """Each sample builds through `tubecad build` in tests/e2e/test_exports.py (valid, volume,
    read back) and is measured by `tubecad report` in tests/e2e/test_spec_cli.py (F = M = 0)."""
    assert {kind: load_spec(SAMPLES / name).axis.describe()["curve"] for kind, name in KINDS.items()} == {
        k: k for k in KINDS
    }


def test_the_points_report_states_the_interpolation():
    axis = load_spec(SAMPLES / "points.toml").axis.describe()
    assert axis["interpolation"] == "cubic spline (C2), centripetal parameterisation, not-a-knot ends"
    assert axis["points"] == 6
