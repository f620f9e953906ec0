"""Axes: slope curves from a natural equation k(s) and an elevation angle (docs/MATH.md section 1)."""

from .custom import CustomCurvature
from .families import CircleInvolute, Clothoid, Helix, LogSpiral
from .slope_curve import AxisSample, SlopeCurve

#: spec-file name -> class
FAMILIES: dict[str, type[SlopeCurve]] = {
    cls.family: cls for cls in (LogSpiral, Helix, Clothoid, CircleInvolute, CustomCurvature)
}

__all__ = ["AxisSample", "SlopeCurve", "LogSpiral", "Helix", "Clothoid", "CircleInvolute", "CustomCurvature", "FAMILIES"]
