"""B-rep shells and solids whose edges are the chosen curvature lines.

Exports are lazy (tubecad.core.lazy): the light modules (layout, wall) load without OCCT."""

from typing import TYPE_CHECKING

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "NetLayout": "tubecad.brep.layout",
    "wall_radii": "tubecad.brep.wall",
    **{
        name: "tubecad.brep.solids"
        for name in (
            "TubeBuild",
            "build_tube_shell",
            "build_tube_solid",
            "build_wall_solid",
            "tube_shell",
            "tube_solid",
            "wall_solid",
        )
    },
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())


if TYPE_CHECKING:  # the names' types for type checkers (nothing is imported here at run time)
    from tubecad.brep.layout import NetLayout as NetLayout
    from tubecad.brep.solids import TubeBuild as TubeBuild
    from tubecad.brep.solids import build_tube_shell as build_tube_shell
    from tubecad.brep.solids import build_tube_solid as build_tube_solid
    from tubecad.brep.solids import build_wall_solid as build_wall_solid
    from tubecad.brep.solids import tube_shell as tube_shell
    from tubecad.brep.solids import tube_solid as tube_solid
    from tubecad.brep.solids import wall_solid as wall_solid
    from tubecad.brep.wall import wall_radii as wall_radii
