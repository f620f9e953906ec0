"""Two Bezier patches in contact only along a common side or at a common corner: the proofs the
pre-boolean check's filter uses for faces that touch (issue 24; tubecad.brep.analyzer).

A patch is its homogeneous control grid G (m+1, n+1, 4): poles w_ij P_ij and weights w_ij > 0,
S(s, t) = sum_ij B_i(s) B_j(t) w_ij P_ij / sum_ij B_i(s) B_j(t) w_ij on [0, 1]^2 (Bernstein B).

**Side contact** (patches a and b share a whole side, a on one side of it, b on the other). Put a on
[0, 1] x [0, 1] and b on [1, 2] x [0, 1], the common side at s = 1: F, a on the left and b on the
right, is continuous and piecewise smooth on the rectangle R = [0, 2] x [0, 1]. For any 2 x 3
matrix M and points x, y of R (the segment between them stays in R, which is convex),

    M (F(x) - F(y)) . (x - y) = integral_0^1 (x - y)^T M DF(y + r (x - y)) (x - y) dr
                              >= mu |x - y|^2,

mu the least eigenvalue of sym(M DF) over R. If mu > 0, F is one-to-one on R and
|F(x) - F(y)| >= mu |x - y| / |M|: two points of a and b closer than d in space are closer than
d |M| / mu in (s, t), so near the common side. (A map whose Jacobian keeps a positive definite
symmetric part is injective on a convex set: Gale & Nikaido, Math. Ann. 159, 1965.)

The bound of mu comes from sets holding the derivatives. Along a direction in which the weights
do not vary (a tube's axis direction), every iso-curve is polynomial and S_t lies in the hull of
n (P_i,j+1 - P_ij). Along a rational direction, the iso-curve at t is C = sum_i W_i B_i Q_i / W with
W_i = sum_j w_ij B_j(t) and Q_i = sum_j gamma_ij P_ij (gamma_ij = w_ij B_j / W_i, convex weights), and

    C'(s) = sum_{i<k} lambda_ik(s) (Q_k - Q_i),  lambda_ik = W_i W_k (B_k' B_i - B_k B_i') / W^2 >= 0

(B_k'/B_k = k/s - (m - k)/(1 - s) grows with k). Q_k - Q_i = sum_j gamma_kj (P_kj - P_ij) +
sum_j (gamma_kj - gamma_ij)(P_ij - c_i), and with r_j = w_kj / w_ij the second sum is at most
(max r / min r - 1) max_j |P_ij - c_i| long (0 when the two rows' weights are in proportion: a
tube's circle; small on a canal surface). So S_s lies in Lambda(s) times the hull of the pole
differences P_kj - P_ij widened by that radius, Lambda = sum lambda_ik bounded for every W_i in
[min_j w_ij, max_j w_ij] (its numerator and W^2 grow with each W_i) by the Bernstein coefficients
of the two on pieces of [0, 1]. With M the pseudo-inverse of the mean chords [L_s, L_t],
sym(M DF) = [[a, c], [c, b]] with a = m1 . S_s, b = m2 . S_t, 2c = m1 . S_t + m2 . S_s; a >= a0 > 0,
b >= b0 > 0 and |c| <= c0 give mu >= (a0 + b0)/2 - sqrt(((a0 - b0)/2)^2 + c0^2).

**Corner contact** (the patches share only a corner V). With n the direction from a's centroid to
b's, S(x) - V = sum beta_ij(x) (P_ij - V), beta >= 0 summing to 1 (positive weights), so if every
pole of a but V has (P - V) . n < -d and every pole of b but V has (P - V) . n > d, the patches are
farther than d apart everywhere except where the weight of V is near 1: around V.
"""

from __future__ import annotations

from functools import lru_cache
from math import comb

import numpy as np

#: contacts within the margin must stay within this share of a patch's width of the common side
CONTACT_ZONE = 0.01


def points(grid: np.ndarray) -> np.ndarray:
    """The poles in space, P_ij = (w P)_ij / w_ij (of one grid or a stack)."""
    return grid[..., :3] / grid[..., 3:]


def _varying(grids: np.ndarray) -> np.ndarray:
    """For each grid (k, m+1, n+1, 4), whether its weights vary along index 0 and along index 1
    (k, 2): the directions in which its iso-curves are rational."""
    w = grids[..., 3]
    scale = np.abs(w).max(axis=(1, 2))
    along_0 = np.abs(w - w[:, :1, :]).max(axis=(1, 2)) > 1e-13 * scale
    along_1 = np.abs(w - w[:, :, :1]).max(axis=(1, 2)) > 1e-13 * scale
    return np.stack([along_0, along_1], axis=1)


def _bernstein(coefficients: np.ndarray, degree: int) -> np.ndarray:
    """The Bernstein coefficients of degree ``degree`` of a polynomial given by its power-basis
    coefficients a_j: b_k = sum_{j<=k} C(k, j) / C(degree, j) a_j."""
    a = np.zeros(degree + 1)
    a[: len(coefficients)] = coefficients[: degree + 1]
    return np.array([sum(comb(k, j) / comb(degree, j) * a[j] for j in range(k + 1)) for k in range(degree + 1)])


#: the pieces [0, 1] is cut into to bound Lambda (each piece's Bernstein bounds are tight)
LAMBDA_PIECES = 16


@lru_cache(maxsize=16)
def _lambda_tables(m: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For degree m, on each of LAMBDA_PIECES pieces of [0, 1]: the Bernstein coefficients (degree
    2m) of D_ik = B_k' B_i - B_k B_i' for i < k and of B_i B_k, with the pairs' indices. Lambda's
    numerator and W^2 are sums of these times w_i w_k: their coefficients are those sums."""
    from numpy.polynomial import Polynomial

    s = Polynomial([0.0, 1.0])
    basis = [comb(m, i) * s**i * (1 - s) ** (m - i) for i in range(m + 1)]
    i, k = np.triu_indices(m + 1, 1)
    starts = np.arange(LAMBDA_PIECES) / LAMBDA_PIECES
    pieces = [Polynomial([start, 1.0 / LAMBDA_PIECES]) for start in starts]  # s on a piece, r in [0, 1]
    slopes = np.array(
        [
            [
                _bernstein((basis[b].deriv() * basis[a] - basis[b] * basis[a].deriv())(piece).coef, 2 * m)
                for a, b in zip(i, k)
            ]
            for piece in pieces
        ]
    )  # (pieces, pairs, 2m + 1)
    products = np.array(
        [
            [[_bernstein((basis[a] * basis[b])(piece).coef, 2 * m) for b in range(m + 1)] for a in range(m + 1)]
            for piece in pieces
        ]
    )  # (pieces, m + 1, m + 1, 2m + 1)
    return slopes, products, i, k


def lambda_bounds(low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Bounds on [0, 1] of Lambda(s) = sum_{i<k} W_i W_k (B_k' B_i - B_k B_i')(s) / W(s)^2, the
    factor of the pole differences in a rational Bezier curve's derivative (module text), for
    weights W_i anywhere in [low_i, high_i]: (rows, 2) for rows of weight boxes (rows, m + 1).
    The numerator's terms and W's are nonnegative, so they grow with every W_i; on each of
    LAMBDA_PIECES pieces of [0, 1] the Bernstein coefficients of the numerator at ``low`` and W^2
    at ``high`` bound Lambda from below, those of the numerator at ``high`` and W^2 at ``low`` from
    above."""
    slopes, products, i, k = _lambda_tables(low.shape[1] - 1)

    def numerator(w: np.ndarray) -> np.ndarray:
        return np.einsum("rq,xqc->rxc", w[:, i] * w[:, k], slopes)  # (rows, pieces, 2m + 1)

    def squared(w: np.ndarray) -> np.ndarray:
        return np.einsum("ra,rb,xabc->rxc", w, w, products)

    least = (np.maximum(numerator(low).min(axis=2), 0.0) / squared(high).max(axis=2)).min(axis=1)
    most = (numerator(high).max(axis=2) / squared(low).min(axis=2)).max(axis=1)
    return np.stack([least, most], axis=1)


def derivative_sets(grids: np.ndarray, axis: int, rational: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The derivatives along ``axis`` (0: s, 1: t) of a stack of patches whose weights vary along
    that axis (``rational``) or not: (Lambda's bounds (k, 2), vectors (k, N, 3), radius (k,)), the
    derivative in [Lambda] x (hull(vectors) + a ball of the radius) everywhere on each patch
    (module text)."""
    along = np.moveaxis(points(grids), axis + 1, 1)  # (k, degree + 1, other, 3)
    k, count = along.shape[:2]
    if not rational:
        return np.ones((k, 2)), ((count - 1) * np.diff(along, axis=1)).reshape(k, -1, 3), np.zeros(k)
    i, j = np.triu_indices(count, 1)
    w = np.moveaxis(grids[..., 3], axis + 1, 1)  # (k, degree + 1, other)
    w = w / w.max(axis=(1, 2), keepdims=True)
    bounds = lambda_bounds(w.min(axis=2), w.max(axis=2))  # each iso-curve's weights lie in these boxes
    # Q_k - Q_i leaves the hull of P_kj - P_ij by at most (max r / min r - 1) max_j |P_ij - c_i|,
    # r_j = w_kj / w_ij (0 when the weights of the two rows are in proportion)
    ratio = w[:, j] / w[:, i]
    spread = ratio.max(axis=2) / ratio.min(axis=2) - 1.0  # (k, pairs)
    centre = 0.5 * (along.max(axis=2) + along.min(axis=2))
    reach = np.linalg.norm(along - centre[:, :, None], axis=3).max(axis=2)  # (k, degree + 1)
    radius = (spread * reach[:, i]).max(axis=1)
    return bounds, (along[:, j] - along[:, i]).reshape(k, -1, 3), radius


def _times(lam: np.ndarray, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The intervals [lam] x [low, high] for lam >= 0 (arrays of intervals)."""
    return (
        low * np.where(low >= 0, lam[:, 0], lam[:, 1]),
        high * np.where(high >= 0, lam[:, 1], lam[:, 0]),
    )


def side_contact_proven(a: np.ndarray, b: np.ndarray, margin: np.ndarray) -> np.ndarray:
    """For stacks of patch pairs, ``a`` (its last row in s the common side) and ``b`` (its first
    row in s the same side, in the same order): whether they meet only near that side, F one-to-one
    on [0, 2] x [0, 1] (module text) and two points closer than ``margin`` within CONTACT_ZONE of
    the side in (s, t)."""
    proven = np.zeros(len(a), dtype=bool)
    kinds = np.concatenate([_varying(a), _varying(b)], axis=1)  # (k, 4)
    for pattern in {tuple(row) for row in kinds.tolist()}:
        at = np.nonzero((kinds == pattern).all(axis=1))[0]
        proven[at] = _side_proof(a[at], b[at], margin[at], pattern)
    return proven


def _side_proof(a: np.ndarray, b: np.ndarray, margin: np.ndarray, pattern: tuple[bool, ...]) -> np.ndarray:
    pa, pb = points(a), points(b)
    chord_s = 0.5 * ((pa[:, -1] - pa[:, 0]).mean(axis=1) + (pb[:, -1] - pb[:, 0]).mean(axis=1))
    chord_t = 0.5 * ((pa[:, :, -1] - pa[:, :, 0]).mean(axis=1) + (pb[:, :, -1] - pb[:, :, 0]).mean(axis=1))
    m = np.linalg.pinv(np.stack([chord_s, chord_t], axis=2))  # (k, 2, 3): M L = I
    a0 = np.full(len(a), np.inf)
    b0 = np.full(len(a), np.inf)
    c0 = np.zeros(len(a))
    size = np.linalg.norm(m, axis=2)  # (k, 2): |m1|, |m2|
    for grids, (rational_s, rational_t) in ((a, pattern[:2]), (b, pattern[2:])):
        lam_s, along_s, radius_s = derivative_sets(grids, 0, rational_s)
        lam_t, along_t, radius_t = derivative_sets(grids, 1, rational_t)
        on_s = np.einsum("knx,kyx->kny", along_s, m)  # (k, vectors, 2): m1 . S_s, m2 . S_s
        on_t = np.einsum("knx,kyx->kny", along_t, m)
        out_s, out_t = radius_s[:, None] * size, radius_t[:, None] * size  # (k, 2): the balls' reach
        low_s, high_s = on_s.min(axis=1) - out_s, on_s.max(axis=1) + out_s
        low_t, high_t = on_t.min(axis=1) - out_t, on_t.max(axis=1) + out_t
        a_low = _times(lam_s, low_s[:, 0], high_s[:, 0])[0]
        b_low = _times(lam_t, low_t[:, 1], high_t[:, 1])[0]
        c_1 = np.abs(np.stack(_times(lam_t, low_t[:, 0], high_t[:, 0]))).max(axis=0)
        c_2 = np.abs(np.stack(_times(lam_s, low_s[:, 1], high_s[:, 1]))).max(axis=0)
        a0, b0, c0 = np.minimum(a0, a_low), np.minimum(b0, b_low), np.maximum(c0, 0.5 * (c_1 + c_2))
    mu = 0.5 * (a0 + b0) - np.hypot(0.5 * (a0 - b0), c0)
    return (a0 > 0) & (b0 > 0) & (mu > 0) & (margin * np.linalg.norm(m, 2, axis=(1, 2)) <= CONTACT_ZONE * mu)


def corner_contact_proven(
    a: np.ndarray, corner_a: np.ndarray, b: np.ndarray, corner_b: np.ndarray, margin: np.ndarray
) -> np.ndarray:
    """For stacks of patch pairs whose poles at ``corner_a`` and ``corner_b`` ((k, 2) indices,
    0 or -1) are one point V: whether they are farther than ``margin`` apart except around V
    (module text)."""
    pa, pb = points(a), points(b)
    k = np.arange(len(a))
    vertex = 0.5 * (pa[k, corner_a[:, 0], corner_a[:, 1]] + pb[k, corner_b[:, 0], corner_b[:, 1]])
    direction = pb.mean(axis=(1, 2)) - pa.mean(axis=(1, 2))
    length = np.linalg.norm(direction, axis=1, keepdims=True)
    direction = np.divide(direction, length, out=np.zeros_like(direction), where=length > 0)
    on_a = np.einsum("kijx,kx->kij", pa - vertex[:, None, None], direction)
    on_b = np.einsum("kijx,kx->kij", pb - vertex[:, None, None], direction)
    on_a[k, corner_a[:, 0], corner_a[:, 1]] = -np.inf
    on_b[k, corner_b[:, 0], corner_b[:, 1]] = np.inf
    return (length[:, 0] > 0) & (on_a.max(axis=(1, 2)) < -margin) & (on_b.min(axis=(1, 2)) > margin)


def oriented(grid: np.ndarray, side: int, last: bool) -> np.ndarray:
    """The grid turned so that its ``side`` (0: s = 0, 1: s = 1, 2: t = 0, 3: t = 1) is its last
    row in s (``last``) or its first."""
    if side >= 2:
        grid = grid.transpose(1, 0, 2)
    at_end = side in (1, 3)
    return grid if at_end == last else grid[::-1]
