"""A junction's shop package (issue 25): each branch's cutting template, its opening's
template, its bevel basis and its pad's development, and the shop package of the junction's
stiffeners (the templates' geometry is :mod:`tubecad.shop.branch_template`, the pad's
:mod:`tubecad.stiffeners.pad`, the stopped stiffeners' :mod:`tubecad.stiffeners.junction`).
No booleans on the wall are needed: the saddles are solved on the exact surfaces."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tubecad.design.stages import stage

if TYPE_CHECKING:
    import numpy as np

    from tubecad.design.model import BranchDesign
    from tubecad.design.wall import WallDesign
    from tubecad.shop.branch_template import BranchTemplate
    from tubecad.shop.fabrication import Fabrication
    from tubecad.shop.package import ShopData
    from tubecad.shop.panel_development import PanelDevelopment

#: points of the templates round the saddle (every 0.5 deg of the branch's girth)
TEMPLATE_SAMPLES = 721


@dataclass
class PadShop:
    """A pad's ``development`` (:class:`tubecad.shop.panel_development.PanelDevelopment`), the
    branch's ``line`` on it and its ``thickness``."""

    development: PanelDevelopment
    line: np.ndarray
    thickness: float


@dataclass
class BranchShop:
    """Branch ``k``'s shop data: the cutting template ``cut`` (the outer saddle unrolled onto
    the branch's outer surface), the opening ``hole`` (the bore's saddle on the main's inner
    surface), the saddle's branch angles ``branch_u`` and the ``dihedral`` angles (degrees)
    between the outer surfaces there; with a pad, its ``pad``."""

    k: int
    cut: BranchTemplate
    hole: BranchTemplate
    branch_u: np.ndarray
    dihedral: np.ndarray
    pad: PadShop | None = None

    def write(self, folder: Path, unit: str) -> dict[str, Any]:
        """The branch's files into ``folder/branches`` and its entry of the index."""
        from tubecad.shop.branch_template import write_bevel_csv

        k, base = self.k, folder / "branches"
        self.cut.save_dxf(base / f"branch_{k}_template.dxf", unit)
        self.hole.save_dxf(base / f"branch_{k}_hole.dxf", unit)
        write_bevel_csv(base / f"branch_{k}_bevel.csv", self.branch_u, self.cut, self.dihedral)
        files = [f"branches/branch_{k}_{part}" for part in ("template.dxf", "hole.dxf", "bevel.csv")]
        pad_info = None
        if self.pad is not None:  # the pad's development with the branch's hole marked on it
            from tubecad.shop.panel_development import write_panel_dxf

            development = self.pad.development
            write_panel_dxf([development], {development.name: [("branch", self.pad.line)]}, base, unit)
            files.append(f"branches/branch_{k}_pad_development.dxf")
            pad_info = {"thickness": self.pad.thickness, "max_strain": development.max_strain}
        return {
            "branch": k,
            "files": files,
            "pad": pad_info,
            "template": {"girth": self.cut.girth, "height": self.cut.height, "strain": self.cut.strain},
            "hole": {"girth": self.hole.girth, "strain": self.hole.strain},
            "dihedral_deg": {"min": float(self.dihedral.min()), "max": float(self.dihedral.max())},
        }


@dataclass
class JunctionShop:
    """A junction's shop package: each branch's (:class:`BranchShop`) and, with stiffeners,
    theirs (:class:`tubecad.shop.package.ShopData`, the wall itself being ``tubecad build``'s)."""

    branches: list[BranchShop]
    stiffeners: ShopData | None
    length_unit: str

    def write(self, folder: Path, name: str) -> dict[str, Any]:
        """Per branch k, into ``folder/branches``: ``branch_k_template.dxf`` (its cutting
        template, girth marks at its stringers), ``branch_k_hole.dxf`` (the opening),
        ``branch_k_bevel.csv`` (the dihedral angle along the saddle, the bevel's basis, at
        each girth position), ``branch_k_pad_development.dxf`` with a pad; with stiffeners
        the package :func:`tubecad.shop.writer.write_shop` writes (web pieces nested on
        plates, flanges, bending tables, the pieces' solids); ``index.json``."""
        import json

        from tubecad.core.atomic import write_text
        from tubecad.shop.writer import write_shop

        index: dict[str, Any] = {"name": name, "units": {"length": self.length_unit}}
        if self.stiffeners is not None:
            index = write_shop(self.stiffeners, folder, name)
        (folder / "branches").mkdir()
        index["branches"] = [branch.write(folder, self.length_unit) for branch in self.branches]
        if "files" in index:  # the stiffeners' package lists its files: the branches' too
            index["files"] += [
                {"path": f, "kind": "branches", "what": f"branch {b['branch']}'s {f.rsplit('_', 1)[-1]}"}
                for b in index["branches"]
                for f in b["files"]
            ]
        write_text(folder / "index.json", json.dumps(index, indent=2) + "\n")
        return index


def junction_shop(
    main: WallDesign,
    branches: Sequence[BranchDesign],
    fab: Fabrication,
    progress: Callable[[str], None] | None = None,
) -> JunctionShop:
    """The shop package of the ``main`` wall with ``branches`` joined on, with the fabrication
    settings ``fab``: with stiffeners, the main's ring frames and stringers stopped at the
    openings (or pads) and the branches' own (:func:`tubecad.shop.package.add_stiffener_data`:
    a ring cut at an opening is the sector of the arc it keeps, a stopped stringer each
    piece's strip); per branch its templates (:func:`branch_shop`). ``progress(stage)``
    hears of each stage."""
    from tubecad.design.junction_parts import branch_walls, junction_stiffeners
    from tubecad.design.junction_shell import refuse_blends
    from tubecad.shop.package import ShopData, add_stiffener_data

    refuse_blends(branches, "the shop package (the templates are cut on the saddle)")
    say = progress or (lambda _stage: None)
    walls = branch_walls(branches)
    data = None
    if main.stiffeners is not None:
        say("stiffeners stopped at the openings")
        data = ShopData(None, junction_stiffeners(main, branches, walls), [], fab)
        with stage("fabrication"):
            add_stiffener_data(data, tuple(main.layout.stringers_deg), main.tolerance, say)
    shops = []
    for k, branch in enumerate(branches):
        say(f"branch {k}: saddles and templates")
        shops.append(branch_shop(main, branch, k))
    return JunctionShop(shops, data, main.length_unit)


def branch_shop(main: WallDesign, branch: BranchDesign, k: int) -> BranchShop:
    """Branch ``k``'s (``branch`` on ``main``) templates: the exact saddles solved densely
    (every polyline point on both surfaces to round-off), the cut unrolled onto the branch,
    the hole onto the main, the dihedral angles, and the pad's development
    (:func:`tubecad.shop.panel_development.develop_panel`)."""
    import numpy as np

    from tubecad.junctions import dihedral_angles, saddle_curve
    from tubecad.shop.branch_template import branch_template, hole_template

    assert main.wall is not None  # a junction joins walls
    main_in, main_out = main.wall.offsets()
    b_in, b_out = branch.wall.offsets()
    main_o, main_i = main.surface.offset(main_out), main.surface.offset(main_in)
    branch_o, branch_i = branch.surface.offset(b_out), branch.surface.offset(b_in)
    with stage("templates", k):
        outer = saddle_curve(main_o, branch_o, TEMPLATE_SAMPLES)
        inner = saddle_curve(main_i, branch_i, TEMPLATE_SAMPLES)
        cut = branch_template(branch_o, outer, len(branch.layout.stringers_deg))
        hole = hole_template(main_i, inner, len(main.layout.stringers_deg))
    shop = BranchShop(k, cut, hole, outer.branch_u, dihedral_angles(main_o, branch_o, outer))
    if branch.pad is not None:
        from tubecad.shop.panel_development import develop_panel
        from tubecad.stiffeners.pad import pad_bounds

        with stage("pads", k):
            pad_s, pad_angles = pad_bounds(main_o, outer, branch.pad.width)
        development = develop_panel(main_o, pad_s, pad_angles, f"branch_{k}_pad")
        line = development.map(np.degrees(outer.main_u), outer.main_s)
        shop.pad = PadShop(development, line, branch.pad.thickness)
    return shop
