"""tubecad: tubular surfaces parameterised by their lines of curvature.

The pipeline, one folder per stage:

- :mod:`tubecad.curves`: axes: slope curves, natural equations k(s), tau(s), parametric
  curves, splines through points, CAD edges (one :class:`~tubecad.curves.Axis` protocol);
- :mod:`tubecad.surface`: the curvature-line tube S(u, s), its forms and regularity;
- :mod:`tubecad.fitting`: the tube fitted into OCCT B-spline surfaces;
- :mod:`tubecad.brep`: shells and solids whose edges are the chosen curvature lines;
- :mod:`tubecad.stiffeners`: curvature lines, stiffeners, panels and flat patterns;
- :mod:`tubecad.export`: CAD files, meshes and pictures;
- :mod:`tubecad.interfaces`: spec files, reports, the ``tubecad`` command line, plugins.

Names are imported on first use (PEP 562), so ``tubecad --help`` and a Ctrl-C at
start-up load no numpy, scipy or OCCT.
"""

from ._lazy import lazy_exports

_PUBLIC = {
    "SlopeCurve": ".curves", "LogSpiral": ".curves", "Helix": ".curves", "Clothoid": ".curves",
    "CircleInvolute": ".curves", "CustomCurvature": ".curves", "Axis": ".curves",
    "NaturalAxis": ".curves.natural", "ParametricAxis": ".curves.parametric", "expression_curve": ".curves.parametric",
    "points_axis": ".curves.points", "edge_axis": ".curves.edge",
    "CurvatureLineTube": ".surface", "FundamentalForms": ".surface", "paper_tube": ".examples",
    "CanalSurface": ".surface.canal", "tube_or_canal": ".surface.canal", "radius_law": ".curves.radius_law",
    "RadiusLaw": ".curves.radius_law",
    "TubecadError": ".errors", "ParameterError": ".errors", "ExpressionError": ".errors",
    "RegularityError": ".errors", "SpecError": ".errors",
    "show": ".interfaces.viewer",
}  # fmt: skip

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
