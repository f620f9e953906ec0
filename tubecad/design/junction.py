"""A junction design: a main wall (:class:`~tubecad.design.wall.WallDesign`) with every
:class:`~tubecad.design.model.BranchDesign` joined on. It is built by
:mod:`tubecad.design.junction_build` (the solid, pads, stiffeners, named edges, report),
meshed by :mod:`tubecad.design.junction_shell` and made into a shop package by
:mod:`tubecad.design.junction_shop`; each of them names this class for its annotations only."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from tubecad.core.progress import Progress
from tubecad.design.model import BranchDesign, StiffenerChoice
from tubecad.design.wall import WallDesign

if TYPE_CHECKING:
    from tubecad.design.result import BuildResult
    from tubecad.design.shell import ShellModel
    from tubecad.design.shop import ShopPackage
    from tubecad.fem.settings import MeshSettings
    from tubecad.shop.fabrication import Fabrication


@dataclass(frozen=True)
class JunctionDesign:
    """A main wall (``main``: its surface, net, wall and stiffeners; panels are not split
    round openings) with every branch of ``branches`` joined on: one solid, W = (A_o u B_o) -
    (A_i u B_i); ``reinforcement`` = (pressure, allowable stress) asks for each opening's
    area-replacement figures in the report.

    Args:
        main: the main wall's design (its ``wall`` required; ``panels`` are not split round openings).
        branches: the branches joined on (:class:`~tubecad.design.model.BranchDesign`).
        reinforcement: (pressure, allowable stress) for each opening's area-replacement
            figures in the report, or None.
    """

    main: WallDesign
    branches: tuple[BranchDesign, ...]
    reinforcement: tuple[float, float] | None = None

    #: what it is written as: CAD files, meshes and a PNG picture (no SVG projection, no polylines yet)
    WRITTEN_AS: ClassVar[frozenset[str]] = frozenset({"cad", "mesh", "png"})
    WHAT: ClassVar[str] = "a junction"
    #: a junction's shop package always has its branches' templates
    SHOP_NEEDS_PARTS: ClassVar[bool] = False

    @property
    def length_unit(self) -> str:
        """The main design's length unit."""
        return self.main.length_unit

    @property
    def stiffeners(self) -> StiffenerChoice | None:
        """The main wall's stiffeners (each branch says whether it has its own)."""
        return self.main.stiffeners

    def build(self, progress: Progress | None = None) -> BuildResult:
        """The junction solid, its pads and stiffeners, named and measured
        (:func:`build_junction`)."""
        from tubecad.design.junction_build import build_junction

        return build_junction(self, progress)

    def shell_model(self, settings: MeshSettings) -> ShellModel:
        """The junction meshed for analysis with ``settings``
        (:func:`tubecad.design.shell.junction_shell_model`)."""
        from tubecad.design.junction_shell import junction_shell_model

        return junction_shell_model(self.main, self.branches, settings)

    def shop(self, fab: Fabrication, progress: Callable[[str], None] | None = None) -> ShopPackage:
        """The junction's shop package with the fabrication settings ``fab``
        (:func:`tubecad.design.junction_shop.junction_shop`)."""
        from tubecad.design.junction_shop import junction_shop

        return junction_shop(self, fab, progress)

    def analysis_ends(self, given: str | None, default: str) -> str:
        """The pressure step's end condition (:func:`tubecad.design.shell.junction_ends`)."""
        from tubecad.design.shell import junction_ends

        return junction_ends(given, default)
