"""A shaded picture of an OCCT shape (e.g. a solid read back from STEP) with its B-rep edges.

What is drawn: the faces, tessellated by ``BRepMesh_IncrementalMesh``, as flat-shaded
triangles (Lambert, light blue-grey; triangles seen from their back side a little darker),
and every unique B-rep edge on top as a thin dark polyline. Edge parts hidden behind faces
are found with a coarse numpy z-buffer of the triangles and drawn faint and thin.
Triangles are painted far to near (painter's algorithm); for a closed shape (every face in a
closed shell) back faces are culled, and long triangles are first halved across their longest
edge (to SPLIT_LENGTH x the bounding-box diagonal), so that the sort by centroid depth holds.

Conventions: orthographic projection. ``view_dir`` points from the shape TOWARDS THE
VIEWER: the camera sits on the +view_dir side and looks along -view_dir, so the default
(1, -1.2, 0.8) looks at the shape from front-right-above. Screen "up" is world +Z projected
(world +Y when looking along Z); screen "right" is up x view_dir. Depth is ``p . view_dir``
(larger = nearer); triangles are painted far to near. The light is fixed in the camera frame
(from upper left, in front), so every view is lit alike. Triangle winding follows the face
normal; faces with TopAbs_REVERSED orientation have their winding flipped.
Note: meshing stores the triangulation in the shape (as every OCCT mesher does).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.GCPnts import GCPnts_QuasiUniformDeflection
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_REVERSED, TopAbs_SHELL
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Shape

from tubecad.core.atomic import atomic_path
from tubecad.occ_compat import IndexedMapOfShape, as_edge, as_face, box_corners

FACE_RGB = np.array([0.72, 0.78, 0.86])  # light blue-grey
BACK_FACTOR = 0.75  # back sides are this much darker
ANGULAR_DEFLECTION = 0.3  # rad
EDGE_SAMPLES = 64  # points per edge, at least
ZBUFFER_PX = 600  # z-buffer resolution along the longer screen side
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
) -> Path:
    """Render ``shape`` (TopoDS_Shape or an object with ``.wrapped``) to the PNG ``path``; return it."""
    shape = getattr(shape, "wrapped", shape)
    corners = box_corners(shape)
    diag = float(np.linalg.norm(np.subtract(corners[1], corners[0]))) if corners else 1.0
    lin = deflection if deflection is not None else 1e-3 * diag
    BRepMesh_IncrementalMesh(shape, lin, False, ANGULAR_DEFLECTION, True)

    right, up, w = _camera(view_dir)
    basis = np.stack([right, up, w], axis=1)  # world -> (x, y, depth)
    tris = _triangles(shape) @ basis  # (n, 3 vertices, xyz)
    edges = [e @ basis for e in _edges(shape, lin)]

    fig = Figure(figsize=(size_px[0] / DPI, size_px[1] / DPI), dpi=DPI)  # no pyplot: no backend switch
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.90 if title else 0.96))
    parts = tris
    if len(tris):
        normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
        normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
        light = np.array([-0.4, 0.6, 1.0]) / np.linalg.norm([-0.4, 0.6, 1.0])  # camera frame
        front = normals[:, 2] >= 0.0
        lambert = np.where(front, np.clip(normals @ light, 0.0, 1.0), np.abs(normals @ light))
        shade = (0.35 + 0.65 * lambert) * np.where(front, 1.0, BACK_FACTOR)
        colours = np.clip(FACE_RGB[None, :] * shade[:, None], 0.0, 1.0)
        keep = front if _is_closed(shape) else np.ones(len(tris), dtype=bool)  # a solid's back is hidden
        parts, owner = _bisect_long(tris[keep], SPLIT_LENGTH * diag)
        paint = colours[keep][owner]
        order = np.argsort(parts[:, :, 2].mean(axis=1))  # far first
        ax.add_collection(
            PolyCollection(
                parts[order][:, :, :2],  # type: ignore[arg-type]  # (an (n, 3, 2) array is fine; the stubs say Sequence)
                facecolors=paint[order],
                edgecolors=paint[order],
                linewidths=0.6,
            )
        )
    visible, hidden = _split_edges(edges, parts, diag)
    ax.add_collection(LineCollection(hidden, colors=edge_color, linewidths=0.4, alpha=0.22))
    ax.add_collection(LineCollection(visible, colors=edge_color, linewidths=0.9))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_axis_off()
    if title:
        fig.suptitle(title, fontsize=13)
    target = Path(path)
    with atomic_path(target) as tmp:
        fig.savefig(tmp, format="png", dpi=DPI, facecolor="white")
    return target


def _camera(view_dir: Sequence[float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Orthonormal (right, up, towards-viewer) for ``view_dir``."""
    w = np.asarray(view_dir, dtype=float)
    w = w / np.linalg.norm(w)
    world_up = np.array([0.0, 0.0, 1.0]) if abs(w[2]) < 0.999 else np.array([0.0, 1.0, 0.0])
    right = np.cross(world_up, w)
    right /= np.linalg.norm(right)
    return right, np.cross(w, right), w


def _triangles(shape: TopoDS_Shape) -> np.ndarray:
    """All mesh triangles, (n, 3, 3) world coordinates, wound along the outward face normal."""
    out = []
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
        out.append(nodes[idx])
    return np.concatenate(out) if out else np.zeros((0, 3, 3))


def _is_closed(shape: TopoDS_Shape) -> bool:
    """True if every face lies in a shell and every shell is closed (so back faces are hidden)."""
    explorer, shells = TopExp_Explorer(shape, TopAbs_SHELL), 0
    while explorer.More():
        if not BRep_Tool.IsClosed_s(explorer.Current()):
            return False
        shells += 1
        explorer.Next()
    return shells > 0 and not TopExp_Explorer(shape, TopAbs_FACE, TopAbs_SHELL).More()


def _bisect_long(tris: np.ndarray, limit: float) -> tuple[np.ndarray, np.ndarray]:
    """Halve triangles across their longest edge until no edge exceeds ``limit``, keeping the
    winding; long slivers otherwise defeat the painter's sort. Returns the parts and, for each,
    the index of the triangle it came from."""
    owner = np.arange(len(tris))
    done, done_owner = [], []
    while len(tris):
        lengths = np.linalg.norm(tris - np.roll(tris, -1, axis=1), axis=2)  # edge k: vertex k -> k+1
        longest = lengths.argmax(axis=1)
        long = lengths[np.arange(len(tris)), longest] > limit
        done.append(tris[~long])
        done_owner.append(owner[~long])
        tris, owner, k = tris[long], owner[long], longest[long]
        rolled = np.take_along_axis(tris, ((k[:, None] + np.arange(3)) % 3)[:, :, None], axis=1)
        a, b, c = rolled[:, 0], rolled[:, 1], rolled[:, 2]  # longest edge is a -> b
        m = 0.5 * (a + b)
        tris = np.concatenate([np.stack([a, m, c], 1), np.stack([m, b, c], 1)])
        owner = np.concatenate([owner, owner])
    return np.concatenate(done), np.concatenate(done_owner)


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


def _zbuffer(tris: np.ndarray, res: int) -> tuple[np.ndarray, np.ndarray, float]:
    """Nearest depth per pixel centre (-inf = empty); also the grid origin and pixel size."""
    lo = tris[:, :, :2].reshape(-1, 2).min(axis=0)
    hi = tris[:, :, :2].reshape(-1, 2).max(axis=0)
    h = max(float((hi - lo).max()), 1e-12) / (res - 1)
    shape = tuple(int(n) + 1 for n in np.ceil((hi - lo) / h))  # (nx, ny)
    z = np.full(shape[0] * shape[1], -np.inf)
    p = (tris[:, :, :2] - lo) / h  # pixel coordinates
    i0, i1 = np.ceil(p.min(axis=1)).astype(int), np.floor(p.max(axis=1)).astype(int)
    extent = np.max(i1 - i0 + 1, axis=1)
    size = np.where(extent <= 1, 1, 2 ** np.ceil(np.log2(np.maximum(extent, 1)))).astype(int)
    for s in np.unique(size[extent > 0]):  # triangles grouped by bounding-box size
        off = np.stack(np.meshgrid(np.arange(s), np.arange(s), indexing="ij"), -1).reshape(-1, 2)
        sel = np.flatnonzero((size == s) & (extent > 0))
        for chunk in np.array_split(sel, max(1, len(sel) * s * s // 2_000_000)):
            a, b, c = p[chunk, 0], p[chunk, 1], p[chunk, 2]
            pix = i0[chunk][:, None, :] + off[None]  # (n, s*s, 2)
            ab, ac, ap = b - a, c - a, pix - a[:, None]
            den = ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0]
            den = np.where(np.abs(den) < 1e-12, np.nan, den)[:, None]
            u = (ap[..., 0] * ac[:, None, 1] - ap[..., 1] * ac[:, None, 0]) / den
            v = (ab[:, None, 0] * ap[..., 1] - ab[:, None, 1] * ap[..., 0]) / den
            d = tris[chunk, :, 2]
            depth = d[:, :1] + u * (d[:, 1:2] - d[:, :1]) + v * (d[:, 2:3] - d[:, :1])
            ok = (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9)
            ok &= (pix[..., 0] < shape[0]) & (pix[..., 1] < shape[1]) & (pix[..., 0] >= 0) & (pix[..., 1] >= 0)
            np.maximum.at(z, pix[..., 0][ok] * shape[1] + pix[..., 1][ok], depth[ok])
    return z.reshape(shape), lo, h


def _split_edges(edges: list[np.ndarray], tris: np.ndarray, diag: float) -> tuple[list, list]:
    """Edge segments (screen xy pairs) split into visible and hidden by a z-buffer of ``tris``
    (the painted triangles: small after bisection, so cheap to rasterise)."""
    segs = np.concatenate([np.stack([e[:-1], e[1:]], 1) for e in edges]) if edges else np.zeros((0, 2, 3))
    if not len(tris) or not len(segs):
        return list(segs[:, :, :2]), []
    z, lo, h = _zbuffer(tris, ZBUFFER_PX)
    padded = np.pad(z, 1, constant_values=-np.inf)
    nx, ny = z.shape  # nearest-surface depth allowing for one pixel of slack: min over 3x3
    zmin = np.min([padded[i : i + nx, j : j + ny] for i in range(3) for j in range(3)], axis=0)
    mid = segs.mean(axis=1)  # test each segment at its midpoint and both ends
    vis = np.zeros(len(segs), dtype=int)
    for pt in (segs[:, 0], mid, segs[:, 1]):
        ij = np.clip(np.rint((pt[:, :2] - lo) / h).astype(int), 0, np.array(z.shape) - 1)
        vis += pt[:, 2] >= zmin[ij[:, 0], ij[:, 1]] - (2.0 * h + 2e-3 * diag)
    shown = vis >= 2
    return list(segs[shown][:, :, :2]), list(segs[~shown][:, :, :2])
