"""Near-equal tees (issue 43): where the branch's radius r approaches the main's R the saddle
turns fast round the branch's sides (the branch grazes the main wall there) and the march
used to leave the branch's span ("s must lie in the span", no key). Now every r/R below 1
is followed to round-off; r = R (tangent surfaces: the equal tee) has its saddle as two curves
through the crotch points (tests/unit/junctions/test_equal_tee*.py). Checked on the closed form of perpendicular cylinders: main y^2 + z^2 = R^2 along
x, branch (x - 150)^2 + y^2 = r^2 along z."""

from __future__ import annotations

import numpy as np
import pytest

from tubecad import NaturalAxis
from tubecad.junctions import branch_surface
from tubecad.junctions.saddle import saddle_curve
from tubecad.surface.canal import tube_or_canal

R = 50.0


@pytest.fixture(scope="module")
def main():
    return tube_or_canal(NaturalAxis("0", "0", (0.0, 300.0), origin=(0, 0, 0), tangent=(1, 0, 0), normal=(0, 1, 0)), R)


@pytest.mark.parametrize("r", [49.0, 49.9, 49.95, 49.99, 49.999])
def test_a_near_equal_saddle_lies_on_both_cylinders(main, r):
    saddle = saddle_curve(main, branch_surface(main, 150.0, 150.0, r))
    p = saddle.points
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R).max() < 1e-9 * r  # measured 1.8e-15 r
    assert np.abs(np.hypot(p[:, 0] - 150.0, p[:, 1]) - r).max() < 1e-9 * r  # measured 3.0e-15 r
    # the lowest points, at the branch's sides (y = +-r), sit at z = sqrt(R^2 - r^2) above the main axis
    assert p[:, 2].min() == pytest.approx(np.sqrt(R**2 - r**2), abs=1e-6)


def test_the_one_rule_takes_a_touching_branch_and_refuses_a_wider_one(main):
    """r = R starts on the main surface (touching: the equal tee, built); r a hair wider starts
    outside it: refused naming the radius, by the spec's rule."""
    from tubecad.junctions.placement import branch_start_problem

    walls = (-2.0, 2.0)
    assert branch_start_problem(main, walls, branch_surface(main, 150.0, 150.0, R), walls, 150.0) is None
    problem = branch_start_problem(main, walls, branch_surface(main, 150.0, 150.0, R * (1 + 1e-6)), walls, 150.0)
    assert problem is not None and problem[1] == "radius" and "must start inside" in problem[0]


@pytest.mark.slow
def test_a_near_equal_tee_part_is_one_valid_solid():
    """r / R = 0.999 with 1 mm walls: one valid solid, its saddle edges within 1e-8 of the
    exact saddle (measured 2.9e-9: OCCT's intersection curves) and covering it."""
    import build123d as bd

    from tubecad import Branch, CurvatureJunction

    tee = CurvatureJunction(
        bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
        radius=R,
        thickness=1.0,
        normal=(0, 1, 0),
        rings=5,
        branches=[Branch(at=150.0, length=150.0, radius=49.95, thickness=1.0)],
    )
    report = tee.report
    assert tee.is_valid and len(tee.solids()) == 1
    for name in ("saddle_outer", "saddle_inner"):
        assert report["saddles"][name]["edges_deviation"] < 1e-8
        assert report["saddles"][name]["coverage"] == pytest.approx(1.0, abs=1e-7)
