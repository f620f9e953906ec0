"""Exact-section NURBS of a canal surface (docs/MATH.md section 8): every s-isoline an exact
rational quadratic circle, only twelve functions of s approximated.

With (sigma, gamma) = (sin(chi0/2), cos(chi0/2)) and (a, b) = Mb(s) (sigma, gamma) (the
half-angle system of :mod:`..surface.canal`), the quadratic forms a^2 + b^2, b^2 - a^2 and 2ab
are affine in (1, cos chi0, sin chi0), since sigma^2 = (1 - cos chi0)/2, gamma^2 = (1 +
cos chi0)/2 and sigma gamma = sin(chi0)/2. Multiplying X = c - r r' t + r q (cos chi r1 +
sin chi r2) by D = a^2 + b^2 therefore gives the homogeneous point

    X_h(chi0, s) = A0(s) + cos(chi0) A1(s) + sin(chi0) A2(s)    (4-vectors (D X, D))

    A_k = (D_k c + r N_k, D_k),   N_k = -r' D_k t + q (B_k r1 + C_k r2)

with D_k, B_k, C_k the coefficients of a^2 + b^2, b^2 - a^2 and 2ab (quadratic in Mb's
entries). N = N0 + cos N1 + sin N2 is D times the unit normal -r' t + q e, and the offset
by d (the canal surface of r + d, same Mb) is A_k + d (N_k, 0): one B-spline in s of the
21-vector (A0, A1, A2, N0, N1, N2) serves every wall surface, as the tube's frame spline
does. Substituting the exact rational unit circle (X_i, Y_i, w_i) of :mod:`.circle` for
(cos chi0, sin chi0), the homogeneous poles are

    H_ij = w_i (A0_j + X_i A1_j + Y_i A2_j)

(A_kj the spline's poles), so every s-isoline is exactly the characteristic circle, and the
u-isolines are the stringers chi0 = const. The weights w_i (D0_j + X_i D1_j + Y_i D2_j) are
positive when each C1 sub-arc of the circle is short enough for the condition number
kappa of Mb: a sub-arc alpha is used with cot(alpha / 4) >= sqrt(3) kappa (then the image
of a sub-arc under the Moebius map stays below 120 deg), and the weights are checked.

The spline is fitted like the frame spline (:func:`.frame_spline.refine_spline`: Greville
interpolation, knots at the rings (of multiplicity the degree: exact there, so a ring's
isoline is its characteristic circle), the axis' joints and a radius table's knots, spans
halved) until, sampled densely at every offset built, the distance of the fitted surface
from the exact canal surface (:meth:`CanalSurface.points` + d :meth:`CanalSurface.normal`,
parameter-matched) is <= tolerance / 2 and |cos| between its isolines <= orthogonality / 2.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from OCP.Geom import Geom_BSplineSurface
from scipy.interpolate import BSpline

from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, DEFAULT_ORTHOGONALITY, check_tolerance
from tubecad.fitting.circle import MAX_SUB_ARC, CircleSpline
from tubecad.fitting.exact_section import TubeSurface
from tubecad.fitting.frame_spline import (
    FitError,
    SpanSamples,
    SplineSize,
    _initial_breaks,
    _joint_multiplicities,
    _with_rings,
    refine_spline,
)
from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals, reals_2d
from tubecad.surface.protocol import CurvatureLineSurface, is_surface

#: angles chi0 around the surface at which the fit is measured (per s sample)
MEASURE_ANGLES = 24
#: a C1 sub-arc alpha of the circle is used with cot(alpha / 4) >= WEIGHT_MARGIN kappa(Mb):
#: its image under the Moebius map then stays below 120 deg (below 180 deg the weights are
#: positive; the margin keeps the middle poles near the circle)
WEIGHT_MARGIN = math.sqrt(3.0)
#: per component group: A0 (x, y, z, w), A1, A2, then N0, N1, N2 (x, y, z)
COMPONENTS = 21


def _quadratic_coefficients(m: np.ndarray) -> tuple[list[np.ndarray], list[np.ndarray], list[np.ndarray]]:
    """The coefficients on (1, cos chi0, sin chi0) of a^2 + b^2, b^2 - a^2 and 2ab, (a, b) = m v."""
    m00, m01, m10, m11 = m[..., 0, 0], m[..., 0, 1], m[..., 1, 0], m[..., 1, 1]
    D = [0.5 * (m00**2 + m01**2 + m10**2 + m11**2), 0.5 * (m01**2 - m00**2 + m11**2 - m10**2), m00 * m01 + m10 * m11]
    B = [0.5 * (m10**2 + m11**2 - m00**2 - m01**2), 0.5 * (m11**2 - m10**2 - m01**2 + m00**2), m10 * m11 - m00 * m01]
    C = [m00 * m10 + m01 * m11, m01 * m11 - m00 * m10, m00 * m11 + m01 * m10]
    return D, B, C


def canal_functions(canal: CurvatureLineSurface, s: np.ndarray) -> np.ndarray:
    """The exact 21-vector (A0, A1, A2 as (xyz, w); N0, N1, N2 as xyz) at ``s``, shape (len(s), 21)."""
    s = np.asarray(s, dtype=float)
    D, B, C = _quadratic_coefficients(canal.moebius_matrix(s))
    c = canal.axis.position(s)
    t, r1, r2 = canal.axis.rotation_minimising_frame(s)
    law = canal.radius_law
    r, dr = law.r(s), law.dr(s)
    q = np.sqrt(1.0 - dr * dr)
    A, N = [], []
    for k in range(3):
        n = (-dr * D[k])[:, None] * t + q[:, None] * (B[k][:, None] * r1 + C[k][:, None] * r2)
        A.append(np.hstack([D[k][:, None] * c + r[:, None] * n, D[k][:, None]]))
        N.append(n)
    return np.hstack(A + N)


def homogeneous(F: np.ndarray, offset: float = 0.0) -> np.ndarray:
    """(A0, A1, A2) of the offset by ``offset`` from rows of the 21-vector: shape (..., 3, 4)."""
    A = F[..., :12].reshape(F.shape[:-1] + (3, 4)).copy()
    if offset:
        A[..., :3] += offset * F[..., 12:].reshape(F.shape[:-1] + (3, 3))
    return A


def condition_number(F: np.ndarray) -> float:
    """The largest condition number of Mb over rows of the 21-vector: sqrt(D_max / D_min)
    with D = D0 + cos D1 + sin D2 = |Mb v|^2."""
    D = F[..., [3, 7, 11]]
    rho = np.hypot(D[..., 1], D[..., 2])
    return float(np.sqrt((D[..., 0] + rho) / (D[..., 0] - rho)).max())


def sub_arc_for(kappa: float) -> float:
    """The longest C1 sub-arc of the circle for a Moebius map of condition number ``kappa``:
    cot(alpha / 4) = WEIGHT_MARGIN kappa, at most the tube's 90 deg."""
    return min(MAX_SUB_ARC, 4.0 * math.atan(1.0 / (WEIGHT_MARGIN * kappa)))


def _points_and_derivatives(A: np.ndarray, dA: np.ndarray, chi0: np.ndarray) -> tuple[np.ndarray, ...]:
    """X, X_chi0, X_s of X = H_xyz / H_w, H = A0 + cos A1 + sin A2, at rows of A (n, 3, 4) x angles."""
    cos, sin = np.cos(chi0)[None, :, None], np.sin(chi0)[None, :, None]
    H = A[:, None, 0] + cos * A[:, None, 1] + sin * A[:, None, 2]
    H_chi = -sin * A[:, None, 1] + cos * A[:, None, 2]
    H_s = dA[:, None, 0] + cos * dA[:, None, 1] + sin * dA[:, None, 2]
    w = H[..., 3:]
    X = H[..., :3] / w
    return X, (H_chi[..., :3] - X * H_chi[..., 3:]) / w, (H_s[..., :3] - X * H_s[..., 3:]) / w


@dataclass(frozen=True)
class CanalSpline(SplineSize):
    """The B-spline in s of the 21-vector (A0, A1, A2, N0, N1, N2) of a canal surface, with
    the bounds it was measured to meet at every offset in ``offsets`` (``radius_bound``: the
    largest radius r + d built on it). Stands in for a :class:`.frame_spline.FrameSpline`
    where a build reports it (degree, poles, spans)."""

    spline: BSpline
    position_bound: float
    orthogonality_bound: float
    radius_bound: float
    offsets: tuple[float, ...]
    #: the longest C1 sub-arc of the circle spline the surfaces use (weights positive)
    max_sub_arc: float
    condition: float
    weights = None
    arc_length = None
    parameter = None

    @property
    def rational(self) -> bool:
        return False

    def values(self, s: np.ndarray | float) -> np.ndarray:
        return self.spline(s)

    def points(self, chi0: np.ndarray, s: np.ndarray, offset: float = 0.0) -> np.ndarray:
        """The fitted surface (before OCCT) at the offset: shape (len(s), len(chi0), 3)."""
        A = homogeneous(self.spline(np.asarray(s, dtype=float)), offset)
        chi0 = np.asarray(chi0, dtype=float)
        H = A[:, None, 0] + np.cos(chi0)[None, :, None] * A[:, None, 1] + np.sin(chi0)[None, :, None] * A[:, None, 2]
        return H[..., :3] / H[..., 3:]


def fit_canal(
    canal: CurvatureLineSurface,
    offsets: Sequence[float] = (0.0,),
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    orthogonality: float = DEFAULT_ORTHOGONALITY,
    degree: int = 7,
    max_spans: int = 4096,
    rings: Sequence[float] = (),
    exact_at_rings: bool = True,
) -> CanalSpline:
    """Fit the 21-vector of ``canal`` adaptively until, at each of the ``offsets`` (the
    normal offsets d of the surfaces that will be built on it: r + d), the fitted surface is
    within ``tolerance`` / 2 of the exact one and its isolines within ``orthogonality`` / 2
    of orthogonal (measured at SAMPLES_PER_SPAN x MEASURE_ANGLES points per span).

    ``rings`` (arc lengths inside the span) become knots, of multiplicity ``degree`` (the
    fit exact there: face boundaries, see the module's text) or, without
    ``exact_at_rings`` (a ring frame's faces span some of its section's s-values), simple
    ones, like the axis' joints (reduced
    continuity as in :func:`.frame_spline.fit_frame`) and a radius table's knots (C1: r' is
    only C1 there), except a table knot a sliver away from a joint or ring, which is left
    out or added back exactly after the fit (see SLIVER_NOISE, DROP)."""
    if not is_surface(canal):
        raise ParameterError(f"canal must be a CanalSurface or a CurvatureLineTube, got {type(canal).__name__}")
    if isinstance(degree, bool) or not (isinstance(degree, int) and 3 <= degree <= 9):
        raise ParameterError(f"degree must be a whole number in [3, 9], got {degree!r}")
    tolerance = check_tolerance("tolerance", tolerance)
    orthogonality = check_tolerance("orthogonality", orthogonality)
    offsets = tuple(float(d) for d in offsets) or (0.0,)
    axis, law = canal.axis, canal.radius_law
    joints = _joint_multiplicities(axis, degree)
    ring_s = np.asarray(rings, dtype=float)
    # a table's knots: the functions are C1 there, knots of multiplicity degree - 1. One a
    # sliver away from a joint or ring (see _table_knots) is not interpolated across (the
    # values in the sliver cannot give its derivatives: their rounding is amplified by
    # 1 / sliver). Where leaving the knot out costs less than DROP of the targets it is left
    # out; otherwise the fit interpolates F - K (s - b)_+^2 / 2 instead (C2 at b, K the jump
    # of F'' there) and gets b back at multiplicity degree - 1 with that term added exactly
    # (knot insertion). One within rounding of a joint or ring is taken onto it.
    slivers = []
    for b, fixed in _table_knots(canal, np.concatenate([ring_s, list(joints)]), orthogonality):
        if fixed is None or b == fixed:
            joints[b] = max(joints.get(b, 1), degree - 1)
        else:
            slivers.append((b, fixed))
    singular = [
        (b, K)
        for (b, fixed), K in zip(slivers, _jumps(canal, [b for b, _ in slivers]))
        if not _droppable(canal, offsets, b, fixed, K, tolerance, orthogonality)
    ]
    breaks = _with_rings(_initial_breaks(axis, 8), np.concatenate([ring_s, list(joints)]))
    chi0 = np.linspace(0.0, 2.0 * math.pi, MEASURE_ANGLES, endpoint=False) + 0.05

    samples = SpanSamples(lambda s: (canal.points(chi0[None, :], s[:, None]), canal.normal(chi0[None, :], s[:, None])))

    def values(s: np.ndarray) -> np.ndarray:
        F = canal_functions(canal, s)
        for b, K in singular:
            F -= np.maximum(s - b, 0.0)[:, None] ** 2 * (0.5 * K)
        return F

    def span_errors(fitted: BSpline, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if not singular:
            return _span_errors(fitted, breaks)
        spline = _with_singular_parts(fitted, singular)
        fine = np.unique(spline.t)  # the slivers sampled too; each fine span lies in one span of breaks
        pos, orth = _span_errors(spline, fine)
        span = np.clip(np.searchsorted(breaks, 0.5 * (fine[:-1] + fine[1:])) - 1, 0, len(breaks) - 2)
        out = np.zeros((2, len(breaks) - 1))
        np.maximum.at(out[0], span, pos)
        np.maximum.at(out[1], span, orth)
        return out[0], out[1]

    def _span_errors(spline: BSpline, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m = len(breaks) - 1
        s, exact, normal = samples(breaks)
        F, dF = spline(s), spline.derivative()(s)
        pos = np.zeros(len(s))
        orth = np.zeros(len(s))
        for d in offsets:
            X, X_chi, X_s = _points_and_derivatives(homogeneous(F, d), homogeneous(dF, d), chi0)
            pos = np.maximum(pos, np.linalg.norm(X - (exact + d * normal), axis=-1).max(axis=1))
            cos = np.abs(np.einsum("ijk,ijk->ij", X_chi, X_s)) / (
                np.linalg.norm(X_chi, axis=-1) * np.linalg.norm(X_s, axis=-1)
            )
            orth = np.maximum(orth, cos.max(axis=1))
        return pos.reshape(m, -1).max(axis=1), orth.reshape(m, -1).max(axis=1)

    spline, pos, orth = refine_spline(
        values if singular else lambda s: canal_functions(canal, s),
        breaks,
        degree,
        joints,
        span_errors,
        tolerance,
        orthogonality,
        max_spans,
        "the canal section spline",
        rings=ring_s.tolist() if exact_at_rings else (),
    )
    spline = _with_singular_parts(spline, singular)
    s_check = np.linspace(*canal.span, 4001)
    kappa = max(condition_number(spline(s_check)), condition_number(spline.c))
    radius_bound = max(law.max_radius + d for d in offsets)
    return CanalSpline(spline, pos, orth, radius_bound, offsets, sub_arc_for(kappa), kappa)


#: a table knot is a sliver away from a joint or ring when, its values' rounding (about
#: eps (|c| + r)) amplified by 1 / gap in the sliver's derivatives, SLIVER_NOISE times that
#: would exceed the orthogonality target (see :func:`fit_canal`)
SLIVER_NOISE = 200.0
#: a sliver's table knot is left out where that costs at most this fraction of the targets,
#: or less than the rounding of the poles, amplified by KEEP_NOISE / gap in the sliver's
#: derivatives, would cost with the knot kept (about eps (|c| + r) KEEP_NOISE / gap)
DROP = 0.1
KEEP_NOISE = 2.0
#: a table knot within this fraction of the span of a joint or ring is taken onto it
COINCIDENT = 1e-12


def _table_knots(
    canal: CurvatureLineSurface, fixed: np.ndarray, orthogonality: float
) -> list[tuple[float, float | None]]:
    """Per radius table knot b: (b, the joint or ring it is a sliver away from, or None); a
    knot within COINCIDENT of the span of one is returned as that break, twice."""
    s0, s1 = canal.span
    fixed = np.asarray(fixed, dtype=float)
    fixed = fixed[(fixed > s0) & (fixed < s1)]
    out: list[tuple[float, float | None]] = []
    if fixed.size == 0:
        return [(float(b), None) for b in canal.radius_law.breaks]
    size = _size(canal) if canal.radius_law.breaks.size else 0.0
    sliver = SLIVER_NOISE * np.finfo(float).eps * size / (0.5 * orthogonality)
    for b in map(float, canal.radius_law.breaks):
        f = float(fixed[np.argmin(np.abs(fixed - b))])
        gap = abs(f - b)
        out.append((f, f) if gap <= COINCIDENT * (s1 - s0) else (b, f if gap < sliver else None))
    return out


def _size(canal: CurvatureLineSurface) -> float:
    """The largest |c| + r over the span: the size of the fitted functions' values."""
    s = np.linspace(*canal.span, 257)
    return float(np.linalg.norm(canal.axis.position(s), axis=1).max() + canal.radius_law.max_radius)


def _jumps(canal: CurvatureLineSurface, knots: Sequence[float]) -> list[np.ndarray]:
    """K = [F''](b) per table knot b, the jump of the 21-vector's second derivative. Only
    r''' jumps there (r, r', r'', Mb, Mb', Mb'' and the axis are continuous: b is no joint),
    and F depends on r'' only through r': K = dF/dr' [r''']."""
    law = canal.radius_law
    s0, s1 = canal.span
    rows = np.unique(np.concatenate([[s0, s1], law.breaks]))
    out = []
    for b in knots:
        i = int(np.searchsorted(rows, b))  # rows[i] == b; r''' is constant on a table's pieces
        jump = float(np.diff(law.dddr(np.array([0.5 * (rows[i - 1] + b), 0.5 * (b + rows[i + 1])])))[0])
        out.append(jump * _dr_partial(canal, np.array([b]))[0])
    return out


def _droppable(
    canal: CurvatureLineSurface,
    offsets: Sequence[float],
    b: float,
    fixed: float,
    K: np.ndarray,
    tolerance: float,
    orthogonality: float,
) -> bool:
    """Whether the table knot ``b`` (a sliver gap from the joint or ring ``fixed``, F'' jumping
    by ``K``) is better left out of the knots (see DROP): the spline then misses a term of F
    supported on the sliver, K (s - b)^2 / 2 there, so X by about |K|_H gap^2 / (2 w) and
    X_s by |K|_H gap / w (|K|_H the largest jump of H = A0 + cos A1 + sin A2 at any offset,
    w = a^2 + b^2 > 0 its weight)."""
    F = canal_functions(canal, np.array([b]))[0]
    D = F[[3, 7, 11]]
    w = D[0] - math.hypot(D[1], D[2])
    jump = max(
        sum(np.linalg.norm(K[4 * k : 4 * k + 3] + d * K[12 + 3 * k : 15 + 3 * k]) for k in range(3)) for d in offsets
    )
    # |X_s| from the exact surface on b's far side from the sliver (over a step far above rounding)
    gap, step = abs(b - fixed), math.copysign(1e-6 * _size(canal), b - fixed)
    chi0 = np.linspace(0.0, 2.0 * math.pi, MEASURE_ANGLES, endpoint=False)
    s = np.array([b, min(max(b + step, canal.span[0]), canal.span[1])])
    speed = min(
        np.linalg.norm(
            np.diff(canal.points(chi0[None, :], s[:, None]) + d * canal.normal(chi0[None, :], s[:, None]), axis=0),
            axis=-1,
        ).min()
        / abs(s[1] - s[0])
        for d in offsets
    )
    kept = KEEP_NOISE * np.finfo(float).eps * _size(canal) / gap
    return jump * gap * gap / (2.0 * w) <= DROP * 0.5 * tolerance and jump * gap / (w * speed) <= max(
        DROP * 0.5 * orthogonality, kept
    )


def _dr_partial(canal: CurvatureLineSurface, s: np.ndarray) -> np.ndarray:
    """dF/dr' with Mb, r and the axis held, (len(s), 21): n_k = -r' D_k t + q (B_k r1 + C_k r2),
    q = sqrt(1 - r'^2), so dn_k = -D_k t - r' / q (B_k r1 + C_k r2) and dA_k = (r dn_k, 0)."""
    D, B, C = _quadratic_coefficients(canal.moebius_matrix(s))
    t, r1, r2 = canal.axis.rotation_minimising_frame(s)
    law = canal.radius_law
    r, dr = law.r(s), law.dr(s)
    slope = dr / np.sqrt(1.0 - dr * dr)
    A, N = [], []
    for k in range(3):
        n = -D[k][:, None] * t - slope[:, None] * (B[k][:, None] * r1 + C[k][:, None] * r2)
        A.append(np.hstack([r[:, None] * n, np.zeros((len(s), 1))]))
        N.append(n)
    return np.hstack(A + N)


def _insert_knot(spline: BSpline, x: float, times: int) -> BSpline:
    """``spline`` with the knot ``x`` inserted ``times`` times (Boehm's algorithm): the same
    function, its new poles convex combinations of the old (no interpolation, no conditioning)."""
    t, c, k = np.asarray(spline.t, dtype=float), np.asarray(spline.c, dtype=float), int(spline.k)
    for _ in range(times):
        i = int(np.searchsorted(t, x, side="right")) - 1  # t[i] <= x < t[i + 1]
        a = ((x - t[i - k + 1 : i + 1]) / (t[i + 1 : i + k + 1] - t[i - k + 1 : i + 1]))[:, None]
        middle = (1.0 - a) * c[i - k : i] + a * c[i - k + 1 : i + 1]
        c = np.concatenate([c[: i - k + 1], middle, c[i:]])
        t = np.insert(t, i + 1, x)
    return BSpline(t, c, k)


def _with_singular_parts(spline: BSpline, singular: Sequence[tuple[float, np.ndarray]]) -> BSpline:
    """``spline`` + sum K (s - b)_+^2 / 2, exactly: each b inserted to multiplicity degree - 1
    (the term is C1 there), then the terms' poles added, their blossoms: zero on a pole whose
    knots t_{i+1..i+k} lie below b, sum_{a<c} (t_a - b)(t_c - b) / (k (k - 1)) on one above."""
    if not singular:
        return spline
    k = int(spline.k)
    for b, _ in singular:
        spline = _insert_knot(spline, b, max(0, k - 1 - int(np.count_nonzero(spline.t == b))))
    t, c = spline.t, np.array(spline.c, dtype=float)
    for b, K in singular:
        for i in range(len(c)):
            u = t[i + 1 : i + k + 1] - b
            if u.min() >= 0.0:
                c[i] += (0.5 * (u.sum() ** 2 - (u * u).sum()) / (k * (k - 1))) * K
    return BSpline(t, c, k)


@dataclass(frozen=True)
class CanalSectionSurface(TubeSurface):
    """An OCCT surface of a canal surface: u = 0 is the stringer chi0 = ``origin_deg`` (its
    angle from r1 at the span's start), u = const the stringers, s = const the exact
    characteristic circles. ``tube`` is the exact :class:`CanalSurface` it approximates
    (of r + ``offset``), ``fit`` the spline it was built from. :meth:`u_at` and
    :meth:`theta_at` convert stringer angles chi0, as for a tube."""

    fit: CanalSpline | None = None
    offset: float = 0.0

    @property
    def canal(self) -> bool:
        """True: a canal surface's section (see :attr:`TubeSurface.canal`)."""
        return True

    @property
    def level(self) -> float:
        """The offset d of this surface (the canal surface of r + d; see :attr:`TubeSurface.level`)."""
        return self.offset


def canal_section_surface(
    canal: CurvatureLineSurface,
    fit: CanalSpline,
    offset: float = 0.0,
    stringers_deg: Sequence[float] | None = None,
    exact: CurvatureLineSurface | None = None,
) -> CanalSectionSurface:
    """The periodic-in-u rational surface of the offset by ``offset`` of ``canal`` on ``fit``
    (``exact``: that offset surface, if already made). With ``stringers_deg`` (angles chi0
    from r1 at the span's start, the face boundaries) the circle's C0 knots are chosen among
    them and the first is u = 0; without, u = 0 is chi0 = 0 and the only C0 knot."""
    angles = np.zeros(1) if stringers_deg is None else np.asarray(stringers_deg, dtype=float)
    origin_deg = float(angles[0])
    F = fit.spline.c
    A = homogeneous(F, offset)  # (poles, 3, 4)
    a = math.radians(origin_deg)
    A1, A2 = math.cos(a) * A[:, 1] + math.sin(a) * A[:, 2], -math.sin(a) * A[:, 1] + math.cos(a) * A[:, 2]
    sub_arc = fit.max_sub_arc
    while True:
        circle = CircleSpline.for_stringers(np.radians(angles - origin_deg), max_sub_arc=sub_arc)
        H = circle.weights[:, None, None] * (
            A[None, :, 0] + circle.x[:, None, None] * A1[None] + circle.y[:, None, None] * A2[None]
        )
        weights = H[..., 3]
        if weights.min() > 1e-6 * weights.max():
            break
        if sub_arc < math.radians(5.0):
            raise FitError(
                f"the canal surface's Moebius map is too far from a rotation (condition number "
                f"{fit.condition:.3g}): its NURBS weights are not positive"
            )
        sub_arc *= 0.5
    s_knots, s_mults = knots_and_multiplicities(fit.spline.t)
    surface = Geom_BSplineSurface(
        points_2d(H[..., :3] / weights[..., None]),
        reals_2d(weights),
        reals(circle.knots),
        reals(s_knots),
        integers(circle.multiplicities),
        integers(s_mults),
        2,
        fit.degree,
        True,
        False,
    )
    exact = exact if exact is not None else (canal if offset == 0.0 else canal.offset(offset, allow_irregular=True))
    return CanalSectionSurface(surface, exact, origin_deg, circle, None, fit, offset)
