"""1:1 cutting drawings of nested plates (issue 13): DXF for the cutting machine, SVG for
people, both at full size with no axes.

Layers (DXF layers, SVG groups of the same ids):
- ``PLATE``: the stock plate's outline;
- ``PARTS``: each piece's finished outline, closed polylines (a full ring's annulus: two
  exact circles; a ring sector: exact arcs as bulges);
- ``CUT``: the cutting path, the outline offset by kerf / 2 away from the part (shapely);
- ``JOINTS``: the butt-joint edges of split pieces;
- ``TEXT``: each piece's name (``stringer_02_a``) and the joint marks' names.
The DXF is in the model's unit, which it states ($INSUNITS); the SVG's user unit is the
millimetre (width and height in mm), so it prints at 1:1.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from tubecad.core.atomic import write_text
from tubecad.core.dxf import Drawing
from tubecad.core.units import length_unit
from tubecad.shop.fabrication import Fabrication
from tubecad.shop.nesting import PlacedPiece, Plate

LAYERS = {"PLATE": 8, "PARTS": 7, "CUT": 1, "JOINTS": 3, "TEXT": 5}  # name -> DXF colour index
SVG_STYLE = {"PLATE": ("#555555", 0.5), "PARTS": ("#10203a", 0.35), "CUT": ("#d04020", 0.2), "JOINTS": ("#2a8a3a", 0.6)}


def joint_edges(placed: PlacedPiece) -> list[tuple[str, np.ndarray]]:
    """The butt-joint edges of a placed piece, ("start" | "end", (2, 2) segment): a stringer
    piece's end rulings (first and last points of its two edges), a ring sector's radial edges."""
    outline, (start, end) = placed.outline, placed.piece.joints
    n = len(outline) // 2
    edges = []
    if start:
        edges.append(("start", np.array([outline[0], outline[-1]])))
    if end:
        edges.append(("end", np.array([outline[n - 1], outline[n]])))
    return edges


def cut_paths(placed: PlacedPiece, kerf: float) -> list[np.ndarray]:
    """The cutting path: kerf / 2 outside the part (and inside its hole), by shapely."""
    polygon = placed.polygon()
    if kerf <= 0.0:
        rings = [polygon.exterior, *polygon.interiors]
    else:
        grown = polygon.buffer(kerf / 2, quad_segs=16, join_style="round")
        rings = [grown.exterior, *grown.interiors]
    return [np.asarray(r.coords) for r in rings]


def label_point(placed: PlacedPiece) -> tuple[float, float]:
    """A point inside the placed piece (shapely's representative point): where its name goes."""
    point = placed.polygon().representative_point()
    return float(point.x), float(point.y)


def text_height(plate: Plate) -> float:
    return 0.012 * min(plate.size)


def write_plate_dxf(plate: Plate, fab: Fabrication, path: str | Path) -> Path:
    """The plate's 1:1 DXF (module docstring), atomically."""
    drawing = Drawing(fab.length_unit, LAYERS)
    length, width = plate.size
    drawing.polyline([(0, 0), (length, 0), (length, width), (0, width)], "PLATE")
    height = text_height(plate)
    for placed in plate.pieces:
        _part_outline(drawing, placed)
        for path_points in cut_paths(placed, fab.kerf):
            drawing.polyline(path_points[:-1], "CUT")
        for end, edge in joint_edges(placed):
            drawing.line(edge[0], edge[1], "JOINTS")
            drawing.text(f"joint {placed.piece.name} {end}", edge.mean(axis=0), height / 2, "TEXT")
        drawing.text(placed.piece.name, label_point(placed), height, "TEXT")
    drawing.text(
        f"{plate.name}  {length:g} x {width:g} {fab.length_unit}  kerf {fab.kerf:g}",
        (0.0, -1.5 * height),
        height,
        "TEXT",
    )
    return drawing.save(path)


def _part_outline(drawing: Drawing, placed: PlacedPiece) -> None:
    """The finished outline on PARTS: exact circles and arcs for rings, else the polyline."""
    pattern = placed.piece.pattern
    if pattern.hole is not None:  # a full annulus: two circles about the placed centre
        centre = tuple(placed.place(np.zeros((1, 2)))[0])
        drawing.circle(centre, float(np.linalg.norm(pattern.outline[0])), "PARTS")
        drawing.circle(centre, float(np.linalg.norm(pattern.hole[0])), "PARTS")
    elif pattern.sector is not None:  # a sector: its arcs as bulges, turned and moved onto the plate
        drawing.sector(*pattern.sector, "PARTS", place=placed.place)
    else:
        drawing.polyline(placed.outline, "PARTS")


def write_plate_svg(plate: Plate, fab: Fabrication, path: str | Path) -> Path:
    """The plate at 1:1: the SVG's user unit is the millimetre, y up as in the DXF."""
    mm = length_unit(fab.length_unit).mm
    length, width = plate.size
    height = text_height(plate)
    pad = 4 * height
    W, H = (length + 2 * pad) * mm, (width + 3 * pad) * mm
    svg = ET.Element(
        "svg",
        xmlns="http://www.w3.org/2000/svg",
        width=f"{W:.6g}mm",
        height=f"{H:.6g}mm",
        viewBox=f"0 0 {W:.6g} {H:.6g}",
    )
    ET.SubElement(svg, "title").text = f"{plate.name}: {length:g} x {width:g} {fab.length_unit}, 1:1"
    # model (x, y) -> SVG mm, y flipped so that the drawing reads as the DXF does
    flip = ET.SubElement(
        svg, "g", transform=f"translate({pad * mm:.6g} {(width + pad) * mm:.6g}) scale({mm:.9g} {-mm:.9g})"
    )

    def group(layer: str) -> ET.Element:
        colour, stroke_mm = SVG_STYLE.get(layer, ("#000000", 0.3))
        return ET.SubElement(
            flip, "g", {"id": layer, "fill": "none", "stroke": colour, "stroke-width": f"{stroke_mm / mm:.6g}"}
        )

    def path_d(points: np.ndarray, close: bool = True) -> str:
        d = "M " + " L ".join(f"{x:.6f} {y:.6f}" for x, y in points)
        return d + (" Z" if close else "")

    ET.SubElement(group("PLATE"), "path", d=path_d(np.array([(0, 0), (length, 0), (length, width), (0, width)])))
    parts, cuts, joints = group("PARTS"), group("CUT"), group("JOINTS")
    for placed in plate.pieces:
        rings = [placed.outline] + ([] if placed.hole is None else [placed.hole])
        ET.SubElement(
            parts, "path", {"d": " ".join(path_d(r) for r in rings), "id": placed.piece.name, "fill-rule": "evenodd"}
        )
        for points in cut_paths(placed, fab.kerf):
            ET.SubElement(cuts, "path", d=path_d(points))
        for _, edge in joint_edges(placed):
            ET.SubElement(joints, "path", d=path_d(edge, close=False))
    text = ET.SubElement(
        svg, "g", {"id": "TEXT", "fill": "#10203a", "font-family": "sans-serif", "font-size": f"{height * mm:.6g}"}
    )
    for placed in plate.pieces:
        x, y = label_point(placed)
        ET.SubElement(
            text, "text", {"x": f"{(x + pad) * mm:.6g}", "y": f"{(width + pad - y) * mm:.6g}", "text-anchor": "middle"}
        ).text = placed.piece.name
    ET.SubElement(text, "text", x=f"{pad * mm:.6g}", y=f"{(width + 2.5 * pad) * mm:.6g}").text = (
        f"{plate.name}  {length:g} x {width:g} {fab.length_unit}  kerf {fab.kerf:g}  "
        f"{len(plate.pieces)} pieces  {utilisation_text(plate, fab.length_unit)}"
    )
    return write_text(path, ET.tostring(svg, encoding="unicode") + "\n")


def utilisation_text(plate: Plate, unit: str) -> str:
    """The plate's utilisation in words: over the strip the nest uses, and over the plate.

    Args:
        plate: a nested plate.
        unit: the length unit's name.

    Returns:
        e.g. "utilisation 8.4 % of the 3000 x 252 mm strip used (1.4 % of the plate; the
        3000 x 1248 mm rest is an offcut)".
    """
    (length, width), (_, used) = plate.size, plate.used_size
    if used >= width:
        return f"utilisation {100 * plate.utilisation:.1f} % of the plate"
    return (
        f"utilisation {100 * plate.utilisation:.1f} % of the {length:g} x {used:.0f} {unit} strip used "
        f"({100 * plate.plate_utilisation:.1f} % of the plate; the {length:g} x {width - used:.0f} {unit} "
        "rest is an offcut)"
    )


def draw_plate(ax, plate: Plate, fontsize: float = 7.0, top: float | None = None) -> int:
    """Draw ``plate`` into the Axes ``ax``: the plate, its used strip's edge, the parts, their
    butt-joint edges (green) and their names, placed so that none overlaps another or crosses
    another part (:func:`tubecad.export.labels.place_labels`). The figure's layout must be final.

    Args:
        ax: a matplotlib Axes.
        plate: the nested plate.
        fontsize: the names' size (points), shrunk where the parts are crowded.
        top: show the plate up to this y only (e.g. its used strip and room for the names;
            default the whole plate).

    Returns:
        How many names were moved off their parts (each with a leader line).
    """
    from matplotlib.patches import Polygon as Patch

    from tubecad.export.labels import place_labels

    length, width = plate.size
    ax.add_patch(
        Patch([(0, 0), (length, 0), (length, width), (0, width)], closed=True, facecolor="#f2f2f2", edgecolor="#555555")
    )
    used = plate.used_size[1]
    if used < width:  # the offcut's edge
        ax.plot([0, length], [used, used], color="#888888", linewidth=0.8, linestyle="--")
    for placed in plate.pieces:
        ax.add_patch(Patch(placed.outline, closed=True, facecolor="#c9d6ea", edgecolor="#10203a", linewidth=0.6))
        if placed.hole is not None:
            ax.add_patch(Patch(placed.hole, closed=True, facecolor="#f2f2f2", edgecolor="#10203a", linewidth=0.6))
        for _, edge in joint_edges(placed):
            ax.plot(edge[:, 0], edge[:, 1], color=SVG_STYLE["JOINTS"][0], linewidth=1.5)
    ax.set_xlim(-0.01 * length, 1.01 * length)
    ax.set_ylim(-0.01 * width, 1.01 * width if top is None else min(top, 1.01 * width))
    ax.set_aspect("equal")
    outlines = [[p.outline] + ([] if p.hole is None else [p.hole]) for p in plate.pieces]
    names = [p.piece.name for p in plate.pieces]
    return place_labels(ax, [label_point(p) for p in plate.pieces], names, fontsize=fontsize, outlines=outlines)


def plate_figure(plate: Plate, fab: Fabrication):
    """A preview of the plate for people (not to scale): parts, their names (none
    overlapping), the butt-joint edges in green, the used strip's edge dashed and the
    utilisation in the title.

    Args:
        plate: the nested plate.
        fab: the shop settings (unit, kerf).

    Returns:
        The matplotlib Figure (never pyplot's), its layout final.
    """
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone

    length, width = plate.size
    fig = Figure(figsize=(12, 0.96 * 12 * width / length + 0.8))
    ax = fig.add_axes((0.02, 0.02, 0.96, 1.0 - 0.02 - 0.75 / fig.get_size_inches()[1]))
    ax.set_axis_off()
    ax.set_title(
        f"{plate.name}: {length:g} x {width:g} {fab.length_unit}, {len(plate.pieces)} pieces, kerf {fab.kerf:g} "
        f"(butt joints green)\n{utilisation_text(plate, fab.length_unit)}",
        fontsize=9,
    )
    draw_plate(ax, plate)
    return fig


def write_plate_picture(plate: Plate, fab: Fabrication, path: str | Path) -> Path:
    """Write :func:`plate_figure` to the PNG ``path`` (atomically); return its path."""
    from tubecad.core.atomic import save_figure

    target = Path(path)
    return save_figure(plate_figure(plate, fab), target.parent, target.stem, ("png",), dpi=120)[0]
