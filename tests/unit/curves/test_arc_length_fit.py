"""A parametric axis re-read in arc length (issue 24): t(s) by Newton from the inverse table,
shared by one fit of (c, T, r1, k1, k2) in s whose parts each meet their own tolerance,
checked against a helix's closed forms; and the piecewise Chebyshev tools that fit uses."""

import math

import numpy as np
import pytest

from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.curves.parametric import ParametricAxis

A, B, TURNS = 30.0, 5.0, 40.0  # x = (A cos t, A sin t, B t), t in [0, TURNS]
SPEED = math.hypot(A, B)  # |x'|: s = SPEED t, k = A / SPEED^2, tau = B / SPEED^2


@pytest.fixture(scope="module")
def helix() -> ParametricAxis:
    return ParametricAxis(lambda t: np.stack([A * np.cos(t), A * np.sin(t), B * t], axis=-1), (0.0, TURNS))


def test_the_helix_in_arc_length_is_the_helix(helix):
    """Six turns and more, several panels: t(s) = s / |x'| and c(s) to 1e-13 of their sizes;
    T (one derivative of the fitted x(t) away) to 1e-11; k = A / |x'|^2 and the frame's turn
    against the Frenet normal, tau = B / |x'|^2, to 1e-10 (two derivatives away)."""
    assert helix.length == pytest.approx(SPEED * TURNS, rel=1e-14)
    s = np.linspace(*helix.span, 20001)
    t = s / SPEED
    assert np.abs(helix.parameter(s) - t).max() < 1e-13 * TURNS
    a = helix.at(s)
    exact = np.stack([A * np.cos(t), A * np.sin(t), B * t], axis=-1)
    assert np.abs(a.position - exact).max() < 1e-13 * B * TURNS
    tangent = np.stack([-A * np.sin(t), A * np.cos(t), np.full_like(t, B)], axis=-1) / SPEED
    assert np.abs(a.t - tangent).max() < 1e-11
    k, tau = A / SPEED**2, B / SPEED**2
    normal = np.stack([-np.cos(t), -np.sin(t), 0 * t], axis=-1)
    assert np.abs(a.curvature_vector - k * normal).max() < 1e-10 * k
    w = np.unwrap(np.arctan2(a.k2, a.k1))  # the Frenet normal's angle in (r1, r2): w0 + tau s
    assert np.abs((w - w[0]) - tau * s).max() < 1e-10 * (1 + tau * s[-1])


def test_at_is_the_axis_protocol_in_one_evaluation(helix):
    """at(s) (one evaluation of the stacked series) gives exactly what position,
    rotation_minimising_frame and normal_development give one by one."""
    s = np.linspace(*helix.span, 997)
    a = helix.at(s)
    T, r1, r2 = helix.rotation_minimising_frame(s)
    k1, k2 = helix.normal_development(s)
    for ours, theirs in [(a.position, helix.position(s)), (a.t, T), (a.r1, r1), (a.r2, r2), (a.k1, k1), (a.k2, k2)]:
        assert np.array_equal(ours, theirs)


def test_each_part_of_a_fit_meets_its_own_tolerance():
    """(1e8 x, 1e-3 sin 5x) fitted together: as one part the small value is resolved only
    relative to the large one's 1e9; as two parts to 1e-13 of its own size."""

    def f(x: np.ndarray) -> np.ndarray:
        return np.stack([1e8 * x, 1e-3 * np.sin(5 * x)], axis=-1)

    x = np.linspace(0.0, 10.0, 5001)
    small = 1e-3 * np.sin(5 * x)
    apart = PiecewiseChebyshev.fit(f, 0.0, 10.0, degree=12, parts=((1, 1e-15), (1, 1e-13)))
    together = PiecewiseChebyshev.fit(f, 0.0, 10.0, degree=12)
    assert np.abs(apart(x)[:, 1] - small).max() < 1e-13 * 1e-3
    assert np.abs(together(x)[:, 1] - small).max() > 1e-9 * 1e-3
    assert np.abs(apart(x)[:, 0] - 1e8 * x).max() < 1e-15 * 1e9
    with pytest.raises(ValueError, match="parts cover 3 values"):
        PiecewiseChebyshev.fit(f, 0.0, 1.0, parts=((1, 1e-15), (2, 1e-13)))


def test_rows_take_each_row_on_its_middle_panel():
    """A series jumping at the break 1 (f = x on [0, 1), 5 + x on [1, 2]): a row of nodes
    on [0, 1] ends on the break, and :meth:`rows` takes its end from its own panel."""
    coeffs = np.array([[[0.5], [0.5]], [[6.5], [0.5]]])  # x = 0.5 + 0.5 z on [0, 1]; 5 + x on [1, 2]
    f = PiecewiseChebyshev(np.array([0.0, 1.0, 2.0]), coeffs)
    row = np.array([[0.0, 0.5, 1.0], [1.0, 1.5, 2.0]])
    assert f(row)[0, 2, 0] == pytest.approx(6.0)  # a point on a break: the panel starting there
    assert np.allclose(f.rows(row)[..., 0], [[0.0, 0.5, 1.0], [6.0, 6.5, 7.0]], atol=1e-15)


def test_stacked_series_evaluate_as_each_one():
    """stack pads a lower degree with zero terms: x, x' and x'' of a series in one evaluation."""
    x = PiecewiseChebyshev.fit(lambda t: np.stack([np.sin(t), np.cos(3 * t), t**2], axis=-1), 0.0, 4.0)
    dx = x.derivative()
    jet = PiecewiseChebyshev.stack([x, dx, dx.derivative()])
    t = np.linspace(0.0, 4.0, 301)
    values = jet(t)
    assert values.shape == (301, 3, 3)
    assert np.allclose(values[:, 0], x(t), rtol=0, atol=1e-15)
    assert np.allclose(values[:, 1], dx(t), rtol=0, atol=1e-14)
    assert np.allclose(values[:, 2], dx.derivative()(t), rtol=0, atol=1e-13)
