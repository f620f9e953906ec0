"""The curvature-line tube S(u, s), its fundamental forms and regularity (docs/MATH.md sections 2-5)."""

from .forms import FundamentalForms, SurfaceDerivatives
from .regularity import RegularityReport, check_regularity
from .tube import CurvatureLineTube
from .canal import CanalRegularity, CanalSurface, tube_or_canal

__all__ = ["CurvatureLineTube", "FundamentalForms", "SurfaceDerivatives", "RegularityReport", "check_regularity",
           "CanalSurface", "CanalRegularity", "tube_or_canal"]
