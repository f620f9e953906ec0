"""build123d objects: ``CurvatureTube``, ``CurvatureWall`` and ``StiffenedCurvatureWall``.

Part objects as build123d's own (``Box``, ``Cylinder``) and bd_warehouse's: usable in
builder mode (``mode``, ``rotation``, ``align``, inside ``Locations``) and in algebra mode
(``+``, ``-``, ``*``, ``Pos(...) * part``). The geometry comes from tubecad's private
engine (:mod:`tubecad.parts.engine`): the tube parameterised by its lines of curvature,
fitted into OCCT B-splines with exact circles, whose face edges are the chosen ring
frames and stringers. Those lines are reachable on the object, labelled::

    from build123d import BuildPart, Box, Mode, Spline
    from tubecad import CurvatureWall

    path = Spline((0, 0, 0), (100, 60, 80), (250, 20, 160))  # a BuildLine object: made outside BuildPart
    with BuildPart() as p:
        Box(400, 400, 20)
        wall = CurvatureWall(path, radius=12, thickness=1.5, rings=9, stringers=8, mode=Mode.ADD)
    assert len(wall.rings) == 9 and wall.rings[3].label == "ring_03"

The object keeps its curvature lines through its own placement (``align``, ``rotation``,
``Locations``); a boolean's result is a new build123d ``Part``, whose faces still carry the
lines as edges but without the names.

Its solids are its build123d ``children``, labelled as ``tubecad build`` names them:
``wall`` (on a tube too, as there), then a stiffened wall's ``ring_03``, ``stringer_05``, ...
in each placed copy, under the part's own label (its class name). So build123d's own
``export_step(wall, "wall.step")`` writes them as named products, as
:func:`tubecad.export.cad.export_named_step` does (without its colours); the curvature
lines are not in it (they are edges of the solids, not solids).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import build123d as bd

from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS
from tubecad.brep.wall import WallSide
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.design.wall import WallDesign
from tubecad.parts.axis_input import AxisLike, RadiusLike
from tubecad.parts.engine import NetEdges, PartArguments, build_part, net_edges
from tubecad.parts.named_part import NamedSolidsPart
from tubecad.stiffeners.profiles import Profile, StiffenerSide


class _Engine:
    """What the part was built from: its design (:class:`~tubecad.design.wall.WallDesign`, as
    a spec's), the B-rep build, the lines' edges. Shared, not copied, by the part's copies
    (OCCT objects do not deep-copy)."""

    def __init__(self, design: WallDesign, build: Any, net: NetEdges) -> None:
        self.design, self.build, self.net = design, build, net
        self.surface, self.layout = design.surface, build.layout

    def __deepcopy__(self, memo: dict) -> _Engine:
        return self

    def report(self) -> dict[str, Any]:
        """The fit's deviation from the exact surface and the isolines' orthogonality on
        dense samples, poles, validity, OCCT's pre-boolean checks, volume against the exact
        one (:func:`tubecad.design.report.build_report`)."""
        from tubecad.design.report import build_report

        return build_report(self.build, self.surface)


class _CurvatureNetPart(NamedSolidsPart):
    """A part whose face edges are curvature lines: ``rings``, ``stringers``, ``seams`` (and on
    a wall ``inner_rings``, ``inner_stringers``, ``inner_seams``) as labelled wires of this
    part's own edges."""

    _tubecad: _Engine

    def __init__(self, args: PartArguments, rotation: bd.RotationLike, align: Any, mode: bd.Mode) -> None:
        design, build = build_part(args)
        engine = _Engine(design, build, net_edges(build))
        self._tubecad = engine  # before the stiffeners are made on it (_part)
        super().__init__(engine, self._part(build), rotation, align, mode)
        #: the inputs, kept as given (build123d's parts keep theirs): the axis as the Axis
        #: it became, the radius (or law) and the fit tolerance
        self.axis = design.surface.axis
        self.radius = args.radius
        self.tolerance = args.tolerance

    def _part(self, build: Any) -> bd.Part | bd.Solid:
        """What is placed: the build's solid (a stiffened wall adds its stiffeners)."""
        return bd.Solid(build.shape.wrapped)

    def _named_lines(self) -> list[bd.Shape]:
        """The rings, stringers and seams of the (outer) surface; a wall's inner ones too,
        labelled ``_inner`` as ``tubecad build`` labels them."""
        lines: list[bd.Shape] = [*self.rings, *self.stringers, *self.seams]
        if self._net.inner_rings:
            for wire in [*self._wires(self._net.inner_rings), *self._wires(self._net.inner_stringers)]:
                wire.label = f"{wire.label}_inner"
                lines.append(wire)
        return lines

    @property
    def seams(self) -> bd.ShapeList[bd.Wire]:
        """The face edges u = const on the outer surface that are no stringer, labelled
        ``seam_00``, ...: where a face would run over the circle's C0 knot it is split there
        (with one stringer, along the line opposite it). Empty with two or more stringers no
        more than 330 deg apart."""
        return self._wires(self._net.seams)


class CurvatureTube(_CurvatureNetPart):
    """A solid tube of ``radius`` about ``axis`` (closed by flat discs at both ends; none on a
    closed axis), its faces bounded by ``rings`` ring frames and ``stringers`` stringers.

    Args:
        axis: a tubecad Axis (any kind), a build123d or CadQuery Edge or Wire, or a sequence
            of (x, y, z) points (with ``bend_radius``: a pipe route of lines and bends;
            without: the C2 cubic spline through them).
        radius: a number, or a radius law r(s) (an expression string in s, a callable, a
            table ``[(s, r), ...]``): a canal surface.
        rings: how many ring frames, equally spaced in arc length (ends included; on a closed
            axis N distinct rings), or their arc lengths.
        stringers: how many stringers, equally spaced round, or their angles in degrees from
            the rotation-minimising normal r1.
        tolerance: the fit's tolerance, in model units (the measured deviation is in ``report``).
        bend_radius, normal, closed: for an axis given as points or an edge (see
            :func:`tubecad.parts.axis_input.as_axis`).
        allow_irregular: build even where the surface folds (refused by default).
        rotation, align, mode: as for build123d's ``Box``; ``align=None`` (the default)
            keeps the tube where its axis is.
    """

    def __init__(
        self,
        axis: AxisLike,
        radius: RadiusLike,
        *,
        rings: int | Sequence[float] = DEFAULT_RINGS,
        stringers: int | Sequence[float] = DEFAULT_STRINGERS,
        tolerance: float = DEFAULT_TOLERANCE,
        bend_radius: float | Sequence[float] | None = None,
        normal: Sequence[float] | None = None,
        closed: bool | None = None,
        allow_irregular: bool = False,
        rotation: bd.RotationLike = (0, 0, 0),
        align: bd.Align | tuple[bd.Align, bd.Align, bd.Align] | None = None,
        mode: bd.Mode = bd.Mode.ADD,
    ) -> None:
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
        super().__init__(args, rotation, align, mode)


class CurvatureWall(_CurvatureNetPart):
    """The wall of ``thickness`` round the tube of ``radius`` about ``axis``: the solid
    between the two surfaces offset along the normal (``side``: ``centered``, ``inside`` or
    ``outside`` the tube), closed by annular caps at the ends (none on a closed axis). Its
    faces are bounded by the ring frames and stringers on both surfaces; ``rings`` and
    ``stringers`` are the outer surface's, ``inner_rings`` and ``inner_stringers`` the
    inner one's. The other arguments are :class:`CurvatureTube`'s.

    Args:
        axis: the tube's axis: a tubecad Axis (any kind), a build123d or CadQuery Edge or
            Wire, a BuildLine or its edges, or (x, y, z) points (see ``CurvatureTube``).
        radius: a number, or a radius law r(s) (expression, callable, table): a canal surface.
        thickness: the wall's thickness (model units, > 0).
        side: where the wall stands: ``centered`` on the tube's surface, ``inside`` or ``outside`` it.
        rings: how many ring frames, equally spaced in arc length, or their arc lengths.
        stringers: how many stringers, equally spaced round, or their angles in degrees.
        tolerance: the fit's tolerance, in model units.
        bend_radius: for an axis given as points: the bends' radius (a pipe route).
        normal: for an axis given as points or an edge: the first stringer's direction at its start.
        closed: for an axis given as points or an edge: whether it closes on itself.
        allow_irregular: build even where the surface folds (refused by default).
        rotation: as for build123d's ``Box``.
        align: as for build123d's ``Box``; None (the default) keeps the part where its axis is.
        mode: as for build123d's ``Box`` (how it combines in a ``BuildPart``).
    """

    def __init__(
        self,
        axis: AxisLike,
        radius: RadiusLike,
        thickness: float,
        *,
        side: WallSide = "centered",
        rings: int | Sequence[float] = DEFAULT_RINGS,
        stringers: int | Sequence[float] = DEFAULT_STRINGERS,
        tolerance: float = DEFAULT_TOLERANCE,
        bend_radius: float | Sequence[float] | None = None,
        normal: Sequence[float] | None = None,
        closed: bool | None = None,
        allow_irregular: bool = False,
        rotation: bd.RotationLike = (0, 0, 0),
        align: bd.Align | tuple[bd.Align, bd.Align, bd.Align] | None = None,
        mode: bd.Mode = bd.Mode.ADD,
    ) -> None:
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
        super().__init__(args, rotation, align, mode)
        self.thickness, self.side = thickness, side

    @property
    def inner_rings(self) -> bd.ShapeList[bd.Wire]:
        """The ring frames on the inner surface (``ring_00``, ...)."""
        return self._wires(self._net.inner_rings)

    @property
    def inner_stringers(self) -> bd.ShapeList[bd.Wire]:
        """The stringers on the inner surface (``stringer_00``, ...)."""
        return self._wires(self._net.inner_stringers)

    @property
    def inner_seams(self) -> bd.ShapeList[bd.Wire]:
        """The seams on the inner surface (``seam_00``, ...; see :attr:`seams`)."""
        return self._wires(self._net.inner_seams)


class StiffenedCurvatureWall(CurvatureWall):
    """A :class:`CurvatureWall` with stiffeners standing on its lines of curvature: ring
    frames on the layout's rings ``ring_frames`` (indices, or ``"all"``) and stringer
    stiffeners on its stringers ``stringer_stiffeners`` (indices, or ``"all"``), of
    ``profile`` (:class:`~tubecad.stiffeners.profiles.Profile`: flat bar, T or L), on the
    wall's ``stiffener_side`` (``outside`` or ``inside``). Ring frames are solids of
    revolution whose base is the wall surface itself, stringers are swept with the
    rotation-minimising frame and start exactly on the wall; each passes BRepCheck and
    OCCT's pre-boolean check.

    The part holds the wall solid, then one solid per stiffener (they overlap the wall and
    each other where they cross, as separate parts of an assembly do; ``Mode.ADD`` in a
    ``BuildPart`` fuses them). ``stiffeners`` gives them, labelled ``ring_03``,
    ``stringer_05``, for every placed copy; ``rings`` and ``stringers`` stay the wall's.
    The other arguments are :class:`CurvatureWall`'s.

    Args:
        axis: the tube's axis: a tubecad Axis (any kind), a build123d or CadQuery Edge or
            Wire, a BuildLine or its edges, or (x, y, z) points (see ``CurvatureTube``).
        radius: a number, or a radius law r(s) (expression, callable, table): a canal surface.
        thickness: the wall's thickness (model units, > 0).
        ring_frames: the layout's rings that carry a ring frame: indices, or ``"all"``.
        stringer_stiffeners: the layout's stringers that carry a stiffener: indices, or ``"all"``.
        profile: the stiffeners' cross-section (a flat bar 10 x 1 when None).
        stiffener_side: the wall's side the stiffeners stand on: ``outside`` or ``inside``.
        side: where the wall stands: ``centered`` on the tube's surface, ``inside`` or ``outside`` it.
        rings: how many ring frames, equally spaced in arc length, or their arc lengths.
        stringers: how many stringers, equally spaced round, or their angles in degrees.
        tolerance: the fit's tolerance, in model units.
        bend_radius: for an axis given as points: the bends' radius (a pipe route).
        normal: for an axis given as points or an edge: the first stringer's direction at its start.
        closed: for an axis given as points or an edge: whether it closes on itself.
        allow_irregular: build even where the surface folds (refused by default).
        rotation: as for build123d's ``Box``.
        align: as for build123d's ``Box``; None (the default) keeps the part where its axis is.
        mode: as for build123d's ``Box`` (how it combines in a ``BuildPart``).
    """

    def __init__(
        self,
        axis: AxisLike,
        radius: RadiusLike,
        thickness: float,
        *,
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
        rotation: bd.RotationLike = (0, 0, 0),
        align: bd.Align | tuple[bd.Align, bd.Align, bd.Align] | None = None,
        mode: bd.Mode = bd.Mode.ADD,
    ) -> None:
        self._choice = (ring_frames, stringer_stiffeners, profile, stiffener_side)
        self.ring_frames, self.stringer_stiffeners = ring_frames, stringer_stiffeners
        self.profile, self.stiffener_side = profile if profile is not None else Profile(), stiffener_side
        super().__init__(
            axis,
            radius,
            thickness,
            side=side,
            rings=rings,
            stringers=stringers,
            tolerance=tolerance,
            bend_radius=bend_radius,
            normal=normal,
            closed=closed,
            allow_irregular=allow_irregular,
            rotation=rotation,
            align=align,
            mode=mode,
        )

    def _part(self, build: Any) -> bd.Part | bd.Solid:
        from tubecad.parts.engine import stiffener_solids

        made = stiffener_solids(self._tubecad.design, build, *self._choice)
        self._names = [name for name, _ in made]
        self._solid_names = ("wall", *self._names)
        wall = bd.Solid(build.shape.wrapped)
        wall.label = "wall"
        parts = [wall]
        for name, shape in made:
            solid = bd.Solid(shape)
            solid.label = name
            parts.append(solid)
        return bd.Part(bd.Compound(parts).wrapped)

    @property
    def stiffeners(self) -> bd.ShapeList[bd.Solid]:
        """The stiffener solids of every placed copy, labelled ``ring_03``, ``stringer_05``."""
        out = []
        solids = list(self.solids())
        for start in range(0, len(solids), self._solids_per_copy):
            for name, solid in zip(self._names, solids[start + 1 : start + self._solids_per_copy]):
                solid.label = name
                out.append(solid)
        return bd.ShapeList(out)
