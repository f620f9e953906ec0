"""The contact proofs of touching faces' cells (tubecad.brep.contact): the derivative bounds hold
the derivatives sampled from an independent evaluation, the side and corner proofs accept patches
of one smooth surface cut apart and refuse patches folded back over each other."""

from __future__ import annotations

from math import comb

import numpy as np
import pytest

from tubecad.brep import contact


def _evaluate(grid: np.ndarray, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """S(s, t) of a rational Bezier patch by its Bernstein sums (points (len(s), 3))."""
    m, n = grid.shape[0] - 1, grid.shape[1] - 1
    bs = np.array([comb(m, i) * s**i * (1 - s) ** (m - i) for i in range(m + 1)])  # (m+1, k)
    bt = np.array([comb(n, j) * t**j * (1 - t) ** (n - j) for j in range(n + 1)])
    homogeneous = np.einsum("ik,jk,ijx->kx", bs, bt, grid)
    return homogeneous[:, :3] / homogeneous[:, 3:]


def _cylinder_patch(radius: float, angles: tuple[float, float], heights: tuple[float, float], degree_t: int = 3):
    """The cylinder x^2 + y^2 = r^2 over an arc (a rational quadratic, exact) and a height range
    (a polynomial of ``degree_t`` in t, the straight line's poles spread evenly)."""
    a0, a1 = angles
    half = 0.5 * (a1 - a0)
    middle = 0.5 * (a0 + a1)
    arc = [
        (radius * np.cos(a0), radius * np.sin(a0), 1.0),
        (radius * np.cos(middle) / np.cos(half), radius * np.sin(middle) / np.cos(half), np.cos(half)),
        (radius * np.cos(a1), radius * np.sin(a1), 1.0),
    ]
    zs = np.linspace(*heights, degree_t + 1)
    grid = np.zeros((3, degree_t + 1, 4))
    for i, (x, y, w) in enumerate(arc):
        for j, z in enumerate(zs):
            grid[i, j] = (w * x, w * y, w * z, w)
    return grid


@pytest.mark.parametrize(
    "weights", [(1.0, 0.7071067811865476, 0.5857864376269051), (1.0, np.cos(np.pi / 8), 1.0), (2.0, 0.3, 1.0)]
)
def test_lambda_bounds_hold_the_rational_quadratic_derivative_factor(weights):
    # C'(s) = 2 [w0 w1 (1-s)^2 (P1-P0) + w0 w2 s(1-s) (P2-P0) + w1 w2 s^2 (P2-P1)] / W^2 (Farin, ch. 13)
    w0, w1, w2 = weights
    s = np.linspace(0.0, 1.0, 4001)
    big_w = w0 * (1 - s) ** 2 + 2 * w1 * s * (1 - s) + w2 * s**2
    factor = 2 * (w0 * w1 * (1 - s) ** 2 + w0 * w2 * s * (1 - s) + w1 * w2 * s**2) / big_w**2
    scale = max(weights)
    w = np.array([[x / scale for x in weights]])
    low, high = contact.lambda_bounds(w, w)[0]
    factor_scaled = factor  # Lambda does not change when every weight is scaled
    assert low <= factor_scaled.min() and factor_scaled.max() <= high * (1 + 1e-12)
    assert low >= 0.85 * factor_scaled.min() and high <= 1.15 * factor_scaled.max()  # tight enough to prove


@pytest.mark.parametrize("weights", ["none", "one index", "both indices"])
def test_the_derivative_sets_hold_the_sampled_derivatives(weights):
    rng = np.random.default_rng(7)
    for _ in range(20):
        poles = rng.normal(size=(3, 6, 3))
        if weights == "none":
            w = np.ones((3, 6))
        elif weights == "one index":
            w = np.repeat(rng.uniform(0.3, 2.0, size=3)[:, None], 6, axis=1)
        else:  # a canal surface's: the circle's weights, changing a little along the axis
            w = rng.uniform(0.3, 2.0, size=3)[:, None] * rng.uniform(0.9, 1.1, size=(3, 6))
        grid = np.concatenate([poles * w[..., None], w[..., None]], axis=-1)
        s, t = rng.uniform(0.01, 0.99, 200), rng.uniform(0.01, 0.99, 200)
        h = 1e-6
        derivatives = [
            (_evaluate(grid, s + h, t) - _evaluate(grid, s - h, t)) / (2 * h),
            (_evaluate(grid, s, t + h) - _evaluate(grid, s, t - h)) / (2 * h),
        ]
        varies = [weights == "both indices" or weights == "one index", weights == "both indices"]
        for axis in (0, 1):
            lam, vectors, radius = contact.derivative_sets(grid[None], axis, varies[axis])
            for direction in rng.normal(size=(5, 3)):
                on = vectors[0] @ direction
                reach = radius[0] * np.linalg.norm(direction)
                corners = np.outer(lam[0], [on.min() - reach, on.max() + reach])
                sampled = derivatives[axis] @ direction
                slack = 1e-6 * (1 + np.abs(sampled).max())
                assert corners.min() - slack <= sampled.min() and sampled.max() <= corners.max() + slack


def test_lambda_bounds_of_a_box_of_weights_hold_every_weight_in_it():
    rng = np.random.default_rng(3)
    low = rng.uniform(0.4, 1.0, size=4)
    high = low * rng.uniform(1.0, 1.05, size=4)
    least, most = contact.lambda_bounds(low[None], high[None])[0]
    s = np.linspace(0.0, 1.0, 1001)[:, None]
    basis = np.concatenate([comb(3, i) * s**i * (1 - s) ** (3 - i) for i in range(4)], axis=1)
    slope = np.gradient(basis, s[:, 0], axis=0)
    for _ in range(50):
        w = rng.uniform(low, high)
        numerator = sum(
            w[i] * w[k] * (slope[:, k] * basis[:, i] - basis[:, k] * slope[:, i])
            for i in range(4)
            for k in range(i + 1, 4)
        )
        factor = numerator / (basis @ w) ** 2
        assert least <= factor.min() * (1 + 1e-3) and factor.max() <= most * (1 + 1e-3)


def test_a_cylinder_cut_in_two_meets_only_along_the_cut_and_a_fold_is_refused():
    a = _cylinder_patch(10.0, (0.0, np.pi / 4), (0.0, 5.0))
    b = _cylinder_patch(10.0, (np.pi / 4, np.pi / 2), (0.0, 5.0))
    # a's last row in s is b's first: the common side
    assert np.abs(contact.points(a)[-1] - contact.points(b)[0]).max() < 1e-12
    assert contact.side_contact_proven(a[None], b[None], np.array([1e-6]))[0]
    # sampled: points of a and b away from the cut are apart, by more as they are farther from it
    s = np.linspace(0.0, 1.0, 41)
    ss, tt = np.meshgrid(s, s, indexing="ij")
    pa = _evaluate(a, ss.ravel(), tt.ravel())
    pb = _evaluate(b, ss.ravel(), tt.ravel())
    far = (ss.ravel() <= 0.9)[:, None] | (ss.ravel() >= 0.1)[None, :]
    distance = np.linalg.norm(pa[:, None] - pb[None, :], axis=2)
    assert distance[far].min() > 0.2
    # b turned back over a (the same arc the other way): the surfaces overlap, no proof
    back = a[::-1]
    assert not contact.side_contact_proven(a[None], back[None], np.array([1e-6]))[0]
    # a half turn round the cylinder is too much for one pair of patches (the proof needs them
    # near a common plane), but each quarter is proven: the filter refines cells until it is
    wide_a = _cylinder_patch(10.0, (-np.pi / 2, np.pi / 4), (0.0, 5.0))
    wide_b = _cylinder_patch(10.0, (np.pi / 4, np.pi), (0.0, 5.0))
    assert not contact.side_contact_proven(wide_a[None], wide_b[None], np.array([1e-6]))[0]


def test_the_side_proof_holds_under_a_transposed_and_reversed_grid():
    a = _cylinder_patch(10.0, (0.0, np.pi / 4), (0.0, 5.0))
    b = _cylinder_patch(10.0, (0.0, np.pi / 4), (5.0, 9.0))  # above a: the common side is t = 1 of a, t = 0 of b
    first, second = contact.oriented(a, 3, last=True), contact.oriented(b, 2, last=False)
    assert np.abs(contact.points(first)[-1] - contact.points(second)[0]).max() < 1e-12
    assert contact.side_contact_proven(first[None], second[None], np.array([1e-6]))[0]
    # the same patches with b's side order reversed do not fit together (a different map): refused
    assert not contact.side_contact_proven(first[None], second[None, :, ::-1], np.array([1e-6]))[0]


def test_diagonal_patches_meet_only_at_their_corner_and_a_patch_over_another_is_refused():
    a = _cylinder_patch(10.0, (0.0, np.pi / 4), (0.0, 5.0))
    b = _cylinder_patch(10.0, (np.pi / 4, np.pi / 2), (5.0, 10.0))
    assert np.abs(contact.points(a)[-1, -1] - contact.points(b)[0, 0]).max() < 1e-12
    proven = contact.corner_contact_proven(a[None], np.array([[-1, -1]]), b[None], np.array([[0, 0]]), np.array([1e-6]))
    assert proven[0]
    # the same corner, b folded over a (a itself, turned round): refused
    over = a[::-1, ::-1]
    refused = contact.corner_contact_proven(
        a[None], np.array([[-1, -1]]), over[None], np.array([[0, 0]]), np.array([1e-6])
    )
    assert not refused[0]
