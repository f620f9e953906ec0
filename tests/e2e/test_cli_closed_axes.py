"""Closed axes (issue 11 item 3) in spec files, from the command line: the key ``closed`` is
taken as true or false, and anything else is refused by ``tubecad report`` in one line.
"""

from click.testing import CliRunner

from tubecad.cli.app import cli
from tubecad.spec.parse import load_spec

SPEC = """
[axis]
curve = "points"
points = [[40, 0, 0], [0, 40, 10], [-40, 0, 0], [0, -40, -10]]
closed = {closed}

[tube]
radius = 4.0
"""


def test_the_spec_key_closed(tmp_path):
    path = tmp_path / "loop.toml"
    path.write_text(SPEC.format(closed="true"))
    assert load_spec(path).axis.closed
    path.write_text(SPEC.format(closed="false"))
    assert not load_spec(path).axis.closed
    path.write_text(SPEC.format(closed='"yes"'))
    result = CliRunner().invoke(cli, ["report", str(path)])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and "[axis] closed must be true or false" in lines[0] and "got a string 'yes'" in lines[0]
