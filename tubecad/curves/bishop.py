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
    panel whose solution is not resolved. ``matrix`` maps an array of x (n,) to A (n, m, m).
    Returns the solution as a piecewise Chebyshev series with values of y0's shape."""
    y0 = np.asarray(y0, dtype=float)
    value_shape = y0.shape
    y = y0.reshape(y0.shape[0], -1)
    m, q = y.shape
    z, D = lobatto_differentiation(degree)
    todo = list(zip(breaks[:-1], breaks[1:]))[::-1]  # a stack: the leftmost panel on top
    done_breaks, done_coeffs = [float(breaks[0])], []
    span = float(breaks[-1] - breaks[0])
    while todo:
        lo, hi = todo.pop()
        x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * z
        A = np.asarray(matrix(x), dtype=float)
        if not np.isfinite(A).all():
            i = int(np.argwhere(~np.isfinite(A))[0][0])
            raise ParameterError(f"{name}: the equations are not finite at {x[i]:.6g}")
        system = np.kron(2.0 / (hi - lo) * D, np.eye(m))
        for i in range(degree + 1):
            system[i * m : (i + 1) * m, i * m : (i + 1) * m] -= A[i]
        system[:m] = 0.0
        system[:m, :m] = np.eye(m)
        rhs = np.zeros(((degree + 1) * m, q))
        rhs[:m] = y
        values = np.linalg.solve(system, rhs).reshape(degree + 1, m, q)
        coeffs = C.chebfit(z, values.reshape(degree + 1, -1), degree).reshape(degree + 1, m, q)
        scale = max(float(np.abs(values).max()), 1e-300)
        if np.abs(coeffs[-4:]).max() <= tol * scale or (hi - lo) <= 1e-12 * span:
            done_breaks.append(float(hi))
            done_coeffs.append(coeffs)
            y = values[-1]
        else:
            mid = 0.5 * (lo + hi)
            todo += [(mid, hi), (lo, mid)]
        if len(done_coeffs) + len(todo) > MAX_PANELS:
            raise ParameterError(
                f"{name} could not be resolved with {MAX_PANELS} panels near {lo:.6g}: the "
                "curve must be smooth there (a kink, a cusp or a curvature that blows up?)"
            )
    coeffs = np.array(done_coeffs).reshape(len(done_coeffs), degree + 1, *value_shape)
    return PiecewiseChebyshev(np.array(done_breaks), coeffs)
