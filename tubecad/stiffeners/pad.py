"""A reinforcement pad: a plate on the main wall round a branch, bounded by lines of curvature
(issue 25; here beside the panels it is made as, above :mod:`tubecad.junctions`; on a main
with a radius law, issue 43).

The pad lies on the main tube's outer wall surface X(u, s) (radius R_o) and reaches ``width``
beyond the branch's outer saddle every way: it is the panel of the wall between the radii R_o
and R_o + thickness over the rings s_a = min s_A - width, s_b = max s_A + width and the
stringers u_a = min u_A - width / R_o, u_b = max u_A + width / R_o (the saddle's (u_A, s_A) on
the main, :mod:`~tubecad.junctions.saddle`), with the branch's outer tube cut out of it. Its
four edges are curvature lines of the main wall (two rings, two stringers), so it develops
like any panel of the wall: exactly (strain 0) where the main axis is straight. On a canal
surface (a radius law) R_o is the smallest outer radius over the pad's rings, and the plate is
the canal wall's panel between the two stringers (:func:`~tubecad.stiffeners.panels.split_into_panels`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import build123d as bd
import numpy as np

from tubecad.brep.layout import NetLayout
from tubecad.brep.properties import is_valid
from tubecad.brep.section_edges import refine_section_edges
from tubecad.brep.solids import build_tube_solid, build_wall_solid
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE
from tubecad.junctions.saddle import SaddleCurve
from tubecad.stiffeners.panels import panel, split_into_panels
from tubecad.surface.protocol import CurvatureLineSurface


@dataclass(frozen=True)
class Pad:
    """The pad's ``solid`` (the branch's hole cut out), the rings ``s_range`` and stringer
    angles ``angles_deg`` that bound it on ``surface`` (the main's outer wall surface), its
    ``thickness`` and ``width`` beyond the saddle."""

    solid: bd.Solid
    surface: CurvatureLineSurface
    s_range: tuple[float, float]
    angles_deg: tuple[float, float]
    thickness: float
    width: float

    @property
    def diameter(self) -> float:
        """D_p of the area-replacement rule: the pad's extent along the main axis, s_b - s_a."""
        return self.s_range[1] - self.s_range[0]


def reinforcement_pad(
    outer: CurvatureLineSurface,
    branch_outer: CurvatureLineSurface,
    saddle: SaddleCurve,
    thickness: float,
    width: float,
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    *,
    key: str = "pad",
) -> Pad:
    """The pad on ``outer`` (the main wall's outer surface) round the saddle ``saddle`` where
    ``branch_outer`` leaves it (see the module). A ParameterError names ``key.thickness`` or
    ``key.width`` where the pad would reach past the main tube's ends or round it, or where
    the main has a radius law (a pad of a canal wall is not made yet)."""
    if not (thickness > 0 and math.isfinite(thickness)):
        raise ParameterError(f"{key}.thickness must be > 0, got {thickness!r:.40}", key=f"{key}.thickness")
    (s_a, s_b), (u_a, u_b) = pad_bounds(outer, saddle, width, key=key)
    piece = outer.restricted((s_a, s_b))
    if outer.constant_radius:  # the fast path: the exact section's patches between the stringers
        radius = outer.radius_law.constant_value
        layout = NetLayout.explicit(piece, [s_a, s_b], [u_a % 360.0])
        wall = build_wall_solid(piece, thickness, "outside", layout, tolerance)
        plate = panel(wall, piece.axis, radius, radius + thickness, u_a, u_b, "pad").solid
    else:  # a radius law: the canal wall's panel between the two stringers (its own faces)
        layout = NetLayout.explicit(piece, [s_a, s_b], [u_a % 360.0, u_b % 360.0])
        wall = build_wall_solid(piece, thickness, "outside", layout, tolerance)
        start = round(u_a % 360.0, 12)  # the bay from u_a counter-clockwise to u_b
        plate = next(p for p in split_into_panels(wall, [0, 1]) if abs(p.angles_deg[0] - start) < 1e-9).solid
    # two stringers: each face of the hole a C1 half turn (one stringer leaves a C0 knot inside
    # its face, which OCCT's pre-boolean check reports on the pad's hole)
    hole = build_tube_solid(branch_outer, NetLayout.equal(branch_outer, 2, 2), tolerance).shape
    cut, _, _ = refine_section_edges(plate.cut(hole).wrapped)
    solids = bd.Shape.cast(cut).solids()
    if len(solids) != 1 or not is_valid(solids[0].wrapped):
        raise ParameterError(f"{key}: OCCT's cut of the branch from the pad gave {len(solids)} solids", key=key)
    return Pad(solids[0], outer, (s_a, s_b), (u_a, u_b), thickness, width)


def pad_bounds(
    outer: CurvatureLineSurface, saddle: SaddleCurve, width: float, *, key: str = "pad"
) -> tuple[tuple[float, float], tuple[float, float]]:
    """((s_a, s_b), (u_a, u_b) in degrees): the rings and stringers that bound the pad
    ``width`` beyond ``saddle`` on ``outer`` (see the module); refused as
    :func:`reinforcement_pad` says."""
    if not (width > 0 and math.isfinite(width)):
        raise ParameterError(f"{key}.width must be > 0, got {width!r:.40}", key=f"{key}.width")
    s0, s1 = outer.span
    (s_lo, s_hi), (u_lo, u_hi) = saddle.extent(saddle.main_s), saddle.extent(saddle.main_u)
    s_a, s_b = s_lo - width, s_hi + width
    # width / r beyond the saddle round the axis: at the smallest radius over the pad's rings (a
    # radius law), so that it is at least width everywhere
    inside = np.linspace(max(s_a, s0), min(s_b, s1), 257)
    radius = float(outer.radius_law.r(inside).min())
    u_a, u_b = math.degrees(u_lo - width / radius), math.degrees(u_hi + width / radius)
    if not (s0 < s_a and s_b < s1):
        raise ParameterError(
            f"{key}.width: the pad reaches s = {s_a:.6g} .. {s_b:.6g}, past the main tube's span ({s0:g}, {s1:g})",
            key=f"{key}.width",
        )
    if u_b - u_a >= 360.0:
        widest = radius * (math.pi - 0.5 * (u_hi - u_lo))
        raise ParameterError(
            f"{key}.width: the pad would reach all round the main tube ({u_b - u_a:.4g} deg); "
            f"width must be < {widest:.6g} here",
            key=f"{key}.width",
        )
    return (s_a, s_b), (u_a, u_b)


def pad_name(k: int, branches: int) -> str:
    """The pad of branch ``k`` among ``branches``: ``pad`` with one branch, ``pad_k`` with several."""
    return "pad" if branches == 1 else f"pad_{k}"


def pad_outline(pad: Pad, points: int = 65) -> np.ndarray:
    """The pad's outer boundary on its surface, (4 (points - 1), 3): ring s_a, stringer u_b,
    ring s_b, stringer u_a (before the hole)."""
    u = np.radians(np.linspace(*pad.angles_deg, points))
    s = np.linspace(*pad.s_range, points)
    sides = [(u, np.full(points, s[0])), (np.full(points, u[-1]), s), (u[::-1], np.full(points, s[-1]))]
    sides.append((np.full(points, u[0]), s[::-1]))
    return np.concatenate([pad.surface.points(a[:-1], b[:-1]) for a, b in sides])
