"""A spec with [[branches]]: its junction's parts, for the commands that take them apart
(the shell model, the shop package, benchmarks).

``tubecad build`` builds a junction spec as it builds any spec (:func:`tubecad.spec.build.build_spec`:
the spec's design, :class:`~tubecad.design.junction.JunctionDesign`, built by
:mod:`tubecad.design.junction`); the functions here take the spec and give that builder's
pieces, with its errors naming the spec's section and key.
"""

from __future__ import annotations

from typing import Any

from tubecad.design import junction as _junction
from tubecad.design import junction_parts as _parts
from tubecad.design.junction import JunctionDesign
from tubecad.junctions import BranchWall, JunctionWall
from tubecad.spec import design
from tubecad.spec.design import spec_errors
from tubecad.spec.parse import TubeSpec
from tubecad.stiffeners.pad import Pad

#: the junction's named assembly (``wall``, stiffeners, pads, ``junction_edges``)
junction_assembly = _junction.junction_assembly


def junction_design(spec: TubeSpec) -> JunctionDesign:
    """``spec``'s junction design (a SpecError if it has no [[branches]])."""
    from tubecad.core.errors import SpecError

    if not spec.branches:
        raise SpecError(f"{spec.source}: has no [[branches]]", key="branches")
    return design.junction_design(spec, design.wall_design(spec))


def branch_walls(spec: TubeSpec) -> list[BranchWall]:
    """The spec's [[branches]] as :class:`~tubecad.junctions.BranchWall` (parse_spec checked them)."""
    return _parts.branch_walls(junction_design(spec).branches)


def build_junction(spec: TubeSpec, walls: list[BranchWall] | None = None) -> JunctionWall:
    """The junction wall of ``spec`` (its [wall] and [[branches]], ``walls`` their
    :func:`branch_walls` if made already); a SpecError naming the key (``branches``,
    ``branches.radius``, ``fit.tolerance``) where it cannot be built."""
    with spec_errors(spec):
        design = junction_design(spec)
        return _parts.junction_wall(design.main, design.branches, walls)


def build_pads(spec: TubeSpec, junction: JunctionWall, walls: list[BranchWall]) -> dict[int, Pad]:
    """The reinforcement pads of the branches that ask for one (``pad`` in their table), by
    branch index (:func:`tubecad.design.junction_parts.junction_pads`)."""
    with spec_errors(spec):
        design = junction_design(spec)
        return _parts.junction_pads(design.main, design.branches, junction, walls)


def build_junction_stiffeners(
    spec: TubeSpec, walls: list[BranchWall], junction: JunctionWall | None = None
) -> list[Any]:
    """The main [stiffeners] stopped at every opening and each branch's own ``stiffeners``
    (:func:`tubecad.design.junction_parts.junction_stiffeners`); [] without [stiffeners]."""
    with spec_errors(spec):
        design = junction_design(spec)
        return _parts.junction_stiffeners(design.main, design.branches, walls, junction)
