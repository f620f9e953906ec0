"""Stiffeners on canal surfaces (a radius law r(s); docs/MATH.md section 8.6).

A canal surface's normals along a characteristic circle all pass through the sphere's
centre c(s): they sweep the *normal cone* K(s) (apex c(s), axis t(s), generators
n = -r' t + q e), a plane where r' = 0. Its offsets r + d share the circles' planes and
the stringers, so:

- **Ring frame** at s: its cross-section is a rectilinear polygon in (s, d), d the offset
  from the wall surface it stands on, swept round: every side of constant d is a face of
  the canal surface of r + d between two characteristic circles (exact rational circles
  in u, one canal fit for every level), every side of constant s a piece of the normal
  cone K(s) between two levels, every corner an exact circle (Geom_Circle) shared by the
  two. The web's faces are normal cones, so they stand normal to the wall all round and
  the web develops exactly to an annular sector. The profile's widths w are laid off along
  the wall: the circles advance along it at the mean stringer speed q - r r'' / q per
  unit s (:func:`along_wall`), so a web of thickness t is t thick at its base.
- **Stringer** along chi0 = const: its profile stands in the plane Pi(s) through the line's
  point X, spanned by the normal n and the across direction ebar = X_u / |X_u| (normal to
  the line's tangent m = n x ebar), so the web is the strip of normals (developable by
  Rodrigues) and its faces are square to the line. A corner (w, v) off the wall is
  X + v n + w ebar; a corner on the wall (v = 0) is the wall's own point in Pi(s) at
  across distance w (Newton on the exact surface), and the base face is the wall between
  them, interpolated at BASE_NODES points of Pi(s) across. Every corner curve is one
  B-spline in s fitted to the exact points (Greville interpolation, spans halved until
  within tolerance / 2), so every face is ruled between two corner curves (the base: a
  B-spline surface through the wall points), sharing its edges, with planar caps in
  Pi(s) at both ends. A square end cannot follow the slanted end circle of a wall where
  r' != 0: there the stringer stops where its whole base lies on the wall, at most
  (t/2)^2 |r'| / (2 r q) short of it (a few micrometres for common sizes).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from OCP.Geom import Geom_BSplineSurface
from OCP.TopoDS import TopoDS_Face, TopoDS_Solid

from tubecad.brep.assembled import CapPlane, Strip, closed_solid, strip_solid
from tubecad.brep.faces import patch_faces
from tubecad.brep.solids import normal_cone_face
from tubecad.core.errors import ParameterError, RegularityError
from tubecad.core.tolerance import MIN_SIZE, orthogonality_for
from tubecad.fitting.canal_section import canal_section_surface, fit_canal
from tubecad.fitting.frame_spline import _initial_breaks, _joint_multiplicities, _with_rings, refine_spline
from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals
from tubecad.stiffeners.profiles import Profile
from tubecad.surface.canal import CanalSurface

Section = list[tuple[float, float]]

#: the ring's tube faces are cut at these angles (C1 circle arcs of at most a quarter turn)
QUARTERS = (0.0, 90.0, 180.0, 270.0)
#: wall points across a stringer's base, through which its base face is interpolated (degree - 1)
BASE_NODES = 7
#: Newton steps for a wall point in a stringer's section plane (quadratic: 1e-16 after 4-5)
NEWTON_STEPS = 8
#: the stringer's corner curves: degree in s and the spans they start from
STRINGER_DEGREE = 7
STRINGER_SPANS = 8


# --- ring frames ---------------------------------------------------------------------------
def wall_speed(base: CanalSurface, s: np.ndarray) -> np.ndarray:
    """q - r r'' / q: how fast the characteristic circles advance along the wall per unit s,
    averaged round the circle (the stringers' speed sqrt(G) less its part that varies round
    it with the axis' curvature)."""
    law = base.radius_law
    dr = law.dr(s)
    q = np.sqrt(1.0 - dr * dr)
    return q - law.r(s) * law.ddr(s) / q


def along_wall(base: CanalSurface, s: float, w: float) -> float:
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


def checked_levels(base: CanalSurface, levels: Sequence[float], name: str) -> dict[float, CanalSurface]:
    """The offsets r + d of ``base`` at ``levels``, each checked regular (a ParameterError
    naming ``height``: too high a stiffener folds its own surface, as on a tube
    (R + height) max|k| must stay < 1) and above MIN_SIZE."""
    out = {}
    for d in levels:
        if d == 0.0:
            out[d] = base
            continue
        law = base.radius_law
        if law.min_radius + d < MIN_SIZE:
            raise ParameterError(
                f"height: {name} reaches in to r {d:+g}, and the radius law's r is {law.min_radius:g} "
                f"at s = {law.s_at_min_radius:.6g}: r {d:+g} must stay >= {MIN_SIZE:g} (lower the "
                "stiffener)"
            )
        try:
            out[d] = base.offset(d)
        except RegularityError as exc:
            raise ParameterError(
                f"height: {name} reaches the canal surface of r {d:+g}, which is not regular "
                f"(lower the stiffener): {exc}"
            ) from None
    return out


def check_spec_heights(surface: CanalSurface, layout, offsets: tuple[float, float], section: dict) -> None:
    """A [stiffeners] section on the wall between the offsets (d_in, d_out) of ``surface``:
    each stiffener's own surfaces regular and off the axis (:func:`checked_levels`; a ring
    over its own width), before anything is built. Other faults are left to the build."""
    from tubecad.stiffeners.limits import chosen_indices, spec_profile

    picked = spec_profile(section)
    if picked is None:
        return
    profile, side = picked
    sign, wall = (1.0, offsets[1]) if side == "outside" else (-1.0, offsets[0])
    levels = sorted({wall + sign * h for _, h in profile.outline()})
    s0, s1 = surface.span
    w = [w for w, _ in profile.outline()]
    for i in chosen_indices(section, "rings", len(layout.s_rings)):
        s = float(layout.s_rings[i])
        lo, hi = max(s0, s + min(w)), min(s1, s + max(w))
        if hi > lo:
            checked_levels(surface.restricted((lo, hi)), levels, f"the ring at s = {s:g}")
    if chosen_indices(section, "stringers", len(layout.stringers_deg)):
        checked_levels(surface, levels, "a stringer")


def canal_ring_solid(base: CanalSurface, section: Section, tolerance: float) -> TopoDS_Solid:
    """The solid swept round by the counter-clockwise rectilinear ``section`` (s, d) of a
    ring frame on ``base`` (module docstring), on one canal fit of every level d."""
    s_values = sorted({p[0] for p in section})
    lo, hi = s_values[0], s_values[-1]
    s0, s1 = base.span
    widen = max(hi - lo, 1e-3 * (s1 - s0))  # a little room either side: the fit's ends stay off the faces
    sub = base.restricted((max(s0, lo - widen), min(s1, hi + widen)))
    levels = sorted({p[1] for p in section})
    exact = checked_levels(sub, levels, "the ring")
    fit = fit_canal(sub, levels, tolerance, orthogonality_for(tolerance), rings=s_values)
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


# --- stringers -----------------------------------------------------------------------------
def stringer_frame(base: CanalSurface, chi0: float, s: np.ndarray) -> tuple[np.ndarray, ...]:
    """X, n, ebar, m along the stringer chi0 at ``s`` (each (len(s), 3)): the point, the
    wall's unit normal, the unit across direction X_u / |X_u| and m = n x ebar (the line's
    unit tangent, as F = 0)."""
    X, X_u, _ = base.tangents(np.full(len(s), chi0), s)
    n = base.normal(np.full(len(s), chi0), s)
    ebar = X_u / np.linalg.norm(X_u, axis=-1, keepdims=True)
    return X, n, ebar, np.cross(n, ebar)


def wall_points_across(
    base: CanalSurface, chi0: float, s: np.ndarray, across: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The wall's points in the section planes Pi(s) of the stringer chi0 at across distance
    ``across`` (broadcast (len(s), len(across))): Z(u, s') with (Z - X).m = 0 and
    (Z - X).ebar = w, by Newton on the exact surface from (chi0 + w / |X_u|, s). Returns the
    points (len(s), len(across), 3) and the s' they lie at (the surface is evaluated with s'
    clamped to the span; an s' past it says how far a section's base would reach outside)."""
    X, n, ebar, m = stringer_frame(base, chi0, s)
    w = np.broadcast_to(np.asarray(across, dtype=float)[None, :], (len(s), len(across)))
    u = chi0 + w / np.linalg.norm(base.tangents(np.full(len(s), chi0), s)[1], axis=-1)[:, None]
    sp = np.broadcast_to(s[:, None], w.shape).copy()
    lo, hi = base.span
    for _ in range(NEWTON_STEPS):
        S, S_u, S_s = base.tangents(u, np.clip(sp, lo, hi))
        diff = S - X[:, None]
        f1 = np.einsum("ijk,ik->ij", diff, m)
        f2 = np.einsum("ijk,ik->ij", diff, ebar) - w
        a, b = np.einsum("ijk,ik->ij", S_u, m), np.einsum("ijk,ik->ij", S_s, m)
        c, e = np.einsum("ijk,ik->ij", S_u, ebar), np.einsum("ijk,ik->ij", S_s, ebar)
        det = a * e - b * c
        du, ds = (e * f1 - b * f2) / det, (a * f2 - c * f1) / det
        u -= du
        sp -= ds
        if max(np.abs(du).max(), np.abs(ds).max() / (hi - lo)) < 1e-15:
            break
    return base.points(u, np.clip(sp, lo, hi)), sp


def _bernstein_inverse(count: int) -> np.ndarray:
    """The matrix taking values at ``count`` equally spaced parameters of [0, 1] to the
    poles of the Bezier curve of degree count - 1 through them."""
    x = np.linspace(0.0, 1.0, count)
    p = count - 1
    basis = np.array([[math.comb(p, i) * xi**i * (1.0 - xi) ** (p - i) for i in range(p + 1)] for xi in x])
    return np.linalg.inv(basis)


def stringer_station_span(
    base: CanalSurface, chi0: float, half_width: float, span: tuple[float, float]
) -> tuple[float, float]:
    """The stations s of the stringer's sections within ``span``: moved in from an end of the
    wall where the section plane's base would reach past its end circle (r' != 0 there) by
    the distance its base reaches, measured on a section near that end."""
    lo, hi = span
    s0, s1 = base.span
    probe = min(0.01 * (s1 - s0), 0.25 * (hi - lo))
    across = np.array([-half_width, half_width])
    out = []
    for end, wall_end, inward in ((lo, s0, 1.0), (hi, s1, -1.0)):
        station = end + inward * probe  # far enough in that the base's wall points lie inside the span
        for _ in range(4):  # the reach at the end, from stations moving towards it (it varies slowly)
            _, sp = wall_points_across(base, chi0, np.array([station]), across)
            reach = float((inward * (station - sp)).max())  # how far the base reaches from its station towards the end
            moved = end + inward * max(0.0, reach - inward * (end - wall_end)) * (1.0 + 1e-3)
            if abs(moved - station) <= 1e-12 * (s1 - s0):
                break
            station = moved
        out.append(station)
    return out[0], out[1]


def canal_stringer_strips(
    base: CanalSurface, chi0: float, profile: Profile, side: str, span: tuple[float, float], tolerance: float
) -> tuple[list[Strip], tuple[float, float], list[CapPlane], list[float], float]:
    """The strips of the stringer chi0 (radians, of ``base``) over ``span`` (module
    docstring): (strips, the stations' span, the cap planes there, the C0 cuts along s, the
    fit's position bound)."""
    sign = 1.0 if side == "outside" else -1.0
    corners = profile.outline()
    tw = profile.thickness / 2
    a, b = stringer_station_span(base, chi0, tw, span)
    across = np.linspace(-tw, tw, BASE_NODES)
    off = np.array([(w, sign * v) for w, v in corners if v != 0.0])
    on = [k for k, (_, v) in enumerate(corners) if v == 0.0]  # the base corners: (+tw, 0) first, (-tw, 0) last

    def values(s: np.ndarray) -> np.ndarray:
        X, n, ebar, _ = stringer_frame(base, chi0, s)
        top = X[:, None] + off[None, :, 1:] * n[:, None] + off[None, :, :1] * ebar[:, None]
        wall, _ = wall_points_across(base, chi0, s, across)
        return np.concatenate([top, wall], axis=1).reshape(len(s), -1)

    count = len(off) + BASE_NODES
    restricted = base.axis.restricted((a, b))
    degree = STRINGER_DEGREE
    joints = _joint_multiplicities(restricted, degree)
    for x in base.radius_law.breaks:
        if a < x < b:
            joints[float(x)] = max(joints.get(float(x), 1), degree - 1)
    breaks = _with_rings(_initial_breaks(restricted, STRINGER_SPANS), np.array(sorted(joints)))

    def span_errors(spline, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        frac = np.linspace(0.0, 1.0, 12)
        s = (breaks[:-1, None] + np.diff(breaks)[:, None] * frac).ravel()
        err = np.linalg.norm((spline(s) - values(s)).reshape(len(s), count, 3), axis=-1).max(axis=1)
        return err.reshape(len(breaks) - 1, -1).max(axis=1), np.zeros(len(breaks) - 1)

    spline, bound, _ = refine_spline(
        values, breaks, degree, joints, span_errors, tolerance, math.inf, 4096, "the stringer's corner curves"
    )
    poles = spline.c.reshape(len(spline.c), count, 3)
    s_knots, s_mults = knots_and_multiplicities(spline.t)
    wall = np.einsum("ij,kjl->kil", _bernstein_inverse(BASE_NODES), poles[:, len(off) :])  # (poles, BASE_NODES, 3)
    curves = {}  # corner index -> its poles along s
    j = 0
    for k, (_, v) in enumerate(corners):
        if v == 0.0:
            curves[k] = wall[:, -1] if k == on[0] else wall[:, 0]
        else:
            curves[k] = poles[:, j]
            j += 1

    def surface(rows: list[np.ndarray], degree_u: int) -> Geom_BSplineSurface:
        return Geom_BSplineSurface(
            points_2d(np.stack(rows)),
            reals([0.0, 1.0]),
            reals(s_knots),
            integers([degree_u + 1, degree_u + 1]),
            integers(s_mults),
            degree_u,
            spline.k,
        )

    strips = [Strip(surface([curves[k], curves[k + 1]], 1), 0.0, 1.0) for k in range(len(corners) - 1)]
    strips.append(Strip(surface([wall[:, i] for i in range(BASE_NODES)], BASE_NODES - 1), 0.0, 1.0))
    X, n, ebar, m = stringer_frame(base, chi0, np.array([a, b]))
    caps = [CapPlane(X[i], m[i], ebar[i]) for i in range(2)]
    cuts = [float(x) for x, mult in joints.items() if mult >= degree]
    return strips, (a, b), caps, cuts, bound


def canal_stringer_solid(
    base: CanalSurface, chi0: float, profile: Profile, side: str, span: tuple[float, float], tolerance: float
) -> tuple[TopoDS_Solid, tuple[float, float], float]:
    """The stringer chi0 (radians) on ``base`` over ``span`` as one solid with shared edges:
    (solid, its stations' span, the fit's position bound)."""
    sign = 1.0 if side == "outside" else -1.0
    strips, (a, b), caps, cuts, bound = canal_stringer_strips(base, chi0, profile, side, span, tolerance)
    # the outline runs counter-clockwise in (w, v) exactly when it runs clockwise about +m (ebar x n = -m)
    corners = [(w, sign * v) for w, v in profile.outline()]
    area = 0.5 * sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(corners, corners[1:] + corners[:1]))
    solid, _ = strip_solid(strips, a, b, (caps[0], caps[1]), area < 0, cuts)
    return solid, (a, b), bound
