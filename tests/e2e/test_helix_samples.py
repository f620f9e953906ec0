"""The helix samples' comments state what tubecad builds (issue 41: they said pitch 64.9 where
the axis rises 110.8 per turn): each number is measured here on the axis itself."""

import re

import numpy as np
import pytest
from conftest import ROOT

from tubecad.spec.parse import load_spec

SAMPLES = ROOT / "samples"
#: "radius ~100, pitch ~110.8" and, optionally, ", a turn ~638" (its arc length)
STATED = re.compile(r"radius ~(?P<radius>[\d.]+), pitch ~(?P<pitch>[\d.]+)(?:, a turn ~(?P<turn>[\d.]+))?")


def measured(axis) -> dict[str, float]:
    """The axis' cylinder radius, its rise per turn and a turn's arc length, from its points
    alone: the helix stands on the z axis, so its angle round z (unwrapped) grows linearly
    with s and z; least-squares lines give dz and ds per 2 pi of that angle."""
    s = np.linspace(*axis.span, 4001)
    x, y, z = axis.position(s).T
    radius = np.hypot(x, y)
    assert np.ptp(radius) < 1e-9 * radius.mean()  # on a cylinder about the z axis
    angle = np.unwrap(np.arctan2(y, x))
    per_turn = {name: 2 * np.pi * np.polyfit(angle, values, 1)[0] for name, values in (("pitch", z), ("turn", s))}
    return {"radius": float(radius.mean()), **{k: abs(float(v)) for k, v in per_turn.items()}}


@pytest.mark.parametrize("path", sorted(SAMPLES.glob("helix*.toml")), ids=lambda p: p.stem)
def test_a_helix_sample_states_the_pitch_its_axis_has(path):
    stated = STATED.search(path.read_text())
    assert stated, f"{path.name}: no 'radius ~R, pitch ~P' in its comments"
    axis = load_spec(path).tube.axis
    found = measured(axis)
    for name, text in stated.groupdict().items():
        if text is None:
            continue
        rounding = 0.5 * 10.0 ** -len(text.partition(".")[2])  # the stated number is rounded to its last digit
        assert abs(float(text) - found[name]) <= rounding, (path.name, name, text, found[name])
    # the closed forms of docs/MATH.md section 1: radius cos^2 b / k, pitch 2 pi sin b cos b / k
    assert found["pitch"] == pytest.approx(axis.pitch, rel=1e-9)
    assert found["radius"] == pytest.approx(axis.cylinder_radius, rel=1e-9)
