"""Boundary conditions and loads of the pressure analysis (:class:`.inp.Step`).

- ``fixed``: both end rings held (every displacement 0);
- ``capped``: the end caps' resultants p pi a^2 (a: the ring's circle radius on the
  reference surface) as consistent nodal forces along the axis tangent, outward at both
  ends, and the six rigid-body motions held at three nodes of ring 0 (3-2-1): a statically
  determinate support, so a self-equilibrated load leaves no reactions;
- ``free``: the 3-2-1 support alone (a closed tube: the pressure on a closed surface is
  self-equilibrated).

Consistent nodal forces of a uniform line load q on an edge of length l: q l / 2 at each
end (linear); q l / 6 at the ends and 2 q l / 3 at the middle (quadratic).
"""

from __future__ import annotations

import math

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.fem.inp import Step
from tubecad.fem.model import FEMesh

ENDS = ("fixed", "capped", "free")


def three_two_one(mesh: FEMesh, ring: np.ndarray) -> tuple[tuple[int, int], ...]:
    """Six held dofs (node, dof 1..3) at three nodes of ``ring`` a quarter and half a turn
    apart: all three at A, at B (opposite) the two global directions least along AB, at C
    the global direction nearest the normal of the plane ABC."""
    order = ring[np.argsort(mesh.parameters[ring, 0])]
    a, b, c = order[0], order[len(order) // 2], order[len(order) // 4]
    ab = mesh.nodes[b] - mesh.nodes[a]
    b_dofs = np.argsort(np.abs(ab))[:2] + 1
    normal = np.cross(ab, mesh.nodes[c] - mesh.nodes[a])
    c_dof = int(np.argmax(np.abs(normal))) + 1
    return tuple(
        [(int(a), 1), (int(a), 2), (int(a), 3), (int(b), int(b_dofs[0])), (int(b), int(b_dofs[1])), (int(c), c_dof)]
    )


def ring_forces(
    mesh: FEMesh, ring_block_nodes: np.ndarray, direction: np.ndarray, total: float, order: int
) -> list[tuple[int, int, float]]:
    """``total`` spread along a closed ring of nodes (in order round it, mid-side nodes
    included for order 2) as consistent nodal forces along ``direction``."""
    nodes = mesh.nodes[ring_block_nodes]
    loop = np.concatenate([ring_block_nodes, ring_block_nodes[:1]])
    forces = np.zeros(len(ring_block_nodes))
    step = order
    pieces = []
    for k in range(0, len(ring_block_nodes), step):
        ends = loop[[k, k + step]]
        pieces.append(np.linalg.norm(mesh.nodes[ends[1]] - mesh.nodes[ends[0]]))
    lengths = np.asarray(pieces)
    q = total / lengths.sum()
    n = len(ring_block_nodes)
    for e, k in enumerate(range(0, n, step)):
        if order == 1:
            forces[k] += q * lengths[e] / 2
            forces[(k + 1) % n] += q * lengths[e] / 2
        else:
            forces[k] += q * lengths[e] / 6
            forces[k + 1] += 2 * q * lengths[e] / 3
            forces[(k + 2) % n] += q * lengths[e] / 6
    del nodes
    return [
        (int(node), d + 1, float(f * direction[d]))
        for node, f in zip(ring_block_nodes, forces)
        for d in range(3)
        if abs(direction[d]) > 1e-15
    ]


def pressure_step(
    mesh: FEMesh, pressure: float, ends: str, surface, lattice_rings: tuple[np.ndarray, np.ndarray] | None = None
) -> Step:
    """The step for internal ``pressure`` with the ``ends`` condition (module docstring);
    ``surface``: the reference surface (for the axis tangents and circle radii at the ends);
    ``lattice_rings``: the end rings' nodes in order round them."""
    if ends not in ENDS:
        raise ParameterError(f"ends must be one of {', '.join(ENDS)}, got {ends!r:.40}", key="ends")
    if not (isinstance(pressure, (int, float)) and math.isfinite(pressure)):
        raise ParameterError(f"pressure must be a finite number, got {pressure!r:.40}", key="pressure")
    if mesh.closed and ends != "free":
        raise ParameterError(f"ends = {ends!r} needs end rings; a closed tube has none: use ends = 'free'", key="ends")
    if ends == "fixed":
        fixed = [
            (int(n), d)
            for n in np.concatenate([mesh.node_sets["start_ring"], mesh.node_sets["end_ring"]])
            for d in (1, 2, 3)
        ]
        return Step(pressure, ends, tuple(fixed))
    held = three_two_one(mesh, mesh.node_sets["ring_00"])
    loads: list[tuple[int, int, float]] = []
    if ends == "capped":
        if lattice_rings is None:
            raise ParameterError("ends = 'capped' needs the end rings' nodes (lattice_rings)", key="lattice_rings")
        s0, s1 = surface.span
        order = 2 if mesh.blocks[0].element.startswith("S8") else 1
        for s, ring, sign in ((s0, lattice_rings[0], -1.0), (s1, lattice_rings[1], 1.0)):
            t = surface.axis.at(np.array([s])).t[0]
            a = float(
                np.mean(np.linalg.norm(np.cross(mesh.nodes[ring] - surface.axis.position(np.array([s]))[0], t), axis=1))
            )
            loads += ring_forces(mesh, ring, sign * t, pressure * math.pi * a * a, order)
    return Step(pressure, ends, held, tuple(loads))
