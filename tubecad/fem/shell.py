"""The wall as a finite-element model on its curvature-line net (issue 14).

Nodes are points S(angle, s) of the exact surface at the lattice of :mod:`.grid`, with the
exact unit normals N = S_u x S_s / |S_u x S_s| (the surface's own ``normal``) and the
principal directions S_u / |S_u| (along the rings) and S_s / |S_s| (along the stringers).
Element edges lie on the layout's rings and stringers (curvature lines, F = M = 0), so the
elements are right-angled up to the chord's turn across one element.

The reference surface is the wall's mid-surface (r + (d_in + d_out) / 2, the section's
middle at the nodes), its inner or outer face (the section offset into the wall), or both
faces as two meshes; the offsets of a tube are tubes and of a canal surface canal surfaces
with the same curvature-line net, so all share the lattice.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from tubecad.brep.layout import NetLayout
from tubecad.brep.wall import wall_offsets
from tubecad.core.errors import ParameterError
from tubecad.fem.beams import beam_directions, clipped, profile_rectangles, section_centre
from tubecad.fem.grid import ParameterGrid, element_counts, lattice_ids, parameter_grid
from tubecad.fem.model import BeamSection, ElementBlock, FEMesh, ShellSection
from tubecad.fem.quality import element_quality
from tubecad.fem.settings import DEFAULT_SIZE_PER_RADIUS, MeshSettings
from tubecad.stiffeners.profiles import SIDES, Profile
from tubecad.surface import CanalSurface, CurvatureLineTube


@dataclass(frozen=True)
class StiffenerPlan:
    """Which layout rings and stringers carry stiffeners, with what profile, on which side."""

    rings: Sequence[int] = ()
    stringers: Sequence[int] = ()
    profile: Profile | None = None
    side: str = "outside"


def _smallest_radius(surface) -> float:
    return float(surface.radius_law.min_radius)  # a tube's law is its constant radius


def shell_mesh(
    surface: CurvatureLineTube | CanalSurface,
    layout: NetLayout,
    *,
    thickness: float | None = None,
    wall_side: str = "centered",
    stiffeners: StiffenerPlan | None = None,
    seams: Sequence[int] | None = None,
    panel_rings: Sequence[int] | None = None,
    settings: MeshSettings | None = None,
    length_unit: str = "mm",
) -> FEMesh:
    """The wall of ``thickness`` placed ``wall_side`` of ``surface`` (no thickness: the
    surface alone, for a surface mesh) as shells on the layout's net, refined to
    ``settings``' sizes, with ``stiffeners`` as beams, and sets for the panels between the
    seam stringers ``seams`` (default all) and the rings ``panel_rings`` (default all)."""
    settings = settings or MeshSettings()
    closed = bool(surface.axis.closed)
    if thickness is None:
        if settings.surface != "mid":
            raise ParameterError(
                f"surface = {settings.surface!r} needs a wall, a thickness to offset into; "
                "without one only the surface itself is meshed (surface = 'mid')",
                key="surface",
            )
        d_in = d_out = 0.0
    else:
        d_in, d_out = wall_offsets(thickness, wall_side)
    #: per reference surface: (element set, offset d from the surface, shell offset or None: no section)
    refs: dict[str, list[tuple[str, float, float | None]]] = {
        "mid": [("wall", 0.5 * (d_in + d_out), 0.0)],
        "inner": [("wall", d_in, -0.5)],
        "outer": [("wall", d_out, 0.5)],
        "both": [("wall_inner", d_in, None), ("wall_outer", d_out, None)],
    }
    references = refs[settings.surface]
    radius = _smallest_radius(surface) + d_in
    size_along = settings.size_along or DEFAULT_SIZE_PER_RADIUS * radius
    size_around = settings.size_around or DEFAULT_SIZE_PER_RADIUS * radius
    offset_surface = {d: (surface if d == 0 else surface.offset(d, allow_irregular=True)) for _, d, _ in references}
    plan = stiffeners if (stiffeners is not None and settings.beams and stiffeners.profile is not None) else None
    rings, strs = _stiffened(plan, layout, closed)

    first = offset_surface[references[0][1]]
    closing = None
    if closed:
        closing = first.closing_angle  # a tube's: u + h; a canal surface's: its Moebius map, then + h
    counts = element_counts(first, layout.s_rings, layout.stringers_deg, size_along, size_around)
    beams = _beam_estimate(plan, counts, rings, strs)
    total = counts[0] * counts[1] * len(references) + beams
    if total > settings.max_elements:
        raise ParameterError(
            f"size_along = {size_along:.6g}, size_around = {size_around:.6g} give {total:,} "
            f"elements ({counts[0]} along x {counts[1]} around x {len(references)} surface(s)"
            f"{f' + {beams:,} beams' if beams else ''}), more than max_elements = "
            f"{settings.max_elements:,}: use a larger size or raise max_elements",
            key="size",
        )
    grid = parameter_grid(first, layout.s_rings, layout.stringers_deg, settings.order, size_along, size_around, closing)

    ids = lattice_ids(grid)
    per_surface = int(ids.max()) + 1
    nodes: list[np.ndarray] = []
    normals: list[np.ndarray] = []
    t_ring: list[np.ndarray] = []
    t_str: list[np.ndarray] = []
    params: list[np.ndarray] = []
    for _, d, _ in references:
        X, N, Tu, Ts = _lattice_geometry(offset_surface[d], grid)
        keep = np.zeros(per_surface, dtype=np.int64)
        rows, cols = np.nonzero(ids[: len(grid.s) - (1 if closed else 0)] >= 0)
        keep[ids[rows, cols]] = rows * len(grid.angles) + cols
        for out, values in ((nodes, X), (normals, N), (t_ring, Tu), (t_str, Ts)):
            out.append(values.reshape(-1, values.shape[-1])[keep])
        uu, ss = np.meshgrid(grid.angles, grid.s)
        params.append(np.column_stack([uu.ravel(), ss.ravel()])[keep])

    blocks: list[ElementBlock] = []
    shell_sections: list[ShellSection] = []
    element_sets: dict[str, np.ndarray] = {}
    cells = _shell_cells(ids, grid.order)
    for k, (name, _, offset) in enumerate(references):
        conn = cells + k * per_surface
        conn = _oriented(conn, np.concatenate(nodes), np.concatenate(normals), grid.order)
        blocks.append(ElementBlock(name, settings.element, conn, sum(len(b.connectivity) for b in blocks)))
        if offset is not None and thickness is not None:
            shell_sections.append(ShellSection(name, float(thickness), offset))
        element_sets[name] = blocks[-1].ids
    node_sets = _node_sets(ids, grid, layout, closed, per_surface, len(references))
    element_sets.update(_panel_sets(blocks, grid, layout, seams, panel_rings))

    beam_sections: list[BeamSection] = []
    if plan is not None:
        base_d = d_out if plan.side == "outside" else d_in
        k = 0 if len(references) == 1 else (1 if plan.side == "outside" else 0)
        ref_name, ref_d, _ = references[k]
        base = offset_surface[ref_d]
        _add_beams(
            blocks,
            beam_sections,
            element_sets,
            plan,
            rings,
            strs,
            ids + k * per_surface,
            grid,
            base,
            base_d - ref_d,
            settings.beam_type,
            layout,
            closed,
        )

    mesh = FEMesh(
        np.concatenate(nodes),
        np.concatenate(normals),
        np.concatenate(t_ring),
        np.concatenate(t_str),
        np.concatenate(params),
        blocks,
        shell_sections,
        beam_sections,
        node_sets,
        element_sets,
        length_unit,
        closed,
    )
    mesh.info.update(
        {
            "surface": settings.surface,
            "element": settings.element,
            "beam": settings.beam_type if plan is not None else None,
            "size_along": size_along,
            "size_around": size_around,
            "elements_along": (len(grid.s) - 1) // grid.order,
            "elements_around": len(grid.angles) // grid.order,
            "thickness": thickness,
            "reference_offsets": [d for _, d, _ in references],
            "quality": element_quality(mesh),
        }
    )
    return mesh


def _stiffened(plan: StiffenerPlan | None, layout: NetLayout, closed: bool) -> tuple[list[int], list[int]]:
    if plan is None:
        return [], []
    n_r, n_s = len(layout.s_rings), len(layout.stringers_deg)
    for key, chosen, count in (("rings", plan.rings, n_r), ("stringers", plan.stringers, n_s)):
        bad = [i for i in chosen if not (isinstance(i, (int, np.integer)) and 0 <= i < count)]
        if bad:
            raise ParameterError(
                f"the stiffeners' {key} must be indices in [0, {count - 1}], got {bad}", key=f"stiffeners.{key}"
            )
    if plan.side not in SIDES:
        raise ParameterError(
            f"the stiffeners' side must be one of {', '.join(SIDES)}, got {plan.side!r}", key="stiffeners.side"
        )
    rings = list(dict.fromkeys(0 if closed and i == n_r - 1 else int(i) for i in plan.rings))
    return rings, list(dict.fromkeys(int(j) for j in plan.stringers))


def _beam_estimate(plan, counts: tuple[int, int], rings, strs) -> int:
    if plan is None:
        return 0
    parts = len(profile_rectangles(plan.profile))
    return parts * (len(rings) * counts[1] + len(strs) * counts[0])


def _lattice_geometry(surface, grid: ParameterGrid) -> tuple[np.ndarray, ...]:
    """Points, unit normals and unit ring and stringer tangents on the lattice (rows s,
    columns angles). On a tube they are the frame's own vectors, the axis evaluated once per
    row: N = e = cos u r1 + sin u r2, S_u / |S_u| = e_u = -sin u r1 + cos u r2 and
    S_s / |S_s| = sign(1 - rho kappa_u) t; on a canal surface, from its derivatives."""
    u, s = grid.angles[None, :], grid.s[:, None]
    unit = lambda v: v / np.linalg.norm(v, axis=-1, keepdims=True)  # noqa: E731
    if surface.constant_radius:  # the tube's fast path
        t, r1, r2 = (v[:, None, :] for v in surface.axis.rotation_minimising_frame(grid.s))
        k1, k2 = surface.axis.normal_development(grid.s)
        cu, su = np.cos(grid.angles)[None, :, None], np.sin(grid.angles)[None, :, None]
        speed = 1.0 - surface.radius_law.value * (k1[:, None] * cu[..., 0] + k2[:, None] * su[..., 0])
        return (
            surface.points(u, s),
            unit(cu * r1 + su * r2),
            unit(cu * r2 - su * r1),
            np.sign(speed)[..., None] * np.broadcast_to(unit(t), speed.shape + (3,)),
        )
    d = surface.derivatives(u, s)
    return surface.points(u, s), unit(surface.normal(u, s)), unit(d.S_u), unit(d.S_s)


def _shell_cells(ids: np.ndarray, p: int) -> np.ndarray:
    """Connectivity of the shells on the lattice ``ids`` (module docstring of .model)."""
    rows, cols = ids.shape
    i0 = np.arange(0, rows - 1, p)[:, None]
    j0 = np.arange(0, cols, p)[None, :]

    def at(i, j):
        shape = (len(i0), j0.shape[1])
        return ids[np.broadcast_to(i, shape), np.broadcast_to(j, shape) % cols]

    if p == 1:
        corners = [at(i0, j0), at(i0, j0 + 1), at(i0 + 1, j0 + 1), at(i0 + 1, j0)]
        return np.stack(corners, axis=-1).reshape(-1, 4)
    corners = [at(i0, j0), at(i0, j0 + 2), at(i0 + 2, j0 + 2), at(i0 + 2, j0)]
    mids = [at(i0, j0 + 1), at(i0 + 1, j0 + 2), at(i0 + 2, j0 + 1), at(i0 + 1, j0)]
    return np.stack(corners + mids, axis=-1).reshape(-1, 8)


def _oriented(conn: np.ndarray, nodes: np.ndarray, normals: np.ndarray, p: int) -> np.ndarray:
    """``conn`` ordered so that the corners turn counter-clockwise about the outward normal."""
    a, b, d = nodes[conn[0, 0]], nodes[conn[0, 1]], nodes[conn[0, 3]]
    if np.cross(b - a, d - a) @ normals[conn[0, 0]] >= 0:
        return conn
    order = [0, 3, 2, 1] if p == 1 else [0, 3, 2, 1, 7, 6, 5, 4]
    return conn[:, order]


def _node_sets(
    ids: np.ndarray, grid: ParameterGrid, layout: NetLayout, closed: bool, per_surface: int, surfaces: int
) -> dict[str, np.ndarray]:
    """ring_03, stringer_05 (the nodes on each layout line), start_ring and end_ring (open
    axes), wall (all): on every meshed surface."""
    every = lambda a: np.unique(np.concatenate([a + k * per_surface for k in range(surfaces)]))  # noqa: E731
    sets = {"wall": np.arange(per_surface * surfaces)}
    count = len(layout.s_rings) - (1 if closed else 0)
    for i in range(count):
        sets[f"ring_{i:02d}"] = every(ids[grid.ring_rows[i]])
    for j, c in enumerate(grid.stringer_columns):
        column = ids[:, c]
        sets[f"stringer_{j:02d}"] = every(column[column >= 0])
    if not closed:
        sets["start_ring"], sets["end_ring"] = sets["ring_00"], sets[f"ring_{count - 1:02d}"]
    return sets


def _panel_sets(
    blocks: list[ElementBlock],
    grid: ParameterGrid,
    layout: NetLayout,
    seams: Sequence[int] | None,
    panel_rings: Sequence[int] | None,
) -> dict[str, np.ndarray]:
    """panel_rI_sJ: the shells between rings I, I+1 of ``panel_rings`` and seams J, J+1
    (counter-clockwise from the smallest seam angle), the names of tubecad's panels."""
    n_r, n_s = len(layout.s_rings), len(layout.stringers_deg)
    seams = list(range(n_s)) if seams is None else list(seams)
    rings = sorted(set(range(n_r) if panel_rings is None else panel_rings) | {0, n_r - 1})
    if not seams or any(not 0 <= j < n_s for j in seams):
        raise ParameterError(f"seams must be stringer indices in [0, {n_s - 1}], got {seams}", key="seams")
    if any(not 0 <= i < n_r for i in rings):
        raise ParameterError(f"panel_rings must be ring indices in [0, {n_r - 1}], got {rings}", key="panel_rings")
    p = grid.order
    cols = len(grid.angles) // p
    starts = sorted(grid.stringer_columns[j] // p for j in set(seams))
    bays = list(zip(starts, starts[1:] + [starts[0] + cols]))
    sets = {}
    for i, (ia, ib) in enumerate(zip(rings, rings[1:])):
        r = np.arange(grid.ring_rows[ia] // p, grid.ring_rows[ib] // p)
        for j, (a, b) in enumerate(bays):
            c = np.arange(a, b) % cols
            cells = (r[:, None] * cols + c[None, :]).ravel()
            sets[f"panel_r{i}_s{j}"] = np.concatenate([blk.first + cells for blk in blocks if blk.shell])
    return sets


def _add_beams(
    blocks,
    beam_sections,
    element_sets,
    plan: StiffenerPlan,
    rings,
    strs,
    ids: np.ndarray,
    grid: ParameterGrid,
    base,
    base_offset: float,
    beam_type: str,
    layout: NetLayout,
    closed: bool,
) -> None:
    """Beam blocks of the stiffened rings and stringers on the lattice ``ids`` (:mod:`.beams`)."""
    profile = plan.profile
    assert profile is not None  # (a plan with beams has a profile: see shell_mesh)
    p = grid.order
    rows, cols = ids.shape
    span = layout.s_rings[0], layout.s_rings[-1]
    lines = []
    for i in rings:
        r = grid.ring_rows[i]
        j = np.arange(0, cols, p)
        conn = np.stack([ids[r, (j + q) % cols] for q in range(p + 1)], axis=-1)
        a_mid, s_mid = _mid_angle(grid, j), np.full(len(j), grid.s[r])
        low, high = (-math.inf if closed else span[0] - grid.s[r]), (math.inf if closed else span[1] - grid.s[r])
        lines.append((f"ring_{i:02d}", "ring", conn, a_mid, s_mid, (low, high)))
    for j in strs:
        c = grid.stringer_columns[j]
        i = np.arange(0, rows - 1, p)
        conn = np.stack([ids[i + q, c] for q in range(p + 1)], axis=-1)
        s_mid = 0.5 * (grid.s[i] + grid.s[i + p])
        lines.append(
            (f"stringer_{j:02d}", "stringer", conn, np.full(len(i), grid.angles[c]), s_mid, (-math.inf, math.inf))
        )
    unit = lambda v: v / np.linalg.norm(v, axis=-1, keepdims=True)  # noqa: E731
    for name, kind, conn, a_mid, s_mid, (low, high) in lines:
        d = base.derivatives(a_mid, s_mid)
        tangent, across = (unit(d.S_u), unit(d.S_s)) if kind == "ring" else (unit(d.S_s), unit(d.S_u))
        n1 = beam_directions(base.normal(a_mid, s_mid), tangent)
        across = float(np.sign(np.einsum("ij,ij->i", across, n1).mean()))  # W . n1: the profile's w along n1
        members = []
        for rect in profile_rectangles(profile):
            part = clipped(rect, low, high) if kind == "ring" else rect
            if part is None:
                continue
            block = ElementBlock(f"{name}_{part.name}", beam_type, conn, sum(len(b.connectivity) for b in blocks))
            blocks.append(block)
            beam_sections.append(
                BeamSection(
                    block.name,
                    name,
                    part.w1 - part.w0,
                    part.h1 - part.h0,
                    section_centre(part, base_offset, plan.side, across),
                    block.ids,
                    n1,
                )
            )
            members.append(block.ids)
        element_sets[name] = np.concatenate(members)


def _mid_angle(grid: ParameterGrid, j: np.ndarray) -> np.ndarray:
    """The angle halfway between lattice columns j and j + order (across the 2 pi wrap)."""
    cols = len(grid.angles)
    a, b = grid.angles[j], grid.angles[(j + grid.order) % cols]
    b = np.where(b <= a, b + 2 * math.pi, b)
    return 0.5 * (a + b)
