"""The design values: what one build is made of, below the spec and the parts.

The :class:`Design` protocol and the choices designs are made of (a wall, stiffeners, panels,
a pad). A :class:`~tubecad.design.wall.WallDesign` is a tube or a wall (the exact surface, its
net, the fit tolerance, the wall, the stiffeners and the panels); a
:class:`~tubecad.design.junction.JunctionDesign` is a main wall with
:class:`~tubecad.design.model.BranchDesign` s joined on. The spec parses TOML into one (:mod:`tubecad.spec.design`),
the build123d parts and the CadQuery plugin build one from keyword arguments
(:mod:`tubecad.parts.engine`); all three build it the same way, by its own :meth:`build`
(the :class:`Design` protocol), into a :class:`~tubecad.design.result.BuildResult`.

Errors raised while a design is built speak Python terms (the parameter or the field at
fault) and carry ``stage``: the design field whose part of the build failed (``"layout"``,
``"wall"``, ``"fit"``, ``"stiffeners"``, ``"panels"``, ``"branches"``, ``"pads"``), which the
spec layer turns into its ``[section]`` (:func:`tubecad.design.stages.stage`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar, Protocol

if TYPE_CHECKING:
    from tubecad.brep.layout import NetLayout
    from tubecad.brep.wall import WallSide
    from tubecad.core.progress import Progress
    from tubecad.design.result import BuildResult
    from tubecad.design.shell import ShellModel
    from tubecad.design.shop import ShopPackage
    from tubecad.fem.settings import MeshSettings
    from tubecad.shop.fabrication import Fabrication
    from tubecad.stiffeners.profiles import Profile, StiffenerSide
    from tubecad.surface.protocol import CurvatureLineSurface


class Design(Protocol):
    """Anything that builds into a :class:`~tubecad.design.result.BuildResult`."""

    #: the output formats it is written as, by kind (``cad``, ``mesh``...) or by name (``png``)
    WRITTEN_AS: ClassVar[frozenset[str]]
    #: what it is, in messages (``a junction``)
    WHAT: ClassVar[str]
    #: whether its shop package needs stiffeners or panels to hold anything
    SHOP_NEEDS_PARTS: ClassVar[bool]

    @property
    def length_unit(self) -> str:
        """The unit of the design's lengths (tubecad.core.units), stated by every file."""
        ...

    @property
    def stiffeners(self) -> StiffenerChoice | None:
        """The stiffeners on the (main) wall, if any."""
        ...

    def build(self, progress: Progress | None = None) -> BuildResult:
        """Build the design's solids, name their edges and measure them (nothing is written)."""
        ...

    def shell_model(self, settings: MeshSettings) -> ShellModel:
        """The design meshed for analysis with ``settings`` (:mod:`tubecad.design.shell`)."""
        ...

    def shop(self, fab: Fabrication, progress: Callable[[str], None] | None = None) -> ShopPackage:
        """The design's shop package with the fabrication settings ``fab`` (:mod:`tubecad.design.shop`)."""
        ...

    @classmethod
    def analysis_ends(cls, given: str | None, default: str) -> str:
        """The end condition of its pressure step: ``given`` if the design's model can take
        it (a ParameterError naming ``ends`` if not), else its default or ``default``."""
        ...


@dataclass(frozen=True)
class WallChoice:
    """A wall of ``thickness`` placed ``side`` of the tube's surface (``centered``, ``inside``
    or ``outside``): its surfaces are the tube's offset along the normal."""

    thickness: float
    side: WallSide = "centered"

    def offsets(self) -> tuple[float, float]:
        """(d_in, d_out): the wall's surfaces as offsets of the tube's (a ParameterError if bad)."""
        from tubecad.brep.wall import wall_offsets

        return wall_offsets(self.thickness, self.side)


@dataclass(frozen=True)
class StiffenerChoice:
    """Stiffeners of ``profile`` on the layout's rings ``rings`` and stringers ``stringers``
    (indices), standing ``side`` of the wall; ``fuse`` merges them into the wall's solid;
    ``density`` (kg per cubic length unit; None: steel) weighs them in the report."""

    rings: tuple[int, ...]
    stringers: tuple[int, ...]
    profile: Profile
    side: StiffenerSide = "outside"
    fuse: bool = False
    density: float | None = None


@dataclass(frozen=True)
class PanelChoice:
    """The wall split into panels along the stringers ``seams`` (indices) and between the
    rings ``rings`` (indices; None: every ring)."""

    seams: tuple[int, ...]
    rings: tuple[int, ...] | None = None


@dataclass(frozen=True)
class PadChoice:
    """A reinforcement pad round a branch: ``thickness`` and ``width`` beyond its saddle."""

    thickness: float
    width: float


@dataclass(frozen=True)
class BranchDesign:
    """A branch of a junction: its exact ``surface`` (placed on the main one:
    :func:`tubecad.junctions.branch_surface`), its ``wall`` and net ``layout``; a ``pad``
    round its opening; with ``stiffened`` its own stiffeners (the main's profile and side) on
    its rings ``stiffener_rings`` and stringers ``stiffener_stringers``, the stringers
    starting ``stiffener_start`` beyond the saddle (None: the profile's height)."""

    surface: CurvatureLineSurface
    wall: WallChoice
    layout: NetLayout
    pad: PadChoice | None = None
    stiffened: bool = False
    stiffener_rings: tuple[int, ...] = ()
    stiffener_stringers: tuple[int, ...] = ()
    stiffener_start: float | None = None
    #: the radius of a crotch blend along its outer saddle (:mod:`tubecad.junctions.blend`), or None
    blend: float | None = None
