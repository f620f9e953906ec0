"""The build123d object CurvatureJunction (issue 25): a part in builder and algebra mode whose
named edges (the saddles, both tubes' nets) follow every placed copy, checked on the closed
form of the perpendicular tee: main y^2 + z^2 = R^2 along x, branch (x - 150)^2 + y^2 = r^2."""

from __future__ import annotations

import build123d as bd
import numpy as np
import pytest

from tubecad import Branch, CurvatureJunction, ParameterError
from tubecad.brep.properties import is_valid

R_OUT, r_OUT, R_IN, r_IN = 52.0, 31.5, 48.0, 28.5


def tee(**placement) -> CurvatureJunction:
    return CurvatureJunction(
        bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
        radius=50.0,
        thickness=4.0,
        normal=(0, 1, 0),  # r1 = y, r2 = z: the branch (around 90 deg) stands up z
        rings=5,
        branches=[Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0)],
        **placement,
    )


@pytest.fixture(scope="module")
def part() -> CurvatureJunction:
    return tee()


def on_tee(edges, offset=(0.0, 0.0, 0.0), big=R_OUT, small=r_OUT) -> float:
    """The largest distance of the edges' points from the two cylinders (moved by offset)."""
    p = np.array([tuple(e.position_at(t)) for e in edges for t in np.linspace(0, 1, 9)]) - offset
    return max(np.abs(np.hypot(p[:, 1], p[:, 2]) - big).max(), np.abs(np.hypot(p[:, 0] - 150, p[:, 1]) - small).max())


def test_the_part_is_one_valid_solid_with_named_saddles(part):
    assert is_valid(part.wrapped) and len(part.solids()) == 1
    named = part.named_edges
    assert {"saddle_outer", "saddle_inner", "main_ring_00", "branch_stringer_03_inner"} <= set(named)
    assert all(e.label == "saddle_outer" for e in part.saddle_outer)
    # measured 2e-7 (OCCT's intersection curves)
    assert on_tee(part.saddle_outer) < 1e-6 and on_tee(part.saddle_inner, big=R_IN, small=r_IN) < 1e-6
    assert part.junction.coverage["saddle_outer"] == pytest.approx(1.0, abs=1e-8)


def test_the_names_follow_the_copies_in_builder_and_algebra_mode(part):
    with bd.BuildPart() as builder:
        with bd.Locations((0, 0, 0), (0, 400, 0)):
            placed = tee(mode=bd.Mode.ADD)
    assert is_valid(builder.part.wrapped) and len(builder.part.solids()) == 2
    saddles = placed.saddle_outer
    assert len(saddles) == 2 * len(part.saddle_outer)
    first, second = saddles[: len(saddles) // 2], saddles[len(saddles) // 2 :]
    assert on_tee(first) < 1e-6 and on_tee(second, (0, 400, 0)) < 1e-6
    moved = bd.Pos(0, 0, 100) * part
    assert on_tee(moved.saddle_outer, (0, 0, 100)) < 1e-6 and on_tee(part.saddle_outer) < 1e-6


def test_a_branch_along_the_main_axis_is_refused_naming_its_key():
    with pytest.raises(ParameterError) as info:
        CurvatureJunction(
            bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
            radius=50.0,
            thickness=4.0,
            branches=[Branch(at=150.0, length=120.0, radius=30.0, angle=0.0)],
        )
    assert info.value.key == "angle" and "\n" not in str(info.value)


def test_a_branch_with_a_pad_gives_the_part_a_pad_solid_in_every_copy():
    with bd.BuildPart() as builder:
        with bd.Locations((0, 0, 0), (0, 400, 0)):
            placed = CurvatureJunction(
                bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
                radius=50.0,
                thickness=4.0,
                normal=(0, 1, 0),
                rings=5,
                branches=[
                    Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0, pad_thickness=6.0, pad_width=20.0)
                ],
                mode=bd.Mode.PRIVATE,
            )
    pads = placed.pads
    assert [p.label for p in pads] == ["pad", "pad"] and all(is_valid(p.wrapped) for p in pads)
    assert pads[1].center().Y - pads[0].center().Y == pytest.approx(400.0)
    assert on_tee(placed.saddle_outer[: len(placed.saddle_outer) // 2]) < 1e-6
    del builder


@pytest.mark.requires("gmsh")
def test_the_part_gives_its_shell_model_on_the_walls_mid_surfaces(part):
    """shell_model: the walls' mid-surfaces (main y^2 + z^2 = 50^2, branch (x - 150)^2 + y^2 =
    30^2 with the branch's 3 mm wall) joined on their saddle, whose nodes lie on both; its
    branch end in the plane z = 120, its ends of the main in x = 0 and x = 300."""
    fe = part.shell_model(size=12.0)
    saddle = fe.nodes[fe.node_sets["saddle"]]
    assert len(saddle) >= 32
    assert np.abs(np.hypot(saddle[:, 1], saddle[:, 2]) - 50.0).max() < 1e-6  # measured 2e-8
    assert np.abs(np.hypot(saddle[:, 0] - 150.0, saddle[:, 1]) - 30.0).max() < 1e-6
    assert np.abs(fe.nodes[fe.node_sets["branch_end"], 2] - 120.0).max() < 1e-9
    assert np.abs(fe.nodes[fe.node_sets["main_end"], 0] - 300.0).max() < 1e-9
    assert {s.block: s.thickness for s in fe.shell_sections}["branch"] == 3.0
    assert [t.name for t in part.shell_tubes] == ["main", "branch"]


def test_the_junction_is_a_part_like_the_others(part, tmp_path):
    """Issue 42: rings, stringers, inner ones, saddles, surface, report and design, as a wall
    part has them. A ring lies on the main's outer cylinder y^2 + z^2 = R_o^2 at its station
    x = s; a stringer the opening cuts (the one at 90 deg, under the branch) is two wires,
    each ending on the outer saddle, which lies on both cylinders; build123d's own
    export_step names the wall."""
    import re

    from tubecad import JunctionDesign, WallDesign

    rings = part.rings
    assert [w.label for w in rings] == [f"ring_{i:02d}" for i in range(5)]
    for wire, s in zip(rings, part.layout.s_rings):
        p = np.array([tuple(wire.position_at(t)) for t in np.linspace(0, 1, 33)])
        assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R_OUT).max() < 1e-7  # measured 1e-13
        assert np.abs(p[:, 0] - s).max() < 1e-7
    for wire in part.inner_rings:
        p = np.array([tuple(wire.position_at(t)) for t in np.linspace(0, 1, 33)])
        assert np.abs(np.hypot(p[:, 1], p[:, 2]) - R_IN).max() < 1e-7
    under = [w for w in part.stringers if w.label == "stringer_02"]  # 8 stringers: 02 at 90 deg, +z
    assert len(under) == 2, [w.label for w in part.stringers]
    saddle = np.array([tuple(e.position_at(t)) for e in part.saddles["saddle_outer"] for t in np.linspace(0, 1, 65)])
    for wire in under:
        ends = [np.array(tuple(wire.position_at(t))) for t in (0.0, 1.0)]
        assert min(np.linalg.norm(saddle - end, axis=1).min() for end in ends) < 0.5  # the saddle's samples' spacing
    assert set(part.saddles) == {"saddle_outer", "saddle_inner"}
    assert part.surface.radius_law.constant_value == 50.0
    assert isinstance(part.design, JunctionDesign) and isinstance(part.design.main, WallDesign)
    report = part.report
    assert report["valid"] and report["saddles"]["saddle_outer"]["edges_deviation"] < 1e-6
    assert report["volume"] == pytest.approx(part.volume, rel=1e-12)
    bd.export_step(part, tmp_path / "tee.step")
    assert re.findall(r"PRODUCT\('([^']*)'", (tmp_path / "tee.step").read_text()) == ["CurvatureJunction", "wall"]
    # with its lines: every named edge set, the saddles on both cylinders as read back
    bd.export_step(part.assembly(), tmp_path / "tee_lines.step")
    lines = {c.label: c for c in bd.import_step(tmp_path / "tee_lines.step").children if c.label == "curvature_lines"}
    sets = {c.label: c for c in lines["curvature_lines"].children}
    assert set(sets) == set(part.named_edges)
    assert (
        on_tee(sets["saddle_outer"].edges()) < 1e-6
        and on_tee(sets["saddle_inner"].edges(), big=R_IN, small=r_IN) < 1e-6
    )


def test_an_equal_tee_part_in_builder_and_algebra_mode():
    """radius = the main's (issue 43): the saddles are two ellipse arcs each, on both cylinders
    (measured 9e-14); the part moves with its names in algebra mode and is placed in a BuildPart."""

    def equal(**placement) -> CurvatureJunction:
        return CurvatureJunction(
            bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
            radius=50.0,
            thickness=4.0,
            normal=(0, 1, 0),
            rings=5,
            branches=[Branch(at=150.0, length=120.0, radius=50.0, thickness=4.0)],
            **placement,
        )

    part = equal()
    assert is_valid(part.wrapped) and len(part.solids()) == 1
    assert on_tee(part.saddle_outer, big=R_OUT, small=R_OUT) < 1e-12 * R_OUT
    assert on_tee(part.saddle_inner, big=R_IN, small=R_IN) < 1e-12 * R_IN
    assert part.report["saddles"]["saddle_outer"]["curves"] == "2 ellipse arcs"
    moved = bd.Pos(0, 0, 100) * part
    assert on_tee(moved.saddle_outer, (0.0, 0.0, 100.0), R_OUT, R_OUT) < 1e-11
    with bd.BuildPart() as builder:
        with bd.Locations((0, 0, 0), (0, 400, 0)):
            placed = equal(mode=bd.Mode.ADD)
    assert is_valid(builder.part.wrapped) and len(builder.part.solids()) == 2
    assert len(placed.saddle_outer) == 2 * len(part.saddle_outer)
