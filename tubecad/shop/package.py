"""The shop package of a stiffened wall (issue 13): everything ``tubecad shop`` writes,
computed in one place from the wall build, its stiffeners, its panels and the
``[fabrication]`` settings, then written into one folder with an index.

Files (their names say what they are):
- ``webs/webs_plate_NN.dxf`` / ``.svg``: the web pieces nested on stock plates, 1:1;
  ``webs/webs_pieces.step``: the wall and the stiffeners split at the same butt joints,
  named ``stringer_02_a``, ...;
- ``flanges/flanges_plate_NN.dxf`` / ``.svg``: stringer flanges developed (the tangent
  developable along their line), split as their webs are, nested;
- ``bending/bending.csv`` + ``bending.png`` / ``.svg``: bending tables and inverse bending
  curves of every stringer piece, stringer flange, ring frame and ring flange;
- ``marking/marking_panel_rI_sJ.step``: each panel with its stiffeners' marking lines;
- ``panels/panel_rI_sJ_development.dxf`` / ``.png``: each panel's development with its
  marking lines and strain;
- ``pin_jig/pin_jig_panel_rI_sJ.csv`` / ``.png``: pin heights for each panel;
- ``index.json`` (every file and every number) and ``overview.png`` / ``.svg``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from tubecad.brep import TubeBuild
from tubecad.core.errors import ParameterError
from tubecad.shop.fabrication import Fabrication
from tubecad.shop.marking import MarkingLine, marking_surface, panel_marking
from tubecad.shop.nesting import Plate, nest
from tubecad.shop.webs import WebPiece, piece_solids, ring_pieces, stringer_pieces
from tubecad.stiffeners.panel import Panel
from tubecad.stiffeners.solids import Stiffener


@dataclass
class ShopData:
    """What the shop gets for one wall: pieces, plates, flanges, bending tables, panels'
    marking lines, developments and pin jigs, and any warnings (nothing is dropped)."""

    build: TubeBuild | None  # None: a junction's stiffeners (its wall is tubecad build's)
    stiffeners: list[Stiffener]
    panels: list[Panel]
    fab: Fabrication
    web_pieces: list[WebPiece] = field(default_factory=list)
    piece_stiffeners: list[Stiffener] = field(default_factory=list)
    web_plates: list[Plate] = field(default_factory=list)
    flange_pieces: list[WebPiece] = field(default_factory=list)
    flange_plates: list[Plate] = field(default_factory=list)
    bending: list = field(default_factory=list)
    marking: dict[str, list[MarkingLine]] = field(default_factory=dict)
    developments: list = field(default_factory=list)
    pin_jigs: list = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)


def shop_data(
    build: TubeBuild,
    stiffeners: list[Stiffener],
    panels: list[Panel],
    fab: Fabrication,
    progress: Callable[[str], None] | None = None,
) -> ShopData:
    """Compute the shop package (module docstring); ``progress(stage)`` hears of each stage."""
    say = progress or (lambda _stage: None)
    data = ShopData(build, stiffeners, panels, fab)
    add_stiffener_data(data, tuple(build.layout.stringers_deg), build.tolerance, say)
    if panels:
        say("marking lines, panel developments and pin jigs")
        data.marking = {p.name: panel_marking(p, stiffeners) for p in panels}
        data.developments = panel_developments(build, panels, stiffeners[0].side if stiffeners else "outside")
        data.pin_jigs = pin_jigs(build, panels, stiffeners, fab, data.warnings)
    else:
        data.warnings.append(
            "no panels: no marking lines, panel developments or pin jigs "
            "(split the wall into panels at seam stringers to have them)"
        )
    return data


def add_stiffener_data(
    data: ShopData, stringers_deg: tuple[float, ...], tolerance: float, say: Callable[[str], None]
) -> None:
    """Fill ``data``'s stiffener part: its stiffeners' web pieces (ring joints kept clear of
    the stringers at ``stringers_deg``), their solids split alike (fitted to ``tolerance``),
    the webs nested on plates, the developed flanges nested, the bending tables."""
    stiffeners, fab = data.stiffeners, data.fab
    say("splitting webs into cuttable pieces")
    by_stiffener: dict[str, list[WebPiece]] = {}
    known = {st.name for st in stiffeners}
    unknown = sorted(set(fab.joints) - known)
    if unknown:
        raise ParameterError(
            f"joints.{unknown[0]}: no such stiffener; the stiffeners are {', '.join(sorted(known)) or 'none'}",
            key=f"joints.{unknown[0]}",
        )
    for st in stiffeners:
        by_stiffener[st.name] = (
            stringer_pieces(st, fab) if st.kind == "stringer" else ring_pieces(st, fab, stringers_deg)
        )
        data.web_pieces += by_stiffener[st.name]
    say("splitting the stiffener solids at the joints")
    for st in stiffeners:
        data.piece_stiffeners += piece_solids(st, by_stiffener[st.name], tolerance)
    say("nesting webs on plates")
    data.web_plates = nest(data.web_pieces, fab)
    say("developing flanges")
    data.flange_pieces = flange_pieces(stiffeners, by_stiffener, fab, data.warnings)
    data.flange_plates = nest(data.flange_pieces, fab) if data.flange_pieces else []
    say("bending tables")
    data.bending = bending_tables(stiffeners, by_stiffener, fab)


def flange_pieces(
    stiffeners: list[Stiffener], by_stiffener: dict[str, list[WebPiece]], fab: Fabrication, warnings: list[str]
) -> list[WebPiece]:
    """The developed flanges of T and L stringers, one per web piece (same span), named
    ``stringer_02_a_flange``. The web's pieces are chosen so that their flanges are
    cuttable too (tubecad.shop.webs); one that is not would be kept and warned of. Ring
    flanges are rolled from flat bar: bending tables, not plate parts."""
    from tubecad.shop.flanges import stringer_flange_flat_pattern
    from tubecad.shop.webs import cuttable

    out = []
    for st in stiffeners:
        if st.profile.kind == "flat" or st.kind != "stringer":
            continue
        for piece in by_stiffener[st.name]:
            name = f"{piece.name}_flange"
            pattern = stringer_flange_flat_pattern(st.base, st.value, st.profile, st.side, span=piece.span, name=name)
            ok, why = cuttable(pattern.outline, fab)
            if not ok:
                warnings.append(f"{name}: {why}; give it butt joints (joints.{st.name}) to split it")
            out.append(WebPiece(name, st.name, "flange", piece.span, pattern, piece.joints))
    return out


def bending_tables(stiffeners: list[Stiffener], by_stiffener: dict[str, list[WebPiece]], fab: Fabrication) -> list:
    """Bending tables of each stringer piece's base line and flange centre line, and of
    each ring's base circle and flange circle in arcs of at most 180 deg."""
    from tubecad.shop.bending import bending_table, ring_arcs, stringer_line
    from tubecad.shop.flanges import flange_level

    tables = []
    tol = fab.bend_back_tolerance
    for st in stiffeners:
        levels = [(0.0, "web base on the wall", "")]
        if st.profile.kind != "flat":
            levels.append((flange_level(st.profile, st.side), "flange centre line", "_flange"))
        for level, line, suffix in levels:
            if st.kind == "stringer":
                for piece in by_stiffener[st.name]:
                    position, length = stringer_line(st.base, st.value, level, piece.span)
                    tables.append(bending_table(position, length, piece.name + suffix, line, max_error=tol))
            else:
                a, b = st.arc_deg or (0.0, 360.0)  # a ring cut at an opening: its arc
                arcs = ring_arcs(st.base, st.value, level, start_deg=a, span_deg=b - a)
                for k, (position, length) in enumerate(arcs, 1):
                    name = f"{st.name}{suffix}_arc{k}"
                    tables.append(
                        bending_table(position, length, name, line.replace("web base", "ring base"), max_error=tol)
                    )
    return tables


def panel_developments(build: TubeBuild, panels: list[Panel], side: str) -> list:
    """Each panel developed on the wall surface its stiffeners stand on (``side``), the
    surface its marking lines lie on."""
    from tubecad.shop.panel_development import develop_panel

    surface = marking_surface(build, side).tube
    return [develop_panel(surface, p.s_range, p.angles_deg, p.name) for p in panels]


def pin_jigs(
    build: TubeBuild, panels: list[Panel], stiffeners: list[Stiffener], fab: Fabrication, warnings: list[str]
) -> list:
    """A pin jig per panel on the surface opposite its stiffeners (inner for outside
    stiffeners, the panel dome-up; outer for inside ones, the panel a trough)."""
    from tubecad.shop.pin_jig import pin_jig

    side = stiffeners[0].side if stiffeners else "outside"
    surface = marking_surface(build, "inside" if side == "outside" else "outside").tube  # the side opposite
    up_sign = 1.0 if side == "outside" else -1.0
    out = []
    for p in panels:
        spacing = fab.pin_spacing or default_pin_spacing(surface, p)
        try:
            out.append(pin_jig(surface, p.s_range, p.angles_deg, spacing, up_sign, fab.pin_clearance, p.name))
        except ParameterError as exc:  # e.g. a panel all round the tube: no jig plane sees it as a height field
            warnings.append(f"{p.name}: no pin jig ({exc})")
    return out


def default_pin_spacing(surface, panel: Panel) -> float:
    """A round spacing (1, 2 or 5 x 10^k) that puts about 6 pins along the panel's
    shorter side (its ring arc or its stringer length, whichever is shorter)."""
    import numpy as np

    s_a, s_b = panel.s_range
    a, b = (math.radians(x) for x in panel.angles_deg)
    s_mid = 0.5 * (s_a + s_b)
    ring = np.linalg.norm(np.diff(surface.points(np.linspace(a, b, 65), s_mid), axis=0), axis=1).sum()
    stringer = np.linalg.norm(np.diff(surface.points(0.5 * (a + b), np.linspace(s_a, s_b, 65)), axis=0), axis=1).sum()
    from tubecad.shop.pin_jig import round_spacing

    return round_spacing(min(ring, stringer))
