"""Analysis-ready meshes of a wall on its curvature-line net (issue 14): shells on the exact
surface with stiffeners as beams (:func:`shell_mesh`), written for CalculiX/Abaqus
(:mod:`.inp`), gmsh and VTU (:mod:`.meshio_formats`), and solved with CalculiX
(:mod:`.calculix`, :mod:`.analysis`).

Exports are lazy (tubecad.core.lazy): the settings load without numpy, for the spec checker."""

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
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
