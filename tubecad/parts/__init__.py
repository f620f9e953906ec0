"""CAD-native objects over the library: build123d parts (``CurvatureTube``, ``CurvatureWall``,
``StiffenedCurvatureWall``, ``CurvatureJunction`` with its ``Branch``, ``CurvatureNet``)
and the engine the CadQuery plugin shares with them.

Exports are lazy (tubecad.core.lazy): importing the package loads no OCCT."""

from typing import TYPE_CHECKING

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "CurvatureTube": "tubecad.parts.build123d_parts",
    "CurvatureWall": "tubecad.parts.build123d_parts",
    "StiffenedCurvatureWall": "tubecad.parts.build123d_parts",
    "CurvatureJunction": "tubecad.parts.junction",
    "CurvatureNet": "tubecad.parts.net",
    "Branch": "tubecad.parts.junction",
    "as_axis": "tubecad.parts.axis_input",
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())


if TYPE_CHECKING:  # the names' types for type checkers (nothing is imported here at run time)
    from tubecad.parts.axis_input import as_axis as as_axis
    from tubecad.parts.build123d_parts import CurvatureTube as CurvatureTube
    from tubecad.parts.build123d_parts import CurvatureWall as CurvatureWall
    from tubecad.parts.build123d_parts import StiffenedCurvatureWall as StiffenedCurvatureWall
    from tubecad.parts.junction import Branch as Branch
    from tubecad.parts.junction import CurvatureJunction as CurvatureJunction
    from tubecad.parts.net import CurvatureNet as CurvatureNet
