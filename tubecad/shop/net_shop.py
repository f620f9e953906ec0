"""The shop package of a host face's net (issue 44): its webs and a T's or L's flanges
developed flat, split where a plate is too small, nested and drawn 1:1, and the net's lines
as marking data, and a pin-jig table per panel (a cell of the net:
:mod:`tubecad.shop.net_pin_jigs`).

Each web develops without strain (it stands along the face's normal on a line of curvature:
:mod:`tubecad.stiffeners.net_webs`); a web that no plate holds is split into the fewest equal
lengths of its base line that every plate holds (:func:`tubecad.shop.webs.cuttable`), the
butt joints' root gap ``joint_gap`` taken from each side; a flange lies in the tangent planes
of the offset surface along its line (developable: :mod:`tubecad.stiffeners.net_webs`) and is
split with its web (:func:`flange_pattern`). The pieces are nested
(:func:`tubecad.shop.nesting.nest`) and drawn (DXF for cutting, SVG, a preview picture:
:mod:`tubecad.shop.drawings`). The marking data are the lines' 3-D polylines (CSV, a row per
point, named ``k1_03``...) and their lengths, for marking the face before the webs are set.
A panel refitted in curvature-line coordinates (``[host] patches = "curvature"``:
:mod:`tubecad.nets.patch_shell`) is developed as a tube's panel is
(:func:`tubecad.shop.panel_development.develop_cell`: its middle k2 line and every k1 line kept
isometric, the strain measured at every node), 1:1 in DXF with a picture of the strain.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from tubecad.core.atomic import write_text
from tubecad.core.errors import ParameterError
from tubecad.shop.net_pin_jigs import CellPinJig, net_pin_jigs
from tubecad.shop.webs import WebPiece, cuttable, piece_names

if TYPE_CHECKING:
    from tubecad.nets import CurvatureNet
    from tubecad.nets.patch_shell import PatchShell
    from tubecad.shop.fabrication import Fabrication
    from tubecad.shop.flanges import FlangePattern
    from tubecad.shop.nesting import Plate
    from tubecad.shop.panel_development import PanelDevelopment
    from tubecad.stiffeners.net_webs import NetWeb
    from tubecad.stiffeners.profiles import Profile

#: the most pieces a web is split into
MAX_PIECES = 200
#: points per line in the marking CSV
MARKING_POINTS = 201
#: a refitted panel's development grid (nodes along k1, along k2)
DEVELOPMENT_SAMPLES = (17, 17)


@dataclass
class NetShop:
    """A net's shop package: the ``pieces`` of its webs nested on ``plates``, the ``net`` for
    its marking lines, the fabrication settings ``fab``."""

    net: CurvatureNet
    webs: list[NetWeb]
    pieces: list[WebPiece]
    plates: list[Plate]
    fab: Fabrication
    pin_jigs: list[CellPinJig] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    #: the refitted panels' developments (``panel_NN``, with ``patches = "curvature"``) and
    #: the lines round each
    developments: list[tuple[PanelDevelopment, str]] = field(default_factory=list)

    def write(self, folder: Path, name: str) -> dict[str, Any]:
        """Write webs/ (plates as DXF, SVG, PNG; the developments side by side as DXF),
        marking/net_lines.csv and index.json into ``folder``; returns the index."""
        from tubecad.shop.drawings import write_plate_dxf, write_plate_picture, write_plate_svg
        from tubecad.shop.nesting import check_nesting
        from tubecad.shop.net_pin_jigs import write_cell_pin_jig_csv
        from tubecad.shop.panel_development import write_panel_dxf, write_panel_picture
        from tubecad.shop.pin_jig import write_pin_jig_picture
        from tubecad.stiffeners.flat import write_dxf

        files: list[dict[str, str]] = []

        def record(path: Path, kind: str, what: str) -> None:
            files.append({"path": path.relative_to(folder).as_posix(), "kind": kind, "what": what})

        unit = self.fab.length_unit
        for sub in ("webs", "marking"):
            (folder / sub).mkdir(parents=True, exist_ok=True)
        for plate in self.plates:
            what = f"{plate.name}: {len(plate.pieces)} web pieces nested, 1:1"
            record(
                write_plate_dxf(plate, self.fab, folder / "webs" / f"webs_{plate.name}.dxf"),
                "webs",
                what + " (DXF for cutting)",
            )
            record(
                write_plate_svg(plate, self.fab, folder / "webs" / f"webs_{plate.name}.svg"), "webs", what + " (SVG)"
            )
            record(
                write_plate_picture(plate, self.fab, folder / "webs" / f"webs_{plate.name}.png"),
                "webs",
                what + " (picture)",
            )
        developed = write_dxf([w.pattern for w in self.webs], folder / "webs" / "webs_developed.dxf", length_unit=unit)
        record(developed, "webs", "each web developed whole, side by side (DXF, a layer per web)")
        if self.pin_jigs:
            (folder / "panels").mkdir(exist_ok=True)
        for jig in self.pin_jigs:
            bounded = f"between {', '.join(jig.lines)}" if jig.lines else "on the boundary"
            what = f"{jig.name} ({bounded}): {len(jig.heights)} pins every {jig.spacing:g}"
            table = write_cell_pin_jig_csv(jig, folder / "panels" / f"{jig.name}_pin_jig.csv", unit)
            record(table, "panels", what + " (CSV)")
            for picture in write_pin_jig_picture(jig, folder / "panels", ("png",)):
                record(picture, "panels", what + " (picture)")
        if self.developments:
            (folder / "panels").mkdir(exist_ok=True)
        for dev, cell in self.developments:
            what = f"{dev.name} ({cell}) developed, largest strain {dev.max_strain:.2e}"
            (dxf,) = write_panel_dxf([dev], {}, folder / "panels", unit)
            record(dxf, "panels", what + " (DXF, 1:1)")
            for picture in write_panel_picture(dev, [], folder / "panels", ("png",)):
                record(picture, "panels", what + " (picture of the strain)")
        marking = folder / "marking" / "net_lines.csv"
        write_text(marking, marking_csv(self.net))
        record(
            marking, "marking", f"the net's lines as 3-D polylines, {MARKING_POINTS} points each (CSV: line, x, y, z)"
        )
        index: dict[str, Any] = {
            "name": name,
            "units": {"length": unit},
            "fabrication": {
                "plate_size": list(self.fab.plate_size),
                "kerf": self.fab.kerf,
                "joint_gap": self.fab.joint_gap,
            },
            "webs": {
                "nesting": check_nesting(self.plates, self.fab),
                "pieces": [_piece(p, self.plates) for p in self.pieces],
                "webs": [
                    {"name": w.name, "line": w.line, "base_length": w.pattern.base_length, "area": w.pattern.area}
                    for w in self.webs
                ],
            },
            "panels": [
                {
                    "name": jig.name,
                    "lines": list(jig.lines),
                    "pins": len(jig.heights),
                    "spacing": jig.spacing,
                    "heights": [float(jig.heights.min()), float(jig.heights.max())],
                    "up": jig.up.tolist(),
                }
                for jig in self.pin_jigs
            ],
            "developments": [
                {
                    "name": dev.name,
                    "cell": cell,
                    "max_strain": dev.max_strain,
                    "surface_area": dev.surface_area,
                    "flat_area": dev.flat_area,
                }
                for dev, cell in self.developments
            ],
            "lines": {n: float(line.sigma[-1] - line.sigma[0]) for n, line in self.net.lines.items()},
            "umbilics": self.net.report()["umbilics"],
            "warnings": list(self.warnings),
            "files": files,
        }
        write_text(folder / "index.json", json.dumps(index, indent=1) + "\n")
        return index


def net_shop(
    net: CurvatureNet,
    webs: list[NetWeb],
    fab: Fabrication,
    levels: tuple[float, float] = (0.0, 0.0),
    refit: PatchShell | None = None,
) -> NetShop:
    """The package of ``webs`` on ``net`` with the settings ``fab`` (module docstring), a
    pin jig per panel (:func:`tubecad.shop.net_pin_jigs.net_pin_jigs`) and each refitted
    panel's development.

    Args:
        net: the face's net.
        webs: its webs (:func:`tubecad.stiffeners.net_webs.net_web`).
        fab: the fabrication settings.
        levels: the wall's inner and outer offsets from the face (its plating's surfaces).
        refit: the net's cells on their curvature-line patches, or None.

    Returns:
        The package, ready to write.

    Raises:
        ParameterError: (``plate_size``) a web no split into MAX_PIECES fits; (``joint_gap``)
            a gap that leaves no piece.
    """
    from tubecad.shop.nesting import nest

    pieces = [piece for web in webs for piece in web_pieces(net, web, fab)]
    warnings: list[str] = []
    side = webs[0].side if webs else "outside"
    jigs = net_pin_jigs(net, levels, side, fab.pin_spacing, fab.pin_clearance, warnings)
    developments = [] if refit is None else refitted_developments(refit)
    return NetShop(net, webs, pieces, nest(pieces, fab) if pieces else [], fab, jigs, warnings, developments)


def refitted_developments(refit: PatchShell) -> list[tuple[PanelDevelopment, str]]:
    """Each refitted cell developed (module docstring), named ``panel_NN`` by its place among
    the split face's faces (the pin jigs' names), with its cell's name."""
    from tubecad.nets.patch_surface import PatchSurface
    from tubecad.shop.panel_development import develop_cell

    out = []
    for cell, patch in sorted(refit.patches.items(), key=lambda item: refit.panels[item[0]]):
        base = PatchSurface(patch.surface)
        name = f"panel_{refit.panels[cell]:02d}"
        out.append((develop_cell(base, base.u_range, base.span, name, DEVELOPMENT_SAMPLES), cell))
    return out


def web_pieces(net: CurvatureNet, web: NetWeb, fab: Fabrication) -> list[WebPiece]:
    """``web`` as the fewest equal lengths of its line that all fit a plate, with its flange's
    pieces (a T or L profile: the same spans, named ``<piece>_flange``) fitting too (module
    docstring)."""
    from tubecad.stiffeners.net_webs import web_pattern

    line, edge = net.lines[web.line], net.edges[web.line]
    total = edge.curve.LastParameter() - edge.curve.FirstParameter()
    half_gap = fab.joint_gap / 2
    height, side, base = web.profile.web_height, web.side, web.base
    for n in range(1, MAX_PIECES + 1):
        cuts = np.linspace(0.0, total, n + 1)
        spans = [
            (lo + half_gap * (i > 0), hi - half_gap * (i < n - 1))
            for i, (lo, hi) in enumerate(zip(cuts[:-1], cuts[1:]))
        ]
        if any(lo >= hi for lo, hi in spans):
            raise ParameterError(f"joint_gap {fab.joint_gap:g} leaves no piece of {web.name}'s web", key="joint_gap")
        names = piece_names(web.name, n)
        patterns = [web_pattern(net.host, nm, line, edge, height, side, base, span) for nm, span in zip(names, spans)]
        flanges = (
            []
            if web.profile.kind == "flat"
            else [flange_pattern(net, nm, web.line, web.profile, side, base, span) for nm, span in zip(names, spans)]
        )
        if all(cuttable(p.outline, fab)[0] for p in patterns + flanges):
            pieces = [
                WebPiece(nm, web.name, "stringer", span, pattern, (i > 0, i < n - 1))
                for i, (nm, span, pattern) in enumerate(zip(names, spans, patterns))
            ]
            return pieces + [
                WebPiece(flange.name, web.name, "flange", piece.span, flange, piece.joints)
                for piece, flange in zip(pieces, flanges)
            ]
    raise ParameterError(
        f"plate_size {list(fab.plate_size)} is too small for {web.name}'s web: no split into up to {MAX_PIECES} "
        "pieces is cuttable",
        key="plate_size",
    )


def flange_pattern(
    net: CurvatureNet,
    name: str,
    line_name: str,
    profile: Profile,
    side: str,
    base: float = 0.0,
    span: tuple[float, float] | None = None,
) -> FlangePattern:
    """The development of the flange of a T or L ``profile``'s stiffener on ``side`` of the
    line (:mod:`tubecad.stiffeners.net_webs`), its web's base ``base`` along the normal from
    the face, over ``span`` (arc lengths from the line's start; None: all of it): the strip
    X + d n + s b at the flange's mid-thickness level d = base +- (h - tf / 2), s across its
    width, developable (its rulings b move along T), with speed 1 - d k and turn g = b . X''
    per unit arc length of the line (:func:`tubecad.shop.flanges.developed_band`).

    Args:
        net: the face's net.
        name: the web's pattern name (the flange's is ``<name>_flange``).
        line_name: the line's name (``k1_03``).
        profile: a T or L profile.
        side: ``outside`` or ``inside``.
        base: the web's base's offset along the normal.
        span: (start, end) arc lengths from the line's start.

    Returns:
        The flange's flat pattern.

    Raises:
        ParameterError: (``profile``) not T or L; (``flange_width``) an edge folding over.
    """
    from tubecad.shop.flanges import developed_band, flange_level, flange_widths
    from tubecad.stiffeners.net_webs import geodesic_curvature, line_curvature, line_kinks

    host, line, edge = net.host, net.lines[line_name], net.edges[line_name]
    level = base + flange_level(profile, side)
    s0 = edge.curve.FirstParameter()
    a, b = (0.0, edge.curve.LastParameter() - s0) if span is None else (float(span[0]), float(span[1]))

    def speed(s: np.ndarray) -> np.ndarray:
        return 1.0 - level * line_curvature(host, edge, line.family, s0 + a + np.asarray(s, dtype=float))

    def turn(s: np.ndarray) -> np.ndarray:
        return geodesic_curvature(host, edge, s0 + a + np.asarray(s, dtype=float))

    return developed_band(
        turn,
        speed,
        (0.0, b - a),
        flange_widths(profile),
        f"{name}_flange",
        breaks=_with_knots(line_kinks(line, a, b), edge.curve, s0 + a),
        level=level,
    )


def _with_knots(breaks: np.ndarray, curve: Any, start: float) -> np.ndarray:
    """``breaks`` (from 0, on a span starting at arc length ``start`` of the curve) with the
    curve's knots inside them: g = b . X'' is read from the edge's quintic pieces, whose second
    derivative is polynomial between knots and may jump at one (a break node's)."""
    knots = np.array([curve.Knot(i) for i in range(1, curve.NbKnots() + 1)]) - start
    inside = knots[(knots > breaks[0]) & (knots < breaks[-1])]
    return np.unique(np.concatenate([breaks, inside]))


def marking_csv(net: CurvatureNet) -> str:
    """The net's lines as 3-D polylines: a header, then ``line, x, y, z`` rows."""
    rows = ["line,x,y,z"]
    for name, edge in net.edges.items():
        curve = edge.curve
        for t in np.linspace(curve.FirstParameter(), curve.LastParameter(), MARKING_POINTS):
            p = curve.Value(float(t))
            rows.append(f"{name},{p.X():.9g},{p.Y():.9g},{p.Z():.9g}")
    return "\n".join(rows) + "\n"


def _piece(piece: WebPiece, plates: list[Plate]) -> dict[str, Any]:
    plate = next((p.name for p in plates if any(q.piece is piece for q in p.pieces)), None)
    pattern = piece.pattern
    return {
        "name": piece.name,
        "stiffener": piece.stiffener,
        "span": list(piece.span),
        "span_of": "arc length along the line from its start",
        "area": pattern.area,
        "base_length": pattern.base_length,
        "top_length": pattern.top_length,
        "joints": {"start": bool(piece.joints[0]), "end": bool(piece.joints[1])},
        "plate": plate,
    }
