"""Stiffeners and seams on the curvature-line net: lines, stiffener solids, flat patterns.

Exports are lazy (tubecad.core.lazy): the height limits load without OCCT."""

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    name: "tubecad.stiffeners.lines"
    for name in ("CurvatureLine", "net_lines", "lines_compound", "polylines_csv", "polylines_json")
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
