"""A small wall in the spec's length unit (issue 5): tests/unit/spec/test_schema_units.py and
tests/e2e/test_cli_schema_units.py."""

SMALL = """
[axis]
curve = "helix"
k = 0.01
beta_deg = 10.0
s = [0.0, 300.0]

[tube]
radius = 10.0

[layout]
rings = 3
stringers = 4

[wall]
thickness = 1.0
"""


def with_units(text: str, unit: str | None) -> str:
    return text if unit is None else f'{text}\n[units]\nlength = "{unit}"\n'


STIFFENED = (
    SMALL
    + """
[stiffeners]
rings = [1]
profile = "flat"
height = 2.0
thickness = 1.0
"""
)
