"""tubecad: tubular surfaces parameterised by their lines of curvature.

The pipeline, one folder per stage:

- :mod:`tubecad.curves`: axes: slope curves, natural equations k(s), tau(s), parametric
  curves, splines through points, CAD edges (one :class:`~tubecad.curves.Axis` protocol);
- :mod:`tubecad.surface`: the curvature-line tube S(u, s), its forms and regularity;
- :mod:`tubecad.fitting`: the tube fitted into OCCT B-spline surfaces;
- :mod:`tubecad.brep`: shells and solids whose edges are the chosen curvature lines;
- :mod:`tubecad.stiffeners`: curvature lines, stiffeners, panels and flat patterns;
- :mod:`tubecad.export`: CAD files, meshes and pictures;
- :mod:`tubecad.fem` and :mod:`tubecad.shop`: analysis meshes and shop-floor outputs;
- :mod:`tubecad.spec` and :mod:`tubecad.batch`: spec files, their builds and reports, batches;
- :mod:`tubecad.parts`: the build123d objects ``CurvatureTube``, ``CurvatureWall`` and
  ``StiffenedCurvatureWall``;
- :mod:`tubecad.cli` and :mod:`tubecad.integrations`: the ``tubecad`` command line, the viewer
  and the CadQuery plugin (``curvatureTube``, ``curvatureWall``);
- :mod:`tubecad.core`: errors, units, validation, the tolerance policy, atomic writes.

Names are imported on first use (PEP 562), so ``tubecad --help`` and a Ctrl-C at
start-up load no numpy, scipy or OCCT.
"""

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "SlopeCurve": "tubecad.curves",
    "LogSpiral": "tubecad.curves",
    "Helix": "tubecad.curves",
    "Clothoid": "tubecad.curves",
    "CircleInvolute": "tubecad.curves",
    "CustomCurvature": "tubecad.curves",
    "Axis": "tubecad.curves",
    "NaturalAxis": "tubecad.curves.natural",
    "ParametricAxis": "tubecad.curves.parametric",
    "expression_curve": "tubecad.curves.parametric",
    "points_axis": "tubecad.curves.points",
    "edge_axis": "tubecad.curves.edge",
    "RouteAxis": "tubecad.curves.route",
    "CurvatureTube": "tubecad.parts",
    "CurvatureWall": "tubecad.parts",
    "StiffenedCurvatureWall": "tubecad.parts",
    "CurvatureJunction": "tubecad.parts",
    "Branch": "tubecad.parts",
    "NetLayout": "tubecad.brep.layout",
    "Profile": "tubecad.stiffeners.profiles",
    "saddle_curve": "tubecad.junctions",
    "fit_saddle": "tubecad.junctions",
    "build_junction_wall": "tubecad.junctions",
    "build_branched_wall": "tubecad.junctions",
    "JunctionWall": "tubecad.junctions",
    "BranchWall": "tubecad.junctions",
    "branch_surface": "tubecad.junctions",
    "CurvatureLineTube": "tubecad.surface",
    "FundamentalForms": "tubecad.surface",
    "paper_tube": "tubecad.spec.paper",
    "CanalSurface": "tubecad.surface.canal",
    "CurvatureLineSurface": "tubecad.surface.protocol",
    "tube_or_canal": "tubecad.surface.canal",
    "radius_law": "tubecad.curves.radius_law",
    "RadiusLaw": "tubecad.curves.radius_law",
    "TubecadError": "tubecad.core.errors",
    "ParameterError": "tubecad.core.errors",
    "ExpressionError": "tubecad.core.errors",
    "RegularityError": "tubecad.core.errors",
    "SpecError": "tubecad.core.errors",
    "show": "tubecad.integrations.viewer",
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
