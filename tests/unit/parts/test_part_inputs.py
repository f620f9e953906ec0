"""What the parts take and keep (issue 42): build123d's pending edges as the axis (a BuildLine,
its Curve, a list of edges, a BuildPart's pending_edges) make the same wall as the spline edge
itself; edges that do not join are refused naming the axis; the constructor's inputs are
kept on the object, as build123d's own parts keep theirs."""

from __future__ import annotations

import build123d as bd
import pytest

from tubecad import CurvatureJunction, CurvatureWall, ParameterError, Profile, StiffenedCurvatureWall
from tubecad.curves import Axis

POINTS = ((0, 0, 0), (100, 60, 80), (250, 20, 160))


@pytest.fixture(scope="module")
def reference() -> CurvatureWall:
    return CurvatureWall(bd.Spline(*POINTS), radius=12, thickness=1.5, rings=5)


def test_a_build_line_its_curve_and_its_edges_are_the_spline_edge(reference):
    """The same curve, whichever way it is handed over: the volume to round-off (measured
    5e-15: a wire's parameter against the edge's) and the rings at the same points."""
    with bd.BuildLine() as path:
        bd.Spline(*POINTS)
    for given in (path, path.line, path.edges()):
        wall = CurvatureWall(given, radius=12, thickness=1.5, rings=5)
        assert wall.is_valid and wall.volume == pytest.approx(reference.volume, rel=1e-13)
        for ring, ref in zip(wall.rings, reference.rings):
            assert (ring.center() - ref.center()).length < 1e-9


def test_a_build_parts_pending_edges_are_an_axis(reference):
    with bd.BuildPart() as p:
        with bd.BuildLine():
            bd.Spline(*POINTS)
        wall = CurvatureWall(p.pending_edges, radius=12, thickness=1.5, rings=5, mode=bd.Mode.PRIVATE)
    assert wall.volume == pytest.approx(reference.volume, rel=1e-13)


def test_edges_that_do_not_join_are_refused_naming_the_axis():
    apart = [bd.Edge.make_line((0, 0, 0), (100, 0, 0)), bd.Edge.make_line((200, 0, 0), (300, 0, 0))]
    with pytest.raises(ParameterError, match=r"^axis: the 2 edges do not join end to end into one line \(2 pieces\)"):
        CurvatureWall(apart, radius=12, thickness=1.5)


def test_the_inputs_are_kept_on_the_part(reference):
    assert isinstance(reference.axis, Axis) and reference.axis.length == pytest.approx(reference.surface.length)
    assert (reference.radius, reference.thickness, reference.side) == (12, 1.5, "centered")
    stiffened = StiffenedCurvatureWall(
        bd.Spline(*POINTS), radius=12, thickness=1.5, rings=3, ring_frames=[1], stringer_stiffeners=()
    )
    assert stiffened.ring_frames == [1] and stiffened.stringer_stiffeners == ()
    assert stiffened.profile == Profile() and stiffened.stiffener_side == "outside"
    # kept through a copy, as build123d keeps a Box's length
    moved = bd.Pos(0, 0, 10) * stiffened
    assert moved.radius == 12 and moved.ring_frames == [1]


@pytest.mark.slow
def test_the_junction_keeps_its_inputs():
    from tubecad import Branch

    branch = Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0)
    tee = CurvatureJunction(bd.Edge.make_line((0, 0, 0), (300, 0, 0)), radius=50.0, thickness=4.0, branches=[branch])
    assert tee.branches == (branch,) and (tee.radius, tee.thickness, tee.side) == (50.0, 4.0, "centered")
    assert tee.axis.length == pytest.approx(300.0, rel=1e-12)
