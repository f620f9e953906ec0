"""B-rep shells and solids whose edges are the chosen curvature lines."""

from .layout import NetLayout
from .solids import (
    TubeBuild, build_tube_shell, build_tube_solid, build_wall_solid, tube_shell, tube_solid, wall_solid, wall_radii,
)  # fmt: skip

__all__ = ["NetLayout", "TubeBuild", "build_tube_shell", "build_tube_solid", "build_wall_solid", "tube_shell",
           "tube_solid", "wall_solid", "wall_radii"]  # fmt: skip
