"""``tubecad mesh`` and ``tubecad analyse`` on a spec with [[branches]] (issue 25): the
junction's shell model (:func:`tubecad.fem.junction.junction_shell_mesh`) from the spec's
main [wall], its branches and their pads, and its pressure step and checks
(:mod:`tubecad.fem.junction_analysis`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from tubecad.core.errors import SpecError, TubecadError
from tubecad.fem.junction import JunctionTube, PadRegion, junction_mesh_size, junction_shell_mesh
from tubecad.fem.model import FEMesh
from tubecad.spec.junction import branch_walls
from tubecad.spec.parse import TubeSpec
from tubecad.spec.sections import spec_error


@dataclass(frozen=True)
class JunctionModel:
    """The junction's shell ``mesh`` with the ``tubes`` it joins (the main first) and its ``pads``."""

    mesh: FEMesh
    tubes: list[JunctionTube]
    pads: list[PadRegion]


def junction_tubes(spec: TubeSpec) -> tuple[list[JunctionTube], list[PadRegion]]:
    """The main tube and the branches as the shell model's tubes (each wall's mid-surface,
    thickness and net) and the pads' regions on the main (from the outer saddle, as the
    built pad: :func:`tubecad.stiffeners.pad.pad_bounds`)."""
    from tubecad.fem.junction import mid_surface_tubes
    from tubecad.junctions.saddle import saddle_curve
    from tubecad.stiffeners.pad import pad_bounds, pad_name

    assert spec.wall is not None  # parse_spec refuses [[branches]] without [wall]
    walls = branch_walls(spec)
    tubes = mid_surface_tubes(spec.tube, spec.wall.thickness, spec.layout.net(spec.tube), walls, side=spec.wall.side)
    outer = spec.tube.offset(spec.wall.offsets()[1])
    pads = []
    for k, (branch, wall) in enumerate(zip(spec.branches, walls)):
        if branch.pad is not None:
            saddle = saddle_curve(outer, wall.surface.offset(wall.offsets()[1]))
            s_range, angles = pad_bounds(outer, saddle, branch.pad.width)
            pads.append(PadRegion(pad_name(k, len(walls)), s_range, angles, branch.pad.thickness))
    return tubes, pads


def junction_model(spec: TubeSpec, settings) -> JunctionModel:
    """The spec's junction meshed with ``settings`` (checked [mesh] settings), its stiffeners as
    beams unless ``[mesh] beams = false`` (:mod:`tubecad.fem.junction_beams`)."""
    from tubecad.fem.junction_beams import add_junction_beams

    try:
        tubes, pads = junction_tubes(spec)
        lines, chosen = stiffener_lines(spec, tubes) if settings.beams else ([], None)
        lines, moved = snapped_to_pads(lines, tubes[0], pads, 0.5 * junction_mesh_size(settings, tubes))
        for k in range(len(tubes)):
            rings = tuple(line.value for line in lines if line.tube == k and line.kind == "ring")
            stringers = tuple(line.value for line in lines if line.tube == k and line.kind == "stringer")
            tubes[k] = replace(tubes[k], stiffened=(rings, stringers))
        mesh = junction_shell_mesh(
            tubes[0],
            tubes[1:],
            pads=pads,
            settings=settings,
            tolerance=spec.fit.tolerance,
            length_unit=spec.length_unit,
        )
        if lines and chosen is not None:
            lengths = add_junction_beams(mesh, tubes, pads, lines, chosen.profile, chosen.side, settings.beam_type)
            mesh.info["beams"] = lengths
            mesh.info["beams_moved_to_pad_edge"] = moved
    except SpecError:
        raise
    except TubecadError as exc:  # the mesh's own keys ([mesh] size, surface), else the branches'
        raise spec_error(spec.source, exc, ("mesh", "stiffeners"), "branches") from None
    return JunctionModel(mesh, tubes, pads)


def stiffener_lines(spec: TubeSpec, tubes: list[JunctionTube]) -> tuple[list[Any], Any]:
    """The junction's stiffeners as lines of its shell model's tubes (the main's [stiffeners],
    each branch's ``stiffeners``, named as their solids: ``ring_03``, ``branch_stringer_02``)
    and the [stiffeners] selection (profile, side); ([], None) without [stiffeners]."""
    from tubecad.fem.junction_beams import StiffenerLine

    if spec.stiffeners is None:
        return [], None
    layout = tubes[0].layout
    chosen = spec.stiffeners.select(layout, spec.source, spec.length_unit)
    lines = [StiffenerLine(f"ring_{i:02d}", 0, "ring", float(layout.s_rings[i])) for i in chosen.rings]
    lines += [
        StiffenerLine(f"stringer_{j:02d}", 0, "stringer", float(layout.stringers_deg[j])) for j in chosen.stringers
    ]
    for k, branch in enumerate(spec.branches):
        if branch.stiffeners is None:
            continue
        net, prefix = tubes[k + 1].layout, "branch" if len(spec.branches) == 1 else f"branch{k}"
        for i in branch.stiffeners.indices("rings", len(net.s_rings)):
            lines.append(StiffenerLine(f"{prefix}_ring_{i:02d}", k + 1, "ring", float(net.s_rings[i])))
        for j in branch.stiffeners.indices("stringers", len(net.stringers_deg)):
            lines.append(StiffenerLine(f"{prefix}_stringer_{j:02d}", k + 1, "stringer", float(net.stringers_deg[j])))
    return lines, chosen


def snapped_to_pads(
    lines: list[Any], main: JunctionTube, pads: list[PadRegion], reach: float
) -> tuple[list[Any], dict[str, float]]:
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


def junction_ends(spec: TubeSpec) -> str:
    """The junction's [analysis] ends: as given (capped or fixed), capped by default."""
    from tubecad.fem.junction_analysis import JUNCTION_ENDS

    ends = (spec.analysis.ends if spec.analysis is not None else None) or "capped"
    if ends not in JUNCTION_ENDS:
        raise SpecError(
            f"{spec.source}: [analysis] ends must be one of {', '.join(JUNCTION_ENDS)} for a junction "
            f"(its main and branch ends are open), got {ends!r:.40}",
            key="analysis.ends",
        )
    return ends


def junction_step(spec: TubeSpec, model: JunctionModel, pressure: float) -> Any:
    """The [analysis] pressure step on the junction."""
    from tubecad.fem.junction_analysis import junction_step as step

    return step(model.mesh, model.tubes, pressure, junction_ends(spec))
