"""The crotch blend from the command line and the build123d part (issue 43): what a blended
junction cannot be yet (its shop package, its shell model, a pad beside it, a blend on an
equal tee) is refused in one line naming the key, exit code 2, no file; the part takes
``blend_radius`` and names the blend's edges."""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from conftest import ROOT

from tubecad.cli.app import cli

SAMPLE = (ROOT / "samples" / "blend_tee.toml").read_text()


@pytest.mark.parametrize(
    ("command", "edit", "key", "says"),
    [
        (["shop", "{spec}", "-o", "{out}/shop"], None, "blend", "the shop package"),
        (["mesh", "{spec}", "-o", "{out}/x.inp"], None, "blend", "its shell model"),
        (
            ["build", "{spec}", "-o", "{out}/x.step"],
            (("blend = {", "pad = { thickness = 6.0, width = 20.0 }\nblend = {"),),
            "blend",
            "with a pad",
        ),
        (
            ["build", "{spec}", "-o", "{out}/x.step"],
            (("blend = { radius = 6.0 }", "blend = { radius = -1.0 }"),),
            "blend.radius",
            "> 0",
        ),
        (
            ["build", "{spec}", "-o", "{out}/x.step"],
            (("radius = 30.0", "radius = 50.0"), ("thickness = 3.0 }", "thickness = 4.0 }")),
            "blend.radius",
            "equal tee",
        ),
    ],
)
def test_what_a_blended_junction_cannot_be_yet_is_refused_naming_the_key(tmp_path, command, edit, key, says):
    text = SAMPLE
    for old, new in edit or ():
        text = text.replace(old, new, 1)
    spec = tmp_path / "tee.toml"
    spec.write_text(text)
    out = tmp_path / "out"
    out.mkdir()
    result = CliRunner().invoke(cli, [a.format(spec=spec, out=out) for a in command])
    assert result.exit_code == 2, result.output
    line = result.output.strip().splitlines()[-1]
    assert "[[branches]]" in line and key.split(".")[0] in line, line
    assert says in line and "Traceback" not in result.output
    assert list(out.iterdir()) == []


@pytest.mark.slow
def test_the_part_takes_a_blend_radius():
    import build123d as bd
    import numpy as np

    from tubecad import Branch, CurvatureJunction

    part = CurvatureJunction(
        bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
        radius=50.0,
        thickness=4.0,
        normal=(0, 1, 0),
        rings=5,
        branches=[Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0, blend_radius=5.0)],
    )
    assert part.is_valid and len(part.solids()) == 1
    names = set(part.named_edges)
    assert {"blend_main", "blend_branch"} <= names and "saddle_outer" not in names
    points = np.array([tuple(e.position_at(t)) for e in part.named_edges["blend_main"] for t in np.linspace(0, 1, 9)])
    assert np.abs(np.hypot(points[:, 1], points[:, 2]) - 52.0).max() < 1e-8
