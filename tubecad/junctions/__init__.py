"""Branches and nozzles: where a branch tube meets a main tube or wall (issue 25).

:mod:`~tubecad.junctions.saddle` computes the saddle curve in the curvature-line parameters
of both surfaces; :mod:`~tubecad.junctions.edges` fits it into the B-spline edge that the
junction's faces share (``saddle_outer``, ``saddle_inner``); :mod:`~tubecad.junctions.solid`
joins a branch wall to a main wall as one solid with the saddles as named edges.
"""

from tubecad.junctions.edges import SaddleEdge, fit_saddle, periodic_bspline, wall_saddles
from tubecad.junctions.placement import branch_surface
from tubecad.junctions.reinforcement import AreaReplacement, area_replacement
from tubecad.junctions.saddle import SaddleCurve, dihedral_angles, saddle_curve
from tubecad.junctions.solid import BranchWall, JunctionWall, build_branched_wall, build_junction_wall

__all__ = [
    "AreaReplacement",
    "BranchWall",
    "JunctionWall",
    "SaddleCurve",
    "SaddleEdge",
    "area_replacement",
    "branch_surface",
    "build_branched_wall",
    "build_junction_wall",
    "dihedral_angles",
    "fit_saddle",
    "periodic_bspline",
    "saddle_curve",
    "wall_saddles",
]
