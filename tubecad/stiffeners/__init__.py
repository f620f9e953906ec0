"""Stiffeners and seams on the curvature-line net: lines, stiffener solids, flat patterns.

Exports are lazy (tubecad.core.lazy): the height limits load without OCCT."""

from typing import TYPE_CHECKING

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    name: "tubecad.stiffeners.lines"
    for name in ("CurvatureLine", "net_lines", "lines_compound", "polylines_csv", "polylines_json")
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())


if TYPE_CHECKING:  # the names' types for type checkers (nothing is imported here at run time)
    from tubecad.stiffeners.lines import CurvatureLine as CurvatureLine
    from tubecad.stiffeners.lines import lines_compound as lines_compound
    from tubecad.stiffeners.lines import net_lines as net_lines
    from tubecad.stiffeners.lines import polylines_csv as polylines_csv
    from tubecad.stiffeners.lines import polylines_json as polylines_json
