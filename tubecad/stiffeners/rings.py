"""Ring frames as solids of revolution about their ring's axis, built with no boolean.

One path for every wall surface (:func:`ring_frame_solid`): the profile's outline placed
at the ring and clipped to the span (:func:`ring_section`, shared), the height checked
before anything is fitted, and the section swept round the surface. On a tube (r = const,
the fast path) the section lies in (s, r) and sweeps into tube faces and planar annuli
(below); on a canal surface (a radius law) it lies in (s, d), d the offset from the wall,
its widths laid off along the wall, and sweeps into canal faces and pieces of the normal
cones (:func:`canal_ring_solid`, docs/MATH.md section 8.6).

On a tube: a ring frame's cross-section is a rectilinear polygon in the (s, r) half-plane (s the arc
length along the axis, r the distance from it) swept once round the tube:
- every polygon edge of constant r is a tube face of radius r over an s-interval (the
  exact-section NURBS on one frame fit of the ring's short span, see :func:`fit_span`);
- every edge of constant s is a planar annulus in the normal plane at s;
- every polygon vertex (s, r) is an exact circle (Geom_Circle, by angle; within the fit's
  deviation of the surface's isoline s = const) shared by the tube face and the annulus
  that meet there; its pcurve on the tube face is (u(theta), s), u(theta) the surface's
  circle parametrisation inverted (:func:`tubecad.brep.faces.ring_pcurve`).
A flat bar is a rectangle, a T or L ring one polygon of 8 or 6 corners: web and flange are
one solid, with shared edges and nothing fused or sewn. The tube faces are cut where the
surface's u-parametrisation is only C0 and at least at quarter turns.

Volume (Pappus on a curved axis, exact for a regular tube): the tube of radius r between
s_a and s_b encloses pi r^2 (s_b - s_a), so by Green's theorem in the (s, r) plane, for a
counter-clockwise polygon (s across, r up),
    V = Int Int 2 pi r dr ds = -pi sum over its edges of r^2 (s_b - s_a).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from OCP.Geom import Geom_Circle
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Curve
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Vec2d
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Solid, TopoDS_Vertex

from tubecad.brep.assembled import TOLERANCE, CapPlane, c0_knots, closed_solid, edge, patch_face, plane_face, vertex
from tubecad.brep.faces import patch_faces, ring_pcurve
from tubecad.brep.solids import normal_cone_face
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import MIN_SIZE, orthogonality_for
from tubecad.curves.axis import Axis
from tubecad.fitting import FitError, TubeSurface, exact_section_surface, fit_frame
from tubecad.fitting.canal_section import canal_section_surface, fit_canal
from tubecad.occ_compat import downcast
from tubecad.stiffeners.limits import checked_levels, checked_reach, fit_failure, max_curvature
from tubecad.stiffeners.profiles import Profile
from tubecad.surface import CurvatureLineTube
from tubecad.surface.protocol import CurvatureLineSurface

Section = list[tuple[float, float]]


def ring_section(
    profile: Profile,
    s: float,
    radius: float,
    side: str,
    span: tuple[float, float],
    along: Callable[[float], float] | None = None,
) -> Section:
    """The ring frame's cross-section at ``s``: the profile's outline (w, h) placed at
    (s + w, R + h) outside or (s + w, R - h) inside and closed by its base r = R, clipped to
    ``span``, counter-clockwise in (s, r). Corners within MIN_SIZE of a span end snap to it.
    ``along(w)``, if given, is the s of the point w along the wall from s (a canal
    surface's rings advance at their own speed: :func:`along_wall`)."""
    sign = 1.0 if side == "outside" else -1.0
    lo, hi = span
    place = along or (lambda w: s + w)
    points = _clip(_clip([(place(w), radius + sign * h) for w, h in profile.outline()], lo, 1.0), hi, -1.0)
    points = _simplified(
        [(lo if abs(p - lo) < MIN_SIZE else hi if abs(p - hi) < MIN_SIZE else p, r) for p, r in points]
    )
    if len(points) < 4:
        raise ParameterError(f"the ring at s = {s:g} lies outside the span [{lo:g}, {hi:g}]")
    if section_area(points) < 0:
        points = points[::-1]
    short = min(abs(a[0] - b[0]) + abs(a[1] - b[1]) for a, b in zip(points, points[1:] + points[:1]))
    if short < MIN_SIZE:
        raise ParameterError(
            f"the ring at s = {s:g} has a side {short:.3g} long in its cross-section (clipped to the "
            f"span [{lo:g}, {hi:g}]); every side must be at least {MIN_SIZE:g}"
        )
    return points


def _clip(points: Section, bound: float, keep: float) -> Section:
    """Sutherland-Hodgman: the part of the polygon where keep * (s - bound) >= 0."""
    out: Section = []
    for a, b in zip(points, points[1:] + points[:1]):
        a_in, b_in = keep * (a[0] - bound) >= 0, keep * (b[0] - bound) >= 0
        if a_in:
            out.append(a)
        if a_in != b_in:  # only edges of constant r cross a line s = const
            out.append((bound, a[1] + (bound - a[0]) / (b[0] - a[0]) * (b[1] - a[1])))
    return out


def _simplified(points: Section) -> Section:
    """Without repeated corners and corners in the middle of a straight side."""
    points = list(points)
    k = 0
    while len(points) >= 3 and k < len(points):
        p, q, r = points[k - 1], points[k], points[(k + 1) % len(points)]
        if q == p or p[0] == q[0] == r[0] or p[1] == q[1] == r[1]:
            del points[k]
            k = 0
        else:
            k += 1
    return points


def section_area(section: Section) -> float:
    """Signed area of the polygon in (s, r) (shoelace), > 0 counter-clockwise."""
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(section, section[1:] + section[:1]))


def section_volume(section: Section) -> float:
    """The exact volume of the swept section: -pi sum r^2 (s_b - s_a) over its edges."""
    return -math.pi * sum(a[1] ** 2 * (b[0] - a[0]) for a, b in zip(section, section[1:] + section[:1]) if a[1] == b[1])


def ring_frame_solid(
    base: CurvatureLineSurface, s: float, profile: Profile, side: str, tolerance: float, name: str = "ring"
) -> TopoDS_Solid:
    """The ring frame at ``s`` on the wall surface ``base`` as one solid (module docstring):
    its section (:func:`ring_section`; on a canal surface its widths laid off along the wall)
    swept round, after the height is checked (a ParameterError) and with a failed fit named
    by ``name`` (a FitError). The tube's fast path: :func:`ring_solid`; a canal surface:
    :func:`canal_ring_solid`."""
    if base.constant_radius:
        radius = base.radius_law.constant_value
        section = ring_section(profile, s, radius, side, base.span)
        sub = base.axis.restricted((min(p[0] for p in section), max(p[0] for p in section)))
        reach = checked_reach(sub, profile, radius, side, "ring")  # before anything is fitted
        try:
            return ring_solid(base.axis, section, tolerance)
        except FitError as exc:
            raise fit_failure(exc, name, sub, reach) from None
    section = ring_section(profile, s, 0.0, side, base.span, along=lambda w: along_wall(base, s, w))
    try:
        return canal_ring_solid(base, section, tolerance)  # its levels checked regular first
    except FitError as exc:
        raise FitError(f"{name}: {exc}") from None


def ring_solid(axis: Axis, section: Section, tolerance: float) -> TopoDS_Solid:
    """The solid swept by the counter-clockwise rectilinear ``section`` round ``axis``, on one
    frame fit of the section's s-range to its largest radius."""
    return swept_section(axis, section, tolerance)[0]


def swept_section(
    axis: Axis, section: Section, tolerance: float, origin_deg: float = 0.0
) -> tuple[TopoDS_Solid, dict[float, list[TopoDS_Face]]]:
    """:func:`ring_solid`, with the tube faces cut (also) at the angle ``origin_deg`` from r1;
    returns the solid and its tube faces by radius."""
    s_values, radii = [p[0] for p in section], [p[1] for p in section]
    sub = axis.restricted(fit_span(axis, min(s_values), max(s_values), max(radii)))
    # where the frame is only C0 (a route's line-bend joint) inside the ring: its tube faces end there
    joints = [s for s, continuity in sub.joints if continuity == 0 and min(s_values) < s < max(s_values)]
    frame = fit_frame(sub, max(radii), tolerance, orthogonality_for(tolerance))
    surfaces: dict[float, TubeSurface] = {}
    for r in radii:
        if r not in surfaces:
            # a route's exact frame has v = s only at its breaks: per radius, the s of its corners
            # and joints (breaks at other radii' corners would be C0 knots inside this radius' faces)
            on = (
                frame
                if not sub.rings_at_joints
                else fit_frame(
                    sub,
                    max(radii),
                    tolerance,
                    orthogonality_for(tolerance),
                    rings=[p[0] for p in section if p[1] == r] + joints,
                )
            )
            surfaces[r] = exact_section_surface(CurvatureLineTube(sub, r, allow_irregular=True), on, origin_deg)
    arcs = {r: _Arcs(ts) for r, ts in surfaces.items()}
    circles = [_circle(arcs[r], s) for s, r in section]
    # the exact circles are within the fit's deviation of the surfaces' isolines
    edge_tolerance = max(TOLERANCE, 2.0 * frame.position_bound)
    faces: list[TopoDS_Face] = []
    tube_faces: dict[float, list[TopoDS_Face]] = {}
    n = len(section)
    for i in range(n):
        j = (i + 1) % n
        (sa, ra), (sb, rb) = section[i], section[j]
        if ra == rb:  # tube faces; the solid lies at larger r when the edge runs along +s
            lo, hi = (i, j) if sa < sb else (j, i)
            rings = (
                [circles[lo]]
                + [_circle(arcs[ra], x) for x in joints if circles[lo].s < x < circles[hi].s]
                + [circles[hi]]
            )
            for bottom, top in zip(rings[:-1], rings[1:]):
                band = _band(arcs[ra], bottom, top, edge_tolerance, reverse=sa < sb)
                tube_faces.setdefault(ra, []).extend(band)
                faces += band
        else:  # an annulus; the solid lies at smaller s when the edge runs along +r
            outer, inner = (j, i) if rb > ra else (i, j)
            faces.append(_annulus(circles[outer], circles[inner], outward=rb > ra))
    return closed_solid(faces), tube_faces


def fit_span(axis: Axis, lo: float, hi: float, reach: float) -> tuple[float, float]:
    """The span the ring's frame is fitted on: [lo, hi] widened, within the axis' span, to
    at least max(reach, 2 (hi - lo)) while reach max|k| < 1 holds on it. On a span of a
    millimetre the fit's derivatives carry rounding of |c| eps / (span / 8), which near the
    regularity limit (divided by 1 - reach |k|) exceeds the orthogonality target; the faces
    are cut to [lo, hi] anyway."""
    s0, s1 = axis.span
    want = min(max(reach, 2.0 * (hi - lo)), s1 - s0)
    a, b = max(s0, lo - (want - (hi - lo)) / 2), min(s1, hi + (want - (hi - lo)) / 2)
    a, b = max(s0, min(a, b - want)), min(s1, max(b, a + want))
    for _ in range(20):
        if max_curvature(axis.restricted((a, b)))[0] * reach < 1.0:
            return a, b
        a, b = 0.5 * (a + lo), 0.5 * (b + hi)
    return lo, hi


def u_cuts(ts: TubeSurface) -> list[float]:
    """Where the tube faces are cut round the surface: its u-knots where it is only C0
    (multiplicity >= degree), and the quarter turns; from the period's start to its end."""
    surface = ts.surface
    u_start, u_end, _, _ = surface.Bounds()
    cuts = [u_start]
    cuts += c0_knots(surface)
    cuts += [float(u) for u in ts.u_at(ts.origin_deg + np.array([90.0, 180.0, 270.0]))]
    period = u_end - u_start
    inside = sorted(u for u in cuts if u_start <= u < u_end - 1e-9 * period)
    out = [inside[0]] + [u for a, u in zip(inside, inside[1:]) if u - a > 1e-9 * period]
    return out + [u_end]


class _Arcs:
    """How one tube surface is cut round: the cuts u_j, their angles theta_j from the
    surface's origin, and per arc the map theta -> u as a plane B-spline curve (the pcurve
    of an exact circle arc, parameterised by angle, on a face of the surface)."""

    def __init__(self, ts: TubeSurface) -> None:
        self.ts = ts
        self.cuts = u_cuts(ts)
        angles = ts.theta_at(np.asarray(self.cuts)) - math.radians(ts.origin_deg)
        angles[-1] = angles[0] + 2 * math.pi
        self.angles = angles
        self._pcurves = [ring_pcurve(ts.circle, a, b) for a, b in zip(angles[:-1], angles[1:])]

    def pcurve(self, j: int, s: float) -> Geom2d_Curve:
        """The pcurve (u(theta), s) of arc j of the circle at ``s``."""
        return downcast(self._pcurves[j].Translated(gp_Vec2d(0.0, s)), Geom2d_BSplineCurve)


class _Circle:
    """The ring s = const of one tube surface as arcs of an exact circle between the cuts."""

    def __init__(self, vertices: list[TopoDS_Vertex], arcs: list[TopoDS_Edge], s: float, plane: CapPlane) -> None:
        self.vertices, self.arcs, self.s, self.plane = vertices, arcs, s, plane


def _circle(arcs: _Arcs, s: float) -> _Circle:
    """The circle of the surface's radius at ``s`` (Geom_Circle: centre c(s), axis t(s),
    angle from the surface's origin, so CAD sees a circle), in arcs between the cuts."""
    ts = arcs.ts
    axis, surface = ts.tube.axis, ts.surface
    t, r1, r2 = (v[0] for v in axis.rotation_minimising_frame(np.array([s])))
    centre = axis.position(np.array([s]))[0]
    a = math.radians(ts.origin_deg)
    x_dir = math.cos(a) * r1 + math.sin(a) * r2
    circle = Geom_Circle(
        gp_Ax2(gp_Pnt(*map(float, centre)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))),
        ts.tube.radius_law.constant_value,  # a tube's radius
    )
    m = len(arcs.cuts) - 1
    points = [surface.Value(u, s) for u in arcs.cuts[:-1]]
    # a vertex is the surface's point; the exact circle passes within the fit's gap of it, so
    # the vertex tolerance covers the gap (a coarse fit far from the origin: above 1e-7)
    gap = max(circle.Value(arcs.angles[j]).Distance(points[j]) for j in range(m))
    vertices = [vertex(p, max(TOLERANCE, 2.0 * gap)) for p in points]
    edges = [edge(circle, vertices[j], vertices[(j + 1) % m], arcs.angles[j], arcs.angles[j + 1]) for j in range(m)]
    return _Circle(vertices, edges, s, CapPlane(centre, t, x_dir))


def _band(arcs: _Arcs, bottom: _Circle, top: _Circle, tolerance: float, reverse: bool) -> list[TopoDS_Face]:
    """The tube faces between the circles ``bottom`` (smaller s) and ``top``, one per arc;
    the circle arcs get their pcurves (u(theta), s) on them."""
    surface, cuts = arcs.ts.surface, arcs.cuts
    m = len(cuts) - 1
    stringers = [
        edge(_iso_part(surface, cuts[j], bottom.s, top.s), bottom.vertices[j], top.vertices[j], bottom.s, top.s)
        for j in range(m)
    ]
    return [
        patch_face(
            surface,
            cuts[j],
            cuts[j + 1],
            bottom.s,
            top.s,
            bottom.arcs[j],
            stringers[(j + 1) % m],
            top.arcs[j],
            stringers[j],
            reverse=reverse,
            ring_pcurves=(arcs.pcurve(j, bottom.s), arcs.pcurve(j, top.s)),
            ring_tolerance=tolerance,
        )
        for j in range(m)
    ]


def _iso_part(surface, u: float, s0: float, s1: float):
    """The isoline u = const for s0 <= s <= s1 only (the frame may run further)."""
    iso = surface.UIso(u)
    iso.Segment(s0, s1)
    return iso


def _annulus(outer: _Circle, inner: _Circle, outward: bool) -> TopoDS_Face:
    """The planar annulus between two circles in the normal plane at their s (exact: the
    circles lie in it); its normal is +t (``outward``) or -t."""
    # the arcs run counter-clockwise about +t: the outer loop must run counter-clockwise
    # about the face normal, the hole clockwise
    loops = []
    for k, circle in enumerate((outer, inner)):
        along = outward == (k == 0)
        loops.append([(arc, along) for arc in (circle.arcs if along else circle.arcs[::-1])])
    plane = outer.plane
    return plane_face(plane.origin, plane.normal if outward else -plane.normal, plane.x_dir, loops)


# --- ring frames on a canal surface (a radius law; docs/MATH.md section 8.6) -------------
#: the ring's canal faces are cut at these angles (C1 circle arcs of at most a quarter turn)
QUARTERS = (0.0, 90.0, 180.0, 270.0)


def wall_speed(base: CurvatureLineSurface, s: np.ndarray) -> np.ndarray:
    """q - r r'' / q: how fast the characteristic circles advance along the wall per unit s,
    averaged round the circle (the stringers' speed sqrt(G) less its part that varies round
    it with the axis' curvature)."""
    law = base.radius_law
    dr = law.dr(s)
    q = np.sqrt(1.0 - dr * dr)
    return q - law.r(s) * law.ddr(s) / q


def along_wall(base: CurvatureLineSurface, s: float, w: float) -> float:
    """The s of the circle w along the wall from the circle at ``s``: Int_s^x speed = w
    (:func:`wall_speed`, Gauss-Legendre), by Newton from x = s + w; clamped to the span
    (the ring's section is clipped there anyway)."""
    if w == 0.0:
        return s
    s0, s1 = base.span
    nodes, weights = np.polynomial.legendre.leggauss(12)
    x = s + w
    for _ in range(8):
        lo, hi = sorted((s, min(max(x, s0), s1)))
        mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        done = float((wall_speed(base, mid + half * nodes) * weights).sum() * half) * math.copysign(1.0, x - s)
        step = (w - done) / float(wall_speed(base, np.array([min(max(x, s0), s1)]))[0])
        x += step
        if abs(step) < 1e-14 * max(1.0, abs(x)):
            break
    return x


def canal_ring_solid(base: CurvatureLineSurface, section: Section, tolerance: float) -> TopoDS_Solid:
    """The solid swept round by the counter-clockwise rectilinear ``section`` (s, d) of a
    ring frame on ``base`` (module docstring), on one canal fit of every level d."""
    s_values = sorted({p[0] for p in section})
    lo, hi = s_values[0], s_values[-1]
    s0, s1 = base.span
    widen = max(hi - lo, 1e-3 * (s1 - s0))  # a little room either side: the fit's ends stay off the faces
    sub = base.restricted((max(s0, lo - widen), min(s1, hi + widen)))
    levels = sorted({p[1] for p in section})
    exact = checked_levels(sub, levels, "the ring")
    fit = fit_canal(sub, levels, tolerance, orthogonality_for(tolerance), rings=s_values, exact_at_rings=False)
    joints = [s for s, _ in sub.axis.joints]
    surfaces = {d: canal_section_surface(sub, fit, d, QUARTERS, exact[d]) for d in levels}
    faces: list[TopoDS_Face] = []
    circles = {}  # (s, d) -> the ring edges of the corner's circle
    n = len(section)
    for i in range(n):  # the sides of constant d: canal faces; the solid lies at larger d when one runs along +s
        (sa, da), (sb, db) = section[i], section[(i + 1) % n]
        if da == db:
            a, b = sorted((sa, sb))
            rings = [a, *[x for x in joints if a < x < b], b]
            patches = patch_faces(surfaces[da], rings, QUARTERS, reverse=sa < sb)
            faces += patches.all_faces()
            circles[(a, da)], circles[(b, da)] = patches.rings[0], patches.rings[-1]
    for i in range(n):  # the sides of constant s: normal cones; the solid lies at smaller s when one runs along +d
        (sa, da), (sb, db) = section[i], section[(i + 1) % n]
        if sa == sb:
            (d_lo, d_hi) = sorted((da, db))
            faces.append(
                normal_cone_face(
                    sa, surfaces[d_lo], circles[(sa, d_lo)], surfaces[d_hi], circles[(sa, d_hi)], outward=db > da
                )
            )
    return closed_solid(faces)
