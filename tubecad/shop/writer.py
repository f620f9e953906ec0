"""Writing the shop package (tubecad.shop.package) into a folder: every file atomically,
then ``index.json`` listing each file with what it is, and the one-page overview."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from tubecad.core.atomic import save_figure, write_text
from tubecad.shop.drawings import draw_plate, utilisation_text, write_plate_dxf, write_plate_picture, write_plate_svg
from tubecad.shop.nesting import Plate, check_nesting
from tubecad.shop.package import ShopData

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def write_shop(data: ShopData, folder: str | Path, name: str = "tubecad", step_schema: str = "AP214") -> dict[str, Any]:
    """Write ``data`` into ``folder`` (created if needed); returns the index (also written
    as index.json). Paths in the index are relative to ``folder``."""
    folder = Path(folder)
    fab = data.fab
    unit = fab.length_unit
    files: list[dict[str, str]] = []

    def record(path: Path, kind: str, what: str) -> None:
        files.append({"path": path.relative_to(folder).as_posix(), "kind": kind, "what": what})

    for sub in ("webs", "flanges", "bending", "marking", "panels", "pin_jig"):
        (folder / sub).mkdir(parents=True, exist_ok=True)
    index: dict[str, Any] = {"name": name, "units": {"length": unit}, "fabrication": _settings(fab)}

    # webs: nested plates 1:1 and the 3-D pieces
    index["webs"] = _plates(data.web_plates, fab, folder / "webs", "webs", record)
    index["webs"]["pieces"] = [_piece(p, data.web_plates) for p in data.web_pieces]
    step = folder / "webs" / "webs_pieces.step"
    _write_pieces_step(data, step, name, step_schema)
    record(
        step,
        "webs",
        f"{'the wall and ' if data.build is not None else ''}the stiffeners split at the web pieces' butt joints "
        "(STEP, named stringer_02_a, ...)",
    )
    index["webs"]["solids"] = [{"name": st.name, "volume": _volume(st.solid)} for st in data.piece_stiffeners]

    # flanges
    index["flanges"] = _plates(data.flange_plates, fab, folder / "flanges", "flanges", record)
    index["flanges"]["pieces"] = [_piece(p, data.flange_plates) for p in data.flange_pieces]

    # bending tables
    if data.bending:
        from tubecad.shop.bending import write_bending_csv, write_bending_picture

        path = write_bending_csv(data.bending, folder / "bending" / "bending.csv", unit)
        record(path, "bending", "bending tables and inverse bending curves, a row per station (CSV)")
        for path in write_bending_picture(_variety_first(data.bending), folder / "bending", "bending"):
            record(path, "bending", "offsets from the chord and inverse bending curves (picture)")
    index["bending"] = [
        {
            "name": t.name,
            "line": t.line,
            "length": t.length,
            "stations": len(t.arc_length),
            "spacing": float(np.diff(t.arc_length).max()) if len(t.arc_length) > 1 else t.length,
            "largest_offset": float(np.hypot(t.offset_y, t.offset_z).max()),
            "bend_back_error": t.bend_back_error,
        }
        for t in data.bending
    ]

    # panels: marking lines in STEP, developments, pin jigs
    index["panels"], index["marking"], index["pin_jig"] = [], [], []
    if data.panels:
        _write_panels(data, folder, step_schema, index, record)
    index["warnings"] = list(data.warnings)
    for path in write_overview(data, folder, index):
        record(path, "overview", "one page: a plate of webs, the most strained panel, its pin jig, a bending table")
    index["files"] = files
    write_text(folder / "index.json", json.dumps(index, indent=1) + "\n")
    return index


def _variety_first(tables: list) -> list:
    """The tables with one of each kind of line of each stiffener first (the picture shows
    the first few), then the rest in order."""
    first: dict[tuple[str, str], Any] = {}
    for t in tables:
        first.setdefault((t.name.split("_")[0], t.line), t)
    chosen = list(first.values())
    return chosen + [t for t in tables if all(t is not c for c in chosen)]


def _settings(fab) -> dict[str, Any]:
    return {
        "plate_size": list(fab.plate_size),
        "kerf": fab.kerf,
        "joint_gap": fab.joint_gap,
        "max_strain": fab.max_strain,
        "pin_spacing": fab.pin_spacing,
        "pin_clearance": fab.pin_clearance,
        "joints": {k: list(v) for k, v in fab.joints.items()},
        "bend_back_tolerance": fab.bend_back_tolerance,
    }


def _plates(plates: list[Plate], fab, sub: Path, kind: str, record) -> dict[str, Any]:
    for plate in plates:
        what = f"{plate.name}: {len(plate.pieces)} {kind} pieces nested, 1:1"
        record(write_plate_dxf(plate, fab, sub / f"{kind}_{plate.name}.dxf"), kind, what + " (DXF for cutting)")
        record(write_plate_svg(plate, fab, sub / f"{kind}_{plate.name}.svg"), kind, what + " (SVG, mm)")
        record(write_plate_picture(plate, fab, sub / f"{kind}_{plate.name}.png"), kind, what + " (preview picture)")
    return {"nesting": check_nesting(plates, fab)}


def _piece(piece, plates: list[Plate]) -> dict[str, Any]:
    plate = next((p.name for p in plates if any(q.piece is piece for q in p.pieces)), None)
    pattern = piece.pattern
    return {
        "name": piece.name,
        "stiffener": piece.stiffener,
        "kind": piece.kind,
        "span": list(piece.span),
        "span_of": "s" if piece.kind in ("stringer", "flange") else "degrees round the ring",
        "area": pattern.area,
        "base_length": pattern.base_length,
        "top_length": pattern.top_length,
        "joints": {"start": bool(piece.joints[0]), "end": bool(piece.joints[1])},
        "plate": plate,
    }


def _volume(solid) -> float:
    from tubecad.brep.properties import volume

    return volume(solid)


def _write_pieces_step(data: ShopData, path: Path, name: str, step_schema: str) -> None:
    import build123d as bd

    from tubecad.export.cad import export_named_step
    from tubecad.stiffeners.assembly import named_assembly, stiffener_solids

    if data.build is None:  # a junction's stiffeners: the pieces alone (tubecad build writes the wall)
        assembly = bd.Compound(label="tubecad", children=stiffener_solids(data.piece_stiffeners))
    else:
        assembly = named_assembly(data.build, data.piece_stiffeners, panels=data.panels)
    export_named_step(assembly, path, step_schema, name, data.fab.length_unit)


def _write_panels(data: ShopData, folder: Path, step_schema: str, index: dict, record) -> None:
    from tubecad.export.cad import export_named_step
    from tubecad.shop.marking import marking_surface, panel_assembly
    from tubecad.shop.panel_development import write_panel_dxf, write_panel_picture
    from tubecad.shop.pin_jig import write_pin_jig_csv, write_pin_jig_picture

    fab = data.fab
    assert data.build is not None  # panels are a wall's (a junction has none yet)
    side = data.stiffeners[0].side if data.stiffeners else "outside"
    surface = marking_surface(data.build, side)
    flat_marks = {}
    for panel, dev in zip(data.panels, data.developments):
        lines = data.marking[panel.name]
        step = folder / "marking" / f"{panel.name}_marking.step"
        export_named_step(
            panel_assembly(panel, lines, surface), step, step_schema, f"{panel.name}_marking", fab.length_unit
        )
        record(step, "marking", f"{panel.name} with its stiffeners' marking lines on its {side} surface (STEP)")
        index["marking"].append(
            {
                "panel": panel.name,
                "surface": side,
                "lines": [{"name": m.name, "kind": m.kind, "value": m.value, "extent": list(m.extent)} for m in lines],
            }
        )
        flat_marks[panel.name] = [
            (m.name, dev.ring_line(m.value) if m.kind == "ring" else dev.stringer_line(m.value)) for m in lines
        ]
        flagged = dev.max_strain > fab.max_strain
        if flagged:
            data.warnings.append(
                f"{panel.name}: its development strains {dev.max_strain:.3g}, more than max_strain = {fab.max_strain:g}"
            )
        index["panels"].append(
            {
                "name": panel.name,
                "s": list(panel.s_range),
                "angles_deg": list(panel.angles_deg),
                "max_strain": dev.max_strain,
                "max_strain_at": {"angle_deg": dev.max_strain_at[0], "s": dev.max_strain_at[1]},
                "max_strain_point": [float(x) for x in dev.max_strain_point],
                "surface_area": dev.surface_area,
                "flat_area": dev.flat_area,
                "exceeds_max_strain": bool(flagged),
            }
        )
    for path in write_panel_dxf(data.developments, flat_marks, folder / "panels", fab.length_unit):
        record(path, "panels", f"{path.stem.replace('_development', '')}: development with marking lines (DXF, 1:1)")
    for dev in data.developments:
        for path in write_panel_picture(dev, flat_marks[dev.name], folder / "panels", ("png",)):
            record(path, "panels", f"{dev.name}: development, marking lines and strain (picture)")
    for jig in data.pin_jigs:
        path = write_pin_jig_csv(jig, folder / "pin_jig" / f"{jig.name}_pin_jig.csv", fab.length_unit)
        record(path, "pin_jig", f"{jig.name}: pin heights above the jig plane (CSV)")
        for path in write_pin_jig_picture(jig, folder / "pin_jig", ("png",)):
            record(path, "pin_jig", f"{jig.name}: pin heights (picture)")
        index["pin_jig"].append(
            {
                "panel": jig.name,
                "pins": int(len(jig.heights)),
                "spacing": jig.spacing,
                "lowest": float(jig.heights.min()) if len(jig.heights) else None,
                "highest": float(jig.heights.max()) if len(jig.heights) else None,
                "origin": [float(x) for x in jig.origin],
                "x_dir": [float(x) for x in jig.x_dir],
                "y_dir": [float(x) for x in jig.y_dir],
                "up": [float(x) for x in jig.up],
            }
        )


def write_overview(data: ShopData, folder: Path, index: dict) -> list[Path]:
    """overview.png and overview.svg: one page of what the folder holds (:func:`overview_figure`).

    Args:
        data: the shop package.
        folder: where to write.
        index: the package's index (its ``name`` titles the page).

    Returns:
        The two paths.
    """
    return save_figure(overview_figure(data, index["name"]), folder, "overview", ("png", "svg"))


#: the overview's width, its title's (per line), its plate's title's and its lower row's heights (inches)
OVERVIEW_WIDTH, TITLE_LINE, PLATE_TITLE, LOWER_ROW = 14.0, 0.25, 0.45, 4.6


def overview_figure(data: ShopData, name: str) -> Figure:
    """One page of a shop package: the first plate of webs across the top (its pieces named,
    no name over another), and below it only the panels there is something for: the most
    strained panel's development, its pin jig, the bending table with the largest offset.
    What is missing (no panels, no pin jig) is said in the title, not drawn as an empty panel.

    Args:
        data: the shop package.
        name: the package's name, for the title.

    Returns:
        The matplotlib Figure (never pyplot's), its layout final.
    """
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone

    lower = _lower_panels(data)
    plate = data.web_plates[0] if data.web_plates else None
    inner = OVERVIEW_WIDTH - 0.6
    shown, top = 0.0, 0.0  # how far up the plate is shown (model units), how tall its row is (inches)
    if plate is not None:
        shown = _plate_view(plate, inner)
        top = inner * (shown + 0.01 * plate.size[1]) / (1.02 * plate.size[0]) + PLATE_TITLE
    title = _overview_title(data, name)
    head = 0.3 + TITLE_LINE * (title.count("\n") + 1)
    height = head + top + (LOWER_ROW if lower else 0.0)
    fig = Figure(figsize=(OVERVIEW_WIDTH, height))
    fig.suptitle(title, fontsize=11, y=1.0 - 0.15 / height, va="top")
    if lower:
        grid = fig.add_gridspec(
            1, len(lower), left=0.06, right=0.96, bottom=0.6 / height, top=(LOWER_ROW - 0.55) / height, wspace=0.35
        )
        for k, draw in enumerate(lower):
            draw(fig.add_subplot(grid[0, k]), fig)
    if plate is not None:  # last: its names are placed once the page's layout is final
        box = (
            0.3 / OVERVIEW_WIDTH,
            (height - head - top) / height,
            inner / OVERVIEW_WIDTH,
            (top - PLATE_TITLE) / height,
        )
        _draw_webs_plate(fig.add_axes(box), data, plate, shown)
    return fig


def _draw_webs_plate(ax, data: ShopData, plate: Plate, shown: float) -> None:
    """The first plate of webs, up to ``shown`` (its used strip and room for the names)."""
    ax.set_axis_off()
    unit = data.fab.length_unit
    ax.set_title(
        f"webs: {plate.name} of {len(data.web_plates)} ({plate.size[0]:g} x {plate.size[1]:g} {unit}), "
        f"{len(plate.pieces)} pieces; {utilisation_text(plate, unit)}",
        fontsize=9,
    )
    draw_plate(ax, plate, fontsize=7.0, top=shown)


#: the plate's picture on the overview: at most this tall, at least this tall where the plate is (inches)
PLATE_MAX, PLATE_MIN = 7.0, 2.4


def _plate_view(plate: Plate, width_in: float) -> float:
    """How far up the plate the overview shows it: its used strip with a fifth more for the
    names, at least PLATE_MIN inches tall where the plate is, and no more than the plate or
    PLATE_MAX inches, drawn ``width_in`` inches wide."""
    length, width = plate.size
    used = plate.used_size[1]
    inches = length / width_in  # model units per inch
    return min(1.01 * width, max(1.2 * used, PLATE_MIN * inches), PLATE_MAX * inches)


def _overview_title(data: ShopData, name: str) -> str:
    """The page's title: what the package holds, and what it lacks and why."""
    title = (
        f"{name}: shop package ({len(data.web_pieces)} web pieces on {len(data.web_plates)} plates, "
        f"{len(data.flange_pieces)} flange pieces, {len(data.bending)} bending tables, {len(data.panels)} panels)"
    )
    if not data.developments:
        why = "the wall is not split into panels" if data.build is not None else "a junction has no panels yet"
        title += f"\nno panel developments or pin jigs: {why}"
    elif not any(len(j.heights) for j in data.pin_jigs):
        title += "\nno pin jig (see the warnings in index.json)"
    return title


def _lower_panels(data: ShopData) -> list[Callable[[Any, Figure], None]]:
    """The lower row's drawers, only of what the package has."""
    panels: list[Callable[[Any, Figure], None]] = []
    if data.developments:
        dev = max(data.developments, key=lambda d: d.max_strain)
        panels.append(lambda ax, fig: _draw_development(ax, fig, data, dev))
        jig = next((j for j in data.pin_jigs if j.name == dev.name), data.pin_jigs[0] if data.pin_jigs else None)
        if jig is not None and len(jig.heights):
            panels.append(lambda ax, fig: _draw_pin_jig(ax, fig, jig, data.fab.length_unit))
    if data.bending:
        panels.append(lambda ax, _fig: _draw_bending(ax, data, data.fab.length_unit))
    return panels


def _draw_development(ax, fig: Figure, data: ShopData, dev) -> None:
    """The panel ``dev`` developed: its strain, outline and marking lines."""
    grid = dev.grid
    mesh = ax.pcolormesh(grid[..., 0], grid[..., 1], dev.strain, shading="gouraud", cmap="viridis", rasterized=True)
    fig.colorbar(mesh, ax=ax, label="largest principal strain")
    ax.plot(*np.vstack([dev.outline(), dev.outline()[:1]]).T, color="#10203a", lw=0.8)
    for mark in data.marking.get(dev.name, []):
        line = dev.ring_line(mark.value) if mark.kind == "ring" else dev.stringer_line(mark.value)
        ax.plot(line[:, 0], line[:, 1], color="#d04020", lw=0.8)
    ax.set_aspect("equal")
    ax.set_title(
        f"{dev.name} developed (the most strained panel)\nmax strain {dev.max_strain:.3g} at "
        f"{dev.max_strain_at[0]:.4g} deg, s = {dev.max_strain_at[1]:.6g}; marking lines red",
        fontsize=9,
    )


def _draw_pin_jig(ax, fig: Figure, jig, unit: str) -> None:
    """A panel's pin jig: the pins coloured by height, the panel's outline."""
    dots = ax.scatter(jig.xy[:, 0], jig.xy[:, 1], c=jig.heights, cmap="magma", s=25)
    fig.colorbar(dots, ax=ax, label=f"pin height ({unit})")
    ax.plot(*np.vstack([jig.outline, jig.outline[:1]]).T, color="#10203a", lw=0.8)
    ax.set_aspect("equal")
    ax.set_title(
        f"{jig.name} pin jig: {len(jig.heights)} pins at {jig.spacing:g} {unit},\nheights "
        f"{jig.heights.min():.4g} to {jig.heights.max():.4g}",
        fontsize=9,
    )


def _draw_bending(ax, data: ShopData, unit: str) -> None:
    """The bending table with the largest offset from its chord, and its inverse curve."""
    table = max(data.bending, key=lambda t: float(np.abs(t.offset_y).max()))
    ax.plot(table.arc_length, table.offset_y, "o-", ms=3, label="offset from the chord")
    ax.plot(table.arc_length, table.inverse_y, "s--", ms=3, label="inverse bending curve")
    ax.legend(fontsize=8, loc="best")
    ax.set_xlabel(f"arc length ({unit})")
    ax.set_ylabel(f"offset ({unit})")
    ax.set_title(
        f"bending table {table.name} ({table.line}):\n{len(table.arc_length)} stations, bend-back "
        f"error {table.bend_back_error:.2g} {unit}",
        fontsize=9,
    )
