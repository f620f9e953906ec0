"""Canal surfaces on closed axes: tests/unit/brep/test_closed_canal.py and
tests/e2e/test_cli_closed_canal.py. The trefoil itself is shared.closed_tubes'."""

#: the trefoil scaled by 40, closed, as a spec: ``CLOSED_TREFOIL.format(radius=...)``
CLOSED_TREFOIL = """
[axis]
curve = "parametric"
x = "40 * (sin(t) + 2 * sin(2 * t))"
y = "40 * (cos(t) - 2 * cos(2 * t))"
z = "-40 * sin(3 * t)"
t = [0.0, 6.283185307179586]
closed = true

[tube]
radius = {radius}

[layout]
rings = 5
stringers = 4

[wall]
thickness = 1.0
"""
