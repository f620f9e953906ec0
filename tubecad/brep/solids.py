"""Shells and solids of curvature-line tubes (issue 3): the tube solid and the wall solid.

- tube shell: patch faces between ring frames and stringers (edges = those curvature lines);
- tube solid: the shell plus planar end discs in the normal planes at both ends;
- wall solid: outer and inner tubes (exact normal offsets rho +- d on one frame fit, so
  every inner edge has its outer twin) and annular end caps.

Each also takes a :class:`~tubecad.surface.CanalSurface` (a radius law r(s); docs/MATH.md
section 8): its surfaces are fitted by :mod:`..fitting.canal_section` (one
spline for the surface and all its offsets r + d), its rings are the exact characteristic
circles, the tube solid's caps are planar discs in the end circles' planes, and the wall's
caps are pieces of the cones through the end circles of r + d_in and r + d_out (the sphere
normals along an end circle meet at the axis point c(s_end); a plane annulus where r' = 0
there). On a closed axis (the law closes: r and r' at the end equal those at the start)
there are no caps, as for the tube: the shell is closed, the solid bounded by it and the
wall by two closed shells, the inner one its cavity; the stringers come back to the closing
ring moved by a Moebius map (:meth:`CanalSurface.closing_angle`), and the closing ring is
cut at their starts and their ends (:func:`.faces._closing_ring`). A CanalSurface whose law
is constant is built as the tube of that radius.

Each returns a :class:`TubeBuild` whose ``shape`` is a build123d Shell or Solid.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import build123d as bd
import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepGProp import BRepGProp_Face
from OCP.BRepLib import BRepLib
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_ConicalSurface, Geom_Plane
from OCP.Geom2d import Geom2d_Line
from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Solid, TopoDS_Wire

from tubecad.brep.assembled import closed_solid, shell_of
from tubecad.brep.faces import TOLERANCE, PatchFaces, _edge, patch_faces
from tubecad.brep.layout import NetLayout
from tubecad.brep.wall import WALL_SIDES, wall_offsets, wall_radii  # noqa: F401  (re-exported)
from tubecad.core.errors import ParameterError, RegularityError
from tubecad.core.tolerance import DEFAULT_TOLERANCE, MIN_SIZE, orthogonality_for  # re-exported
from tubecad.fitting import FrameSpline, TubeSurface, exact_section_surface, fit_frame
from tubecad.fitting.canal_section import CanalSpline, canal_section_surface, fit_canal
from tubecad.occ_compat import as_face
from tubecad.surface import CanalSurface, CurvatureLineSurface, CurvatureLineTube, is_surface

#: progress(step, done, total), called as a build advances (the library never prints)
Progress = Callable[[str, int, int], None]


@dataclass
class TubeBuild:
    """A built shape and what it was built from.

    For a canal surface ``frame`` is its :class:`~tubecad.fitting.canal_section.CanalSpline`,
    each of ``surfaces`` a :class:`~tubecad.fitting.canal_section.CanalSectionSurface` whose
    ``tube`` is the exact canal surface it approximates (r + d), and ``radii`` holds the mean
    radius over the span (arc-length average of r + d) of each surface, outer first."""

    shape: bd.Shape
    surfaces: list[TubeSurface]  # outer first
    patches: list[PatchFaces]
    layout: NetLayout
    frame: FrameSpline | CanalSpline
    tolerance: float
    radii: list[float] = field(default_factory=list)
    #: a constant radius' frame fit (the same as ``frame``), on which any radius' exact-section
    #: surface is built (a panel's refit: tubecad.stiffeners.panels); None for a canal surface
    section_frame: FrameSpline | None = None

    def ring_wires(self, surface: int = 0) -> list[bd.Wire]:
        """The ring frames (s = const) on surface ``surface`` (0 outer, 1 inner): closed wires."""
        return [bd.Wire([bd.Edge(e) for e in ring]) for ring in self.patches[surface].rings]

    def stringer_wires(self, surface: int = 0) -> list[bd.Wire]:
        """The stringers (u = const) on surface ``surface``, from the first ring to the last."""
        return [bd.Wire([bd.Edge(e) for e in col]) for col in self.patches[surface].stringers]

    def face_grid(self, surface: int = 0) -> list[list[bd.Face]]:
        """Faces [between rings i, i+1][between stringers j, j+1] of surface ``surface``."""
        return [[bd.Face(f) for f in row] for row in self.patches[surface].faces]


def _as_tube(tube: CurvatureLineSurface) -> CurvatureLineSurface:
    """A surface in the form that takes the fast path (a CanalSurface of a constant law as the
    tube of that radius: :meth:`~tubecad.surface.CurvatureLineSurface.fast_path`), else ``tube``."""
    return tube.fast_path() if is_surface(tube) else tube


def _checked(tube: object, layout: NetLayout | None) -> NetLayout:
    """The arguments every builder shares: a tube (or a canal surface), a layout (default
    equal), a buildable radius."""
    if not is_surface(tube):
        raise ParameterError(f"tube must be a CurvatureLineTube or a CanalSurface, got {type(tube).__name__}")
    if layout is None:
        layout = NetLayout.equal(tube)
    elif not isinstance(layout, NetLayout):
        raise ParameterError(
            f"layout must be a NetLayout (NetLayout.equal or NetLayout.explicit), got {type(layout).__name__}"
        )
    s0, s1 = tube.span
    if not (
        math.isclose(layout.s_rings[0], s0, abs_tol=1e-9 * (s1 - s0))
        and math.isclose(layout.s_rings[-1], s1, abs_tol=1e-9 * (s1 - s0))
    ):
        raise ParameterError(
            f"layout rings must run from the tube's span start {s0:g} to its end {s1:g}, got "
            f"[{layout.s_rings[0]:g}, {layout.s_rings[-1]:g}] (a layout made for another tube?)"
        )
    if tube.length < MIN_SIZE:
        raise ParameterError(
            f"the span must be at least {MIN_SIZE:g} model units long for a B-rep, got {tube.length:g}"
        )
    law = tube.radius_law
    if law.min_radius < MIN_SIZE:
        if tube.constant_radius:
            raise ParameterError(
                f"radius must be >= {MIN_SIZE:g} model units for a B-rep (100 x OCCT's edge precision 1e-7), "
                f"got {law.min_radius:g}"
            )
        raise ParameterError(
            f"radius: r must stay >= {MIN_SIZE:g} model units for a B-rep (100 x OCCT's edge "
            f"precision 1e-7), got {law.min_radius:g} at s = {law.s_at_min_radius:g}"
        )
    if tube.axis.closed:
        law.check_closes()  # (checked when the CanalSurface was made; a law made elsewhere is checked here)
        if len(layout.s_rings) < 3:
            raise ParameterError(
                "a closed tube needs a ring frame besides the closing one: rings must be >= 2 (s_rings: one arc length inside the span)"
            )
        return layout
    ends = tube.axis.position(np.array(tube.span))
    gap = float(np.linalg.norm(ends[1] - ends[0]))
    if gap <= 1e-6 * tube.length:  # its end discs would coincide
        raise ParameterError(
            f"the axis' ends meet ({gap:.3g} apart) but it is not a closed loop (its tangents differ "
            "there, or closed = false): the end caps would coincide; shorten the span"
        )
    return layout


def build_tube_shell(
    tube: CurvatureLineSurface, layout: NetLayout | None = None, tolerance: float = DEFAULT_TOLERANCE
) -> TubeBuild:
    """The tube's shell: faces between rings and stringers (open, or closed round a closed axis)."""
    tube = _as_tube(tube)
    layout = _checked(tube, layout)
    fit, section_frame, built = _surfaces(tube, (0.0,), [tube], layout, tolerance)
    ((surface, patches),) = built
    shell = shell_of(patches.all_faces(), closed=tube.axis.closed)
    return TubeBuild(
        bd.Shell(shell), [surface], [patches], layout, fit, tolerance, _radii(tube, [surface]), section_frame
    )


def build_tube_solid(
    tube: CurvatureLineSurface,
    layout: NetLayout | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    progress: Progress | None = None,
) -> TubeBuild:
    """The tube closed by planar discs in the normal planes at both ends (a closed axis:
    the closed tube, no caps). ``progress(step, done, total)`` is called after the frame
    fit, the surface and the solid."""
    report = progress or (lambda *_: None)
    tube = _as_tube(tube)
    layout = _checked(tube, layout)
    done = iter(range(1, 3))
    fit, section_frame, built = _surfaces(
        tube, (0.0,), [tube], layout, tolerance, lambda step: report(step, next(done), 3)
    )
    ((surface, patches),) = built
    caps = [] if tube.axis.closed else [_end_cap(tube, built, k, layout.s_rings[k]) for k in (0, -1)]
    solid = _solid([patches.all_faces() + caps], tube)
    report("solid", 3, 3)
    return TubeBuild(
        bd.Solid(solid), [surface], [patches], layout, fit, tolerance, _radii(tube, [surface]), section_frame
    )


def build_wall_solid(
    tube: CurvatureLineSurface,
    thickness: float,
    side: str = "centered",
    layout: NetLayout | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    progress: Progress | None = None,
) -> TubeBuild:
    """The wall between the tubes of radii r_in < r_out on ``tube``'s axis, with annular caps
    (a closed axis: no caps; the solid is bounded by the two closed tubes, the inner one a
    cavity). ``progress(step, done, total)`` is called after the frame fit, each surface and
    the solid. A canal surface's wall lies between the canal surfaces of r + d_in and
    r + d_out (:func:`~.wall.wall_offsets`), with conical caps (see the module)."""
    report = progress or (lambda *_: None)
    tube = _as_tube(tube)
    layout = _checked(tube, layout)
    offsets, exact = _wall_surfaces(tube, thickness, side)
    done = iter(range(1, 4))
    fit, section_frame, built = _surfaces(
        tube, offsets, exact, layout, tolerance, lambda step: report(step, next(done), 4)
    )
    (outer, outer_patches), (inner, inner_patches) = built
    if tube.axis.closed:  # no caps: the outer closed shell and the inner one, its cavity
        shells = [outer_patches.all_faces(), inner_patches.all_faces()]
    else:
        caps = [_end_cap(tube, built, k, layout.s_rings[k]) for k in (0, -1)]
        shells = [outer_patches.all_faces() + inner_patches.all_faces() + caps]
    solid = _solid(shells, tube)
    report("solid", 4, 4)
    return TubeBuild(
        bd.Solid(solid),
        [outer, inner],
        [outer_patches, inner_patches],
        layout,
        fit,
        tolerance,
        _radii(tube, [outer, inner]),
        section_frame,
    )


def tube_shell(
    tube: CurvatureLineTube, layout: NetLayout | None = None, tolerance: float = DEFAULT_TOLERANCE
) -> bd.Shell:
    """build123d Shell of the tube (see :func:`build_tube_shell`)."""
    return build_tube_shell(tube, layout, tolerance).shape


def tube_solid(
    tube: CurvatureLineTube, layout: NetLayout | None = None, tolerance: float = DEFAULT_TOLERANCE
) -> bd.Solid:
    """build123d Solid of the capped tube (see :func:`build_tube_solid`)."""
    return build_tube_solid(tube, layout, tolerance).shape


def wall_solid(
    tube: CurvatureLineTube,
    thickness: float,
    side: str = "centered",
    layout: NetLayout | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
) -> bd.Solid:
    """build123d Solid of the wall (see :func:`build_wall_solid`)."""
    return build_wall_solid(tube, thickness, side, layout, tolerance).shape


# --- construction: one path, the tube's fast path chosen here -----------------------------
def _surfaces(
    tube: CurvatureLineSurface,
    offsets: tuple[float, ...],
    exact: list[CurvatureLineSurface],
    layout: NetLayout,
    tolerance: float,
    step: Callable[[str], None] = lambda _: None,
) -> tuple[FrameSpline | CanalSpline, FrameSpline | None, list[tuple[TubeSurface, PatchFaces]]]:
    """Fit ``tube`` once for all the surfaces ``exact`` (its normal offsets by ``offsets``,
    outer first) and build the patch faces of each (the second reversed, the inner wall of a
    solid), calling ``step(name)`` after the fit and each surface. Returns the fit, the
    tube's frame fit again (None for a canal surface: :attr:`TubeBuild.section_frame`) and
    each surface with its faces.

    The one place the fit is chosen: a constant radius takes the tube's fast path, the
    9-component frame F = (c, rho r1, rho r2) fitted for the largest radius (every surface
    the exact-section tube of its radius on it, :func:`~tubecad.fitting.fit_frame`); a
    radius law the 21-component spline of the canal surface, one for all r + d
    (:func:`~tubecad.fitting.canal_section.fit_canal`)."""
    orthogonality = orthogonality_for(tolerance)
    fit: FrameSpline | CanalSpline
    section_frame: FrameSpline | None = None
    if tube.constant_radius:
        radii = tuple(e.radius_law.constant_value for e in exact)
        extra: dict[str, Any] = {"radii": radii} if len(radii) > 1 else {}
        frame = fit = section_frame = fit_frame(
            tube.axis, radii[0], tolerance, orthogonality, rings=layout.s_rings, **extra
        )

        def section(k: int) -> TubeSurface:
            # a constant radius: the surfaces are tubes (fast_path, _wall_surfaces)
            return exact_section_surface(exact[k], frame, stringers_deg=layout.stringers_deg)

    else:
        spline = fit = fit_canal(tube, offsets, tolerance, orthogonality, rings=layout.s_rings)

        def section(k: int) -> TubeSurface:
            return canal_section_surface(tube, spline, offsets[k], layout.stringers_deg, exact[k])

    step("frame fit")
    names = ("surface",) if len(offsets) == 1 else ("outer surface", "inner surface")
    closing = tube.axis.holonomy if tube.axis.closed else None
    built = []
    for k in range(len(offsets)):
        surface = section(k)
        built.append(
            (surface, patch_faces(surface, list(layout.s_rings), layout.stringers_deg, reverse=k > 0, closing=closing))
        )
        step(names[k])
    return fit, section_frame, built


def _wall_surfaces(
    tube: CurvatureLineSurface, thickness: float, side: str
) -> tuple[tuple[float, float], list[CurvatureLineSurface]]:
    """((d_out, d_in), [outer, inner]): the offsets of a wall of ``thickness`` placed ``side``
    (:func:`~.wall.wall_offsets`) and its two exact surfaces, each checked (a tube: its radii
    by :func:`~.wall.wall_radii` and both tubes regular; a canal surface: r + d_in >= MIN_SIZE
    and both offsets regular, allowed irregular if the surface itself was)."""
    d_in, d_out = wall_offsets(thickness, side)
    law = tube.radius_law
    if tube.constant_radius:
        r_in, r_out = wall_radii(law.constant_value, thickness, side)
        try:
            return (d_out, d_in), [CurvatureLineTube(tube.axis, r_out), CurvatureLineTube(tube.axis, r_in)]
        except RegularityError as exc:
            raise RegularityError(
                f"thickness {float(thickness):g} (side = {side!r}) gives a wall between radii {r_in:g} and "
                f"{r_out:g}: {exc}"
            ) from None
    if law.min_radius + d_in < MIN_SIZE:  # (side centered or inside)
        limit = 2 * law.min_radius if side == "centered" else law.min_radius
        raise ParameterError(
            f"thickness must be < {limit:g} for side = {side!r} (the radius law's smallest r is "
            f"{law.min_radius:g} at s = {law.s_at_min_radius:g}; the inner surface's r must stay >= "
            f"{MIN_SIZE:g}), got {float(thickness):g}"
        )
    try:  # a surface built with allow_irregular=True has its offsets allowed too
        exact = [tube if d == 0.0 else tube.offset(d, allow_irregular=not tube.regularity.ok) for d in (d_out, d_in)]
    except RegularityError as exc:
        raise RegularityError(
            f"thickness {float(thickness):g} (side = {side!r}) gives a wall between the canal "
            f"surfaces of r {d_in:+g} and r {d_out:+g}: {exc}"
        ) from None
    return (d_out, d_in), exact


def _end_cap(tube: CurvatureLineSurface, built: list[tuple[TubeSurface, PatchFaces]], k: int, s: float) -> TopoDS_Face:
    """The cap at ring ``k`` (0 the start, -1 the end, where its normal is +t) of the surfaces
    ``built`` (one: a disc; two: a wall's annulus): in the normal plane at ``s`` (x along
    r1) on a tube; on a canal surface the disc of the end circle or the piece of the normal
    cone through the wall's two end circles (:func:`_canal_cap`)."""
    outward = k == -1
    if tube.constant_radius:
        return _cap(tube, s, [patches.rings[k] for _, patches in built], outward)
    (outer, outer_patches), *rest = built
    inner = (rest[0][0], rest[0][1].rings[k]) if rest else None
    return _canal_cap(outer, s, outer_patches.rings[k], inner, outward)


def _radii(tube: CurvatureLineSurface, surfaces: list[TubeSurface]) -> list[float]:
    """Each surface's radius (a tube's rho), or a canal surface's mean r + d over the span."""
    if tube.constant_radius:
        return [surface.tube.radius_law.constant_value for surface in surfaces]
    return [_mean_radius(surface.tube) for surface in surfaces]


def _cap(tube: CurvatureLineSurface, s: float, rings: list[list[TopoDS_Edge]], outward: bool) -> TopoDS_Face:
    """Planar face in the normal plane at ``s`` bounded by ``rings`` (outer first, then the hole);
    its normal is +t at the end of the tube (``outward``) and -t at the start."""
    a = tube.axis.at(np.array([s]))
    return _plane_cap(a.position[0], a.t[0], a.r1[0], rings, outward)


def _plane_cap(
    centre: np.ndarray, t: np.ndarray, x_dir: np.ndarray, rings: list[list[TopoDS_Edge]], outward: bool
) -> TopoDS_Face:
    """The planar face through ``centre`` normal to ``t`` bounded by ``rings`` (outer first, then
    the hole), its normal +t (``outward``) or -t."""
    builder = BRep_Builder()
    normal = t if outward else -t
    plane = Geom_Plane(gp_Ax3(gp_Pnt(*map(float, centre)), gp_Dir(*map(float, normal)), gp_Dir(*map(float, x_dir))))
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


def _solid(shells: list[list[TopoDS_Face]], tube: CurvatureLineSurface) -> TopoDS_Solid:
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


def _points_away_from_axis(face: TopoDS_Face, tube: CurvatureLineSurface) -> bool:
    """Does the face's normal (as oriented in the face) point away from the axis at its middle?"""
    u0, u1, s0, s1 = BRepTools.UVBounds_s(face)
    point, normal = gp_Pnt(), gp_Vec()
    BRepGProp_Face(face).Normal(0.5 * (u0 + u1), 0.5 * (s0 + s1), point, normal)
    centre = tube.axis.position(np.array([0.5 * (s0 + s1)]))[0]
    return normal.Dot(gp_Vec(*(np.array([point.X(), point.Y(), point.Z()]) - centre))) > 0


def exact_volume(build: TubeBuild, tube: CurvatureLineSurface) -> float:
    """pi (r_out^2 - r_in^2) L for a wall, pi rho^2 L for a tube solid (docs/MATH.md section 4).

    A canal surface: the volume its surface encloses with the discs of its end circles
    (:attr:`CanalSurface.volume`, a quadrature); a wall's is the outer's minus the inner's,
    corrected at each end by the cone frustum between the two end circles that the conical
    cap adds (r' > 0 at the last end: the outer disc lies behind the inner one) or cuts off.
    On a closed axis (no caps, the end discs coincide) a canal surface encloses
    V = pi Int (r q)^2 (q^2 - r r'') ds round the loop (:meth:`CanalSurface.swept_measures`:
    the characteristic discs swept), and a wall V(r + d_out) - V(r + d_in)."""
    if not tube.constant_radius:
        exact = [surface.tube for surface in build.surfaces]
        enclosed = [_enclosed_volume(surface) for surface in exact]
        volume = enclosed[0] - (enclosed[1] if len(exact) > 1 else 0.0)
        if tube.axis.closed:
            return volume
        if len(exact) > 1:
            for k, sign in ((0, -1.0), (1, 1.0)):
                s = np.array([tube.span[k]])
                (_, r_out, _), (_, r_in, _) = exact[0].circle(s), exact[1].circle(s)
                offset = float(exact[0].radius_law.r(s)[0] - exact[1].radius_law.r(s)[0])
                dr = float(tube.radius_law.dr(s)[0])
                h = abs(dr) * offset  # the distance of the end circles' planes
                R1, R2 = float(r_out[0]), float(r_in[0])
                volume += sign * math.copysign(1.0, dr) * math.pi * h * (R1 * R1 + R1 * R2 + R2 * R2) / 3.0
        return volume
    radii = build.radii
    return math.pi * (radii[0] ** 2 - (radii[1] ** 2 if len(radii) > 1 else 0.0)) * tube.length


def _enclosed_volume(surface: CurvatureLineSurface) -> float:
    """The volume ``surface`` encloses with the discs of its end circles: a tube's pi rho^2 L;
    a canal surface's :attr:`CanalSurface.volume` (a quadrature), or round a closed axis the
    characteristic discs swept (:meth:`CanalSurface.swept_measures`)."""

    def canal(exact: CanalSurface) -> float:
        return exact.swept_measures()[1] if exact.axis.closed else exact.volume

    return surface.dispatch(lambda exact: exact.volume_exact, canal)


# --- canal surfaces ----------------------------------------------------------------------
def _mean_radius(canal: CurvatureLineSurface) -> float:
    """The arc-length mean of r(s) over the span (Gauss-Legendre panels)."""
    s0, s1 = canal.span
    x, w = np.polynomial.legendre.leggauss(16)
    edges = np.linspace(s0, s1, 65)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    s = (mid[:, None] + half[:, None] * x).ravel()
    return float((canal.radius_law.r(s) * (half[:, None] * w).ravel()).sum() / (s1 - s0))


#: below this |r'| at an end a wall's cap is the plane annulus (the cone would be within
#: |r'| thickness of it, far below the edge tolerance)
FLAT_CAP_SLOPE = 1e-12


def _canal_cap(outer, s: float, outer_ring: list[TopoDS_Edge], inner: tuple | None, outward: bool) -> TopoDS_Face:
    """The cap at ``s`` of a canal surface's solid: the planar disc of the end circle of
    ``outer`` (a CanalSectionSurface), or with ``inner`` (its inner surface and ring edges)
    the piece of the normal cone through both end circles (:func:`normal_cone_face`)."""
    if inner is None:
        centre, _, t, x_dir, _ = outer.ring(s)
        return _plane_cap(centre, t, x_dir, [outer_ring], outward)
    return normal_cone_face(s, inner[0], inner[1], outer, outer_ring, outward)


def normal_cone_face(
    s: float, low, low_ring: list[TopoDS_Edge], high, high_ring: list[TopoDS_Edge], outward: bool
) -> TopoDS_Face:
    """The face between the circles at ``s`` of two offsets of one canal surface, ``low`` of
    the smaller law and ``high`` (CanalSectionSurfaces with the same origin stringer, their
    ring edges ``low_ring``/``high_ring`` from it along +theta): the piece of the normal cone
    through both (the plane annulus where r' = 0), its normal along +t when ``outward``.

    The cone has its apex at c(s): a circle of r + d lies on it at distance r + d from
    the apex along the generator n = -r' t + q e (the sphere normal). Placed at the low
    circle (centre C_lo, radius R_lo, axis +t, x direction the origin stringer's, so its u is
    the rings' angle theta) with semi-angle a = k atan2(q, |r'|) and v = k (r_high - r_low),
    k = -sign(r'), its v-isolines are the two circles exactly."""
    centre, _, t, x_dir, _ = high.ring(s)
    dr = float(high.tube.radius_law.dr(np.array([s]))[0])
    if abs(dr) <= FLAT_CAP_SLOPE:
        return _plane_cap(centre, t, x_dir, [high_ring, low_ring], outward)
    builder = BRep_Builder()
    face = TopoDS_Face()
    c_lo, radius_lo, _, _, _ = low.ring(s)
    r_high = float(high.tube.radius_law.r(np.array([s]))[0])
    r_low = float(low.tube.radius_law.r(np.array([s]))[0])
    q = math.sqrt(1.0 - dr * dr)
    k = -math.copysign(1.0, dr)
    cone = Geom_ConicalSurface(
        gp_Ax3(gp_Pnt(*map(float, c_lo)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))),
        k * math.atan2(q, abs(dr)),
        radius_lo,
    )
    builder.MakeFace(face, cone, TOLERANCE)
    v_high = k * (r_high - r_low)
    (first, v_first), (second, v_second) = (
        ((low_ring, 0.0), (high_ring, v_high)) if v_high > 0 else ((high_ring, v_high), (low_ring, 0.0))
    )
    # a seam along the generator u = 0 (OCCT wants one on a closed surface): from the lower
    # circle's point at theta = 0 (the origin stringer's vertex) to the upper one's
    seam = _edge(cone.UIso(0.0), TopExp.FirstVertex_s(first[0]), TopExp.FirstVertex_s(second[0]), v_first, v_second)
    wire = TopoDS_Wire()
    builder.MakeWire(wire)  # counter-clockwise in (u, v): the lower circle along +u, the seam up, the upper back
    for edge in first:
        builder.UpdateEdge(
            edge, Geom2d_Line(gp_Pnt2d(0.0, v_first), gp_Dir2d(1.0, 0.0)), face, BRep_Tool.Tolerance_s(edge)
        )
        builder.Add(wire, edge.Oriented(TopAbs_FORWARD))
    builder.UpdateEdge(
        seam,
        Geom2d_Line(gp_Pnt2d(2.0 * math.pi, 0.0), gp_Dir2d(0.0, 1.0)),
        Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(0.0, 1.0)),
        face,
        TOLERANCE,
    )
    builder.Add(wire, seam.Oriented(TopAbs_FORWARD))
    for edge in second[::-1]:
        builder.UpdateEdge(
            edge, Geom2d_Line(gp_Pnt2d(0.0, v_second), gp_Dir2d(1.0, 0.0)), face, BRep_Tool.Tolerance_s(edge)
        )
        builder.Add(wire, edge.Oriented(TopAbs_REVERSED))
    builder.Add(wire, seam.Oriented(TopAbs_REVERSED))
    wire.Closed(True)
    builder.Add(face, wire)
    point, normal = gp_Pnt(), gp_Vec()  # the cone's own normal is sign(r') m, m = q t + r' e the stringers'
    BRepGProp_Face(face).Normal(0.5 * math.pi, 0.5 * v_high, point, normal)
    pointing_out = normal.Dot(gp_Vec(*map(float, t))) > 0
    return face if pointing_out == outward else as_face(face.Reversed())
