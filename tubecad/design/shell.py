"""A design's finite-element shell model: the one path of ``tubecad mesh`` and ``analyse``.

Each design makes its own model (:meth:`~tubecad.design.wall.WallDesign.shell_model`,
:meth:`~tubecad.design.junction.JunctionDesign.shell_model`: the meshing itself is in
:mod:`tubecad.design.wall` and :mod:`tubecad.design.junction_shell`), and the model knows its loads and checks, so the mesh
and analysis commands never ask which kind they hold (the :class:`ShellModel` protocol):

- :class:`WallShellModel`: the wall (or surface) meshed on the exact surface by
  :func:`tubecad.fem.shell_mesh` (shells on the net, stiffeners as beams, panels as sets);
  its pressure step :func:`tubecad.fem.loads.pressure_step` (capped, fixed, free or closed
  ends, loaded on the reference surface);
- :class:`JunctionShellModel`: the main and branch walls' mid-surfaces joined on their saddle
  (:func:`tubecad.fem.junction.junction_shell_mesh`), pads as thicker shells, stiffeners as
  beams snapped to the pads' edges; its pressure step
  :func:`tubecad.fem.junction_analysis.junction_step` and the membrane and saddle checks
  (:func:`tubecad.fem.junction_analysis.junction_checks`).

Errors speak Python terms (the mesh settings' names, ``size``, ``surface``, ``ends``) and
carry the stage ``mesh`` (or ``branches``, ``stiffeners``), which the spec turns into sections.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

from tubecad.design.stages import stage

if TYPE_CHECKING:
    import numpy as np

    from tubecad.fem.inp import Step
    from tubecad.fem.junction import JunctionTube, PadRegion
    from tubecad.fem.model import FEMesh
    from tubecad.surface.protocol import CurvatureLineSurface


class ShellModel(Protocol):
    """A design meshed for analysis: its ``mesh``, and the loads and checks that fit it."""

    @property
    def mesh(self) -> FEMesh:
        """The finite-element model (nodes, shells, beams, sets)."""
        ...

    def pressure_step(self, pressure: float, ends: str) -> Step:
        """The step of internal ``pressure`` with the ``ends`` condition."""
        ...

    def checks(self, stress: np.ndarray, ring_stress: np.ndarray, pressure: float) -> dict[str, Any] | None:
        """What the model checks in a solved stress field (None: nothing beyond the summary)."""
        ...


@dataclass(frozen=True)
class WallShellModel:
    """A wall's (or a surface's) shell model and the surface its first shells lie on."""

    mesh: FEMesh
    surface: CurvatureLineSurface

    def pressure_step(self, pressure: float, ends: str) -> Step:
        """:func:`tubecad.fem.loads.pressure_step` on the reference surface, the end rings'
        node sets in order."""
        from tubecad.fem.loads import pressure_step

        d = self.mesh.info["reference_offsets"][0]
        surface = self.surface if d == 0 else self.surface.offset(d, allow_irregular=True)
        rings = (self.mesh.node_sets.get("start_ring"), self.mesh.node_sets.get("end_ring"))
        with stage("analysis"):
            return pressure_step(self.mesh, pressure, ends, surface, rings)  # type: ignore[arg-type]

    def checks(self, stress: np.ndarray, ring_stress: np.ndarray, pressure: float) -> None:  # noqa: ARG002 - the protocol's signature
        """A wall's figures are the summary's (membrane stresses along the rings): None."""
        return None


@dataclass(frozen=True)
class JunctionShellModel:
    """A junction's shell ``mesh`` with the ``tubes`` it joins (the main first) and its ``pads``."""

    mesh: FEMesh
    tubes: list[JunctionTube]
    pads: list[PadRegion]

    def pressure_step(self, pressure: float, ends: str) -> Step:
        """:func:`tubecad.fem.junction_analysis.junction_step`."""
        from tubecad.fem.junction_analysis import junction_step

        with stage("analysis"):
            return junction_step(self.mesh, self.tubes, pressure, junction_ends(ends, ends))

    def checks(self, stress: np.ndarray, ring_stress: np.ndarray, pressure: float) -> dict[str, Any]:
        """The membrane check per tube and the saddle's stress concentration."""
        from tubecad.fem.junction_analysis import junction_checks

        return junction_checks(self.mesh, self.tubes, stress, ring_stress, pressure)


@dataclass(frozen=True)
class NetShellModel:
    """A host face's shell ``mesh`` (:func:`tubecad.fem.net_shell.net_shell_mesh`): shells on
    its net's patches, webs as beams, its boundary held."""

    mesh: FEMesh

    def pressure_step(self, pressure: float, ends: str) -> Step:  # noqa: ARG002 - the protocol's signature
        """:func:`tubecad.fem.net_shell.net_pressure_step`: the pressure on the shells, the
        face's boundary fixed (the design's ends: always ``fixed``)."""
        from tubecad.fem.net_shell import net_pressure_step

        with stage("analysis"):
            return net_pressure_step(self.mesh, pressure)

    def checks(self, stress: np.ndarray, ring_stress: np.ndarray, pressure: float) -> None:  # noqa: ARG002 - the protocol's signature
        """A face's figures are the summary's: None."""
        return None


# --- the end conditions a model takes -------------------------------------------------------
def wall_ends(given: str | None, default: str) -> str:
    """A wall's ends: ``given`` (checked by its step), else the settings' ``default`` (fixed;
    free round a closed axis: :func:`tubecad.fem.settings.analysis_settings`)."""
    return default if given is None else given


def junction_ends(given: str | None, default: str) -> str:  # noqa: ARG001 - the designs' signature
    """A junction's ends: ``given`` if one of capped or fixed (its main and branch ends are
    open tubes), else capped (not the settings' ``default``, a lone tube's); a
    ParameterError naming ``ends`` otherwise."""
    from tubecad.core.errors import ParameterError
    from tubecad.fem.junction_analysis import JUNCTION_ENDS

    ends = given or "capped"
    if ends not in JUNCTION_ENDS:
        raise ParameterError(
            f"ends must be one of {', '.join(JUNCTION_ENDS)} for a junction (its main and branch ends are "
            f"open), got {ends!r:.40}",
            key="ends",
        )
    return ends
