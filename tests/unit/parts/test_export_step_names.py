"""build123d's own ``export_step`` on a tubecad part (issue 42): the part's solids are its
labelled children, so the file holds them as named products (``wall``, ``ring_01``,
``stringer_00``, ...) under the part's label, as ``tubecad build`` names them, read back by
build123d's ``import_step`` and by OCCT's XCAF reader; the part stays one valid solid per
component, of its volume, in builder and algebra mode and through copies."""

from __future__ import annotations

import copy

import build123d as bd
import numpy as np
import pytest

from tubecad import CurvatureWall, Profile, StiffenedCurvatureWall
from tubecad.export.cad import step_names

#: the volumes read back against the part's own: measured 6.4e-13 at most (stringer_01, of 300 mm^3;
#: 1.1e-13 for the ring frame, 3e-15 for the wall), 7.4e-14 for a whole part
VOLUME_RTOL = 1e-12

SPLINE_POINTS = ((0, 0, 0), (60, 30, 40), (120, 0, 90))


def stiffened(**placement) -> StiffenedCurvatureWall:
    """A small straight wall with a ring frame and two stringer stiffeners (0.1 s)."""
    return StiffenedCurvatureWall(
        bd.Edge.make_line((0, 0, 0), (0, 0, 100)),
        radius=10,
        thickness=1,
        rings=3,
        stringers=2,
        ring_frames=[1],
        stringer_stiffeners="all",
        profile=Profile("flat", height=3, thickness=1),
        **placement,
    )


def plain() -> CurvatureWall:
    return CurvatureWall(bd.Spline(*SPLINE_POINTS), radius=8, thickness=1.0, rings=5, stringers=4)


def round_trip(part: bd.Shape, path) -> bd.Compound:
    bd.export_step(part, str(path))
    back = bd.import_step(str(path))
    assert isinstance(back, bd.Compound)
    return back


def same_solids(children, solids) -> bool:
    """Whether the children are the part's solids themselves (TopoDS IsSame), in order."""
    return len(children) == len(solids) and all(c.wrapped.IsSame(s.wrapped) for c, s in zip(children, solids))


def relative(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def test_a_stiffened_walls_step_file_names_the_wall_and_each_stiffener(tmp_path):
    part = stiffened()
    stiffener_names = [s.label for s in part.stiffeners]
    assert stiffener_names == ["ring_01", "stringer_00", "stringer_01"]
    back = round_trip(part, tmp_path / "stiffened.step")
    assert back.label == "StiffenedCurvatureWall"
    assert [c.label for c in back.children] == ["wall", *stiffener_names]
    # OCCT's XCAF reader: one assembly product, a product per solid under it
    assert step_names(tmp_path / "stiffened.step") == [
        (0, "StiffenedCurvatureWall"),
        (1, "wall"),
        *[(1, name) for name in stiffener_names],
    ]
    # each product one valid solid, of the part's solid's volume
    for child, solid in zip(back.children, part.solids()):
        assert len(child.solids()) == 1 and child.is_valid
        assert relative(child.volume, solid.volume) < VOLUME_RTOL
    assert relative(back.volume, part.volume) < VOLUME_RTOL


def test_a_plain_walls_step_file_names_its_wall(tmp_path):
    part = plain()
    back = round_trip(part, tmp_path / "wall.step")
    assert back.label == "CurvatureWall" and [c.label for c in back.children] == ["wall"]
    assert step_names(tmp_path / "wall.step") == [(0, "CurvatureWall"), (1, "wall")]
    assert len(back.solids()) == 1 and back.is_valid
    assert relative(back.volume, part.volume) < VOLUME_RTOL
    # the curvature lines are edges of the solid, not products of their own
    assert len(back.edges()) == len(part.edges())


def test_the_children_are_the_parts_own_solids_and_leave_it_as_it_was():
    part = stiffened()
    solids, volume = part.solids(), part.volume
    assert [c.label for c in part.children] == ["wall", "ring_01", "stringer_00", "stringer_01"]
    assert same_solids(part.children, solids) and all(c.parent is part for c in part.children)
    assert same_solids(part.solids(), solids) and part.volume == pytest.approx(volume, rel=1e-15)
    assert part.is_valid and all(s.is_valid for s in part.solids())
    assert [s.label for s in part.stiffeners] == ["ring_01", "stringer_00", "stringer_01"]
    assert len(part.rings) == 3 and len(part.stringers) == 2


def test_a_label_of_ones_own_is_the_files_top_product(tmp_path):
    part = plain()
    part.label = "hull"
    bd.export_step(part, str(tmp_path / "hull.step"))
    assert step_names(tmp_path / "hull.step") == [(0, "hull"), (1, "wall")]


def test_in_an_assembly_of_ones_own_the_part_is_a_named_sub_assembly(tmp_path):
    part = stiffened()
    box = bd.Pos(50, 0, 0) * bd.Box(5, 5, 5)
    box.label = "box"
    back = round_trip(bd.Compound(label="rig", children=[part, box]), tmp_path / "rig.step")
    assert step_names(tmp_path / "rig.step") == [
        (0, "rig"),
        (1, "StiffenedCurvatureWall"),
        *[(2, name) for name in ("wall", "ring_01", "stringer_00", "stringer_01")],
        (1, "box"),
    ]
    assert relative(back.volume, part.volume + 125) < VOLUME_RTOL


@pytest.mark.slow  # 3 to 4 s: the builder fuses the stiffeners, the walls and the plate
def test_builder_mode_names_every_placed_copy(tmp_path):
    with bd.BuildPart() as p:
        bd.Box(300, 300, 10, align=(bd.Align.CENTER, bd.Align.CENTER, bd.Align.MAX))
        with bd.Locations((0, 0, 0), (100, 0, 0)):
            part = stiffened()
    assert p.part.is_valid and len(p.part.solids()) == 1
    names = ["wall", "ring_01", "stringer_00", "stringer_01"]
    assert [c.label for c in part.children] == names * 2
    assert same_solids(part.children, part.solids())
    back = round_trip(part, tmp_path / "two.step")
    assert [c.label for c in back.children] == names * 2
    first, second = back.children[:4], back.children[4:]
    for a, b, solid in zip(first, second, part.solids()):  # the same solid, 100 apart in x
        assert np.allclose(np.array(tuple(b.center())) - np.array(tuple(a.center())), (100, 0, 0), atol=1e-7)
        assert relative(a.volume, solid.volume) < VOLUME_RTOL
    assert relative(back.volume, part.volume) < VOLUME_RTOL


def test_rotation_align_and_locations_place_the_named_solids(tmp_path):
    """Mode.PRIVATE: placed, not fused (a fuse of the copies turned by 30 deg takes OCCT 40 s)."""
    with bd.BuildPart():
        with bd.Locations((0, 0, 0), (0, 0, 300)):
            part = stiffened(
                rotation=(0, 90, 0), align=(bd.Align.MIN, bd.Align.CENTER, bd.Align.MIN), mode=bd.Mode.PRIVATE
            )
    assert [c.label for c in part.children] == ["wall", "ring_01", "stringer_00", "stringer_01"] * 2
    assert same_solids(part.children, part.solids())
    back = round_trip(part, tmp_path / "placed.step")
    assert [c.label for c in back.children] == [c.label for c in part.children]
    for child, solid in zip(back.children, part.solids()):  # where the part has them
        assert np.allclose(tuple(child.center()), tuple(solid.center()), atol=1e-7)
        assert relative(child.volume, solid.volume) < VOLUME_RTOL
    wall = back.children[0].bounding_box()  # the axis along x after the turn, from x = 0
    assert wall.min.X == pytest.approx(0, abs=1e-6) and wall.max.X == pytest.approx(100, abs=1e-5)


@pytest.mark.slow  # 2.5 s: booleans, copies and three STEP round trips
def test_algebra_mode_booleans_placements_and_copies(tmp_path):
    part = stiffened()
    volume, solids = part.volume, part.solids()
    box = bd.Box(40, 40, 40)  # the origin's box takes the wall's first end away
    cut, fused = part - box, part + bd.Pos(0, 0, 150) * box
    assert cut.is_valid and 0 < cut.volume < volume
    assert fused.is_valid and len(fused.solids()) == 2  # the wall with its stiffeners fused, and the box
    assert part.volume == pytest.approx(volume, rel=1e-15) and same_solids(part.solids(), solids)

    moved = bd.Pos(0, 200, 0) * part
    assert [c.label for c in moved.children] == [c.label for c in part.children]
    assert same_solids(moved.children, moved.solids())
    assert moved.children[0].center().Y == pytest.approx(part.children[0].center().Y + 200, abs=1e-9)
    back = round_trip(moved, tmp_path / "moved.step")
    assert [c.label for c in back.children] == ["wall", "ring_01", "stringer_00", "stringer_01"]
    assert back.children[0].center().Y == pytest.approx(200, abs=1e-7)
    assert relative(back.volume, volume) < VOLUME_RTOL

    for other in (copy.copy(part), copy.deepcopy(part)):
        assert other.label == "StiffenedCurvatureWall"
        assert [c.label for c in other.children] == ["wall", "ring_01", "stringer_00", "stringer_01"]
        assert same_solids(other.children, other.solids()) and all(c.parent is other for c in other.children)
        assert other.is_valid and relative(other.volume, volume) < 1e-15
    assert same_solids(copy.copy(part).solids(), solids)  # a shallow copy shares the solids

    part.move(bd.Pos(0, 0, 50))  # in place: the children follow
    assert part.children[0].center().Z == pytest.approx(solids[0].center().Z + 50, abs=1e-9)
    back = round_trip(part, tmp_path / "in_place.step")
    assert back.children[0].center().Z == pytest.approx(solids[0].center().Z + 50, abs=1e-7)


def test_the_assembly_keeps_the_lines_names_through_build123ds_export(tmp_path):
    """``part.assembly()`` adds the curvature lines, labelled as ``tubecad build`` labels them,
    and build123d's export_step keeps every name. Read back with build123d's import_step and
    checked on the closed form of a straight wall along z: the outer rings on x^2 + y^2 = 11^2
    at z = 0, 50, 100, the inner ones on 9^2, the stringers on the same cylinders."""
    wall = CurvatureWall(bd.Edge.make_line((0, 0, 0), (0, 0, 100)), radius=10.0, thickness=2.0, rings=3, stringers=4)
    path = tmp_path / "wall.step"
    bd.export_step(wall.assembly(), path)
    read = bd.import_step(path)
    by_label = {child.label: child for child in read.children}
    assert set(by_label) == {"wall", "curvature_lines"}
    lines = {child.label: child for child in by_label["curvature_lines"].children}
    expected = {f"ring_{i:02d}{s}" for i in range(3) for s in ("", "_inner")}
    expected |= {f"stringer_{j:02d}{s}" for j in range(4) for s in ("", "_inner")}
    assert set(lines) == expected
    for name, line in lines.items():
        points = np.array([tuple(e.position_at(t)) for e in line.edges() for t in np.linspace(0, 1, 9)])
        radius = 9.0 if name.endswith("_inner") else 11.0
        assert np.abs(np.hypot(points[:, 0], points[:, 1]) - radius).max() < 1e-7, name  # measured 2e-15
        if name.startswith("ring_"):
            assert np.abs(points[:, 2] - 50.0 * int(name[5:7])).max() < 1e-9, name
    assert wall.children and all(child.parent is wall for child in wall.children)  # the part is unchanged
