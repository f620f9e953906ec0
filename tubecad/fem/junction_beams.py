"""A junction's stiffeners as beam elements on its shell model (issue 25).

Each stiffener stands on a ring (s = s_i) or a stringer (u = u_j) of its tube, and the shell
model keeps those lines as lines of elements wherever they lie
(:attr:`~tubecad.fem.junction.JunctionTube.stiffened`), so its beams share the shells' nodes:
an element side (two corners, and the middle node of a quadratic element) is the stiffener's
where all its nodes lie on the line, on the stiffener's own tube. The opening is a hole of the
model, so the beams end where the shells do, on the saddle; a stiffener stops on a pad's edge,
so the sides inside a pad are left out. Each beam is oriented along +u (a ring) or +s (a
stringer), and its profile's rectangles are sections offset from the nodes as on a plain wall
(:mod:`tubecad.fem.beams`): the wall face the stiffener stands on lies half the wall's thickness
from the mid-surface nodes, outside or inside.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from tubecad.fem.beams import beam_directions, clipped, profile_rectangles, section_centre
from tubecad.fem.junction import JunctionTube, PadRegion, tube_index
from tubecad.fem.model import BeamSection, ElementBlock, FEMesh
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.stiffeners.profiles import Profile

#: a node lies on a ring (s = s_i) or a stringer (u = u_j) within this, relative to the tube's
#: radius (the mesh's nodes are gmsh's points of the model's edges, fitted to ~1e-8)
ON_LINE = 1e-6


@dataclass(frozen=True)
class StiffenerLine:
    """A stiffener of the junction: ``name`` (``ring_03``, ``branch_stringer_02``), the index
    of its ``tube`` among the model's tubes, ``kind`` (ring, stringer) and ``value`` (the
    ring's s or the stringer's angle in degrees)."""

    name: str
    tube: int
    kind: str
    value: float


def add_junction_beams(
    mesh: FEMesh,
    tubes: Sequence[JunctionTube],
    pads: Sequence[PadRegion],
    lines: Sequence[StiffenerLine],
    profile: Profile,
    side: str,
    beam_type: str,
) -> dict[str, float]:
    """Add to ``mesh`` the beam blocks (``ring_03_web``, ``ring_03_flange``...), their sections
    and an element set per stiffener (see the module). Returns each stiffener's beam length."""
    names = [t.name for t in tubes]
    first = mesh.element_count
    lengths: dict[str, float] = {}
    for line in lines:
        tube = tubes[line.tube]
        sides = _sides_on(mesh, names, tube, line, pads)
        if not len(sides):
            continue
        points = mesh.nodes[sides]
        c = surface_coordinates(tube.surface, points.reshape(-1, 3))
        u = c.u.reshape(sides.shape)[:, [0, -1]]
        s = c.s.reshape(sides.shape)[:, [0, -1]]
        u_mid = u[:, 0] + 0.5 * np.angle(np.exp(1j * (u[:, 1] - u[:, 0])))
        s_mid = s.mean(axis=1)
        d = tube.surface.derivatives(u_mid, s_mid)
        along = d.S_u if line.kind == "ring" else d.S_s
        chord = points[:, -1] - points[:, 0]
        backwards = np.einsum("ij,ij->i", chord, along) < 0
        sides[backwards] = sides[backwards][:, ::-1]
        chord[backwards] *= -1.0
        tangent = chord / np.linalg.norm(chord, axis=1, keepdims=True)
        normal = tube.surface.normal(u_mid, s_mid)
        n1 = beam_directions(normal, tangent)
        across_dir = d.S_s if line.kind == "ring" else d.S_u
        across = float(np.sign(np.einsum("ij,ij->i", across_dir, n1).mean()))  # the profile's w along n1
        base_offset = (0.5 if side == "outside" else -0.5) * tube.thickness  # the wall face from the mid-surface
        s0, s1 = tube.surface.span
        low, high = (s0 - line.value, s1 - line.value) if line.kind == "ring" else (-math.inf, math.inf)
        conn = sides  # B31: the ends; B32: end, middle, end
        members = []
        for rect in profile_rectangles(profile):
            part = clipped(rect, low, high) if line.kind == "ring" else rect
            if part is None:
                continue
            block = ElementBlock(f"{line.name}_{part.name}", beam_type, conn, first)
            first += len(conn)
            mesh.blocks.append(block)
            mesh.beam_sections.append(
                BeamSection(
                    block.name,
                    line.name,
                    part.w1 - part.w0,
                    part.h1 - part.h0,
                    section_centre(part, base_offset, side, across),
                    block.ids,
                    n1,
                )
            )
            members.append(block.ids)
        mesh.element_sets[line.name] = np.concatenate(members)
        lengths[line.name] = float(np.linalg.norm(np.diff(points, axis=1), axis=2).sum())
    return lengths


def _sides_on(
    mesh: FEMesh, names: list[str], tube: JunctionTube, line: StiffenerLine, pads: Sequence[PadRegion]
) -> np.ndarray:
    """The distinct element sides of ``tube``'s shells on ``line`` outside every pad: (m, 2)
    corner pairs, or (m, 3) (corner, middle node, corner) for quadratic elements."""
    found: dict[tuple[int, int], tuple[int, ...]] = {}
    for block in mesh.shell_blocks:
        k = tube_index(block.name, names)
        if k is None or names[k] != tube.name or (line.tube == 0 and _is_pad(block.name, pads)):
            continue
        corners = block.corners
        conn = block.connectivity
        nodes = np.unique(conn)
        c = surface_coordinates(tube.surface, mesh.nodes[nodes])
        if line.kind == "ring":
            on = np.abs(c.s - line.value) <= ON_LINE * tube.radius
        else:
            on = np.abs(np.angle(np.exp(1j * (c.u - math.radians(line.value))))) * tube.radius <= ON_LINE * tube.radius
        on_line = np.zeros(len(mesh.nodes), dtype=bool)
        on_line[nodes[on]] = True
        for k in range(corners):
            a, b = conn[:, k], conn[:, (k + 1) % corners]
            side = [a, b] if conn.shape[1] == corners else [a, conn[:, corners + k], b]  # end, middle, end
            hit = np.all([on_line[x] for x in side], axis=0)
            for row in np.flatnonzero(hit):
                key = (int(min(a[row], b[row])), int(max(a[row], b[row])))
                found.setdefault(key, tuple(int(x[row]) for x in side))
    if not found:
        return np.zeros((0, 2), dtype=np.int64)
    sides = np.array(list(found.values()), dtype=np.int64)
    if line.tube == 0 and pads:  # a stiffener stops on a pad's edge: its sides inside a pad are left out
        c = surface_coordinates(tube.surface, mesh.nodes[sides].mean(axis=1))
        inside = np.zeros(len(sides), dtype=bool)
        for pad in pads:
            inside |= pad.holds(c.u, c.s)
        sides = sides[~inside]
    return sides


def _is_pad(block: str, pads: Sequence[PadRegion]) -> bool:
    return any(block.removesuffix("_tri") == pad.name for pad in pads)
