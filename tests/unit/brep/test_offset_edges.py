"""A net's wall thickened from a B-spline face (the hull panel) keeps its edges on its offset
faces after a STEP round trip (tubecad.brep.offset_edges): OCCT's offset gives them 3-D curves
1e-5 mm off the offset surface, which STEP's reader re-tolerances a hair short, so the wall read
back failed OCCT's pre-boolean check (InvalidCurveOnSurface, 240 findings on the sample).

The reference is the offset surface evaluated here, X(u, v) + d N(u, v) with N from the basis
surface's first derivatives (X_u x X_v normalised), at the edge's pcurve: not OCCT's offset code.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ROOT


@pytest.fixture(scope="module")
def hull_net():
    from tubecad.brep.segments import segmented
    from tubecad.export.cad import read_faces
    from tubecad.nets import curvature_net
    from tubecad.occ_compat import as_face

    net = curvature_net(as_face(read_faces(ROOT / "samples" / "hull_panel.step")[0][1]), 3, 3)
    segmented(net.patches)  # as build_net does
    return net


def _offset_face_gaps(wall) -> list[float]:
    """For each edge on an offset face: the largest distance, at 50 parameters, between its
    3-D curve and the offset surface X + d N evaluated here at its pcurve."""
    from OCP.BRep import BRep_Tool
    from OCP.Geom import Geom_OffsetSurface
    from OCP.gp import gp_Pnt, gp_Vec
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
    from OCP.TopExp import TopExp

    from tubecad.occ_compat import IndexedDataMapOfShapeListOfShape, as_edge, as_face

    owners = IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(wall, TopAbs_EDGE, TopAbs_FACE, owners)
    gaps = []
    for index in range(1, owners.Extent() + 1):
        edge = as_edge(owners.FindKey(index))
        if BRep_Tool.Degenerated_s(edge):
            continue
        for face in map(as_face, owners.FindFromIndex(index)):
            surface = BRep_Tool.Surface_s(face)
            if not isinstance(surface, Geom_OffsetSurface):
                continue
            basis, distance = surface.BasisSurface(), surface.Offset()
            curve = BRep_Tool.Curve_s(edge, 0.0, 1.0)
            pcurve = BRep_Tool.CurveOnSurface_s(edge, face, 0.0, 0.0)
            first, last = BRep_Tool.Range_s(edge)
            worst = 0.0
            for t in np.linspace(first, last, 50):
                uv = pcurve.Value(t)
                point, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
                basis.D1(uv.X(), uv.Y(), point, du, dv)
                normal = np.cross(np.array(du.Coord()), np.array(dv.Coord()))
                exact = np.array(point.Coord()) + distance * normal / np.linalg.norm(normal)
                worst = max(worst, float(np.linalg.norm(np.array(curve.Value(t).Coord()) - exact)))
            gaps.append(worst)
    return gaps


@pytest.mark.slow
@pytest.mark.parametrize("side", ["centered", "inside", "outside"])
def test_a_walls_offset_edges_lie_on_the_offset_and_survive_a_step_file(hull_net, tmp_path, side):
    from OCP.BRepCheck import BRepCheck_Analyzer

    from tubecad.brep import properties as props
    from tubecad.brep.analyzer import analyzer_findings
    from tubecad.design.model import WallChoice
    from tubecad.design.net import thickened
    from tubecad.export.cad import import_shape, write_step

    wall = thickened(hull_net.patches, WallChoice(12.0, side))
    gaps = _offset_face_gaps(wall)
    assert len(gaps) > 20  # the offset faces' edges: the lines and the boundary, on one or two offsets
    print(f"{side}: {len(gaps)} edges on offset faces, within {max(gaps):.1e} mm of X + d N")
    assert max(gaps) < 2e-9  # measured 9.4e-10 (rebuilt to 1e-9; OCCT's own offset: 1e-5)
    assert BRepCheck_Analyzer(wall).IsValid() and analyzer_findings(wall) == {}
    write_step(wall, tmp_path / "wall.step")
    back = import_shape(tmp_path / "wall.step")
    assert BRepCheck_Analyzer(back).IsValid()
    assert analyzer_findings(back, prefilter=False) == {}  # OCCT's whole check on what a user reads
    assert props.volume(back) == pytest.approx(props.volume(wall), rel=1e-10)


@pytest.mark.slow
def test_a_nets_lines_are_c1_across_the_hosts_knot_lines(hull_net):
    """A line crossing a knot line of the bicubic panel has a node there where its pcurve
    turns (C0) but its 3-D curve stays C1 (OCCT's check reports a C0 edge)."""
    from OCP.GeomAbs import GeomAbs_C0

    from tubecad.brep.analyzer import analyzer_findings

    breaks = 0
    for line in hull_net.edges.values():
        curve = line.curve
        assert curve.Continuity() != GeomAbs_C0
        breaks += sum(curve.Multiplicity(i) == 4 for i in range(2, curve.NbKnots()))
    assert breaks > 0  # the panel's knot lines are crossed
    assert "GeomAbs_C0" not in analyzer_findings(hull_net.patches)
