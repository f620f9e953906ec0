"""How closely a mesh follows the B-rep (the one policy for STL, 3MF and glTF), and the
triangles themselves.

- The linear tolerance (deflection, model units) defaults to 1e-3 of the smallest tube
  radius and may be set from 1e-4 to 1 times it (``tubecad build --mesh-tolerance``); the
  angular tolerance (the turn of the normal between neighbouring triangles) defaults to
  0.1 rad and may be set from 1 to 45 degrees (``--mesh-angle``). Both bounds apply: the
  finer one wins.
- A tube or wall (tubecad.brep.TubeBuild) is meshed on its curvature-line grid
  (tubecad.export.tessellate), to a bound that holds by construction (a canal surface's:
  measured on the exact surface as the grid is made); everything else
  (stiffeners, panels, a fused wall) by OCCT's BRepMesh with the same tolerances as
  absolute values (build123d's exporters ask BRepMesh for *relative* ones, which leave a
  tube's triangles several times the deflection away from it).
- The writers then use these triangulations as they are: STL through OCCT's StlAPI_Writer,
  3MF through lib3mf (here, one mesh object per solid with its name and colour), glTF
  through build123d's exporter, which keeps a triangulation within the deflection.
"""

from __future__ import annotations

import ctypes
import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from tubecad.core.errors import ParameterError

if TYPE_CHECKING:
    import build123d as bd
    from OCP.TopoDS import TopoDS_Shape

    from tubecad.brep import TubeBuild

#: default linear deflection of a mesh, relative to the smallest tube radius (or size) meshed
RELATIVE_DEFLECTION = 1e-3
#: default angular deflection (radians)
ANGULAR_DEFLECTION = 0.1
#: the linear deflection allowed, relative to the smallest tube radius
LINEAR_RANGE = (1e-4, 1.0)
#: the angular deflection allowed, degrees
ANGLE_RANGE_DEG = (1.0, 45.0)


def checked_tolerance(
    linear: float | None,
    angle_deg: float | None,
    radius: float,
    names: tuple[str, str] = ("mesh tolerance", "mesh angle"),
) -> tuple[float, float]:
    """(linear deflection, angular deflection in radians) for a model whose smallest tube
    radius is ``radius``: the defaults where None, else the values checked against
    LINEAR_RANGE x ``radius`` and ANGLE_RANGE_DEG; a ParameterError names ``names[0]`` or
    ``names[1]`` and the allowed range."""
    lo, hi = (f * radius for f in LINEAR_RANGE)
    if linear is None:
        linear = RELATIVE_DEFLECTION * radius
    elif not (isinstance(linear, (int, float)) and math.isfinite(linear) and lo <= linear <= hi):
        raise ParameterError(
            f"{names[0]} must be in [{lo:.6g}, {hi:.6g}] (model units: {LINEAR_RANGE[0]:g} to "
            f"{LINEAR_RANGE[1]:g} x the smallest tube radius {radius:g}), got {linear:g}"
        )
    if angle_deg is None:
        return float(linear), ANGULAR_DEFLECTION
    a, b = ANGLE_RANGE_DEG
    if not (isinstance(angle_deg, (int, float)) and math.isfinite(angle_deg) and a <= angle_deg <= b):
        raise ParameterError(f"{names[1]} must be in [{a:g}, {b:g}] degrees, got {angle_deg:g}")
    return float(linear), math.radians(angle_deg)


def tessellate(parts: list, deflection: float, angular: float, build: TubeBuild | None = None) -> None:
    """Triangulate the faces of ``parts`` (build123d shapes): ``build``'s tube or wall faces
    on their curvature-line grid (they are the same faces in an assembly that holds the
    build's wall), every other part by BRepMesh with absolute tolerances. Remove them with
    ``BRepTools.Clean_s``."""
    import build123d as bd
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.BRepTools import BRepTools
    from OCP.IMeshTools import IMeshTools_Parameters

    from tubecad.export.tessellate import triangulate_build

    # a canal surface's grid has its own step rules, measured on the exact surfaces (tessellate.canal_grid);
    # round a closed axis its stringers come back moved by a Moebius map, which the closing ring's
    # nodes do not follow yet (they follow a turn): BRepMesh meshes a closed canal surface
    exact = build.surfaces[0].tube if build is not None else None
    on_grid = exact is not None and (exact.constant_radius or not exact.axis.closed)
    if build is not None and on_grid and any(p.wrapped.IsSame(build.shape.wrapped) for p in parts):
        triangulate_build(build, deflection, angular)
    rest = [p for p in parts if not BRepTools.Triangulation_s(p.wrapped, deflection)]
    if rest:
        params = IMeshTools_Parameters()
        params.Deflection, params.Angle, params.Relative, params.InParallel = deflection, angular, False, True
        whole = rest[0] if len(rest) == 1 else bd.Compound(children=[bd.Shape.cast(p.wrapped) for p in rest])
        BRepMesh_IncrementalMesh(whole.wrapped, params)  # the faces in parallel


def meshed_deflection(shape: TopoDS_Shape) -> float:
    """The largest deflection OCCT records on the triangulations of ``shape``'s faces (BRepMesh
    records what it reached, which may be a little above what it was asked for)."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location

    from tubecad.occ_compat import as_face

    largest = 0.0
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        tri = BRep_Tool.Triangulation_s(as_face(explorer.Current()), TopLoc_Location())
        if tri is not None:
            largest = max(largest, tri.Deflection())
        explorer.Next()
    return largest


def face_triangles(shape: TopoDS_Shape) -> tuple[np.ndarray, np.ndarray]:
    """The triangulations on ``shape``'s faces as (vertices n x 3, triangles m x 3, 0-based),
    each triangle counter-clockwise about the outward normal (reversed faces flipped)."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location

    from tubecad.occ_compat import as_face

    nodes, triangles, offset = [], [], 0
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        face = as_face(explorer.Current())
        location = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face, location)
        if tri is not None:
            trsf = location.Transformation()
            points = (tri.Node(i).Transformed(trsf) for i in range(1, tri.NbNodes() + 1))
            nodes.append(np.array([(p.X(), p.Y(), p.Z()) for p in points]).reshape(-1, 3))
            faces = np.array([tri.Triangle(i).Get() for i in range(1, tri.NbTriangles() + 1)]).reshape(-1, 3) - 1
            triangles.append((faces[:, ::-1] if face.Orientation() == TopAbs_REVERSED else faces) + offset)
            offset += tri.NbNodes()
        explorer.Next()
    if not nodes:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=int)
    return np.concatenate(nodes), np.concatenate(triangles)


def write_3mf(parts: list, path: Path, unit: bd.Unit) -> None:
    """One 3MF mesh object per part (named after its label, coloured by its colour), from the
    triangulations on its faces; coincident vertices merged, so each solid is one closed mesh."""
    import build123d as bd
    from lib3mf import Lib3MF

    mesher = bd.Mesher(unit)  # build123d's lib3mf model, in the model's unit
    model, wrapper = mesher.model, mesher.wrapper
    for part in parts:
        vertices, triangles = face_triangles(part.wrapped)
        _, first, inverse = np.unique(np.round(vertices, 9), axis=0, return_index=True, return_inverse=True)
        triangles = inverse.reshape(-1)[triangles]
        keep = (
            (triangles[:, 0] != triangles[:, 1])
            & (triangles[:, 1] != triangles[:, 2])
            & (triangles[:, 2] != triangles[:, 0])
        )
        mesh = model.AddMeshObject()
        positions = [Lib3MF.Position((ctypes.c_float * 3)(*v)) for v in vertices[first].tolist()]
        faces = [Lib3MF.Triangle((ctypes.c_uint * 3)(*t)) for t in triangles[keep].tolist()]
        mesh.SetGeometry(positions, faces)
        if part.label:
            mesh.SetName(part.label)
        if part.color is not None:
            group = model.AddBaseMaterialGroup()
            material = group.AddMaterial(
                Name=str(part.color), DisplayColor=wrapper.FloatRGBAToColor(*tuple(part.color))
            )
            mesh.SetObjectLevelProperty(group.GetResourceID(), material)
        model.AddBuildItem(mesh, wrapper.GetIdentityTransform())
    writer = model.QueryWriter("3mf")
    writer.WriteToFile(str(path))
