"""Closed axes' tubes (issue 11 item 3): tests/unit/brep/test_closed_tubes.py and
tests/e2e/test_cli_closed_tubes.py (and the canal surfaces' tests/unit/brep/test_closed_canal.py
and tests/e2e/test_cli_closed_canal.py): the trefoil, and the closed meshes on the
curvature-line grid (tubecad.export.tessellate) counted from the step rules alone."""

import math

import numpy as np

TWO_PI = 2 * math.pi


def trefoil(t: np.ndarray) -> np.ndarray:
    return np.stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)], axis=-1)


def closed_mesh(vertices: np.ndarray, triangles: np.ndarray) -> tuple[set, float]:
    """(how many triangles use each edge, as a set; the signed volume) of a mesh."""
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return set(uses.tolist()), float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def grid_counts(
    axis, layout, radius: float, tolerance: float, angular: float = 0.1, columns_deg=None
) -> tuple[int, int, float]:
    """The grid's columns round the tube and row steps along it, from the step rules alone:
    each sector between stringers (the face columns ``columns_deg`` where the faces are also
    split at a C0 knot of the circle) cut into equal steps of at most angle_step, each ring bay
    into equal steps of at most arc_step at the bay's largest axis curvature (sampled densely
    inside the bay: the curvature may jump at its ends, a route's line-bend joints); and the
    ring polygon's area deficit 1 - sum(sin(step)) / (2 pi)."""
    from tubecad.export.tessellate import angle_step, arc_step

    step = angle_step(radius, tolerance, angular)
    columns_deg = columns_deg or layout.stringers_deg
    ends = [*columns_deg, columns_deg[0] + 360.0]
    sectors = [math.radians(b - a) for a, b in zip(ends[:-1], ends[1:])]
    cuts = [math.ceil(width / step) for width in sectors]
    deficit = 1.0 - sum(n * math.sin(width / n) for n, width in zip(cuts, sectors)) / TWO_PI
    rows = 0
    for s0, s1 in zip(layout.s_rings[:-1], layout.s_rings[1:]):
        k = float(np.max(np.abs(axis.curvature(np.linspace(s0, s1, 1001)[1:-1]))))
        rows += max(1, math.ceil((s1 - s0) / arc_step(k, radius, tolerance, angular)))
    return sum(cuts), rows, deficit


def on_closing_ring(axis, vertices: np.ndarray, reach: float) -> int:
    """How many vertices lie in the closing ring's plane (the normal plane at the span's
    start), within ``reach`` of the axis."""
    start = axis.at(np.array([axis.span[0]]))
    offset = vertices - start.position[0]
    return int(np.count_nonzero((np.abs(offset @ start.t[0]) < 1e-5) & (np.linalg.norm(offset, axis=1) < reach)))
