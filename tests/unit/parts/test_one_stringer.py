"""One stringer is one stringer (issue 41): a layout of one stringer still splits its faces
at the circle's C0 knot opposite it (a periodic face needs an edge there, and OCCT's
pre-boolean check reports a face over a C0 knot: tests/unit/brep/test_face_columns.py), but
that edge is a seam, not a stringer: ``seam_00`` in ``wall.seams``, ``line_seam_00`` in the
STEP file's ``curvature_lines``, ``main_seam_00`` on a junction, never a second stringer.

Checked on a straight cylinder, where the seam is the line diametrically opposite the
stringer: its points lie 2 rho from the stringer's at the same s."""

from __future__ import annotations

import math

import build123d as bd
import pytest

from tubecad import CurvatureTube, CurvatureWall, NaturalAxis, StiffenedCurvatureWall
from tubecad.brep import NetLayout, build_wall_solid
from tubecad.core.errors import SpecError
from tubecad.export.cad import export_named_step, step_names
from tubecad.spec.build import wall_lines
from tubecad.spec.model import StiffenersSection
from tubecad.stiffeners.assembly import named_assembly
from tubecad.surface.canal import tube_or_canal

RHO, THICKNESS, LENGTH = 10.0, 1.0, 100.0
R_OUT, R_IN = RHO + THICKNESS / 2, RHO - THICKNESS / 2


def axis() -> NaturalAxis:
    return NaturalAxis("0", "0", (0.0, LENGTH))


def apart(a, b) -> float:
    """The distance of the straight line ``b`` from the points of the straight line ``a`` (two
    u = const lines of the cylinder over the same span), checked to be the same all along."""
    d = [b.distance_to(a.position_at(t)) for t in (0.0, 0.5, 1.0)]
    assert max(d) - min(d) < 1e-9 * max(d)
    return float(d[0])


def test_a_one_stringer_wall_has_one_stringer_and_one_seam():
    wall = CurvatureWall(axis(), radius=RHO, thickness=THICKNESS, rings=3, stringers=1)
    assert [w.label for w in wall.stringers] == ["stringer_00"]
    assert [w.label for w in wall.inner_stringers] == ["stringer_00"]
    assert [w.label for w in wall.seams] == ["seam_00"] and [w.label for w in wall.inner_seams] == ["seam_00"]
    part_edges = wall.edges()
    for wires, radius in (((wall.stringers, wall.seams), R_OUT), ((wall.inner_stringers, wall.inner_seams), R_IN)):
        stringer, seam = (w[0] for w in wires)
        assert len(seam.edges()) == 2  # one per ring bay, edges of the part itself
        assert all(any(e.wrapped.IsSame(p.wrapped) for p in part_edges) for e in seam.edges())
        assert apart(stringer, seam) == pytest.approx(2 * radius, rel=1e-9)
    # every face edge u = const of the wall is the stringer or the seam: 2 surfaces x 2 bays each
    straight = [e for e in part_edges if e.geom_type != bd.GeomType.CIRCLE]
    assert len(straight) == 2 * 2 * 2


@pytest.mark.parametrize(("stringers", "seams"), [([0.0, 10.0], 1), (4, 0), (2, 0)])
def test_seams_only_where_the_stringers_leave_an_arc_over_330_deg(stringers, seams):
    """[0, 10]: the arc from 10 to 360 deg is split at its middle, 185 deg, a seam; four or two
    stringers split the circle themselves."""
    tube = CurvatureTube(axis(), radius=RHO, rings=2, stringers=stringers)
    count = len(stringers) if isinstance(stringers, list) else stringers
    assert [w.label for w in tube.stringers] == [f"stringer_{j:02d}" for j in range(count)]
    assert [w.label for w in tube.seams] == [f"seam_{k:02d}" for k in range(seams)]
    if seams:  # 2 rho sin((185 - 0) / 2) from the first stringer
        seam, first = tube.seams[0].edges()[0], tube.stringers[0].edges()[0]
        assert apart(first, seam) == pytest.approx(2 * RHO * math.sin(math.radians(185.0) / 2), rel=1e-9)


def test_the_step_file_names_the_seam_a_seam(tmp_path):
    """The named assembly's ``curvature_lines`` as OCCT's XCAF reader reads them back: one
    stringer line and one seam line on each wall surface, and the seam where it is."""
    tube = tube_or_canal(axis(), RHO)
    build = build_wall_solid(tube, THICKNESS, "centered", NetLayout.equal(tube, 3, 1))
    path = export_named_step(named_assembly(build, [], wall_lines(build)), tmp_path / "one.step")
    names = [name for _, name in step_names(path)]
    stringers = [n for n in names if "stringer" in n]
    seams = [n for n in names if "seam" in n]
    assert stringers == ["line_stringer_00", "line_stringer_00_inner"]
    assert seams == ["line_seam_00", "line_seam_00_inner"]
    assert len(names) == len(set(names))
    [curves] = [c for c in bd.import_step(path).children if c.label == "curvature_lines"]
    lines = {c.label: c.edges()[0] for c in curves.children}  # each line a labelled compound of its edge
    for suffix, radius in (("", R_OUT), ("_inner", R_IN)):
        stringer, seam = lines[f"line_stringer_00{suffix}"], lines[f"line_seam_00{suffix}"]
        assert apart(stringer, seam) == pytest.approx(2 * radius, rel=1e-9)


def test_stringer_stiffeners_choose_among_the_stringers_only():
    """Stringer stiffeners on "all" stringers: the one stringer; index 1 (the seam's place,
    were it a stringer) is refused, by the part and by a spec's [stiffeners]."""
    wall = StiffenedCurvatureWall(
        axis(), radius=RHO, thickness=THICKNESS, rings=3, stringers=1, ring_frames=[], stringer_stiffeners="all"
    )
    assert [s.label for s in wall.stiffeners] == ["stringer_00"] and len(wall.stringers) == 1
    with pytest.raises(ValueError, match=r"stringer_stiffeners must be .* in \[0, 0\]"):
        StiffenedCurvatureWall(axis(), radius=RHO, thickness=THICKNESS, rings=3, stringers=1, stringer_stiffeners=[1])
    layout = NetLayout.equal(tube_or_canal(axis(), RHO), 3, 1)
    section = StiffenersSection(rings=(), stringers="all", height=2.0, thickness=1.0)
    assert list(section.select(layout, "spec.toml").stringers) == [0]
    with pytest.raises(SpecError, match=r"\[stiffeners\] stringers must be indices in \[0, 0\], got \[1\]"):
        StiffenersSection(rings=(), stringers=(1,), height=2.0, thickness=1.0).select(layout, "spec.toml")


@pytest.mark.slow
def test_a_junction_names_its_main_walls_seam():
    """A tee whose main wall has one stringer (at +y, the seam at -y, both away from the
    branch up +z): main_stringer_00 and main_seam_00 whole on both surfaces, no stringer_01."""
    from tubecad.junctions import build_junction_wall

    length, big, small = 300.0, 50.0, 30.0
    main = tube_or_canal(
        NaturalAxis("0", "0", (0.0, length), origin=(-length / 2, 0.0, 0.0), tangent=(1, 0, 0), normal=(0, 1, 0)), big
    )
    branch = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 120.0), origin=(0.0, 0.0, 0.0), tangent=(0, 0, 1), normal=(1, 0, 0)), small
    )
    tee = build_junction_wall(
        main, branch, 4.0, 3.0, main_layout=NetLayout.equal(main, 3, 1), branch_layout=NetLayout.equal(branch, 3, 4)
    )
    names = set(tee.edges)
    assert {"main_stringer_00", "main_seam_00", "main_stringer_00_inner", "main_seam_00_inner"} <= names
    assert not any(n.startswith("main_stringer_01") or n.startswith("branch_seam") for n in names)
    for side, radius in (("", big + 2.0), ("_inner", big - 2.0)):
        for name, y in ((f"main_stringer_00{side}", radius), (f"main_seam_00{side}", -radius)):
            edges = tee.edges[name]
            assert sum(e.length for e in edges) == pytest.approx(length, rel=1e-12)
            assert all(abs(e.center().Y - y) < 1e-9 and abs(e.center().Z) < 1e-9 for e in edges)
