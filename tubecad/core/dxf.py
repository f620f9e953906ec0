"""The one DXF writer: plane drawings at 1:1 in the model's length unit, written atomically.

Every DXF tubecad writes (the webs' flat patterns, the nested plates, the panels'
developments) is made here: closed or open polylines (arcs exact, as bulges), circles,
lines and text, each on a named layer, in a file that states its unit ($INSUNITS, and
$MEASUREMENT: imperial for in and ft, metric otherwise). Coordinates are the model's own,
never rescaled. In core/ because the stiffeners' flat patterns, below export/, write DXF too;
light on import (ezdxf is imported when a drawing is made).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from tubecad.core.atomic import atomic_path
from tubecad.core.units import DEFAULT_LENGTH_UNIT, length_unit

Points = Callable[[np.ndarray], np.ndarray]


class Drawing:
    """A DXF drawing in ``unit`` (a spec's [units] length name), its layers given as
    ``{name: DXF colour index or None}`` (None: the layer's default colour) or added with
    :meth:`layer`; :meth:`save` writes it atomically."""

    def __init__(self, unit: str = DEFAULT_LENGTH_UNIT, layers: Mapping[str, int | None] | None = None) -> None:
        import ezdxf

        self.unit = length_unit(unit)
        self.doc = ezdxf.new(units=self.unit.dxf)  # sets $INSUNITS and $MEASUREMENT
        self.space = self.doc.modelspace()
        for name, colour in (layers or {}).items():
            self.layer(name, colour)

    def layer(self, name: str, colour: int | None = None) -> None:
        """Add the layer ``name`` (DXF colour index ``colour``; None: ezdxf's default)."""
        if colour is None:
            self.doc.layers.add(name)
        else:
            self.doc.layers.add(name, color=colour)

    def polyline(self, points: Any, layer: str, closed: bool = True, bulges: Iterable[float] | None = None) -> None:
        """A polyline through ``points`` ((n, 2)); ``bulges``: one per vertex, the arc to the
        next vertex (tan of a quarter of its angle, > 0 counter-clockwise; 0 a straight edge)."""
        attribs = {"layer": layer}
        if bulges is None:
            self.space.add_lwpolyline(np.asarray(points).tolist(), close=closed, dxfattribs=attribs)
        else:
            vertices = [(x, y, b) for (x, y), b in zip(np.asarray(points).tolist(), bulges)]
            self.space.add_lwpolyline(vertices, format="xyb", close=closed, dxfattribs=attribs)

    def sector(self, r_in: float, r_out: float, angle: float, layer: str, place: Points | None = None) -> None:
        """The annular sector of radii ``r_in`` < ``r_out`` and ``angle`` (radians) about the
        origin, symmetric about +y, as one closed polyline with exact arcs (each half arc,
        <= 180 deg, one bulge): outer arc, radial edge, inner arc back, radial edge.
        ``place``: a rigid motion of the points (a rotation and shift keep every bulge)."""
        bulge = math.tan(angle / 8.0)
        a = 0.5 * math.pi + 0.5 * angle * np.array([-1.0, 0.0, 1.0])
        arc = np.stack([np.cos(a), np.sin(a)], axis=1)
        corners = np.concatenate([r_out * arc, r_in * arc[::-1]])
        corners = corners if place is None else place(corners)
        self.polyline(corners, layer, closed=True, bulges=[bulge, bulge, 0.0, -bulge, -bulge, 0.0])

    def circle(self, centre: Any, radius: float, layer: str) -> None:
        self.space.add_circle(tuple(centre), float(radius), dxfattribs={"layer": layer})

    def line(self, start: Any, end: Any, layer: str) -> None:
        self.space.add_line(tuple(start), tuple(end), dxfattribs={"layer": layer})

    def text(self, text: str, insert: Any, height: float, layer: str) -> None:
        """``text`` of ``height`` (model units) with its baseline's start at ``insert``."""
        self.space.add_text(text, height=height, dxfattribs={"layer": layer, "insert": tuple(insert)})

    def save(self, path: str | Path) -> Path:
        """Write the drawing to ``path`` atomically (a failed write leaves no partial file)."""
        with atomic_path(path) as tmp:
            self.doc.saveas(tmp)
        return Path(path)
