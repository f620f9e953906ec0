"""Stiffeners on a junction (issue 25): ring frames and stringers of the main tube that cross a
branch's opening stop on its saddle, or on its pad's edge, with square ends; the branch's own
rings and stringers start beyond its saddle.

Where a stiffener stands on the wall surface X(u, s) (the outer one outside, the bore inside),
the branch's opening there is the region inside the saddle of that surface with the branch's
surface on the same side (:func:`~tubecad.junctions.saddle.saddle_curve`, sampled in the
curvature-line parameters of both). The stiffener's base is a band of the web's thickness w
about its line; it must stay clear of the opening:

- a stringer u = u_j stops where its band |u - u_j| <= w / (2 R) meets the opening: the
  opening's extent in s over the band is the extent of the saddle's points in it (the saddle
  bounds the opening), [s_lo, s_hi]; the stringer is made over [s0, s_lo] and [s_hi, s1]
  (:func:`~tubecad.stiffeners.solids.stringer_stiffener` over a span: its ends square, in the
  ring planes there), pieces ``stringer_05_a`` and ``stringer_05_b``;
- a ring s = s_i stops where its band |s - s_i| <= w / 2 meets the opening, [u_lo, u_hi]
  (unwrapped); the full ring frame is cut by the wedge between the half-planes through the
  axis at u_lo and u_hi (OCCT's boolean): its ends square, in planes through the ring's axis,
  the arc it keeps, u_hi .. u_lo + 2 pi, its ``arc_deg`` (its web develops as that sector of
  the annulus: :func:`tubecad.shop.webs.ring_pieces`);
- a pad (outside) takes the place of the opening: the stiffeners crossing it stop on its
  edge (its bounding rings and stringers), as they would on the opening's;
- on the branch, a stringer starts where its band leaves the saddle (the saddle's largest
  s_B over the band) and a ring must lie at least ``start`` beyond the saddle's highest point:
  a ring nearer is refused (it would cross the saddle), naming the key.

A stiffener the opening would leave in no piece, or in a piece shorter than its web's height,
is refused rather than dropped or made as a sliver.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import build123d as bd
import numpy as np

from tubecad.brep.section_edges import refine_section_edges
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE
from tubecad.junctions.saddle import SaddleCurve
from tubecad.stiffeners.profiles import Profile
from tubecad.stiffeners.solids import Stiffener, ring_stiffener, stringer_stiffener
from tubecad.surface.protocol import CurvatureLineSurface

#: polygon sides of the wedge that cuts a ring frame at an opening (its arc outside the frame)
WEDGE_SIDES = 64


@dataclass(frozen=True)
class Keepout:
    """Where a main stiffener may not stand: the opening bounded by ``saddle`` (on the
    stiffener's surface), or a pad's rings ``s_range`` and stringers ``angles_deg``."""

    saddle: SaddleCurve | None = None
    s_range: tuple[float, float] | None = None
    angles_deg: tuple[float, float] | None = None

    def along_stringer(self, u: float, band: float) -> tuple[float, float] | None:
        """The s-range the stringer u (radians) with its base's half-width ``band`` (radians)
        may not cover, or None."""
        if self.s_range is not None and self.angles_deg is not None:
            lo, hi = (math.radians(a) for a in self.angles_deg)
            if _angle_in(u, lo - band, hi + band):
                return self.s_range
            return None
        assert self.saddle is not None
        inside = np.abs(_wrapped(self.saddle.main_u - u)) <= band
        if not inside.any():
            return None
        s = self.saddle.main_s[inside]
        return float(s.min()), float(s.max())

    def along_ring(self, s: float, band: float) -> tuple[float, float] | None:
        """The angles (u_lo, u_hi) in radians, u_lo < u_hi, the ring at s with its base's
        half-width ``band`` (length) may not cover, or None."""
        if self.s_range is not None and self.angles_deg is not None:
            if self.s_range[0] - band <= s <= self.s_range[1] + band:
                lo, hi = self.angles_deg
                return math.radians(lo), math.radians(hi)
            return None
        assert self.saddle is not None
        inside = np.abs(self.saddle.main_s - s) <= band
        if not inside.any():
            return None
        u = self.saddle.main_u[inside]  # unwrapped along the saddle
        return float(u.min()), float(u.max())


def main_stiffeners(
    base: CurvatureLineSurface,
    rings_s: Sequence[tuple[int, float]],
    stringers_deg: Sequence[tuple[int, float]],
    profile: Profile,
    side: str,
    keepouts: Sequence[Keepout],
    tolerance: float = DEFAULT_FIT_TOLERANCE,
) -> list[Stiffener]:
    """The main tube's ring frames (index, s) and stringers (index, angle) on ``base`` (the
    wall surface they stand on: a tube, or a canal surface with its radius law), each stopped
    at every keepout it crosses (module docstring; on a canal surface the stringer's band is
    taken at the smallest radius, and the ring's wedge at the stringers' angles round that
    ring). A ParameterError names ``stiffeners.rings`` or ``stiffeners.stringers`` for a
    stiffener no piece of which is left."""
    law = base.radius_law
    smallest = float(law.min_radius)
    reach = float(law.max_radius) + profile.height
    out: list[Stiffener] = []
    for i, s in rings_s:
        ring = ring_stiffener(base, s, profile, side, tolerance, f"ring_{i:02d}")
        for keepout in keepouts:
            cut = keepout.along_ring(s, 0.5 * profile.thickness)
            if cut is not None:
                ring = _ring_cut(base, ring, s, cut, reach, profile)
        out.append(ring)
    for j, angle in stringers_deg:
        u = math.radians(angle)
        cuts = [c for k in keepouts if (c := k.along_stringer(u, 0.5 * profile.thickness / smallest)) is not None]
        for span, tag in _pieces(base.span, cuts, profile.height, f"stringer {j} at {angle:g} deg", "stringers"):
            out.append(stringer_stiffener(base, angle, profile, side, span, tolerance, f"stringer_{j:02d}{tag}"))
    return out


def branch_stiffeners(
    base: CurvatureLineSurface,
    saddle: SaddleCurve,
    rings_s: Sequence[tuple[int, float]],
    stringers_deg: Sequence[tuple[int, float]],
    profile: Profile,
    side: str,
    start: float,
    prefix: str = "branch",
    tolerance: float = DEFAULT_FIT_TOLERANCE,
) -> list[Stiffener]:
    """The branch's stringers from its saddle (on ``base``, the branch's wall surface they
    stand on) to its end, and its rings, each at least ``start`` beyond the saddle's highest
    point (else a ParameterError naming ``branches.stiffeners.rings``). On a branch with a
    radius law the stringers' bands are taken at its smallest radius."""
    radius = float(base.radius_law.min_radius)
    top = float(saddle.branch_s.max())
    out: list[Stiffener] = []
    for i, s in rings_s:
        if s - 0.5 * profile.thickness < top + start:
            raise ParameterError(
                f"stiffeners.rings: the branch's ring {i} at s = {s:.6g} is within {start:g} of its saddle "
                f"(which reaches s = {top:.6g}): choose rings beyond s = {top + start + 0.5 * profile.thickness:.6g}",
                key="branches.stiffeners.rings",
            )
        out.append(ring_stiffener(base, s, profile, side, tolerance, f"{prefix}_ring_{i:02d}"))
    s1 = base.span[1]
    for j, angle in stringers_deg:
        band = np.abs(_wrapped(saddle.branch_u - math.radians(angle))) <= 0.5 * profile.thickness / radius
        first = float(saddle.branch_s[band].max()) if band.any() else top
        if s1 - first < profile.height:
            raise ParameterError(
                f"stiffeners.stringers: the branch's stringer {j} would be {s1 - first:.3g} long above its "
                f"saddle, less than its height {profile.height:g}",
                key="branches.stiffeners.stringers",
            )
        out.append(stringer_stiffener(base, angle, profile, side, (first, s1), tolerance, f"{prefix}_stringer_{j:02d}"))
    return out


def _pieces(
    span: tuple[float, float], cuts: list[tuple[float, float]], shortest: float, what: str, key: str
) -> list[tuple[tuple[float, float], str]]:
    """The parts of ``span`` outside every cut, each at least ``shortest`` long, tagged
    '' (uncut) or _a, _b, ... in order; a ParameterError naming ``stiffeners.<key>`` where none is left."""
    if not cuts:
        return [(span, "")]
    parts = [span]
    for lo, hi in cuts:
        parts = [p for a, b in parts for p in ((a, min(b, lo)), (max(a, hi), b)) if p[1] > p[0]]
    kept = [p for p in parts if p[1] - p[0] >= shortest]
    if not kept:
        raise ParameterError(
            f"stiffeners.{key}: the {what} lies in a branch's opening (or pad) over its whole length: "
            "it cannot stop on it; leave it out",
            key=f"stiffeners.{key}",
        )
    return [(p, f"_{chr(ord('a') + k)}") for k, p in enumerate(kept)]


def _ring_cut(
    base: CurvatureLineSurface, ring: Stiffener, s: float, cut: tuple[float, float], reach: float, profile: Profile
) -> Stiffener:
    """``ring`` less the wedge between the half-planes through its axis at the angles ``cut``
    (radians, from r1): one arc, its ends square."""
    u_lo, u_hi = cut
    if u_hi - u_lo >= 2 * math.pi - 1e-9:
        raise ParameterError(
            f"stiffeners.rings: {ring.name} at s = {s:.6g} lies all round an opening", key="stiffeners.rings"
        )
    # the stringers' angles round this ring (a canal surface's turn by the Moebius map; u on a tube)
    chi_lo, chi_hi = (float(base.stringer_angle(np.array(u), np.array(s))) for u in (u_lo, u_hi))
    wedge = ring_wedge(base, s, chi_lo, chi_hi, reach, profile)
    pieces, _, _ = refine_section_edges(ring.solid.cut(wedge).wrapped)
    solids = bd.Shape.cast(pieces).solids()
    if len(solids) != 1 or not solids[0].is_valid:
        raise ParameterError(
            f"stiffeners.rings: {ring.name} at s = {s:.6g} cut at the opening gave {len(solids)} pieces",
            key="stiffeners.rings",
        )
    kept = (math.degrees(u_hi), math.degrees(u_lo) + 360.0)  # from the opening's far side round to its near one
    return Stiffener(ring.name, "ring", ring.value, solids[0], ring.profile, ring.side, ring.base, kept)


def ring_wedge(
    base: CurvatureLineSurface, s: float, u_lo: float, u_hi: float, reach: float, profile: Profile
) -> bd.Solid:
    """The wedge between the half-planes through the axis at s at the angles u_lo < u_hi
    (radians from r1, u_hi - u_lo < 2 pi), reaching past a ring frame of ``profile`` whose
    farthest point is ``reach`` from the axis: a prism on the polygon of the axis point and
    WEDGE_SIDES + 1 points of the arc at twice ``reach`` (its chords outside the frame)."""
    frame = base.axis.at(np.array([s]))
    c, t, r1, r2 = frame.position[0], frame.t[0], frame.r1[0], frame.r2[0]
    u = np.linspace(u_lo, u_hi, WEDGE_SIDES + 1)
    far = 2.0 * reach / math.cos(0.5 * (u_hi - u_lo) / WEDGE_SIDES)  # the polygon's chords outside the frame
    rim = [c + far * (math.cos(a) * r1 + math.sin(a) * r2) for a in u]
    half = 2.0 * (profile.flange_width + profile.thickness + profile.height)  # past the frame along the axis
    outline = [tuple(p - half * t) for p in [c, *rim]]
    base_face = bd.Face(bd.Wire.make_polygon([bd.Vector(*p) for p in outline], close=True))
    return bd.Solid.extrude(base_face, bd.Vector(*(2 * half * t)))


def _wrapped(a: np.ndarray) -> np.ndarray:
    """Angles to (-pi, pi]."""
    return np.angle(np.exp(1j * np.asarray(a)))


def _angle_in(u: float, lo: float, hi: float) -> bool:
    return (u - lo) % (2 * math.pi) <= (hi - lo)
