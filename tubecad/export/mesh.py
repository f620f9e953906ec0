"""Triangle meshes for visual use: STL, 3MF and glTF (.gltf/.glb), through build123d's
exporters, and read back with independent readers (OCCT's RWStl and RWGltf_CafReader,
lib3mf for 3MF).

A mesh is not the exact surface: its triangles are within ``deflection`` (model units) of
the B-rep, and its vertices lie on the B-rep up to the file's number format (32-bit floats
in all three formats). Use STEP or BREP for the exact geometry.

A ``.gltf`` file is written self-contained (its binary buffer embedded as a base64 data URI),
so that it is one file, written atomically like every other output.
"""

from __future__ import annotations

import base64
import json
import struct
import tempfile
from pathlib import Path

import numpy as np
from ..occ_compat import as_face

from ..brep.properties import topods
from ..errors import TubecadError

#: default linear deflection of a mesh, relative to the smallest tube radius (or size) meshed
RELATIVE_DEFLECTION = 1e-3
#: default angular deflection (radians)
ANGULAR_DEFLECTION = 0.1


class MeshError(TubecadError):
    """A mesh file could not be written or read."""


def default_deflection(shape) -> float:
    """1e-3 of the smallest extent of ``shape``'s bounding box (a tube: of its diameter)."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(topods(shape), box)
    if box.IsVoid():
        return RELATIVE_DEFLECTION
    x0, y0, z0, x1, y1, z1 = box.Get()
    extents = [v for v in (x1 - x0, y1 - y0, z1 - z0) if v > 0]
    return RELATIVE_DEFLECTION * (min(extents) if extents else 1.0)


def _solids(shape) -> list:
    """The leaves of a build123d assembly that have faces (curve compounds carry no triangles)."""
    import build123d as bd

    node = shape if isinstance(shape, bd.Shape) else bd.Shape.cast(topods(shape))
    leaves = [node] if not getattr(node, "children", ()) else [leaf for leaf in node.leaves]
    return [leaf for leaf in leaves if leaf.wrapped is not None and leaf.faces()]


def write_mesh(fmt: str, shape, path: str | Path, deflection: float | None = None,
               angular: float = ANGULAR_DEFLECTION) -> None:  # fmt: skip
    """Write ``shape`` as ``fmt`` ('stl', '3mf', 'gltf' or 'glb') to ``path`` (not atomic)."""
    import build123d as bd
    from OCP.BRepTools import BRepTools

    deflection = default_deflection(shape) if deflection is None else deflection
    path = Path(path)
    parts = _solids(shape)
    if not parts:
        raise MeshError(f"{path.name}: nothing to mesh (the shape has no faces)")
    try:
        if fmt == "stl":
            whole = parts[0] if len(parts) == 1 else bd.Compound(children=[bd.Shape.cast(p.wrapped) for p in parts])
            ok = bd.export_stl(whole, str(path), tolerance=deflection, angular_tolerance=angular)
        elif fmt == "3mf":
            mesher = bd.Mesher()
            for part in parts:
                mesher.add_shape(part, linear_deflection=deflection, angular_deflection=angular)
            mesher.write(str(path))
            ok = path.stat().st_size > 0
        else:
            node = shape if isinstance(shape, bd.Shape) else bd.Shape.cast(topods(shape))
            if fmt == "glb":
                ok = bd.export_gltf(node, str(path), binary=True, linear_deflection=deflection,
                                    angular_deflection=angular)  # fmt: skip
            else:
                with tempfile.TemporaryDirectory() as folder:
                    glb = Path(folder) / "mesh.glb"
                    ok = bd.export_gltf(node, str(glb), binary=True, linear_deflection=deflection,
                                        angular_deflection=angular)  # fmt: skip
                    if ok:
                        path.write_text(glb_to_gltf(glb.read_bytes()), encoding="utf-8")
    finally:
        for part in parts:  # meshing left triangulations on the caller's faces
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


def read_mesh(path: str | Path, fmt: str) -> tuple[np.ndarray, int]:
    """The vertices (n x 3, model units, Z up) and the triangle count of a mesh file, read by
    OCCT (STL, glTF) or lib3mf (3MF): returns (vertices, triangles)."""
    path = Path(path)
    if fmt == "stl":
        from OCP.RWStl import RWStl

        tri = RWStl.ReadFile_s(str(path))
        if tri is None or tri.NbNodes() == 0:
            raise MeshError(f"cannot read STL file {str(path)!r}")
        nodes = np.array([(p.X(), p.Y(), p.Z()) for p in (tri.Node(i) for i in range(1, tri.NbNodes() + 1))])
        return nodes, tri.NbTriangles()
    if fmt == "3mf":
        import build123d as bd

        mesher = bd.Mesher()
        reader = mesher.model.QueryReader("3mf")
        reader.ReadFromFile(str(path))
        nodes, triangles = [], 0
        objects = mesher.model.GetMeshObjects()
        for _ in range(objects.Count()):
            objects.MoveNext()
            mesh = objects.GetCurrentMeshObject()
            nodes += [tuple(v.Coordinates) for v in mesh.GetVertices()]
            triangles += mesh.GetTriangleCount()
        scale = {0: 1e-3, 1: 1.0, 2: 10.0, 3: 25.4, 4: 304.8, 5: 1000.0}.get(int(mesher.model.GetUnit()), 1.0)
        return np.array(nodes, dtype=float).reshape(-1, 3) * scale, triangles
    return _read_gltf(path)


def _read_gltf(path: Path) -> tuple[np.ndarray, int]:
    from OCP.BRep import BRep_Tool
    from OCP.Message import Message_ProgressRange
    from OCP.RWGltf import RWGltf_CafReader
    from OCP.RWMesh import RWMesh_CoordinateSystem
    from OCP.TCollection import TCollection_AsciiString, TCollection_ExtendedString
    from OCP.TDocStd import TDocStd_Document
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFApp import XCAFApp_Application

    doc = TDocStd_Document(TCollection_ExtendedString("BinXCAF"))
    XCAFApp_Application.GetApplication_s().NewDocument(TCollection_ExtendedString("BinXCAF"), doc)
    reader = RWGltf_CafReader()
    reader.SetDocument(doc)
    reader.SetSystemLengthUnit(0.001)  # millimetres, Z up, as the model was (glTF: metres, Y up)
    reader.SetSystemCoordinateSystem(RWMesh_CoordinateSystem.RWMesh_CoordinateSystem_Zup)
    if not reader.Perform(TCollection_AsciiString(str(path)), Message_ProgressRange()):
        raise MeshError(f"cannot read glTF file {str(path)!r}")
    explorer = TopExp_Explorer(reader.SingleShape(), TopAbs_FACE)
    nodes, triangles = [], 0
    while explorer.More():
        location = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(as_face(explorer.Current()), location)
        if tri is not None:
            trsf = location.Transformation()
            for i in range(1, tri.NbNodes() + 1):
                p = tri.Node(i).Transformed(trsf)
                nodes.append((p.X(), p.Y(), p.Z()))
            triangles += tri.NbTriangles()
        explorer.Next()
    return np.array(nodes, dtype=float).reshape(-1, 3), triangles

