"""tubecad: tubular surfaces parameterised by their lines of curvature.

The pipeline, one folder per stage:

- :mod:`tubecad.curves`: axes from a natural equation k(s) and an elevation angle;
- :mod:`tubecad.surface`: the curvature-line tube S(u, s), its forms and regularity;
- :mod:`tubecad.export`: pictures (and, later, CAD files);
- :mod:`tubecad.interfaces`: spec files, reports and the ``tubecad`` command line.
"""

from .curves import CircleInvolute, Clothoid, CustomCurvature, Helix, LogSpiral, SlopeCurve
from .errors import ExpressionError, ParameterError, RegularityError, SpecError, TubecadError
from .examples import paper_tube
from .surface import CurvatureLineTube, FundamentalForms

__all__ = [
    "SlopeCurve", "LogSpiral", "Helix", "Clothoid", "CircleInvolute", "CustomCurvature",
    "CurvatureLineTube", "FundamentalForms", "paper_tube",
    "TubecadError", "ParameterError", "ExpressionError", "RegularityError", "SpecError",
]  # fmt: skip
