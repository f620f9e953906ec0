"""The typed model of a spec: one frozen dataclass per section, made once from the checked
tables (:func:`tubecad.spec.parse.parse_spec`), so that the later stages (build, report,
mesh, shop, batch) read attributes, not dicts.

The field names are the spec's keys (:mod:`tubecad.spec.keys`; a test holds the two
together); an optional key that is absent is its default where the default is a plain
value (``[wall] side = "centered"``), else None (the rule that owns it fills it in:
:func:`tubecad.fem.settings.mesh_settings`, :func:`tubecad.shop.fabrication.fabrication_settings`).
``[axis]`` keeps its checked keys as a table: each kind of axis has keys of its own, and
:func:`tubecad.spec.axis.build_axis` turns them into the axis.

Light on purpose (no numpy, no OCCT): the rules behind the methods are imported when called.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any, Literal

from tubecad.core.errors import ParameterError, SpecError
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.core.units import DEFAULT_LENGTH_UNIT

if TYPE_CHECKING:
    from tubecad.brep.layout import NetLayout
    from tubecad.fem.settings import AnalysisSettings, MeshSettings
    from tubecad.shop.fabrication import Fabrication
    from tubecad.stiffeners.profiles import Profile
    from tubecad.surface.protocol import CurvatureLineSurface

#: a [stiffeners] or [panels] choice of layout lines: "all", or their indices
Selection = Literal["all"] | tuple[int, ...]


def _selection(value: Any) -> Selection:
    return "all" if value == "all" else tuple(value)


def selected_indices(value: Selection, count: int, name: str, key: str) -> list[int]:
    """A selection (indices or "all") as indices into ``count`` lines; a ParameterError naming
    ``name`` in its text and ``key`` for any outside [0, count - 1]."""
    chosen = list(range(count)) if value == "all" else list(value)
    bad = [i for i in chosen if not 0 <= i < count]
    if bad:
        raise ParameterError(f"{name} must be indices in [0, {count - 1}], got {bad}", key=key)
    return chosen


def _listed(value: Any) -> Any:
    """A selection as the spec file gives it: "all" or a list."""
    return value if value == "all" else list(value)


class _Table:
    """A section whose keys are passed on, as a table, to the rule that checks them."""

    def table(self) -> dict[str, Any]:
        """The keys the spec gives (None: absent), as the spec file has them."""
        return {f.name: getattr(self, f.name) for f in fields(self) if getattr(self, f.name) is not None}  # type: ignore[arg-type]


@contextmanager
def _in_section(section: str) -> Iterator[None]:
    """A library's settings error (``element must be one of ...``, key ``element``) told in the
    section's terms: ``[mesh] element must be one of ...``, key ``mesh.element``."""
    try:
        yield
    except ParameterError as exc:
        key = exc.key if exc.key and exc.key.startswith(f"{section}.") else f"{section}.{exc.key or ''}".rstrip(".")
        raise ParameterError(f"[{section}] {exc}", key=key) from None


@dataclass(frozen=True)
class AxisSection:
    """[axis]: the kind of axis and its checked keys (``curve`` included)."""

    curve: str
    values: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class TubeSection:
    """[tube]: a constant radius, or a radius law (an expression in s, or a table of [s, r] rows)."""

    radius: Any
    allow_irregular: bool = False


@dataclass(frozen=True)
class LayoutSection:
    """[layout]: ring and stringer counts, or their explicit positions (None: absent)."""

    rings: int | None = None
    stringers: int | None = None
    s_rings: tuple[float, ...] | None = None
    u_stringers_deg: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        for name in ("s_rings", "u_stringers_deg"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, tuple):
                object.__setattr__(self, name, tuple(value))

    def net(self, tube: CurvatureLineSurface) -> NetLayout:
        """The layout on ``tube``: the given positions, else the counts (default 11 rings,
        8 stringers) equally spaced; a ParameterError names the key at fault."""
        from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS, NetLayout, equal_rings, equal_stringers

        if self.s_rings is not None:
            s_rings: Any = self.s_rings
        else:
            rings = DEFAULT_RINGS if self.rings is None else self.rings
            s_rings = _keyed("layout.rings", lambda: equal_rings(tube, rings))  # N distinct rings on a loop
        if self.u_stringers_deg is not None:
            angles: Any = self.u_stringers_deg
        else:
            stringers = DEFAULT_STRINGERS if self.stringers is None else self.stringers
            angles = _keyed("layout.stringers", lambda: equal_stringers(stringers))
        return _keyed("layout", lambda: NetLayout.explicit(tube, s_rings, angles))


@dataclass(frozen=True)
class WallSection:
    """[wall]: a wall solid of this thickness, centred on the tube or inside or outside it."""

    thickness: float
    side: str = "centered"

    def offsets(self) -> tuple[float, float]:
        """(d_in, d_out): the wall's surfaces as offsets of the tube's (ParameterError if bad)."""
        from tubecad.brep.wall import wall_offsets

        return wall_offsets(self.thickness, self.side)

    def radii(self, radius: float) -> tuple[float, float]:
        """(r_in, r_out) of the wall of a tube of ``radius`` (ParameterError if bad)."""
        from tubecad.brep.wall import wall_radii

        return wall_radii(radius, self.thickness, self.side)


@dataclass(frozen=True)
class PadSection:
    """A [[branches]] table's pad: its ``thickness`` and its ``width`` beyond the saddle."""

    thickness: float
    width: float


@dataclass(frozen=True)
class BlendSection:
    """A [[branches]] table's crotch blend: the rolling ball's ``radius``."""

    radius: float


#: a branch's rings when its [[branches]] table has no layout
DEFAULT_BRANCH_RINGS = 3


@dataclass(frozen=True)
class BranchStiffenersSection:
    """A [[branches]] table's stiffeners: ``rings`` and ``stringers`` of the branch's layout
    (indices or "all"), its rings at least ``start`` beyond its saddle (None: the profile's height)."""

    rings: Selection = ()
    stringers: Selection = ()
    start: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "rings", _selection(self.rings))
        object.__setattr__(self, "stringers", _selection(self.stringers))

    def indices(self, key: str, count: int) -> list[int]:
        """``rings`` or ``stringers`` as indices into ``count`` lines of the branch's layout; a
        ParameterError naming ``branches.stiffeners.<key>`` otherwise."""
        return selected_indices(getattr(self, key), count, f"stiffeners.{key}", f"branches.stiffeners.{key}")


@dataclass(frozen=True)
class BranchSection:
    """One [[branches]] table: a branch tube of ``radius`` and ``length`` leaving the main
    axis at arc length ``at``, ``angle`` degrees from its tangent, on the side ``around``
    degrees round it from its first stringer, its axis ``offset`` sideways and, with ``axis``,
    curving by its natural equations k(s), tau(s) (None: straight); its own ``wall``,
    ``layout`` and ``pad`` (None: the main [wall], 3 rings and the main's stringers, no pad)."""

    at: float
    length: float
    radius: Any
    angle: float = 90.0
    around: float = 90.0
    offset: float = 0.0
    axis: dict[str, str] | None = None
    wall: WallSection | None = None
    layout: LayoutSection | None = None
    pad: PadSection | None = None
    stiffeners: BranchStiffenersSection | None = None
    blend: BlendSection | None = None

    def __post_init__(self) -> None:
        for name, kind in (
            ("wall", WallSection),
            ("layout", LayoutSection),
            ("pad", PadSection),
            ("stiffeners", BranchStiffenersSection),
            ("blend", BlendSection),
        ):
            value = getattr(self, name)
            if isinstance(value, dict):  # the checked inline table, typed
                object.__setattr__(self, name, kind(**value))

    def net(self, surface: CurvatureLineSurface, main_stringers: int) -> Any:
        """The branch's rings and stringers on its ``surface``: its ``layout``, else
        DEFAULT_BRANCH_RINGS rings and the main's ``main_stringers`` stringers."""
        from tubecad.brep.layout import NetLayout

        if self.layout is not None:
            return self.layout.net(surface)
        return NetLayout.equal(surface, DEFAULT_BRANCH_RINGS, main_stringers)

    def surface(self, main: CurvatureLineSurface) -> CurvatureLineSurface:
        """The branch's tube (or canal surface) placed on ``main``
        (:func:`tubecad.junctions.placement.branch_surface`); a ParameterError names the key."""
        from tubecad.junctions.placement import branch_surface

        axis = self.axis or {}
        return branch_surface(
            main,
            self.at,
            self.length,
            self.radius,
            angle=self.angle,
            around=self.around,
            offset=self.offset,
            k=axis.get("k", "0"),
            tau=axis.get("tau", "0"),
        )


@dataclass(frozen=True)
class FitSection:
    """[fit]: the largest deviation of the B-spline surfaces from the exact tube."""

    tolerance: float = DEFAULT_TOLERANCE


@dataclass(frozen=True)
class StiffenerSelection:
    """What a [stiffeners] section asks for, checked against a layout: the ring and stringer
    indices, the profile, the side, whether to fuse, the density (kg per cubic unit)."""

    rings: list[int]
    stringers: list[int]
    profile: Profile
    side: str
    fuse: bool
    density: float

    def base(self, build: Any) -> Any:
        """The wall surface the stiffeners stand on: outer (outside) or inner (inside)."""
        from tubecad.stiffeners.assembly import stiffener_base

        return stiffener_base(build, self.side)


@dataclass(frozen=True)
class StiffenersSection:
    """[stiffeners]: which layout lines carry stiffeners, their profile and side.

    Parsed once, for the build and the mesh alike: :meth:`select` checks the profile, the
    side, the density and the indices against a layout, with the messages of the spec."""

    height: float
    thickness: float
    rings: Selection = ()
    stringers: Selection = ()
    k1: Selection = ()  # a [host] net's lines
    k2: Selection = ()
    profile: str = "flat"
    flange_width: float = 0.0
    flange_thickness: float = 0.0
    side: str = "outside"
    fuse: bool = False
    density: float | None = None  # None: steel, in the spec's length unit

    def __post_init__(self) -> None:
        object.__setattr__(self, "rings", _selection(self.rings))
        object.__setattr__(self, "stringers", _selection(self.stringers))
        object.__setattr__(self, "k1", _selection(self.k1))
        object.__setattr__(self, "k2", _selection(self.k2))
        object.__setattr__(self, "k1", _selection(self.k1))
        object.__setattr__(self, "k2", _selection(self.k2))

    def table(self) -> dict[str, Any]:
        """The section as a spec file's table (what tubecad.stiffeners.limits reads)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if getattr(self, f.name) is not None}
        out["rings"], out["stringers"] = _listed(self.rings), _listed(self.stringers)
        for key in ("k1", "k2"):  # a tube's table has none (tubecad.stiffeners.limits reads it)
            if out.pop(key) != ():
                out[key] = _listed(getattr(self, key))
        return out

    def make_profile(self) -> Profile:
        """The cross-section (a ParameterError names what is wrong with it)."""
        from tubecad.stiffeners.profiles import Profile

        return Profile(self.profile, self.height, self.thickness, self.flange_width, self.flange_thickness)

    def indices(self, key: str, count: int) -> list[int]:
        """``rings`` or ``stringers`` as indices into ``count`` layout lines; a ParameterError
        (key ``stiffeners.<key>``) for any outside them."""
        return selected_indices(getattr(self, key), count, key, f"stiffeners.{key}")

    def select(self, layout: Any, source: str, length_unit: str = DEFAULT_LENGTH_UNIT) -> StiffenerSelection:
        """The section checked against ``layout`` (anything with ``s_rings`` and
        ``stringers_deg``): a SpecError naming [stiffeners] and the key otherwise."""
        from tubecad.core.units import steel_density
        from tubecad.stiffeners.profiles import SIDES

        def fail(text: str, key: str) -> SpecError:
            return SpecError(f"{source}: [stiffeners] {text}", key=key)

        try:
            profile = self.make_profile()
        except ParameterError as exc:
            raise fail(str(exc), exc.key or "stiffeners.profile") from None
        if self.side not in SIDES:
            raise fail(f"side must be one of {', '.join(SIDES)}, got {self.side!r}", "stiffeners.side")
        density = steel_density(length_unit) if self.density is None else self.density  # kg per cubic unit
        if not density > 0:
            raise fail(f"density must be > 0, got {density}", "stiffeners.density")
        try:
            rings = self.indices("rings", len(layout.s_rings))
            stringers = self.indices("stringers", len(layout.stringers_deg))
        except ParameterError as exc:
            raise fail(str(exc), exc.key or "stiffeners") from None
        return StiffenerSelection(rings, stringers, profile, self.side, self.fuse, density)


@dataclass(frozen=True)
class PanelsSection:
    """[panels]: the seam stringers the wall is split along, and the rings bounding the panels."""

    seams: Selection
    rings: Selection = "all"

    def __post_init__(self) -> None:
        object.__setattr__(self, "seams", _selection(self.seams))
        object.__setattr__(self, "rings", _selection(self.rings))

    def seam_indices(self, stringers: int) -> list[int]:
        return list(range(stringers)) if self.seams == "all" else list(self.seams)

    def ring_indices(self) -> list[int] | None:
        """The bounding rings, or None for every ring."""
        return None if self.rings == "all" else list(self.rings)


@dataclass(frozen=True)
class UnitsSection:
    """[units]: the unit of every length in the spec and in the files written from it."""

    length: str = DEFAULT_LENGTH_UNIT


@dataclass(frozen=True)
class FabricationSection(_Table):
    """[fabrication]: the shop's settings (None: the default of tubecad.shop.fabrication)."""

    plate_size: list[float] | None = None
    kerf: float | None = None
    joint_gap: float | None = None
    max_strain: float | None = None
    pin_spacing: float | None = None
    pin_clearance: float | None = None
    joints: dict[str, list[float]] | None = None

    def settings(self, length_unit: str = DEFAULT_LENGTH_UNIT) -> Fabrication:
        """The checked settings, in ``length_unit`` (a ParameterError names the key)."""
        from tubecad.shop.fabrication import fabrication_settings

        with _in_section("fabrication"):
            return fabrication_settings(self.table(), length_unit)


@dataclass(frozen=True)
class MeshSection(_Table):
    """[mesh]: the finite-element mesh's settings (None: the default of tubecad.fem.settings)."""

    element: str | None = None
    beam: str | None = None
    size: float | None = None
    size_along: float | None = None
    size_around: float | None = None
    surface: str | None = None
    max_elements: int | None = None
    beams: bool | None = None

    def settings(self, **overrides: Any) -> MeshSettings:
        """The checked settings; ``overrides`` (not None) win over the section."""
        from tubecad.fem.settings import mesh_settings

        with _in_section("mesh"):
            return mesh_settings(self.table(), **overrides)


@dataclass(frozen=True)
class AnalysisSection(_Table):
    """[analysis]: the pressure case (None: the default of tubecad.fem.settings)."""

    pressure: float | None = None
    ends: str | None = None
    youngs_modulus: float | None = None
    poisson_ratio: float | None = None
    allowable_stress: float | None = None

    def settings(self, length_unit: str = DEFAULT_LENGTH_UNIT, closed: bool = False) -> AnalysisSettings:
        """The checked settings, in ``length_unit`` (a ParameterError names the key)."""
        from tubecad.fem.settings import analysis_settings

        with _in_section("analysis"):
            return analysis_settings(self.table(), length_unit, closed)


@dataclass(frozen=True)
class BatchSection:
    """[batch]: where ``tubecad build`` runs a batch of this spec."""

    scheduler: str | None = None


#: section name -> its dataclass (besides [axis])
SECTION_TYPES: dict[str, type] = {
    "tube": TubeSection,
    "layout": LayoutSection,
    "wall": WallSection,
    "fit": FitSection,
    "stiffeners": StiffenersSection,
    "panels": PanelsSection,
    "units": UnitsSection,
    "fabrication": FabricationSection,
    "mesh": MeshSection,
    "analysis": AnalysisSection,
    "batch": BatchSection,
}


@dataclass(frozen=True)
class SpecModel:
    """Every section of a checked spec, typed. The optional sections are None when absent,
    except [layout], [fit] and [units], whose absence means their defaults."""

    axis: AxisSection
    tube: TubeSection
    layout: LayoutSection = field(default_factory=LayoutSection)
    fit: FitSection = field(default_factory=FitSection)
    units: UnitsSection = field(default_factory=UnitsSection)
    wall: WallSection | None = None
    stiffeners: StiffenersSection | None = None
    panels: PanelsSection | None = None
    fabrication: FabricationSection | None = None
    mesh: MeshSection | None = None
    analysis: AnalysisSection | None = None
    batch: BatchSection | None = None
    branches: tuple[BranchSection, ...] = ()

    @classmethod
    def from_sections(cls, sections: dict[str, Any]) -> SpecModel:
        """The model of checked tables (every key known and of its type: parse_spec checks them)."""
        axis = AxisSection(sections["axis"]["curve"], dict(sections["axis"]))
        typed = {
            name: SECTION_TYPES[name](**values) for name, values in sections.items() if name not in ("axis", "branches")
        }
        branches = tuple(BranchSection(**table) for table in sections.get("branches", ()))
        return cls(axis, **typed, branches=branches)


def _keyed(key: str, build: Any) -> Any:
    """``build()``, its ParameterError given ``key`` if it has none."""
    try:
        return build()
    except ParameterError as exc:
        if exc.key is None:
            exc.key = key
        raise


class SpecSections:
    """The sections every checked spec has (a tube's, :class:`~tubecad.spec.parse.TubeSpec`; a
    face's, :class:`~tubecad.spec.host.HostSpec`), read from its typed ``model``."""

    model: Any

    @property
    def length_unit(self) -> str:
        """The unit of every length in the spec and in the files written from it ([units] length)."""
        return str(self.model.units.length)

    @property
    def units(self) -> UnitsSection:
        return self.model.units

    @property
    def wall(self) -> WallSection | None:
        return self.model.wall

    @property
    def stiffeners(self) -> StiffenersSection | None:
        return self.model.stiffeners

    @property
    def fabrication(self) -> FabricationSection | None:
        return self.model.fabrication

    @property
    def mesh(self) -> MeshSection | None:
        return self.model.mesh

    @property
    def analysis(self) -> AnalysisSection | None:
        return self.model.analysis
