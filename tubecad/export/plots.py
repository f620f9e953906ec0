"""Pictures of a tube with its curvature-line net: frontal and horizontal projections,
like the paper's Fig. 2 (a: frontal, onto XZ seen from -Y; b: horizontal, onto XY seen
from +Z).

What is drawn: the exact surface, sampled finely whatever the net (U_SAMPLES round the tube;
along the axis as many rings of samples as keep each step within STEP_TURN of the normal's
turning and STEP_LENGTH x the girth step, capped at MAX_S_SAMPLES), shaded smoothly
(Gouraud, :mod:`tubecad.export.shading`) and painted far to near; over it the net, the ring
frames (s = const) and the stringers (u = const) in two colours, the parts the surface hides
found by a z-buffer and drawn faint; the axis as a thin centre line. The title states the
net as built (its rings x stringers), the radius, the span and, when given, the fit's
largest deviation and tolerance. The surface is rasterised in vector formats (SVG), the
lines stay vectors.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from tubecad.core.atomic import save_figure
from tubecad.export.shading import paint_gouraud, shade_of, shades, visible_mask, zbuffer
from tubecad.surface import CurvatureLineSurface

#: (title, horizontal axis, vertical axis, towards the viewer)
VIEWS = {
    "frontal": ("a - frontal projection (XZ)", 0, 2, np.array([0.0, -1.0, 0.0])),
    "horizontal": ("b - horizontal projection (XY)", 0, 1, np.array([0.0, 0.0, 1.0])),
}
SURFACE_RGB = (0.66, 0.78, 0.93)  # light blue
RING_COLOUR, STRINGER_COLOUR, AXIS_COLOUR = "#b2182b", "#08306b", "#4d4d4d"
#: surface samples round the tube
U_SAMPLES = 72
#: along the axis, over a sample step the surface's normal turns by at most this (radians) ...
STEP_TURN = 0.03
#: ... and is at most this x the girth step (2 pi r / U_SAMPLES)
STEP_LENGTH = 2.0
MAX_S_SAMPLES = 1500
#: a canal surface gets at most this many times U_SAMPLES round it
MAX_U_FACTOR = 4
#: points along each ring line, per surface sample round the tube
RING_OVERSAMPLE = 4
#: about how many pixels a view's longer side spans (at 150 dpi)
VIEW_PX = 900
#: a line's visible or hidden runs shorter than this many segments are taken as the run before
MIN_RUN = 4


def projection_figure(
    tube: CurvatureLineSurface,
    rings: int = 41,
    stringers: int = 24,
    subdivisions: int = 6,
    s_rings: Sequence[float] | None = None,
    stringers_deg: Sequence[float] | None = None,
    fit_deviation: float | None = None,
    tolerance: float | None = None,
    wall: float | None = None,
) -> Figure:
    """The frontal and horizontal projections side by side (module docstring).

    Args:
        tube: any curvature-line surface (a tube or a canal surface).
        rings: equal ring frames, if ``s_rings`` is not given (the span's ends included).
        stringers: equal stringers, if ``stringers_deg`` is not given.
        subdivisions: the surface is sampled at least this finely per net cell each way.
        s_rings: a layout's ring frames (arc lengths); the span's ends close the net (a
            closed axis' rings do not repeat its start).
        stringers_deg: a layout's stringer angles chi from r1 (u = chi), degrees.
        fit_deviation: the fitted surface's largest deviation from the exact one, for the title.
        tolerance: the fit's tolerance, for the title.
        wall: the wall's thickness, for the title, when ``tube`` is a wall's outer surface.

    Returns:
        The matplotlib Figure (never pyplot's).
    """
    s_lines, u_lines = _net(tube, rings, stringers, s_rings, stringers_deg)
    u = _u_samples(tube, max(U_SAMPLES, subdivisions * (len(u_lines) - 1)))
    s = _s_samples(tube, s_lines, subdivisions, u[:: max(1, len(u) // 36)])
    pts, normals = tube.grid(u, s), tube.normal(u[:, None], s[None, :])
    ring_lines = [tube.points(np.linspace(0.0, 2.0 * math.pi, RING_OVERSAMPLE * len(u)), x) for x in s_lines]
    stringer_lines = [tube.points(x, s) for x in u_lines[:-1]]

    fig = Figure(figsize=(14, 7))  # no pyplot: the user's backend is left alone
    axes = fig.subplots(1, 2)
    axis_line = tube.axis.position(s)
    for ax, (title, i, j, towards) in zip(axes, VIEWS.values()):
        _draw_view(ax, pts, normals, ring_lines, stringer_lines, (i, j, towards))
        ax.plot(axis_line[:, i], axis_line[:, j], "-.", color=AXIS_COLOUR, linewidth=0.6, zorder=4)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_title(title)
        ax.set_xlabel("XYZ"[i])
        ax.set_ylabel("XYZ"[j])
    closed = int(bool(tube.axis.closed))  # the last ring is the first one again
    n_rings, n_stringers = len(s_lines) - closed, len(u_lines) - 1
    fig.legend(handles=_legend(n_rings, n_stringers), loc="lower center", ncol=4, fontsize=9, frameon=False)
    fig.suptitle(projection_title(tube, n_rings, n_stringers, fit_deviation, tolerance, wall), fontsize=10)
    height = fig.get_size_inches()[1]
    fig.tight_layout(rect=(0.0, 0.45 / height, 1.0, 1.0 - 0.5 / height))  # above the legend, below the title
    return fig


def projection_figure_of_build(build: Any, fit_deviation: float | None = None) -> Figure:
    """:func:`projection_figure` of a build's outer surface on its own net as built.

    Args:
        build: a :class:`~tubecad.brep.TubeBuild` (a tube or a wall).
        fit_deviation: the fit's largest deviation measured (e.g. the report's), for the title.

    Returns:
        The Figure, titled with the build's rings x stringers, its fit tolerance and, for a
        wall, its thickness.
    """
    layout = build.layout
    radii = list(build.radii)
    return projection_figure(
        build.surfaces[0].tube,
        s_rings=layout.s_rings,
        stringers_deg=layout.stringers_deg,
        fit_deviation=fit_deviation,
        tolerance=build.tolerance,
        wall=radii[0] - radii[1] if len(radii) == 2 else None,
    )


def write_projections(
    tube: CurvatureLineSurface, folder: str | Path, stem: str = "projections", **kwargs: Any
) -> list[Path]:
    """Write ``stem``.png and ``stem``.svg of :func:`projection_figure` into ``folder``, atomically.

    Args:
        tube: the surface.
        folder: where to write.
        stem: the files' name without extension.
        **kwargs: :func:`projection_figure`'s.

    Returns:
        The two paths.
    """
    return save_figure(projection_figure(tube, **kwargs), folder, stem)


def projection_title(
    tube: CurvatureLineSurface,
    rings: int,
    stringers: int,
    fit_deviation: float | None = None,
    tolerance: float | None = None,
    wall: float | None = None,
) -> str:
    """Two lines: the axis, radius (a wall's: of its outer surface, and its thickness) and
    span; the net ("11 rings x 8 stringers") and the fit."""
    a = tube.axis
    r = np.abs(tube.radius_law.r(np.linspace(*tube.span, 1001)))
    radius = f"rho = {r[0]:g}" if tube.constant_radius else f"r from {r.min():.4g} to {r.max():.4g}"
    if wall is not None:
        radius = f"outer {radius}, wall {wall:g} thick"
    parameters, beta_deg = getattr(a, "parameters", None), getattr(a, "beta_deg", None)  # a slope curve's
    kind = a.family
    if parameters is not None and beta_deg is not None:
        kind += " " + ", ".join(f"{k} = {_shown(v)}" for k, v in parameters().items()) + f", beta = {beta_deg:g} deg"
    fit = []
    if fit_deviation is not None:
        fit.append(f"max fit deviation {fit_deviation:.2g}")
    if tolerance is not None:
        fit.append(f"fit tolerance {tolerance:g}")
    return (
        f"Tube referred to lines of curvature: {kind}, {radius}, s in [{tube.span[0]:g}, {tube.span[1]:g}]\n"
        f"net: {rings} rings x {stringers} stringers" + "".join(f"; {x}" for x in fit)
    )


def _shown(value: Any) -> str:
    """A parameter as the title shows it: a number to 6 digits, anything else (an expression) as it is."""
    return f"{value:.6g}" if isinstance(value, (int, float)) else str(value)


def _net(
    tube: CurvatureLineSurface,
    rings: int,
    stringers: int,
    s_rings: Sequence[float] | None,
    stringers_deg: Sequence[float] | None,
) -> tuple[np.ndarray, np.ndarray]:
    """The net's ring arc lengths (the span's ends included) and stringer angles u (radians,
    sorted, the first repeated a turn later)."""
    if s_rings is None:
        s_lines = np.linspace(*tube.span, rings)
    else:
        s_lines = np.unique(np.concatenate([np.asarray(s_rings, dtype=float), tube.span]))
    if stringers_deg is None:
        u_lines = np.linspace(0.0, 2.0 * math.pi, stringers + 1)
    else:
        angles = np.sort(np.radians(np.asarray(stringers_deg, dtype=float)) % (2.0 * math.pi))
        u_lines = np.append(angles, angles[0] + 2.0 * math.pi)
    return s_lines, u_lines


def _u_samples(tube: CurvatureLineSurface, count: int) -> np.ndarray:
    """The stringer parameters u of the surface's samples round it, [0, 2 pi]: ``count``
    equal steps on a tube; on a canal surface, whose u is the angle at the span's start
    carried along by a Moebius map (points crowd on one side of a circle and thin out on
    the other), as many as keep the normal's turn between neighbours within 2 pi / ``count``
    on every circle (at most MAX_U_FACTOR x ``count``)."""
    if tube.constant_radius:
        return np.linspace(0.0, 2.0 * math.pi, count + 1)
    fine = np.linspace(0.0, 2.0 * math.pi, 16 * count + 1)
    normals = tube.normal(fine[:, None], np.linspace(*tube.span, 41)[None, :])
    cosines = np.clip(np.einsum("ijk,ijk->ij", normals[1:], normals[:-1]), -1.0, 1.0)
    turned = np.arccos(cosines).max(axis=1)  # the largest turn on any circle, per fine step
    cumulative = np.concatenate([[0.0], np.cumsum(turned)])
    n = int(min(max(math.ceil(cumulative[-1] * count / (2.0 * math.pi)), count), MAX_U_FACTOR * count))
    return np.interp(np.linspace(0.0, cumulative[-1], n + 1), cumulative, fine)


def _s_samples(tube: CurvatureLineSurface, s_lines: np.ndarray, subdivisions: int, u: np.ndarray) -> np.ndarray:
    """Arc lengths of the surface's rings of samples: steps over which the surface's normal
    turns by at most STEP_TURN and its points move at most STEP_LENGTH girth steps (measured
    at the stringer parameters ``u`` on a pre-sample of the exact surface, so a canal surface
    whose circles sweep fast is sampled as finely as a tight bend), at least ``subdivisions``
    per ring bay, and the net's rings and the surface's breaks."""
    fine = np.linspace(*tube.span, 2001)
    pts, normals = tube.grid(u, fine), tube.normal(u[:, None], fine[None, :])
    ds = np.diff(fine)
    moved = np.linalg.norm(np.diff(pts, axis=1), axis=2).max(axis=0) / ds
    cosines = np.clip(np.einsum("ijk,ijk->ij", normals[:, 1:], normals[:, :-1]), -1.0, 1.0)
    turned = np.arccos(cosines).max(axis=0) / ds
    girth = np.linalg.norm(np.diff(pts, axis=0), axis=2).sum(axis=0)  # round each ring of the pre-sample
    step = STEP_LENGTH * np.maximum(0.5 * (girth[1:] + girth[:-1]), 1e-9 * tube.length) / U_SAMPLES
    density = np.maximum(turned / STEP_TURN, moved / step)  # samples per unit s, on each pre-sample step
    cumulative = np.concatenate([[0.0], np.cumsum(density * ds)])
    count = int(min(max(math.ceil(cumulative[-1]), 2), MAX_S_SAMPLES))
    s = np.interp(np.linspace(0.0, cumulative[-1], count + 1), cumulative, fine)
    bays = np.concatenate([np.linspace(a, b, subdivisions + 1) for a, b in zip(s_lines[:-1], s_lines[1:])])
    return np.unique(np.concatenate([s, bays, s_lines, np.asarray(tube.s_breaks(), dtype=float)]))


def _draw_view(ax, pts: np.ndarray, normals: np.ndarray, rings: list, stringers: list, view: tuple) -> None:
    """One projection: the surface grid ``pts`` (nu, ns, 3) shaded from its ``normals``, then
    the ring and stringer polylines, the hidden parts faint."""
    i, j, towards = view
    basis = _basis(i, j, towards)
    tris, tri_normals = _grid_triangles(pts @ basis), _grid_triangles(normals @ basis)
    facing = tri_normals[:, :, 2].mean(axis=1) >= 0.0  # the outward normal towards the viewer
    pixel = float(np.ptp(tris[:, :, :2].reshape(-1, 2), axis=0).max()) / VIEW_PX  # about a pixel on the screen
    painted = paint_gouraud(
        ax, tris, shade_of(tri_normals, facing), shades(SURFACE_RGB), grow=0.7 * pixel, rasterized=True
    )
    painted.set(zorder=1, gid="surface")
    diag = float(np.linalg.norm(np.ptp(pts.reshape(-1, 3), axis=0)))
    buffer = zbuffer(tris)
    for family, lines, colour in (("rings", rings, RING_COLOUR), ("stringers", stringers, STRINGER_COLOUR)):
        visible, hidden = [], []
        for line in lines:
            screen = line @ basis
            shown = _without_flicker(visible_mask(np.stack([screen[:-1], screen[1:]], 1), buffer, diag))
            visible += _runs(screen[:, :2], shown)
            hidden += _runs(screen[:, :2], ~shown)
        ax.add_collection(
            LineCollection(hidden, colors=colour, linewidths=0.5, alpha=0.25, zorder=2, gid=f"{family} hidden")
        )
        ax.add_collection(LineCollection(visible, colors=colour, linewidths=1.1, zorder=3, gid=f"{family} visible"))


def _without_flicker(shown: np.ndarray) -> np.ndarray:
    """A line's visible mask with runs shorter than MIN_RUN segments (where the line grazes
    the silhouette and the z-buffer cannot tell) turned to the state of the run before them."""
    out = shown.copy()
    edges = np.flatnonzero(np.diff(out.astype(int))) + 1
    starts, ends = np.concatenate([[0], edges]), np.concatenate([edges, [len(out)]])
    for a, b in zip(starts[1:], ends[1:]):
        if b - a < MIN_RUN and b < len(out):
            out[a:b] = out[a - 1]
    return out


def _runs(points: np.ndarray, mask: np.ndarray) -> list[np.ndarray]:
    """The polylines of ``points`` (m + 1, 2) over each run of consecutive segments where
    ``mask`` (m,) holds."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(int), [0]])))
    return [points[a : b + 1] for a, b in zip(edges[::2], edges[1::2])]


def _basis(i: int, j: int, towards: np.ndarray) -> np.ndarray:
    """World -> (screen x = world axis i, screen y = world axis j, depth along ``towards``)."""
    eye = np.eye(3)
    return np.stack([eye[i], eye[j], towards], axis=1)


def _grid_triangles(grid: np.ndarray) -> np.ndarray:
    """The (nu, ns, 3) grid's cells, two triangles each: (2 (nu - 1) (ns - 1), 3, 3)."""
    a, b = grid[:-1, :-1], grid[1:, :-1]
    c, d = grid[1:, 1:], grid[:-1, 1:]
    first = np.stack([a, b, c], axis=2).reshape(-1, 3, 3)
    second = np.stack([a, c, d], axis=2).reshape(-1, 3, 3)
    return np.concatenate([first, second])


def _legend(rings: int, stringers: int) -> list[Line2D]:
    """The legend's entries: the net's two families (with their counts) and the axis."""
    return [
        Line2D([], [], color=RING_COLOUR, linewidth=1.1, label=f"{rings} ring frames (s = const)"),
        Line2D([], [], color=STRINGER_COLOUR, linewidth=1.1, label=f"{stringers} stringers (u = const)"),
        Line2D([], [], color="#777777", linewidth=0.5, alpha=0.6, label="hidden parts (faint)"),
        Line2D([], [], color=AXIS_COLOUR, linestyle="-.", linewidth=0.6, label="axis"),
    ]
