"""CadQuery Workplane plugin: ``curvatureTube``, ``curvatureWall``,
``stiffenedCurvatureWall``, ``curvatureJunction`` and ``curvatureNet``, the build123d objects' twins (the same arguments, the same engine: :mod:`tubecad.parts.engine`; a face's net: :class:`tubecad.design.net.NetDesign`).

    import cadquery as cq
    import tubecad.integrations.cadquery_plugin  # registers the methods

    axis = cq.Edge.makeSpline([cq.Vector(0, 0, 0), cq.Vector(100, 60, 80), cq.Vector(250, 20, 160)])
    wall = cq.Workplane().curvatureWall(axis, radius=12, thickness=1.5, rings=9, stringers=8)
    solid = wall.val()
    assert len(solid.rings) == 9 and solid.rings[3].label == "ring_03"

The solid is pushed onto the stack in the axis' own (global) coordinates, as built, and
combined with what is there as CadQuery's own solids are (``combine``); it is a ``cq.Solid``
whose faces are bounded by the chosen ring frames and stringers, which it carries as
``rings``, ``stringers`` and ``seams`` (``inner_rings``, ``inner_stringers``, ``inner_seams`` on
a wall): lists of labelled ``cq.Wire`` of its own edges. ``curvatureLineTube`` and
``curvatureLineWall`` (a tube object in, CadQuery 2.x plugin of tubecad 0.x) are deprecated
names of the same.

``curvatureNet`` thickens a face the user already has (a ``cq.Face``, say a STEP file's) into a
wall whose edges are its lines of curvature, as ``tubecad.CurvatureNet`` does::

    dome = cq.importers.importStep("samples/dome.step").faces().val()
    net = cq.Workplane().curvatureNet(dome, 6, 8, thickness=8.0, side="inside").val()
    assert net.label == "wall" and [e.label for e in net.k1][:2] == ["k1_00", "k1_01"]
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from typing import Any

try:
    import cadquery as cq
except ImportError as exc:  # CadQuery is an extra: it pins OCP 7.9, build123d 0.13 needs OCP 8
    raise ImportError(
        "tubecad's CadQuery plugin needs CadQuery: pip install 'tubecad[cadquery]' "
        "(CadQuery 2.8 runs on OCP 7.9, so it brings build123d 0.12)"
    ) from exc

from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS
from tubecad.brep.wall import WallSide
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.design.net import DEFAULT_LINES, LineSelection, PatchSurfaces
from tubecad.occ_compat import as_edge
from tubecad.parts.axis_input import AxisLike, RadiusLike
from tubecad.parts.engine import PartArguments, build_part, edge_map_of, net_edges, stiffener_solids
from tubecad.stiffeners.profiles import Profile, StiffenerSide
from tubecad.surface.protocol import CurvatureLineSurface


def curvature_tube(
    self: cq.Workplane,
    axis: AxisLike,
    radius: RadiusLike,
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
    bend_radius: float | Sequence[float] | None = None,
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
    allow_irregular: bool = False,
    combine: bool = True,
) -> cq.Workplane:
    """The solid tube of ``radius`` about ``axis`` (arguments: tubecad.CurvatureTube's)."""
    args = PartArguments(
        axis,
        radius,
        rings=rings,
        stringers=stringers,
        tolerance=tolerance,
        bend_radius=bend_radius,
        normal=normal,
        closed=closed,
        allow_irregular=allow_irregular,
    )
    return _pushed(self, args, combine)


def curvature_wall(
    self: cq.Workplane,
    axis: AxisLike,
    radius: RadiusLike,
    thickness: float,
    side: WallSide = "centered",
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
    bend_radius: float | Sequence[float] | None = None,
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
    allow_irregular: bool = False,
    combine: bool = True,
) -> cq.Workplane:
    """The wall of ``thickness`` round the tube of ``radius`` about ``axis`` (arguments:
    tubecad.CurvatureWall's)."""
    args = PartArguments(
        axis,
        radius,
        thickness,
        side,
        rings=rings,
        stringers=stringers,
        tolerance=tolerance,
        bend_radius=bend_radius,
        normal=normal,
        closed=closed,
        allow_irregular=allow_irregular,
    )
    return _pushed(self, args, combine)


def stiffened_curvature_wall(
    self: cq.Workplane,
    axis: AxisLike,
    radius: RadiusLike,
    thickness: float,
    ring_frames: Sequence[int] | str = "all",
    stringer_stiffeners: Sequence[int] | str = (),
    profile: Profile | None = None,
    stiffener_side: StiffenerSide = "outside",
    side: WallSide = "centered",
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
    bend_radius: float | Sequence[float] | None = None,
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
    allow_irregular: bool = False,
    combine: bool = True,
) -> cq.Workplane:
    """The wall with ring frames and stringer stiffeners on its curvature lines (arguments:
    tubecad.StiffenedCurvatureWall's). Pushes a ``cq.Compound`` of the wall solid and the
    stiffener solids, carrying the wall's ``rings`` and ``stringers`` and ``stiffeners``
    (labelled ``cq.Solid``: ``ring_03``, ``stringer_05``); with ``combine`` and a solid on
    the stack, all of them are fused into it."""
    args = PartArguments(
        axis,
        radius,
        thickness,
        side,
        rings=rings,
        stringers=stringers,
        tolerance=tolerance,
        bend_radius=bend_radius,
        normal=normal,
        closed=closed,
        allow_irregular=allow_irregular,
    )
    return _pushed(self, args, combine, (ring_frames, stringer_stiffeners, profile, stiffener_side))


def _pushed(
    workplane: cq.Workplane, args: PartArguments, combine: bool, stiffened: tuple | None = None
) -> cq.Workplane:
    design, build = build_part(args)
    solid = cq.Solid(build.shape.wrapped)
    net = net_edges(build)
    edge_map = edge_map_of(solid.wrapped)
    for name, lines in (
        ("rings", net.rings),
        ("stringers", net.stringers),
        ("seams", net.seams),  # face edges u = const that are no stringer (the build123d objects' seams)
        ("inner_rings", net.inner_rings),
        ("inner_stringers", net.inner_stringers),
        ("inner_seams", net.inner_seams),
    ):
        if net.inner_rings or not name.startswith("inner_"):  # inner_...: on a wall
            setattr(solid, name, [_wire(label, [edge_map.FindKey(i) for i in found]) for label, found in lines.items()])
    pushed: cq.Shape = solid
    stiffeners: list[cq.Solid] = []
    if stiffened is not None:
        for label, shape in stiffener_solids(design, build, *stiffened):
            stiffener = cq.Solid(shape)
            stiffener.label = label
            stiffeners.append(stiffener)
        pushed = cq.Compound.makeCompound([solid, *stiffeners])
        for name in ("rings", "stringers", "seams", "inner_rings", "inner_stringers", "inner_seams"):
            if hasattr(solid, name):
                setattr(pushed, name, getattr(solid, name))
        pushed.stiffeners = stiffeners  # type: ignore[attr-defined,unused-ignore]
    try:
        base = workplane.findSolid()
    except ValueError:  # nothing solid on the stack or its parents
        base = None
    if not combine or base is None:
        return workplane.newObject([pushed])
    # the solids one by one, so the stiffeners fuse with the wall too (not only with the base)
    return workplane.union(cq.Workplane().newObject([solid, *stiffeners]))


def curvature_junction(
    self: cq.Workplane,
    axis: AxisLike,
    radius: RadiusLike,
    thickness: float,
    branches: Sequence[Any],
    side: WallSide = "centered",
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
    bend_radius: float | Sequence[float] | None = None,
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
    combine: bool = True,
) -> cq.Workplane:
    """The wall round the tube of ``radius`` about ``axis`` with every branch of ``branches``
    (``tubecad.Branch``) joined on: one solid (arguments: tubecad.CurvatureJunction's, the same
    engine: :func:`tubecad.parts.junction.build_junction_part`). Pushes a ``cq.Solid`` carrying
    ``named_edges`` (name -> its labelled ``cq.Edge``: ``saddle_outer``, ``saddle_inner``,
    ``main_ring_03``, ``branch_stringer_05_inner``, ...) and ``junction`` (what was built and
    measured); with pads, a ``cq.Compound`` of it and the pads (labelled ``cq.Solid``: ``pad``,
    ``pad_0``, ...) carrying the same and ``pads``. With ``combine`` and a solid on the stack,
    they are fused into it (the names then refer to the unfused solid's edges)."""
    from tubecad.parts.junction import build_junction_part

    built = build_junction_part(
        axis,
        radius,
        thickness,
        branches,
        side=side,
        rings=rings,
        stringers=stringers,
        tolerance=tolerance,
        bend_radius=bend_radius,
        normal=normal,
        closed=closed,
    )
    wall = cq.Solid(built.junction.shape.wrapped)
    named: dict[str, list[cq.Edge]] = {}
    for name, edges in sorted(built.junction.edges.items()):
        named[name] = []
        for edge in edges:
            found = cq.Edge(edge.wrapped)
            found.label = name
            named[name].append(found)
    pads = []
    for name, pad in built.pads:
        solid = cq.Solid(pad.solid.wrapped)
        solid.label = name
        pads.append(solid)
    pushed: cq.Shape = wall if not pads else cq.Compound.makeCompound([wall, *pads])
    for target in {id(wall): wall, id(pushed): pushed}.values():
        target.named_edges = named  # type: ignore[attr-defined,unused-ignore]
        target.junction = built.junction  # type: ignore[attr-defined,unused-ignore]
    if pads:
        pushed.pads = pads  # type: ignore[attr-defined,unused-ignore]
    return _put(self, pushed, [wall, *pads], combine)


def curvature_net(
    self: cq.Workplane,
    face: Any,
    k1_lines: int | None = DEFAULT_LINES,
    k2_lines: int | None = DEFAULT_LINES,
    *,
    thickness: float,
    side: WallSide = "centered",
    k1_spacing: float | None = None,
    k2_spacing: float | None = None,
    seed: Sequence[float] | None = None,
    stiffened: Mapping[str, LineSelection | Sequence[int]] | None = None,
    profile: Profile | None = None,
    stiffener_side: StiffenerSide = "outside",
    patches: PatchSurfaces = "host",
    combine: bool = True,
    clean: bool = True,
) -> cq.Workplane:
    """The face's curvature-line net as a wall of ``thickness`` (arguments:
    tubecad.CurvatureNet's, the same design: :class:`tubecad.design.net.NetDesign` built by
    :func:`tubecad.design.net.build_net`). ``face``: a ``cq.Face`` (or any object whose
    ``wrapped`` is a face), a Workplane holding one face, or an OCCT ``TopoDS_Face``.

    Pushes the wall, a ``cq.Solid`` labelled ``wall`` in the face's own (global) coordinates,
    or with ``stiffened`` lines a ``cq.Compound`` of it and the webs (labelled ``cq.Solid``:
    ``stiffener_k1_03``..., in ``stiffeners``). Both carry ``k1`` and ``k2`` (the lines as
    labelled ``cq.Edge`` on the face: ``k1_00``...), ``umbilics`` (labelled ``cq.Vertex``:
    ``umbilic_0``..., their types in ``report["host"]["umbilics"]``), ``report`` (what was
    measured, as ``tubecad build``'s report.json) and ``design``. With ``combine`` and a solid
    on the stack, the wall and the webs are fused into it (``clean``: CadQuery's union's).

    Raises:
        ParameterError: naming the argument (``face``, ``k1_lines``, ``seed``, ``thickness``,
            ``profile``, ``k1``...).
    """
    if isinstance(face, cq.Workplane):  # a selection, as CadQuery's own methods take one
        held = face.vals()
        if len(held) != 1 or not isinstance(held[0], cq.Face):
            what = ", ".join(type(v).__name__ for v in held[:3]) or "nothing"
            raise ParameterError(f"face must be a Workplane holding one Face, got one holding {what}", key="face")
        face = held[0]
    from tubecad.parts.net_arguments import net_part_design

    built = net_part_design(
        face,
        k1_lines,
        k2_lines,
        thickness,
        side,
        k1_spacing,
        k2_spacing,
        seed,
        stiffened,
        profile,
        stiffener_side,
        patches,
    ).build_net()
    solids = []
    for name, shape in built.solids:  # the wall, then each web
        solid = cq.Solid(shape)
        solid.label = name
        solids.append(solid)
    wall, webs = solids[0], solids[1:]
    lines: dict[str, list[cq.Edge]] = {"k1": [], "k2": []}
    for name, line in built.design.net.edges.items():
        edge = cq.Edge(line.edge)
        edge.label = name
        lines[name[:2]].append(edge)
    umbilics = []
    for name, vertex in built.design.net.vertices.items():
        point = cq.Vertex(vertex)
        point.label = name
        umbilics.append(point)
    pushed: cq.Shape = wall if not webs else cq.Compound.makeCompound(solids)
    for target in {id(wall): wall, id(pushed): pushed}.values():
        target.k1 = lines["k1"]  # type: ignore[attr-defined,unused-ignore]
        target.k2 = lines["k2"]  # type: ignore[attr-defined,unused-ignore]
        target.umbilics = umbilics  # type: ignore[attr-defined,unused-ignore]
        target.report = built.report  # type: ignore[attr-defined,unused-ignore]
        target.design = built.design  # type: ignore[attr-defined,unused-ignore]
    if webs:
        pushed.stiffeners = webs  # type: ignore[attr-defined,unused-ignore]
    return _put(self, pushed, solids, combine, clean)


def _put(workplane: cq.Workplane, pushed: cq.Shape, solids: list, combine: bool, clean: bool = True) -> cq.Workplane:
    """``pushed`` on a new workplane object, or with ``combine`` and a solid on the stack (or
    its parents) ``solids`` fused into it."""
    try:
        base = workplane.findSolid()
    except ValueError:  # nothing solid on the stack or its parents
        base = None
    if not combine or base is None:
        return workplane.newObject([pushed])
    return workplane.union(cq.Workplane().newObject(solids), clean=clean)


def _wire(label: str, edges: list) -> cq.Wire:
    wire = cq.Wire.assembleEdges([cq.Edge(as_edge(e)) for e in edges])
    wire.label = label
    return wire


def curvature_line_tube(
    self: cq.Workplane,
    tube: CurvatureLineSurface,
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
) -> cq.Workplane:
    """Deprecated: ``curvatureTube(tube.axis, tube.radius_law, ...)``."""
    warnings.warn(
        "curvatureLineTube(tube, ...) is deprecated: use curvatureTube(axis, radius, ...)",
        DeprecationWarning,
        stacklevel=2,
    )
    return curvature_tube(self, tube.axis, tube.radius_law, rings, stringers, tolerance, combine=False)


def curvature_line_wall(
    self: cq.Workplane,
    tube: CurvatureLineSurface,
    thickness: float,
    side: WallSide = "centered",
    rings: int | Sequence[float] = DEFAULT_RINGS,
    stringers: int | Sequence[float] = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
) -> cq.Workplane:
    """Deprecated: ``curvatureWall(tube.axis, tube.radius_law, thickness, ...)``."""
    warnings.warn(
        "curvatureLineWall(tube, ...) is deprecated: use curvatureWall(axis, radius, thickness, ...)",
        DeprecationWarning,
        stacklevel=2,
    )
    return curvature_wall(self, tube.axis, tube.radius_law, thickness, side, rings, stringers, tolerance, combine=False)


# the plugin's methods, patched onto Workplane (CadQuery's plugin convention; its class does not declare them)
cq.Workplane.curvatureTube = curvature_tube  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.curvatureWall = curvature_wall  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.stiffenedCurvatureWall = stiffened_curvature_wall  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.curvatureJunction = curvature_junction  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.curvatureNet = curvature_net  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.curvatureLineTube = curvature_line_tube  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.curvatureLineWall = curvature_line_wall  # type: ignore[attr-defined,unused-ignore]
