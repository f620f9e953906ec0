"""The keyword arguments of the plugin objects as a design, and its build's edges by name.

An axis, a radius (or a radius law), a wall and a layout in: :func:`part_design` makes the
:class:`~tubecad.design.wall.WallDesign` that the spec makes from TOML, and the design layer
builds it (:func:`tubecad.design.wall.build_solid`, :func:`~tubecad.design.wall.build_wall_stiffeners`):
one engine under the spec, the build123d parts and the CadQuery plugin. Both front ends
(:mod:`tubecad.parts.build123d_parts`, the CadQuery plugin) call :func:`build_part` and
:func:`net_edges`, so their arguments and results are the same.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from tubecad.brep import NetLayout, TubeBuild
from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS
from tubecad.brep.wall import WallSide, as_wall_side
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.design.model import StiffenerChoice, WallChoice
from tubecad.design.wall import WallDesign, build_solid, build_wall_stiffeners
from tubecad.parts.axis_input import AxisLike, RadiusLike, as_axis
from tubecad.surface import CurvatureLineSurface
from tubecad.surface.canal import tube_or_canal


@dataclass(frozen=True)
class PartArguments:
    """What a plugin object is built from (the keyword arguments of ``CurvatureTube`` and
    ``CurvatureWall``, checked)."""

    axis: AxisLike
    radius: RadiusLike
    thickness: float | None = None
    side: WallSide = "centered"
    rings: int | Sequence[float] = DEFAULT_RINGS
    stringers: int | Sequence[float] = DEFAULT_STRINGERS
    tolerance: float = DEFAULT_TOLERANCE
    bend_radius: float | Sequence[float] | None = None
    normal: Sequence[float] | None = None
    closed: bool | None = None
    allow_irregular: bool = False


def part_design(args: PartArguments) -> WallDesign:
    """The design the arguments describe: the exact surface about the axis (a tube, or a
    canal surface for a radius law), its net, and with a ``thickness`` the wall placed
    ``side`` of it; stiffeners are added by :func:`stiffener_solids`."""
    axis = as_axis(args.axis, bend_radius=args.bend_radius, normal=args.normal, closed=args.closed)
    surface = tube_or_canal(axis, args.radius, allow_irregular=args.allow_irregular)
    layout = layout_of(surface, args.rings, args.stringers)
    wall = None if args.thickness is None else WallChoice(args.thickness, as_wall_side(args.side))
    return WallDesign(surface, layout, args.tolerance, wall)


def build_part(args: PartArguments) -> tuple[WallDesign, TubeBuild]:
    """(the design, its B-rep build): the capped tube solid, or with a ``thickness`` the wall
    solid between the surfaces offset along the normal (``side``)."""
    design = part_design(args)
    return design, build_solid(design)


def layout_of(surface: CurvatureLineSurface, rings: Any, stringers: Any) -> NetLayout:
    """A count of rings (equally spaced in s; N distinct rings on a closed axis) or their arc
    lengths, and a count of stringers (equally spaced round) or their angles in degrees."""
    from tubecad.brep.layout import equal_rings, equal_stringers

    s_rings = equal_rings(surface, rings) if _is_count(rings, "rings") else rings
    angles = equal_stringers(stringers) if _is_count(stringers, "stringers") else stringers
    return NetLayout.explicit(surface, s_rings, angles)


def chosen_indices(name: str, chosen: Any, count: int) -> list[int]:
    """``"all"`` as every index below ``count``, else the whole-number indices as given, each in
    [0, count - 1]; anything else is refused naming ``name``."""
    if isinstance(chosen, str) and chosen == "all":
        return list(range(count))
    refusal = ParameterError(f'{name} must be "all" or a list of indices in [0, {count - 1}], got {chosen!r}')
    if isinstance(chosen, str) or not isinstance(chosen, Sequence):
        raise refusal
    if not all(isinstance(i, int) and not isinstance(i, bool) and 0 <= i < count for i in chosen):
        raise refusal
    return list(chosen)


def stiffener_solids(
    design: WallDesign, build: TubeBuild, ring_frames: Any, stringer_stiffeners: Any, profile: Any, side: str
) -> list[tuple[str, Any]]:
    """(name, OCCT solid) of each stiffener a stiffened part carries: ring frames on the
    layout's rings ``ring_frames`` and stringer stiffeners on ``stringer_stiffeners``
    (indices or ``"all"``), of ``profile`` (a flat bar when None) on the wall's ``side``,
    built on ``design``'s ``build`` as the spec's [stiffeners] are
    (:func:`tubecad.design.wall.build_wall_stiffeners`)."""
    from tubecad.stiffeners.profiles import Profile, as_stiffener_side

    rings = chosen_indices("ring_frames", ring_frames, len(build.layout.s_rings))
    stringers = chosen_indices("stringer_stiffeners", stringer_stiffeners, len(build.layout.stringers_deg))
    chosen = StiffenerChoice(
        tuple(rings), tuple(stringers), profile if profile is not None else Profile(), as_stiffener_side(side)
    )
    made = build_wall_stiffeners(replace(design, stiffeners=chosen), build)
    return [(st.name, st.solid.wrapped) for st in made]


def _is_count(value: Any, name: str) -> bool:
    if isinstance(value, bool):
        raise ParameterError(f"{name} must be a whole number or a list of positions, got {value!r}")
    return isinstance(value, int) or (isinstance(value, float) and value.is_integer())


@dataclass(frozen=True)
class NetEdges:
    """The chosen curvature lines as B-rep edges of the build's solid, by name (``ring_03``,
    ``stringer_05``): for each line the indices of its edges in the solid's edge map
    (``TopExp.MapShapes``, 1-based), in order along the line; on the outer surface and (a
    wall) on the inner one. Indices, not shapes: a placed or copied solid explores its edges
    in the same order, so the same indices find the line on it. ``seams`` (``seam_00``, ...):
    the face edges u = const that are no stringer, where the faces are split at the circle's
    C0 knots (one stringer: the line opposite it; :attr:`~tubecad.brep.faces.PatchFaces.seams`)."""

    rings: dict[str, list[int]]
    stringers: dict[str, list[int]]
    inner_rings: dict[str, list[int]]
    inner_stringers: dict[str, list[int]]
    seams: dict[str, list[int]] = field(default_factory=dict)
    inner_seams: dict[str, list[int]] = field(default_factory=dict)


def net_edges(build: TubeBuild) -> NetEdges:
    """The ring, stringer and seam edges of ``build``'s solid, by name. On a closed axis the closing
    ring (the first and last ring of the layout) is ``ring_00`` once, made of all its arcs."""
    edge_map = edge_map_of(build.shape.wrapped)
    closed = build.surfaces[0].tube.axis.closed
    out = []
    for patches in build.patches:
        rings = patches.rings[:-1] if closed else patches.rings
        named = {f"ring_{i:02d}": list(edges) for i, edges in enumerate(rings)}
        if closed and patches.closing_arcs:
            named["ring_00"] = [arc for _, _, arc in patches.closing_arcs]
        stringers = {f"stringer_{j:02d}": list(col) for j, col in enumerate(patches.stringers)}
        seams = {f"seam_{k:02d}": list(col) for k, col in enumerate(patches.seams)}
        out.append(
            tuple(
                {name: _indices(edge_map, edges, name) for name, edges in lines.items()}
                for lines in (named, stringers, seams)
            )
        )
    inner = out[1] if len(out) > 1 else ({}, {}, {})
    return NetEdges(out[0][0], out[0][1], inner[0], inner[1], out[0][2], inner[2])


def edge_map_of(shape: Any) -> Any:
    """The solid's edges, each once, in OCCT's exploration order (TopTools_IndexedMapOfShape)."""
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp

    from tubecad.occ_compat import IndexedMapOfShape

    edge_map = IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_EDGE, edge_map)
    return edge_map


def _indices(edge_map: Any, edges: list[Any], name: str) -> list[int]:
    found = [edge_map.FindIndex(e) for e in edges]
    if 0 in found:  # pragma: no cover - the solid is made of these very faces and edges
        raise AssertionError(f"{name}: an edge of the line is not an edge of the solid")
    return found
