"""Patch faces of a tube surface between ring frames and stringers, with shared edges.

Vertices and edges are built once and used by both neighbouring faces. Each edge's 3D
curve is an isoline of the surface (ring: the exact circle s = const; stringer: the
curvature line u = const) and its pcurves are the straight lines s = const / u = const of
the parameter plane, with the same parameter, so the edges are same-parameter by
construction and no sewing is needed. Each face lies on its own Segment()-ed copy of the
surface, which keeps seams out of multi-face tubes; a single face around the tube uses a
seam edge instead.
"""

from __future__ import annotations

from dataclasses import dataclass

from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.Geom import Geom_BSplineSurface
from OCP.Geom2d import Geom2d_Line
from OCP.gp import gp_Dir2d, gp_Pnt2d
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Vertex, TopoDS_Wire

from ..errors import TubecadError

#: edge and vertex tolerance: Precision::Confusion(); the geometry is far tighter
TOLERANCE = 1e-7


@dataclass
class PatchFaces:
    """Faces [ring i][stringer j] and the edges they share, for one tube surface."""

    faces: list[list[TopoDS_Face]]
    rings: list[list[TopoDS_Edge]]  # rings[i][j]: arc of ring i from stringer j to j+1, along +u
    stringers: list[list[TopoDS_Edge]]  # stringers[j][i]: stringer j from ring i to i+1, along +s

    def all_faces(self) -> list[TopoDS_Face]:
        return [f for row in self.faces for f in row]


def patch_faces(surface: Geom_BSplineSurface, s_rings: list[float], u_cuts: list[float], reverse: bool = False) -> PatchFaces:
    """Faces of ``surface`` between rings ``s_rings`` and stringer cuts ``u_cuts``
    ([0, ..., 2 pi]); ``reverse`` flips every face (for the inner wall of a solid)."""
    builder = BRep_Builder()
    n_rings, n_cuts = len(s_rings), len(u_cuts)
    n_stringers = n_cuts - 1
    seam = n_stringers == 1

    vertices = [[_vertex(builder, surface.Value(u_cuts[j], s)) for j in range(n_stringers)] for s in s_rings]
    rings = []
    for i, s in enumerate(s_rings):
        iso = surface.VIso(s)
        rings.append([
            _edge(iso, vertices[i][j], vertices[i][(j + 1) % n_stringers], u_cuts[j], u_cuts[j + 1])
            for j in range(n_stringers)
        ])  # fmt: skip
    stringers = []
    for j in range(n_stringers):
        iso = surface.UIso(u_cuts[j])
        stringers.append([
            _edge(iso, vertices[i][j], vertices[i + 1][j], s_rings[i], s_rings[i + 1]) for i in range(n_rings - 1)
        ])  # fmt: skip

    faces = []
    for i in range(n_rings - 1):
        row = []
        s0, s1 = s_rings[i], s_rings[i + 1]
        band = surface.Copy()  # cut the band between two rings once, then each patch from it:
        band.Segment(u_cuts[0], u_cuts[-1], s0, s1)  # far fewer poles to copy per patch
        for j in range(n_stringers):
            u0, u1 = u_cuts[j], u_cuts[j + 1]
            piece = band if seam else band.Copy()
            if not seam:
                piece.Segment(u0, u1, s0, s1)
            face = TopoDS_Face()
            builder.MakeFace(face, piece, TOLERANCE)
            bottom, top = rings[i][j], rings[i + 1][j]
            left, right = stringers[j][i], stringers[(j + 1) % n_stringers][i]
            builder.UpdateEdge(bottom, _line(0.0, s0, 1, 0), face, TOLERANCE)
            builder.UpdateEdge(top, _line(0.0, s1, 1, 0), face, TOLERANCE)
            if seam:  # one edge used twice: pcurve u = 2 pi for its forward use, u = 0 reversed
                builder.UpdateEdge(right, _line(u1, 0.0, 0, 1), _line(u0, 0.0, 0, 1), face, TOLERANCE)
            else:
                builder.UpdateEdge(right, _line(u1, 0.0, 0, 1), face, TOLERANCE)
                builder.UpdateEdge(left, _line(u0, 0.0, 0, 1), face, TOLERANCE)
            wire = TopoDS_Wire()
            builder.MakeWire(wire)  # counter-clockwise in (u, s): outward normal S_u x S_s
            for edge, orientation in ((bottom, TopAbs_FORWARD), (right, TopAbs_FORWARD),
                                      (top, TopAbs_REVERSED), (left, TopAbs_REVERSED)):  # fmt: skip
                builder.Add(wire, edge.Oriented(orientation))
            wire.Closed(True)
            builder.Add(face, wire)
            row.append(TopoDS_Face.Reversed(face) if reverse else face)
        faces.append(row)
    return PatchFaces(faces, rings, stringers)


def _vertex(builder: BRep_Builder, point) -> TopoDS_Vertex:
    vertex = TopoDS_Vertex()
    builder.MakeVertex(vertex, point, TOLERANCE)
    return vertex


def _edge(curve, v0: TopoDS_Vertex, v1: TopoDS_Vertex, t0: float, t1: float) -> TopoDS_Edge:
    maker = BRepBuilderAPI_MakeEdge(curve, v0, v1, t0, t1)
    if not maker.IsDone():
        raise TubecadError(f"OCCT could not make an edge on [{t0:g}, {t1:g}] (error {maker.Error()})")
    return maker.Edge()


def _line(x: float, y: float, dx: float, dy: float) -> Geom2d_Line:
    return Geom2d_Line(gp_Pnt2d(x, y), gp_Dir2d(dx, dy))
