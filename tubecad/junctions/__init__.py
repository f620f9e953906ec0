"""Branches and nozzles: where a branch tube meets a main tube or wall (issue 25).

:mod:`~tubecad.junctions.saddle` computes the saddle curve in the curvature-line parameters
of both surfaces; :mod:`~tubecad.junctions.edges` fits it into the B-spline edge that the
junction's faces share (``saddle_outer``, ``saddle_inner``); :mod:`~tubecad.junctions.solid`
joins a branch wall to a main wall as one solid with the saddles as named edges;
:mod:`~tubecad.junctions.placement` places a straight branch on the main axis.

:mod:`~tubecad.junctions.crotch` and :mod:`~tubecad.junctions.crotch_edges` give an equal tee's saddle
(two curves through the crotch points), :mod:`~tubecad.junctions.touching` joins faces along
exact curves without intersecting them, :mod:`~tubecad.junctions.blend` makes the crotch blend.

Exports are lazy (tubecad.core.lazy): the spec checker places a branch without loading OCCT.
"""

from typing import TYPE_CHECKING

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    **{name: ".edges" for name in ("SaddleEdge", "fit_saddle", "periodic_bspline", "wall_saddles")},
    "branch_surface": ".placement",
    **{name: ".blend" for name in ("RollingBall", "rolling_ball")},
    **{name: ".reinforcement" for name in ("AreaReplacement", "area_replacement")},
    **{name: ".saddle" for name in ("SaddleCurve", "dihedral_angles", "saddle_curve")},
    **{
        name: ".solid"
        for name in ("BranchWall", "JunctionWall", "build_branched_wall", "build_junction_wall", "saddle_name")
    },
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())


if TYPE_CHECKING:  # the names' types for type checkers (nothing is imported here at run time)
    from tubecad.junctions.blend import RollingBall as RollingBall
    from tubecad.junctions.blend import rolling_ball as rolling_ball
    from tubecad.junctions.edges import SaddleEdge as SaddleEdge
    from tubecad.junctions.edges import fit_saddle as fit_saddle
    from tubecad.junctions.edges import periodic_bspline as periodic_bspline
    from tubecad.junctions.edges import wall_saddles as wall_saddles
    from tubecad.junctions.placement import branch_surface as branch_surface
    from tubecad.junctions.reinforcement import AreaReplacement as AreaReplacement
    from tubecad.junctions.reinforcement import area_replacement as area_replacement
    from tubecad.junctions.saddle import SaddleCurve as SaddleCurve
    from tubecad.junctions.saddle import dihedral_angles as dihedral_angles
    from tubecad.junctions.saddle import saddle_curve as saddle_curve
    from tubecad.junctions.solid import BranchWall as BranchWall
    from tubecad.junctions.solid import JunctionWall as JunctionWall
    from tubecad.junctions.solid import build_branched_wall as build_branched_wall
    from tubecad.junctions.solid import build_junction_wall as build_junction_wall
    from tubecad.junctions.solid import saddle_name as saddle_name
