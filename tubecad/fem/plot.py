"""A picture of a result on the deformed shell: each shell element a quadrilateral through
its corners moved by the displacement (scaled so that the largest is ``exaggeration`` of the
model's size), coloured by the mean of a nodal value over its corners (:func:`shell_colours`:
a node a stiffener's beam shares is left out, where CalculiX's nodal value mixes the beam's
stress with the shell's)."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from tubecad.fem.analysis import PressureResult


def deformed_figure(
    result: PressureResult, values: np.ndarray, label: str, exaggeration: float = 0.05, title: str = ""
):
    """The matplotlib figure (module docstring); ``label`` names ``values`` on the colour bar."""
    import matplotlib
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    mesh = result.mesh
    size = float(np.ptp(mesh.nodes, axis=0).max())
    u = np.nan_to_num(result.displacement)
    largest = float(np.linalg.norm(u, axis=1).max())
    scale = exaggeration * size / largest if largest > 0 else 0.0
    moved = mesh.nodes + scale * u
    corners = [b.connectivity[:, : b.corners] for b in mesh.shell_blocks]  # quads and triangles
    colour = shell_colours(mesh, values)
    polygons = [polygon for c in corners for polygon in moved[c]]
    fig = Figure(figsize=(9, 7))  # no pyplot: the user's backend is left alone
    ax = fig.add_subplot(projection="3d")
    cmap = matplotlib.colormaps["viridis"]
    lo, hi = float(np.nanmin(colour)), float(np.nanmax(colour))
    norm = Normalize(lo, hi if hi > lo else lo + 1.0)
    quads = Poly3DCollection(polygons, facecolors=cmap(norm(colour)), edgecolors="none", linewidths=0)
    ax.add_collection3d(quads)
    low, high = moved.min(axis=0), moved.max(axis=0)
    ax.set_xlim(low[0], high[0]), ax.set_ylim(low[1], high[1]), ax.set_zlim(low[2], high[2])
    ax.set_box_aspect(tuple(np.maximum(high - low, 1e-9 * size)))
    ax.set_axis_off()
    ax.view_init(elev=30, azim=-60)
    bar = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax, shrink=0.7)
    bar.set_label(label)
    ax.set_title(f"{title}\ndisplacements x {scale:.3g} (largest {largest:.3g} {mesh.length_unit})", fontsize=10)
    return fig


def shell_colours(mesh, values: np.ndarray) -> np.ndarray:
    """Per shell element (blocks in order), the mean of the nodal ``values`` over its corners
    that no beam element uses (all its corners where every one is a beam's); NaN where no
    corner has a value."""
    shared = np.zeros(len(mesh.nodes), dtype=bool)
    for block in mesh.beam_blocks:
        shared[block.connectivity.ravel()] = True
    out = []
    for block in mesh.shell_blocks:
        c = block.connectivity[:, : block.corners]
        v = np.asarray(values, dtype=float)[c]
        own = np.where(shared[c] & ~shared[c].all(axis=1, keepdims=True), np.nan, v)
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # an element with no value: NaN, said above
            out.append(np.nanmean(own, axis=1))
    return np.concatenate(out) if out else np.zeros(0)


def save_deformed(
    result: PressureResult, values: np.ndarray, label: str, folder: str | Path, stem: str, title: str = ""
) -> list[Path]:
    """:func:`deformed_figure` saved as ``stem``.png in ``folder``, atomically."""
    from tubecad.core.atomic import save_figure

    return save_figure(deformed_figure(result, values, label, title=title), folder, stem, formats=("png",), dpi=110)
