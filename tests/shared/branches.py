"""A straight main tube and a branch, as spec text (issue 25): tests/unit/spec/test_branches.py
and tests/e2e/test_cli_branches.py."""

MAIN = """
[axis]
curve = "natural"
k = "0"
tau = "0"
s = [0.0, 400.0]

[tube]
radius = 50.0

[wall]
thickness = 4.0
"""
BRANCH = """
[[branches]]
at = 150.0
length = 150.0
radius = 30.0
"""


def spec_text(branch: str = BRANCH, main: str = MAIN) -> str:
    return main + branch
