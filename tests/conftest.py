"""Shared fixtures: one tube per axis family, each regular over its span."""

from pathlib import Path

import numpy as np
import pytest

from tubecad import CircleInvolute, Clothoid, CurvatureLineTube, CustomCurvature, Helix, LogSpiral

FAMILY_CASES = {
    "log_spiral": (lambda: LogSpiral(10.0, 10.0, (200.0, 1200.0)), 15.0),
    "helix": (lambda: Helix(0.0097, 10.0, (0.0, 1500.0)), 12.0),
    "circle": (lambda: Helix(0.02, 0.0, (0.0, 250.0)), 10.0),
    "clothoid": (lambda: Clothoid(400.0, 5.0, (-600.0, 900.0)), 10.0),
    "involute": (lambda: CircleInvolute(20.0, 15.0, (50.0, 2000.0)), 8.0),
    "custom": (lambda: CustomCurvature("0.004 + 0.003 * sin(2 * pi * s / 500)", 8.0, (0.0, 1500.0)), 20.0),
    "negative_beta": (lambda: LogSpiral(4.0, -35.0, (60.0, 400.0)), 5.0),
}


#: the paper's tube as a minimal spec ([axis] and [tube] only)
PAPER_SPEC = """
[axis]
curve = "log_spiral"
a = 10.0
beta_deg = 10.0
s = [200.0, 1200.0]

[tube]
radius = 15.0
"""


@pytest.fixture(params=sorted(FAMILY_CASES))
def family_tube(request) -> CurvatureLineTube:
    make_axis, radius = FAMILY_CASES[request.param]
    return CurvatureLineTube(make_axis(), radius)


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261122)


def assert_build_refused(tmp_path, spec_text: str, says: str) -> None:
    """`tubecad build` of ``spec_text`` exits 2 with one line containing ``says``, and
    writes no file."""
    from click.testing import CliRunner

    from tubecad.cli.app import cli

    spec = tmp_path / "bad.toml"
    spec.write_text(spec_text)
    out = tmp_path / "out.step"
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(out)])
    assert result.exit_code == 2, result.output
    message = result.output.strip()
    assert "\n" not in message and says in message, message
    assert not out.exists()


#: a small stiffened wall for PAPER_SPEC: 4 x 4 layout, rings 1 and 2 and stringers 0 and 2
#: stiffened; the profile's keys follow
SMALL_STIFFENED_WALL = """
[layout]
rings = 4
stringers = 4

[wall]
thickness = 2.0

[stiffeners]
rings = [1, 2]
stringers = [0, 2]
"""


SAMPLES = Path(__file__).resolve().parent.parent / "samples"


def sample_wall_spec(name: str) -> str:
    """samples/NAME.toml without its [stiffeners] section (which the samples keep last): its
    wall alone, for tests that do not need the stiffeners."""
    return (SAMPLES / f"{name}.toml").read_text().split("\n[stiffeners]")[0]


def fit_circle(xy: np.ndarray) -> tuple[float, float, np.ndarray]:
    """(largest distance from the least-squares circle, its radius, its centre) of plane points."""
    import math

    sol = np.linalg.lstsq(np.c_[2 * xy, np.ones(len(xy))], (xy**2).sum(axis=1), rcond=None)[0]
    radius = math.sqrt(sol[2] + sol[0] ** 2 + sol[1] ** 2)
    return np.abs(np.linalg.norm(xy - sol[:2], axis=1) - radius).max(), radius, sol[:2]


#: a small helix tube for batches (about half a second a job): radius 5, 300 long, 3 rings, 2 stringers
SMALL_BATCH_TUBE = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 300.0]

[tube]
radius = 5.0

[layout]
rings = 3
stringers = 2
"""
