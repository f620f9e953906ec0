"""Canal surfaces referred to their lines of curvature (issue 12, docs/MATH.md section 8).

Every expected value here comes from a closed form written in this file (a cone's, a
frustum's, a Dupin cyclide's, a disc sweep's) or from an independent integrator, never from
the code's own output.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from tubecad import (
    CurvatureLineTube,
    Helix,
    NaturalAxis,
    ParameterError,
    ParametricAxis,
    RegularityError,
)
from tubecad.curves.radius_law import radius_law
from tubecad.surface.canal import CanalSurface, tube_or_canal
from tubecad.surface.checks import net_errors

# --- a straight axis with r = r0 + m s: a cone ------------------------------------------------
R0, SLOPE, LENGTH = 2.0, 0.3, 40.0


@pytest.fixture(scope="module")
def cone():
    axis = NaturalAxis("0", "0", (0.0, LENGTH))  # the x axis from the origin
    return CanalSurface(axis, f"{R0} + {SLOPE} * s")


def test_cone_points_lie_on_the_cone(cone):
    """The envelope of spheres centred on a line whose radius grows like m s is the cone with
    apex at s = -r0 / m on the line and sin(half-angle) = m: distance from the line =
    (axial distance from the apex) tan(half-angle)."""
    chi0 = np.linspace(0.0, 2 * math.pi, 37)[:, None]
    s = np.linspace(0.0, LENGTH, 41)[None, :]
    p = cone.points(chi0, s)
    apex = -R0 / SLOPE
    tan_half = SLOPE / math.sqrt(1.0 - SLOPE**2)
    expected = (p[..., 0] - apex) * tan_half
    assert np.abs(np.hypot(p[..., 1], p[..., 2]) - expected).max() < 1e-12 * (R0 + SLOPE * LENGTH)
    # a stringer is a generator: its points stay on one ray from the apex (constant angle)
    angle = np.arctan2(p[..., 2], p[..., 1])
    assert np.abs(np.angle(np.exp(1j * (angle - angle[:, :1])))).max() < 1e-12


def test_cone_frustum_area_and_volume(cone):
    """Between the first and last characteristic circles (radius R = r q, in the planes
    x = s - r r'), the surface is a frustum: area pi (R0 + R1) slant, volume
    pi h (R0^2 + R0 R1 + R1^2) / 3."""
    q = math.sqrt(1.0 - SLOPE**2)
    r_end = R0 + SLOPE * LENGTH
    radii = (R0 * q, r_end * q)
    h = (LENGTH - r_end * SLOPE) - (0.0 - R0 * SLOPE)
    slant = math.hypot(h, radii[1] - radii[0])
    area, volume = cone.measures()
    assert area == pytest.approx(math.pi * sum(radii) * slant, rel=1e-10)
    assert volume == pytest.approx(math.pi * h * (radii[0] ** 2 + radii[0] * radii[1] + radii[1] ** 2) / 3.0, rel=1e-10)
    assert cone.area == pytest.approx(area, rel=1e-15) and cone.volume == pytest.approx(volume, rel=1e-15)


def test_a_two_point_table_is_the_same_cone(cone):
    """Two table rows interpolate linearly (not-a-knot cubic through 2 points)."""
    table = CanalSurface(cone.axis, [[0.0, R0], [LENGTH, R0 + SLOPE * LENGTH]])
    assert "not-a-knot" in table.radius_law.describe()["interpolation"]
    chi0, s = np.linspace(0.0, 6.0, 7)[:, None], np.linspace(0.0, LENGTH, 9)[None, :]
    assert np.abs(table.points(chi0, s) - cone.points(chi0, s)).max() < 1e-12 * LENGTH


# --- the ring Dupin cyclide: all its curvature lines are circles --------------------------------
A, B, C, MU = 10.0, 8.0, 6.0, 8.0  # c^2 = a^2 - b^2, 0 < c < mu < a


@pytest.fixture(scope="module")
def cyclide():
    axis = ParametricAxis(lambda t: np.stack([A * np.cos(t), B * np.sin(t), 0.0 * t], axis=-1), (0.0, 2 * math.pi))
    assert axis.closed
    return CanalSurface(axis, lambda s: MU - (C / A) * axis.position(s)[..., 0])


def circle_fit(points):
    """(largest distance from the fitted circle, its radius): the plane by SVD, then the
    circle in the plane by linear least squares (|p|^2 = 2 p.m + const)."""
    centre = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centre)
    off_plane = np.abs((points - centre) @ vt[2]).max()
    xy = (points - centre) @ vt[:2].T
    sol = np.linalg.lstsq(np.c_[2 * xy, np.ones(len(xy))], (xy**2).sum(axis=1), rcond=None)[0]
    radius = math.sqrt(sol[2] + sol[0] ** 2 + sol[1] ** 2)
    return max(off_plane, np.abs(np.linalg.norm(xy - sol[:2], axis=1) - radius).max()), radius


@pytest.mark.parametrize("chi0", [0.0, 0.7, 1.5, 2.5, math.pi, 4.0, 5.5])
def test_cyclide_stringers_are_circles(cyclide, chi0):
    s = np.linspace(*cyclide.span, 50)
    residual, radius = circle_fit(cyclide.points(chi0, s))
    assert residual <= 1e-10 * A
    assert 0.1 < radius < 2 * A
    # a circle closes: the stringer comes back to its start after one turn of the ellipse
    assert np.linalg.norm(cyclide.points(chi0, s[-1]) - cyclide.points(chi0, s[0])) < 1e-10 * A


def test_cyclide_characteristic_circles(cyclide):
    """Points at fixed s lie on the circle of radius r q about c - r r' t, in the plane normal
    to t (r = mu - (c/a) x, r' = -(c/a) t_x computed here from the axis)."""
    s = np.linspace(*cyclide.span, 23)
    frame = cyclide.axis.at(s)
    r, dr = MU - (C / A) * frame.position[:, 0], -(C / A) * frame.t[:, 0]
    centre = frame.position - (r * dr)[:, None] * frame.t
    p = cyclide.points(np.linspace(0.0, 2 * math.pi, 40)[:, None], s[None, :])
    assert np.abs(np.linalg.norm(p - centre, axis=-1) - r * np.sqrt(1 - dr**2)).max() < 1e-12 * A
    assert np.abs(np.einsum("...i,...i", p - centre, frame.t)).max() < 1e-12 * A
    c, radius, _ = cyclide.circle(s)
    assert np.allclose(c, centre, rtol=0, atol=1e-12 * A) and np.allclose(radius, r * np.sqrt(1 - dr**2), rtol=1e-13)


def test_cyclide_net_is_a_curvature_line_net(cyclide):
    net = net_errors(cyclide, nu=64, ns=401)
    assert net.max_orthogonality_error <= 1e-10 and net.max_M_error <= 1e-10


# --- a variable radius on a curved, twisted axis -----------------------------------------------
def twisted_axis():
    return NaturalAxis("0.08 + 0.03 * sin(s / 15)", "0.05 * cos(s / 30)", (0.0, 120.0))


def r_twisted(s):  # "3 + 2 * sin(s / 8)" and its derivatives, written out
    return 3 + 2 * np.sin(s / 8), 0.25 * np.cos(s / 8), -(2 / 64) * np.sin(s / 8)


@pytest.fixture(scope="module")
def twisted():
    return CanalSurface(twisted_axis(), "3 + 2 * sin(s / 8)")


@pytest.fixture(scope="module")
def helical():
    return CanalSurface(Helix(0.02, 30.0, (0.0, 200.0)), "3 + 0.5*sin(s/20)")


@pytest.mark.parametrize("name", ["twisted", "helical"])
def test_net_is_orthogonal_and_conjugate(name, request):
    net = net_errors(request.getfixturevalue(name), nu=64, ns=801)
    assert net.max_orthogonality_error <= 1e-10 and net.max_M_error <= 1e-10


def test_stringers_solve_their_equation(twisted):
    """chi(s) from the Moebius solution equals an independent Runge-Kutta integration of
    d chi / ds = -(r'/q)(k1 sin chi - k2 cos chi), rtol 1e-12."""
    axis = twisted.axis

    def rhs(s, chi):
        dr = r_twisted(s)[1]
        k1, k2 = axis.normal_development(np.array(s))
        return -(dr / math.sqrt(1 - dr * dr)) * (k1 * np.sin(chi) - k2 * np.cos(chi))

    s = np.linspace(*twisted.span, 61)
    turned = 0.0
    for chi0 in np.linspace(0.0, 2 * math.pi, 9):
        ref = solve_ivp(rhs, twisted.span, [chi0], method="DOP853", rtol=1e-12, atol=1e-13, t_eval=s).y[0]
        assert np.abs(twisted.stringer_angle(chi0, s) - ref).max() < 1e-10
        turned = max(turned, float(np.ptp(ref)))
    assert turned > 0.3  # the stringers really do turn away from chi = const


def test_derivative_vectors_are_derivatives_of_the_points(twisted):
    """The S_u, S_s, S_uu, S_us, S_ss that F, M are measured on equal finite differences of the
    points themselves."""
    P, D = twisted.points, twisted.derivatives
    chi0 = np.linspace(0.1, 6.2, 11)[:, None]
    s = np.linspace(1.0, 119.0, 31)[None, :]
    d = D(chi0, s)

    def cd(f, h):
        return (-f(2 * h) + 8 * f(h) - 8 * f(-h) + f(-2 * h)) / (12 * h)

    h = 1e-3
    assert np.abs(cd(lambda e: P(chi0 + e, s), h) - d.S_u).max() < 1e-9
    assert np.abs(cd(lambda e: P(chi0, s + e), h) - d.S_s).max() < 1e-9
    assert np.abs(cd(lambda e: D(chi0 + e, s).S_u, h) - d.S_uu).max() < 1e-9
    assert np.abs(cd(lambda e: D(chi0, s + e).S_u, h) - d.S_us).max() < 1e-9
    assert np.abs(cd(lambda e: D(chi0, s + e).S_s, h) - d.S_ss).max() < 1e-9


def test_area_and_volume_match_the_closed_forms(twisted):
    """Area 2 pi Int r (q^2 - r r'') ds (the stringer speed q - r r''/q - r kappa averaged over
    the circle: kappa integrates to 0) and volume pi Int (r q)^2 (q^2 - r r'') ds (the discs of
    the characteristic circles swept along the axis: their centres advance by q^2 - r r'' per
    unit s along t); the code integrates 3-D vectors by the divergence theorem instead."""

    def area_density(s):
        r, dr, ddr = r_twisted(s)
        return 2 * math.pi * r * (1 - dr**2 - r * ddr)

    def volume_density(s):
        r, dr, ddr = r_twisted(s)
        return math.pi * r**2 * (1 - dr**2) * (1 - dr**2 - r * ddr)

    area, volume = twisted.measures()
    opts = {"epsabs": 0, "epsrel": 1e-13, "limit": 200}
    assert area == pytest.approx(quad(area_density, *twisted.span, **opts)[0], rel=1e-10)
    assert volume == pytest.approx(quad(volume_density, *twisted.span, **opts)[0], rel=1e-10)


def test_a_table_law_gives_a_curvature_line_net():
    axis = twisted_axis()
    surface = CanalSurface(axis, [[0, 3], [30, 4], [55, 3.2], [90, 3.8], [120, 3]])
    assert list(surface.radius_law.breaks) == [30, 55, 90]
    net = net_errors(surface, nu=48, ns=601)
    assert net.max_orthogonality_error <= 1e-10 and net.max_M_error <= 1e-10


# --- a constant law is today's tube ------------------------------------------------------------
def test_constant_law_is_the_tube():
    axis = twisted_axis()
    tube, canal = CurvatureLineTube(axis, 3.0), CanalSurface(axis, 3.0)
    u, s = np.linspace(0.0, 2 * math.pi, 33)[:, None], np.linspace(*axis.span, 57)[None, :]
    assert np.array_equal(canal.points(u, s), tube.points(u, s))
    assert np.array_equal(canal.stringer_angle(u, s), u + 0 * s)
    dt, dc = tube.derivatives(u, s), canal.derivatives(u, s)
    for name in ("S", "S_u", "S_s", "S_uu", "S_us", "S_ss"):
        assert np.abs(getattr(dc, name) - getattr(dt, name)).max() <= 1e-15 * (1 + np.abs(getattr(dt, name)).max())
    area, volume = canal.measures()
    assert area == pytest.approx(tube.area_exact, rel=1e-13) and volume == pytest.approx(tube.volume_exact, rel=1e-13)
    assert canal.regularity.max_fold == pytest.approx(tube.regularity.max_rho_k, rel=1e-12)
    assert type(tube_or_canal(axis, 3.0)) is CurvatureLineTube
    assert type(tube_or_canal(axis, "3 + 0.1 * sin(s)")) is CanalSurface


def test_offset_keeps_the_stringers(twisted):
    outer = twisted.offset(0.5)
    chi0, s = np.linspace(0.0, 6.0, 5)[:, None], np.linspace(*twisted.span, 13)[None, :]
    assert np.abs(outer.stringer_angle(chi0, s) - twisted.stringer_angle(chi0, s)).max() < 1e-13
    gap = np.linalg.norm(outer.points(chi0, s) - twisted.points(chi0, s), axis=-1)
    assert np.abs(gap - 0.5).max() < 1e-12


# --- bad input: one line naming the key and where ----------------------------------------------
def refused(error, match, *args, **kwargs):
    with pytest.raises(error) as info:
        CanalSurface(*args, **kwargs)
    message = str(info.value)
    assert "\n" not in message and "radius" in message and match in message, message
    return message


@pytest.mark.parametrize(
    "law, says",
    [
        ("2 - 0.1 * s", "r reaches -2 at s = 40"),
        ("3 + 0.02 * s**2", "|r'| reaches 1.6 at s = 40"),
        ("3 + 1 / (s - 20)", "not finite at s = 20"),
        ("sqrt(s - 5)", "not finite at s = 0"),
        ([[0, 3], [30, 4], [20, 3], [40, 3]], "s = 20 (row 2) follows s = 30 (row 1)"),
        ([[0, 3], [20, 4], [20, 3], [40, 3]], "s = 20 (row 2) appears twice"),
        ([[5, 3], [40, 3]], "misses s = 0"),
        ([[0, 3], [30, 3]], "misses s = 40"),
        ([[0, 3], [20, -1], [40, 3]], "r = -1 at s = 20"),
        ([[0, 1], [10, 1], [12, 4], [40, 4]], "r reaches -2.9"),  # the spline overshoots between rows
        ([[0, 3], [40, 50]], "|r'| reaches 1.175 at s = "),
    ],
)
def test_bad_laws_are_refused(law, says):
    axis = NaturalAxis("0.01", "0", (0.0, 40.0))
    refused(ParameterError, says, axis, law)


def test_a_folding_law_is_refused_with_where():
    axis = NaturalAxis("0.2", "0", (0.0, 31.0))  # a circle of radius 5, not quite closed
    message = refused(RegularityError, "at s = 15.70", axis, "4 + 2.5 * sin(s / 10)")
    assert "folds" in message and "allow_irregular" in message
    surface = CanalSurface(axis, "4 + 2.5 * sin(s / 10)", allow_irregular=True)
    ((a, b),) = surface.regularity.folded_intervals
    # r (k q + r'') / q^2 = 1 at the ends of the folded run, from the law written out here
    for s in (a, b):
        r, dr, ddr = 4 + 2.5 * math.sin(s / 10), 0.25 * math.cos(s / 10), -0.025 * math.sin(s / 10)
        q = math.sqrt(1 - dr * dr)
        assert r * (0.2 * q + ddr) / q**2 == pytest.approx(1.0, abs=1e-9)


def test_describe_names_the_law_and_its_extremes():
    law = radius_law("3 + 0.5*sin(s/20)", (0.0, 200.0))
    d = law.describe()
    assert d["kind"] == "expression" and d["radius"] == "3 + 0.5*sin(s/20)"
    assert d["max_abs_slope"] == pytest.approx(0.025, rel=1e-10)
    assert d["s_at_max_abs_slope"] == pytest.approx(0.0, abs=1e-6)
    assert d["min"] == pytest.approx(2.5, rel=1e-12) and d["s_at_min"] == pytest.approx(30 * math.pi, rel=1e-6)
    constant = radius_law(3, (0.0, 1.0))
    assert constant.constant and constant.dr(np.array([0.5])).tolist() == [0.0] and constant.ddr(0.2) == 0.0


def test_stringer_speed_is_the_fold_formula(twisted):
    """sqrt(G) measured on the derivative vectors equals q - r r''/q - r (k1 cos chi + k2 sin chi),
    the speed whose zero is the fold condition r (k q + r'') / q^2 = 1 (r, r', r'' written out)."""
    chi0, s = np.linspace(0.0, 2 * math.pi, 24, endpoint=False)[:, None], np.linspace(*twisted.span, 101)[None, :]
    forms = twisted.fundamental_forms(chi0, s)
    r, dr, ddr = r_twisted(s)
    q = np.sqrt(1 - dr**2)
    chi = twisted.stringer_angle(chi0, s)
    k1, k2 = twisted.axis.normal_development(s)
    speed = q - r * ddr / q - r * (k1 * np.cos(chi) + k2 * np.sin(chi))
    assert np.abs(np.sqrt(forms.G) - speed).max() < 1e-11
    lowest = q * (1 - r * (np.hypot(k1, k2) * q + ddr) / q**2)  # on the stringer where kappa = k
    assert (np.sqrt(forms.G) - lowest).min() > -1e-11
    # 24 stringers come within an angle pi/24 of the lowest one at every s
    gap = np.sqrt(forms.G).min(axis=0) - lowest[0]
    assert gap.max() <= (r * np.hypot(k1, k2)).max() * (1 - math.cos(math.pi / 24)) + 1e-11


# --- the envelope distance round a long closed loop (random-spec cases 163, 715, 727, 967) -----
def test_envelope_distance_round_a_long_loop():
    """Points on a closed canal surface whose loop is ~6000 radii long lie at distance 0 from
    it, also on both sides of the closing ring. The points are the characteristic circles'
    by hand: centre c - r r' t, radius r sqrt(1 - r'^2), in the plane of n and b (a circle
    axis of radius R: t, n, b are closed forms). The read-back measure once sampled such a
    loop more than a radius apart, and kept s inside [0, L] instead of running on across the
    closing, and refused the files of regular tubes."""
    from tubecad.surface.checks import envelope_distance

    R, r0, a = 2.0e4, 20.0, 2.0
    L = 2 * math.pi * R
    axis = ParametricAxis(
        lambda t: np.stack([R * np.cos(t), R * np.sin(t), 0.0 * t], axis=-1), (0.0, 2 * math.pi), closed=True
    )
    canal = CanalSurface(axis, f"{r0!r} + {a!r} * cos(2 * pi * s / {axis.length!r})")
    s = np.concatenate([np.linspace(0.0, L, 97), [0.3, 1.0, L - 0.3, L - 1.0]])
    phi = np.linspace(0.0, 2 * math.pi, 7)[:, None]
    w = s / R
    c = np.stack([R * np.cos(w), R * np.sin(w), 0 * w], axis=-1)
    t = np.stack([-np.sin(w), np.cos(w), 0 * w], axis=-1)
    n = -c / R
    b = np.array([0.0, 0.0, 1.0])
    r = r0 + a * np.cos(2 * math.pi * s / L)
    dr = -a * 2 * math.pi / L * np.sin(2 * math.pi * s / L)
    centre = c - (r * dr)[:, None] * t
    size = (r * np.sqrt(1 - dr**2))[None, :, None]
    points = centre[None] + size * (np.cos(phi)[..., None] * n[None] + np.sin(phi)[..., None] * b)
    distance, found = envelope_distance(canal, points)
    assert np.abs(distance).max() < 1e-9 * R
    ring = np.minimum(np.abs(found - s[None]), L - np.abs(found - s[None]))  # the sphere each point is on
    assert ring.max() < 1e-6 * r0
