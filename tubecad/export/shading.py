"""The pictures' shared numpy part: the camera, smooth (Gouraud) shading and hidden lines,
for :mod:`tubecad.export.render` (a B-rep read back) and :mod:`tubecad.export.plots` (the
exact surface's projections).

Screen coordinates are (x, y) and depth (larger = nearer the viewer). Shading is per
vertex: ambient light, a Lambert term and a soft Blinn highlight from a light fixed in the
camera frame (upper left, in front), so every view is lit alike; a colour map
(:func:`shades`) turns the shade into the surface's colour, darker for sides seen from
their back. Hidden lines: a coarse z-buffer of the screen triangles, and line segments split
into the parts it shows and the parts it hides. The triangles should be small (each picture
cuts or samples its surface finely), so the buffer is cheap to fill: triangles are grouped
by the size of their pixel box and filled a group at a time.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.colors import ListedColormap

#: z-buffer resolution along the longer screen side: about a view's pixels (a projection's
#: panel is ~700 px wide at 150 dpi); the hidden-line test allows a pixel of slack round it
ZBUFFER_PX = 600
#: the light, in the camera frame (x right, y up, z towards the viewer): upper left, in front
LIGHT = np.array([-0.4, 0.6, 1.0]) / np.linalg.norm([-0.4, 0.6, 1.0])
AMBIENT, DIFFUSE, SPECULAR, SHININESS = 0.3, 0.62, 0.25, 24.0
BACK_FACTOR = 0.75  # back sides are this much darker
#: shades run from 0 (black) through 1 (the surface's colour, fully lit) up to SHADE_TOP (the highlight)
SHADE_TOP = 1.25


def camera(view_dir: Sequence[float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The camera's axes for a view from ``view_dir``.

    Args:
        view_dir: from the scene towards the viewer.

    Returns:
        Orthonormal (right, up, towards the viewer): screen up is world +Z projected (world +Y
        when looking along Z), right = up x towards.
    """
    w = np.asarray(view_dir, dtype=float)
    w = w / np.linalg.norm(w)
    world_up = np.array([0.0, 0.0, 1.0]) if abs(w[2]) < 0.999 else np.array([0.0, 1.0, 0.0])
    right = np.cross(world_up, w)
    right /= np.linalg.norm(right)
    return right, np.cross(w, right), w


def shade_of(normals: np.ndarray, facing: np.ndarray) -> np.ndarray:
    """The shade of each vertex (0 .. SHADE_TOP, for :func:`shades`).

    Args:
        normals: (n, 3, 3) unit vertex normals in the camera frame, per triangle.
        facing: (n,) whether each triangle faces the viewer; one seen from its back is lit
            from its back side (its normals turned) and BACK_FACTOR darker.

    Returns:
        (n, 3) shades: ambient, Lambert and a Blinn highlight from LIGHT.
    """
    n = np.where(facing[:, None, None], normals, -normals)
    half = LIGHT + np.array([0.0, 0.0, 1.0])
    half /= np.linalg.norm(half)
    lambert = np.clip(n @ LIGHT, 0.0, 1.0)
    highlight = np.clip(n @ half, 0.0, 1.0) ** SHININESS
    shade = AMBIENT + DIFFUSE * lambert + SPECULAR * highlight
    return np.clip(shade * np.where(facing, 1.0, BACK_FACTOR)[:, None], 0.0, SHADE_TOP)


def shades(rgb: Sequence[float]) -> ListedColormap:
    """The colour map of :func:`shade_of`'s shades over [0, SHADE_TOP]: black up to ``rgb``
    at 1, then towards white (the highlight)."""
    v = np.linspace(0.0, SHADE_TOP, 256)[:, None]
    lit = np.asarray(rgb, dtype=float)[None, :] * np.minimum(v, 1.0)
    white = np.clip((v - 1.0) / (SHADE_TOP - 1.0), 0.0, 1.0)
    return ListedColormap(lit + (1.0 - lit) * 0.8 * white)


def paint_gouraud(ax, tris: np.ndarray, shade: np.ndarray, cmap: ListedColormap, grow: float = 0.0, **kwargs):
    """Paint screen triangles far to near, each shaded smoothly between its vertices.

    Args:
        ax: the matplotlib Axes.
        tris: (n, 3, >= 3) triangles: screen x, y, depth per vertex.
        shade: (n, 3) the vertices' shades (:func:`shade_of`).
        cmap: :func:`shades` of the surface's colour.
        grow: each triangle is drawn this much larger (screen units, away from its centroid),
            about a pixel, so that antialiased neighbours leave no hairline between them.
        **kwargs: passed to ``Axes.tripcolor`` (e.g. ``rasterized=True``, ``zorder``).

    Returns:
        The tripcolor artist.
    """
    from matplotlib.tri import Triangulation

    order = np.argsort(tris[:, :, 2].mean(axis=1))  # far first
    xy = tris[order][:, :, :2]
    if grow > 0.0:
        out = xy - xy.mean(axis=1, keepdims=True)
        xy = xy + grow * out / np.maximum(np.linalg.norm(out, axis=2, keepdims=True), 1e-300)
    xy = xy.reshape(-1, 2)
    mesh = Triangulation(xy[:, 0], xy[:, 1], np.arange(len(xy)).reshape(-1, 3))
    return ax.tripcolor(mesh, shade[order].ravel(), shading="gouraud", cmap=cmap, vmin=0.0, vmax=SHADE_TOP, **kwargs)


def zbuffer(tris: np.ndarray, res: int = ZBUFFER_PX) -> tuple[np.ndarray, np.ndarray, float]:
    """The nearest depth at each pixel centre of a ``res``-pixel grid over the triangles.

    Args:
        tris: (n, 3, 3) triangles, screen x, y and depth per vertex (at least one).
        res: pixels along the longer side of the triangles' screen box.

    Returns:
        (depths, origin, pixel size): depths (nx, ny), the nearest surface within one pixel
        of each pixel centre (the hidden-line test's slack: the least of the 3 x 3 pixels
        round it), -inf where no triangle is that near; the grid's lower-left corner (x, y);
        the pixel's side.
    """
    lo = tris[:, :, :2].reshape(-1, 2).min(axis=0)
    hi = tris[:, :, :2].reshape(-1, 2).max(axis=0)
    h = max(float((hi - lo).max()), 1e-12) / (res - 1)
    shape = tuple(int(n) + 1 for n in np.ceil((hi - lo) / h))  # (nx, ny)
    z = np.full(shape[0] * shape[1], -np.inf)
    p = (tris[:, :, :2] - lo) / h  # pixel coordinates
    i0, i1 = np.ceil(p.min(axis=1)).astype(int), np.floor(p.max(axis=1)).astype(int)
    extent = i1 - i0 + 1  # (n, 2): pixel centres inside each triangle's box, along x and y
    covers = np.all(extent > 0, axis=1)
    size = (2 ** np.ceil(np.log2(np.maximum(extent, 1)))).astype(int)  # boxes grouped by size, x and y apart
    for sx, sy in np.unique(size[covers], axis=0):
        off = np.stack(np.meshgrid(np.arange(sx), np.arange(sy), indexing="ij"), -1).reshape(-1, 2)
        sel = np.flatnonzero(covers & (size[:, 0] == sx) & (size[:, 1] == sy))
        for chunk in np.array_split(sel, max(1, len(sel) * sx * sy // 2_000_000)):
            _fill(z, shape, p[chunk], tris[chunk, :, 2], i0[chunk][:, None, :] + off[None])
    return _with_slack(z.reshape(shape)), lo, h


def _with_slack(z: np.ndarray) -> np.ndarray:
    """Each pixel's depth as the least of the 3 x 3 pixels round it (outside: -inf)."""
    padded = np.pad(z, 1, constant_values=-np.inf)
    nx, ny = z.shape
    return np.min([padded[i : i + nx, j : j + ny] for i in range(3) for j in range(3)], axis=0)


def _fill(z: np.ndarray, shape: tuple[int, ...], p: np.ndarray, d: np.ndarray, pix: np.ndarray) -> None:
    """Keep in the flat buffer ``z`` the nearest depth of each triangle (pixel coordinates
    ``p``, vertex depths ``d``) at the candidate pixels ``pix`` (n, k, 2) it covers."""
    a, b, c = p[:, 0], p[:, 1], p[:, 2]
    ab, ac, ap = b - a, c - a, pix - a[:, None]
    den = ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0]
    den = np.where(np.abs(den) < 1e-12, np.nan, den)[:, None]
    u = (ap[..., 0] * ac[:, None, 1] - ap[..., 1] * ac[:, None, 0]) / den
    v = (ab[:, None, 0] * ap[..., 1] - ab[:, None, 1] * ap[..., 0]) / den
    depth = d[:, :1] + u * (d[:, 1:2] - d[:, :1]) + v * (d[:, 2:3] - d[:, :1])
    ok = (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9)
    ok &= (pix[..., 0] < shape[0]) & (pix[..., 1] < shape[1]) & (pix[..., 0] >= 0) & (pix[..., 1] >= 0)
    np.maximum.at(z, pix[..., 0][ok] * shape[1] + pix[..., 1][ok], depth[ok])


def split_visible(
    segs: np.ndarray, buffer: tuple[np.ndarray, np.ndarray, float] | None, diag: float
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Line segments split into those a surface leaves visible and those it hides
    (:func:`visible_mask`).

    Args:
        segs: (m, 2, 3) segments, screen x, y and depth per end.
        buffer: the surface's :func:`zbuffer` in the same coordinates (None: no surface).
        diag: the picture's size (its bounding box diagonal), for the depth slack.

    Returns:
        (visible, hidden): lists of (2, 2) screen segments.
    """
    shown = visible_mask(segs, buffer, diag)
    return list(segs[shown][:, :, :2]), list(segs[~shown][:, :, :2])


def visible_mask(segs: np.ndarray, buffer: tuple[np.ndarray, np.ndarray, float] | None, diag: float) -> np.ndarray:
    """Which segments a surface leaves visible: those of which at least two of the ends and
    the midpoint lie no deeper than the nearest surface there (allowing for a pixel round it
    and 2e-3 ``diag``).

    Args:
        segs: (m, 2, 3) segments, screen x, y and depth per end.
        buffer: the surface's :func:`zbuffer` in the same coordinates (None: no surface).
        diag: the picture's size (its bounding box diagonal), for the depth slack.

    Returns:
        (m,) booleans.
    """
    if buffer is None or not len(segs):
        return np.ones(len(segs), dtype=bool)
    zmin, lo, h = buffer  # the nearest surface, with a pixel of slack round it (zbuffer)
    mid = segs.mean(axis=1)  # test each segment at its midpoint and both ends
    vis = np.zeros(len(segs), dtype=int)
    for pt in (segs[:, 0], mid, segs[:, 1]):
        ij = np.clip(np.rint((pt[:, :2] - lo) / h).astype(int), 0, np.array(zmin.shape) - 1)
        vis += pt[:, 2] >= zmin[ij[:, 0], ij[:, 1]] - (2.0 * h + 2e-3 * diag)
    return vis >= 2
