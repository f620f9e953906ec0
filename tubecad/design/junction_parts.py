"""The pieces a junction design is built of, each from the main wall's design and the
branches' (:class:`~tubecad.design.wall.WallDesign`, :class:`~tubecad.design.model.BranchDesign`):
the branch walls, the joined wall (:func:`tubecad.junctions.build_branched_wall`), the pads
and the stiffeners stopped at the openings. The junction design
(:mod:`tubecad.design.junction`) and its shop package (:mod:`tubecad.design.junction_shop`)
both build from them."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from tubecad.core.errors import ParameterError
from tubecad.design.stages import stage

if TYPE_CHECKING:
    from tubecad.design.model import BranchDesign
    from tubecad.design.wall import WallDesign
    from tubecad.junctions import BranchWall, JunctionWall
    from tubecad.stiffeners.pad import Pad
    from tubecad.surface.protocol import CurvatureLineSurface


def branch_walls(branches: Sequence[BranchDesign]) -> list[BranchWall]:
    """The branches as :class:`~tubecad.junctions.BranchWall` s (the junction library's input)."""
    from tubecad.junctions import BranchWall

    return [BranchWall(b.surface, b.wall.thickness, b.wall.side, b.layout, b.blend) for b in branches]


def junction_wall(
    main: WallDesign, branches: Sequence[BranchDesign], walls: list[BranchWall] | None = None
) -> JunctionWall:
    """The wall ``main`` with ``branches`` joined on (``walls``: their :func:`branch_walls` if
    made already)."""
    from tubecad.junctions import build_branched_wall

    assert main.wall is not None  # a junction joins walls
    with stage("branches"):
        return build_branched_wall(
            main.surface,
            main.wall.thickness,
            walls if walls is not None else branch_walls(branches),
            main_side=main.wall.side,
            main_layout=main.layout,
            tolerance=main.tolerance,
        )


def junction_pads(
    main: WallDesign, branches: Sequence[BranchDesign], junction: JunctionWall, walls: list[BranchWall]
) -> dict[int, Pad]:
    """The reinforcement pads of the ``branches`` that have one, by branch index: each on the
    ``main`` wall's outer surface round the branch's outer saddle."""
    from tubecad.junctions import saddle_name
    from tubecad.stiffeners.pad import reinforcement_pad

    assert main.wall is not None
    main_out = main.wall.offsets()[1]
    pads = {}
    for k, (branch, wall) in enumerate(zip(branches, walls)):
        if branch.pad is None:
            continue
        if branch.blend is not None:
            with stage("branches", k):
                raise ParameterError("blend: a blend with a pad round the branch is not made yet", key="blend")
        with stage("pads", k):
            pads[k] = reinforcement_pad(
                main.surface.offset(main_out),
                wall.surface.offset(wall.offsets()[1]),
                junction.saddles[saddle_name("saddle_outer", k, len(walls))].saddle,
                branch.pad.thickness,
                branch.pad.width,
                main.tolerance,
            )
    _check_pads_apart(main.surface.offset(main_out), junction, pads, len(walls))
    return pads


def _check_pads_apart(outer: CurvatureLineSurface, junction: JunctionWall, pads: dict[int, Pad], n: int) -> None:
    """Refuse a pad that reaches another branch's opening or pad on the main's outer surface
    ``outer`` (both unrolled: :mod:`tubecad.junctions.placement`), naming its width and the
    clearance it would need."""
    from tubecad.junctions import saddle_name
    from tubecad.junctions.placement import region_clearance, unrolled_opening, unrolled_patch

    openings = {
        m: unrolled_opening(outer, junction.saddles[saddle_name("saddle_outer", m, n)].saddle) for m in range(n)
    }
    patches = {k: unrolled_patch(outer, pad.s_range, pad.angles_deg) for k, pad in pads.items()}
    for k, patch in patches.items():
        others = [(f"the opening of branch {m}", region) for m, region in openings.items() if m != k]
        others += [(f"the pad of branch {m}", region) for m, region in patches.items() if m > k]
        for what, region in others:
            if region_clearance(outer, patch, region) <= 0.0:
                overlap = patch.intersection(region).area
                with stage("pads", k):
                    raise ParameterError(
                        f"pad.width: the pad of branch {k} (width {pads[k].width:g}) reaches {what} on the main "
                        f"tube (they overlap over {overlap:.4g} square units): a narrower pad, or the branches apart",
                        key="pad.width",
                    )


def junction_stiffeners(
    main: WallDesign, branches: Sequence[BranchDesign], walls: list[BranchWall], junction: JunctionWall | None = None
) -> list[Any]:
    """The ``main`` design's stiffeners on the main wall, each stopped at every branch's opening
    (on the surface it stands on: the outer saddle outside, the bore's inside) or at its
    pad's edge (a pad outside), and each stiffened branch's own (its stringers from its
    saddle, its rings beyond it); [] without stiffeners (:mod:`tubecad.stiffeners.junction`).
    ``junction``: the built wall, whose saddles start Newton (no new march round a branch)."""
    from tubecad.junctions import saddle_name
    from tubecad.junctions.saddle import saddle_curve
    from tubecad.stiffeners.junction import Keepout, branch_stiffeners, main_stiffeners
    from tubecad.stiffeners.pad import pad_bounds

    chosen = main.stiffeners
    if chosen is None:
        return []
    assert main.wall is not None
    layout, outside = main.layout, chosen.side == "outside"
    main_base = main.surface.offset(main.wall.offsets()[1 if outside else 0])
    keepouts, saddles = [], []
    for k, (branch, wall) in enumerate(zip(branches, walls)):
        branch_base = wall.surface.offset(wall.offsets()[1 if outside else 0])
        known = saddle_name("saddle_outer" if outside else "saddle_inner", k, len(walls))
        near = junction.saddles[known].saddle if junction is not None else None
        if outside and junction is not None and k in junction.blends:
            # a crotch blend: the stiffeners stop on its edges (its spine's parameters are the contacts')
            saddle = junction.outer_boundary(k, len(walls))
        else:
            saddle = saddle_curve(main_base, branch_base, near=near)
        saddles.append((branch_base, saddle))
        if outside and branch.pad is not None:
            s_range, angles = pad_bounds(main_base, saddle, branch.pad.width)
            keepouts.append(Keepout(s_range=s_range, angles_deg=angles))
        else:
            keepouts.append(Keepout(saddle=saddle))
    with stage("stiffeners"):
        out = main_stiffeners(
            main_base,
            [(i, layout.s_rings[i]) for i in chosen.rings],
            [(j, layout.stringers_deg[j]) for j in chosen.stringers],
            chosen.profile,
            chosen.side,
            keepouts,
            main.tolerance,
        )
    for k, (branch, (branch_base, saddle)) in enumerate(zip(branches, saddles)):
        if not branch.stiffened:
            continue
        net = branch.layout
        start = chosen.profile.height if branch.stiffener_start is None else branch.stiffener_start
        with stage("stiffeners", k):
            out += branch_stiffeners(
                branch_base,
                saddle,
                [(i, net.s_rings[i]) for i in branch.stiffener_rings],
                [(j, net.stringers_deg[j]) for j in branch.stiffener_stringers],
                chosen.profile,
                chosen.side,
                start,
                "branch" if len(walls) == 1 else f"branch{k}",
                main.tolerance,
            )
    return out
