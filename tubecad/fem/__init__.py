"""Analysis-ready meshes of a wall on its curvature-line net (issue 14): shells on the exact
surface with stiffeners as beams (:func:`shell_mesh`), written for CalculiX/Abaqus
(:mod:`.inp`), gmsh and VTU (:mod:`.meshio_formats`), and solved with CalculiX
(:mod:`.calculix`, :mod:`.analysis`).

Exports are lazy (tubecad.core.lazy): the settings load without numpy, for the spec checker."""

from typing import TYPE_CHECKING

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    **{name: "tubecad.fem.model" for name in ("FEMesh", "ElementBlock", "ShellSection", "BeamSection")},
    **{
        name: "tubecad.fem.settings"
        for name in ("MeshSettings", "mesh_settings", "AnalysisSettings", "analysis_settings")
    },
    **{name: "tubecad.fem.shell" for name in ("StiffenerPlan", "shell_mesh")},
    **{name: "tubecad.fem.inp" for name in ("Material", "Step", "write_inp", "inp_text")},
    **{name: "tubecad.fem.calculix" for name in ("run_ccx", "read_frd", "CalculixError")},
    **{name: "tubecad.fem.junction" for name in ("JunctionTube", "PadRegion", "junction_shell_mesh")},
    **{name: "tubecad.fem.junction_analysis" for name in ("junction_step", "junction_checks")},
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())


if TYPE_CHECKING:  # the names' types for type checkers (nothing is imported here at run time)
    from tubecad.fem.calculix import CalculixError as CalculixError
    from tubecad.fem.calculix import read_frd as read_frd
    from tubecad.fem.calculix import run_ccx as run_ccx
    from tubecad.fem.inp import Material as Material
    from tubecad.fem.inp import Step as Step
    from tubecad.fem.inp import inp_text as inp_text
    from tubecad.fem.inp import write_inp as write_inp
    from tubecad.fem.junction import JunctionTube as JunctionTube
    from tubecad.fem.junction import PadRegion as PadRegion
    from tubecad.fem.junction import junction_shell_mesh as junction_shell_mesh
    from tubecad.fem.junction_analysis import junction_checks as junction_checks
    from tubecad.fem.junction_analysis import junction_step as junction_step
    from tubecad.fem.model import BeamSection as BeamSection
    from tubecad.fem.model import ElementBlock as ElementBlock
    from tubecad.fem.model import FEMesh as FEMesh
    from tubecad.fem.model import ShellSection as ShellSection
    from tubecad.fem.settings import AnalysisSettings as AnalysisSettings
    from tubecad.fem.settings import MeshSettings as MeshSettings
    from tubecad.fem.settings import analysis_settings as analysis_settings
    from tubecad.fem.settings import mesh_settings as mesh_settings
    from tubecad.fem.shell import StiffenerPlan as StiffenerPlan
    from tubecad.fem.shell import shell_mesh as shell_mesh
