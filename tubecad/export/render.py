"""A shaded picture of an OCCT shape (e.g. a solid read back from STEP) with its B-rep edges.

What is drawn: the faces, tessellated finely by ``BRepMesh_IncrementalMesh`` (a linear
deflection of LINEAR_DEFLECTION x the bounding-box diagonal and ANGULAR_DEFLECTION), shaded
smoothly (Gouraud): each mesh node is lit by the surface's own normal there (OCCT's, from
the node's (u, v) on the face), light blue-grey, with a Lambert term, a soft highlight and
ambient light; triangles seen from their back side are a little darker. Every unique B-rep
edge is drawn on top as a thin dark polyline; edge parts hidden behind faces are found with
a numpy z-buffer of the triangles (:mod:`tubecad.export.zbuffer`) and drawn faint and thin.
Triangles are painted far to near (painter's algorithm); for a closed shape (every face in a
closed shell) back faces are culled, and long triangles are first halved across their longest
edge (to SPLIT_LENGTH x the bounding-box diagonal), so that the sort by centroid depth holds.

Conventions: orthographic projection. ``view_dir`` points from the shape TOWARDS THE
VIEWER: the camera sits on the +view_dir side and looks along -view_dir, so the default
(1, -1.2, 0.8) looks at the shape from front-right-above. Screen "up" is world +Z projected
(world +Y when looking along Z); screen "right" is up x view_dir. Depth is ``p . view_dir``
(larger = nearer); triangles are painted far to near. The light is fixed in the camera frame
(from upper left, in front), so every view is lit alike. Triangle winding follows the face
normal; faces with TopAbs_REVERSED orientation have their winding and normals flipped.
Note: meshing stores the triangulation in the shape (as every OCCT mesher does).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepLib import BRepLib_ToolTriangulatedShape
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.GCPnts import GCPnts_QuasiUniformDeflection
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_REVERSED, TopAbs_SHELL
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Shape

from tubecad.core.atomic import atomic_path
from tubecad.export.shading import camera, paint_gouraud, shade_of, shades, split_visible, zbuffer
from tubecad.occ_compat import IndexedMapOfShape, as_edge, as_face, box_corners

FACE_RGB = (0.72, 0.78, 0.86)  # light blue-grey
LINEAR_DEFLECTION = 2e-4  # x the bounding-box diagonal
ANGULAR_DEFLECTION = 0.1  # rad: about 63 facets round a circle
EDGE_SAMPLES = 64  # points per edge, at least
ZBUFFER_PX = 900  # z-buffer resolution along the longer screen side
DPI = 100
SPLIT_LENGTH = 0.02  # painted triangles are cut to at most this x the bounding-box diagonal


def render_shape_png(
    shape: Any,
    path: str | Path,
    *,
    title: str = "",
    view_dir: Sequence[float] = (1.0, -1.2, 0.8),
    size_px: tuple[int, int] = (1600, 1200),
    edge_color: str = "#10203a",
    deflection: float | None = None,
    marks: Sequence[tuple[Sequence[float], str]] = (),
) -> Path:
    """Render ``shape`` to a PNG: its faces smoothly shaded, its B-rep edges on top, and
    ``marks`` (points with a label each: a net's umbilics and their types) over all.

    Args:
        shape: a TopoDS_Shape or an object with ``.wrapped`` (build123d).
        path: the PNG to write (atomically).
        title: the picture's title, if any.
        view_dir: from the shape towards the viewer (module docstring).
        size_px: (width, height) in pixels.
        edge_color: the B-rep edges' colour.
        deflection: the mesh's linear deflection in model units (default LINEAR_DEFLECTION x
            the bounding-box diagonal).
        marks: (point (x, y, z), label) drawn as a red dot with its label.

    Returns:
        ``path``.
    """
    shape = getattr(shape, "wrapped", shape)
    corners = box_corners(shape)
    diag = float(np.linalg.norm(np.subtract(corners[1], corners[0]))) if corners else 1.0
    lin = deflection if deflection is not None else LINEAR_DEFLECTION * diag
    BRepMesh_IncrementalMesh(shape, lin, False, ANGULAR_DEFLECTION, True)

    basis = np.stack(camera(view_dir), axis=1)  # world -> (x, y, depth)
    tris, normals = _triangles(shape)
    tris, normals = tris @ basis, normals @ basis
    edges = [e @ basis for e in _edges(shape, lin)]

    fig = Figure(figsize=(size_px[0] / DPI, size_px[1] / DPI), dpi=DPI)  # no pyplot: no backend switch
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.90 if title else 0.96))
    extent = np.ptp(tris[:, :, :2].reshape(-1, 2), axis=0) if len(tris) else np.ones(2)
    pixel = float(max(extent[0] / (0.96 * size_px[0]), extent[1] / (0.9 * size_px[1])))
    parts = _paint_faces(ax, tris, normals, _is_closed(shape), diag, 0.7 * pixel)
    segs = np.concatenate([np.stack([e[:-1], e[1:]], 1) for e in edges]) if edges else np.zeros((0, 2, 3))
    visible, hidden = split_visible(segs, zbuffer(parts, ZBUFFER_PX) if len(parts) else None, diag)
    ax.add_collection(LineCollection(hidden, colors=edge_color, linewidths=0.4, alpha=0.22))
    ax.add_collection(LineCollection(visible, colors=edge_color, linewidths=0.9))
    for point, label in marks:
        x, y, _ = np.asarray(point, dtype=float) @ basis
        ax.plot([x], [y], "o", color="#c0282d", markersize=7, zorder=5)
        ax.annotate(label, (x, y), xytext=(6, 6), textcoords="offset points", color="#c0282d", fontsize=10, zorder=5)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_axis_off()
    if title:
        fig.suptitle(title, fontsize=13)
    target = Path(path)
    with atomic_path(target) as tmp:
        fig.savefig(tmp, format="png", dpi=DPI, facecolor="white")
    return target


def _paint_faces(ax, tris: np.ndarray, normals: np.ndarray, closed: bool, diag: float, grow: float) -> np.ndarray:
    """Paint the screen triangles ``tris`` (n, 3, xyz) far to near, Gouraud-shaded from their
    vertex ``normals`` (n, 3, xyz, camera frame), each ``grow`` larger (no hairlines); a closed
    shape's back faces culled. Returns the painted (bisected) triangles, for the hidden-line test."""
    if not len(tris):
        return tris
    facing = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])[:, 2] >= 0.0
    keep = facing if closed else np.ones(len(tris), dtype=bool)  # a solid's back is hidden
    shade = shade_of(normals, facing)
    parts = _bisect_long(np.concatenate([tris, shade[..., None]], axis=2)[keep], SPLIT_LENGTH * diag)
    paint_gouraud(ax, parts[:, :, :3], parts[:, :, 3], shades(FACE_RGB), grow)
    return parts[:, :, :3]


def _triangles(shape: TopoDS_Shape) -> tuple[np.ndarray, np.ndarray]:
    """All mesh triangles, (n, 3, 3) world coordinates, wound along the outward face normal,
    and their vertex normals (n, 3, 3): the face's surface normal at each node, outward."""
    out, out_normals = [], []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        face = as_face(explorer.Current())
        explorer.Next()
        loc = TopLoc_Location()
        poly = BRep_Tool.Triangulation_s(face, loc)
        if poly is None or poly.NbTriangles() == 0:
            continue
        nodes = np.array([poly.Node(i).Coord() for i in range(1, poly.NbNodes() + 1)])
        trsf = loc.Transformation()
        m = np.array([[trsf.Value(r, c) for c in range(1, 5)] for r in range(1, 4)])
        nodes = nodes @ m[:, :3].T + m[:, 3]
        idx = np.array([poly.Triangle(i).Get() for i in range(1, poly.NbTriangles() + 1)]) - 1
        if face.Orientation() == TopAbs_REVERSED:
            idx = idx[:, ::-1]
        tris = nodes[idx]
        out.append(tris)
        out_normals.append(_node_normals(face, poly, m[:, :3], idx, tris))
    if not out:
        return np.zeros((0, 3, 3)), np.zeros((0, 3, 3))
    return np.concatenate(out), np.concatenate(out_normals)


def _node_normals(face, poly, rotation: np.ndarray, idx: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """The unit normals (len(idx), 3, 3) at the triangles' nodes: the face's surface normal
    (OCCT's, from each node's (u, v)), turned the way the triangles wind; where OCCT gives
    none (no (u, v) nodes), the mean of the node's triangles' normals."""
    flat = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])  # along the winding, area-weighted
    if not poly.HasNormals():
        BRepLib_ToolTriangulatedShape.ComputeNormals_s(face, poly)
    if poly.HasNormals():
        normals = np.array([poly.Normal(i).Coord() for i in range(1, poly.NbNodes() + 1)]) @ rotation.T
    else:
        normals = np.zeros((poly.NbNodes(), 3))
        np.add.at(normals, idx.ravel(), np.repeat(flat, 3, axis=0))
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    per_vertex = normals[idx]
    if np.einsum("ij,ij->", per_vertex.sum(axis=1), flat) < 0.0:  # OCCT's normal against the winding
        per_vertex = -per_vertex
    return per_vertex


def _is_closed(shape: TopoDS_Shape) -> bool:
    """True if every face lies in a shell and every shell is closed (so back faces are hidden)."""
    explorer, shells = TopExp_Explorer(shape, TopAbs_SHELL), 0
    while explorer.More():
        if not BRep_Tool.IsClosed_s(explorer.Current()):
            return False
        shells += 1
        explorer.Next()
    return shells > 0 and not TopExp_Explorer(shape, TopAbs_FACE, TopAbs_SHELL).More()


def _bisect_long(tris: np.ndarray, limit: float) -> np.ndarray:
    """Halve triangles (n, 3, k: xyz first, then any values carried linearly, e.g. a shade)
    across their longest edge until no edge exceeds ``limit`` in xyz, keeping the winding;
    long slivers otherwise defeat the painter's sort."""
    done = []
    while len(tris):
        lengths = np.linalg.norm(tris[:, :, :3] - np.roll(tris[:, :, :3], -1, axis=1), axis=2)  # edge k: k -> k+1
        longest = lengths.argmax(axis=1)
        long = lengths[np.arange(len(tris)), longest] > limit
        done.append(tris[~long])
        tris, k = tris[long], longest[long]
        rolled = np.take_along_axis(tris, ((k[:, None] + np.arange(3)) % 3)[:, :, None], axis=1)
        a, b, c = rolled[:, 0], rolled[:, 1], rolled[:, 2]  # longest edge is a -> b
        m = 0.5 * (a + b)
        tris = np.concatenate([np.stack([a, m, c], 1), np.stack([m, b, c], 1)])
    return np.concatenate(done) if done else tris


def _edges(shape: TopoDS_Shape, deflection: float) -> list[np.ndarray]:
    """Each unique, non-degenerate edge sampled at EDGE_SAMPLES parameter values, or more if the
    chord deflection asks for more, (m, 3)."""
    emap = IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_EDGE, emap)
    out = []
    for i in range(1, emap.Extent() + 1):
        edge = as_edge(emap.FindKey(i))
        if BRep_Tool.Degenerated_s(edge):
            continue
        curve = BRepAdaptor_Curve(edge)  # includes the edge's location
        ts = np.linspace(curve.FirstParameter(), curve.LastParameter(), EDGE_SAMPLES)
        sampler = GCPnts_QuasiUniformDeflection(curve, deflection)  # finer where the edge bends
        if sampler.IsDone() and sampler.NbPoints() > EDGE_SAMPLES:
            ts = np.array([sampler.Parameter(j) for j in range(1, sampler.NbPoints() + 1)])
        out.append(np.array([curve.Value(t).Coord() for t in ts]))
    return out
