"""The unit circle as a periodic rational quadratic B-spline (8 poles, 4 arcs of 90 deg).

Its parameter u runs over [0, 2 pi) but is not the angle: on each quarter q,
theta(u) = q pi/2 + pi/4 + 2 atan(tan(pi/8) (2 t - 1)), t the fraction of the quarter.
theta = u exactly at u = k pi/4. A u-isoline of the tube surface is a curve of constant
theta, so it is still a line of curvature; stringers at angle theta sit at u_of_theta.
"""

from __future__ import annotations

import math

import numpy as np

_H = math.sqrt(0.5)
POLES_X = np.array([1, 1, 0, -1, -1, -1, 0, 1], dtype=float)
POLES_Y = np.array([0, 1, 1, 1, 0, -1, -1, -1], dtype=float)
WEIGHTS = np.array([1, _H, 1, _H, 1, _H, 1, _H])
KNOTS = np.arange(5) * math.pi / 2
MULTIPLICITIES = [2] * 5
QUARTER = math.pi / 2
_T8 = math.tan(math.pi / 8)


def theta_of_u(u: np.ndarray | float) -> np.ndarray:
    """Angle on the circle at NURBS parameter u."""
    u = np.asarray(u, dtype=float)
    q = np.floor(u / QUARTER)
    t = u / QUARTER - q
    return q * QUARTER + math.pi / 4 + 2 * np.arctan(_T8 * (2 * t - 1))


def u_of_theta(theta: np.ndarray | float) -> np.ndarray:
    """NURBS parameter u at angle theta (the inverse of :func:`theta_of_u`)."""
    theta = np.asarray(theta, dtype=float)
    q = np.floor(theta / QUARTER)
    d = theta - q * QUARTER - math.pi / 4
    return q * QUARTER + math.pi / 4 * (1 + np.tan(d / 2) / _T8)
