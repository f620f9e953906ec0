"""``tubecad shop`` on a spec with [[branches]]: each branch's cutting template, its opening's
template, its bevel basis and its pad's development, and, with [stiffeners], the shop package
of the junction's stiffeners (issue 25; the templates' geometry is
:mod:`tubecad.shop.branch_template`, the pad's :mod:`tubecad.stiffeners.pad`, the stopped
stiffeners' :mod:`tubecad.stiffeners.junction`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from tubecad.core.errors import ParameterError, RegularityError, SpecError
from tubecad.spec.junction import branch_walls
from tubecad.spec.parse import TubeSpec
from tubecad.spec.sections import in_section, spec_error

#: points of the templates round the saddle (every 0.5 deg of the branch's girth)
TEMPLATE_SAMPLES = 721


def junction_shop(spec: TubeSpec, output: Path, say: Any = None) -> dict[str, Any]:
    """``tubecad shop`` on a spec with [[branches]]: per branch k, into ``output/branches``:
    ``branch_k_template.dxf`` (the outer saddle unrolled onto the branch's outer surface, its
    cutting template, girth marks at its stringers), ``branch_k_hole.dxf`` (the bore's saddle
    on the main's inner surface: the opening), ``branch_k_bevel.csv`` (the dihedral angle
    between the outer surfaces along the saddle, the bevel's basis, at each girth position),
    and ``index.json``. With [stiffeners], the main's ring frames and stringers stopped at the
    openings (or pads) and the branches' own, as ``tubecad shop`` gives a wall's
    (:func:`tubecad.shop.package.add_stiffener_data`): web pieces nested on plates
    (``webs/``: a ring cut at an opening is the sector of the arc it keeps, a stopped
    stringer each piece's strip), developed flanges, bending tables and the pieces' solids.
    No booleans on the wall are needed: the saddles are solved on the exact surfaces.
    Written into a staging folder and moved into place once complete
    (:func:`tubecad.core.atomic.staged_folder`)."""
    import json

    from tubecad.core.atomic import staged_folder, write_text
    from tubecad.junctions import dihedral_angles, saddle_curve
    from tubecad.shop.branch_template import branch_template, hole_template, write_bevel_csv

    assert spec.wall is not None
    say = say or (lambda _stage: None)
    unit = spec.length_unit
    main_in, main_out = spec.wall.offsets()
    name = Path(str(spec.source)).stem
    index: dict[str, Any] = {"name": name, "units": {"length": unit}}
    with staged_folder(output) as staging:
        all_walls = branch_walls(spec)
        if spec.stiffeners is not None:
            index = _stiffener_shop(spec, all_walls, staging, name, say)
        index["branches"] = []
        (staging / "branches").mkdir()
        for k, walls in enumerate(all_walls):
            say(f"branch {k}: saddles and templates")
            b_in, b_out = walls.offsets()
            main_o, main_i = spec.tube.offset(main_out), spec.tube.offset(main_in)
            branch_o, branch_i = walls.surface.offset(b_out), walls.surface.offset(b_in)
            try:  # the exact saddles, densely: each polyline point on both surfaces to round-off
                outer = saddle_curve(main_o, branch_o, TEMPLATE_SAMPLES)
                inner = saddle_curve(main_i, branch_i, TEMPLATE_SAMPLES)
                assert walls.layout is not None  # branch_walls gives every branch its net
                cut = branch_template(branch_o, outer, len(walls.layout.stringers_deg), key="branches")
                hole = hole_template(main_i, inner, len(spec.layout.net(spec.tube).stringers_deg), key="tube")
            except (ParameterError, RegularityError) as exc:
                raise in_section(
                    spec.source, "branches", exc, label=f"[[branches]] #{k + 1}", key=exc.key or "branches"
                ) from None
            angles = dihedral_angles(main_o, branch_o, outer)
            base = staging / "branches" / f"branch_{k}"
            cut.save_dxf(base.with_name(f"branch_{k}_template.dxf"), unit)
            hole.save_dxf(base.with_name(f"branch_{k}_hole.dxf"), unit)
            write_bevel_csv(base.with_name(f"branch_{k}_bevel.csv"), outer.branch_u, cut, angles)
            files = [f"branches/branch_{k}_{part}" for part in ("template.dxf", "hole.dxf", "bevel.csv")]
            pad = spec.branches[k].pad
            pad_info = None
            if pad is not None:  # the pad's development with the branch's hole marked on it
                from tubecad.shop.panel_development import develop_panel, write_panel_dxf
                from tubecad.stiffeners.pad import pad_bounds

                try:
                    pad_s, pad_angles = pad_bounds(main_o, outer, pad.width)
                except ParameterError as exc:
                    raise in_section(spec.source, "branches", exc, label=f"[[branches]] #{k + 1}") from None
                development = develop_panel(main_o, pad_s, pad_angles, f"branch_{k}_pad")
                hole_line = development.map(np.degrees(outer.main_u), outer.main_s)
                write_panel_dxf([development], {development.name: [("branch", hole_line)]}, staging / "branches", unit)
                files.append(f"branches/branch_{k}_pad_development.dxf")
                pad_info = {"thickness": pad.thickness, "max_strain": development.max_strain}
            index["branches"].append(
                {
                    "branch": k,
                    "files": files,
                    "pad": pad_info,
                    "template": {"girth": cut.girth, "height": cut.height, "strain": cut.strain},
                    "hole": {"girth": hole.girth, "strain": hole.strain},
                    "dihedral_deg": {"min": float(angles.min()), "max": float(angles.max())},
                }
            )
        if "files" in index:  # the stiffeners' package lists its files: the branches' too
            index["files"] += [
                {"path": f, "kind": "branches", "what": f"branch {b['branch']}'s {f.rsplit('_', 1)[-1]}"}
                for b in index["branches"]
                for f in b["files"]
            ]
        write_text(staging / "index.json", json.dumps(index, indent=2) + "\n")
    return index


def _stiffener_shop(spec: TubeSpec, walls: list, staging: Path, name: str, say: Any) -> dict[str, Any]:
    """The junction's stiffeners' shop package written into ``staging`` (its index)."""
    from tubecad.shop.package import ShopData, add_stiffener_data
    from tubecad.shop.writer import write_shop
    from tubecad.spec.junction import build_junction_stiffeners
    from tubecad.spec.model import FabricationSection

    try:
        fab = (spec.fabrication or FabricationSection()).settings(spec.length_unit)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key or "fabrication") from None
    say("stiffeners stopped at the openings")
    stiffeners = build_junction_stiffeners(spec, walls)
    data = ShopData(None, stiffeners, [], fab)
    try:
        add_stiffener_data(data, tuple(spec.layout.net(spec.tube).stringers_deg), spec.fit.tolerance, say)
    except ParameterError as exc:  # a [fabrication] value the pieces cannot have (a plate too small, a joint)
        raise spec_error(spec.source, exc, ("fabrication",)) from None
    say("writing the stiffeners' files")
    return write_shop(data, staging, name)
