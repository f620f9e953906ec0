"""The CadQuery plugin's curvatureTube and curvatureWall (issue 23): the build123d objects'
twins, the same arguments and engine; tested where CadQuery is installed (CI's OCP 7.9
environment), with booleans, a fillet on an end ring and a STEP round trip."""

from __future__ import annotations

import math

import pytest

cq = pytest.importorskip("cadquery", reason="CadQuery is the extra tubecad[cadquery]")

import tubecad.integrations.cadquery_plugin  # noqa: F401  (registers the methods)
from tubecad import ParameterError
from tubecad.brep import properties as props

pytestmark = pytest.mark.slow

POINTS = [cq.Vector(0, 0, 0), cq.Vector(100, 60, 80), cq.Vector(250, 20, 160)]


@pytest.fixture(scope="module")
def wall():
    axis = cq.Edge.makeSpline(POINTS)
    return cq.Workplane().curvatureWall(axis, radius=12, thickness=1.5, rings=9, stringers=8).val()


def test_the_wall_is_valid_and_carries_its_named_lines(wall):
    assert isinstance(wall, cq.Solid) and wall.isValid()
    assert len(wall.rings) == 9 and [w.label for w in wall.rings][:2] == ["ring_00", "ring_01"]
    assert len(wall.stringers) == 8 and len(wall.inner_rings) == 9
    net = [
        e
        for group in (wall.rings, wall.stringers, wall.inner_rings, wall.inner_stringers)
        for w in group
        for e in w.Edges()
    ]
    edges = wall.Edges()
    assert len(edges) == len(net) and all(any(e.wrapped.IsSame(n.wrapped) for n in net) for e in edges)
    assert len(wall.Faces()) == 2 * 8 * 8 + 2


def test_the_same_wall_as_the_build123d_object(wall):
    import build123d as bd

    from tubecad import CurvatureWall

    twin = CurvatureWall(bd.Edge(cq.Edge.makeSpline(POINTS).wrapped), radius=12, thickness=1.5, rings=9, stringers=8)
    assert props.volume(wall.wrapped) == pytest.approx(props.volume(twin.wrapped), rel=1e-12)


def test_combined_with_the_stack_cut_filleted_and_round_tripped(wall, tmp_path):
    axis = cq.Edge.makeLine(cq.Vector(0, 0, 0), cq.Vector(0, 0, 100))
    plate = cq.Workplane().box(80, 80, 10).curvatureWall(axis, radius=10, thickness=2, rings=3, stringers=4)
    solid = plate.val()
    assert solid.isValid() and len(plate.solids().vals()) == 1  # fused with the plate
    assert props.volume(solid.wrapped) == pytest.approx(80 * 80 * 10 + math.pi * (11**2 - 9**2) * 95, rel=1e-9)
    tube = cq.Workplane().curvatureWall(axis, radius=10, thickness=2, rings=3, stringers=4).val()
    rounded = tube.fillet(0.5, tube.rings[-1].Edges())
    assert rounded.isValid() and rounded.Volume() < tube.Volume()
    cut = cq.Workplane().add(tube).cut(cq.Workplane().box(30, 30, 30)).val()
    assert cut.isValid() and props.volume(cut.wrapped) == pytest.approx(math.pi * (11**2 - 9**2) * 85, rel=1e-9)
    path = tmp_path / "wall.step"
    cq.exporters.export(cq.Workplane().add(cut), str(path))
    back = cq.importers.importStep(str(path)).val()
    assert back.isValid() and props.volume(back.wrapped) == pytest.approx(props.volume(cut.wrapped), rel=1e-9)


def test_the_old_names_still_work_and_say_so():
    from tubecad import CurvatureLineTube
    from tubecad.curves.edge import edge_axis

    tube = CurvatureLineTube(edge_axis(cq.Edge.makeSpline(POINTS)), 12.0)
    with pytest.warns(DeprecationWarning, match="use curvatureWall"):
        old = cq.Workplane().curvatureLineWall(tube, thickness=1.5, rings=3, stringers=4).val()
    assert old.isValid() and len(old.rings) == 3


def test_a_bad_axis_is_refused_by_name():
    with pytest.raises(ParameterError, match="axis must be a tubecad Axis"):
        cq.Workplane().curvatureTube(42, radius=5)


def test_the_stiffened_wall_carries_labelled_stiffeners_of_exact_volume():
    """Flat-bar ring frames on a straight wall: annuli of radii R and R + h, width w (R the
    outer wall radius), as the build123d object's; fused into the stack with combine."""
    from tubecad import Profile

    axis = cq.Edge.makeLine(cq.Vector(0, 0, 0), cq.Vector(0, 0, 300))
    radius, thickness, h, w = 20.0, 2.0, 5.0, 1.5
    made = cq.Workplane().stiffenedCurvatureWall(
        axis,
        radius=radius,
        thickness=thickness,
        rings=4,
        stringers=4,
        ring_frames=[1, 2],
        stringer_stiffeners=[0],
        profile=Profile("flat", height=h, thickness=w),
    )
    compound = made.val()
    assert [s.label for s in compound.stiffeners] == ["ring_01", "ring_02", "stringer_00"]
    assert len(compound.rings) == 4 and len(compound.Solids()) == 4
    assert all(s.isValid() and props.analyzer_findings(s.wrapped) == {} for s in compound.Solids())
    r = radius + thickness / 2
    for ring in compound.stiffeners[:2]:
        assert props.volume(ring.wrapped) == pytest.approx(math.pi * ((r + h) ** 2 - r**2) * w, rel=1e-9)
    fused = cq.Workplane().box(100, 100, 10).stiffenedCurvatureWall(axis, radius=radius, thickness=thickness, rings=4)
    assert len(fused.solids().vals()) == 1 and fused.val().isValid()
    with pytest.raises(ParameterError, match="ring_frames must be"):
        cq.Workplane().stiffenedCurvatureWall(axis, radius=radius, thickness=thickness, ring_frames=[99])


def test_a_junction_carries_its_named_saddles_and_pads():
    """curvatureJunction, the CurvatureJunction's twin: a main wall round the x axis (outer radius
    52) with a square branch at x = 150 (outer radius 32) and its pad. Every point of the named
    outer saddle lies on both outer cylinders (the branch's axis through (150, 0, 0) square to
    x, along the saddle's mean direction in the yz plane, by symmetry); the solid is valid, as
    the build123d object's to 1e-12 in volume; the pad is its own labelled solid; on a plate the
    parts fuse into one valid solid."""
    import build123d as bd
    import numpy as np

    from tubecad import Branch, CurvatureJunction

    branch = Branch(at=150.0, length=120.0, radius=30.0, thickness=4.0, pad_thickness=6.0, pad_width=15.0)
    axis = cq.Edge.makeLine(cq.Vector(0, 0, 0), cq.Vector(300, 0, 0))
    tee = cq.Workplane().curvatureJunction(axis, 50.0, 4.0, [branch], rings=7, stringers=8).val()
    assert isinstance(tee, cq.Compound) and [p.label for p in tee.pads] == ["pad"]
    wall = tee.Solids()[0]
    assert wall.isValid() and tee.pads[0].isValid()
    saddle = tee.named_edges["saddle_outer"]
    assert saddle and all(e.label == "saddle_outer" for e in saddle)
    points = np.array([tuple(e.positionAt(t)) for e in saddle for t in np.linspace(0.0, 1.0, 9)])
    assert np.abs(np.hypot(points[:, 1], points[:, 2]) - 52.0).max() < 1e-8
    d = np.array([0.0, *points[:, 1:].mean(axis=0)])
    d /= np.linalg.norm(d)
    off_axis = points - [150.0, 0.0, 0.0]
    off_axis -= np.outer(off_axis @ d, d)
    assert np.abs(np.linalg.norm(off_axis, axis=1) - 32.0).max() < 1e-8
    twin = CurvatureJunction(bd.Edge(axis.wrapped), 50.0, 4.0, [branch], rings=7, stringers=8)
    assert props.volume(wall.wrapped) == pytest.approx(props.volume(twin.solids()[0].wrapped), rel=1e-12)
    plate = cq.Workplane().box(400, 200, 10).curvatureJunction(axis, 50.0, 4.0, [branch], rings=7, stringers=8)
    assert len(plate.solids().vals()) == 1 and plate.val().isValid()


def test_an_equal_tee_from_the_workplane_is_the_build123d_ones():
    """curvatureJunction with the branch's radius and wall the main's (issue 43): one valid
    solid whose outer saddle lies on both outer cylinders (radius 52; the branch's axis along
    the saddle's mean direction in the yz plane, as above) and in the planes bisecting the
    axes, the build123d object's volume to 1e-12."""
    import build123d as bd
    import numpy as np

    from tubecad import Branch, CurvatureJunction

    branch = Branch(at=150.0, length=120.0, radius=50.0, thickness=4.0)
    axis = cq.Edge.makeLine(cq.Vector(0, 0, 0), cq.Vector(300, 0, 0))
    tee = cq.Workplane().curvatureJunction(axis, 50.0, 4.0, [branch], rings=7, stringers=8).val()
    wall = tee.Solids()[0]
    assert wall.isValid()
    points = np.array([tuple(e.positionAt(t)) for e in tee.named_edges["saddle_outer"] for t in np.linspace(0, 1, 9)])
    assert np.abs(np.hypot(points[:, 1], points[:, 2]) - 52.0).max() < 1e-12 * 52
    up = np.array([0.0, *points[:, 1:].mean(axis=0)])
    up /= np.linalg.norm(up)
    x = points[:, 0] - 150.0
    height = points @ up
    assert np.minimum(np.abs(x - height), np.abs(x + height)).max() < 1e-11 * 52
    twin = CurvatureJunction(bd.Edge(axis.wrapped), 50.0, 4.0, [branch], rings=7, stringers=8)
    assert props.volume(wall.wrapped) == pytest.approx(props.volume(twin.solids()[0].wrapped), rel=1e-12)


def test_a_blended_tee_from_the_workplane():
    """A Branch with ``blend_radius`` (issue 43): one valid solid whose blend edges lie on the
    outer cylinders (52 and 31.5), no outer saddle edge left."""
    import numpy as np

    from tubecad import Branch

    branch = Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0, blend_radius=5.0)
    axis = cq.Edge.makeLine(cq.Vector(0, 0, 0), cq.Vector(300, 0, 0))
    tee = cq.Workplane().curvatureJunction(axis, 50.0, 4.0, [branch], rings=7, stringers=8).val()
    assert tee.Solids()[0].isValid() and "saddle_outer" not in tee.named_edges
    on_main = np.array([tuple(e.positionAt(t)) for e in tee.named_edges["blend_main"] for t in np.linspace(0, 1, 9)])
    assert np.abs(np.hypot(on_main[:, 1], on_main[:, 2]) - 52.0).max() < 1e-8
