"""Fitting the curvature-line tube into OCCT B-spline surfaces (docs/MATH.md section 6)."""

from .exact_section import TubeSurface, exact_section_surface
from .frame_spline import FitError, FrameSpline, fit_frame
from .measure import SurfaceMeasure, measure_surface

__all__ = ["TubeSurface", "exact_section_surface", "FrameSpline", "fit_frame", "FitError", "SurfaceMeasure", "measure_surface"]
