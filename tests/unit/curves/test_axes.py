"""Axes (docs/MATH.md section 1): closed forms checked against their definitions and against
the independent numeric (Chebyshev quadrature) path."""

import math

import numpy as np
import pytest

from tubecad import CircleInvolute, Clothoid, CustomCurvature, Helix, LogSpiral

CLOSED_FORMS = {
    "log_spiral": (LogSpiral(10.0, 10.0, (200.0, 1200.0)), "10 / s"),
    "helix": (Helix(0.02, 30.0, (0.0, 1000.0)), "0.02"),
    "circle": (Helix(0.05, 0.0, (0.0, 125.0)), "0.05"),
    "clothoid": (Clothoid(300.0, 20.0, (-500.0, 800.0)), "s / 300**2"),
    "involute": (CircleInvolute(50.0, 15.0, (10.0, 1000.0)), "1 / sqrt(2 * 50 * s)"),
    "steep_log_spiral": (LogSpiral(3.0, -60.0, (5.0, 300.0)), "3 / s"),
}


def central_difference(f, s, h):
    """Fourth-order central difference of f at s."""
    return (-f(s + 2 * h) + 8 * f(s + h) - 8 * f(s - h) + f(s - 2 * h)) / (12 * h)


@pytest.mark.parametrize("name", sorted(CLOSED_FORMS))
def test_numeric_path_matches_closed_form_to_1e12_relative(name):
    axis, k_text = CLOSED_FORMS[name]
    s0 = axis.span[0]
    numeric = CustomCurvature(
        k_text, axis.beta_deg, axis.span, psi0_deg=math.degrees(axis.psi(s0)), origin=axis.position(s0)
    )
    s = np.linspace(*axis.span, 5001)
    scale = axis.length
    assert np.abs(numeric.position(s) - axis.position(s)).max() / scale < 1e-12
    assert np.abs(numeric.psi(s) - axis.psi(s)).max() < 1e-12 * max(1.0, np.abs(axis.psi(s)).max())
    for a, b in zip(numeric.frame(s), axis.frame(s)):
        assert np.abs(a - b).max() < 1e-12
    dk_scale = np.abs(axis.curvature_derivative(s)).max() + np.abs(axis.curvature(s)).max() / axis.length
    assert np.abs(numeric.curvature_derivative(s) - axis.curvature_derivative(s)).max() / dk_scale < 1e-9


def test_numeric_path_accepts_python_callable():
    axis = CustomCurvature(lambda s: 10.0 / s, 10.0, (200.0, 1200.0))
    text = CustomCurvature("10 / s", 10.0, (200.0, 1200.0))
    s = np.linspace(200, 1200, 101)
    assert np.abs(axis.position(s) - text.position(s)).max() < 1e-12 * 1000
    assert np.allclose(axis.position(200.0), 0.0)


@pytest.mark.parametrize("name", sorted(CLOSED_FORMS))
def test_closed_form_is_arc_length_parameterised_with_curvature_k(name):
    """c' = t (unit), |c''| = |k|, torsion = k tan b: by finite differences of c(s)."""
    axis, _ = CLOSED_FORMS[name]
    s0, s1 = axis.span
    h = 1e-3 * (s1 - s0) / 100
    s = np.linspace(s0 + 4 * h, s1 - 4 * h, 301)
    a = axis.evaluate(s)
    d1 = central_difference(axis.position, s, h)
    assert np.abs(d1 - a.t).max() < 1e-8
    assert np.abs(np.linalg.norm(a.t, axis=-1) - 1).max() < 1e-14
    dt = central_difference(lambda x: axis.frame(x)[0], s, h)
    assert np.abs(dt - a.k[:, None] * a.n).max() < 1e-8 * max(1.0, np.abs(a.k).max())
    dbn = central_difference(lambda x: axis.frame(x)[2], s, h)
    assert np.abs(dbn + a.torsion[:, None] * a.n).max() < 1e-8 * max(1.0, np.abs(a.torsion).max())
    assert np.allclose(a.torsion, a.k * math.tan(axis.beta), rtol=0, atol=1e-15)


@pytest.mark.parametrize("name", sorted(CLOSED_FORMS))
def test_frenet_frame_is_right_handed_orthonormal(name):
    axis, _ = CLOSED_FORMS[name]
    t, n, bn = axis.frame(np.linspace(*axis.span, 257))
    for u, v in ((t, n), (n, bn), (t, bn)):
        assert np.abs(np.einsum("ij,ij->i", u, v)).max() < 1e-15
    assert np.abs(np.cross(t, n) - bn).max() < 1e-15


def test_log_spiral_is_the_papers_equation_9():
    """x0, y0 of paper eq. 9 written out independently, and z0 = s sin b."""
    a, beta = 10.0, math.radians(10.0)
    axis = LogSpiral(a, 10.0, (200.0, 1200.0))
    s = np.linspace(200, 1200, 11)
    cb, q = math.cos(beta), a * np.log(s) / math.cos(beta)
    x0 = s * cb**2 / (a**2 + cb**2) * (cb * np.cos(q) + a * np.sin(q))
    y0 = s * cb**2 / (a**2 + cb**2) * (cb * np.sin(q) - a * np.cos(q))
    assert np.allclose(axis.position(s), np.stack([x0, y0, s * math.sin(beta)], axis=1), rtol=0, atol=1e-11)


def test_helix_geometry_from_radius_and_pitch():
    helix = Helix.from_radius_pitch(50.0, 40.0, (0.0, 2000.0))
    assert helix.cylinder_radius == pytest.approx(50.0, rel=1e-14)
    assert helix.pitch == pytest.approx(40.0, rel=1e-14)
    p = helix.position(np.linspace(0, 2000, 1001))
    centre = p[:, :2] - p[:, :2].mean(axis=0)  # many full turns: mean ~ the cylinder axis
    turns = 2000 / (2 * math.pi * 50 / math.cos(helix.beta))
    assert turns > 5
    radial = np.linalg.norm(p[:, :2] - (p[:, :2].max(axis=0) + p[:, :2].min(axis=0)) / 2, axis=1)
    assert np.abs(radial - 50.0).max() < 1e-3 and centre.shape == (1001, 2)
    z_per_turn = p[:, 2][-1] / turns
    assert z_per_turn == pytest.approx(40.0, rel=1e-12)


def test_zero_curvature_helix_is_a_straight_line():
    line = Helix(0.0, 30.0, (0.0, 10.0))
    p = line.position(np.array([0.0, 10.0]))
    assert np.allclose(p[1] - p[0], [10 * math.cos(math.radians(30)), 0, 10 * math.sin(math.radians(30))])
