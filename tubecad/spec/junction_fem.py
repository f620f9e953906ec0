"""``tubecad mesh`` and ``tubecad analyse`` on a spec with [[branches]] (issue 25): the
junction's shell model (:func:`tubecad.fem.junction.junction_shell_mesh`) from the spec's
main [wall], its branches and their pads, and its pressure step and checks
(:mod:`tubecad.fem.junction_analysis`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from tubecad.core.errors import ParameterError, RegularityError, SpecError, TubecadError
from tubecad.fem.junction import JunctionTube, PadRegion, junction_shell_mesh
from tubecad.fem.model import FEMesh
from tubecad.spec.junction import branch_walls
from tubecad.spec.parse import TubeSpec


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
    """The spec's junction meshed with ``settings`` (checked [mesh] settings)."""
    if settings.beams and (spec.stiffeners is not None or any(b.stiffeners for b in spec.branches)):
        raise SpecError(
            f"{spec.source}: [mesh] beams: the stiffeners of a junction are not made as beams yet; set "
            "[mesh] beams = false to mesh the junction's shell without them",
            key="mesh.beams",
        )
    try:
        tubes, pads = junction_tubes(spec)
        if len(pads) > 1:
            raise ParameterError("a shell model with more than one pad is not made yet", key="branches.pad")
        mesh = junction_shell_mesh(
            tubes[0],
            tubes[1:],
            pads=pads,
            settings=settings,
            tolerance=spec.fit.tolerance,
            length_unit=spec.length_unit,
        )
    except (ParameterError, RegularityError) as exc:
        key = exc.key or "branches"
        where = "" if str(exc).startswith("[") else "[[branches]] "
        raise SpecError(f"{spec.source}: {where}{exc}", key=key) from None
    except TubecadError as exc:
        raise SpecError(f"{spec.source}: [[branches]] {exc}", key=exc.key or "branches") from None
    return JunctionModel(mesh, tubes, pads)


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
