"""B-rep shells and solids whose edges are the chosen curvature lines.

Exports are lazy (tubecad.core.lazy): the light modules (layout, wall) load without OCCT."""

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
