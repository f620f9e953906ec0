"""OCCT's pre-boolean check with the self-intersection part on the faces that can touch (issue 24):
the same findings as OCCT's check of the whole part, on clean walls ({}) and on shapes OCCT flags
as self-intersecting (the same kinds), while the face pairs proven apart never reach OCCT."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
from OCP.gp import gp_Trsf, gp_Vec
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Compound

from tubecad import LogSpiral
from tubecad.brep import NetLayout, build_tube_solid, build_wall_solid
from tubecad.brep import analyzer as checks
from tubecad.brep import properties as props
from tubecad.brep.face_cells import FaceCells
from tubecad.surface import CurvatureLineTube

SELF = ("SelfInterMode",)


def _faces(shape) -> list:
    return checks.sub_shapes(shape, TopAbs_FACE)


def _compound(shapes) -> TopoDS_Compound:
    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    for shape in shapes:
        builder.Add(compound, shape)
    return compound


def _moved(shape, x: float, y: float, z: float):
    trsf = gp_Trsf()
    trsf.SetTranslation(gp_Vec(x, y, z))
    return BRepBuilderAPI_Transform(shape, trsf, True).Shape()


@pytest.fixture(scope="module")
def clean_wall():
    """The paper's wall on its first 200 of arc length, 3 rings x 4 stringers: 18 faces, the
    tube's coil 0.8 away from the next outside it."""
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (200.0, 400.0)), 15.0)
    return build_wall_solid(tube, 2.0, layout=NetLayout.equal(tube, 3, 4)).shape.wrapped


@pytest.fixture(scope="module")
def coiled_tube():
    """The paper's axis with a tube of radius 17: the axis comes back within 32.8 of itself, so
    the tube runs through its own coil (a valid B-rep by BRepCheck, which OCCT's check flags).
    4 rings x 4 stringers: 14 faces."""
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (200.0, 500.0)), 17.0, allow_irregular=True)
    return build_tube_solid(tube, NetLayout.equal(tube, 4, 4)).shape.wrapped


@pytest.fixture(scope="module")
def crossing_tubes():
    """Two capped tubes, the second moved 6 across: their faces in one compound (no solid, so
    checked whole), the surfaces crossing each other."""
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (600.0, 1000.0)), 15.0)
    solid = build_tube_solid(tube, NetLayout.equal(tube, 5, 4)).shape.wrapped
    return _compound(_faces(solid) + _faces(_moved(solid, 6.0, 0.0, 0.0)))


def test_a_clean_wall_has_no_finding_either_way_and_the_filter_proves_pairs_apart(clean_wall):
    plan = checks.plan_self_intersection(clean_wall)
    assert plan is not None and len(plan.faces) == 18
    # the inner and outer surfaces 2 apart, faces across the tube: proven apart, never intersected
    assert len(plan.candidates) < plan.pairs_overlapping
    assert props.analyzer_findings(clean_wall, prefilter=False) == {}
    assert props.analyzer_findings(clean_wall) == {}


def test_every_face_pair_sharing_a_vertex_reaches_occt_or_is_proven_to_meet_only_on_what_it_shares(clean_wall):
    plan = checks.plan_self_intersection(clean_wall)
    assert plan is not None
    touching, _ = checks._touching(clean_wall, plan.faces)
    together = {(i, j) for group in plan.groups for i in group for j in group if i < j}
    touching_pairs = {(int(i), int(j)) for i, j in zip(*np.nonzero(np.triu(touching, 1)))}
    assert touching_pairs <= set(plan.candidates) | set(plan.in_contact)
    assert not set(plan.candidates) & set(plan.in_contact)
    assert set(plan.candidates) <= together
    assert set().union(*map(set, plan.groups)) == set(range(len(plan.faces)))  # every face's own checks
    # the skin faces (B-splines bounded by their boxes' sides) are proven, the caps' pairs go to OCCT
    planes = {i for i, face in enumerate(plan.faces) if FaceCells(face).spline is None}
    assert len(planes) == 2
    assert {pair for pair in touching_pairs if not set(pair) & planes} == set(plan.in_contact)
    assert {pair for pair in touching_pairs if set(pair) & planes} <= set(plan.candidates)
    assert all(set(pair) & planes for pair in plan.candidates)  # the others near a cap, not proven apart


def _folded_shell(loop: list[tuple[float, float]]):
    """A cubic B-spline curve through ``loop``'s poles in the xy plane, swept 6 along z, as 2 x 6
    faces (each its own segment of the surface) sewn into a shell: the faces of the second half
    share edges with the first's."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_Sewing
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    from tubecad.fitting.occ_arrays import integers, reals
    from tubecad.occ_compat import Array2OfPnt

    poles = Array2OfPnt(1, len(loop), 1, 2)
    for i, (x, y) in enumerate(loop):
        for j, z in enumerate((0.0, 6.0)):
            poles.SetValue(i + 1, j + 1, gp_Pnt(x, y, z))
    inner = len(loop) - 4
    knots = np.linspace(0.0, 1.0, inner + 2)
    surface = Geom_BSplineSurface(
        poles, reals(knots), reals([0.0, 1.0]), integers([4] + [1] * inner + [4]), integers([2, 2]), 3, 1
    )
    sewing = BRepBuilderAPI_Sewing(1e-6)
    for u0, u1 in ((0.0, 0.5), (0.5, 1.0)):
        for k in range(6):
            piece = surface.Copy()
            piece.Segment(u0, u1, k / 6, (k + 1) / 6)
            sewing.Add(BRepBuilderAPI_MakeFace(piece, 1e-7).Face())
    sewing.Perform()
    return sewing.SewedShape()


def test_faces_crossing_the_faces_they_share_edges_with_are_flagged_the_same_either_way():
    # the second half of the curve comes back through the first: each face of it crosses the face
    # it shares an edge with (no contact proof can hold there)
    crossing = _folded_shell([(0, 0), (3, 0), (6, 0), (9, 0), (10, 3), (8, 5), (6, 3), (6, -3)])
    assert props.is_valid(crossing)
    whole = props.analyzer_findings(crossing, SELF, prefilter=False)
    assert "SelfIntersect" in whole
    assert props.analyzer_findings(crossing, SELF) == whole
    plan = checks.plan_self_intersection(crossing)
    assert plan is not None
    across = {(k, 6 + k) for k in range(6)}  # the faces sharing the edge u = 0.5
    assert across <= set(plan.candidates)
    # the same curve turning away instead: every touching pair proven, nothing for OCCT to compare
    clean = _folded_shell([(0, 0), (3, 0), (6, 0), (9, 0), (10, 3), (8, 5), (6, 5), (4, 6)])
    assert props.is_valid(clean)
    plan = checks.plan_self_intersection(clean)
    assert plan is not None and plan.candidates == [] and across <= set(plan.in_contact)
    assert props.analyzer_findings(clean, SELF, prefilter=False) == props.analyzer_findings(clean, SELF) == {}


@pytest.mark.parametrize("name", ["coiled_tube", "crossing_tubes"])
def test_a_self_intersecting_shape_is_flagged_the_same_either_way(name, request):
    shape = request.getfixturevalue(name)
    assert props.is_valid(shape)  # BRepCheck sees nothing: only the self-intersection check does
    plan = checks.plan_self_intersection(shape)
    assert plan is not None and len(plan.candidates) < plan.pairs_overlapping  # some pairs proven apart
    whole = props.analyzer_findings(shape, SELF, prefilter=False)
    assert "SelfIntersect" in whole
    assert set(props.analyzer_findings(shape, SELF)) == set(whole)
    # the finest cover: each candidate pair alone (and each face alone, for its own checks)
    pairwise = dataclasses.replace(
        plan, groups=[list(pair) for pair in plan.candidates] + [[i] for i in range(len(plan.faces))]
    )
    assert set(pairwise.run()) == set(whole)


def test_every_check_on_a_self_intersecting_shape_gives_the_same_kinds(coiled_tube):
    whole = props.analyzer_findings(coiled_tube, prefilter=False)
    assert "SelfIntersect" in whole
    assert set(props.analyzer_findings(coiled_tube)) == set(whole)


def test_the_cells_hold_the_face(clean_wall):
    """Surface points of a face lie in the convex hull of some cell (checked on each cell's box),
    at every refinement level."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools

    from tubecad.occ_compat import as_face

    for shape in _faces(clean_wall)[:6]:
        face = as_face(shape)
        owner = FaceCells(face)
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        points = np.array([surface.Value(u, v).Coord() for u in np.linspace(u0, u1, 7) for v in np.linspace(v0, v1, 9)])
        for level in range(3):
            cells = owner.cells(level)
            inside = (points[:, None, :] >= cells.low[None] - 1e-9) & (points[:, None, :] <= cells.high[None] + 1e-9)
            assert inside.all(axis=2).any(axis=1).all(), level


def test_a_small_part_is_checked_whole():
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (600.0, 700.0)), 15.0)
    solid = build_tube_solid(tube, NetLayout.equal(tube, 2, 1)).shape.wrapped
    assert checks.plan_self_intersection(solid) is None  # 3 faces
    assert props.analyzer_findings(solid) == props.analyzer_findings(solid, prefilter=False)
