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

from typing import TYPE_CHECKING

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
    "CurvatureNet": "tubecad.parts",
    "Branch": "tubecad.parts",
    "NetLayout": "tubecad.brep.layout",
    "AxisLike": "tubecad.parts.axis_input",
    "RadiusLike": "tubecad.parts.axis_input",
    "WallSide": "tubecad.brep.wall",
    "StiffenerSide": "tubecad.stiffeners.profiles",
    "Profile": "tubecad.stiffeners.profiles",
    "CurvatureLineTube": "tubecad.surface",
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
    "load_spec": "tubecad.spec.parse",
    "build_spec": "tubecad.spec.build",
    "export_shape": "tubecad.export.registry",
    "WallDesign": "tubecad.design.wall",
    "JunctionDesign": "tubecad.design.junction",
    "BuildResult": "tubecad.design.result",
}

#: names the top level used to offer, moved to the package that owns them (issue 42): still
#: importable from here with a DeprecationWarning naming their home, left out of ``__all__``
_MOVED = {
    "saddle_curve": "tubecad.junctions",
    "fit_saddle": "tubecad.junctions",
    "build_junction_wall": "tubecad.junctions",
    "build_branched_wall": "tubecad.junctions",
    "JunctionWall": "tubecad.junctions",
    "BranchWall": "tubecad.junctions",
    "branch_surface": "tubecad.junctions",
    "paper_tube": "tubecad.spec.paper",
    "FundamentalForms": "tubecad.surface",
}

__all__ = list(_PUBLIC)
_lazy_getattr, __dir__ = lazy_exports(__name__, _PUBLIC, globals())


def __getattr__(name: str) -> object:
    """A public name, imported on first use; a moved one with a DeprecationWarning."""
    if name in _MOVED:
        import warnings
        from importlib import import_module

        warnings.warn(
            f"tubecad.{name} moved: import it from {_MOVED[name]} (the top level keeps the parts, axes, "
            "laws, layouts, profiles, specs, export and errors)",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(import_module(_MOVED[name]), name)
    return _lazy_getattr(name)


if TYPE_CHECKING:  # the public names' own types for type checkers and IDEs (nothing is imported at run time)
    from tubecad.brep.layout import NetLayout as NetLayout
    from tubecad.brep.wall import WallSide as WallSide
    from tubecad.core.errors import ExpressionError as ExpressionError
    from tubecad.core.errors import ParameterError as ParameterError
    from tubecad.core.errors import RegularityError as RegularityError
    from tubecad.core.errors import SpecError as SpecError
    from tubecad.core.errors import TubecadError as TubecadError
    from tubecad.curves import Axis as Axis
    from tubecad.curves import CircleInvolute as CircleInvolute
    from tubecad.curves import Clothoid as Clothoid
    from tubecad.curves import CustomCurvature as CustomCurvature
    from tubecad.curves import Helix as Helix
    from tubecad.curves import LogSpiral as LogSpiral
    from tubecad.curves import SlopeCurve as SlopeCurve
    from tubecad.curves.edge import edge_axis as edge_axis
    from tubecad.curves.natural import NaturalAxis as NaturalAxis
    from tubecad.curves.parametric import ParametricAxis as ParametricAxis
    from tubecad.curves.parametric import expression_curve as expression_curve
    from tubecad.curves.points import points_axis as points_axis
    from tubecad.curves.radius_law import RadiusLaw as RadiusLaw
    from tubecad.curves.radius_law import radius_law as radius_law
    from tubecad.curves.route import RouteAxis as RouteAxis
    from tubecad.design.junction import JunctionDesign as JunctionDesign
    from tubecad.design.result import BuildResult as BuildResult
    from tubecad.design.wall import WallDesign as WallDesign
    from tubecad.export.registry import export_shape as export_shape
    from tubecad.integrations.viewer import show as show
    from tubecad.junctions import BranchWall as BranchWall
    from tubecad.junctions import JunctionWall as JunctionWall
    from tubecad.junctions import branch_surface as branch_surface
    from tubecad.junctions import build_branched_wall as build_branched_wall
    from tubecad.junctions import build_junction_wall as build_junction_wall
    from tubecad.junctions import fit_saddle as fit_saddle
    from tubecad.junctions import saddle_curve as saddle_curve
    from tubecad.parts import Branch as Branch
    from tubecad.parts import CurvatureJunction as CurvatureJunction
    from tubecad.parts import CurvatureNet as CurvatureNet
    from tubecad.parts import CurvatureTube as CurvatureTube
    from tubecad.parts import CurvatureWall as CurvatureWall
    from tubecad.parts import StiffenedCurvatureWall as StiffenedCurvatureWall
    from tubecad.parts.axis_input import AxisLike as AxisLike
    from tubecad.parts.axis_input import RadiusLike as RadiusLike
    from tubecad.spec.build import build_spec as build_spec
    from tubecad.spec.paper import paper_tube as paper_tube
    from tubecad.spec.parse import load_spec as load_spec
    from tubecad.stiffeners.profiles import Profile as Profile
    from tubecad.stiffeners.profiles import StiffenerSide as StiffenerSide
    from tubecad.surface import CurvatureLineTube as CurvatureLineTube
    from tubecad.surface import FundamentalForms as FundamentalForms
    from tubecad.surface.canal import CanalSurface as CanalSurface
    from tubecad.surface.canal import tube_or_canal as tube_or_canal
    from tubecad.surface.protocol import CurvatureLineSurface as CurvatureLineSurface
