"""The curvature-line tube (docs/MATH.md sections 2-4), measured numerically on every family."""

import math

import numpy as np
import pytest

from tubecad import CurvatureLineTube, LogSpiral, RegularityError
from tubecad.surface import FundamentalForms, SurfaceDerivatives
from tubecad.surface.checks import area_by_quadrature, axis_distance_errors, net_errors

ROUND_OFF = 1e-13


def dense_grid(tube, nu=181, ns=1201):
    u = np.linspace(0.0, 2.0 * math.pi, nu, endpoint=False)[:, None]
    return u, np.linspace(*tube.span, ns)[None, :]


def test_net_is_orthogonal_and_conjugate_at_round_off(family_tube):
    net = net_errors(family_tube, nu=181, ns=1201)
    assert net.max_orthogonality_error < ROUND_OFF
    assert net.max_M_error < ROUND_OFF


def test_forms_match_the_closed_expressions(family_tube):
    tube = family_tube
    u, s = dense_grid(tube, 91, 601)
    f = tube.fundamental_forms(u, s)
    k, phi, rho = tube.axis.curvature(s), tube.phi(u, s), tube.radius
    g = 1 - rho * k * np.cos(phi)
    assert np.allclose(f.E, rho**2, rtol=1e-13, atol=0)
    assert np.allclose(f.G, g**2, rtol=1e-12, atol=1e-14)
    assert np.allclose(f.L, -rho, rtol=1e-13, atol=0)
    assert np.allclose(f.N, k * np.cos(phi) * g, rtol=1e-11, atol=1e-14)
    k1, k2 = f.principal_curvatures()
    kappa_u = k * np.cos(phi) / g
    assert np.allclose(np.minimum(k1, k2), np.minimum(-1 / rho, kappa_u), rtol=1e-10, atol=1e-14)
    assert np.allclose(np.maximum(k1, k2), np.maximum(-1 / rho, kappa_u), rtol=1e-10, atol=1e-14)


def test_derivative_vectors_are_derivatives_of_the_points(family_tube):
    """The analytic S_u, S_s, S_us, S_ss equal finite differences of S(u, s) itself, so the
    round-off F = M = 0 above is a fact about the surface we evaluate, not about a formula."""
    tube = family_tube
    s0, s1 = tube.span
    hs, hu = 1e-4 * (s1 - s0) / 10, 1e-4
    u = np.linspace(0.1, 6.2, 13)[:, None]
    s = np.linspace(s0 + 10 * hs, s1 - 10 * hs, 41)[None, :]
    d = tube.derivatives(u, s)
    P = tube.points

    def cd(f, h):
        return (-f(2 * h) + 8 * f(h) - 8 * f(-h) + f(-2 * h)) / (12 * h)

    scale = tube.radius + 1.0
    assert np.abs(cd(lambda h: P(u + h, s), hu) - d.S_u).max() < 1e-8 * scale
    assert np.abs(cd(lambda h: P(u, s + h), hs) - d.S_s).max() < 1e-8 * scale
    assert np.abs(cd(lambda h: tube.derivatives(u, s + h).S_u, hs) - d.S_us).max() < 1e-7 * scale
    assert np.abs(cd(lambda h: tube.derivatives(u, s + h).S_s, hs) - d.S_ss).max() < 1e-7 * scale
    assert np.allclose(d.S, P(u, s), rtol=0, atol=1e-12 * (1 + np.abs(d.S).max()))
    # The net measured from finite differences alone: orthogonal to FD accuracy.
    fd = SurfaceDerivatives(d.S, cd(lambda h: P(u + h, s), hu), cd(lambda h: P(u, s + h), hs), d.S_uu, d.S_us, d.S_ss)
    assert FundamentalForms.from_derivatives(fd).orthogonality_error.max() < 1e-8


def test_the_twist_compensation_is_what_makes_the_net_orthogonal():
    """Control: the Frenet-frame tube (v = u, no twist) has |cos| = rho sigma / sqrt(G),
    far from zero: the checks above would catch a wrong phi."""
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (200.0, 1200.0)), 15.0)
    u, s = dense_grid(tube, 64, 200)
    a = tube.axis.evaluate(s)
    ring_u = -np.sin(u)[..., None] * a.n + np.cos(u)[..., None] * a.bn
    S_u = tube.radius * ring_u
    dn, dbn = -a.k[..., None] * a.t + a.torsion[..., None] * a.bn, -a.torsion[..., None] * a.n
    S_s = a.t + tube.radius * (np.cos(u)[..., None] * dn + np.sin(u)[..., None] * dbn)
    cos_angle = np.abs(np.einsum("...i,...i", S_u, S_s)) / np.linalg.norm(S_u, axis=-1) / np.linalg.norm(S_s, axis=-1)
    assert cos_angle.max() > 0.01


def test_every_point_is_rho_from_the_axis_at_the_same_s(family_tube):
    u, s = dense_grid(family_tube, 24, 151)
    dist_err, s_err = axis_distance_errors(family_tube, u, s)
    assert dist_err < 1e-9 * family_tube.radius
    assert s_err < 1e-8 * family_tube.length


def test_numerically_integrated_area_is_2_pi_rho_L(family_tube):
    area = area_by_quadrature(family_tube)
    assert area == pytest.approx(family_tube.area_exact, rel=1e-12)
    assert family_tube.area_exact == pytest.approx(2 * math.pi * family_tube.radius * family_tube.length)
    assert family_tube.volume_exact == pytest.approx(
        math.pi * family_tube.radius**2 * family_tube.length, rel=1e-15
    )  # measured 0: the same closed form


def test_rings_are_exact_circles_in_the_normal_planes(family_tube):
    tube = family_tube
    s = np.linspace(*tube.span, 7)
    u = np.linspace(0, 2 * math.pi, 50)
    P = tube.grid(u, s)
    a = tube.axis.evaluate(s)
    offset = P - a.position[None]
    assert np.abs(np.linalg.norm(offset, axis=-1) - tube.radius).max() < 1e-12 * (1 + np.abs(P).max())
    assert np.abs(np.einsum("usi,si->us", offset, a.t)).max() < 1e-11 * (1 + np.abs(P).max())


def test_points_broadcast_and_grid_agree():
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (200.0, 1200.0)), 15.0)
    u = np.array([0.0, 1.0, 2.5])
    s = np.array([200.0, 700.0, 1200.0, 950.0])
    g = tube.grid(u, s)
    assert g.shape == (3, 4, 3)
    assert np.array_equal(g[1, 2], tube.points(u[1], s[2]))
    paired = tube.points(u, s[:3])
    assert np.allclose(paired, g[[0, 1, 2], [0, 1, 2]], rtol=0, atol=1e-12)


def test_offset_keeps_the_axis_and_net():
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (200.0, 1200.0)), 15.0)
    outer = tube.offset(1.0)
    u, s = dense_grid(tube, 16, 50)
    normal = tube.normal(u, s)
    assert np.allclose(outer.points(u, s), tube.points(u, s) + 1.0 * normal, rtol=0, atol=1e-11)
    assert outer.radius == 16.0
    # The paper's axis comes back within 32.8 of itself: radius 16.5 would self-intersect.
    with pytest.raises(RegularityError, match="comes back within 32.79"):
        tube.offset(1.5)
