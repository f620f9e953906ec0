"""Integrating the rotation-minimising frame: linear ODEs y' = A(x) y solved by Chebyshev
spectral collocation, panel by panel (docs/MATH.md section 7).

On a panel [a, b] the solution is sought as a Chebyshev series of degree N through the
N + 1 Lobatto points x_i; with D the spectral differentiation matrix (Trefethen, *Spectral
Methods in MATLAB*, 2000, ch. 6, ``cheb``) the equations

    sum_j D_ij y_j - A(x_i) y_i = 0   (i = 1..N),   y_0 = the value carried from the left

form one dense linear system of size m (N + 1). For smooth A the error falls
geometrically with N, so a panel is accepted when the solution's last Chebyshev
coefficients are below ``tol`` times its scale and halved otherwise. The frame is then
known to ~1e-14: unlike a fixed-step Runge-Kutta scheme, no step size limits the accuracy.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.polynomial import chebyshev as C

from tubecad.core.errors import ParameterError
from tubecad.curves.chebyshev import PiecewiseChebyshev

#: the series degree per panel
DEGREE = 24
MAX_PANELS = 4096


def lobatto_differentiation(n: int) -> tuple[np.ndarray, np.ndarray]:
    """(x, D): the n + 1 Chebyshev-Lobatto points on [-1, 1], ascending, and the matrix
    with (D f)(x_i) = f'(x_i) for every polynomial f of degree <= n (Trefethen's cheb)."""
    x = np.cos(np.pi * np.arange(n + 1) / n)
    c = np.where((np.arange(n + 1) == 0) | (np.arange(n + 1) == n), 2.0, 1.0) * (-1.0) ** np.arange(n + 1)
    dx = x[:, None] - x[None, :]
    D = np.outer(c, 1.0 / c) / (dx + np.eye(n + 1))
    D -= np.diag(D.sum(axis=1))
    return x[::-1].copy(), D[::-1, ::-1].copy()


def solve_linear_ode(
    matrix: Callable[[np.ndarray], np.ndarray],
    breaks: np.ndarray,
    y0: np.ndarray,
    *,
    name: str = "the frame",
    tol: float = 1e-14,
    degree: int = DEGREE,
) -> PiecewiseChebyshev:
    """y' = A(x) y from y(breaks[0]) = y0 (shape (m,) or (m, q): q solutions at once) over
    [breaks[0], breaks[-1]], starting from the panels between ``breaks`` and halving any
    panel whose solution is not resolved. ``matrix`` maps an array of x (panels, nodes), each
    row one panel's nodes, to A (panels, nodes, m, m). Returns the solution as a piecewise
    Chebyshev series with values of y0's shape.

    The equations are linear, so each panel's solutions are Y(x) y(a) with Y the panel's
    fundamental matrix (Y(a) = I): every panel of a round is collocated at once for its Y
    (one batched solve), a panel is resolved when Y's last coefficients are below ``tol``
    times its scale, and the resolved panels are chained from y0, y(b) = Y(b) y(a)."""
    y0 = np.asarray(y0, dtype=float)
    value_shape = y0.shape
    y = y0.reshape(y0.shape[0], -1)
    m = y.shape[0]
    z, D = lobatto_differentiation(degree)
    nodes = degree + 1
    base = np.kron(D, np.eye(m))
    first_block = np.zeros((nodes * m, m))
    first_block[:m] = np.eye(m)
    todo = list(zip(breaks[:-1].tolist(), breaks[1:].tolist()))
    done: list[tuple[float, float, np.ndarray, np.ndarray]] = []  # (lo, hi, Y(hi), Y's coefficients)
    span = float(breaks[-1] - breaks[0])
    while todo:
        lo, hi = np.array(todo).T
        x = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * z
        A = np.asarray(matrix(x), dtype=float)
        if not np.isfinite(A).all():
            where = np.argwhere(~np.isfinite(A))[0]
            raise ParameterError(f"{name}: the equations are not finite at {x[where[0], where[1]]:.6g}")
        system = (2.0 / (hi - lo))[:, None, None] * base
        for i in range(nodes):  # sum_j D_ij Y_j - A(x_i) Y_i = 0 at the nodes after the first
            system[:, i * m : (i + 1) * m, i * m : (i + 1) * m] -= A[:, i]
        system[:, :m] = first_block.T  # Y_0 = I
        Y = np.linalg.solve(system, np.broadcast_to(first_block, (len(todo), nodes * m, m))).reshape(-1, nodes, m, m)
        coeffs = C.chebfit(z, np.moveaxis(Y, 1, 0).reshape(nodes, -1), degree).reshape(nodes, len(todo), m, m)
        coeffs = np.moveaxis(coeffs, 0, 1)  # (panels, nodes, m, m)
        tails = np.abs(coeffs[:, -4:]).max(axis=(1, 2, 3))
        scales = np.maximum(np.abs(Y).max(axis=(1, 2, 3)), 1e-300)
        resolved = (tails <= tol * scales) | ((hi - lo) <= 1e-12 * span)
        next_todo = []
        for k, (a, b) in enumerate(todo):
            if resolved[k]:
                done.append((a, b, Y[k, -1], coeffs[k]))
            else:
                next_todo += [(a, 0.5 * (a + b)), (0.5 * (a + b), b)]
        if len(done) + len(next_todo) > MAX_PANELS:
            lo_w = min(next_todo, key=lambda p: p[1] - p[0])[0]
            raise ParameterError(
                f"{name} could not be resolved with {MAX_PANELS} panels near {lo_w:.6g}: the "
                "curve must be smooth there (a kink, a cusp or a curvature that blows up?)"
            )
        todo = next_todo
    done.sort(key=lambda panel: panel[0])
    out = []
    for _, _, Y_end, coeffs_k in done:  # y(x) = Y(x) y(a), panel after panel
        out.append(coeffs_k @ y)
        y = Y_end @ y
    coeffs_all = np.array(out).reshape(len(done), nodes, *value_shape)
    return PiecewiseChebyshev(np.array([done[0][0]] + [panel[1] for panel in done]), coeffs_all)
