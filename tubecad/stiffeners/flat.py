"""Flat patterns of stiffener webs (issue 4): webs cut from flat plate.

Along a line of curvature the surface normals form a developable strip (Rodrigues:
dN = -kappa_n dX), so a web standing along the normal develops without stretching:
- a stringer's web develops to the region between the plane curve whose curvature is
  kappa_g = +-kappa_n (+ outside, - inside) and its offset by the web height h. With
  phi = theta - Int sigma ds (docs/MATH.md section 2) and s the axis arc length:
      d alpha / ds = +-k cos phi,  d gamma / ds = (1 - R k cos phi) (cos alpha, sin alpha),
  the base edge has length Int (1 - R k cos phi) ds, the top edge is the same curvature
  line on the tube of radius R +- h: length Int |1 - (R +- h) k cos phi| ds, and the area is
  Int [h (1 - R k cos phi) -+ h^2 / 2 k cos phi] ds;
- a ring frame's web is an annulus of radii R and R +- h.
The quadratures use the adaptive Chebyshev series of :mod:`tubecad.curves.chebyshev`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..curves.chebyshev import PiecewiseChebyshev
from ..export.atomic import atomic_path, save_figure
from ..surface import CurvatureLineTube
from ..units import DEFAULT_LENGTH_UNIT, length_unit as length_unit_of


@dataclass(frozen=True)
class FlatPattern:
    """A web's flat outline (closed polygon, model units) and its exact measures."""

    name: str
    kind: str  # ring | stringer
    outline: np.ndarray  # (n, 2); for a ring the outer circle, the hole is ``hole``
    base_length: float
    top_length: float
    area: float
    hole: np.ndarray | None = None


def stringer_flat_pattern(base: CurvatureLineTube, theta_deg: float, height: float, side: str = "outside",
                          name: str = "stringer", samples: int = 2001) -> FlatPattern:  # fmt: skip
    """The developed web of height ``height`` along the stringer at ``theta_deg`` on ``base``."""
    sign = 1.0 if side == "outside" else -1.0
    axis, R, h = base.axis, base.radius, height
    s0, s1 = axis.span
    theta = math.radians(theta_deg)

    def kc(s: np.ndarray) -> np.ndarray:  # kappa_u = k1 cos theta + k2 sin theta (= k cos phi)
        return base.normal_curvature(theta, s)

    alpha = PiecewiseChebyshev.fit(lambda s: sign * kc(s), s0, s1, name="k cos phi").antiderivative()
    speed = lambda s: 1.0 - R * kc(s)  # noqa: E731
    x = PiecewiseChebyshev.fit(lambda s: speed(s) * np.cos(alpha(s)), s0, s1, name="flat x").antiderivative()
    y = PiecewiseChebyshev.fit(lambda s: speed(s) * np.sin(alpha(s)), s0, s1, name="flat y").antiderivative()
    s = np.linspace(s0, s1, samples)
    base_curve = np.stack([x(s), y(s)], axis=1)
    normal = np.stack([-np.sin(alpha(s)), np.cos(alpha(s))], axis=1)  # the ruling's image, left of the curve
    top_curve = base_curve + h * normal
    integral = lambda f, label: float(PiecewiseChebyshev.fit(f, s0, s1, name=label).antiderivative()(s1))  # noqa: E731
    return FlatPattern(
        name, "stringer", np.concatenate([base_curve, top_curve[::-1]]),
        base_length=integral(speed, "base"),
        top_length=integral(lambda s: np.abs(1.0 - (R + sign * h) * kc(s)), "top"),
        area=integral(lambda s: h * speed(s) - sign * h * h / 2 * kc(s), "area"),
    )  # fmt: skip


def ring_flat_pattern(radius: float, height: float, side: str = "outside", name: str = "ring",
                      samples: int = 721) -> FlatPattern:  # fmt: skip
    """The annulus of a ring frame's web on a wall surface of ``radius``."""
    r_in, r_out = (radius, radius + height) if side == "outside" else (radius - height, radius)
    a = np.linspace(0.0, 2 * math.pi, samples, endpoint=False)
    circle = np.stack([np.cos(a), np.sin(a)], axis=1)
    base, top = (r_in, r_out) if side == "outside" else (r_out, r_in)
    return FlatPattern(name, "ring", r_out * circle, 2 * math.pi * base, 2 * math.pi * top,
                       math.pi * (r_out**2 - r_in**2), hole=r_in * circle)  # fmt: skip


def polygon_area(points: np.ndarray) -> float:
    """Shoelace area of a closed polygon."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def write_dxf(patterns: list[FlatPattern], path: str | Path, gap: float | None = None,
              length_unit: str = DEFAULT_LENGTH_UNIT) -> Path:  # fmt: skip
    """All patterns side by side in one DXF, one layer per pattern, outlines as closed
    polylines (rings: two circles). The coordinates are in ``length_unit`` (the spec's
    [units] length), which the file states ($INSUNITS, and $MEASUREMENT: imperial for in and
    ft, metric otherwise); ``gap`` between patterns: default 10 mm in that unit."""
    import ezdxf

    unit = length_unit_of(length_unit)
    gap = 10.0 / unit.mm if gap is None else gap
    doc = ezdxf.new(units=unit.dxf)  # sets $INSUNITS and $MEASUREMENT
    space = doc.modelspace()
    x_offset = 0.0
    for pattern in patterns:
        lo = pattern.outline.min(axis=0)
        shift = np.array([x_offset - lo[0], -lo[1]])
        doc.layers.add(pattern.name)
        if pattern.kind == "ring":
            r_out = float(np.linalg.norm(pattern.outline[0]))
            centre = (x_offset + r_out, r_out)
            space.add_circle(centre, r_out, dxfattribs={"layer": pattern.name})
            space.add_circle(centre, float(np.linalg.norm(pattern.hole[0])), dxfattribs={"layer": pattern.name})
        else:
            space.add_lwpolyline((pattern.outline + shift).tolist(), close=True, dxfattribs={"layer": pattern.name})
        x_offset += float(np.ptp(pattern.outline[:, 0])) + gap
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return Path(path)


def write_picture(pattern: FlatPattern, folder: str | Path) -> list[Path]:
    """``name``.svg and ``name``.png of one pattern, with its measures in the title."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    fig, ax = plt.subplots(figsize=(10, 6))
    ax.add_patch(Polygon(pattern.outline, closed=True, facecolor="#c9d6ea", edgecolor="#10203a", linewidth=0.8))
    if pattern.hole is not None:
        ax.add_patch(Polygon(pattern.hole, closed=True, facecolor="white", edgecolor="#10203a", linewidth=0.8))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(f"{pattern.name}: flat pattern of the web, area {pattern.area:.6g}, edges "
                 f"{pattern.base_length:.6g} (on the wall) and {pattern.top_length:.6g}", fontsize=9)  # fmt: skip
    return save_figure(fig, folder, pattern.name, ("svg", "png"))
