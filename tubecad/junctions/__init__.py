"""Branches and nozzles: where a branch tube meets a main tube or wall (issue 25).

:mod:`~tubecad.junctions.saddle` computes the saddle curve in the curvature-line parameters
of both surfaces; :mod:`~tubecad.junctions.edges` fits it into the B-spline edge that the
junction's faces share (``saddle_outer``, ``saddle_inner``).
"""

from tubecad.junctions.edges import SaddleEdge, fit_saddle, periodic_bspline, wall_saddles
from tubecad.junctions.reinforcement import AreaReplacement, area_replacement
from tubecad.junctions.saddle import SaddleCurve, dihedral_angles, saddle_curve

__all__ = [
    "AreaReplacement",
    "SaddleCurve",
    "SaddleEdge",
    "area_replacement",
    "dihedral_angles",
    "fit_saddle",
    "periodic_bspline",
    "saddle_curve",
    "wall_saddles",
]
