"""A pressurised junction (issue 25): its loads and what its solution is checked against.

Loads (:func:`junction_step`), on the shell model of :mod:`.junction`: the internal pressure
p on every shell and, with ``capped`` ends, each open end's cap resultant p pi a^2 along the
axis' tangent out of the tube (a: the main's bore radius r - t / 2, on whose face CalculiX's
expanded shells take the pressure; a branch's mid-surface radius, that of the hole it cuts
in the main's shell), spread
over the end ring as consistent nodal forces (:func:`~tubecad.fem.loads.ring_forces`), the
six rigid-body motions held at three nodes of the main's start ring (3-2-1,
:func:`~tubecad.fem.loads.three_two_one`): pressure and caps are in equilibrium on the
joined surface, so the support takes (almost) no load. ``fixed``: every end ring held.

Checks (:func:`junction_checks`), at the nodes far from the junction: on each tube farther
than FAR sqrt(r t) from the saddle (a shell's bending boundary layer decays as
exp(-x / (0.78 sqrt(r t))): e^-5 at FAR = 4) and from its ring frames (made as beams: each
holds the wall in, a layer of its own), from where the axis' curvature changes (a
line meeting a bend: a layer of its own) and from the open ends (held, or carrying the caps and the support: CalculiX joins the
shells at the saddle by a knot and takes the pressure on a surface the caps do not balance
exactly; the support reacts the difference, 3.6 % of a cap's load measured on a d/D = 0.6
tee):

- the hoop stress along the rings against membrane theory (:func:`membrane_hoop`: p a / t
  on a straight piece, the torus' value on an arc; docs/MATH.md section 10) with a = r - t / 2, the radius of the face the pressure acts on (CalculiX
  expands a shell into a layer of solid elements and loads its inner face; the half ring's
  equilibrium then fixes the mean hoop stress at p (r - t / 2) / t: measured 24.54 against
  24.5, where the mid-surface's p r / t is 25): the largest relative difference at a node,
  and of a ring's mean (:func:`ring_means`), the ring's hoop force, which equilibrium fixes
  even where the ring ovalises (a free branch end lets the saddle's cos 2u ovalisation run
  along the whole branch: measured 1.4 % of p r / t on a d/D = 0.6 tee, unchanged by
  refining the mesh from 8 to 5 mm);
- the stress concentration at the saddle: the largest von Mises stress at the nodes within
  sqrt(R t) of the saddle over the main's p R / t (R, t: its mid-surface radius and wall),
  the stress CalculiX gives at the shell's reference nodes (``*EL FILE, OUTPUT=2D``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.fem.inp import Step
from tubecad.fem.junction import JunctionTube, radius_at, ring_in_order, smallest_distance, tube_index
from tubecad.fem.loads import ring_forces, three_two_one
from tubecad.fem.model import FEMesh

#: far from the junction: this many sqrt(r t) from the saddle (and a bend, and fixed ends)
FAR = 4.0
#: a steady axis: its (k1, k2) change by less than this over the radius between samples
STEADY = 1e-9
#: nodes of one ring: s equal to this fraction of the span's size
RING_MATCH = 1e-9
#: a ring's mean is taken over at least this many nodes, none more than pi / 8 apart
MIN_RING_NODES = 16
#: junction ends: capped (the caps' resultants, free of support) or fixed
JUNCTION_ENDS = ("capped", "fixed")


def _ends(mesh: FEMesh, tubes: Sequence[JunctionTube]) -> list[tuple[np.ndarray, JunctionTube, float, float]]:
    """(end ring nodes, tube, s of the end, outward sign along the tangent) of every open end."""
    out = [
        (mesh.node_sets["main_start"], tubes[0], tubes[0].surface.span[0], -1.0),
        (mesh.node_sets["main_end"], tubes[0], tubes[0].surface.span[1], 1.0),
    ]
    out += [(mesh.node_sets[f"{t.name}_end"], t, t.surface.span[1], 1.0) for t in tubes[1:]]
    return out


def junction_step(mesh: FEMesh, tubes: Sequence[JunctionTube], pressure: float, ends: str = "capped") -> Step:
    """The pressure step (module docstring); ``tubes``: the main first, as meshed."""
    if ends not in JUNCTION_ENDS:
        raise ParameterError(
            f"ends must be one of {', '.join(JUNCTION_ENDS)} for a junction, got {ends!r:.40}",
            key="ends",
        )
    if ends == "fixed":
        fixed = [(int(n), d) for ring, *_ in _ends(mesh, tubes) for n in ring for d in (1, 2, 3)]
        return Step(pressure, ends, tuple(fixed))
    order = 2 if mesh.blocks[0].element.startswith("S8") else 1
    loads: list[tuple[int, int, float]] = []
    for ring, tube, s, sign in _ends(mesh, tubes):
        tangent = tube.surface.axis.at(np.array([s])).t[0]
        # the main's caps balance the pressure on its bore face (r - t / 2); a branch's, the
        # hole its mid-surface cuts in the main's shell (r): measured, they leave the support least
        a = radius_at(tube.surface, s) - (0.5 * tube.thickness if tube is tubes[0] else 0.0)
        loads += ring_forces(mesh, ring_in_order(mesh, ring), sign * tangent, pressure * math.pi * a * a, order)
    held = three_two_one(mesh, ring_in_order(mesh, mesh.node_sets["main_start"]))
    return Step(pressure, ends, held, tuple(loads))


def von_mises(stress: np.ndarray) -> np.ndarray:
    """sqrt(3/2 s:s), s the deviator, per tensor (n, 3, 3)."""
    dev = stress - np.trace(stress, axis1=1, axis2=2)[:, None, None] * np.eye(3) / 3.0
    return np.sqrt(1.5 * np.einsum("nij,nij->n", dev, dev))


def junction_checks(
    mesh: FEMesh,
    tubes: Sequence[JunctionTube],
    stress: np.ndarray,
    ring_stress: np.ndarray,
    pressure: float,
) -> dict[str, Any]:
    """The membrane check per tube and the saddle's stress concentration (module docstring)."""
    saddle = mesh.nodes[mesh.node_sets["saddle"]]
    to_saddle = smallest_distance(mesh.nodes, saddle)
    owner = _owners(mesh, tubes)
    # a beam's node carries CalculiX's mean of the shell's and the expanded beam's stresses
    on_beams = np.zeros(len(mesh.nodes), dtype=bool)
    for block in mesh.blocks:
        if not block.shell:
            on_beams[block.connectivity.ravel()] = True
    out: dict[str, Any] = {"membrane": {}}
    for k, tube in enumerate(tubes):
        nodes = np.flatnonzero(owner == k)
        s = mesh.parameters[nodes, 1]
        reach = FAR * math.sqrt(tube.radius * tube.thickness)
        far = (to_saddle[nodes] > reach) & _steady_around(tube, s, reach) & ~on_beams[nodes]
        for ring in tube.stiffened[0]:  # a ring frame's beams hold the wall in: away from them too
            far &= np.abs(s - ring) > reach
        s0, s1 = tube.surface.span  # the ends: held, or loaded by the caps beside the support
        far &= (s - s0 > reach if k == 0 else True) & (s1 - s > reach)
        far_nodes = nodes[far & np.isfinite(ring_stress[nodes])]
        entry: dict[str, Any] = {"far_nodes": int(far_nodes.size), "far_from_saddle": reach}
        if far_nodes.size and tube.surface.constant_radius:
            expected = membrane_hoop(tube, mesh.nodes[far_nodes], mesh.parameters[far_nodes, 1], pressure)
            ratio = ring_stress[far_nodes] / expected
            means = ring_means(mesh.parameters[far_nodes], ratio)
            entry.update(
                hoop_expected_min=float(expected.min()),
                hoop_expected_max=float(expected.max()),
                hoop_min=float(ring_stress[far_nodes].min()),
                hoop_max=float(ring_stress[far_nodes].max()),
                hoop_max_relative_error=float(np.abs(ratio - 1.0).max()),
                whole_rings=int(len(means)),
                ring_mean_max_relative_error=float(np.abs(means - 1.0).max()) if len(means) else None,
            )
        out["membrane"][tube.name] = entry
    main = tubes[0]
    nominal = pressure * main.radius / main.thickness
    near = np.flatnonzero(to_saddle <= math.sqrt(main.radius * main.thickness))
    vm = von_mises(stress[near])
    peak = int(near[np.nanargmax(vm)])
    out["saddle"] = {
        "nodes": int(len(saddle)),
        "peak_von_mises": float(np.nanmax(vm)),
        "at": [float(x) for x in mesh.nodes[peak]],
        "nominal_hoop": nominal,
        "stress_concentration": float(np.nanmax(vm)) / nominal,
        "note": "von Mises stress at the shells' reference nodes (CalculiX OUTPUT=2D) over p R / t of the main",
    }
    return out


def ring_means(parameters: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The mean of ``values`` round each whole ring among the nodes (parameters (u, s): the
    nodes of one ring share s), by the trapezoidal rule over u (periodic): the ring's hoop
    force over its length, which the half ring's equilibrium fixes whatever the ring's
    ovalisation (a cos 2u term averages out)."""
    s = parameters[:, 1]
    scale = max(float(np.abs(s).max()), 1.0)
    keys = np.round(s / (RING_MATCH * scale)).astype(np.int64)
    out = []
    for key in np.unique(keys):
        rows = np.flatnonzero(keys == key)
        u = np.sort(np.mod(parameters[rows, 0], 2 * np.pi))
        gaps = np.diff(np.concatenate([u, u[:1] + 2 * np.pi]))
        if len(rows) < MIN_RING_NODES or gaps.max() > np.pi / 8:
            continue  # not a whole ring: cut by the opening, or too few nodes far from the saddle
        order = np.argsort(np.mod(parameters[rows, 0], 2 * np.pi))
        v = values[rows][order]
        out.append(float(np.sum(0.5 * (v + np.roll(v, -1)) * gaps) / (2 * np.pi)))
    return np.asarray(out)


def _owners(mesh: FEMesh, tubes: Sequence[JunctionTube]) -> np.ndarray:
    """Per node the index of the tube whose elements hold it first (the main's pad blocks are
    the main's; a node only a blend's elements hold: -1)."""
    names = [t.name for t in tubes]
    owner = np.full(len(mesh.nodes), -1, dtype=np.int64)
    for block in mesh.shell_blocks:
        k = tube_index(block.name, names)
        if k is None:  # a crotch blend's shells: no tube's
            continue
        used = np.unique(block.connectivity)
        owner[used[owner[used] < 0]] = k
    return owner


def membrane_hoop(tube: JunctionTube, points: np.ndarray, s: np.ndarray, pressure: float) -> np.ndarray:
    """Membrane theory's hoop stress at ``points`` (at rings ``s``) of a tube of constant
    radius whose axis bends with the curvature vector kappa there (a torus piece; docs/MATH.md
    section 10): p a (2 - q) / (2 t (1 - q)), q = a kappa . e, e the unit radius from the axis
    to the point and a = r - t / 2 the radius the pressure acts on (q = 0: p a / t; on a
    torus q = -a sin(theta) / R, the section's (2R + a sin theta) / (2 (R + a sin theta)))."""
    a = radius_at(tube.surface, float(s[0])) - 0.5 * tube.thickness
    frame = tube.surface.axis.at(s)
    kappa = frame.k1[:, None] * frame.r1 + frame.k2[:, None] * frame.r2
    e = points - tube.surface.axis.position(s)
    e /= np.linalg.norm(e, axis=1, keepdims=True)
    q = a * np.einsum("nk,nk->n", kappa, e)
    return pressure * a * (2.0 - q) / (2.0 * tube.thickness * (1.0 - q))


def _steady_around(tube: JunctionTube, s: np.ndarray, reach: float) -> np.ndarray:
    """Whether the axis' curvature (k1, k2) in its rotation-minimising frame stays the same
    (to STEADY / r) within ``reach`` of each s: a straight piece or a circular arc, away from
    where they meet (sampled; a helix, whose frame turns, is not steady)."""
    s0, s1 = tube.surface.span
    table = np.linspace(s0, s1, 2049)
    a = tube.surface.axis.at(table)
    development = np.column_stack([a.k1, a.k2])  # the curvature in the rotation-minimising frame
    change = np.linalg.norm(np.diff(development, axis=0), axis=1) * tube.radius > STEADY
    if not change.any():
        return np.ones(len(s), dtype=bool)
    where = 0.5 * (table[:-1] + table[1:])[change]
    step = (s1 - s0) / 2048
    return smallest_distance(s[:, None], where[:, None]) > reach + step
