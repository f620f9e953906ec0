"""Edges' B-spline curves cut to the ranges the edges use.

OCCT's splitters and offsets keep each piece of a split edge on the whole curve it came from,
its range a part of it; a file then holds the whole curve (3-D and each pcurve) once per piece.
A line of curvature's edge has a pole every few degrees of turn (hundreds), so a net split
into tens of patches wrote tens of MB of STEP. :func:`segmented` replaces every B-spline
curve of an edge that uses only part of it by a copy cut to that part
(``Geom_BSplineCurve::Segment``: the same curve, exactly, over the range), in place.
"""

from __future__ import annotations

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.Geom import Geom_BSplineCurve
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location

from tubecad.occ_compat import as_edge, as_face, downcast, topods

#: a range shorter than the curve's by more than this share of it is cut
SHARE = 1e-9


def segmented(shape: object) -> int:
    """Cut the B-spline curves (3-D and on each face) of ``shape``'s edges to their ranges,
    in place (module docstring); returns how many curves were cut."""
    builder, cut = BRep_Builder(), 0
    faces = TopExp_Explorer(topods(shape), TopAbs_FACE)
    while faces.More():
        face = as_face(faces.Current())
        edges = TopExp_Explorer(face, TopAbs_EDGE)
        while edges.More():
            edge = as_edge(edges.Current())
            first, last = BRep_Tool.Range_s(edge)
            cut += _cut_curve(builder, edge, first, last)  # a shared edge's: cut once, then whole
            cut += _cut_pcurve(builder, edge, face, first, last)
            edges.Next()
        faces.Next()
    return cut


def _cut_curve(builder: BRep_Builder, edge, first: float, last: float) -> int:
    location = TopLoc_Location()
    spline = BRep_Tool.Curve_s(edge, location, 0.0, 0.0)
    if not isinstance(spline, Geom_BSplineCurve) or not location.IsIdentity() or not _shorter(spline, first, last):
        return 0
    piece = downcast(spline.Copy(), Geom_BSplineCurve)
    piece.Segment(first, last)
    builder.UpdateEdge(edge, piece, BRep_Tool.Tolerance_s(edge))
    return 1


def _cut_pcurve(builder: BRep_Builder, edge, face, first: float, last: float) -> int:
    spline = BRep_Tool.CurveOnSurface_s(edge, face, 0.0, 0.0)
    if (
        not isinstance(spline, Geom2d_BSplineCurve)
        or not _shorter(spline, first, last)
        or BRep_Tool.IsClosed_s(edge, face)
    ):
        return 0
    piece = downcast(spline.Copy(), Geom2d_BSplineCurve)
    piece.Segment(first, last)
    builder.UpdateEdge(edge, piece, face, BRep_Tool.Tolerance_s(edge))
    return 1


def _shorter(spline, first: float, last: float) -> bool:
    a, b = spline.FirstParameter(), spline.LastParameter()
    return (first - a) > SHARE * (b - a) or (b - last) > SHARE * (b - a)
