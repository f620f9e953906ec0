"""What a CAD user hands over as an axis, made a tubecad :class:`~tubecad.curves.Axis`.

One rule for the build123d objects and the CadQuery plugin alike:

- an :class:`~tubecad.curves.Axis` (any kind: slope curve, natural equations, parametric,
  route, ...) is taken as it is;
- a build123d or CadQuery ``Edge`` or ``Wire``, a ``TopoDS`` edge or wire, or an OCCT
  ``Geom_Curve``: the curve itself (:func:`~tubecad.curves.edge.edge_axis`);
- build123d's line builder (``with BuildLine() as path: ...``, then ``path``), its ``Curve``
  (``path.line``) or a list of edges joined end to end (``path.edges()``, a ``BuildPart``'s
  ``pending_edges``): the wire they make;
- a sequence of points: with ``bend_radius`` the pipe route of straight legs and circular
  bends through them (:class:`~tubecad.curves.route.RouteAxis`), without it the C2 cubic
  spline through them (:func:`~tubecad.curves.points.points_axis`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.curves import Axis
from tubecad.curves.radius_law import RadiusLaw

if TYPE_CHECKING:
    import build123d as bd

AXIS_KINDS = "a tubecad Axis, a build123d or CadQuery Edge or Wire, or a sequence of (x, y, z) points"

#: what the parts take as an axis (see the module): a tubecad Axis, a build123d Edge or Wire
#: (or a CadQuery one, a TopoDS edge or wire, an OCCT Geom_Curve: typed Any by their
#: libraries), or (x, y, z) points
AxisLike: TypeAlias = (
    "Axis | bd.Edge | bd.Wire | bd.Curve | bd.BuildLine | Sequence[bd.Edge] | Sequence[Sequence[float]] | np.ndarray"
)
#: what the parts take as a radius: a number (a tube), an expression in s or a table of
#: [s, r] rows (a canal surface's radius law), or a RadiusLaw
RadiusLike: TypeAlias = "float | str | Sequence[Sequence[float]] | RadiusLaw"


def as_axis(
    axis: AxisLike,
    *,
    bend_radius: float | Sequence[float] | None = None,
    normal: Sequence[float] | None = None,
    closed: bool | None = None,
) -> Axis:
    """The :class:`~tubecad.curves.Axis` that ``axis`` stands for (see the module)."""
    axis = _joined(axis)
    if isinstance(axis, Axis):
        if bend_radius is not None or normal is not None or closed is not None:
            raise ParameterError(
                "bend_radius, normal and closed apply to an axis given as points or an edge, not to an Axis"
            )
        return axis
    if _is_curve(axis):
        if bend_radius is not None:
            raise ParameterError(
                "bend_radius applies to an axis given as points (a route); an edge keeps its own shape"
            )
        from tubecad.curves.edge import edge_axis

        return edge_axis(axis, normal=normal, closed=closed)
    if isinstance(axis, (str, bytes)) or not isinstance(axis, Sequence | np.ndarray):
        raise ParameterError(f"axis must be {AXIS_KINDS}, got {type(axis).__name__}")
    if bend_radius is not None:
        from tubecad.curves.route import RouteAxis

        return RouteAxis(axis, bend_radius, normal=normal, closed=closed)
    from tubecad.curves.points import points_axis

    return points_axis(axis, normal=normal, closed=closed)


def _joined(axis: Any) -> Any:
    """build123d's pending edges as one wire: a BuildLine builder's line, a Curve (a compound of
    edges) or a list of build123d edges joined end to end (a ParameterError if they do not
    join); anything else as it is."""
    import build123d as bd

    if isinstance(axis, bd.BuildLine):
        axis = axis.line
    if isinstance(axis, bd.Curve):
        edges = list(axis.edges())
    elif isinstance(axis, Sequence) and axis and all(isinstance(e, bd.Edge) for e in axis):
        edges = list(axis)
    else:
        return axis
    if not edges:
        raise ParameterError("axis: the line has no edges")
    wires = bd.Wire.combine(edges)
    if len(wires) != 1:
        raise ParameterError(f"axis: the {len(edges)} edges do not join end to end into one line ({len(wires)} pieces)")
    return wires[0]


def _is_curve(axis: Any) -> bool:
    """An OCCT curve or a CAD object holding an OCCT shape (build123d and CadQuery: ``.wrapped``)."""
    if hasattr(axis, "wrapped"):
        return True
    module = type(axis).__module__ or ""
    return module.startswith("OCP.")
