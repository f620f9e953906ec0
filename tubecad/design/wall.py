"""A :class:`WallDesign`, a tube or a wall, and its build: the tube or wall solid, its stiffeners
and panels, the named assembly its files are written from, and what was measured."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

from tubecad.core.errors import RegularityError
from tubecad.core.progress import Progress
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.design.model import PanelChoice, StiffenerChoice, WallChoice
from tubecad.design.shell import ShellModel, WallShellModel
from tubecad.design.shop import ShopPackage, WallShop
from tubecad.design.stages import stage

if TYPE_CHECKING:
    from tubecad.brep.layout import NetLayout
    from tubecad.brep.solids import TubeBuild
    from tubecad.design.result import BuildResult
    from tubecad.export.registry import Exportable, OutputFormat
    from tubecad.fem.settings import MeshSettings
    from tubecad.shop.fabrication import Fabrication
    from tubecad.surface.protocol import CurvatureLineSurface


@dataclass(frozen=True)
class WallDesign:
    """A tube (``wall`` None: the capped tube solid) or a wall about the exact ``surface``,
    its faces bounded by the net ``layout``, fitted to ``tolerance``; with ``stiffeners``
    and ``panels`` the named assembly of the wall (or its panels) and the stiffeners.

    Args:
        surface: the exact curvature-line surface (a tube or a canal surface).
        layout: its net: the rings' arc lengths and the stringers' angles.
        tolerance: the fit's tolerance, in model units (tubecad.core.tolerance).
        wall: the wall's thickness and side (None: the capped tube solid).
        stiffeners: the stiffeners on the layout's rings and stringers (None: none).
        panels: the wall split into panels (None: one solid).
        length_unit: the unit of every length, stated by every file (mm, cm, m, in, ft).
        report_grid: the (nu, ns) grid the exact surface's report is measured on.
    """

    surface: CurvatureLineSurface
    layout: NetLayout
    tolerance: float = DEFAULT_TOLERANCE
    wall: WallChoice | None = None
    stiffeners: StiffenerChoice | None = None
    panels: PanelChoice | None = None
    length_unit: str = DEFAULT_LENGTH_UNIT
    #: the (nu, ns) grid the exact surface's report is measured on
    report_grid: tuple[int, int] = (64, 501)

    #: what it is written as: output format kinds and names (tubecad.export.formats)
    WRITTEN_AS: ClassVar[frozenset[str]] = frozenset({"cad", "mesh", "polylines", "picture"})
    #: what it is called in messages
    WHAT: ClassVar[str] = "a tube or wall"
    #: a wall's shop package is its stiffeners' and panels': it needs one or the other
    SHOP_NEEDS_PARTS: ClassVar[bool] = True

    def build(self, progress: Progress | None = None) -> BuildResult:
        """The tube or wall solid, its stiffeners and panels, named and measured
        (:func:`build_wall`)."""
        return build_wall(self, progress)

    def shell_model(self, settings: MeshSettings) -> ShellModel:
        """The wall (or the surface) meshed for analysis with ``settings``
        (:func:`tubecad.design.shell.wall_shell_model`); nothing is built in OCCT."""
        return wall_shell_model(self, settings)

    def shop(self, fab: Fabrication, progress: Callable[[str], None] | None = None) -> ShopPackage:
        """The wall's shop package with the fabrication settings ``fab`` (:func:`wall_shop`)."""
        return wall_shop(self, fab, progress)

    @classmethod
    def analysis_ends(cls, given: str | None, default: str) -> str:
        """The pressure step's end condition (:func:`tubecad.design.shell.wall_ends`)."""
        from tubecad.design.shell import wall_ends

        return wall_ends(given, default)


@dataclass
class WallResult:
    """A tube or wall built (:class:`~tubecad.design.result.BuildResult`): the B-rep
    ``build``, its ``stiffeners`` and ``panels``, the ``shape`` its files are written from
    (the named assembly with stiffeners or panels, else the solid) and the ``report``."""

    design: WallDesign
    build: TubeBuild
    stiffeners: list = field(default_factory=list)
    panels: list = field(default_factory=list)
    shape: Any = None
    report: dict[str, Any] = field(default_factory=dict)

    @property
    def kind(self) -> str:
        """``wall``, ``tube_solid`` or ``tube_shell`` (the report's ``brep.kind``)."""
        return str(self.report.get("brep", {}).get("kind", "wall" if self.design.wall else "tube_solid"))

    @property
    def length_unit(self) -> str:
        return self.design.length_unit

    @property
    def named(self) -> bool:
        """Whether ``shape`` is the named assembly (wall or panels, stiffeners, lines)."""
        return bool(self.stiffeners or self.panels)

    @property
    def wall_solids(self) -> int | None:
        """For the assembly, how many of its first solids are the wall (or its panels)."""
        return (len(self.panels) or 1) if self.named else None

    @property
    def surfaces(self) -> list:
        """The exact surface the build was made about."""
        return [self.design.surface]

    @property
    def solids(self) -> list[tuple[str, Any]]:
        """(name, OCCT solid): the wall (or the tube) first, then each stiffener."""
        return [("wall", self.build.shape.wrapped), *((st.name, st.solid.wrapped) for st in self.stiffeners)]

    @property
    def named_edges(self) -> dict[str, list[Any]]:
        """The net's edges of the wall's solid by name: ``ring_03``, ``stringer_05``,
        ``seam_00`` on the outer surface, ``ring_03_inner``... on the inner one."""
        return net_edge_sets(self.build)

    @property
    def mesh_radius(self) -> float:
        """The smallest radius of the wall's surfaces (mesh tolerances are checked against it)."""
        wall = self.design.wall
        return self.design.surface.radius_law.min_radius + (0.0 if wall is None else wall.offsets()[0])

    def lines(self) -> list:
        """The layout's curvature lines on every wall surface (``..._inner`` on the inner one)."""
        from tubecad.stiffeners import net_lines

        build = self.build
        lines = net_lines(build.surfaces[0], build.layout)
        if len(build.surfaces) > 1:
            lines += net_lines(build.surfaces[1], build.layout, "_inner")
        return lines

    def exportable(self, step_schema: str, deflection: float, angular: float) -> Exportable:
        """What every output of this build is written from."""
        from tubecad.export.registry import Exportable

        return Exportable(
            self.shape,
            self.lines,
            step_schema,
            mesh_deflection=deflection,
            length_unit=self.length_unit,
            mesh_angular=angular,
            build=self.build,
        )

    def written_reference(self) -> Any:
        """The shape written, its area and volume integrated once for all the files."""
        from tubecad.export.readback import WrittenShape

        if self.shape is self.build.shape and "volume" in self.report.get("brep", {}):
            return WrittenShape(self.shape, {"volume": self.report["brep"]["volume"]})  # build_report's
        return WrittenShape(self.shape)

    def check_file(
        self, tmp: Path, fmt: OutputFormat, target: Path, reference: Any, deflection: float, angular: float
    ) -> dict[str, Any]:
        """Read a just-written temporary file back and measure it (tubecad.export.readback);
        raises if it does not hold the build's tolerance, so it is never moved into place."""
        from tubecad.export.readback import mesh_report, picture_report, readback_report

        unit, build = self.length_unit, self.build
        if fmt.kind == "cad":
            return readback_report(tmp, reference, build, target, self.wall_solids, unit)
        if fmt.kind == "mesh":
            return mesh_report(tmp, fmt.name, build, deflection, target, self.wall_solids, unit, angular)
        if fmt.kind == "picture":
            return picture_report(tmp, fmt.name, build)
        return {"bytes": tmp.stat().st_size, "lines": len(self.lines())}


def net_edge_sets(build: TubeBuild) -> dict[str, list[Any]]:
    """The ring, stringer and seam edges of ``build``'s solid by name (``ring_03``,
    ``stringer_05``, ``seam_00``; ``..._inner`` on a wall's inner surface). On a closed axis
    the closing ring (the layout's first and last) is ``ring_00`` once, made of all its arcs."""
    closed = build.surfaces[0].tube.axis.closed
    out: dict[str, list[Any]] = {}
    for k, patches in enumerate(build.patches):
        suffix = "" if k == 0 else "_inner"
        rings = patches.rings[:-1] if closed else patches.rings
        for i, edges in enumerate(rings):
            out[f"ring_{i:02d}{suffix}"] = list(edges)
        if closed and patches.closing_arcs:
            out[f"ring_00{suffix}"] = [arc for _, _, arc in patches.closing_arcs]
        for j, col in enumerate(patches.stringers):
            out[f"stringer_{j:02d}{suffix}"] = list(col)
        for m, col in enumerate(patches.seams):
            out[f"seam_{m:02d}{suffix}"] = list(col)
    return out


def build_wall(design: WallDesign, progress: Progress | None = None) -> WallResult:
    """Build ``design``'s solid (the wall, or the capped tube), its stiffeners and panels (then
    the named assembly), and measure them: the report of ``tubecad build``. Nothing is written.

    Raises:
        ParameterError, RegularityError, FitError: tagged with the stage that failed
            (:func:`tubecad.design.stages.stage`).
    """
    from tubecad.core.units import steel_density
    from tubecad.design.report import build_report, stiffener_report, tube_report
    from tubecad.stiffeners import net_lines
    from tubecad.stiffeners.assembly import named_assembly

    progress = progress if progress is not None else Progress(enabled=False)
    unit = design.length_unit
    progress.step(f"building the {'wall' if design.wall is not None else 'tube'}", 4 if design.wall else 3)
    build = build_solid(design, progress.update)
    report = tube_report(design.surface, *design.report_grid, length_unit=unit)
    report["brep"] = build_report(build, design.surface)
    if design.stiffeners is not None:
        progress.step("building stiffeners")
    stiffeners = build_wall_stiffeners(design, build, progress.update)
    if design.panels is not None:
        progress.step("splitting the wall into panels")
    panels = build_panels(design, build)
    result = WallResult(design, build, stiffeners, panels, build.shape, report)
    if result.named:
        chosen = design.stiffeners
        fuse = bool(chosen and chosen.fuse)
        progress.step("assembling" + (" (fusing the stiffeners into the wall)" if fuse else ""))
        lines = net_lines(build.surfaces[0], build.layout)
        result.shape = named_assembly(build, stiffeners, lines, fuse=fuse, panels=panels)
        density = chosen.density if chosen and chosen.density is not None else steel_density(unit)
        report["stiffeners"] = stiffener_report(stiffeners, lines, density, unit)
        report["panels"] = panel_report(panels, density)
    return result


def build_solid(design: WallDesign, progress: Any = None) -> TubeBuild:
    """The wall solid of ``design`` if it has a wall, else the capped tube solid;
    ``progress(step, done, total)`` is called as it is built."""
    from tubecad.brep import build_tube_solid, build_wall_solid
    from tubecad.core.tolerance import check_tolerance

    with stage("fit"):
        tolerance = check_tolerance("tolerance", design.tolerance)
    wall = design.wall
    if wall is None:
        with stage("fit"):
            return build_tube_solid(design.surface, design.layout, tolerance, progress)
    with stage("wall"):
        try:
            return build_wall_solid(design.surface, wall.thickness, wall.side, design.layout, tolerance, progress)
        except RegularityError as exc:
            raise RegularityError(f"the wall's outer surface is not regular: {exc}", key="thickness") from None


def build_wall_stiffeners(design: WallDesign, build: TubeBuild, progress: Any = None) -> list:
    """``design``'s stiffener solids on ``build``'s wall ([] without stiffeners), each ring
    once (a closed tube's closing ring is its first); ``progress(name, done, total)``."""
    from tubecad.stiffeners.assembly import build_stiffeners, distinct_rings

    chosen = design.stiffeners
    if chosen is None:
        return []
    with stage("stiffeners"):
        rings = distinct_rings(build, chosen.rings)
        return build_stiffeners(build, rings, chosen.stringers, chosen.profile, chosen.side, build.tolerance, progress)


def build_panels(design: WallDesign, build: TubeBuild) -> list:
    """``design``'s panels of the wall ([] without panels)."""
    from tubecad.core.errors import ParameterError
    from tubecad.stiffeners.panels import split_into_panels

    chosen = design.panels
    if chosen is None:
        return []
    n_s, n_r = len(build.layout.stringers_deg), len(build.layout.s_rings)
    with stage("panels"):
        try:
            rings = None if chosen.rings is None else list(chosen.rings)
            return split_into_panels(build, list(chosen.seams), rings)
        except ParameterError as exc:
            raise ParameterError(f"{exc} (the layout has {n_s} stringers and {n_r} rings)", key=exc.key) from None


def panel_report(panels: list, density: float) -> list[dict[str, Any]]:
    """Each panel's name, bounds, outer area, volume and mass at ``density``."""
    from tubecad.brep.properties import volume

    return [
        {
            "name": p.name,
            "s": list(p.s_range),
            "angles_deg": list(p.angles_deg),
            "outer_area": p.outer_area,
            "volume": volume(p.solid),
            "mass_kg": p.mass(density),
        }
        for p in panels
    ]


def wall_shell_model(design: WallDesign, settings: MeshSettings) -> WallShellModel:
    """``design`` meshed with ``settings``: its wall (or surface), stiffeners as beams, panels
    as sets (:func:`tubecad.fem.shell_mesh`)."""
    from tubecad.fem import StiffenerPlan, shell_mesh

    chosen, wall, panels = design.stiffeners, design.wall, design.panels
    plan = None if chosen is None else StiffenerPlan(chosen.rings, chosen.stringers, chosen.profile, chosen.side)
    with stage("mesh"):
        mesh = shell_mesh(
            design.surface,  # type: ignore[arg-type]
            design.layout,
            thickness=None if wall is None else wall.thickness,
            wall_side="centered" if wall is None else wall.side,
            stiffeners=plan,
            seams=None if panels is None else panels.seams,
            panel_rings=None if panels is None else panels.rings,
            settings=settings,
            length_unit=design.length_unit,
        )
    return WallShellModel(mesh, design.surface)


def wall_shop(design: WallDesign, fab: Fabrication, progress: Callable[[str], None] | None = None) -> WallShop:
    """``design``'s wall, stiffeners and panels built (no report, no assembly) and their shop
    package computed with ``fab`` (:func:`tubecad.shop.package.shop_data`); ``progress(stage)``
    hears of each stage."""
    from tubecad.shop.package import shop_data

    say = progress or (lambda _stage: None)
    say("building the wall")
    build = build_solid(design)
    say("building stiffeners")
    stiffeners = build_wall_stiffeners(design, build)
    panels = build_panels(design, build)
    with stage("fabrication"):
        return WallShop(shop_data(build, stiffeners, panels, fab, say))
