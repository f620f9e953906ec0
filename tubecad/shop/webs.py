"""Cuttable web pieces (issue 13): each stiffener's web split at butt joints into pieces
that can be cut from the stock plate as drawn.

A stringer's web develops exactly (tubecad.stiffeners.flat, the strip of normals along a
line of curvature), but its plane outline can cross itself: its base edge turns by
Int kappa_n sqrt(G) ds, several turns on the paper's log spiral, and a web that turns past
a full turn overlaps itself. A web is cuttable when its outline is a simple polygon
(shapely) and its minimum-area rectangle fits the plate less a kerf at each edge; a T or L
stringer's piece must also have a cuttable flange (tubecad.shop.flanges, developed over the
same span: web and flange are butt-jointed together). A web that is not is split at butt joints into equal lengths of its base line (chosen joints
from ``fab.joints`` first, then as few equal pieces between them as make every
piece cuttable). A joint with a root gap g ends both pieces g / 2 short of it, measured
along the base line. A stringer piece is the development of the strip over its own span
(congruent to that part of the whole web), so its lengths and area are exact; a ring
piece is a sector of the ring's annulus (a tube) or of its cone's sector (a canal surface).

Pieces are named after their stiffener, ``stringer_02`` when whole, ``stringer_02_a``,
``_b``, ... when split; :func:`piece_solids` splits the 3-D stiffener the same way (a
stringer rebuilt over each piece's span, a ring cut by the planes through its axis at the
joints), so the STEP solids carry the same names.
"""

from __future__ import annotations

import math
import string
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from tubecad.core.errors import ParameterError
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.shop.fabrication import Fabrication
from tubecad.stiffeners.flat import FlatPattern, ring_web_flat_pattern, stringer_flat_pattern, stringer_rates
from tubecad.stiffeners.solids import Stiffener

#: the most pieces one web (between chosen joints) is split into before the plate is called too small
MAX_PIECES = 200
#: points along each edge of a stringer piece's outline
PIECE_SAMPLES = 1001
#: points along each arc of a ring piece's outline
ARC_SAMPLES = 361


@dataclass(frozen=True)
class WebPiece:
    """One cuttable piece of a stiffener's web: its flat pattern (in its own frame) and where
    it lies on the stiffener: ``span`` in s along a stringer, in degrees round a ring (the
    angle of the circle from r1 at the ring, increasing counter-clockwise about t)."""

    name: str
    stiffener: str
    kind: str  # ring | stringer
    span: tuple[float, float]
    pattern: FlatPattern
    joints: tuple[bool, bool]  # whether its start / end is a butt joint

    @property
    def area(self) -> float:
        return self.pattern.area


def piece_names(stiffener: str, count: int) -> list[str]:
    """``stiffener`` for one piece; ``stiffener_a``, ``_b``, ..., ``_z``, ``_aa``, ... for more."""
    if count == 1:
        return [stiffener]
    letters = string.ascii_lowercase

    def label(i: int) -> str:
        return letters[i] if i < 26 else label(i // 26 - 1) + letters[i % 26]

    return [f"{stiffener}_{label(i)}" for i in range(count)]


def cuttable(outline: np.ndarray, fab: Fabrication) -> tuple[bool, str]:
    """(ok, why not): a simple polygon whose minimum-area rectangle fits the usable plate."""
    from shapely.geometry import Polygon

    polygon = Polygon(outline)
    if not polygon.is_valid:
        return False, "its outline crosses itself"
    long, short = rectangle_sides(polygon)
    usable = fab.usable
    if long > usable[0] + 1e-9 * usable[0] or short > usable[1] + 1e-9 * usable[1]:
        return (
            False,
            f"it needs {long:.6g} x {short:.6g}, more than the plate's usable {usable[0]:.6g} x {usable[1]:.6g}",
        )
    return True, ""


def rectangle_sides(polygon) -> tuple[float, float]:
    """(long, short) sides of a polygon's minimum-area enclosing rectangle."""
    rect = np.asarray(polygon.minimum_rotated_rectangle.exterior.coords)[:4]
    sides = np.linalg.norm(np.diff(np.vstack([rect, rect[:1]]), axis=0), axis=1)[:2]
    return float(sides.max()), float(sides.min())


# --- stringers ------------------------------------------------------------------------------------


def stringer_pieces(st: Stiffener, fab: Fabrication) -> list[WebPiece]:
    """The cuttable pieces of stringer ``st``'s web: split at its chosen joints
    (``fab.joints[st.name]``, s strictly inside its span), then each part into the fewest
    equal base-line lengths that are all cuttable; a ParameterError naming
    ``plate_size`` (its key) if even MAX_PIECES pieces are not."""
    base, h, side = st.base, st.profile.web_height, st.side
    s0, s1 = base.span
    _check_height(st, fab)
    turn, speed, breaks = stringer_rates(base, st.value)
    length = PiecewiseChebyshev.fit(speed, s0, s1, name="the stringer's base line", breaks=breaks).antiderivative()
    total = float(length(s1))
    chosen = sorted(fab.joints.get(st.name, ()))
    for s in chosen:
        if not s0 < s < s1:
            raise ParameterError(
                f"joints.{st.name}: {s:g} is outside the stringer, whose s runs in ({s0:g}, {s1:g})",
                key=f"joints.{st.name}",
            )
    half_gap = fab.joint_gap / 2

    def s_at(arc: float) -> float:  # the s at base-line length ``arc`` from the start
        if arc <= 0.0:
            return s0
        if arc >= total:
            return s1
        return brentq(lambda s: float(length(s)) - arc, s0, s1, xtol=1e-13 * (s1 - s0), rtol=1e-15)

    def develop(a: float, b: float, name: str) -> FlatPattern:
        return stringer_flat_pattern(base, st.value, h, side, name, PIECE_SAMPLES, span=(a, b))

    def piece_cuttable(a: float, b: float) -> bool:  # the web, and a T or L profile's flange, as drawn
        if not cuttable(develop(a, b, st.name).outline, fab)[0]:
            return False
        if st.profile.kind == "flat":
            return True
        from tubecad.shop.flanges import stringer_flange_flat_pattern

        flange = stringer_flange_flat_pattern(base, st.value, st.profile, side, span=(a, b), samples=PIECE_SAMPLES)
        return cuttable(flange.outline, fab)[0]

    cuts = [0.0] + [float(length(s)) for s in chosen] + [total]  # the joints as base-line lengths
    spans: list[tuple[float, float, bool, bool]] = []  # (from, to) in base-line length, joints at start / end
    for a, b in zip(cuts[:-1], cuts[1:]):
        for n in range(1, MAX_PIECES + 1):
            edges = np.linspace(a, b, n + 1)
            edges[0], edges[-1] = a, b
            parts = [(float(lo), float(hi), bool(lo > 0.0), bool(hi < total)) for lo, hi in zip(edges[:-1], edges[1:])]
            parts = [
                (lo + half_gap * at_start, hi - half_gap * at_end, at_start, at_end)
                for lo, hi, at_start, at_end in parts
            ]
            if any(lo >= hi for lo, hi, _, _ in parts):
                raise ParameterError(
                    f"joint_gap {fab.joint_gap:g} leaves no piece of {st.name}'s web "
                    f"between its joints ({(b - a) / n:.6g} of base line each)",
                    key="joint_gap",
                )
            if all(piece_cuttable(s_at(lo), s_at(hi)) for lo, hi, _, _ in parts):
                spans += parts
                break
        else:
            raise ParameterError(
                f"plate_size {list(fab.plate_size)} is too small for {st.name}'s web: "
                f"no split into up to {MAX_PIECES} pieces is cuttable",
                key="plate_size",
            )
    names = piece_names(st.name, len(spans))
    pieces = []
    for name, (lo, hi, start_joint, end_joint) in zip(names, spans):
        a, b = s_at(lo), s_at(hi)
        pieces.append(WebPiece(name, st.name, "stringer", (a, b), develop(a, b, name), (start_joint, end_joint)))
    return pieces


def _check_height(st: Stiffener, fab: Fabrication) -> None:
    """No piece of the web (or of a T or L stringer's flange) can be narrower than its
    height (its flange's width): refused at once if that exceeds the usable plate."""
    widths = [("web", "height", st.profile.web_height)]
    if st.profile.kind != "flat" and st.kind == "stringer":
        widths.append(("flange", "width", st.profile.flange_width))
    for part, what, size in widths:
        if size > fab.usable[1]:
            raise ParameterError(
                f"plate_size {list(fab.plate_size)} is too small for {st.name}'s "
                f"{part}: its {what} {size:g} exceeds the plate's usable width {fab.usable[1]:g} "
                f"(the width less a kerf at each edge)",
                key="plate_size",
            )


# --- rings ----------------------------------------------------------------------------------------


def ring_pieces(st: Stiffener, fab: Fabrication, stringers_deg: tuple[float, ...] = ()) -> list[WebPiece]:
    """The cuttable pieces of ring ``st``'s web: the whole annulus (or a canal ring's sector)
    if it fits the plate, else equal sectors between joints through the ring's axis.
    Chosen joints (``fab.joints[st.name]``, degrees in [0, 360) round the ring, measured as
    the stringers' angles are) come first; automatic joints keep clear of the layout's
    stringers at ``stringers_deg``. A ring cut at a branch's opening (``st.arc_deg``) is the
    sector of its arc, or equal sectors of it (:func:`_arc_pieces`)."""
    _check_height(st, fab)
    whole = ring_web_flat_pattern(st.base, st.value, st.profile.web_height, st.side, st.name)
    chosen = sorted(fab.joints.get(st.name, ()))
    for angle in chosen:
        if not 0.0 <= angle < 360.0:
            raise ParameterError(
                f"joints.{st.name}: {angle:g} is outside the ring's angles [0, 360) degrees", key=f"joints.{st.name}"
            )
    if st.arc_deg is not None:
        return _arc_pieces(st, fab, whole, chosen)
    if (
        not chosen
        and cuttable(whole.outline, fab)[0]
        and whole.hole is None
        or not chosen
        and whole.hole is not None
        and 2 * float(np.linalg.norm(whole.outline[0])) <= fab.usable[1]
    ):
        return [WebPiece(st.name, st.name, "ring", (0.0, 360.0), whole, (False, False))]
    if chosen:
        marks = [_ring_angle(st, a) for a in chosen]
        bays = list(zip(marks, marks[1:] + [marks[0] + 360.0]))
        return _sector_pieces(st, fab, whole, lambda _n: bays, first=1)

    def around(n: int) -> list[tuple[float, float]]:  # n equal sectors from the joint clearest of the stringers
        start = _clear_start(st, n, stringers_deg)
        return [(start, start + 360.0)]

    return _sector_pieces(st, fab, whole, around, first=2)


def _arc_pieces(st: Stiffener, fab: Fabrication, whole: FlatPattern, chosen: list[float]) -> list[WebPiece]:
    """The pieces of a ring kept over the arc a .. b (``st.arc_deg``: its ends square on a
    branch's opening, no butt joints there): the arc's sector of the annulus, or, split at
    the chosen joints (inside the arc) and then into equal parts, as few sectors as are all
    cuttable; the root gap is left at the joints only."""
    assert st.arc_deg is not None  # ring_pieces sends only a cut ring here
    a, b = st.arc_deg
    marks = []
    for angle in chosen:
        mark = a + (_ring_angle(st, angle) - a) % 360.0
        if not a < mark < b:
            raise ParameterError(
                f"joints.{st.name}: {angle:g} is not on the ring, which a branch's opening "
                f"cuts: it runs from {a % 360.0:.6g} round to {b % 360.0:.6g} deg",
                key=f"joints.{st.name}",
            )
        marks.append(mark)
    bays = list(zip([a, *sorted(marks)], [*sorted(marks), b]))
    return _sector_pieces(st, fab, whole, lambda _n: bays, first=1, square=(a, b))


def _sector_pieces(
    st: Stiffener,
    fab: Fabrication,
    whole: FlatPattern,
    bays: Callable[[int], list[tuple[float, float]]],
    first: int,
    square: tuple[float, float] | None = None,
) -> list[WebPiece]:
    """The fewest pieces, n = ``first``, first + 1, ... equal sectors of each bay of
    ``bays(n)`` (circle degrees), that are all cuttable: a butt joint's root gap is left at
    every sector end except the ends ``square`` of a cut ring's arc."""
    r_in, r_out, q = _annulus(whole)
    base_radius = r_in if st.side == "outside" else r_out  # the web's edge on the wall, in the development
    half_gap = 0.5 * math.degrees(fab.joint_gap / (base_radius * q))  # along the base circle, in 3-D degrees
    for n in range(first, MAX_PIECES + 1):
        arcs = [(lo + (hi - lo) * j / n, lo + (hi - lo) * (j + 1) / n) for lo, hi in bays(n) for j in range(n)]
        joints = [(square is None or x > square[0], square is None or y < square[1]) for x, y in arcs]
        arcs = [(x + half_gap * start, y - half_gap * end) for (x, y), (start, end) in zip(arcs, joints)]
        if any(x >= y for x, y in arcs):
            break
        if all(cuttable(_sector(r_in, r_out, math.radians(q * (y - x))), fab)[0] for x, y in arcs):
            names = piece_names(st.name, len(arcs))
            return [
                WebPiece(name, st.name, "ring", (x, y), _sector_pattern(name, r_in, r_out, q, x, y, st.side), joint)
                for name, (x, y), joint in zip(names, arcs, joints)
            ]
    what = "sectors of its arc" if square else "sectors"
    raise ParameterError(
        f"plate_size {list(fab.plate_size)} is too small for {st.name}'s web: no split "
        f"into up to {MAX_PIECES} {what} is cuttable",
        key="plate_size",
    )


def _annulus(whole: FlatPattern) -> tuple[float, float, float]:
    """(inner radius, outer radius, q): the ring web's development is the sector of angle
    2 pi q of that annulus (q = 1 on a tube)."""
    if whole.sector is not None:
        r_in, r_out, angle = whole.sector
        return r_in, r_out, angle / (2 * math.pi)
    assert whole.hole is not None  # a full ring's pattern: the annulus
    return float(np.linalg.norm(whole.hole[0])), float(np.linalg.norm(whole.outline[0])), 1.0


def _ring_angle(st: Stiffener, angle_deg: float) -> float:
    """The circle's angle (degrees from r1 at the ring) of the stringer angle ``angle_deg``:
    the same on a tube; chi(chi0, s) on a canal surface."""
    if st.base.constant_radius:  # chi = u
        return float(angle_deg)
    return math.degrees(float(st.base.stringer_angle(math.radians(angle_deg), st.value)))


def _clear_start(st: Stiffener, n: int, stringers_deg: tuple[float, ...]) -> float:
    """The first of n equally spaced joints, placed where the joints keep farthest from
    the stringers (a butt joint under a stringer crossing is hard to weld)."""
    if not stringers_deg:
        return 0.0
    marks = np.array([_ring_angle(st, a) for a in stringers_deg])
    candidates = np.linspace(0.0, 360.0 / n, 181)
    joints = (candidates[:, None] + 360.0 * np.arange(n)[None, :] / n)[..., None]
    apart = np.abs((joints - marks[None, None, :] + 180.0) % 360.0 - 180.0).min(axis=(1, 2))
    return float(candidates[int(np.argmax(apart))])


def _sector(r_in: float, r_out: float, angle: float, samples: int = ARC_SAMPLES) -> np.ndarray:
    """The annular sector of those radii and ``angle`` (radians), symmetric about +y: outer
    arc, radial edge, inner arc back, radial edge (the FlatPattern.sector convention)."""
    a = 0.5 * math.pi + 0.5 * angle * np.linspace(-1.0, 1.0, samples)
    arc = np.stack([np.cos(a), np.sin(a)], axis=1)
    return np.concatenate([r_out * arc, r_in * arc[::-1]])


def _sector_pattern(
    name: str, r_in: float, r_out: float, q: float, a_deg: float, b_deg: float, side: str
) -> FlatPattern:
    """The flat pattern of the ring piece from a_deg to b_deg (3-D degrees): a sector of
    angle q (b - a) of the annulus; base edge on the wall (r_in outside, r_out inside)."""
    angle = q * math.radians(b_deg - a_deg)
    base, top = (r_in, r_out) if side == "outside" else (r_out, r_in)
    return FlatPattern(
        name,
        "ring",
        _sector(r_in, r_out, angle),
        angle * base,
        angle * top,
        0.5 * angle * (r_out**2 - r_in**2),
        sector=(r_in, r_out, angle),
    )


# --- the 3-D pieces -------------------------------------------------------------------------------


def piece_solids(st: Stiffener, pieces: list[WebPiece], tolerance: float) -> list[Stiffener]:
    """The stiffener ``st`` split as its web is: one Stiffener per piece, named after it. A
    stringer piece is the stringer rebuilt over the piece's span (its ends in the normal
    planes there, as the web piece's end rulings are); a ring piece is the ring solid
    between the planes through its axis at the piece's angles (each holds a ruling of the
    web: a radius of the annulus, a generator of a canal ring's cone)."""
    from dataclasses import replace

    from tubecad.stiffeners.solids import stringer_stiffener

    whole = st.base.span if st.kind == "stringer" else (st.arc_deg or (0.0, 360.0))
    if len(pieces) == 1 and pieces[0].span == whole:
        return [replace(st, name=pieces[0].name)]
    if st.kind == "stringer":
        return [
            replace(
                stringer_stiffener(
                    st.base, st.value, st.profile, st.side, span=p.span, tolerance=tolerance, name=p.name
                ),
                base=st.base,
            )
            for p in pieces
        ]
    if st.arc_deg is not None:
        return [replace(st, name=p.name, solid=_sector_solid(st, *p.span), arc_deg=p.span) for p in pieces]
    return [replace(st, name=p.name, solid=_sector_solid(st, *p.span)) for p in pieces]


def _sector_solid(st: Stiffener, a_deg: float, b_deg: float):
    """The part of a ring (whole, or cut: ``st.arc_deg``) between the circle angles a_deg < b_deg:
    its common with the wedge between the half-planes through the axis there (any angle below
    360 deg; each half-plane holds a ruling of the web)."""
    import build123d as bd
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common

    from tubecad.brep.properties import is_valid
    from tubecad.brep.section_edges import refine_section_edges
    from tubecad.stiffeners.junction import ring_wedge

    reach = st.base_radius + st.profile.height
    wedge = ring_wedge(st.base, st.value, math.radians(a_deg), math.radians(b_deg), reach, st.profile)
    common, _, _ = refine_section_edges(BRepAlgoAPI_Common(st.solid.wrapped, wedge.wrapped).Shape())
    solids = bd.Shape.cast(common).solids()
    if len(solids) != 1 or not is_valid(solids[0].wrapped):
        raise ParameterError(f"{st.name}: the ring piece from {a_deg:g} to {b_deg:g} deg is not one valid solid")
    return solids[0]
