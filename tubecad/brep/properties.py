"""Measured properties of B-rep shapes: validity, counts, free edges, volume and area.

OCCT's default mass-property integration is a fixed Gauss rule that is ~1e-4 wrong on
long multi-span B-spline faces; the adaptive overloads with a relative ``eps`` are used.
"""

from __future__ import annotations

from collections.abc import Iterable

from OCP.BRep import BRep_Builder
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Compound

# OCCT's pre-boolean check (BOPAlgo_ArgumentAnalyzer) lives in tubecad.brep.analyzer; its names stay here
from tubecad.brep.analyzer import ANALYZER_MODES as ANALYZER_MODES
from tubecad.brep.analyzer import analyzer_findings as analyzer_findings
from tubecad.brep.analyzer import sub_shapes as sub_shapes
from tubecad.occ_compat import IndexedDataMapOfShapeListOfShape, IndexedMapOfShape, as_edge, box_corners
from tubecad.occ_compat import topods as topods

EPS = 1e-10
KINDS = {"solid": TopAbs_SOLID, "face": TopAbs_FACE, "edge": TopAbs_EDGE, "vertex": TopAbs_VERTEX}


def is_valid(shape: object) -> bool:
    return BRepCheck_Analyzer(topods(shape)).IsValid()


def count(shape: object, kind: str) -> int:
    """Number of distinct sub-shapes of ``kind`` (solid, face, edge, vertex)."""
    found = IndexedMapOfShape()
    TopExp.MapShapes_s(topods(shape), KINDS[kind], found)
    return found.Extent()


def count_circle_edges(shape: object) -> int:
    """Edges whose 3D curve is a circle (OCCT's GeomAbs_Circle, what CAD selectors see)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GeomAbs import GeomAbs_Circle

    found = IndexedMapOfShape()
    TopExp.MapShapes_s(topods(shape), TopAbs_EDGE, found)
    return sum(
        BRepAdaptor_Curve(as_edge(found.FindKey(i))).GetType() == GeomAbs_Circle for i in range(1, found.Extent() + 1)
    )


def free_edges(shape: object) -> int:
    """Edges used by fewer than two faces (a closed solid has none)."""
    edge_faces = IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(topods(shape), TopAbs_EDGE, TopAbs_FACE, edge_faces)
    return sum(1 for i in range(1, edge_faces.Extent() + 1) if edge_faces.FindFromIndex(i).Extent() < 2)


def largest_coordinate(shape: object) -> float:
    """max |x|, |y|, |z| over the shape's bounding box (BRepBndLib, OCCT's optimal box)."""
    corners = box_corners(shape)
    return 0.0 if corners is None else max(abs(v) for v in (*corners[0], *corners[1]))


def volume(shape: object, eps: float = EPS) -> float:
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(topods(shape), props, eps)
    return props.Mass()


def area(shape: object, eps: float = EPS) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(topods(shape), props, eps)
    return props.Mass()


def faces_area(faces: Iterable[object], eps: float = EPS) -> float:
    """Total area of a list of faces."""
    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    for face in faces:
        builder.Add(compound, topods(face))
    return area(compound, eps)
