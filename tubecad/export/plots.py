"""Pictures of a tube with its curvature-line net: frontal and horizontal projections,
like the paper's Fig. 2 (a: frontal, onto XZ seen from -Y; b: horizontal, onto XY seen
from +Z). Each net cell is a shaded polygon, drawn far to near (painter's algorithm), with
its borders, the ring frames (s = const) and stringers (u = const), drawn over it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

from tubecad.core.atomic import save_figure
from tubecad.surface import CurvatureLineSurface

#: (title, horizontal axis, vertical axis, viewing direction)
VIEWS = {
    "frontal": ("a - frontal projection (XZ)", 0, 2, np.array([0.0, 1.0, 0.0])),
    "horizontal": ("b - horizontal projection (XY)", 0, 1, np.array([0.0, 0.0, -1.0])),
}
LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def projection_figure(
    tube: CurvatureLineSurface,
    rings: int = 41,
    stringers: int = 24,
    subdivisions: int = 6,
    s_rings: Sequence[float] | None = None,
    stringers_deg: Sequence[float] | None = None,
) -> Figure:
    """A matplotlib Figure with the frontal and horizontal projections side by side, of any
    curvature-line surface (a tube or a canal surface): the net of ``rings`` equal ring frames
    and ``stringers`` equal stringers, or of a layout's own ``s_rings`` (arc lengths) and
    ``stringers_deg`` (angles chi from r1, u = chi); the span's ends close the net (a closed
    axis' rings do not repeat its start)."""
    if s_rings is None:
        s_lines = np.linspace(*tube.span, rings)
    else:
        s_lines = np.unique(np.concatenate([np.asarray(s_rings, dtype=float), tube.span]))
    if stringers_deg is None:
        u_lines = np.linspace(0.0, 2.0 * math.pi, stringers + 1)
    else:
        angles = np.sort(np.radians(np.asarray(stringers_deg, dtype=float)) % (2.0 * math.pi))
        u_lines = np.append(angles, angles[0] + 2.0 * math.pi)
    stringers, rings = len(u_lines) - 1, len(s_lines)
    closed = int(bool(tube.axis.closed))  # the last ring is the first one again
    u = _subdivided(u_lines, subdivisions)
    s = _subdivided(s_lines, subdivisions)
    pts = tube.grid(u, s)
    normals = tube.normal(u[:, None], s[None, :])
    cells = _cell_outlines(pts, stringers, rings - 1, subdivisions)
    centres = _cell_centres(normals, stringers, rings - 1, subdivisions)
    cell_normals = centres / np.linalg.norm(centres, axis=-1, keepdims=True)
    cell_points = cells.mean(axis=1)

    fig = Figure(figsize=(14, 7))  # no pyplot: the user's backend is left alone
    axes = fig.subplots(1, 2)
    axis_line = tube.axis.position(s)
    for ax, (title, i, j, view) in zip(axes, VIEWS.values()):
        order = np.argsort(cell_points @ view)[::-1]  # far first
        shade = 0.35 + 0.6 * np.abs(cell_normals @ LIGHT)
        facing = (cell_normals @ view) < 0
        colours = np.where(facing[:, None], [[0.55, 0.72, 0.95]], [[0.75, 0.78, 0.85]]) * shade[:, None]
        polys = PolyCollection(
            cells[order][:, :, [i, j]],  # type: ignore[arg-type]  # (an (n, k, 2) array is fine; the stubs say Sequence)
            facecolors=np.clip(colours[order], 0, 1),
            edgecolors="#1d2a44",
            linewidths=0.35,
        )
        ax.add_collection(polys)
        ax.plot(axis_line[:, i], axis_line[:, j], "-.", color="#b03030", linewidth=0.7, label="axis")
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_title(title)
        ax.set_xlabel("XYZ"[i])
        ax.set_ylabel("XYZ"[j])
        ax.legend(loc="upper left", fontsize=8)
    a = tube.axis
    law = tube.radius_law
    ends = law.r(np.array(tube.span))
    radius = f"rho = {ends[0]:g}" if tube.constant_radius else f"r from {ends[0]:g} to {ends[1]:g}"
    parameters, beta_deg = getattr(a, "parameters", None), getattr(a, "beta_deg", None)  # a slope curve's
    kind = a.family if parameters is None or beta_deg is None else f"{a.family} {parameters()}, beta = {beta_deg:g} deg"
    fig.suptitle(
        f"Tube referred to lines of curvature: {kind}, "
        f"{radius}, s in [{tube.span[0]:g}, {tube.span[1]:g}]\n"
        f"{rings - closed} ring frames (s = const) x {stringers} stringers (u = const)",
        fontsize=10,
    )
    fig.tight_layout()
    return fig


def write_projections(
    tube: CurvatureLineSurface, folder: str | Path, stem: str = "projections", **kwargs: Any
) -> list[Path]:
    """Write ``stem``.png and ``stem``.svg into ``folder`` (atomically); return their paths."""
    return save_figure(projection_figure(tube, **kwargs), folder, stem)


def _subdivided(lines: np.ndarray, sub: int) -> np.ndarray:
    """``sub`` equal steps between consecutive values of ``lines``: (len - 1) * sub + 1 values."""
    steps = np.linspace(0.0, 1.0, sub, endpoint=False)
    inner = lines[:-1, None] + np.diff(lines)[:, None] * steps[None, :]
    return np.append(inner.ravel(), lines[-1])


def _cell_outlines(pts: np.ndarray, nu_cells: int, ns_cells: int, sub: int) -> np.ndarray:
    """Closed outlines (4 * sub points) of every net cell, following the curved borders."""
    outlines = []
    for i in range(nu_cells):
        for j in range(ns_cells):
            u0, u1, s0, s1 = i * sub, (i + 1) * sub, j * sub, (j + 1) * sub
            outlines.append(
                np.concatenate(
                    [
                        pts[u0:u1, s0],
                        pts[u1, s0:s1],
                        pts[u1:u0:-1, s1],
                        pts[u0, s1:s0:-1],
                    ]
                )
            )
    return np.array(outlines)


def _cell_centres(values: np.ndarray, nu_cells: int, ns_cells: int, sub: int) -> np.ndarray:
    mid = sub // 2
    return values[mid : nu_cells * sub : sub, mid : ns_cells * sub : sub].reshape(-1, 3)
