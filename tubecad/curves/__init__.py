"""Axes: the :class:`Axis` protocol every stage takes (docs/MATH.md section 7) and its kinds;
slope curves from a natural equation k(s) and an elevation angle (section 1).
"""

from tubecad.curves.axis import Axis, AxisFrame
from tubecad.curves.custom import CustomCurvature
from tubecad.curves.families import CircleInvolute, Clothoid, Helix, LogSpiral
from tubecad.curves.radius_law import RadiusLaw, radius_law
from tubecad.curves.slope_curve import AxisSample, SlopeCurve

#: spec-file name -> class
FAMILIES: dict[str, type[SlopeCurve]] = {
    cls.family: cls for cls in (LogSpiral, Helix, Clothoid, CircleInvolute, CustomCurvature)
}

__all__ = [
    "Axis",
    "AxisFrame",
    "AxisSample",
    "SlopeCurve",
    "LogSpiral",
    "Helix",
    "Clothoid",
    "CircleInvolute",
    "CustomCurvature",
    "FAMILIES",
    "RadiusLaw",
    "radius_law",
]
