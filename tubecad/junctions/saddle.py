"""The saddle curve: where a branch surface meets a main surface, in the curvature-line
parameters of both (docs/MATH.md section 13).

Both surfaces are curvature-line surfaces X_A(u_A, s_A) (the main tube or wall) and
X_B(u_B, s_B) (the branch). The saddle is the closed curve of points with

    F(u_A, s_A, s_B; u_B) = X_A(u_A, s_A) - X_B(u_B, s_B) = 0,

three equations in four unknowns: one curve, parameterised by the branch's stringer angle
u_B, which runs once round the branch. For each u_B Newton's method solves F = 0 for
(u_A, s_A, s_B) with the Jacobian J = [dX_A/du_A, dX_A/ds_A, -dX_B/ds_B], to round-off.
The curve is marched in u_B with the tangent as predictor,

    d(u_A, s_A, s_B)/du_B = J^-1 dX_B/du_B,

and corrected by Newton at every sample (Allgower & Georg, *Introduction to Numerical
Continuation Methods*, 2003, ch. 2: predictor-corrector continuation). J is singular where the
surfaces are tangent (an equal-radius tee's two crossing points, a branch grazing the main
tube): there the saddle is no longer one smooth closed curve round the branch, and it is
refused naming the branch's radius.

The start: along the branch's stringer u_B from the branch's first ring, the first point
outside the main surface, found from the main surface's rings (the ring through a point P
is the one whose plane holds P; P is outside when farther from that ring's centre than its
radius), then Newton.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from tubecad.core.errors import ParameterError
from tubecad.junctions.crotch import Crotch, crotch
from tubecad.surface.protocol import CurvatureLineSurface

FloatArray = np.ndarray

#: Newton stops when |F| is below this times the surfaces' size (round-off of the coordinates)
RESIDUAL = 1e-13
#: at most this many Newton steps per sample
NEWTON_STEPS = 40
#: samples of the first, sequential march round the branch
COARSE = 12
#: the shortest step (rad of the branch's turn) the march halves down to before it gives up
MIN_STEP = 1e-6
#: |J|'s reciprocal condition number below which the surfaces are taken as tangent
TANGENCY = 1e-6


#: Newton steps for an extreme of a sampled saddle (:meth:`SaddleCurve.extent`)
EXTENT_STEPS = 8
#: at most this many Gauss-Newton steps for a point's foot on the saddle (:func:`saddle_distance`),
#: which stop where they are below FOOT_CONVERGED radians of u_B
FOOT_STEPS, FOOT_CONVERGED = 12, 1e-14
#: how near (rad of u_B) an equal tee's crotch points a point's distance from the saddle is taken
#: as its distance from the two surfaces (:func:`_crotched_distance`)
CROTCH_BAND = 0.05


@dataclass(frozen=True)
class SaddleCurve:
    """The saddle sampled at ``branch_u`` (u_B, increasing over one turn, the last sample
    the first plus 2 pi): the branch's (u_B, s_B), the main surface's (u_A, s_A) of the same
    points (u_A unwrapped along the curve), the points and the largest |X_A - X_B| left."""

    branch_u: FloatArray
    branch_s: FloatArray
    main_u: FloatArray
    main_s: FloatArray
    points: FloatArray
    residual: float
    #: the samples at the crotch points of an equal tee (their first, the other, the first
    #: again at the end), where the saddle's two curves cross: () for a smooth closed saddle
    corners: tuple[int, ...] = ()

    def __len__(self) -> int:
        return len(self.branch_u)

    def extent(self, values: FloatArray) -> tuple[float, float]:
        """The least and the greatest of ``values`` (one of this curve's arrays: a smooth
        periodic function of u_B, sampled evenly with it) along the saddle, between the
        samples too: the trigonometric interpolant of the samples (numpy's FFT: spectrally
        accurate for a smooth periodic function) has its extremes found by Newton's method
        on its derivative from the extreme samples. The samples alone miss an extreme
        between them by O(h^2): 2.3e-4 rad of a tee's opening at 128 samples."""
        f = np.asarray(values, dtype=float)[:-1]  # the last sample is the first again
        n = len(f)
        k = np.arange(n // 2 + 1)
        c = np.fft.rfft(f) / n * np.where((k == 0) | (2 * k == n), 1.0, 2.0)  # f = Re sum c_k e^(2 pi i k x / n)
        w = 2j * np.pi * k / n

        def derivatives(x: float) -> tuple[float, float, float]:
            e = c * np.exp(w * x)
            return float(e.sum().real), float((w * e).sum().real), float((w * w * e).sum().real)

        def extreme(start: int, sign: float) -> float:  # sign -1: the least, +1: the greatest
            x = float(start)
            for _ in range(EXTENT_STEPS):
                _, slope, bend = derivatives(x)
                if bend == 0.0:
                    break
                step = max(-1.0, min(1.0, -slope / bend))  # within a sample of where it started
                x += step
                if abs(step) < 1e-13:
                    break
            return float(sign * max(sign * f[start], sign * derivatives(x)[0]))  # never short of the sample

        if self.corners:
            return self._piecewise_extent(np.asarray(values, dtype=float))
        return extreme(int(np.argmin(f)), -1.0), extreme(int(np.argmax(f)), 1.0)

    def _piecewise_extent(self, values: FloatArray) -> tuple[float, float]:
        """:meth:`extent` of a saddle with corners: each smooth curve between two crotch points
        interpolated by a cubic spline (not-a-knot), evaluated 32 times per sample interval."""
        low, high = float(values.min()), float(values.max())
        for a, b in zip(self.corners[:-1], self.corners[1:]):
            u = self.branch_u[a : b + 1]
            fine = np.linspace(u[0], u[-1], 32 * (b - a) + 1)
            between = CubicSpline(u, values[a : b + 1])(fine)
            low, high = min(low, float(between.min())), max(high, float(between.max()))
        return low, high


def _ring_coordinates(main: CurvatureLineSurface, points: FloatArray, samples: int = 2001):
    """For each point P: the main ring whose plane holds P (s_A), the angle chi of P round
    it from r1, and P's distance from the ring's centre minus the ring's radius (> 0:
    outside the main surface). Rings whose plane holds P several times: the nearest."""
    s = np.linspace(*main.span, samples)
    centre, radius, normal = main.circle(s)
    d = points[:, None, :] - centre[None, :, :]
    h = np.einsum("psk,sk->ps", d, normal)
    change = np.signbit(h[:, :-1]) != np.signbit(h[:, 1:])
    dist = np.linalg.norm(d, axis=-1)
    score = np.where(change, dist[:, :-1], np.inf)
    j = np.argmin(score, axis=1)
    found = np.isfinite(score[np.arange(len(points)), j])
    h0, h1 = h[np.arange(len(points)), j], h[np.arange(len(points)), j + 1]
    w = np.where(found, h0 / np.where(h0 != h1, h0 - h1, 1.0), 0.0)
    s_a = s[j] + w * (s[j + 1] - s[j])
    c, r, _ = main.circle(s_a)
    _, r1, r2 = main.axis.rotation_minimising_frame(s_a)
    e = points - c
    chi = np.arctan2(np.einsum("pk,pk->p", e, r2), np.einsum("pk,pk->p", e, r1))
    gap = np.where(found, np.linalg.norm(e, axis=-1) - r, -np.inf)
    return s_a, chi, gap


def _u_of_chi(main: CurvatureLineSurface, chi: FloatArray, s: FloatArray) -> FloatArray:
    """The stringer u whose angle at s is chi: (sin u/2, cos u/2) ~ Mb(s)^-1 (sin chi/2, cos chi/2)."""
    half = np.stack([np.sin(chi / 2), np.cos(chi / 2)], axis=-1)
    back = np.linalg.solve(main.moebius_matrix(s), half[..., None])[..., 0]
    return 2.0 * np.arctan2(back[..., 0], back[..., 1])


def _solve(main: CurvatureLineSurface, branch: CurvatureLineSurface, u_b: FloatArray, x: FloatArray, scale: float):
    """Newton on X_A(x[:, 0], x[:, 1]) = X_B(u_b, x[:, 2]) for every sample at once, from x
    (shape (n, 3)); returns (x, |F| per sample, J per sample (n, 3, 3), dX_B/du_B (n, 3))."""
    converged = False
    for _ in range(NEWTON_STEPS):
        a = main.derivatives(x[:, 0], x[:, 1])
        b = branch.derivatives(u_b, x[:, 2])
        f = a.S - b.S
        jac = np.stack([a.S_u, a.S_s, -b.S_s], axis=-1)
        size = np.linalg.norm(f, axis=-1)
        if converged:
            break
        # one step more once within RESIDUAL: quadratic convergence takes it to round-off
        converged = bool(size.max() <= RESIDUAL * scale)
        x = x - np.linalg.solve(jac, f[..., None])[..., 0]
    return x, size, jac, b.S_u


def _tangency(jac: FloatArray) -> FloatArray:
    """1 / cond(J) with the columns scaled to unit length, per sample: 0 where the surfaces are tangent."""
    j = jac / np.linalg.norm(jac, axis=-2, keepdims=True)
    return 1.0 / np.linalg.cond(j)


def _start(main: CurvatureLineSurface, branch: CurvatureLineSurface, u_b: float, key: str) -> FloatArray:
    """(u_A, s_A, s_B) of the first point of the branch's stringer u_b outside the main surface."""
    s = np.linspace(*branch.span, 801)
    points = branch.points(np.full_like(s, u_b), s)
    s_a, chi, gap = _ring_coordinates(main, points)
    outside = gap > 0
    if outside[0] or not outside.any():
        raise ParameterError(
            f"{key}: the branch must start inside the main surface and leave it through its wall "
            f"(its stringer {u_b:.3g} rad {'starts outside' if outside[0] else 'never leaves'})",
            key=key,
        )
    i = int(np.argmax(outside))
    w = -gap[i - 1] / (gap[i] - gap[i - 1])
    s_b = s[i - 1] + w * (s[i] - s[i - 1])
    s_main = s_a[i - 1] + w * (s_a[i] - s_a[i - 1])
    return np.array([float(_u_of_chi(main, chi[i : i + 1], s_a[i : i + 1])[0]), s_main, s_b])


def saddle_curve(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    samples: int = 257,
    *,
    key: str = "branches",
    near: SaddleCurve | None = None,
) -> SaddleCurve:
    """The saddle where ``branch`` leaves ``main``, at ``samples`` stringer angles u_B evenly
    spaced over one turn (the last the first plus 2 pi), each point solved by Newton to
    |X_A - X_B| <= 1e-13 times the surfaces' size.

    ``near``: the same saddle at other samples (a coarser solve), whose interpolation starts
    Newton instead of a new march.

    Refused (a ParameterError naming ``key``) where the branch does not start inside the main
    surface and leave it through its wall, or where the surfaces are tangent on the curve."""
    if samples < 8:
        raise ParameterError(f"samples must be at least 8, got {samples}", key="samples")
    scale = _scale(main, branch)
    touch = crotch(main, branch, scale)
    if touch is not None:
        return _crotched(main, branch, touch, samples, scale, key, near)
    u_b = np.linspace(0.0, 2.0 * np.pi, samples)
    if near is None:
        near = _march(main, branch, scale, key)
    sol = _corrected(main, branch, u_b, _interpolated(near, u_b), scale)  # all samples at once
    if sol is not None:
        x, size, jac, _ = sol
        _check(size, jac, u_b, scale, key)
        return SaddleCurve(u_b, x[:, 2], np.unwrap(x[:, 0]), x[:, 1], main.points(x[:, 0], x[:, 1]), float(size.max()))
    # the interpolated start left a span or Newton did not converge from it (a saddle that turns
    # fast, near tangency): march through the samples one by one instead
    start = _interpolated(near, u_b[:1])[0]
    _, x, residual = _follow(main, branch, u_b, start, scale, key)
    return SaddleCurve(u_b, x[:, 2], np.unwrap(x[:, 0]), x[:, 1], main.points(x[:, 0], x[:, 1]), residual)


def saddle_parameters(
    main: CurvatureLineSurface, branch: CurvatureLineSurface, u_b: FloatArray, near: SaddleCurve
) -> FloatArray | None:
    """(u_A, s_A, s_B) of the saddle at the branch's stringer angles ``u_b``, by Newton from
    ``near``'s interpolation (the same saddle sampled), to round-off; None where Newton does not
    converge or leaves a span.

    Args:
        main: the main surface.
        branch: the branch surface.
        u_b: the branch's stringer angles (any turn: taken modulo 2 pi).
        near: the saddle sampled.

    Returns:
        (n, 3) parameters, or None.
    """
    u = np.mod(np.asarray(u_b, dtype=float).ravel(), 2.0 * np.pi)
    solved = _corrected(main, branch, u, _interpolated(near, u), _scale(main, branch))
    return None if solved is None else solved[0]


def _crotched(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    touch: Crotch,
    samples: int,
    scale: float,
    key: str,
    near: SaddleCurve | None,
) -> SaddleCurve:
    """The saddle of an equal tee (:mod:`~tubecad.junctions.crotch`): its two curves from
    crotch point to crotch point, each sampled at (samples - 1) / 2 even steps of u_B, the
    crotch points themselves exact (their own closed form) and the samples between them by
    Newton, from ``near``'s interpolation (a saddle with the same corners) or marched (each
    curve from its first point after the crotch, :func:`_start`)."""
    m = max(4, (samples - 1) // 2)
    ends = [float(touch.branch_u[0]), float(touch.branch_u[1]), float(touch.branch_u[0]) + 2.0 * np.pi]
    u_b = np.concatenate([np.linspace(ends[k], ends[k + 1], m + 1)[:-1] for k in (0, 1)] + [ends[2:]])
    corners = (0, m, 2 * m)
    interior = np.setdiff1d(np.arange(2 * m + 1), corners)
    x = np.empty((2 * m + 1, 3))
    for i, c in zip(corners, (0, 1, 0)):
        x[i] = (touch.main_u[c], touch.main_s[c], touch.branch_s)
    sol = None
    if near is not None and near.corners:
        sol = _corrected(main, branch, u_b[interior], _interpolated(near, u_b[interior]), scale)
    if sol is not None:
        x[interior], size, jac, _ = sol
        _check(size, jac, u_b[interior], scale, key)
        residual = float(size.max())
    else:
        residual = 0.0
        for k in (0, 1):
            inside = u_b[k * m + 1 : (k + 1) * m]
            _, x[k * m + 1 : (k + 1) * m], piece = _follow(
                main, branch, inside, _start(main, branch, float(inside[0]), key), scale, key
            )
            residual = max(residual, piece)
    points = main.points(x[:, 0], x[:, 1])
    points[list(corners)] = touch.points[[0, 1, 0]]
    return SaddleCurve(u_b, x[:, 2], np.unwrap(x[:, 0]), x[:, 1], points, residual, corners)


def _scale(main: CurvatureLineSurface, branch: CurvatureLineSurface) -> float:
    """The model's size that Newton's residual is measured against: the largest coordinate of
    the surfaces' end points plus the main's largest end radius."""
    corners = np.concatenate(
        [main.points(np.zeros(2), np.array(main.span)), branch.points(np.zeros(2), np.array(branch.span))]
    )
    return float(np.abs(corners).max() + main.radius_law.r(np.array(main.span)).max())


def saddle_distance(
    main: CurvatureLineSurface, branch: CurvatureLineSurface, points: FloatArray, u_b: FloatArray, near: SaddleCurve
) -> FloatArray:
    """How far each of ``points`` lies from the exact saddle of ``main`` and ``branch``: |P - X(u*)|
    at the foot u* of P on it, where g(u) = (X(u) - P) . X'(u) = 0.

    X(u) is the saddle's point at the branch's stringer angle u, solved by Newton as in
    :func:`saddle_curve` (to round-off), and X'(u) = X_A,u du_A/du + X_A,s ds_A/du with
    d(u_A, s_A, s_B)/du = J^-1 X_B,u (the continuation's tangent). u* by Gauss-Newton steps
    du = -g / |X'|^2 (g' = |X'|^2 + (X - P) . X'', the second term as small as P's distance)
    from ``u_b``, each Newton solve started from the step's tangent prediction.

    Args:
        main: the main surface X_A.
        branch: the branch surface X_B.
        points: (n, 3) points near the saddle (an edge's samples).
        u_b: (n,) their first guesses of u* (their parameters on a fitted saddle edge).
        near: the saddle sampled (its interpolation starts the first Newton solve).

    Returns:
        (n,) distances from the exact saddle.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    u = np.asarray(u_b, dtype=float).ravel().copy()
    scale = _scale(main, branch)
    if near.corners:
        return _crotched_distance(main, branch, points, u, near, scale)
    return _foot_distance(main, branch, points, u, near, scale)


def _foot_distance(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    points: FloatArray,
    u: FloatArray,
    near: SaddleCurve,
    scale: float,
    bounds: tuple[FloatArray, FloatArray] | None = None,
) -> FloatArray:
    """:func:`saddle_distance`'s Gauss-Newton feet, u kept within ``bounds`` (per point) if given."""
    x = _interpolated(near, u)
    for _ in range(FOOT_STEPS):
        x, _, jac, b_u = _solve(main, branch, u, x, scale)
        rate = np.linalg.solve(jac, b_u[..., None])[..., 0]  # d(u_A, s_A, s_B)/du
        tangent = jac[:, :, 0] * rate[:, :1] + jac[:, :, 1] * rate[:, 1:2]  # X'(u)
        gap = main.points(x[:, 0], x[:, 1]) - points
        step = -np.einsum("pk,pk->p", gap, tangent) / np.einsum("pk,pk->p", tangent, tangent)
        if bounds is not None:
            step = np.clip(u + step, *bounds) - u
        if np.abs(step).max() <= FOOT_CONVERGED:
            break
        u, x = u + step, x + rate * step[:, None]
    return np.linalg.norm(gap, axis=-1)


def _crotched_distance(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    points: FloatArray,
    u: FloatArray,
    near: SaddleCurve,
    scale: float,
) -> FloatArray:
    """:func:`saddle_distance` on an equal tee's saddle (``near`` has corners): each point's foot
    looked for on the curve its first guess lies on, kept CROTCH_BAND of u_B from the crotch
    points. Near them the saddle's two curves cross where the surfaces touch and the crossing
    is ill-conditioned (the Jacobian's least singular value vanishes there, and a point within
    e of both surfaces may lie sqrt(e r) from it): a point whose foot would come nearer to a
    crotch point than CROTCH_BAND gets NaN, for the caller to measure against the saddle's
    closed form there (:meth:`~tubecad.junctions.edges.SaddleEdge.exact_distance`)."""
    u0 = near.branch_u[0]
    u = u0 + np.mod(u - u0, 2.0 * np.pi)
    corner_u = near.branch_u[list(near.corners)]
    piece = np.searchsorted(corner_u[1:-1], u)
    low, high = corner_u[piece] + CROTCH_BAND, corner_u[piece + 1] - CROTCH_BAND
    result = np.empty(len(points))
    far = (u > low) & (u < high)
    if far.any():
        result[far] = _foot_distance(main, branch, points[far], u[far], near, scale, (low[far], high[far]))
    result[~far] = np.nan
    return result


def _march(main: CurvatureLineSurface, branch: CurvatureLineSurface, scale: float, key: str) -> SaddleCurve:
    """The saddle at COARSE + 1 samples and every sample the march took between them
    (:func:`_follow` from the first point of the branch's stringer 0 outside the main)."""
    targets = np.linspace(0.0, 2.0 * np.pi, COARSE + 1)
    branch_u, marched, residual = _follow(main, branch, targets, _start(main, branch, 0.0, key), scale, key, True)
    points = main.points(marched[:, 0], marched[:, 1])
    return SaddleCurve(branch_u, marched[:, 2], np.unwrap(marched[:, 0]), marched[:, 1], points, residual)


def _follow(
    main: CurvatureLineSurface,
    branch: CurvatureLineSurface,
    targets: FloatArray,
    start: FloatArray,
    scale: float,
    key: str,
    keep_all: bool = False,
) -> tuple[FloatArray, FloatArray, float]:
    """(u_B, (u_A, s_A, s_B), largest residual) at each of ``targets`` (increasing from 0),
    marched from ``start`` (the point at targets[0]): the tangent J^-1 dX_B/du_B predicts the
    next point, Newton corrects it. The step is halved where the prediction leaves either
    surface's span or Newton does not converge from it (near tangency, r -> R, the saddle's
    s_B moves fast as the branch grazes the main wall), down to MIN_STEP, and doubled again
    after a step that went through; with ``keep_all`` every point reached is returned, not
    only the targets'. The march never evaluates a surface outside its span."""
    u = float(targets[0])
    sol = _corrected(main, branch, np.array([u]), start[None, :], scale)
    if sol is None:
        raise ParameterError(f"{key}: the saddle curve did not converge at the branch's stringer {u:.4g} rad", key=key)
    x, size, jac, b_u = sol
    _check(size, jac, np.array([u]), scale, key)
    us, xs, residual = [u], [x[0]], float(size[0])
    h = float(targets[1] - targets[0])
    for target in targets[1:]:
        while u < target:
            h = min(h, target - u)
            predicted = x + np.linalg.solve(jac, b_u[..., None])[..., 0] * h
            sol = _corrected(main, branch, np.array([u + h]), predicted, scale)
            if sol is None:
                if h < MIN_STEP:
                    raise ParameterError(
                        f"{key}: the saddle curve cannot be followed past the branch's stringer {u:.4g} rad "
                        "(the branch leaves the main surface's span there, or grazes it)",
                        key=key,
                    )
                h /= 2.0
                continue
            x, size, jac, b_u = sol
            u = float(target) if target - (u + h) < 1e-15 else u + h
            _check(size, jac, np.array([u]), scale, key)
            residual = max(residual, float(size[0]))
            if keep_all or u == target:
                us.append(u)
                xs.append(x[0])
            h *= 2.0  # a step that went through: try a longer one next
    return np.array(us), np.array(xs), residual


def _corrected(
    main: CurvatureLineSurface, branch: CurvatureLineSurface, u_b: FloatArray, x: FloatArray, scale: float
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray] | None:
    """:func:`_solve` from ``x``, or None where the prediction or a Newton step leaves a
    surface's span or Newton does not converge (the caller shortens its step)."""
    if not (_within(main, x[:, 1]) and _within(branch, x[:, 2])):
        return None
    try:
        x, size, jac, b_u = _solve(main, branch, u_b, x, scale)
    except ParameterError:  # a Newton step out of a span: evaluating there is refused
        return None
    if not (size.max() <= RESIDUAL * scale and _within(main, x[:, 1]) and _within(branch, x[:, 2])):
        return None
    return x, size, jac, b_u


def _within(surface: CurvatureLineSurface, s: FloatArray) -> bool:
    s0, s1 = surface.span
    return bool(np.all((s >= s0) & (s <= s1)))


def _interpolated(curve: SaddleCurve, u_b: FloatArray) -> FloatArray:
    """(u_A, s_A, s_B) at ``u_b`` from ``curve``'s samples: periodic cubic splines, u_A's
    winding (how often it turns round the main tube per turn of the branch) taken out first."""
    if curve.corners:
        return _interpolated_piecewise(curve, u_b)
    turns = np.round((curve.main_u[-1] - curve.main_u[0]) / (2.0 * np.pi))
    values = np.column_stack([curve.main_u - turns * curve.branch_u, curve.main_s, curve.branch_s])
    values[-1] = values[0]  # the same point, to Newton's round-off
    guess = CubicSpline(curve.branch_u, values, bc_type="periodic")(u_b)
    guess[:, 0] += turns * u_b
    return guess


def _interpolated_piecewise(curve: SaddleCurve, u_b: FloatArray) -> FloatArray:
    """:func:`_interpolated` for a saddle with corners: a cubic spline (not-a-knot) along
    each of its curves between two crotch points (``u_b`` taken round into its turn)."""
    u0 = curve.branch_u[0]
    u = u0 + np.mod(np.asarray(u_b, dtype=float) - u0, 2.0 * np.pi)
    values = np.column_stack([curve.main_u, curve.main_s, curve.branch_s])
    out = np.empty((len(u), 3))
    for a, b in zip(curve.corners[:-1], curve.corners[1:]):
        inside = (u >= curve.branch_u[a]) & (u <= curve.branch_u[b])
        out[inside] = CubicSpline(curve.branch_u[a : b + 1], values[a : b + 1])(u[inside])
    return out


def _check(size: FloatArray, jac: FloatArray, u_b: FloatArray, scale: float, key: str) -> None:
    """Refuse a sample Newton left off the curve, or where the surfaces are tangent."""
    u_b = np.broadcast_to(u_b, size.shape)
    bad = size > RESIDUAL * scale
    if bad.any():
        i = int(np.argmax(bad))
        raise ParameterError(
            f"{key}: the saddle curve did not converge at the branch's stringer {u_b[i]:.4g} rad "
            f"(|X_A - X_B| = {size[i]:.2e})",
            key=key,
        )
    flat = _tangency(jac) < TANGENCY
    if flat.any():
        raise ParameterError(
            f"{key}.radius: the branch and the main surface are tangent at the branch's stringer "
            f"{u_b[int(np.argmax(flat))]:.4g} rad (an equal-radius tee, or a branch grazing the main "
            "tube): the saddle is not one smooth curve round the branch; make the branch's radius "
            "smaller than the main's",
            key=f"{key}.radius",
        )


def dihedral_angles(main: CurvatureLineSurface, branch: CurvatureLineSurface, saddle: SaddleCurve) -> FloatArray:
    """The angle between the two surfaces along the saddle, in degrees, at each sample:
    phi = arccos(n_A . n_B) of the outward normals (90 where the branch stands square on the
    main wall; the bevel a cut edge needs to sit on the other wall follows from it)."""
    n_a = main.normal(np.mod(saddle.main_u, 2 * np.pi), saddle.main_s)
    n_b = branch.normal(saddle.branch_u, saddle.branch_s)
    return np.degrees(np.arccos(np.clip(np.einsum("pk,pk->p", n_a, n_b), -1.0, 1.0)))
