"""Triangle meshes for visual use: STL, 3MF and glTF (.gltf/.glb), meshed to one tolerance
(tubecad.export.meshing) and written by OCCT (STL), lib3mf (3MF) and build123d (glTF), and
read back with independent readers (OCCT's RWStl and RWGltf_CafReader, lib3mf for 3MF).

A mesh is not the exact surface: its triangles are within ``deflection`` (model units) of
the B-rep, and its vertices lie on the B-rep up to the file's number format (32-bit floats
in all three formats). Use STEP or BREP for the exact geometry.

A ``.gltf`` file is written self-contained (its binary buffer embedded as a base64 data URI),
so that it is one file, written atomically like every other output.

Units: 3MF records the model's length unit (``length_unit``, tubecad.core.units) and keeps the
coordinates; glTF is always in metres, so its coordinates are scaled from the model's unit;
STL records no unit (the coordinates are the model's).
"""

from __future__ import annotations

import base64
import json
import struct
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from tubecad.brep.properties import topods
from tubecad.core.errors import TubecadError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.core.units import length_unit as unit_of
from tubecad.export.meshing import ANGULAR_DEFLECTION, RELATIVE_DEFLECTION  # the defaults, tubecad.export.meshing
from tubecad.occ_compat import box_corners

if TYPE_CHECKING:
    from tubecad.brep import TubeBuild


class MeshError(TubecadError):
    """A mesh file could not be written or read."""


def default_deflection(shape: object) -> float:
    """1e-3 of the smallest extent of ``shape``'s bounding box (a tube: of its diameter)."""
    corners = box_corners(shape)
    if corners is None:
        return RELATIVE_DEFLECTION
    extents = [b - a for a, b in zip(*corners) if b > a]
    return RELATIVE_DEFLECTION * (min(extents) if extents else 1.0)


def _solids(shape: object) -> list:
    """The leaves of a build123d assembly that have faces (curve compounds carry no triangles)."""
    import build123d as bd

    node = shape if isinstance(shape, bd.Shape) else bd.Shape.cast(topods(shape))
    leaves = [node] if not getattr(node, "children", ()) else [leaf for leaf in node.leaves]
    return [leaf for leaf in leaves if leaf.wrapped is not None and leaf.faces()]


def write_mesh(
    fmt: str,
    shape: object,
    path: str | Path,
    deflection: float | None = None,
    angular: float = ANGULAR_DEFLECTION,
    length_unit: str = DEFAULT_LENGTH_UNIT,
    build: TubeBuild | None = None,
) -> None:
    """Write ``shape`` as ``fmt`` ('stl', '3mf', 'gltf' or 'glb') to ``path`` (not atomic);
    its coordinates are in ``length_unit``. Its triangles stay within ``deflection`` (model
    units) and ``angular`` (radians) of the B-rep; ``build`` (a TubeBuild whose tube or wall
    ``shape`` is or holds) is meshed on its curvature-line grid (tubecad.export.meshing)."""
    import build123d as bd
    from OCP.BRepTools import BRepTools
    from OCP.StlAPI import StlAPI_Writer

    from tubecad.export.meshing import meshed_deflection, tessellate, write_3mf

    unit = bd.Unit[unit_of(length_unit).build123d]

    deflection = default_deflection(shape) if deflection is None else deflection
    path = Path(path)
    parts = _solids(shape)
    if not parts:
        raise MeshError(f"{path.name}: nothing to mesh (the shape has no faces)")
    try:
        tessellate(parts, deflection, angular, build)  # the writers below use these triangles as they are
        if fmt == "stl":
            whole = parts[0] if len(parts) == 1 else bd.Compound(children=[bd.Shape.cast(p.wrapped) for p in parts])
            writer = StlAPI_Writer()
            writer.ASCIIMode = False
            ok = writer.Write(whole.wrapped, str(path))
        elif fmt == "3mf":
            write_3mf(parts, path, unit)
            ok = path.stat().st_size > 0
        else:
            node = shape if isinstance(shape, bd.Shape) else bd.Shape.cast(topods(shape))
            deflection = max(deflection, meshed_deflection(node.wrapped))  # build123d keeps a mesh within it
            if fmt == "glb":
                ok = bd.export_gltf(
                    node, str(path), unit=unit, binary=True, linear_deflection=deflection, angular_deflection=angular
                )
            else:
                with tempfile.TemporaryDirectory() as folder:
                    glb = Path(folder) / "mesh.glb"
                    ok = bd.export_gltf(
                        node, str(glb), unit=unit, binary=True, linear_deflection=deflection, angular_deflection=angular
                    )
                    if ok:
                        path.write_text(glb_to_gltf(glb.read_bytes()), encoding="utf-8")
    finally:
        for part in (
            *parts,
            *([build.shape] if build is not None else []),
        ):  # meshing left triangulations on the caller's faces
            BRepTools.Clean_s(part.wrapped)
    if not ok:
        raise MeshError(f"build123d could not write {fmt.upper()} to {str(path)!r}")


def glb_to_gltf(data: bytes) -> str:
    """A binary glTF as one self-contained .gltf text (the buffer as a base64 data URI)."""
    magic, version, _ = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2:
        raise MeshError("not a glTF 2.0 binary")
    offset, doc, binary = 12, None, b""
    while offset < len(data):
        length, kind = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8 : offset + 8 + length]
        if kind == 0x4E4F534A:  # JSON
            doc = json.loads(chunk)
        elif kind == 0x004E4942:  # BIN
            binary = chunk
        offset += 8 + length
    if doc is None:
        raise MeshError("glTF binary without a JSON chunk")
    if doc.get("buffers"):
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode("ascii")
    return json.dumps(doc, separators=(",", ":")) + "\n"


def read_mesh(path: str | Path, fmt: str, length_unit: str = DEFAULT_LENGTH_UNIT) -> tuple[np.ndarray, int]:
    """The vertices (n x 3, in ``length_unit``, Z up) and the triangle count of a mesh file,
    read by OCCT (STL, glTF) or lib3mf (3MF): returns (vertices, triangles). STL holds no
    unit: its coordinates are taken as they are."""
    vertices, triangles = read_mesh_triangles(path, fmt, length_unit)
    return vertices, len(triangles)


def read_mesh_triangles(
    path: str | Path, fmt: str, length_unit: str = DEFAULT_LENGTH_UNIT
) -> tuple[np.ndarray, np.ndarray]:
    """As :func:`read_mesh`, with the triangles: (vertices n x 3, triangles m x 3 indices
    into them, 0-based)."""
    path = Path(path)
    unit = unit_of(length_unit)
    if fmt == "stl":
        from OCP.RWStl import RWStl

        tri = RWStl.ReadFile_s(str(path))
        if tri is None or tri.NbNodes() == 0:
            raise MeshError(f"cannot read STL file {str(path)!r}")
        nodes = np.array([(p.X(), p.Y(), p.Z()) for p in (tri.Node(i) for i in range(1, tri.NbNodes() + 1))])
        faces = np.array([tri.Triangle(i).Get() for i in range(1, tri.NbTriangles() + 1)], dtype=int).reshape(-1, 3)
        return nodes, faces - 1
    if fmt == "3mf":
        import build123d as bd

        mesher = bd.Mesher()
        reader = mesher.model.QueryReader("3mf")
        reader.ReadFromFile(str(path))
        points: list[tuple[float, ...]] = []
        triangles: list[list[int]] = []
        objects = mesher.model.GetMeshObjects()
        for _ in range(objects.Count()):
            objects.MoveNext()
            mesh = objects.GetCurrentMeshObject()
            triangles += [[i + len(points) for i in t.Indices] for t in mesh.GetTriangleIndices()]
            points += [tuple(v.Coordinates) for v in mesh.GetVertices()]
        # lib3mf's units (micron, millimeter, centimeter, inch, foot, meter) in millimetres
        file_mm = {0: 1e-3, 1: 1.0, 2: 10.0, 3: 25.4, 4: 304.8, 5: 1000.0}.get(int(mesher.model.GetUnit()), 1.0)
        vertices = np.array(points, dtype=float).reshape(-1, 3) * (file_mm / unit.mm)
        return vertices, np.array(triangles, dtype=int).reshape(-1, 3)
    return _read_gltf(path, unit.metres)


def _read_gltf(path: Path, metres: float = 1e-3) -> tuple[np.ndarray, np.ndarray]:
    """glTF (metres, Y up) read into the unit of ``metres`` per unit, Z up: (vertices, triangles)."""
    from OCP.Message import Message_ProgressRange
    from OCP.RWGltf import RWGltf_CafReader
    from OCP.RWMesh import RWMesh_CoordinateSystem
    from OCP.TCollection import TCollection_AsciiString, TCollection_ExtendedString
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFApp import XCAFApp_Application

    from tubecad.export.meshing import face_triangles

    doc = TDocStd_Document(TCollection_ExtendedString("BinXCAF"))
    XCAFApp_Application.GetApplication_s().NewDocument(TCollection_ExtendedString("BinXCAF"), doc)
    reader = RWGltf_CafReader()
    reader.SetDocument(doc)
    reader.SetSystemLengthUnit(metres)  # the model's unit, Z up, as the model was (glTF: metres, Y up)
    reader.SetSystemCoordinateSystem(RWMesh_CoordinateSystem.RWMesh_CoordinateSystem_Zup)
    if not reader.Perform(TCollection_AsciiString(str(path)), Message_ProgressRange()):
        raise MeshError(f"cannot read glTF file {str(path)!r}")
    return face_triangles(reader.SingleShape())
