"""The edges of an offset wall made exact enough to survive a STEP file (issue 44).

OCCT's offset and thicken (``BRepOffset_MakeOffset``) give each edge on an offset face a 3-D
curve approximating the offset of the original edge, ``S(u, v) + d N(u, v)`` along its pcurve,
to about 1e-5 mm, and raise the edge's tolerance to cover it. In memory the wall is valid.
A STEP file keeps no per-edge tolerance, though. OCCT's reader recomputes each edge's
tolerance from its own samples (``ShapeFix_Edge::FixSameParameter``), a hair below the
deviation OCCT's pre-boolean check then finds by optimisation (6.7430e-6 against 6.7433e-6
on the dome's wall). So the wall read back from the file fails ``BOPAlgo_ArgumentAnalyzer``
(``InvalidCurveOnSurface``) on every such edge. Only deviations below the reader's floor,
the file's uncertainty (1e-7), survive the round trip.

:func:`tighten_offset_edges` therefore rebuilds the 3-D curve of every edge lying on an offset
face from that face's pcurve (``BRepLib::BuildCurve3d``: an approximation of the curve on the
surface, here to ``ACCURACY``). Its other faces follow it:

- on a plane (the lateral face where a wall's boundary stands on a plane, as at a dome's
  equator) its pcurve is projected again from the new curve;
- on the ruled lateral face the thicken built between the face's boundary edge and its offset
  (a B-spline of degree 1 across, its row of poles at the offset side the old curve, in the
  edge's own parameter), that row is replaced by the new curve's poles, the two made
  compatible first (the same degree and knots: degree elevation and knot insertion, exact), so
  every pcurve on the face stays what it was.

The rebuilt edges' tolerances are then recomputed (``BRepLib::SameParameter``). An edge with
another kind of face keeps its curve (none is made by OCCT's offset of a B-spline face).
"""

from __future__ import annotations

from collections.abc import Iterator

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepLib import BRepLib
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_C2, GeomAbs_OffsetSurface, GeomAbs_Plane
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Shape

from tubecad.core.errors import TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.occ_compat import IndexedDataMapOfShapeListOfShape, IndexedMapOfShape, as_edge, as_face, copy_of, downcast

#: how close the rebuilt 3-D curves follow the offset surface along the pcurve (mm)
ACCURACY = 1e-9
#: the highest degree and the most spans of a rebuilt curve (BRepLib::BuildCurve3d's limits)
MAX_DEGREE, MAX_SPANS = 14, 0  # 0: as many as the accuracy needs
#: knots of a ruled face and of its new edge curve closer than this share of the span are one
KNOT_MERGE = 1e-12


def tighten_offset_edges(shape: TopoDS_Shape) -> int:
    """Rebuild, in place, the 3-D curves of ``shape``'s edges on offset faces from their pcurves
    (see the module's docstring); returns how many edges were rebuilt.

    Args:
        shape: an offset or thickened shape (a solid or a shell), changed in place.

    Returns:
        The number of edges given a new 3-D curve.
    """
    owners = IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, owners)
    builder, rebuilt, reshaped = BRep_Builder(), 0, IndexedMapOfShape()
    for edge, faces in _edges_and_faces(owners):
        kinds = [BRepAdaptor_Surface(face).GetType() for face in faces]
        ruled = [_ruled_row(edge, face) if kind == GeomAbs_BSplineSurface else None for face, kind in zip(faces, kinds)]
        if GeomAbs_OffsetSurface not in kinds or any(
            kind not in (GeomAbs_OffsetSurface, GeomAbs_Plane) and row is None for kind, row in zip(kinds, ruled)
        ):
            continue
        _rebuild_curve(edge)
        for face, kind in zip(faces, kinds):
            if kind == GeomAbs_Plane:  # its pcurve projected again from the new curve
                builder.UpdateEdge(edge, None, face, EDGE_TOLERANCE)  # type: ignore[call-overload]  # None: a null handle
                BRepLib.BuildPCurveForEdgeOnPlane_s(edge, face)
        for face, row in zip(faces, ruled):
            if row is not None:
                _replace_row(face, row, edge)
                reshaped.Add(face)
        BRepLib.SameParameter_s(edge, EDGE_TOLERANCE)
        rebuilt += 1
    # the edges across the ruled faces (their ends, iso-lines of them) follow the new rows' ends
    for edge, faces in _edges_and_faces(owners):
        if all(reshaped.Contains(face) for face in faces):
            _rebuild_curve(edge)
            BRepLib.SameParameter_s(edge, EDGE_TOLERANCE)
            rebuilt += 1
    BRepLib.UpdateTolerances_s(shape, False)  # the vertices cover their edges' new ends
    return rebuilt


def _edges_and_faces(owners: IndexedDataMapOfShapeListOfShape) -> Iterator[tuple[TopoDS_Edge, list[TopoDS_Face]]]:
    """Each edge but the degenerate ones, with the faces it bounds."""
    for index in range(1, owners.Extent() + 1):
        edge = as_edge(owners.FindKey(index))
        if not BRep_Tool.Degenerated_s(edge):
            yield edge, [as_face(face) for face in owners.FindFromIndex(index)]


def _rebuild_curve(edge: TopoDS_Edge) -> None:
    """``edge``'s 3-D curve made again from its (first) pcurve to ``ACCURACY``."""
    # the old one removed (None: OCCT's null handle, which OCP takes and its stubs do not type)
    BRep_Builder().UpdateEdge(edge, None, TopLoc_Location(), EDGE_TOLERANCE)  # type: ignore[call-overload]
    if not BRepLib.BuildCurve3d_s(edge, ACCURACY, GeomAbs_C2, MAX_DEGREE, MAX_SPANS):
        raise TubecadError("OCCT could not rebuild an offset edge's 3-D curve")


def _ruled_row(edge: TopoDS_Edge, face: TopoDS_Face) -> int | None:
    """The row of poles (1 or 2, in v) of ``face``'s ruled B-spline surface that ``edge``
    lies on, its pcurve the iso-line there in the edge's own parameter; None if the face is
    not such a ruled face."""
    surface = downcast(BRep_Tool.Surface_s(face), Geom_BSplineSurface)
    if surface.VDegree() != 1 or surface.NbVPoles() != 2 or surface.IsVPeriodic():
        return None
    pcurve = BRep_Tool.CurveOnSurface_s(edge, face, 0.0, 0.0)
    if pcurve is None:
        return None
    first, last = BRep_Tool.Range_s(edge, face)
    start, end = pcurve.Value(first), pcurve.Value(last)
    (u0, v0), (u1, v1) = (start.X(), start.Y()), (end.X(), end.Y())
    low, high, v_low, v_high = surface.Bounds()
    if not (abs(v0 - v1) < 1e-12 and abs(u0 - first) < 1e-12 and abs(u1 - last) < 1e-12):
        return None
    if abs(u0 - low) > 1e-12 or abs(u1 - high) > 1e-12:  # the whole row, not a part of it
        return None
    return 1 if abs(v0 - v_low) < 1e-12 else 2 if abs(v0 - v_high) < 1e-12 else None


def _replace_row(face: TopoDS_Face, row: int, edge: TopoDS_Edge) -> None:
    """``face``'s ruled surface with its pole row ``row`` made ``edge``'s 3-D curve: the two
    made compatible (the higher degree, the union of the knots) and the row's poles replaced."""
    # changed in place: the edges' pcurves are kept against this very surface (a new one
    # would leave the face's edges without pcurves)
    surface = downcast(BRep_Tool.Surface_s(face), Geom_BSplineSurface)
    low, high = surface.Bounds()[:2]
    curve = copy_of(downcast(BRep_Tool.Curve_s(edge, 0.0, 1.0), Geom_BSplineCurve))
    curve.Segment(low, high)
    degree = max(surface.UDegree(), curve.Degree())
    surface.IncreaseDegree(degree, 1)
    curve.IncreaseDegree(degree)
    # the interior knots of each into the other (the ends are the same parameters: a hair
    # apart in round-off they would be out of the other's range); knots closer than
    # KNOT_MERGE of the span taken as one
    merge = KNOT_MERGE * (high - low)
    for index in range(2, curve.NbKnots()):
        surface.InsertUKnot(curve.Knot(index), curve.Multiplicity(index), merge, False)
    for index in range(2, surface.NbUKnots()):
        curve.InsertKnot(surface.UKnot(index), surface.UMultiplicity(index), merge, False)
    if curve.NbPoles() != surface.NbUPoles():
        raise TubecadError("a ruled side face of the wall and its new edge curve could not be made compatible")
    for index in range(1, curve.NbPoles() + 1):
        surface.SetPole(index, row, curve.Pole(index), curve.Weight(index))
