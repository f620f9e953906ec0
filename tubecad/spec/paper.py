"""The paper's example tube (Nesvidomin et al. 2026, section 5.2, Fig. 2).

k = 10 / s (a logarithmic spiral in plan), beta = 10 deg, rho = 15. The paper gives no
span; tubecad uses s in [200, 1200], where the tube is regular (rho k <= 0.75 < 1 and the
axis never comes back within 2 rho = 30 of itself: its closest return is about 32.8).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from tubecad.curves import LogSpiral
from tubecad.surface import CurvatureLineTube

if TYPE_CHECKING:
    from tubecad.brep import NetLayout, TubeBuild
    from tubecad.stiffeners.solids import Stiffener

PAPER_A = 10.0
PAPER_BETA_DEG = 10.0
PAPER_RADIUS = 15.0
PAPER_SPAN = (200.0, 1200.0)
#: the wall `tubecad paper` writes: 2 thick, centred (radii 14 and 16). The axis comes back
#: within 32.8 of itself near s = 200, so an outer radius above about 16.4 self-intersects.
PAPER_WALL_THICKNESS = 2.0
PAPER_RINGS = 11
PAPER_STRINGERS = 8


def PAPER_LAYOUT(tube: CurvatureLineTube) -> NetLayout:  # noqa: N802 - reads as a constant
    """11 ring frames every 100 along the axis (ends included) and 8 stringers 45 deg apart."""
    from tubecad.brep import NetLayout  # OCCT is loaded only when B-rep is asked for

    return NetLayout.equal(tube, PAPER_RINGS, PAPER_STRINGERS)


def paper_tube(span: tuple[float, float] = PAPER_SPAN) -> CurvatureLineTube:
    """The paper's tube over ``span`` (default s in [200, 1200])."""
    return CurvatureLineTube(LogSpiral(PAPER_A, PAPER_BETA_DEG, span), PAPER_RADIUS)


#: the stiffeners `tubecad paper` adds, inside the wall (outside, the next coil is only
#: 32.8 - 32 = 0.8 away near s = 200): flat-bar ring frames 3 high, 1 thick at the 9
#: interior rings, and flat-bar stringers 2 high, 1 thick at 0, 90, 180 and 270 deg. They
#: are separate solids that overlap where stringers cross rings (fuse merges them).
PAPER_STIFFENER_RINGS = list(range(1, PAPER_RINGS - 1))
PAPER_STIFFENER_STRINGERS = [0, 2, 4, 6]
PAPER_RING_PROFILE = ("flat", 3.0, 1.0)
PAPER_STRINGER_PROFILE = ("flat", 2.0, 1.0)
STEEL_DENSITY = 7.85e-6  # kg / mm^3


def paper_wall() -> TubeBuild:
    """The wall `tubecad paper` writes: the paper's tube, PAPER_WALL_THICKNESS thick,
    centred, on PAPER_LAYOUT."""
    from tubecad.brep import build_wall_solid

    tube = paper_tube()
    return build_wall_solid(tube, PAPER_WALL_THICKNESS, "centered", PAPER_LAYOUT(tube))


def paper_stiffeners(build: TubeBuild) -> list[Stiffener]:
    """The stiffeners `tubecad paper` adds to ``build`` (the paper wall): flat-bar ring frames
    at PAPER_STIFFENER_RINGS and stringers at PAPER_STIFFENER_STRINGERS, inside the wall."""
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.profiles import Profile

    rings = build_stiffeners(build, PAPER_STIFFENER_RINGS, [], Profile(*PAPER_RING_PROFILE), "inside")
    return rings + build_stiffeners(build, [], PAPER_STIFFENER_STRINGERS, Profile(*PAPER_STRINGER_PROFILE), "inside")
