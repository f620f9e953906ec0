"""Fitting the curvature-line tube (docs/MATH.md section 6) and canal surfaces (section 8)
into OCCT B-spline surfaces.

Exports are lazy (tubecad._lazy): the tolerance policy and the frame fit load without OCCT."""

from .._lazy import lazy_exports

_PUBLIC = {
    "TubeSurface": ".exact_section", "exact_section_surface": ".exact_section",
    "FrameSpline": ".frame_spline", "fit_frame": ".frame_spline", "FitError": ".frame_spline",
    "SurfaceMeasure": ".measure", "measure_surface": ".measure",
    "CanalSpline": ".canal_section", "CanalSectionSurface": ".canal_section", "fit_canal": ".canal_section",
    "canal_section_surface": ".canal_section",
}  # fmt: skip

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
