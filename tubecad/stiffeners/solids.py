"""Stiffener solids standing on a wall along its curvature lines (issues 4 and 9).

One path for every wall surface (:func:`ring_stiffener`, :func:`stringer_stiffener`: the
checks, the closing ring, the names, the strips' assembly and the :class:`Stiffener`); the
tube (r = const) takes its fast path, described here, and a canal surface (a radius law) the
geometry of docs/MATH.md section 8.6 (:func:`.rings.canal_ring_solid`,
:func:`.canal.canal_stringer_strips`).

Ring frame at s_i: its cross-section, a polygon in the (s, r) half-plane (the profile's
web s_i -+ t/2 between radii R and R +- h, and a T or L flange), swept round the tube
(:mod:`.rings`): tube faces, planar annuli in the normal planes and circle edges, one
solid with no boolean. Its base *is* the wall surface, so it meets the wall with no gap.

Stringer at angle theta: the profile outline swept with the rotation-minimising frame,
P(w, v; s) = C(s) + v N(s) + w E(s) with N = cos th R1 + sin th R2 (the surface normal
along the line) and E = -sin th R1 + cos th R2. Each outline edge is a ruled B-spline
face whose poles are affine combinations of the frame spline's poles (as exact as the
wall). Its base is the wall surface patch between the angles th -+ asin(t / 2R), so the
web's side faces start exactly on the wall. The faces share their edges
(:func:`tubecad.brep.assembled.strip_solid`): nothing is sewn.

Every frame is fitted to the largest distance from the axis that the stiffener reaches
(:mod:`.limits`), and a stiffener too high for the wall's curvature is refused before that.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.Geom import Geom_BSplineSurface

from tubecad.brep.assembled import CapPlane, Strip, closed_strip_solid, strip_solid
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, orthogonality_for
from tubecad.fitting import FitError, exact_section_surface, fit_frame
from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals, reals_2d
from tubecad.occ_compat import copy_of
from tubecad.stiffeners.canal import canal_stringer_strips
from tubecad.stiffeners.limits import checked_levels, checked_reach, fit_failure
from tubecad.stiffeners.profiles import SIDES, Profile
from tubecad.stiffeners.rings import Section, ring_frame_solid
from tubecad.surface import CanalSurface, CurvatureLineTube
from tubecad.surface.protocol import CurvatureLineSurface


@dataclass
class Stiffener:
    """A named stiffener solid and what it stands on."""

    name: str  # ring_03, stringer_05
    kind: str  # ring | stringer
    value: float  # s of a ring, angle (deg) of a stringer
    solid: bd.Solid
    profile: Profile
    side: str
    #: the wall surface it stands on, over its own span: a tube, or a canal surface (then a
    #: stringer's ``value`` is its angle chi0 at the wall's start, in degrees)
    base: CurvatureLineSurface
    #: a ring cut at a branch's opening (:mod:`.junction`): the arc it keeps, (a, b) in degrees
    #: of the circle from r1 at the ring, counter-clockwise about t, b - a < 360; None: all round
    arc_deg: tuple[float, float] | None = None

    @property
    def base_radius(self) -> float:
        """R of a tube; on a canal surface the radius of the ring's characteristic circle
        (r q), or a stringer's mean r over its span."""
        if self.base.constant_radius:
            return self.base.radius_law.constant_value
        if self.kind == "ring":
            return float(self.base.circle(np.array([self.value]))[1][0])
        return float(np.mean(self.base.radius_law.r(np.linspace(*self.base.span, 257))))

    def length(self) -> float:
        """Length of its line on the wall: the ring's circle, 2 pi R (2 pi r q on a canal
        surface; a cut ring's arc, R (b - a)); Int sqrt(G) ds along u = angle for a stringer (Gauss-Legendre on the exact
        G, on 32 panels also cut at the axis' joints, where k may jump: a route's line-bend
        joints)."""
        if self.kind == "ring":
            turn = 2 * math.pi if self.arc_deg is None else math.radians(self.arc_deg[1] - self.arc_deg[0])
            return turn * self.base_radius
        x, w = np.polynomial.legendre.leggauss(32)
        s0, s1 = self.base.span
        edges = np.unique(
            np.concatenate([np.linspace(s0, s1, 33), [s for s, _ in self.base.axis.joints if s0 < s < s1]])
        )
        s = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * x).ravel()
        g = self.base.fundamental_forms(math.radians(self.value), s).G
        return float((np.sqrt(g) * np.tile(w, len(edges) - 1) * np.repeat(0.5 * np.diff(edges), 32)).sum())


def ring_stiffener(
    tube: CurvatureLineSurface,
    s: float,
    profile: Profile,
    side: str = "outside",
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    name: str = "ring",
) -> Stiffener:
    """The ring frame at ``s`` on the wall surface ``tube`` it stands on (a tube of radius
    R = tube.radius, or a canal surface): its cross-section swept round as one solid, clipped
    to the span (:func:`.rings.ring_frame_solid`). On a closed axis the ring at either end of
    the span is the closing ring: its halves at both ends, fused into one solid."""
    _check_side(side)
    base = tube.fast_path()  # a constant law's canal surface: the tube of that radius
    s0, s1 = base.span
    closing = base.axis.closed and min(abs(s - s0), abs(s - s1)) <= 1e-9 * (s1 - s0)
    # the closing ring of a closed tube or canal surface stands on both ends of the span: a half
    # at each (clipped there), which meet in the closing circle's normal cone (a plane where r' = 0)
    ends = (s0, s1) if closing else (s,)
    halves = [bd.Solid(ring_frame_solid(base, at, profile, side, tolerance, name)) for at in ends]
    solid = halves[0] if len(halves) == 1 else _fused(halves, name)
    if base.constant_radius:
        base = CurvatureLineTube(base.axis, base.radius_law.constant_value, allow_irregular=True)
    return Stiffener(name, "ring", float(ends[0]), solid, profile, side, base)


def _fused(halves: list[bd.Solid], name: str) -> bd.Solid:
    """The two halves of the closing ring (they meet in its plane) as one solid."""
    fused = halves[0].fuse(halves[1]).clean()
    solids = fused.solids()
    if len(solids) != 1:
        raise ParameterError(f"{name}: the halves of the closing ring did not fuse into one solid")
    return solids[0]


def stringer_stiffener(
    tube: CurvatureLineSurface,
    theta_deg: float,
    profile: Profile,
    side: str = "outside",
    span: tuple[float, float] | None = None,
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    name: str = "stringer",
) -> Stiffener:
    """The stringer at angle ``theta_deg`` on the wall surface ``tube`` it stands on, over
    ``span``: the outline's ruled faces and the wall under the web, one solid with shared
    edges (:func:`tubecad.brep.assembled.strip_solid`). On a tube of radius R = tube.radius
    (the fast path: :func:`_tube_stringer_strips`) on a frame fitted to the farthest corner;
    on a canal surface its angle is chi0 at the span's start, its corner curves fitted to
    the exact points (:func:`tubecad.stiffeners.canal.canal_stringer_strips`)."""
    _check_side(side)
    # the tube's fast path, or a canal surface's geometry: the surface calls back the one for its kind
    strips, (s0, s1), caps, cuts, corners, base = tube.dispatch(
        lambda exact: _tube_stringer_strips(exact, theta_deg, profile, side, span, tolerance, name),
        lambda exact: _canal_stringer_strips(exact, theta_deg, profile, side, span, tolerance, name),
    )
    # the outline runs counter-clockwise in (w, v), i.e. clockwise about the line's tangent
    # (+t on a tube: E x N = -t), when the stiffener stands outside; mirrored (inside) it
    # runs counter-clockwise
    ccw = _shoelace(corners) < 0
    if caps is None:  # a tube's stringer round a closed axis that closes on itself
        solid, _ = closed_strip_solid(strips, s0, s1, ccw, cuts)
    else:
        solid, _ = strip_solid(strips, s0, s1, (caps[0], caps[1]), ccw, cuts)
    return Stiffener(name, "stringer", float(theta_deg), bd.Solid(solid), profile, side, base)


#: what a stringer is made of: its strips, the span of its stations, its cap planes (None where it
#: closes on itself round a closed axis), the C0 cuts along s, the outline's corners, the wall it stands on
StringerParts = tuple[
    list[Strip], tuple[float, float], list[CapPlane] | None, list[float], Section, CurvatureLineSurface
]


def _canal_stringer_strips(
    base: CanalSurface,
    theta_deg: float,
    profile: Profile,
    side: str,
    span: tuple[float, float] | None,
    tolerance: float,
    name: str,
) -> StringerParts:
    """A canal surface's :func:`stringer_stiffener` (a varying law): (strips, span, cap planes,
    C0 cuts along s, the outline's corners (w, v off the wall), the wall it stands on), as
    :func:`_tube_stringer_strips` returns them; its angle is chi0 at the span's start."""
    sign = 1.0 if side == "outside" else -1.0
    if base.axis.closed and span is None:
        _clears_its_start(base, math.radians(theta_deg), profile, side, name)
    smallest = base.radius_law.min_radius
    if not profile.thickness < 2 * smallest:
        raise ParameterError(
            f"thickness must be < 2 r = {2 * smallest:g} (the wall's smallest radius, at s = "
            f"{base.radius_law.s_at_min_radius:.6g}), got {profile.thickness:g}"
        )
    checked_levels(base, sorted({sign * h for _, h in profile.outline()}), name)  # before anything is fitted
    try:
        strips, (s0, s1), caps, cuts, _ = canal_stringer_strips(
            base, math.radians(theta_deg), profile, side, span or base.span, tolerance
        )
    except FitError as exc:
        raise FitError(f"{name}: {exc}") from None
    corners = [(w, sign * v) for w, v in profile.outline()]
    return strips, (s0, s1), caps, cuts, corners, base


def _tube_stringer_strips(
    tube: CurvatureLineTube,
    theta_deg: float,
    profile: Profile,
    side: str,
    span: tuple[float, float] | None,
    tolerance: float,
    name: str,
) -> StringerParts:
    """The tube's fast path of :func:`stringer_stiffener`: (strips, span, cap planes or None
    where it closes on itself round a closed axis, C0 cuts along s, the outline's corners
    (w, distance from the axis), the wall it stands on)."""
    R, sign = tube.radius_law.constant_value, (1.0 if side == "outside" else -1.0)
    tw = profile.thickness
    if not tw < 2 * R:
        raise ParameterError(f"thickness must be < 2 R = {2 * R:g}, got {tw:g}")
    axis = tube.axis.restricted(span) if span else tube.axis
    s0, s1 = axis.span
    reach = checked_reach(axis, profile, R, side, "stringer")  # before anything is fitted
    try:
        frame = fit_frame(axis, reach, tolerance, orthogonality_for(tolerance))
    except FitError as exc:
        raise fit_failure(exc, name, axis, reach) from None
    theta = math.radians(theta_deg)
    delta = math.asin(tw / (2 * R))

    def radial(h: float) -> float:  # distance from the axis along N of an outline corner
        return R * math.cos(delta) if h == 0.0 else R + sign * h

    corners = [(w, radial(h)) for w, h in profile.outline()]
    strips = [Strip(ruled_surface(frame, theta, p, q), 0.0, 1.0) for p, q in zip(corners[:-1], corners[1:])]
    base_tube = CurvatureLineTube(axis, R, allow_irregular=True)
    base = exact_section_surface(base_tube, frame, origin_deg=math.degrees(theta - delta))
    u1 = float(base.u_at(math.degrees(theta + delta)))
    strips.append(Strip(surface_part(base.surface, 0.0, u1), 0.0, u1))
    cuts = [s for s, continuity in axis.joints if continuity == 0]  # e.g. a route's line-bend joints: faces end there
    caps = None if _closes_on_itself(axis, corners, name) else [cap_plane(frame, s0), cap_plane(frame, s1)]
    return strips, (s0, s1), caps, cuts, corners, base_tube


#: a stringer round a closed axis closes on itself when its section comes back within this
CLOSING_GAP = 1e-8


def _closes_on_itself(axis, corners: list[tuple[float, float]], name: str) -> bool:
    """Round a closed axis a stringer's section comes back turned by the holonomy h (its
    end at angle th + h on the closing ring, where it started at th). h = 0 (a planar loop):
    it closes on itself, no caps. Otherwise its end cap must clear its start cap: |h| must
    exceed the section's angular width as seen from the axis (else refused, named)."""
    if not axis.closed:
        return False
    turn = math.remainder(axis.holonomy, 2 * math.pi)
    reach = max(r for _, r in corners)
    if reach * abs(turn) <= CLOSING_GAP:
        return True
    angles = [math.atan2(w, r) for w, r in corners]
    width = max(angles) - min(angles)
    if abs(turn) <= width + 1e-9:
        raise ParameterError(
            f"{name} would touch its own start where the closed tube closes: the rotation-minimising "
            f"frame comes back turned by the holonomy {math.degrees(turn):.6g} deg, less than the "
            f"stringer's angular width {math.degrees(width):.6g} deg; leave it out or narrow the profile"
        )
    return False


def _clears_its_start(base: CurvatureLineSurface, chi0: float, profile: Profile, side: str, name: str) -> None:
    """Round a closed axis a canal wall's stringer leaving the closing circle at chi0 comes
    back to it at phi(chi0) (the Moebius map, :meth:`CanalSurface.closing_angle`), where its
    end cap must clear its start cap: |phi - chi0| must exceed the section's angular width
    on the circle of radius r q (a corner w across and v off the wall: atan2(|w|, q (r + v))),
    else refused, named. A stringer that closes on itself (phi = chi0) is not built on a
    canal wall yet (a tube's is: one solid, no caps)."""
    s0 = base.span[0]
    turn = math.remainder(float(base.closing_angle(chi0)) - chi0, 2 * math.pi)
    r, q = float(base.radius_law.r(s0)), math.sqrt(1.0 - float(base.radius_law.dr(s0)) ** 2)
    sign = 1.0 if side == "outside" else -1.0
    width = max(2.0 * math.atan2(abs(w), q * (r + sign * v)) for w, v in profile.outline())
    if abs(turn) <= width + 1e-9:
        raise ParameterError(
            f"{name} would touch its own start where the closed canal wall closes: it comes back "
            f"{math.degrees(turn):.6g} deg from where it started (the closing ring's Moebius map), less "
            f"than its angular width {math.degrees(width):.6g} deg; leave it out or narrow the profile"
        )


def cap_plane(frame, s: float) -> CapPlane:
    """The normal plane at ``s`` of the fitted frame: through C(s), spanned by R1(s), R2(s),
    in which every section s = const of the surfaces built on the frame lies exactly."""
    F = frame.values(s)
    c, r1, r2 = F[:3], F[3:6], F[6:]
    normal = np.cross(r1, r2)
    return CapPlane(c, normal / np.linalg.norm(normal), r1 / np.linalg.norm(r1))


def surface_part(surface: Geom_BSplineSurface, u0: float, u1: float) -> Geom_BSplineSurface:
    """The part u0 <= u <= u1 of a surface periodic in u, as a non-periodic B-spline (its
    isolines then have no knots outside the part)."""
    piece = copy_of(surface)
    _, _, v0, v1 = surface.Bounds()
    piece.Segment(u0, u1, v0, v1)
    return piece


def _shoelace(points: list[tuple[float, float]]) -> float:
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(points, points[1:] + points[:1]))


def ruled_surface(frame, theta: float, p: tuple[float, float], q: tuple[float, float]) -> Geom_BSplineSurface:
    """The ruled face from corner p = (w, v) to q in the cross-section plane, swept along s:
    poles C_j + v N_j + w E_j (degree 1 across, the frame spline's knots along s), with
    N = cos th R1 + sin th R2 and E = -sin th R1 + cos th R2."""
    F = frame.spline.c
    C, R1, R2 = F[:, :3], F[:, 3:6], F[:, 6:]
    N = math.cos(theta) * R1 + math.sin(theta) * R2
    E = -math.sin(theta) * R1 + math.cos(theta) * R2
    poles = np.stack([C + p[1] * N + p[0] * E, C + q[1] * N + q[0] * E])
    s_knots, s_mults = knots_and_multiplicities(frame.spline.t)
    if frame.weights is not None:  # a route's rational frame: the same weights along s
        return Geom_BSplineSurface(
            points_2d(poles),
            reals_2d(np.vstack([frame.weights, frame.weights])),
            reals([0.0, 1.0]),
            reals(s_knots),
            integers([2, 2]),
            integers(s_mults),
            1,
            frame.degree,
        )
    return Geom_BSplineSurface(
        points_2d(poles), reals([0.0, 1.0]), reals(s_knots), integers([2, 2]), integers(s_mults), 1, frame.degree
    )


def web_face(
    base: CurvatureLineTube,
    theta_deg: float,
    height: float,
    side: str = "outside",
    tolerance: float = DEFAULT_FIT_TOLERANCE,
) -> bd.Face:
    """The web's mid-surface along the stringer at ``theta_deg``: the strip of surface normals
    from the wall (radius R) to R +- height, a ruled B-spline face on the frame fit."""
    _check_side(side)
    R, sign = base.radius, (1.0 if side == "outside" else -1.0)
    reach = checked_reach(base.axis, Profile("flat", height, 1.0), R, side, "ring")  # max(R, R +- height)
    frame = fit_frame(base.axis, reach, tolerance, orthogonality_for(tolerance))
    surface = ruled_surface(frame, math.radians(theta_deg), (0.0, R), (0.0, R + sign * height))
    return bd.Face(BRepBuilderAPI_MakeFace(surface, 0.0, 1.0, *base.span, 1e-7).Face())


def _check_side(side: str) -> None:
    if side not in SIDES:
        raise ParameterError(f"side must be one of {', '.join(SIDES)}, got {side!r}")
