"""Shells and solids of curvature-line tubes (issue 3): the tube solid and the wall solid.

- tube shell: patch faces between ring frames and stringers (edges = those curvature lines);
- tube solid: the shell plus planar end discs in the normal planes at both ends;
- wall solid: outer and inner tubes (exact normal offsets rho +- d on one frame fit, so
  every inner edge has its outer twin) and annular end caps.

Each returns a :class:`TubeBuild` whose ``shape`` is a build123d Shell or Solid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import build123d as bd
import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepLib import BRepLib
from OCP.Geom import Geom_Plane
from OCP.BRepGProp import BRepGProp_Face
from OCP.BRepTools import BRepTools
from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Solid, TopoDS_Wire

from ..errors import ParameterError, RegularityError
from ..fitting import FrameSpline, TubeSurface, exact_section_surface, fit_frame
from ..fitting.tolerance import DEFAULT_TOLERANCE, MIN_SIZE, orthogonality_for  # noqa: F401  (re-exported)
from ..surface import CurvatureLineTube
from .assembled import closed_solid, shell_of
from .faces import TOLERANCE, PatchFaces, patch_faces
from .layout import NetLayout
from .wall import WALL_SIDES, wall_radii  # noqa: F401  (re-exported)

#: progress(step, done, total), called as a build advances (the library never prints)
Progress = Callable[[str, int, int], None]


@dataclass
class TubeBuild:
    """A built shape and what it was built from."""

    shape: bd.Shape
    surfaces: list[TubeSurface]  # outer first
    patches: list[PatchFaces]
    layout: NetLayout
    frame: FrameSpline
    tolerance: float
    radii: list[float] = field(default_factory=list)

    def ring_wires(self, surface: int = 0) -> list[bd.Wire]:
        """The ring frames (s = const) on surface ``surface`` (0 outer, 1 inner): closed wires."""
        return [bd.Wire([bd.Edge(e) for e in ring]) for ring in self.patches[surface].rings]

    def stringer_wires(self, surface: int = 0) -> list[bd.Wire]:
        """The stringers (u = const) on surface ``surface``, from the first ring to the last."""
        return [bd.Wire([bd.Edge(e) for e in col]) for col in self.patches[surface].stringers]

    def face_grid(self, surface: int = 0) -> list[list[bd.Face]]:
        """Faces [between rings i, i+1][between stringers j, j+1] of surface ``surface``."""
        return [[bd.Face(f) for f in row] for row in self.patches[surface].faces]


def _checked(tube: object, layout: object) -> NetLayout:
    """The arguments every builder shares: a tube, a layout (default equal), a buildable radius."""
    if not isinstance(tube, CurvatureLineTube):
        raise ParameterError(f"tube must be a CurvatureLineTube, got {type(tube).__name__}")
    if layout is None:
        layout = NetLayout.equal(tube)
    elif not isinstance(layout, NetLayout):
        raise ParameterError(f"layout must be a NetLayout (NetLayout.equal or NetLayout.explicit), got {type(layout).__name__}")
    s0, s1 = tube.span
    if not (math.isclose(layout.s_rings[0], s0, abs_tol=1e-9 * (s1 - s0))
            and math.isclose(layout.s_rings[-1], s1, abs_tol=1e-9 * (s1 - s0))):  # fmt: skip
        raise ParameterError(f"layout rings must run from the tube's span start {s0:g} to its end {s1:g}, got "
                             f"[{layout.s_rings[0]:g}, {layout.s_rings[-1]:g}] (a layout made for another tube?)")  # fmt: skip
    if tube.length < MIN_SIZE:
        raise ParameterError(f"the span must be at least {MIN_SIZE:g} model units long for a B-rep, got {tube.length:g}")
    if tube.radius < MIN_SIZE:
        raise ParameterError(f"radius must be >= {MIN_SIZE:g} model units for a B-rep (100 x OCCT's edge precision 1e-7), "
                             f"got {tube.radius:g}")  # fmt: skip
    if tube.axis.closed:
        if len(layout.s_rings) < 3:
            raise ParameterError("a closed tube needs a ring frame besides the closing one: rings must be >= 3")
        return layout
    ends = tube.axis.position(np.array(tube.span))
    gap = float(np.linalg.norm(ends[1] - ends[0]))
    if gap <= 1e-6 * tube.length:  # its end discs would coincide
        raise ParameterError(f"the axis' ends meet ({gap:.3g} apart) but it is not a closed loop (its tangents differ "
                             "there, or closed = false): the end caps would coincide; shorten the span")  # fmt: skip
    return layout


def build_tube_shell(tube: CurvatureLineTube, layout: NetLayout | None = None,
                     tolerance: float = DEFAULT_TOLERANCE) -> TubeBuild:  # fmt: skip
    """The tube's shell: faces between rings and stringers (open, or closed round a closed axis)."""
    layout = _checked(tube, layout)
    frame = fit_frame(tube.axis, tube.radius, tolerance, orthogonality_for(tolerance), rings=layout.s_rings)
    surface, patches = _tube_faces(tube, frame, layout)
    shell = shell_of(patches.all_faces(), closed=tube.axis.closed)
    return TubeBuild(bd.Shell(shell), [surface], [patches], layout, frame, tolerance, [tube.radius])


def build_tube_solid(tube: CurvatureLineTube, layout: NetLayout | None = None,
                     tolerance: float = DEFAULT_TOLERANCE, progress: Progress | None = None) -> TubeBuild:  # fmt: skip
    """The tube closed by planar discs in the normal planes at both ends (a closed axis:
    the closed tube, no caps). ``progress(step, done, total)`` is called after the frame
    fit, the surface and the solid."""
    report = progress or (lambda *_: None)
    layout = _checked(tube, layout)
    frame = fit_frame(tube.axis, tube.radius, tolerance, orthogonality_for(tolerance), rings=layout.s_rings)
    report("frame fit", 1, 3)
    surface, patches = _tube_faces(tube, frame, layout)
    report("surface", 2, 3)
    caps = [] if tube.axis.closed else [_cap(tube, layout.s_rings[0], [patches.rings[0]], outward=False),
                                        _cap(tube, layout.s_rings[-1], [patches.rings[-1]], outward=True)]  # fmt: skip
    solid = _solid([patches.all_faces() + caps], tube)
    report("solid", 3, 3)
    return TubeBuild(bd.Solid(solid), [surface], [patches], layout, frame, tolerance, [tube.radius])


def build_wall_solid(tube: CurvatureLineTube, thickness: float, side: str = "centered",
                     layout: NetLayout | None = None, tolerance: float = DEFAULT_TOLERANCE,
                     progress: Progress | None = None) -> TubeBuild:  # fmt: skip
    """The wall between the tubes of radii r_in < r_out on ``tube``'s axis, with annular caps
    (a closed axis: no caps; the solid is bounded by the two closed tubes, the inner one a
    cavity). ``progress(step, done, total)`` is called after the frame fit, each surface and
    the solid."""
    report = progress or (lambda *_: None)
    layout = _checked(tube, layout)
    r_in, r_out = wall_radii(tube.radius, thickness, side)
    try:
        outer_tube, inner_tube = CurvatureLineTube(tube.axis, r_out), CurvatureLineTube(tube.axis, r_in)
    except RegularityError as exc:
        raise RegularityError(f"thickness {float(thickness):g} (side = {side!r}) gives a wall between radii {r_in:g} "
                              f"and {r_out:g}: {exc}") from None  # fmt: skip
    frame = fit_frame(tube.axis, r_out, tolerance, orthogonality_for(tolerance), rings=layout.s_rings,
                      radii=(r_out, r_in))  # fmt: skip
    report("frame fit", 1, 4)
    outer, outer_patches = _tube_faces(outer_tube, frame, layout)
    report("outer surface", 2, 4)
    inner, inner_patches = _tube_faces(inner_tube, frame, layout, reverse=True)
    report("inner surface", 3, 4)
    if tube.axis.closed:
        shells = [outer_patches.all_faces(), inner_patches.all_faces()]
    else:
        shells = [outer_patches.all_faces() + inner_patches.all_faces() + [
            _cap(tube, layout.s_rings[0], [outer_patches.rings[0], inner_patches.rings[0]], outward=False),
            _cap(tube, layout.s_rings[-1], [outer_patches.rings[-1], inner_patches.rings[-1]], outward=True),
        ]]  # fmt: skip
    solid = _solid(shells, tube)
    report("solid", 4, 4)
    return TubeBuild(bd.Solid(solid), [outer, inner], [outer_patches, inner_patches], layout, frame, tolerance,
                     [r_out, r_in])  # fmt: skip


def tube_shell(tube: CurvatureLineTube, layout: NetLayout | None = None, tolerance: float = DEFAULT_TOLERANCE) -> bd.Shell:
    """build123d Shell of the tube (see :func:`build_tube_shell`)."""
    return build_tube_shell(tube, layout, tolerance).shape


def tube_solid(tube: CurvatureLineTube, layout: NetLayout | None = None, tolerance: float = DEFAULT_TOLERANCE) -> bd.Solid:
    """build123d Solid of the capped tube (see :func:`build_tube_solid`)."""
    return build_tube_solid(tube, layout, tolerance).shape


def wall_solid(tube: CurvatureLineTube, thickness: float, side: str = "centered", layout: NetLayout | None = None,
               tolerance: float = DEFAULT_TOLERANCE) -> bd.Solid:  # fmt: skip
    """build123d Solid of the wall (see :func:`build_wall_solid`)."""
    return build_wall_solid(tube, thickness, side, layout, tolerance).shape


# --- construction ------------------------------------------------------------------------
def _tube_faces(tube: CurvatureLineTube, frame: FrameSpline, layout: NetLayout,
                reverse: bool = False) -> tuple[TubeSurface, PatchFaces]:  # fmt: skip
    surface = exact_section_surface(tube, frame, stringers_deg=layout.stringers_deg)
    closing = tube.axis.holonomy if tube.axis.closed else None
    return surface, patch_faces(surface, list(layout.s_rings), layout.stringers_deg, reverse=reverse, closing=closing)


def _cap(tube: CurvatureLineTube, s: float, rings: list[list[TopoDS_Edge]], outward: bool) -> TopoDS_Face:
    """Planar face in the normal plane at ``s`` bounded by ``rings`` (outer first, then the hole);
    its normal is +t at the end of the tube (``outward``) and -t at the start."""
    builder = BRep_Builder()
    a = tube.axis.at(np.array([s]))
    centre, t, n = a.position[0], a.t[0], a.r1[0]
    normal = t if outward else -t
    plane = Geom_Plane(gp_Ax3(gp_Pnt(*centre), gp_Dir(*normal), gp_Dir(*n)))
    face = TopoDS_Face()
    builder.MakeFace(face, plane, TOLERANCE)
    for k, edges in enumerate(rings):
        # Ring edges run along +u, counter-clockwise about +t. The outer wire must run
        # counter-clockwise about the face normal and a hole clockwise.
        forward = outward == (k == 0)
        wire = TopoDS_Wire()
        builder.MakeWire(wire)
        for edge in edges if forward else edges[::-1]:
            builder.Add(wire, edge.Oriented(TopAbs_FORWARD if forward else TopAbs_REVERSED))
            BRepLib.BuildPCurveForEdgeOnPlane_s(edge, face)
        wire.Closed(True)
        builder.Add(face, wire)
    return face


def _solid(shells: list[list[TopoDS_Face]], tube: CurvatureLineTube) -> TopoDS_Solid:
    """The solid bounded by closed shells of faces (the first face an outer tube face; a
    closed wall's second shell bounds its cavity).

    The faces are oriented by construction (outer normal S_u x S_s points away from the
    axis); one normal is checked. OCCT's general OrientClosedSolid classifies a point by
    ray casting through every face (over half the build time of a 10,000-face wall), so
    it is only the fallback.
    """
    solid = closed_solid(*shells)
    if not _points_away_from_axis(shells[0][0], tube):
        BRepLib.OrientClosedSolid_s(solid)
    return solid


def _points_away_from_axis(face: TopoDS_Face, tube: CurvatureLineTube) -> bool:
    """Does the face's normal (as oriented in the face) point away from the axis at its middle?"""
    u0, u1, s0, s1 = BRepTools.UVBounds_s(face)
    point, normal = gp_Pnt(), gp_Vec()
    BRepGProp_Face(face).Normal(0.5 * (u0 + u1), 0.5 * (s0 + s1), point, normal)
    centre = tube.axis.position(np.array([0.5 * (s0 + s1)]))[0]
    return normal.Dot(gp_Vec(*(np.array([point.X(), point.Y(), point.Z()]) - centre))) > 0


def exact_volume(build: TubeBuild, tube: CurvatureLineTube) -> float:
    """pi (r_out^2 - r_in^2) L for a wall, pi rho^2 L for a tube solid (docs/MATH.md section 4)."""
    radii = build.radii
    return math.pi * (radii[0] ** 2 - (radii[1] ** 2 if len(radii) > 1 else 0.0)) * tube.length
