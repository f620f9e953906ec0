"""The OCP names that moved between OCCT generations, in one place.

build123d 0.12 and CadQuery 2.8 sit on OCP 7.9, build123d 0.13 on OCP 8. OCP 8 moved the
NCollection instances (the TColgp / TColStd arrays, the TopTools maps, TDF_LabelSequence) into
``OCP.collections`` under template-style names (``Array1_double`` for
``TColStd_Array1OfReal``), and the TopoDS downcasts lost their ``_s`` suffix
(``TopoDS.Face`` for ``TopoDS.Face_s``). Everything else tubecad uses kept its name.
Import these names from here, never from OCP directly.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypeVar

try:
    import OCP.collections  # noqa: F401  (OCP 8 has it, OCP 7.9 not)

    OCP_GENERATION = 8
except ImportError:
    OCP_GENERATION = 7

# mypy reads the OCP 8 branch only (OCP's type stubs, cadquery-ocp-stubs, describe OCP 8)
if TYPE_CHECKING or OCP_GENERATION == 8:
    from OCP.collections import (
        Array1_double as Array1OfReal,
    )
    from OCP.collections import (
        Array1_gp_Pnt as Array1OfPnt,
    )
    from OCP.collections import (
        Array1_gp_Pnt2d as Array1OfPnt2d,
    )
    from OCP.collections import (
        Array1_int as Array1OfInteger,
    )
    from OCP.collections import (
        Array2_double as Array2OfReal,
    )
    from OCP.collections import (
        Array2_gp_Pnt as Array2OfPnt,
    )
    from OCP.collections import (
        IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as IndexedDataMapOfShapeListOfShape,
    )
    from OCP.collections import (
        IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as IndexedMapOfShape,
    )
    from OCP.collections import (
        List_TopoDS_Shape as ListOfShape,
    )
    from OCP.collections import (
        Sequence_TDF_Label as LabelSequence,
    )
else:  # OCP 7.9
    from OCP.TColgp import TColgp_Array1OfPnt as Array1OfPnt
    from OCP.TColgp import TColgp_Array1OfPnt2d as Array1OfPnt2d
    from OCP.TColgp import TColgp_Array2OfPnt as Array2OfPnt
    from OCP.TColStd import TColStd_Array1OfInteger as Array1OfInteger
    from OCP.TColStd import TColStd_Array1OfReal as Array1OfReal
    from OCP.TColStd import TColStd_Array2OfReal as Array2OfReal
    from OCP.TDF import TDF_LabelSequence as LabelSequence
    from OCP.TopTools import TopTools_IndexedDataMapOfShapeListOfShape as IndexedDataMapOfShapeListOfShape
    from OCP.TopTools import TopTools_IndexedMapOfShape as IndexedMapOfShape
    from OCP.TopTools import TopTools_ListOfShape as ListOfShape

from OCP.TopoDS import (
    TopoDS,
    TopoDS_Edge,
    TopoDS_Face,
    TopoDS_Shape,
    TopoDS_Shell,
    TopoDS_Solid,
    TopoDS_Vertex,
    TopoDS_Wire,
)

if TYPE_CHECKING:
    from OCP.Geom import Geom_Geometry
    from OCP.Geom2d import Geom2d_Geometry

_T = TypeVar("_T")
_Geometry = TypeVar("_Geometry", bound="Geom_Geometry | Geom2d_Geometry")


def downcast(value: object, kind: type[_T]) -> _T:
    """``value``, an OCCT handle that OCCT (and so OCP's type stubs) declares as a base class
    (Geom_Surface from BRep_Tool.Surface_s, Geom_Geometry from Copy()), as the subclass ``kind``
    it is. OCP has no DownCast: it hands every handle to Python as its dynamic class already,
    on OCP 7.9 and 8 alike; this only checks that class (a TypeError otherwise) and tells the
    type checker."""
    if not isinstance(value, kind):
        raise TypeError(f"expected an OCCT {kind.__name__}, got {type(value).__name__}")
    return value


def topods(shape: object) -> TopoDS_Shape:
    """The OCCT shape of a build123d or CadQuery object (its ``wrapped``), or ``shape`` itself
    if it is one (a TypeError otherwise)."""
    return downcast(getattr(shape, "wrapped", shape), TopoDS_Shape)


def copy_of(geometry: _Geometry) -> _Geometry:
    """A copy (OCCT's Copy()) of a Geom or Geom2d object, as its own class: OCCT declares
    Copy() to return the base class Geom_Geometry (Geom2d_Geometry)."""
    return downcast(geometry.Copy(), type(geometry))


def _downcast(name: str):
    return getattr(TopoDS, name, None) or getattr(TopoDS, f"{name}_s")


_face, _edge, _solid, _wire = _downcast("Face"), _downcast("Edge"), _downcast("Solid"), _downcast("Wire")
_vertex, _shell = _downcast("Vertex"), _downcast("Shell")


def as_face(shape: TopoDS_Shape) -> TopoDS_Face:
    """``shape`` (a face found by an explorer or map) as a TopoDS_Face."""
    return _face(shape)


def as_edge(shape: TopoDS_Shape) -> TopoDS_Edge:
    """``shape`` as a TopoDS_Edge."""
    return _edge(shape)


def as_solid(shape: TopoDS_Shape) -> TopoDS_Solid:
    """``shape`` as a TopoDS_Solid."""
    return _solid(shape)


def as_wire(shape: TopoDS_Shape) -> TopoDS_Wire:
    """``shape`` as a TopoDS_Wire."""
    return _wire(shape)


def as_shell(shape: TopoDS_Shape) -> TopoDS_Shell:
    """``shape`` as a TopoDS_Shell."""
    return _shell(shape)


def as_vertex(shape: TopoDS_Shape) -> TopoDS_Vertex:
    """``shape`` as a TopoDS_Vertex."""
    return _vertex(shape)


def shapes_in(shapes) -> list[TopoDS_Shape]:
    """The shapes of an OCP list of shapes (TopTools_ListOfShape), in order. Python's own
    iteration of one costs about 0.7 ms a list, empty or not (pybind11's iterator; measured
    on OCP 7.9 and 8 alike: 0.27 s for the history of one junction's edges); taking the first
    of a copy until it is empty, 5 to 45 microseconds."""
    if shapes.IsEmpty():
        return []
    rest, out = ListOfShape(), []
    rest.Assign(shapes)
    while not rest.IsEmpty():
        out.append(rest.First())
        rest.RemoveFirst()
    return out


def box_corners(shape: object) -> tuple[tuple[float, float, float], tuple[float, float, float]] | None:
    """The lowest and highest corners of ``shape``'s bounding box (BRepBndLib: OCCT's box,
    enlarged by the shapes' tolerances), None for an empty shape. Bnd_Box.Get() returns a
    struct in OCP 8 and a tuple in OCP 7.9; its corners read the same in both."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(topods(shape), box)  # a build123d or CadQuery object's OCCT shape, or the shape
    if box.IsVoid():
        return None
    return box.CornerMin().Coord(), box.CornerMax().Coord()


__all__ = [
    "OCP_GENERATION",
    "Array1OfInteger",
    "Array1OfPnt",
    "Array1OfPnt2d",
    "Array1OfReal",
    "Array2OfPnt",
    "Array2OfReal",
    "IndexedDataMapOfShapeListOfShape",
    "IndexedMapOfShape",
    "LabelSequence",
    "ListOfShape",
    "as_edge",
    "as_face",
    "as_shell",
    "as_solid",
    "as_vertex",
    "shapes_in",
    "as_wire",
    "box_corners",
    "copy_of",
    "downcast",
]
