"""Fitting the curvature-line tube (docs/MATH.md section 6) and canal surfaces (section 8)
into OCCT B-spline surfaces.

Exports are lazy (tubecad.core.lazy): the tolerance policy and the frame fit load without OCCT."""

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "TubeSurface": "tubecad.fitting.exact_section",
    "exact_section_surface": "tubecad.fitting.exact_section",
    "FrameSpline": "tubecad.fitting.frame_spline",
    "fit_frame": "tubecad.fitting.frame_spline",
    "FitError": "tubecad.fitting.frame_spline",
    "SurfaceMeasure": "tubecad.fitting.measure",
    "measure_surface": "tubecad.fitting.measure",
    "CanalSpline": "tubecad.fitting.canal_section",
    "CanalSectionSurface": "tubecad.fitting.canal_section",
    "fit_canal": "tubecad.fitting.canal_section",
    "canal_section_surface": "tubecad.fitting.canal_section",
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
