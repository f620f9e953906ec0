"""Flat patterns of the flanges of T and L stiffeners (issue 13; docs/MATH.md section 9).

A T or L flange lies at the top of its web, at mid-thickness on the offset surface of level
d = sign (h - tf / 2) (sign +1 outside, -1 inside; h the web height, tf the flange thickness),
along the same curvature line. With N the surface normal, T the line's unit tangent and
E = T x N the across direction (E = -sin th R1 + cos th R2 on a tube, as in
:mod:`tubecad.stiffeners.solids`), the strip of tangent planes X + w E is developable
(geodesic torsion 0): Darboux gives dE/ds = -turn T, so

    d(X + w E) / ds = (speed - w turn) T,     speed = |S_s|,  turn = kg speed,

kg the line's geodesic curvature towards +E. In the plane the centre line turns by turn per
unit s towards +w (alpha' = turn, gamma' = speed (cos alpha, sin alpha)), each edge w is its
parallel curve at distance w to the left, of length Int |speed - w turn| ds, and the band
w0 <= w <= w1 has area Int [(w1 - w0) speed - (w1^2 - w0^2) / 2 turn] ds.

turn is computed from the offset surface's derivatives, turn = -(S_ss . (N x S_s)) / |S_s|^2
(N x T = -E); in closed form it is kbar = k2 cos th - k1 sin th on a tube and kbar / q
(chi in place of th) on a canal surface, the same on every offset.

Ring flanges: the tangent planes of the offset surface along the ring circle envelop a
cylinder (tube) or a cone (canal surface), developed exactly to a rectangle or an annular
sector (:func:`ring_flange_flat_pattern`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from tubecad.core.errors import ParameterError, RegularityError
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.stiffeners.flat import FlatPattern, RateFunction, _side_sign
from tubecad.stiffeners.profiles import Profile
from tubecad.surface import CurvatureLineSurface

Surface = CurvatureLineSurface  # a tube or a canal surface


@dataclass(frozen=True)
class FlangePattern(FlatPattern):
    """A flange's flat pattern: ``base_length`` is the edge at w0, ``top_length`` the edge
    at w1 (``widths`` = (w0, w1) across the web's mid-plane, +w along E), ``centre_length``
    the centre line's (w = 0, the web's mid-plane) and ``level`` the offset d it lies on."""

    centre_length: float = math.nan
    widths: tuple[float, float] = (0.0, 0.0)
    level: float = 0.0


def flange_level(profile: Profile, side: str = "outside") -> float:
    """d = sign (h - tf / 2): the flange's mid-thickness above (outside) or below the wall."""
    if profile.kind not in ("T", "L"):
        raise ParameterError(f"profile: a flange needs a T or L profile, got {profile.kind!r}")
    return _side_sign(side) * (profile.height - profile.flange_thickness / 2.0)


def flange_widths(profile: Profile) -> tuple[float, float]:
    """(w0, w1): T from -bf/2 to +bf/2, L from -tw/2 to -tw/2 + bf (profiles.outline: to +w)."""
    bf, tw = profile.flange_width, profile.thickness
    return (-bf / 2.0, bf / 2.0) if profile.kind == "T" else (-tw / 2.0, -tw / 2.0 + bf)


def offset_surface(base: Surface, level: float, key: str = "height") -> Surface:
    """``base``.offset(level), an irregular or vanishing offset refused naming ``key``."""
    if level == 0.0:
        return base
    try:
        return base.offset(level)
    except (RegularityError, ParameterError) as exc:
        raise ParameterError(f"{key}: the offset surface at {level:+g} is not a regular surface: {exc}") from None


def flange_rates(surface: Surface, u: float) -> tuple[RateFunction, RateFunction]:
    """(turn, speed) along the stringer ``u`` (radians; chi0 on a canal surface) of ``surface``:
    speed = |S_s| and turn = -(S_ss . (N x S_s)) / |S_s|^2 = kg speed, the geodesic turn of
    the line towards +E = T x N per unit s."""

    def both(s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s = np.asarray(s, dtype=float)
        flat = s.ravel()
        d = surface.derivatives(np.full(flat.shape, float(u)), flat)
        cross = np.cross(d.normal, d.S_s)
        speed2 = np.einsum("...i,...i", d.S_s, d.S_s)
        turn = -np.einsum("...i,...i", d.S_ss, cross) / speed2
        return turn.reshape(s.shape), np.sqrt(speed2).reshape(s.shape)

    return (lambda s: both(s)[0]), (lambda s: both(s)[1])


def developed_band(
    turn: RateFunction,
    speed: RateFunction,
    span: tuple[float, float],
    widths: tuple[float, float],
    name: str = "flange",
    samples: int = 2001,
    breaks: np.ndarray | None = None,
    level: float = 0.0,
) -> FlangePattern:
    """The development of the tangent-plane strip X + w E, w in ``widths`` = (w0, w1), along a
    curvature line with speed(s) = |X_s| and turn(s) = kg |X_s| (towards +E): the centre line
    alpha' = turn, gamma' = speed (cos alpha, sin alpha), the edges gamma + w (-sin alpha,
    cos alpha); lengths Int |speed - w turn| ds, area Int [(w1 - w0) speed - (w1^2 - w0^2) / 2
    turn] ds (Chebyshev quadratures, round-off accurate). The outline runs along the edge w0
    from the span's start, then back along the edge w1. An edge whose speed - w turn reaches 0
    (the flange wider than the line's geodesic radius of curvature) is refused."""
    s0, s1 = span
    w0, w1 = (float(w) for w in widths)
    edges = np.array([s0, s1]) if breaks is None else np.asarray(breaks, dtype=float)

    def fit(f: RateFunction, label: str) -> PiecewiseChebyshev:
        return PiecewiseChebyshev.fit(f, s0, s1, name=label, breaks=edges)

    # resolved together, turn scaled by the span: its round-off noise (zero on a cone) is then
    # measured against the turn over the span in radians, not against itself
    scale = s1 - s0
    pair = fit(lambda t: np.stack([speed(t), scale * turn(t)], axis=-1), "the flange's speed and geodesic turn")
    speed_c = lambda t: pair(t)[..., 0]  # noqa: E731
    turn_c = lambda t: pair(t)[..., 1] / scale  # noqa: E731
    s = np.linspace(s0, s1, samples)
    for w in (w0, w1):
        rate = speed_c(s) - w * turn_c(s)
        if rate.min() <= 0.0:
            at = float(s[np.argmin(rate)])
            raise ParameterError(
                f"flange_width: the flange edge at w = {w:g} folds over near s = {at:.6g} (its width "
                "exceeds the line's geodesic radius of curvature there)"
            )
    turned = pair.antiderivative()
    alpha = lambda t: turned(t)[..., 1] / scale  # noqa: E731
    x = fit(lambda t: speed_c(t) * np.cos(alpha(t)), "flat x").antiderivative()
    y = fit(lambda t: speed_c(t) * np.sin(alpha(t)), "flat y").antiderivative()
    a = alpha(s)
    centre = np.stack([x(s), y(s)], axis=1)
    left = np.stack([-np.sin(a), np.cos(a)], axis=1)  # the ruling E's image

    def integral(f: RateFunction, label: str) -> float:
        return float(fit(f, label).antiderivative()(s1))

    return FlangePattern(
        name,
        "flange",
        np.concatenate([centre + w0 * left, (centre + w1 * left)[::-1]]),
        base_length=integral(lambda t: speed_c(t) - w0 * turn_c(t), "edge w0"),
        top_length=integral(lambda t: speed_c(t) - w1 * turn_c(t), "edge w1"),
        area=integral(lambda t: (w1 - w0) * speed_c(t) - 0.5 * (w1 * w1 - w0 * w0) * turn_c(t), "area"),
        centre_length=float(turned(s1)[0]),
        widths=(w0, w1),
        level=level,
    )


def on_span(base: Surface, u: float, span: tuple[float, float] | None) -> tuple[Surface, float]:
    """``base`` over ``span`` (inside its own) and the stringer u's angle there: the same u on a
    tube (the restricted axis keeps its frame), chi(u, span start) on a canal surface, whose
    restricted stringers are named by their angle at the sub-span's start."""
    if span is None or tuple(span) == tuple(base.span):
        return base, u
    piece = base.restricted(span)
    return piece, float(base.stringer_angle(u, piece.span[0]))  # a tube's: u


def span_breaks(base: Surface) -> np.ndarray:
    """The span's ends and the axis' joints (and a radius table's knots) inside it."""
    s0, s1 = base.span
    inner = base.s_breaks()
    return np.unique(np.concatenate([[s0, s1], [x for x in inner if s0 < x < s1]]))


def stringer_flange_flat_pattern(
    base: Surface,
    theta_deg: float,
    profile: Profile,
    side: str = "outside",
    span: tuple[float, float] | None = None,
    name: str = "stringer_flange",
    samples: int = 2001,
) -> FlangePattern:
    """The developed flange of the T or L stringer at ``theta_deg`` (u on a tube, chi0 at the
    wall's start on a canal surface) over ``span`` (default the wall's): the band w0..w1
    (:func:`flange_widths`) of the tangent planes of the offset surface at
    :func:`flange_level` along the stringer (:func:`developed_band`, :func:`flange_rates`).
    base_length is the edge at w0, top_length the edge at w1, centre_length the line's."""
    level = flange_level(profile, side)
    piece, u = on_span(base, math.radians(theta_deg), span)
    turn, speed = flange_rates(offset_surface(piece, level), u)
    return developed_band(turn, speed, piece.span, flange_widths(profile), name, samples, span_breaks(piece), level)


def ring_flange_flat_pattern(
    base: Surface, s: float, profile: Profile, side: str = "outside", name: str = "ring_flange", samples: int = 721
) -> FlangePattern:
    """The developed flange of the T or L ring frame at ``s``: the band w0..w1 (along the wall,
    towards +s) of the tangent planes of the offset surface at d = :func:`flange_level` along
    its circle s = const, of radius a = R + d (tube) or (r + d) q (canal, q = sqrt(1 - r'^2)).

    On a tube (or where r' = 0) the tangent planes envelop a cylinder: a rectangle 2 pi a by
    w1 - w0. On a canal surface they envelop the cone with apex on the axis through the
    circle's centre, generators m = q t + r' e, slant a / |r'| to the circle: an annular
    sector of angle 2 pi |r'| whose edge w has radius a / |r'| + sign(r') w (the apex lies
    behind the circle, towards -s, where r' > 0). The ring solid's flange face is the offset
    wall surface itself; this band touches it along the centre circle and departs from it by
    O(k w^2) (k the wall's curvature along s): the flange is rolled or bent to the wall (see
    :mod:`.bending`)."""
    level = flange_level(profile, side)
    w0, w1 = flange_widths(profile)
    at = base.axis.inside(np.array([float(s)]))  # s inside the span
    # only this circle of the offset matters, not the whole offset surface (a tube's law: r = R, r' = 0)
    r, dr = float(base.radius_law.r(at)[0]), float(base.radius_law.dr(at)[0])
    if not r + level > 0.0:
        raise ParameterError(f"height: the ring flange at s = {s:g} would lie at radius {r:g} {level:+g} <= 0")
    a = (r + level) * math.sqrt(1.0 - dr * dr)
    extra: dict[str, Any] = dict(centre_length=2 * math.pi * a, widths=(w0, w1), level=level)
    if abs(dr) <= 1e-12:  # a cylinder band: develops to a rectangle
        length = 2 * math.pi * a
        outline = np.array([[0.0, w0], [length, w0], [length, w1], [0.0, w1]])
        return FlangePattern(name, "flange", outline, length, length, length * (w1 - w0), **extra)
    slant, angle = a / abs(dr), 2 * math.pi * abs(dr)
    toward = 1.0 if dr > 0 else -1.0  # +w leads away from the apex where r' > 0
    r0, r1 = slant + toward * w0, slant + toward * w1
    arc = 0.5 * math.pi + 0.5 * angle * np.linspace(-1.0, 1.0, samples)
    ring = np.stack([np.cos(arc), np.sin(arc)], axis=1)
    outline = np.concatenate([r0 * ring, r1 * ring[::-1]])  # edge w0, radial end, edge w1 back, radial end
    r_in, r_out = min(r0, r1), max(r0, r1)
    return FlangePattern(
        name,
        "flange",
        outline,
        angle * r0,
        angle * r1,
        0.5 * angle * (r_out**2 - r_in**2),
        sector=(r_in, r_out, angle),
        **extra,
    )
