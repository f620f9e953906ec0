"""Element quality of a shell mesh: aspect ratio, corner angles, and the orthogonality of
the net at the nodes.

- aspect ratio: longest / shortest side of each element (its corner chords);
- skew: the largest |corner angle - 90 deg| of each element, from its corner chords;
- orthogonality: max |cos| of the angle between the ring and stringer tangents at the
  nodes, F / sqrt(E G) of the exact surface (0 on the curvature-line net up to round-off).

On the curvature-line net the corner angles differ from 90 deg only by the turn of the
lines across one element (the chords are not the tangents), so the skew falls as the mesh
is refined.
"""

from __future__ import annotations

import numpy as np


def corner_measures(nodes: np.ndarray, corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(aspect ratio, skew in degrees) per element of ``corners`` ((m, 4) node numbers)."""
    p = nodes[corners]  # (m, 4, 3)
    sides = np.roll(p, -1, axis=1) - p
    length = np.linalg.norm(sides, axis=-1)
    aspect = length.max(axis=1) / length.min(axis=1)
    a, b = -np.roll(sides, 1, axis=1), sides  # the two sides leaving each corner
    cos = np.einsum("mkj,mkj->mk", a, b) / (np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1))
    skew = np.degrees(np.abs(np.arcsin(np.clip(cos, -1.0, 1.0)))).max(axis=1)
    return aspect, skew


def element_quality(mesh) -> dict:
    """Aspect ratio and skew of the shells (max and mean) and the net's orthogonality, from
    the mesh's unit ring and stringer tangents (the exact surface's, at the nodes)."""
    shells = [b for b in mesh.blocks if b.shell]
    corners = np.concatenate([b.connectivity[:, :4] for b in shells])
    aspect, skew = corner_measures(mesh.nodes, corners)
    ortho = np.abs(np.einsum("ij,ij->i", mesh.ring_tangents, mesh.stringer_tangents))
    return {
        "aspect_ratio_max": float(aspect.max()),
        "aspect_ratio_mean": float(aspect.mean()),
        "skew_deg_max": float(skew.max()),
        "skew_deg_mean": float(skew.mean()),
        "orthogonality_max": float(ortho.max()),
    }
