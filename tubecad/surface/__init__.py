"""The curvature-line tube S(u, s), its fundamental forms and regularity (docs/MATH.md sections 2-5)."""

from tubecad.surface.canal import CanalRegularity, CanalSurface, tube_or_canal
from tubecad.surface.forms import FundamentalForms, SurfaceDerivatives
from tubecad.surface.protocol import CurvatureLineSurface, is_surface
from tubecad.surface.regularity import RegularityReport, check_regularity
from tubecad.surface.tube import CurvatureLineTube

__all__ = [
    "CurvatureLineTube",
    "CurvatureLineSurface",
    "is_surface",
    "FundamentalForms",
    "SurfaceDerivatives",
    "RegularityReport",
    "check_regularity",
    "CanalSurface",
    "CanalRegularity",
    "tube_or_canal",
]
