"""Shared fixtures: one tube per axis family, each regular over its span."""

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
