"""The tee of the junction's shell model (issue 25): tests/unit/fem/test_junction_fem.py and
tests/e2e/test_cli_junction_fem.py. Its mid-surfaces are the cylinders y^2 + z^2 = R^2 along x
(the main) and (x - AT)^2 + y^2 = r^2 along z (the branch)."""

from __future__ import annotations

import numpy as np
import pytest

R, T, r, t, AT = 50.0, 2.0, 30.0, 2.0, 300.0
TEE = f"""
[axis]
curve = "natural"
k = "0"
tau = "0"
s = [0.0, 600.0]

[tube]
radius = {R}

[layout]
rings = 5
stringers = 8

[wall]
thickness = {T}

[[branches]]
at = {AT}
length = 250.0
radius = {r}
wall = {{ thickness = {t} }}
layout = {{ rings = 4, stringers = 8 }}

[mesh]
size = 8.0
"""
PAD = "pad = { thickness = 3.0, width = 20.0 }\n"


@pytest.fixture(scope="module", name="tee")
def tee_fixture(tmp_path_factory):
    """The tee's spec (with a pad) and its mesh as tubecad mesh writes it."""
    from tubecad.spec.mesh import mesh_from_spec
    from tubecad.spec.parse import load_spec

    folder = tmp_path_factory.mktemp("tee")
    spec = folder / "tee.toml"
    spec.write_text(TEE.replace("layout = { rings = 4", PAD + "layout = { rings = 4"))
    return spec, mesh_from_spec(load_spec(spec))


def main_gap(p: np.ndarray) -> np.ndarray:
    return np.hypot(p[..., 1], p[..., 2]) - R


def branch_gap(p: np.ndarray) -> np.ndarray:
    return np.hypot(p[..., 0] - AT, p[..., 1]) - r
