"""The heights stiffeners may have (issue 9, item 7), from the command line: `tubecad build`
refuses a height the wall cannot take in one line, exit code 2, no file."""

import build123d as bd
import pytest
from click.testing import CliRunner
from conftest import PAPER_SPEC, SMALL_STIFFENED_WALL

from tubecad.cli.app import cli

STIFFENED = (
    SMALL_STIFFENED_WALL
    + """profile = "T"
height = HEIGHT
thickness = 1.0
flange_width = 4.0
flange_thickness = 1.0
side = "SIDE"
"""
)


@pytest.mark.slow
@pytest.mark.parametrize(
    "side, height, says",
    [
        (
            "outside",
            5.0,
            "[stiffeners] height must be < 3.89975 for side = 'outside' on this wall: the stringer's outer "
            "corners, sqrt((R + height)^2 + 2^2) from the axis, times max|k| must stay < 1 (R = 16, "
            "max|k| = 0.05 at s = 200), got 5",
        ),
        ("inside", 14.0, "[stiffeners] height must be < R = 14 for side = 'inside' on this wall"),
        ("inside", 6.0, None),
    ],
)
def test_stiffener_heights_on_the_command_line(tmp_path, side, height, says):
    spec = tmp_path / "s.toml"
    spec.write_text(PAPER_SPEC + STIFFENED.replace("HEIGHT", str(height)).replace("SIDE", side))
    out = tmp_path / "a.step"
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(out)])
    if says is None:
        assert result.exit_code == 0, result.output
        assert [c.label for c in bd.import_step(out).children][1:5] == [
            "ring_01",
            "ring_02",
            "stringer_00",
            "stringer_02",
        ]
    else:
        assert result.exit_code == 2 and says in result.output, result.output
        assert len(result.output.strip().splitlines()) == 1 and "Traceback" not in result.output
        assert not out.exists() and list(tmp_path.iterdir()) == [spec]
