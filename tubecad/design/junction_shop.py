"""A junction's shop package (issue 25): each branch's cutting template, its opening's
template, its bevel basis and its pad's development, and the shop package of the junction's
stiffeners (the templates' geometry is :mod:`tubecad.shop.branch_template`, the pad's
:mod:`tubecad.stiffeners.pad`, the stopped stiffeners' :mod:`tubecad.stiffeners.junction`).
No booleans on the wall are needed: the saddles are solved on the exact surfaces."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from tubecad.design.stages import stage

if TYPE_CHECKING:
    import numpy as np

    from tubecad.design.model import BranchDesign
    from tubecad.design.wall import WallDesign
    from tubecad.junctions.saddle import SaddleCurve
    from tubecad.shop.blend_strips import BlendStrip
    from tubecad.shop.branch_template import BranchTemplate
    from tubecad.shop.fabrication import Fabrication
    from tubecad.shop.package import ShopData
    from tubecad.shop.panel_development import PanelDevelopment
    from tubecad.surface.protocol import CurvatureLineSurface

#: points of the templates round the saddle (every 0.5 deg of the branch's girth)
TEMPLATE_SAMPLES = 721
#: how far the panel of a hole on a main whose radius varies reaches beyond the opening, as a
#: share of the branch's bore radius
HOLE_MARGIN = 0.1


@dataclass
class PadShop:
    """A pad's ``development`` (:class:`tubecad.shop.panel_development.PanelDevelopment`), the
    branch's ``line`` on it and its ``thickness``."""

    development: PanelDevelopment
    line: np.ndarray
    thickness: float


class OpeningTemplate(Protocol):
    """A developed line's drawing: on a tube's strip (:class:`~tubecad.shop.branch_template.BranchTemplate`)
    or on a panel of a main whose radius varies (:class:`~tubecad.shop.hole_development.HolePanel`)."""

    def save_dxf(self, path: Path, unit: str = "mm") -> Path: ...

    def info(self) -> dict[str, Any]: ...


@dataclass
class BlendShop:
    """A crotch blend's shop data: its ball's ``radius``, its toe on the main (``toe_main``:
    drawn on the main's outer surface with the outer saddle) and its ``strips``
    (:mod:`tubecad.shop.blend_strips`), which develop where their largest strain is within
    ``max_strain`` (the fabrication's)."""

    radius: float
    toe_main: OpeningTemplate
    strips: list[BlendStrip]
    max_strain: float

    def write(self, base: Path, k: int, unit: str) -> tuple[list[str], dict[str, Any]]:
        """``branch_k_blend_main.dxf`` and the strips' developments into ``base``
        (``branch_k_blend/``); the files and the index's entry."""
        from tubecad.shop.panel_development import write_panel_dxf

        self.toe_main.save_dxf(base / f"branch_{k}_blend_main.dxf", unit)
        folder = base / f"branch_{k}_blend"
        folder.mkdir()
        developments = [strip.development for strip in self.strips]
        write_panel_dxf(developments, {s.development.name: s.toes for s in self.strips}, folder, unit)
        files = [f"branches/branch_{k}_blend_main.dxf"]
        files += [f"branches/branch_{k}_blend/{d.name}_development.dxf" for d in developments]
        strips = [
            {
                "name": d.name,
                "s_range": list(d.s_range),
                "max_strain": d.max_strain,
                "develops": d.max_strain <= self.max_strain,
            }
            for d in developments
        ]
        info = {
            "radius": self.radius,
            "toe_main": self.toe_main.info(),
            "strips": strips,
            "develops": all(strip["develops"] for strip in strips),
        }
        return files, info


@dataclass
class BranchShop:
    """Branch ``k``'s shop data: the cutting template ``cut`` (the outer saddle unrolled onto
    the branch's outer surface; with a blend, its toe on the branch too), the opening ``hole``
    (the bore's saddle on the main's inner surface: on its strip, or where the main's radius
    varies on a panel of it round the opening, :mod:`tubecad.shop.hole_development`), the
    saddle's branch angles ``branch_u`` and the ``dihedral`` angles (degrees) between the
    outer surfaces there; with a pad, its ``pad``; with a crotch blend, its ``blend``."""

    k: int
    cut: BranchTemplate
    hole: OpeningTemplate
    branch_u: np.ndarray
    dihedral: np.ndarray
    pad: PadShop | None = None
    blend: BlendShop | None = None

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
        blend_info = None
        if self.blend is not None:
            blend_files, blend_info = self.blend.write(base, k, unit)
            files += blend_files
        return {
            "branch": k,
            "files": files,
            "pad": pad_info,
            "blend": blend_info,
            "template": self.cut.info(),
            "hole": self.hole.info(),
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
    from tubecad.shop.package import ShopData, add_stiffener_data

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
        shops.append(branch_shop(main, branch, k, fab.max_strain))
    return JunctionShop(shops, data, main.length_unit)


def branch_shop(main: WallDesign, branch: BranchDesign, k: int, max_strain: float = 0.01) -> BranchShop:
    """Branch ``k``'s (``branch`` on ``main``) templates: the exact saddles solved densely
    (every polyline point on both surfaces to round-off), the cut unrolled onto the branch,
    the hole onto the main (:func:`on_main`), the dihedral angles, and the pad's development
    (:func:`tubecad.shop.panel_development.develop_panel`). With a crotch blend of radius rb
    (welded: the pipes are cut as without it) its toes are the saddle of the outer surfaces
    offset by rb (the ball's centre curve) read on each: on the branch drawn on the cutting
    template (layer ``blend_toe``), on the main in ``branch_k_blend_main.dxf`` (with the outer
    saddle, layer ``saddle_outer``, on a strip); its strips developed
    (:func:`tubecad.shop.blend_strips.blend_strips`), developing within ``max_strain``."""
    import numpy as np

    from tubecad.junctions import dihedral_angles, saddle_curve
    from tubecad.shop.branch_template import branch_template

    assert main.wall is not None  # a junction joins walls
    main_in, main_out = main.wall.offsets()
    b_in, b_out = branch.wall.offsets()
    main_o, main_i = main.surface.offset(main_out), main.surface.offset(main_in)
    branch_o, branch_i = branch.surface.offset(b_out), branch.surface.offset(b_in)
    stringers = list(main.layout.stringers_deg)
    margin = HOLE_MARGIN * float(branch_i.radius_law.r(branch_i.span[0]))
    with stage("templates", k):
        outer = saddle_curve(main_o, branch_o, TEMPLATE_SAMPLES)
        inner = saddle_curve(main_i, branch_i, TEMPLATE_SAMPLES)
        cut = branch_template(branch_o, outer, len(branch.layout.stringers_deg))
        hole = on_main(main_i, inner, stringers, margin, f"branch_{k}_hole")
    shop = BranchShop(k, cut, hole, outer.branch_u, dihedral_angles(main_o, branch_o, outer))
    if branch.blend is not None:
        from dataclasses import replace

        from tubecad.junctions.blend import rolling_ball
        from tubecad.shop.blend_strips import blend_strips

        with stage("branches", k):
            ball = rolling_ball(main_o, branch_o, branch.blend, main.tolerance)
            toe = saddle_curve(main_o.offset(branch.blend), branch_o.offset(branch.blend), TEMPLATE_SAMPLES)
            toe_main = on_main(main_o, toe, stringers, margin, f"branch_{k}_blend_main", outer)
            shop.cut = replace(cut, lines={"blend_toe": branch_template(branch_o, toe).points})
            shop.blend = BlendShop(branch.blend, toe_main, blend_strips(ball, f"branch_{k}_blend"), max_strain)
    if branch.pad is not None:
        from tubecad.shop.panel_development import develop_panel
        from tubecad.stiffeners.pad import pad_bounds

        with stage("pads", k):
            pad_s, pad_angles = pad_bounds(main_o, outer, branch.pad.width)
        development = develop_panel(main_o, pad_s, pad_angles, f"branch_{k}_pad")
        line = development.map(np.degrees(outer.main_u), outer.main_s)
        shop.pad = PadShop(development, line, branch.pad.thickness)
    return shop


def on_main(
    surface: CurvatureLineSurface,
    line: SaddleCurve,
    stringers: list[float],
    margin: float,
    name: str,
    outer: SaddleCurve | None = None,
) -> OpeningTemplate:
    """A closed line round a branch (its ``line``'s main parameters) drawn on the main's
    ``surface``: on its strip (R u, s - s_0) where the radius is constant
    (:func:`tubecad.shop.branch_template.hole_template`, with ``outer``'s line too on layer
    ``saddle_outer``), else on the development of the panel ``margin`` round it
    (:func:`tubecad.shop.hole_development.hole_development`: a canal surface develops to a
    sector, not a strip), the main's ``stringers`` (degrees) marked; named ``name``."""
    from dataclasses import replace

    from tubecad.shop.branch_template import hole_template

    if surface.constant_radius:
        template = hole_template(surface, line, len(stringers))
        if outer is None:
            return template
        return replace(template, lines={"saddle_outer": hole_template(surface, outer, len(stringers)).points})
    from tubecad.shop.hole_development import HolePanel, hole_development

    development, developed = hole_development(surface, line, margin, name)
    return HolePanel(development, developed, {f"stringer_{j:02d}": a for j, a in enumerate(stringers)})
