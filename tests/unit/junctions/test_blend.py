"""The crotch blend (issue 43) against closed forms that do not come from its code: on the tee
whose outer surfaces are the cylinders y^2 + z^2 = 52^2 (main along x) and
(x - 150)^2 + y^2 = 31.5^2 (branch up z), a ball of radius 5 rolled along the outer saddle.
Its rings are circles of radius 5 whose centres lie 5 from both cylinders (on
y^2 + z^2 = 57^2 and (x - 150)^2 + y^2 = 36.5^2); its edges lie on the cylinders; the wall
is one valid solid, clean by the pre-boolean check, read back from STEP."""

from __future__ import annotations

import numpy as np
import pytest

from tubecad import NaturalAxis, ParameterError
from tubecad.brep import NetLayout
from tubecad.brep.properties import analyzer_findings, is_valid, volume
from tubecad.junctions import BranchWall, branch_surface, build_branched_wall
from tubecad.surface.canal import tube_or_canal

R_O, r_O, RB = 52.0, 31.5, 5.0
MAIN = tube_or_canal(NaturalAxis("0", "0", (0.0, 300.0), origin=(0, 0, 0), tangent=(1, 0, 0), normal=(0, 1, 0)), 50.0)


@pytest.fixture(scope="module")
def blended():
    branch = branch_surface(MAIN, 150.0, 150.0, 30.0)
    return build_branched_wall(MAIN, 4.0, [BranchWall(branch, 3.0, blend=RB)], main_layout=NetLayout.equal(MAIN, 7, 8))


def points_of(edges, n=21) -> np.ndarray:
    return np.array([tuple(e.position_at(t)) for e in edges for t in np.linspace(0, 1, n)])


def test_the_blended_tee_is_one_valid_solid_larger_than_the_unblended(blended):
    plain = build_branched_wall(
        MAIN, 4.0, [BranchWall(branch_surface(MAIN, 150.0, 150.0, 30.0), 3.0)], main_layout=NetLayout.equal(MAIN, 7, 8)
    )
    assert len(blended.shape.solids()) == 1 and is_valid(blended.shape.wrapped)
    assert volume(blended.shape.wrapped) > volume(plain.shape.wrapped)  # the blend fills the corner
    assert "saddle_outer" not in blended.edges and blended.edges["saddle_inner"]


def test_the_blends_edges_lie_on_the_walls(blended):
    on_main = points_of(blended.edges["blend_main"])
    on_branch = points_of(blended.edges["blend_branch"])
    # measured 1.6e-9 and 2.9e-11 (the contact curves fitted to 2.5e-9 of the exact contacts)
    assert np.abs(np.hypot(on_main[:, 1], on_main[:, 2]) - R_O).max() < 1e-8
    assert np.abs(np.hypot(on_branch[:, 0] - 150.0, on_branch[:, 1]) - r_O).max() < 1e-8
    assert (np.hypot(on_branch[:, 1], on_branch[:, 2]) > R_O).all()  # the branch's contact clear of the main wall


def test_the_blends_rings_are_circles_of_the_ball_touching_both_walls(blended):
    """Each ring piece is an arc of radius 5 (three of its points' circumcircle) whose centre
    lies 5 from both cylinders: the ball's characteristic circle."""
    rings = [name for name in blended.edges if name.startswith("blend_ring_")]
    assert len(rings) >= 10
    for name in rings:
        for edge in blended.edges[name]:
            a, b, c = (np.array(tuple(edge.position_at(t))) for t in (0.0, 0.5, 1.0))
            ab, ac = b - a, c - a
            normal = np.cross(ab, ac)
            centre = a + (np.dot(ac, ac) * np.cross(normal, ab) + np.dot(ab, ab) * np.cross(ac, normal)) / (
                2 * np.dot(normal, normal)
            )
            assert np.linalg.norm(a - centre) == pytest.approx(RB, abs=1e-6)  # measured 2e-8
            assert np.hypot(centre[1], centre[2]) == pytest.approx(R_O + RB, abs=1e-6)
            assert np.hypot(centre[0] - 150.0, centre[1]) == pytest.approx(r_O + RB, abs=1e-6)
            points = points_of([edge])
            assert np.abs(np.linalg.norm(points - centre, axis=1) - RB).max() < 1e-6
            # the arc faces the corner: outside both walls
            assert (np.hypot(points[:, 1], points[:, 2]) > R_O - 1e-9).all()
            assert (np.hypot(points[:, 0] - 150.0, points[:, 1]) > r_O - 1e-9).all()


@pytest.mark.slow
def test_the_blended_tee_is_clean_and_reads_back(blended, tmp_path):
    from shared.step_read_back import step_read_back

    assert analyzer_findings(blended.shape.wrapped) == {}
    back = step_read_back(blended.shape, tmp_path / "blend.step")
    assert len(back.solids()) == 1 and is_valid(back.wrapped)
    assert analyzer_findings(back.solids()[0].wrapped) == {}
    assert volume(back.wrapped) == pytest.approx(volume(blended.shape.wrapped), rel=1e-12)


def test_a_blend_on_an_equal_tee_or_of_no_radius_is_refused_naming_its_key():
    equal = branch_surface(MAIN, 150.0, 150.0, 50.0)
    with pytest.raises(ParameterError, match="equal tee") as info:
        build_branched_wall(MAIN, 4.0, [BranchWall(equal, 4.0, blend=RB)])
    assert info.value.key == "branches.blend.radius"
    from tubecad.junctions.blend import rolling_ball

    with pytest.raises(ParameterError, match="radius must be > 0") as info:
        rolling_ball(MAIN, branch_surface(MAIN, 150.0, 150.0, 30.0), 0.0, 1e-8)
    assert info.value.key == "blend.radius"


@pytest.mark.parametrize(
    ("length", "radius", "says"),
    [
        # the centre's offset surfaces: the branch's (r + rb) must leave the main's (R + rb)
        # before its end, z = length on the square tee: R + rb = 52 + 100 > 150
        (150.0, 100.0, "to the branch's end (2 inside there)"),
        # the toe on the main reaches 150 +- (r + rb) along it: beyond [0, 300] for rb > 118.5
        (400.0, 120.0, "toe on the main reaches its end"),
    ],
)
def test_a_ball_that_cannot_roll_round_the_saddle_is_refused_before_anything_is_built(length, radius, says):
    """placement.blend_problem, the rule of the spec and of rolling_ball: on the square tee
    (outer R = 52, r = 31.5) the offsets' saddle runs z in [sqrt((R + rb)^2 - (r + rb)^2),
    R + rb] up the branch and 150 +- (r + rb) along the main (the closed form)."""
    from tubecad.junctions.blend import rolling_ball
    from tubecad.junctions.placement import blend_problem

    outer_main = MAIN.offset(2.0)
    outer_branch = branch_surface(MAIN, 150.0, length, 30.0).offset(1.5)
    assert says in (blend_problem(outer_main, outer_branch, radius) or "")
    with pytest.raises(ParameterError, match="does not roll") as info:
        rolling_ball(outer_main, outer_branch, radius, 1e-8)
    assert info.value.key == "blend.radius"
    # just inside both bounds: it rolls
    assert blend_problem(outer_main, branch_surface(MAIN, 150.0, 400.0, 30.0).offset(1.5), 117.0) is None
