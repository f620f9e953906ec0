"""Radius laws in the spec (issue 12): tests/unit/spec/test_canal_spec.py and
tests/e2e/test_cli_canal_spec.py.

NOZZLE: a straight axis 200 long whose radius steps smoothly from 40 to 15."""

NOZZLE = """
[axis]
curve = "natural"
k = "0"
tau = "0"
s = [0.0, 200.0]

[tube]
radius = "40 - 25 * (s / 200)**2 * (3 - 2 * s / 200)"
"""
