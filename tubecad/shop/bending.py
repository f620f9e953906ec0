"""Bending tables and inverse bending curves (issue 13).

Profiles (ring frames, stringers, flanges) are bent from straight bar and checked against a
table: per station, the arc length sigma along the piece and the curve's offset from the
straight chord between its ends. In the chord frame (origin P(0), x along the chord
P(L) - P(0), y towards the curve's farthest point from the chord, z = x cross y) a station
sigma_i has

    chord_x = (P(sigma_i) - P(0)) . x,   offset_y = (P(sigma_i) - P(0)) . y,   offset_z = ... . z

(offset_z = 0 for a planar curve, e.g. a ring arc). The inverse bending curve is -offset_y:
marked on the straight bar at the stations, it becomes straight when the bar is bent right.

Bend back: the table alone (sigma_i, chord_x, offset_y, offset_z) is interpolated by a cubic
spline in sigma (scipy's not-a-knot CubicSpline); its bend-back error is the larger of the
largest distance |spline(sigma) - P(sigma)| (same sigma, densely sampled) and |Int |spline'|
dsigma - L|: how far a piece bent to the table can be from the model.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from tubecad.core.atomic import save_figure, write_text
from tubecad.core.errors import ParameterError
from tubecad.core.units import length_unit as length_unit_of
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.shop.flanges import Surface, offset_surface, on_span, span_breaks

Curve = Callable[[np.ndarray], np.ndarray]

#: the bend-back check samples the curve at least this densely (and 16 per station interval)
DENSE_SAMPLES = 4097
#: spacing None: station intervals tried, fewest first (spacing = length / n); the last is the floor
INTERVALS = (4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512, 768, 1024)
#: Newton steps inverting the arc length (quadratic: round-off after 4-5)
NEWTON_STEPS = 12


@dataclass(frozen=True)
class BendingTable:
    """One piece's bending table (module docstring), stations in arc length from its start."""

    name: str  # e.g. stringer_02_a, ring_03_flange
    line: str  # which curve: "web base on the wall", "flange centre line", "ring base circle", ...
    length: float  # arc length of the piece
    arc_length: np.ndarray  # (n,) stations
    chord_x: np.ndarray  # (n,) along the chord from the start
    offset_y: np.ndarray  # (n,) from the chord, in the plane of the chord and the farthest point
    offset_z: np.ndarray  # (n,) out of that plane
    bend_back_error: float  # measured: see the module docstring
    spacing: float = math.nan  # the station spacing asked for or chosen (the last interval may be shorter)

    @property
    def inverse_y(self) -> np.ndarray:
        """The inverse bending curve: -offset_y at each station."""
        return -self.offset_y

    @property
    def max_offset(self) -> float:
        """The largest |offset_y| at the stations (the bar's sagitta)."""
        return float(np.abs(self.offset_y).max())


def chord_frame(position: Curve, length: float, name: str) -> tuple[np.ndarray, np.ndarray]:
    """(origin P(0), rows x, y, z): x along the chord, y towards the curve's farthest point from
    the chord line (any normal to x for a straight piece). The farthest of DENSE_SAMPLES points
    is refined to the root of d/dsigma |p|^2 / 2 = p . p' (p the part of P - P(0) normal to x,
    p' by central differences), so the plane does not depend on the sampling. A closed curve
    has no chord: refused."""
    ends = np.asarray(position(np.array([0.0, length])), dtype=float)
    chord = ends[1] - ends[0]
    span = float(np.linalg.norm(chord))
    if not span > 1e-9 * length:
        raise ParameterError(
            f"length: {name} ends where it starts ({span:.3g} apart): a closed curve has no chord; "
            "split it into arcs of at most 180 deg"
        )
    x = chord / span

    def perp(sigma: np.ndarray) -> np.ndarray:
        d = np.asarray(position(np.clip(sigma, 0.0, length)), dtype=float) - ends[0]
        return d - np.outer(d @ x, x)

    sigma = np.linspace(0.0, length, DENSE_SAMPLES)
    far2 = np.einsum("ij,ij->i", *(2 * [perp(sigma)]))
    i = int(np.argmax(far2))
    if far2[i] <= (1e-12 * length) ** 2:  # a straight piece: any plane through the chord
        far = np.cross(x, np.eye(3)[np.argmin(np.abs(x))])
    else:
        h = 1e-5 * length

        def slope(t: float) -> float:
            lo, hi = max(t - h, 0.0), min(t + h, length)
            p = perp(np.array([t, lo, hi]))
            return float(p[0] @ (p[2] - p[1])) / (hi - lo)

        a, b = sigma[max(i - 1, 0)], sigma[min(i + 1, DENSE_SAMPLES - 1)]
        at = brentq(slope, a, b, xtol=1e-15 * length) if slope(a) > 0.0 > slope(b) else sigma[i]
        far = perp(np.array([at]))[0]
    y = far / np.linalg.norm(far)
    return ends[0], np.stack([x, y, np.cross(x, y)])


def _stations(length: float, spacing: float) -> np.ndarray:
    """0, spacing, 2 spacing, ... and the end (a station within 1e-9 L of it dropped)."""
    inner = np.arange(1, math.ceil(length / spacing) + 1) * spacing
    return np.concatenate([[0.0], inner[inner < length * (1 - 1e-9)], [length]])


def bend_back_error(
    arc_length: np.ndarray, local: np.ndarray, exact: Callable[[np.ndarray], np.ndarray], length: float
) -> float:
    """max(largest |spline(sigma) - exact(sigma)|, |spline length - length|), the spline the
    not-a-knot cubic through the stations ``local`` (n, 3) at ``arc_length``; ``exact``
    gives the curve in the same (chord) frame."""
    spline = CubicSpline(arc_length, local, axis=0)
    sigma = np.linspace(0.0, length, max(DENSE_SAMPLES, 16 * (len(arc_length) - 1) + 1))
    distance = float(np.linalg.norm(spline(sigma) - exact(sigma), axis=1).max())
    nodes, weights = np.polynomial.legendre.leggauss(8)
    mid, half = 0.5 * (arc_length[1:] + arc_length[:-1]), 0.5 * np.diff(arc_length)
    speed = np.linalg.norm(spline(mid[:, None] + half[:, None] * nodes, 1), axis=-1)
    return max(distance, abs(float((speed * weights).sum(axis=1) @ half) - length))


def bending_table(
    position: Curve, length: float, name: str, line: str, spacing: float | None = None, max_error: float = 0.1
) -> BendingTable:
    """The bending table of the curve ``position``(sigma) -> (n, 3), sigma its exact arc
    length in [0, ``length``], with stations every ``spacing`` from the start and at the end.
    ``spacing`` None: the largest of length / n, n in INTERVALS, whose bend-back error is
    <= ``max_error`` (model units: the caller converts 0.1 mm). Refused (ParameterError naming
    the key) when ``spacing`` <= 0, ``max_error`` <= 0, or the error exceeds ``max_error`` at
    the given spacing or at the floor length / INTERVALS[-1]."""
    length = float(length)
    if not (math.isfinite(length) and length > 0.0):
        raise ParameterError(f"length: {name} must have a positive length, got {length!r}")
    if not (isinstance(max_error, (int, float)) and max_error > 0.0):
        raise ParameterError(f"max_error must be > 0, got {max_error!r}")
    if spacing is not None and not (isinstance(spacing, (int, float)) and spacing > 0.0):
        raise ParameterError(f"spacing must be > 0 (or None to choose one), got {spacing!r}")
    origin, frame = chord_frame(position, length, name)

    def local(sigma: np.ndarray) -> np.ndarray:
        return (np.asarray(position(np.clip(sigma, 0.0, length)), dtype=float) - origin) @ frame.T

    def table(step: float) -> BendingTable:
        arc = _stations(length, step)
        xyz = local(arc)
        xyz[0], xyz[-1, 1:] = 0.0, 0.0  # the chord's ends, exactly
        error = bend_back_error(arc, xyz, local, length)
        return BendingTable(name, line, length, arc, xyz[:, 0], xyz[:, 1], xyz[:, 2], error, float(step))

    if spacing is not None:
        out = table(float(spacing))
        if out.bend_back_error > max_error:
            raise ParameterError(
                f"spacing: {name}: the bend-back error {out.bend_back_error:.3g} exceeds max_error "
                f"{max_error:g} at spacing {spacing:g}; use a smaller spacing (or none to choose "
                "one)"
            )
        return out
    for n in INTERVALS:
        out = table(length / n)
        if out.bend_back_error <= max_error:
            return out
    raise ParameterError(
        f"max_error: {name}: the bend-back error is still {out.bend_back_error:.3g} > max_error "
        f"{max_error:g} with {INTERVALS[-1]} intervals (spacing {length / INTERVALS[-1]:.6g}); "
        "raise max_error"
    )


def stringer_line(
    base: Surface, theta_deg: float, level: float = 0.0, span: tuple[float, float] | None = None
) -> tuple[Curve, float]:
    """The stringer at ``theta_deg`` (u on a tube, chi0 at the wall's start on a canal surface)
    on the offset surface at ``level`` (0: the web's base on the wall; a flange's centre line:
    :func:`.flanges.flange_level`) over ``span``, by arc length: (position(sigma), length).
    sigma(s) = Int |S_s| ds is a Chebyshev series (round-off accurate); it is inverted by Newton
    from a table, to round-off, and the points are ``base.offset(level).points``."""
    piece, u = on_span(base, math.radians(theta_deg), span)
    surface = offset_surface(piece, float(level), key="level")
    s0, s1 = piece.span

    def speed(s: np.ndarray) -> np.ndarray:
        flat = np.asarray(s, dtype=float).ravel()
        return np.linalg.norm(surface.derivatives(np.full(flat.shape, u), flat).S_s, axis=-1).reshape(np.shape(s))

    rate = PiecewiseChebyshev.fit(speed, s0, s1, name="the stringer's speed", breaks=span_breaks(piece))
    sigma_of = rate.antiderivative()
    length = float(sigma_of(s1))
    grid = np.linspace(s0, s1, 1025)
    table = sigma_of(grid)

    def s_of(sigma: np.ndarray) -> np.ndarray:
        sigma = np.clip(np.asarray(sigma, dtype=float), 0.0, length)
        s = np.interp(sigma, table, grid)
        for _ in range(NEWTON_STEPS):
            step = (sigma_of(s) - sigma) / rate(s)
            s = np.clip(s - step, s0, s1)
            if np.abs(step).max(initial=0.0) <= 4e-16 * (abs(s0) + abs(s1)):
                break
        return s

    def position(sigma: np.ndarray) -> np.ndarray:
        s = s_of(sigma)
        return surface.points(np.full(s.shape, u), s)

    return position, length


def ring_arcs(
    base: Surface,
    s: float,
    level: float = 0.0,
    pieces: int | None = None,
    start_deg: float = 0.0,
    span_deg: float = 360.0,
) -> list[tuple[Curve, float]]:
    """The ring circle at ``s`` on the offset surface at ``level`` (a tube's circle of radius
    R + level; on a canal surface the characteristic circle of r + level, centre c - (r + d) r' t,
    radius (r + d) q), from ``start_deg`` from r1(s) over ``span_deg`` (all round, or the arc a
    ring cut at an opening keeps), split into ``pieces`` equal arcs (default: the fewest of at
    most 180 deg each: a full circle has no chord): each as (position(sigma), length),
    position = centre + a (cos(phi_j + sigma / a) r1 + sin(...) r2)."""
    if not 0.0 < span_deg <= 360.0:
        raise ParameterError(f"span_deg must be in (0, 360] degrees, got {span_deg!r}")
    fewest = max(1, math.ceil(span_deg / 180.0 - 1e-12))
    count = fewest if pieces is None else pieces
    if not (isinstance(count, int) and count >= fewest):
        raise ParameterError(
            f"pieces must be an integer >= {fewest} (arcs of at most 180 deg; a full circle has no chord), "
            f"got {pieces!r}"
        )
    surface = offset_surface(base, float(level), key="level")
    at = np.array([float(s)])
    _, r1, r2 = base.axis.rotation_minimising_frame(base.axis.inside(at))
    centre, radius, _ = surface.circle(at)  # a tube's: the axis point, R + level
    centre, a = centre[0], float(radius[0])
    step = math.radians(span_deg) / count

    def arc(phi0: float) -> Curve:
        def position(sigma: np.ndarray) -> np.ndarray:
            phi = phi0 + np.asarray(sigma, dtype=float)[:, None] / a
            return centre + a * (np.cos(phi) * r1[0] + np.sin(phi) * r2[0])

        return position

    start = math.radians(start_deg)
    return [(arc(start + j * step), a * step) for j in range(count)]


COLUMNS = ("name", "line", "station", "arc_length", "chord_x", "offset_y", "offset_z", "inverse_y")


def write_bending_csv(tables: list[BendingTable], path: str | Path, length_unit: str = "mm") -> Path:
    """One row per station (COLUMNS; floats as repr, so they read back exactly) after a
    comment line stating the length unit; written atomically."""
    unit = length_unit_of(length_unit).name
    out = io.StringIO()
    out.write(f"# bending tables, lengths in {unit}; inverse_y = -offset_y (mark on the straight bar)\n")
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(COLUMNS)
    for t in tables:
        for i, row in enumerate(zip(t.arc_length, t.chord_x, t.offset_y, t.offset_z, t.inverse_y)):
            writer.writerow([t.name, t.line, i, *(repr(float(v)) for v in row)])
    return write_text(path, out.getvalue())


#: panels in one picture
MAX_PANELS = 12


def write_bending_picture(tables: list[BendingTable], folder: str | Path, stem: str = "bending") -> list[Path]:
    """``stem``.png and ``stem``.svg: one panel per table (the first MAX_PANELS, named in the
    title) with the offset curve and the inverse curve over arc length (the cubic through the
    stations, which are marked), offset_z where it is not 0, and the bend-back error."""
    if not tables:
        raise ParameterError("tables: nothing to draw")
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone

    shown = tables[:MAX_PANELS]
    cols = min(3, len(shown))
    rows = math.ceil(len(shown) / cols)
    fig = Figure(figsize=(4.6 * cols, 3.0 * rows + 0.6))
    axes = fig.subplots(rows, cols, squeeze=False)
    for ax, t in zip(axes.ravel(), shown):
        sigma = np.linspace(0.0, t.length, 400)
        curves = [(t.offset_y, "offset y", "#10203a", "o"), (t.inverse_y, "inverse", "#c0392b", "s")]
        if np.abs(t.offset_z).max() > 1e-9 * t.length:
            curves.append((t.offset_z, "offset z", "#7f8c8d", "^"))
        for values, label, colour, marker in curves:
            smooth = CubicSpline(t.arc_length, values)(sigma) if len(t.arc_length) > 1 else sigma * 0
            ax.plot(sigma, smooth, color=colour, linewidth=1.0, label=label)
            ax.plot(t.arc_length, values, marker, color=colour, markersize=3)
        ax.axhline(0.0, color="#999999", linewidth=0.5)
        ax.set_title(
            f"{t.name} ({t.line}), {len(t.arc_length)} stations\nmax bend-back error {t.bend_back_error:.3g}",
            fontsize=8,
        )
        ax.set_xlabel("arc length", fontsize=7)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
    for ax in axes.ravel()[len(shown) :]:
        ax.set_visible(False)
    which = f"all {len(tables)}" if len(shown) == len(tables) else f"the first {len(shown)} of {len(tables)}"
    fig.suptitle(
        f"bending tables ({which} shown: {shown[0].name} .. {shown[-1].name}): offset from the chord and "
        "the inverse bending curve",
        fontsize=9,
    )
    fig.tight_layout()
    return save_figure(fig, folder, stem, ("png", "svg"))
