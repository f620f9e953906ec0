"""Axes through points: a C2 cubic spline interpolating them (docs/MATH.md section 7).

The points P_0..P_n are given parameters by chord length (t_{i+1} - t_i = |P_{i+1} - P_i|)
or centripetally (|P_{i+1} - P_i|^(1/2), Lee 1989: no cusps or loops on uneven spacing),
and interpolated by the cubic spline with not-a-knot ends (scipy CubicSpline). The spline is C2, so its
rotation-minimising frame is C1 and the tube is G1 with continuous curvature lines; the
panels of the axis start at the spline's knots, where x''' jumps. A closed loop (the last
point repeats the first, or ``closed=True``) is interpolated by the periodic cubic spline
instead: C2 all round, the closing point included.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.interpolate import CubicSpline

from tubecad.core.errors import ParameterError
from tubecad.core.validation import MAX_LENGTH
from tubecad.curves.parametric import ParametricAxis

PARAMETERISATIONS = {"centripetal": 0.5, "chord": 1.0}
MAX_POINTS = 100_000


def checked_points(points: object, least: int) -> np.ndarray:
    """``points`` as an (n, 3) array of finite coordinates, ``least`` <= n <= MAX_POINTS, each
    point differing from the next; a ParameterError naming the point otherwise."""
    try:
        p = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("points must be a list of [x, y, z] coordinates") from None
    if p.ndim != 2 or p.shape[1] != 3:
        raise ParameterError(f"points must be a list of [x, y, z] coordinates, got an array of shape {p.shape}")
    if not least <= len(p) <= MAX_POINTS:
        raise ParameterError(f"points must hold {least} to {MAX_POINTS} points, got {len(p)}")
    if not np.isfinite(p).all() or np.abs(p).max() > MAX_LENGTH:
        raise ParameterError(f"points must be finite coordinates within +-{MAX_LENGTH:g}")
    steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
    repeated = np.flatnonzero(steps <= 1e-12 * (float(np.abs(p).max()) or 1.0))
    if repeated.size:
        i = int(repeated[0])
        raise ParameterError(
            f"points[{i + 1}] {shown(p[i + 1])} repeats points[{i}]; every point must differ from the next"
        )
    return p


def same_point(a: np.ndarray, b: np.ndarray, points: np.ndarray) -> bool:
    """Whether points a and b coincide, to 1e-12 of the largest coordinate of ``points``
    (the test by which :func:`checked_points` refuses a repeated point)."""
    return float(np.linalg.norm(a - b)) <= 1e-12 * (float(np.abs(points).max()) or 1.0)


def closed_loop(points: np.ndarray, closed: object) -> bool:
    """Whether ``points`` make a closed loop: ``closed`` None when the last point repeats
    the first, True always, False never."""
    if closed is not None and not isinstance(closed, (bool, np.bool_)):
        raise ParameterError(f"closed must be true or false, got {closed!r:.80}")
    return bool(closed) if closed is not None else same_point(points[0], points[-1], points)


def shown(point: np.ndarray) -> str:
    """A point as [x, y, z] for a message."""
    return "[" + ", ".join(f"{v:g}" for v in point) + "]"


def points_axis(
    points: Sequence[Sequence[float]] | np.ndarray,
    *,
    parameterisation: str = "centripetal",
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
) -> ParametricAxis:
    """The axis through ``points`` (n x 3), interpolated by a C2 cubic spline. ``closed``: a
    closed loop (None: when the last point repeats the first; True: the first point is
    appended if the last differs; False: an open spline even so), interpolated by the
    periodic cubic spline through 3 or more distinct points.

    Args:
        points: the points [[x, y, z], ...], model units: 3 to 100,000, finite, each
            differing from the next.
        parameterisation: how the spline's parameter steps between points: ``"centripetal"``
            (default, |P_{i+1} - P_i|^(1/2): no cusps or loops on uneven spacing) or
            ``"chord"`` (|P_{i+1} - P_i|).
        normal: the initial r1 at the first point, made orthogonal to the tangent; None
            (default): the principal normal (see :class:`~.parametric.ParametricAxis`).
        closed: None (default): a closed loop when the last point repeats the first; True:
            always a loop; False: an open spline.

    Returns:
        The :class:`~.parametric.ParametricAxis` along the spline, in arc length from 0 at
        the first point, with C1 joints at the inner points.

    Raises:
        ParameterError: bad or repeated points, an unknown ``parameterisation``, or a
            closed loop of fewer than 3 distinct points.
    """
    if parameterisation not in PARAMETERISATIONS:
        raise ParameterError(
            f"parameterisation must be one of {', '.join(PARAMETERISATIONS)}, got {parameterisation!r:.80}"
        )
    p = checked_points(points, 3)
    given = len(p)
    loop = closed_loop(p, closed)
    if loop:
        distinct = p[:-1] if same_point(p[0], p[-1], p) else p
        if len(distinct) < 3:
            raise ParameterError(f"a closed loop of points needs 3 or more distinct points, got {len(distinct)}")
        p = np.vstack([distinct, distinct[:1]])  # the last point exactly the first: the periodic spline's condition
    steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
    t = np.concatenate([[0.0], np.cumsum(steps ** PARAMETERISATIONS[parameterisation])])
    spline = CubicSpline(t, p, bc_type="periodic" if loop else "not-a-knot", axis=0)
    interpolation = (
        f"periodic cubic spline (C2, closed), {parameterisation} parameterisation"
        if loop
        else f"cubic spline (C2), {parameterisation} parameterisation, not-a-knot ends"
    )
    description = {"curve": "points", "points": given, "interpolation": interpolation}
    # the third derivative jumps at the knots: c is C2 there, k only C0, so the frame (c, r1, r2) is C1
    joints = [(float(x), 1) for x in t[1:-1]]
    return ParametricAxis(
        spline,
        (float(t[0]), float(t[-1])),
        breaks=t,
        joints=joints,
        normal=normal,
        description=description,
        name="the spline through the points",
        closed=loop,
    )
