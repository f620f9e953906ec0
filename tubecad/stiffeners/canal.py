"""Stiffeners on canal surfaces (a radius law r(s); docs/MATH.md section 8.6).

A canal surface's normals along a characteristic circle all pass through the sphere's
centre c(s): they sweep the *normal cone* K(s) (apex c(s), axis t(s), generators
n = -r' t + q e), a plane where r' = 0. Its offsets r + d share the circles' planes and
the stringers, so:

Both are built from the shared stiffener path (:func:`tubecad.stiffeners.solids.ring_stiffener`,
:func:`~tubecad.stiffeners.solids.stringer_stiffener`: the checks, the names, the assembly of
the strips), which takes the tube's fast path where r' = 0; this module holds the stringer's
canal geometry, the ring frame's is in :mod:`.rings` (:func:`.rings.canal_ring_solid`) and the
height check of the offsets in :mod:`.limits` (:func:`.limits.checked_levels`).

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

import numpy as np
from OCP.Geom import Geom_BSplineSurface
from OCP.TopoDS import TopoDS_Solid

from tubecad.brep.assembled import CapPlane, Strip, strip_solid
from tubecad.fitting.frame_spline import _initial_breaks, _joint_multiplicities, _with_rings, refine_spline
from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals
from tubecad.stiffeners.limits import check_canal_spec_heights, checked_levels
from tubecad.stiffeners.profiles import Profile
from tubecad.stiffeners.rings import QUARTERS, along_wall, canal_ring_solid, wall_speed
from tubecad.surface.canal import CanalSurface

#: the [stiffeners] height check of a canal wall (now :func:`.limits.check_canal_spec_heights`)
check_spec_heights = check_canal_spec_heights

# the canal ring frame's pieces, importable from here as before
__all__ = [
    "QUARTERS",
    "along_wall",
    "canal_ring_solid",
    "canal_stringer_solid",
    "canal_stringer_strips",
    "check_spec_heights",
    "checked_levels",
    "stringer_frame",
    "stringer_station_span",
    "wall_points_across",
    "wall_speed",
]

#: wall points across a stringer's base, through which its base face is interpolated (degree - 1)
BASE_NODES = 7
#: Newton steps for a wall point in a stringer's section plane (quadratic: 1e-16 after 4-5)
NEWTON_STEPS = 8
#: the stringer's corner curves: degree in s and the spans they start from
STRINGER_DEGREE = 7
STRINGER_SPANS = 8


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
