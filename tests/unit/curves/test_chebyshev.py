"""The piecewise Chebyshev series every parametric axis is made of (tubecad.curves.chebyshev):
resolved to round-off and evaluated to round-off on both of its paths (Clenshaw's recurrence
over all points at once, in blocks, or panel by panel where many points share one), against
closed forms, at panel ends and breaks too."""

from __future__ import annotations

import numpy as np
import pytest

from tubecad.curves import chebyshev
from tubecad.curves.chebyshev import PiecewiseChebyshev


def _curve(t: np.ndarray) -> np.ndarray:
    return np.stack([np.sin(t), np.exp(t / 10.0), 1.0 / (1.0 + t)], axis=-1)


@pytest.fixture(scope="module")
def series():
    return PiecewiseChebyshev.fit(_curve, 0.0, 30.0, breaks=np.linspace(0.0, 30.0, 9))


@pytest.mark.parametrize("points", [1, 7, 128, 3000, chebyshev.BLOCK_POINTS + 1, 20000])
def test_every_evaluation_path_is_the_closed_form_to_round_off(series, points):
    rng = np.random.default_rng(points)
    x = rng.uniform(0.0, 30.0, points)
    x[: min(points, 3)] = [0.0, 30.0, series.breaks[3]][: min(points, 3)]  # the ends and a break
    exact = _curve(x)
    got = series(x)
    assert got.shape == (points, 3)
    # the series' own resolution is 1e-15 of the scale (e^3 = 20.1); evaluation adds a few ulps
    assert np.abs(got - exact).max() <= 1e-14 * np.exp(3.0)


def test_the_paths_meet_at_their_crossovers(series):
    """The same points evaluated one by one, together (all at once) and many per panel
    (panel by panel): equal to a few ulps."""
    x = np.linspace(0.0, 30.0, 40001)
    grouped = series(x)  # 5000 points per panel: the per-panel path
    together = np.concatenate([series(x[i : i + 1000]) for i in range(0, len(x), 1000)])  # 125 a panel
    alone = np.array([series(np.array([v]))[0] for v in x[::97]])
    assert np.abs(grouped - together).max() <= 4e-15 * np.exp(3.0)
    assert np.abs(grouped[::97] - alone).max() <= 4e-15 * np.exp(3.0)


def test_antiderivative_and_derivative_are_the_closed_forms(series):
    x = np.linspace(0.0, 30.0, 777)
    integral = series.antiderivative(np.array([0.0, 10.0, 0.0]))(x)
    assert np.abs(integral[:, 0] - (1.0 - np.cos(x))).max() < 1e-13
    assert np.abs(integral[:, 1] - 10.0 * np.exp(x / 10.0)).max() < 1e-13 * 10.0 * np.exp(3.0)
    assert np.abs(integral[:, 2] - np.log1p(x)).max() < 1e-13
    assert np.abs(series.derivative()(x)[:, 0] - np.cos(x)).max() < 1e-12


def test_a_scalar_and_a_grid_keep_their_shapes(series):
    assert series(np.array(2.0)).shape == (3,)
    assert series(np.full((4, 5), 2.0)).shape == (4, 5, 3)
