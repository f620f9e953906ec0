"""Flat patterns of T and L flanges (tubecad/shop/flanges.py; docs/MATH.md section 9).

Every expected value comes from a closed form written here (a helix tube's geodesic turn and
edge lengths, a cone's slant, a torus parallel's tangent cone) or from the 3-D flange strip
X + w E measured here: X and N from the surfaces' points and normals, T by finite
differences, E = T x N, edge lengths as polylines and the area as the strip's quads, never
from the flange code's output.
"""

import math

import numpy as np
import pytest
from conftest import fit_circle

from tubecad import CurvatureLineTube, Helix, NaturalAxis
from tubecad.core.errors import ParameterError
from tubecad.shop.flanges import flange_rates, ring_flange_flat_pattern, stringer_flange_flat_pattern
from tubecad.stiffeners.flat import polygon_area
from tubecad.stiffeners.profiles import Profile
from tubecad.surface.canal import CanalSurface

T_PROFILE = Profile("T", height=4.0, thickness=0.5, flange_width=3.0, flange_thickness=0.4)
L_PROFILE = Profile("L", height=4.0, thickness=0.5, flange_width=3.0, flange_thickness=0.4)
LEVEL = 4.0 - 0.4 / 2  # h - tf / 2


def widths(profile):
    bf, tw = profile.flange_width, profile.thickness
    return (-bf / 2, bf / 2) if profile.kind == "T" else (-tw / 2, -tw / 2 + bf)


def polyline(p):
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def edges(pattern):
    n = len(pattern.outline) // 2
    return pattern.outline[:n], pattern.outline[n:][::-1]


def strip_3d(surface, u, span, w0, w1, n=10001):
    """(edge w0 length, edge w1 length, area) of the 3-D strip X + w E, E = T x N, on ``surface``
    (already the offset one) along the stringer u: polylines and quads of n and 2n - 1 stations,
    each O(h^2), Richardson-extrapolated (4 fine - coarse) / 3."""
    return tuple(
        (
            4 * np.array(_strip_3d(surface, u, span, w0, w1, 2 * n - 1))
            - np.array(_strip_3d(surface, u, span, w0, w1, n))
        )
        / 3
    )


def _strip_3d(surface, u, span, w0, w1, n):
    s = np.linspace(*span, n)
    X = surface.points(np.full(n, u), s)
    N = surface.normal(np.full(n, u), s)
    T = np.gradient(X, s, axis=0, edge_order=2)
    T /= np.linalg.norm(T, axis=1, keepdims=True)
    E = np.cross(T, N)
    E /= np.linalg.norm(E, axis=1, keepdims=True)
    A, B = X + w0 * E, X + w1 * E
    quads = 0.5 * np.linalg.norm(np.cross(B[1:] - A[:-1], A[1:] - B[:-1]), axis=1)  # half the diagonals' cross
    return polyline(A), polyline(B), float(quads.sum())


# --- a helix tube ---------------------------------------------------------------------------------
K, BETA, LENGTH, R = 0.01, 20.0, 600.0, 10.0


@pytest.fixture(scope="module")
def helix_tube():
    return CurvatureLineTube(Helix(K, BETA, (0.0, LENGTH)), R)


@pytest.mark.parametrize("profile, side, theta", [(T_PROFILE, "outside", 30.0), (L_PROFILE, "inside", 200.0)])
def test_helix_stringer_flange_matches_the_3d_strip(helix_tube, profile, side, theta):
    """Edge lengths and area equal the 3-D flange strip's, and the closed forms: on the slope-
    curve helix the RMF is r1 = cos w n - sin w bn, w = k s tan b (docs/MATH.md section 2), so
    k1 = k cos w, k2 = k sin w, the turn towards E is k2 cos th - k1 sin th = k sin(c s - th),
    c = k tan b, and the speed on the tube of radius R' is 1 - R' k cos(th - c s)."""
    sign = 1.0 if side == "outside" else -1.0
    Rp, th, c = R + sign * LEVEL, math.radians(theta), K * math.tan(math.radians(BETA))
    w0, w1 = widths(profile)
    pattern = stringer_flange_flat_pattern(helix_tube, theta, profile, side, samples=20001)
    assert pattern.kind == "flange" and pattern.level == pytest.approx(sign * LEVEL, abs=1e-15)

    s = np.linspace(0.0, LENGTH, 101)
    turn, speed = flange_rates(CurvatureLineTube(helix_tube.axis, Rp), th)
    assert np.abs(turn(s) - K * np.sin(c * s - th)).max() < 2e-17  # measured 5.2e-18 (round-off of 0.01)
    assert np.abs(speed(s) - (1 - Rp * K * np.cos(th - c * s))).max() < 2e-15  # measured 4.4e-16

    def edge(w):  # Int_0^L [1 - R' k cos(th - c s) - w k sin(c s - th)] ds
        return (
            LENGTH
            - Rp * K * (math.sin(th) - math.sin(th - c * LENGTH)) / c
            - w * K * (math.cos(th) - math.cos(c * LENGTH - th)) / c
        )

    area = (w1 - w0) * edge(0.0) - 0.5 * (w1**2 - w0**2) * K * (math.cos(th) - math.cos(c * LENGTH - th)) / c
    assert pattern.base_length == pytest.approx(edge(w0), rel=2e-15)  # measured <= 6.3e-16
    assert pattern.top_length == pytest.approx(edge(w1), rel=2e-15)
    assert pattern.centre_length == pytest.approx(edge(0.0), rel=2e-15)
    assert pattern.area == pytest.approx(area, rel=2e-15)

    e0, e1, a3 = strip_3d(CurvatureLineTube(helix_tube.axis, Rp), th, (0.0, LENGTH), w0, w1)
    assert pattern.base_length == pytest.approx(e0, rel=2e-13)  # measured <= 1.5e-14
    assert pattern.top_length == pytest.approx(e1, rel=2e-13)
    assert pattern.area == pytest.approx(a3, rel=2e-13)  # measured <= 6.7e-15

    base, top = edges(pattern)  # the developed outline itself: 20001 points, its chords
    assert polyline(base) == pytest.approx(pattern.base_length, rel=3e-9)  # measured <= 1.8e-9
    assert polyline(top) == pytest.approx(pattern.top_length, rel=3e-9)
    assert polygon_area(pattern.outline) == pytest.approx(pattern.area, rel=1.5e-8)  # measured <= 7.6e-9
    assert np.linalg.norm(top[0] - base[0]) == pytest.approx(w1 - w0, rel=1e-14)  # the end rulings: straight
    assert np.linalg.norm(top[-1] - base[-1]) == pytest.approx(w1 - w0, rel=1e-14)


def test_cylinder_l_flange_is_a_rectangle():
    """k = 0: no geodesic turn, the band is the rectangle L x bf, from -tw/2 to -tw/2 + bf."""
    tube = CurvatureLineTube(NaturalAxis("0", "0", (0.0, 100.0)), 5.0)
    pattern = stringer_flange_flat_pattern(tube, 75.0, L_PROFILE, "outside", samples=11)
    w0, w1 = -0.25, 2.75
    base, top = edges(pattern)
    assert np.abs(base - np.c_[np.linspace(0, 100, 11), np.full(11, w0)]).max() < 1e-13
    assert np.abs(top - np.c_[np.linspace(0, 100, 11), np.full(11, w1)]).max() < 1e-13
    assert (pattern.base_length, pattern.top_length) == pytest.approx((100.0, 100.0), rel=1e-15)
    assert pattern.area == pytest.approx(300.0, rel=1e-15)
    with pytest.raises(ParameterError, match="profile: a flange needs a T or L profile, got 'flat'"):
        stringer_flange_flat_pattern(tube, 0.0, Profile("flat", 4.0, 0.5))


# --- a cone ----------------------------------------------------------------------------------------
R0, SLOPE, CONE_LENGTH = 2.0, 0.3, 40.0


@pytest.fixture(scope="module")
def cone():
    return CanalSurface(NaturalAxis("0", "0", (0.0, CONE_LENGTH)), f"{R0} + {SLOPE} * s")


def cone_circle(s, r0):
    """The characteristic circle at s of the cone r = r0 + a s, from its geometry alone: the
    sphere of radius r centred at x = s touches the cone of apex x = -r0 / a, sin beta = a,
    along the circle at axial distance D cos^2 beta from the apex (D = s + r0 / a), radius
    D cos beta sin beta: (x, radius, slant D cos beta from the apex)."""
    beta = math.asin(SLOPE)
    D = s + r0 / SLOPE
    return -r0 / SLOPE + D * math.cos(beta) ** 2, D * math.cos(beta) * math.sin(beta), D * math.cos(beta)


@pytest.mark.parametrize("side, span", [("outside", (0.0, CONE_LENGTH)), ("inside", (15.0, CONE_LENGTH))])
def test_cone_stringer_flange_is_a_rectangle(cone, side, span):
    """A stringer is a generatrix: its tangent planes are one plane, the band a rectangle of
    the offset cone's slant between its end circles by bf (inside, the offset r - 3.8 is only
    a surface for s > 6.0: a sub-span)."""
    d = (1 if side == "outside" else -1) * LEVEL
    (x0, a0, _), (x1, a1, _) = cone_circle(span[0], R0 + d), cone_circle(span[1], R0 + d)
    slant = math.hypot(x1 - x0, a1 - a0)
    pattern = stringer_flange_flat_pattern(cone, 30.0, T_PROFILE, side, span=span, samples=101)
    assert pattern.base_length == pytest.approx(slant, rel=5e-13)  # measured 1.6e-13 (the radius law's r')
    assert pattern.top_length == pytest.approx(slant, rel=5e-13)
    assert pattern.area == pytest.approx(3.0 * slant, rel=5e-13)
    base, top = edges(pattern)
    assert np.abs(base[:, 1] + 1.5).max() < 1e-12 and np.abs(top[:, 1] - 1.5).max() < 1e-12


def test_curved_canal_stringer_flange_matches_the_3d_strip():
    """A canal surface on a bent axis: the turn is kbar / q (kbar = k2 cos chi - k1 sin chi,
    from dm/ds . ebar with m = q t + r' e, chi' = (r'/q) kbar), and the developed band's
    edges and area are the 3-D strip's."""
    canal = CanalSurface(NaturalAxis("0.01", "0", (0.0, 40.0)), "2.0 + 0.03 * s")
    chi0 = math.radians(40.0)
    top = canal.offset(LEVEL)
    s = np.linspace(0.0, 40.0, 41)
    chi = canal.stringer_angle(chi0, s)
    k1, k2 = canal.axis.normal_development(s)
    turn, _ = flange_rates(top, chi0)
    # measured 4.7e-13 at the span's ends (S_ss differentiates the Moebius series twice), 1e-14 inside
    assert np.abs(turn(s) - (k2 * np.cos(chi) - k1 * np.sin(chi)) / math.sqrt(1 - 0.03**2)).max() < 1e-12
    pattern = stringer_flange_flat_pattern(canal, 40.0, L_PROFILE, "outside", samples=20001)
    e0, e1, a3 = strip_3d(top, chi0, (0.0, 40.0), -0.25, 2.75)
    assert pattern.base_length == pytest.approx(e0, rel=2e-12)  # measured 2.1e-14
    assert pattern.top_length == pytest.approx(e1, rel=2e-12)  # measured 2.5e-13
    assert pattern.area == pytest.approx(a3, rel=2e-12)  # measured 1.1e-13
    assert polygon_area(pattern.outline) == pytest.approx(pattern.area, rel=5e-11)  # measured 2.6e-11 (chords)
    # over a sub-span: the same line (chi0 named at the whole wall's start), its 3-D strip there
    part = stringer_flange_flat_pattern(canal, 40.0, L_PROFILE, "outside", span=(10.0, 30.0))
    e0, e1, a3 = strip_3d(top, chi0, (10.0, 30.0), -0.25, 2.75)
    assert (part.base_length, part.top_length, part.area) == pytest.approx((e0, e1, a3), rel=2e-12)  # <= 6.1e-13


# --- a torus --------------------------------------------------------------------------------------
def test_torus_stringer_flange_is_an_annular_sector():
    """On the arc of radius a = 100 (k = 0.01, r1 the principal normal towards the centre) the
    stringer th is the parallel of radius rho = a - R' cos th about the torus axis. Its
    tangent planes envelop a cone with apex on that axis: the across direction E = -sin th r1
    + cos th r2 leaves the axis at the rate sin th, so the slant to the parallel is
    rho / sin th (= (a - R' cos th) / sin th). Over the arc (angle 3 rad) the band develops to
    the annular sector of angle 3 rho / slant = 3 sin th, the edge w at radius slant + w."""
    axis = NaturalAxis("0.01", "0", (0.0, 300.0))
    tube = CurvatureLineTube(axis, R)
    th = math.radians(60.0)
    Rp = R + LEVEL
    rho = 100.0 - Rp * math.cos(th)
    s = np.linspace(0.0, 300.0, 7)
    points = CurvatureLineTube(axis, Rp).points(np.full(7, th), s)  # the parallel: centre (0, 100, 0), axis z
    assert np.abs(np.hypot(points[:, 0], points[:, 1] - 100.0) - rho).max() < 1e-11
    slant, angle = rho / math.sin(th), 3.0 * math.sin(th)
    pattern = stringer_flange_flat_pattern(tube, 60.0, T_PROFILE, "outside", samples=4001)
    assert pattern.base_length == pytest.approx(angle * (slant - 1.5), rel=1e-14)  # measured 8.3e-16
    assert pattern.top_length == pytest.approx(angle * (slant + 1.5), rel=1e-14)
    assert pattern.centre_length == pytest.approx(angle * slant, rel=1e-14)
    assert pattern.area == pytest.approx(0.5 * angle * ((slant + 1.5) ** 2 - (slant - 1.5) ** 2), rel=1e-14)
    base, top = edges(pattern)
    gap0, radius0, centre0 = fit_circle(base)
    gap1, radius1, centre1 = fit_circle(top)
    assert max(gap0, gap1) < 1e-12  # measured 2.1e-13 (round-off of the fit)
    assert (radius0, radius1) == pytest.approx((slant - 1.5, slant + 1.5), rel=1e-14)  # measured 1e-15
    assert np.linalg.norm(centre0 - centre1) < 1e-12  # measured 8.5e-14
    e0, e1, a3 = strip_3d(CurvatureLineTube(axis, Rp), th, (0.0, 300.0), -1.5, 1.5)
    assert (pattern.base_length, pattern.top_length, pattern.area) == pytest.approx((e0, e1, a3), rel=2e-13)  # 1.8e-14
    part = stringer_flange_flat_pattern(tube, 60.0, T_PROFILE, "outside", span=(100.0, 250.0))  # half the arc
    assert (part.base_length, part.area) == pytest.approx((angle * (slant - 1.5) / 2, pattern.area / 2), rel=1e-14)


# --- ring flanges ---------------------------------------------------------------------------------
@pytest.mark.parametrize("profile, side", [(T_PROFILE, "outside"), (L_PROFILE, "inside")])
def test_tube_ring_flange_is_a_rectangle(helix_tube, profile, side):
    """The tangent planes along the ring circle of radius R' = R +- (h - tf/2) envelop a
    cylinder: the rectangle 2 pi R' by bf (its circumference also as a 3-D polyline)."""
    Rp = R + (1 if side == "outside" else -1) * LEVEL
    w0, w1 = widths(profile)
    pattern = ring_flange_flat_pattern(helix_tube, 250.0, profile, side)
    u = np.linspace(0.0, 2 * math.pi, 20001)
    ring = CurvatureLineTube(helix_tube.axis, Rp).points(u, np.full_like(u, 250.0))
    assert polyline(ring) == pytest.approx(2 * math.pi * Rp, rel=5e-9)  # measured 4.1e-9 (chords)
    assert (pattern.base_length, pattern.top_length) == pytest.approx((2 * math.pi * Rp,) * 2, rel=1e-15)
    assert pattern.area == pytest.approx(2 * math.pi * Rp * 3.0, rel=1e-15)
    expected = np.array([[0.0, w0], [2 * math.pi * Rp, w0], [2 * math.pi * Rp, w1], [0.0, w1]])
    assert np.abs(pattern.outline - expected).max() < 1e-13


@pytest.mark.parametrize("profile, side", [(T_PROFILE, "outside"), (L_PROFILE, "inside")])
def test_cone_ring_flange_is_an_annular_sector(cone, profile, side):
    """On a cone the tangent cone along a circle is the (offset) cone itself: its slant from the
    apex to the circle at s is D cos beta (:func:`cone_circle`), the band develops to the
    annular sector of angle 2 pi a / slant = 2 pi sin beta = 2 pi r', the edge w at radius
    slant + w (+w leads away from the apex, r' > 0)."""
    d = (1 if side == "outside" else -1) * LEVEL
    _, a, slant = cone_circle(20.0, R0 + d)
    angle = 2 * math.pi * a / slant
    assert angle == pytest.approx(2 * math.pi * SLOPE, rel=1e-15)
    w0, w1 = widths(profile)
    pattern = ring_flange_flat_pattern(cone, 20.0, profile, side)
    assert pattern.sector == pytest.approx((slant + w0, slant + w1, angle), rel=1e-14)  # measured 2.1e-15
    assert pattern.base_length == pytest.approx(angle * (slant + w0), rel=1e-14)
    assert pattern.top_length == pytest.approx(angle * (slant + w1), rel=1e-14)
    assert pattern.area == pytest.approx(0.5 * angle * ((slant + w1) ** 2 - (slant + w0) ** 2), rel=1e-14)
    assert pattern.centre_length == pytest.approx(2 * math.pi * a, rel=1e-14)
    base, top = edges(pattern)
    # round-off of the rotations at radii ~40: measured 8.5e-14 on one machine, 2.2e-13 on another
    assert np.abs(np.linalg.norm(base, axis=1) - (slant + w0)).max() < 3e-13
    assert np.abs(np.linalg.norm(top, axis=1) - (slant + w1)).max() < 3e-13
    assert polygon_area(pattern.outline) == pytest.approx(pattern.area, rel=1.5e-6)  # 1.14e-6: 720 chords


def test_a_flange_wider_than_its_line_bends_is_refused():
    """On the torus above, the parallel at th = 90 deg has geodesic radius rho = 100: a flange
    over 200 wide would fold its inner edge."""
    tube = CurvatureLineTube(NaturalAxis("0.01", "0", (0.0, 300.0)), R)
    wide = Profile("T", height=4.0, thickness=0.5, flange_width=201.0, flange_thickness=0.4)
    with pytest.raises(ParameterError, match=r"^flange_width: the flange edge at w = -100.5 folds over near s = "):
        stringer_flange_flat_pattern(tube, 90.0, wide)
