"""A junction meshed for analysis (:class:`~tubecad.design.shell.JunctionShellModel`): the
main and branch walls' mid-surfaces joined on their saddle
(:func:`tubecad.fem.junction.junction_shell_mesh`), the pads as thicker shells, the
stiffeners as beams snapped to the pads' edges (:mod:`tubecad.fem.junction_beams`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from tubecad.design.shell import JunctionShellModel
from tubecad.design.stages import stage

if TYPE_CHECKING:
    from tubecad.design.model import BranchDesign
    from tubecad.design.wall import WallDesign
    from tubecad.fem.junction import JunctionTube, PadRegion
    from tubecad.fem.junction_beams import StiffenerLine
    from tubecad.fem.settings import MeshSettings


def junction_shell_model(
    main: WallDesign, branches: Sequence[BranchDesign], settings: MeshSettings
) -> JunctionShellModel:
    """The junction of the ``main`` wall and its ``branches`` meshed with ``settings``: the
    main and branch mid-surfaces joined on their saddle, the pads, and the stiffeners as beams unless ``settings.beams`` is off
    (:mod:`tubecad.fem.junction_beams`)."""
    from tubecad.fem.junction import junction_mesh_size, junction_shell_mesh
    from tubecad.fem.junction_beams import add_junction_beams

    tubes, pads = junction_tubes(main, branches)
    chosen = main.stiffeners
    lines = stiffener_lines(main, branches, tubes) if settings.beams and chosen is not None else []
    lines, moved = snapped_to_pads(lines, tubes[0], pads, 0.5 * junction_mesh_size(settings, tubes))
    for k in range(len(tubes)):
        rings = tuple(line.value for line in lines if line.tube == k and line.kind == "ring")
        stringers = tuple(line.value for line in lines if line.tube == k and line.kind == "stringer")
        tubes[k] = replace(tubes[k], stiffened=(rings, stringers))
    with stage("mesh"):
        mesh = junction_shell_mesh(
            tubes[0],
            tubes[1:],
            pads=pads,
            settings=settings,
            tolerance=main.tolerance,
            length_unit=main.length_unit,
        )
    if lines and chosen is not None:
        with stage("stiffeners"):
            lengths = add_junction_beams(mesh, tubes, pads, lines, chosen.profile, chosen.side, settings.beam_type)
        mesh.info["beams"] = lengths
        mesh.info["beams_moved_to_pad_edge"] = moved
    return JunctionShellModel(mesh, tubes, pads)


def junction_tubes(main: WallDesign, branches: Sequence[BranchDesign]) -> tuple[list[JunctionTube], list[PadRegion]]:
    """The main tube and the branches as the shell model's tubes (each wall's mid-surface,
    thickness and net) and the pads' regions on the main (from the outer saddle, as the
    built pad: :func:`tubecad.stiffeners.pad.pad_bounds`)."""
    from tubecad.fem.junction import PadRegion, mid_surface_tubes
    from tubecad.junctions import BranchWall
    from tubecad.junctions.saddle import saddle_curve
    from tubecad.stiffeners.pad import pad_bounds, pad_name

    assert main.wall is not None  # a junction joins walls (JunctionDesign's contract)
    walls = [BranchWall(b.surface, b.wall.thickness, b.wall.side, b.layout, blend=b.blend) for b in branches]
    with stage("branches"):
        tubes = mid_surface_tubes(main.surface, main.wall.thickness, main.layout, walls, side=main.wall.side)
        outer = main.surface.offset(main.wall.offsets()[1])
    pads = []
    for k, (branch, wall) in enumerate(zip(branches, walls)):
        if branch.pad is not None:
            with stage("pads", k):
                saddle = saddle_curve(outer, wall.surface.offset(wall.offsets()[1]))
                s_range, angles = pad_bounds(outer, saddle, branch.pad.width)
            pads.append(PadRegion(pad_name(k, len(walls)), s_range, angles, branch.pad.thickness))
    return tubes, pads


def stiffener_lines(
    main: WallDesign, branches: Sequence[BranchDesign], tubes: Sequence[JunctionTube]
) -> list[StiffenerLine]:
    """The junction's stiffeners as lines of its shell model's tubes: the main's (its
    ``stiffeners``' rings and stringers) and each stiffened branch's, named as their solids
    (``ring_03``, ``branch_stringer_02``, ``branch1_ring_00``)."""
    from tubecad.fem.junction_beams import StiffenerLine

    chosen = main.stiffeners
    if chosen is None:
        return []
    layout = tubes[0].layout
    lines = [StiffenerLine(f"ring_{i:02d}", 0, "ring", float(layout.s_rings[i])) for i in chosen.rings]
    lines += [
        StiffenerLine(f"stringer_{j:02d}", 0, "stringer", float(layout.stringers_deg[j])) for j in chosen.stringers
    ]
    for k, branch in enumerate(branches):
        if not branch.stiffened:
            continue
        net, prefix = tubes[k + 1].layout, "branch" if len(branches) == 1 else f"branch{k}"
        lines += [
            StiffenerLine(f"{prefix}_ring_{i:02d}", k + 1, "ring", float(net.s_rings[i]))
            for i in branch.stiffener_rings
        ]
        lines += [
            StiffenerLine(f"{prefix}_stringer_{j:02d}", k + 1, "stringer", float(net.stringers_deg[j]))
            for j in branch.stiffener_stringers
        ]
    return lines


def snapped_to_pads(
    lines: list[StiffenerLine], main: JunctionTube, pads: list[PadRegion], reach: float
) -> tuple[list[StiffenerLine], dict[str, float]]:
    """The main's stiffener lines within ``reach`` (half an element) of a pad's bounding ring
    or stringer moved onto it, and how far each moved (model units): the shell model cannot
    hold two lines closer than an element without slivers between them, and a stiffener that
    close to the pad's edge stands on it for the model's purposes."""
    out, moved = [], {}
    for line in lines:
        value = line.value
        if line.tube == 0:
            for pad in pads:
                if line.kind == "ring":
                    near = min(pad.s_range, key=lambda b: abs(b - value))
                    gap = abs(near - value)
                else:
                    near = min(pad.angles_deg, key=lambda b: abs((b - value + 180.0) % 360.0 - 180.0))
                    gap = math.radians(abs((near - value + 180.0) % 360.0 - 180.0)) * main.radius
                if 0.0 < gap < reach:
                    value, moved[line.name] = float(near), gap
        out.append(replace(line, value=value))
    return out, moved
