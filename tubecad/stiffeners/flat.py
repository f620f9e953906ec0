"""Flat patterns of stiffener webs (issue 4): webs cut from flat plate.

Along a line of curvature the surface normals form a developable strip (Rodrigues:
dN = -kappa_n dX), so a web standing along the normal develops without stretching
(docs/MATH.md section 9). For a curvature line X(s) of speed |X_s| = sqrt(G) and normal
curvature kappa_n = N / G (outward normal; > 0 where the line bends towards it), the web of
height h outside (+) or inside (-) the wall develops to the region between the plane curve
of signed curvature +-kappa_n and its offset by h:
      d alpha / ds = +-kappa_n sqrt(G),  d gamma / ds = sqrt(G) (cos alpha, sin alpha),
the base edge has length Int sqrt(G) ds, the top edge (d(X +- h n) = sqrt(G) (1 -+ h kappa_n)
dX / |dX|) Int |sqrt(G) (1 -+ h kappa_n)| ds, and the area Int [h sqrt(G) -+ h^2 / 2
kappa_n sqrt(G)] ds. :func:`developed_strip` does this for any turn(s) = kappa_n sqrt(G)
and speed(s) = sqrt(G):
- on the tube of radius R, a stringer at u: turn = k cos phi (= k1 cos u + k2 sin u, with
  phi = u - Int sigma ds, docs/MATH.md section 2) and speed = 1 - R k cos phi;
- on the canal surface (docs/MATH.md section 8), the stringer chi0: along it the normal
  n = -r' t + q e changes by dn / ds = -(r'' / q + kappa) (q t + r' e), kappa = k1 cos chi +
  k2 sin chi, while dX / ds = sqrt(G) (q t + r' e); so turn = r'' / q + kappa and
  speed = q - r r'' / q - r kappa = q - r turn (r' = 0: the tube's, bit for bit).
Ring webs: on the tube the normals along a ring lie in its plane, so the web is the annulus
of radii R and R +- h; on the canal surface the normals along the characteristic circle at s
all pass through the sphere centre c(s), so the web is a piece of the cone with apex c(s)
whose circle at slant rho has radius rho q: it develops to the annular sector of radii r and
r +- h and angle 2 pi q (a full annulus when r' = 0).
The quadratures use the adaptive Chebyshev series of :mod:`tubecad.curves.chebyshev`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tubecad.core.atomic import save_figure
from tubecad.core.dxf import Drawing
from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.surface import CurvatureLineSurface

RateFunction = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class FlatPattern:
    """A web's flat outline (closed polygon, model units) and its exact measures."""

    name: str
    kind: str  # ring | stringer
    outline: np.ndarray  # (n, 2); for a full ring the outer circle, the hole is ``hole``
    base_length: float
    top_length: float
    area: float
    hole: np.ndarray | None = None
    #: a canal ring's annular sector (inner radius, outer radius, angle), centred on the
    #: origin and symmetric about +y; the outline then goes round it (no hole)
    sector: tuple[float, float, float] | None = None


def _side_sign(side: str) -> float:
    if side not in ("outside", "inside"):
        raise ParameterError(f"side must be one of outside, inside, got {side!r}")
    return 1.0 if side == "outside" else -1.0


def developed_strip(
    turn: RateFunction,
    speed: RateFunction,
    span: tuple[float, float],
    height: float,
    side: str = "outside",
    name: str = "stringer",
    samples: int = 2001,
    breaks: np.ndarray | None = None,
    turn_floor: float = 0.0,
) -> FlatPattern:
    """The development of the normal strip X + v n, v from 0 to +-``height`` (``side``), along a
    curvature line X(s), s in ``span``, with speed(s) = |X_s| = sqrt(G) and turn(s) = kappa_n
    sqrt(G) (kappa_n = N / G, outward normal): the base edge is the plane curve turning by
    +-turn per unit s (alpha' = +-turn, gamma' = speed (cos alpha, sin alpha)), the top edge its
    offset by ``height`` to the left (the rulings develop to the curve's normals). ``breaks``
    (the span's ends and any kinks of turn or speed) start the Chebyshev panels; ``turn_floor``:
    the least turn the fit of turn is resolved against (a nearly straight line's turn is then
    resolved in radians over the span, not against its own round-off)."""
    sign = _side_sign(side)
    h = float(height)
    s0, s1 = span
    edges = np.array([s0, s1]) if breaks is None else np.asarray(breaks, dtype=float)

    def fit(f: RateFunction, label: str, floor: float = 0.0) -> PiecewiseChebyshev:
        return PiecewiseChebyshev.fit(f, s0, s1, name=label, breaks=edges, floor=floor).antiderivative()

    alpha = fit(lambda s: sign * turn(s), "the stringer's normal curvature", turn_floor)
    x = fit(lambda s: speed(s) * np.cos(alpha(s)), "flat x")
    y = fit(lambda s: speed(s) * np.sin(alpha(s)), "flat y")
    s = np.linspace(s0, s1, samples)
    base_curve = np.stack([x(s), y(s)], axis=1)
    normal = np.stack([-np.sin(alpha(s)), np.cos(alpha(s))], axis=1)  # the ruling's image, left of the curve
    top_curve = base_curve + h * normal
    integral = lambda f, label: float(fit(f, label)(s1))  # noqa: E731
    return FlatPattern(
        name,
        "stringer",
        np.concatenate([base_curve, top_curve[::-1]]),
        base_length=integral(speed, "base"),
        top_length=integral(lambda s: np.abs(speed(s) - sign * h * turn(s)), "top"),
        area=integral(lambda s: h * speed(s) - sign * h * h / 2 * turn(s), "area"),
    )


def canal_stringer_rates(canal: CurvatureLineSurface, chi0: float) -> tuple[RateFunction, RateFunction]:
    """(turn, speed) along the canal stringer ``chi0`` (radians): turn = kappa_n sqrt(G) =
    r'' / q + k1 cos chi + k2 sin chi and speed = sqrt(G) = q - r turn (module docstring)."""
    law, axis = canal.radius_law, canal.axis

    def turn(s: np.ndarray) -> np.ndarray:
        chi = canal.stringer_angle(chi0, s)
        k1, k2 = axis.normal_development(s)
        dr = law.dr(s)
        return law.ddr(s) / np.sqrt(1.0 - dr * dr) + (k1 * np.cos(chi) + k2 * np.sin(chi))

    def speed(s: np.ndarray) -> np.ndarray:
        dr = law.dr(s)
        return np.sqrt(1.0 - dr * dr) - law.r(s) * turn(s)

    return turn, speed


def stringer_rates(base: CurvatureLineSurface, theta_deg: float) -> tuple[RateFunction, RateFunction, np.ndarray]:
    """(turn, speed, breaks) along the stringer at ``theta_deg`` on ``base`` (module
    docstring): one formula, :func:`canal_stringer_rates`, which on a tube (r' = r'' = 0, chi = u)
    is turn = kappa_u = k1 cos u + k2 sin u and speed = 1 - R kappa_u, the same operations bit
    for bit. ``breaks``: the span's ends and the s where turn or speed may kink (an axis'
    joints, a radius law's knots: :meth:`~tubecad.surface.CurvatureLineSurface.s_breaks`)."""
    turn, speed = canal_stringer_rates(base, math.radians(theta_deg))
    return turn, speed, np.asarray(base.s_breaks(), dtype=float)


def stringer_flat_pattern(
    base: CurvatureLineSurface,
    theta_deg: float,
    height: float,
    side: str = "outside",
    name: str = "stringer",
    samples: int = 2001,
    span: tuple[float, float] | None = None,
) -> FlatPattern:
    """The developed web of height ``height`` along the stringer at ``theta_deg`` on ``base``:
    on a tube the stringer's angle u, on a canal surface chi0 (its angle at the span's start);
    over ``span`` (a piece of the stringer; default ``base.span``)."""
    s0, s1 = base.span if span is None else (float(span[0]), float(span[1]))
    if not base.span[0] <= s0 < s1 <= base.span[1]:
        raise ParameterError(f"span must lie in [{base.span[0]:g}, {base.span[1]:g}] with start < end, got {span}")
    turn, speed, breaks = stringer_rates(base, theta_deg)
    breaks = np.unique(np.concatenate([[s0, s1], breaks[(breaks > s0) & (breaks < s1)]]))
    return developed_strip(turn, speed, (s0, s1), height, side, name, samples, breaks)


def ring_flat_pattern(
    radius: float, height: float, side: str = "outside", name: str = "ring", samples: int = 721, q: float = 1.0
) -> FlatPattern:
    """The flat web of a ring frame on a wall of (sphere) radius ``radius``: for ``q`` = 1 (a
    tube, or a canal ring where r' = 0) the annulus of radii R and R +- h; for q < 1 (a canal
    ring, q = sqrt(1 - r'^2)) the annular sector of those radii and angle 2 pi q, the
    development of the cone of the normals along the characteristic circle."""
    sign = _side_sign(side)
    if not 0.0 < q <= 1.0:
        raise ParameterError(f"q must lie in (0, 1], got {q!r}")
    r_in, r_out = (radius, radius + height) if sign > 0 else (radius - height, radius)
    base, top = (r_in, r_out) if sign > 0 else (r_out, r_in)
    area = q * math.pi * (r_out**2 - r_in**2)
    if q == 1.0:
        a = np.linspace(0.0, 2 * math.pi, samples, endpoint=False)
        circle = np.stack([np.cos(a), np.sin(a)], axis=1)
        return FlatPattern(
            name, "ring", r_out * circle, 2 * math.pi * base, 2 * math.pi * top, area, hole=r_in * circle
        )
    a = 0.5 * math.pi + math.pi * q * np.linspace(-1.0, 1.0, samples)
    arc = np.stack([np.cos(a), np.sin(a)], axis=1)
    outline = np.concatenate([r_out * arc, r_in * arc[::-1]])  # outer arc, radial edge, inner arc, radial edge
    return FlatPattern(
        name,
        "ring",
        outline,
        2 * math.pi * q * base,
        2 * math.pi * q * top,
        area,
        sector=(r_in, r_out, 2 * math.pi * q),
    )


def canal_ring_flat_pattern(
    canal: CurvatureLineSurface, s: float, height: float, side: str = "outside", name: str = "ring", samples: int = 721
) -> FlatPattern:
    """The flat web of the ring frame on ``canal``'s characteristic circle at ``s``: the annular
    sector of (slant) radii r(s) and r(s) +- h and angle 2 pi q(s)."""
    s = float(canal.inside(s))
    law = canal.radius_law
    r, dr = float(law.r(s)), float(law.dr(s))
    if side == "inside" and not height < r:
        raise ParameterError(f"height must be < r(s) = {r:g} for a ring web inside, got {height!r}")
    return ring_flat_pattern(r, height, side, name, samples, q=math.sqrt(1.0 - dr * dr))


def ring_web_flat_pattern(
    base: CurvatureLineSurface, s: float, height: float, side: str = "outside", name: str = "ring"
) -> FlatPattern:
    """The flat web of the ring frame at ``s`` on ``base``, the wall surface it stands on: an
    annulus on a tube, an annular sector on a canal surface."""
    if base.constant_radius:  # q = 1: the annulus of radii R and R +- h
        return ring_flat_pattern(base.radius_law.constant_value, height, side, name)
    return canal_ring_flat_pattern(base, s, height, side, name)


def _shifted(shift: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """p -> p + ``shift`` (a pattern's place on the sheet)."""
    return lambda p: p + shift


def polygon_area(points: np.ndarray) -> float:
    """Shoelace area of a closed polygon."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def write_dxf(
    patterns: list[FlatPattern], path: str | Path, gap: float | None = None, length_unit: str = DEFAULT_LENGTH_UNIT
) -> Path:
    """All patterns side by side in one DXF, one layer per pattern, outlines as closed
    polylines (full rings: two circles; a canal ring's sector: one closed polyline whose arcs
    are exact, as bulges). The coordinates are in ``length_unit`` (the spec's
    [units] length), which the file states ($INSUNITS, and $MEASUREMENT: imperial for in and
    ft, metric otherwise); ``gap`` between patterns: default 10 mm in that unit."""
    drawing = Drawing(length_unit)
    gap = 10.0 / drawing.unit.mm if gap is None else gap
    x_offset = 0.0
    for pattern in patterns:
        lo = pattern.outline.min(axis=0)
        shift = np.array([x_offset - lo[0], -lo[1]])
        drawing.layer(pattern.name)
        if pattern.sector is not None:  # a canal ring: the sector's arcs exact (bulges)
            drawing.sector(*pattern.sector, pattern.name, place=_shifted(shift))
        elif pattern.hole is not None:  # a full annulus: two circles
            r_out = float(np.linalg.norm(pattern.outline[0]))
            centre = (x_offset + r_out, r_out)
            drawing.circle(centre, r_out, pattern.name)
            drawing.circle(centre, float(np.linalg.norm(pattern.hole[0])), pattern.name)
        else:
            drawing.polyline(pattern.outline + shift, pattern.name)
        x_offset += float(np.ptp(pattern.outline[:, 0])) + gap
    return drawing.save(path)


def write_picture(pattern: FlatPattern, folder: str | Path) -> list[Path]:
    """``name``.svg and ``name``.png of one pattern, with its measures in the title."""
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone
    from matplotlib.patches import Polygon

    fig = Figure(figsize=(10, 6))
    ax = fig.subplots()
    ax.add_patch(Polygon(pattern.outline, closed=True, facecolor="#c9d6ea", edgecolor="#10203a", linewidth=0.8))
    if pattern.hole is not None:
        ax.add_patch(Polygon(pattern.hole, closed=True, facecolor="white", edgecolor="#10203a", linewidth=0.8))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(
        f"{pattern.name}: flat pattern of the web, area {pattern.area:.6g}, edges "
        f"{pattern.base_length:.6g} (on the wall) and {pattern.top_length:.6g}",
        fontsize=9,
    )
    return save_figure(fig, folder, pattern.name, ("svg", "png"))
