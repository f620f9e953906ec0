"""The paper's example tube (Nesvidomin et al. 2026, section 5.2, Fig. 2).

k = 10 / s (a logarithmic spiral in plan), beta = 10 deg, rho = 15. The paper gives no
span; tubecad uses s in [200, 1200], where the tube is regular (rho k <= 0.75 < 1 and the
axis never comes back within 2 rho = 30 of itself: its closest return is about 32.8).
"""

from __future__ import annotations

from .curves import LogSpiral
from .surface import CurvatureLineTube

PAPER_A = 10.0
PAPER_BETA_DEG = 10.0
PAPER_RADIUS = 15.0
PAPER_SPAN = (200.0, 1200.0)


def paper_tube(span: tuple[float, float] = PAPER_SPAN) -> CurvatureLineTube:
    """The paper's tube over ``span`` (default s in [200, 1200])."""
    return CurvatureLineTube(LogSpiral(PAPER_A, PAPER_BETA_DEG, span), PAPER_RADIUS)
