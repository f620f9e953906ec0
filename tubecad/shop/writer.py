"""Writing the shop package (tubecad.shop.package) into a folder: every file atomically,
then ``index.json`` listing each file with what it is, and the one-page overview."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from tubecad.core.atomic import save_figure, write_text
from tubecad.shop.drawings import write_plate_dxf, write_plate_picture, write_plate_svg
from tubecad.shop.nesting import Plate, check_nesting
from tubecad.shop.package import ShopData


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
        _write_panels(data, folder, name, step_schema, index, record)
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


def _write_panels(data: ShopData, folder: Path, name: str, step_schema: str, index: dict, record) -> None:
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
                f"{panel.name}: its development strains {dev.max_strain:.3g}, more than "
                f"[fabrication] max_strain = {fab.max_strain:g}"
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
    """overview.png and overview.svg: one page of what the folder holds."""
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone
    from matplotlib.patches import Polygon as Patch

    fig = Figure(figsize=(14, 9.5))
    axes = fig.subplots(2, 2)
    (a_plate, a_panel), (a_jig, a_bend) = axes
    unit = data.fab.length_unit
    if data.web_plates:
        plate = data.web_plates[0]
        a_plate.add_patch(
            Patch(
                [(0, 0), (plate.size[0], 0), plate.size, (0, plate.size[1])],
                closed=True,
                facecolor="#f2f2f2",
                edgecolor="#555555",
            )
        )
        for placed in plate.pieces:
            a_plate.add_patch(Patch(placed.outline, closed=True, facecolor="#c9d6ea", edgecolor="#10203a", lw=0.5))
            if placed.hole is not None:
                a_plate.add_patch(Patch(placed.hole, closed=True, facecolor="#f2f2f2", edgecolor="#10203a", lw=0.5))
            x, y = placed.polygon().representative_point().coords[0]
            a_plate.text(x, y, placed.piece.name, fontsize=5, ha="center", va="center")
        a_plate.set_xlim(-0.02 * plate.size[0], 1.02 * plate.size[0])
        a_plate.set_ylim(-0.02 * plate.size[1], 1.02 * plate.size[1])
        nesting = index["webs"]["nesting"]
        a_plate.set_title(
            f"webs: {plate.name} of {nesting['plates']} ({plate.size[0]:g} x {plate.size[1]:g} {unit}), "
            f"{len(plate.pieces)} pieces, utilisation {100 * plate.utilisation:.1f} %",
            fontsize=9,
        )
    a_plate.set_aspect("equal")
    if data.developments:
        dev = max(data.developments, key=lambda d: d.max_strain)
        grid = dev.grid
        mesh = a_panel.pcolormesh(
            grid[..., 0], grid[..., 1], dev.strain, shading="gouraud", cmap="viridis", rasterized=True
        )
        fig.colorbar(mesh, ax=a_panel, label="largest principal strain")
        a_panel.plot(*np.vstack([dev.outline(), dev.outline()[:1]]).T, color="#10203a", lw=0.8)
        for mark in data.marking.get(dev.name, []):
            line = dev.ring_line(mark.value) if mark.kind == "ring" else dev.stringer_line(mark.value)
            a_panel.plot(line[:, 0], line[:, 1], color="#d04020", lw=0.8)
        a_panel.set_aspect("equal")
        a_panel.set_title(
            f"{dev.name} developed (the most strained panel)\nmax strain {dev.max_strain:.3g} at "
            f"{dev.max_strain_at[0]:.4g} deg, s = {dev.max_strain_at[1]:.6g}; marking lines red",
            fontsize=9,
        )
        jig = next((j for j in data.pin_jigs if j.name == dev.name), data.pin_jigs[0] if data.pin_jigs else None)
        if jig is not None and len(jig.heights):
            dots = a_jig.scatter(jig.xy[:, 0], jig.xy[:, 1], c=jig.heights, cmap="magma", s=25)
            fig.colorbar(dots, ax=a_jig, label=f"pin height ({unit})")
            a_jig.plot(*np.vstack([jig.outline, jig.outline[:1]]).T, color="#10203a", lw=0.8)
            a_jig.set_aspect("equal")
            a_jig.set_title(
                f"{jig.name} pin jig: {len(jig.heights)} pins at {jig.spacing:g} {unit}, heights "
                f"{jig.heights.min():.4g} to {jig.heights.max():.4g}",
                fontsize=9,
            )
        else:
            a_jig.text(0.5, 0.5, "no pin jig (see the warnings in index.json)", ha="center", va="center")
            a_jig.set_axis_off()
    else:
        why = "the spec has no [panels] section" if data.build is not None else "a junction has no panels yet"
        for ax, what in ((a_panel, "panel developments"), (a_jig, "pin jigs")):
            ax.text(0.5, 0.5, f"no {what}: {why}", ha="center", va="center")
            ax.set_axis_off()
    if data.bending:
        table = max(data.bending, key=lambda t: float(np.abs(t.offset_y).max()))
        a_bend.plot(table.arc_length, table.offset_y, "o-", ms=3, label="offset from the chord")
        a_bend.plot(table.arc_length, table.inverse_y, "s--", ms=3, label="inverse bending curve")
        a_bend.legend(fontsize=8)
        a_bend.set_xlabel(f"arc length ({unit})")
        a_bend.set_title(
            f"bending table {table.name} ({table.line}): {len(table.arc_length)} stations, bend-back "
            f"error {table.bend_back_error:.2g} {unit}",
            fontsize=9,
        )
    fig.suptitle(
        f"{index['name']}: shop package ({len(data.web_pieces)} web pieces on {len(data.web_plates)} plates, "
        f"{len(data.flange_pieces)} flange pieces, {len(data.bending)} bending tables, {len(data.panels)} panels)"
    )
    fig.tight_layout()
    return save_figure(fig, folder, "overview", ("png", "svg"))
