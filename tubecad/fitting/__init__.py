"""Fitting the curvature-line tube (docs/MATH.md section 6) and canal surfaces (section 8)
into OCCT B-spline surfaces.

Exports are lazy (tubecad.core.lazy): the tolerance policy and the frame fit load without OCCT."""

from typing import TYPE_CHECKING

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


if TYPE_CHECKING:  # the names' types for type checkers (nothing is imported here at run time)
    from tubecad.fitting.canal_section import CanalSectionSurface as CanalSectionSurface
    from tubecad.fitting.canal_section import CanalSpline as CanalSpline
    from tubecad.fitting.canal_section import canal_section_surface as canal_section_surface
    from tubecad.fitting.canal_section import fit_canal as fit_canal
    from tubecad.fitting.exact_section import TubeSurface as TubeSurface
    from tubecad.fitting.exact_section import exact_section_surface as exact_section_surface
    from tubecad.fitting.frame_spline import FitError as FitError
    from tubecad.fitting.frame_spline import FrameSpline as FrameSpline
    from tubecad.fitting.frame_spline import fit_frame as fit_frame
    from tubecad.fitting.measure import SurfaceMeasure as SurfaceMeasure
    from tubecad.fitting.measure import measure_surface as measure_surface
