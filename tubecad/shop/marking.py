"""Marking lines (issue 13): where each stiffener stands on each panel, as curves on the
panel's surface, so that the yard can mark the plate before fitting.

A stiffener stands on a line of curvature of the wall surface on its side (outer for
``outside``, inner for ``inside``). On a panel its marking line is that line between the
panel's seams (a ring) or rings (a stringer). Both are isolines of the wall's fitted
surface, the surface whose pieces are the panel's faces: a ring the isoline v = s (the
exact rational circle), a stringer the isoline u = u(theta), trimmed to the panel, so
they lie on the panel's face to the fit's rounding, not merely within the fit tolerance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import build123d as bd
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge

from tubecad.brep import TubeBuild
from tubecad.fitting import TubeSurface
from tubecad.stiffeners.panel import Panel
from tubecad.stiffeners.solids import Stiffener

#: how far (a fraction of the span) a ring may lie outside a panel's s range and still mark it
EDGE_SLACK = 1e-9


@dataclass(frozen=True)
class MarkingLine:
    """A stiffener's line on one panel: a ring at ``value`` = s across ``extent`` (degrees),
    or a stringer at ``value`` = angle (degrees) along ``extent`` (s)."""

    name: str  # mark_ring_03, mark_stringer_02
    stiffener: str
    kind: str
    value: float
    extent: tuple[float, float]

    def edge(self, surface: TubeSurface) -> bd.Edge:
        """The line as an edge of ``surface``'s isoline (module docstring)."""
        geom = surface.surface
        if self.kind == "ring":
            u0 = float(surface.u_at(self.extent[0]))
            sweep = self.extent[1] - self.extent[0]
            u1 = u0 + 2 * math.pi if sweep >= 360.0 - 1e-9 else float(surface.u_at(self.extent[1]))
            if u1 <= u0:
                u1 += 2 * math.pi
            maker = BRepBuilderAPI_MakeEdge(geom.VIso(float(self.value)), u0, u1)
        else:
            maker = BRepBuilderAPI_MakeEdge(geom.UIso(float(surface.u_at(self.value))), *map(float, self.extent))
        edge = bd.Edge(maker.Edge())
        edge.label = self.name
        return edge


def marking_surface(build: TubeBuild, side: str) -> TubeSurface:
    """The wall's fitted surface that stiffeners on ``side`` stand on."""
    return build.surfaces[0] if side == "outside" else build.surfaces[-1]


def panel_marking(panel: Panel, stiffeners: list[Stiffener]) -> list[MarkingLine]:
    """The marking lines of ``stiffeners`` (whole stiffeners, not pieces) on ``panel``:
    rings whose s lies in the panel's s range (its edges included), stringers whose angle
    lies between its seams (the seams included)."""
    s_a, s_b = panel.s_range
    a, b = panel.angles_deg
    slack = EDGE_SLACK * (s_b - s_a)
    lines = []
    for st in stiffeners:
        if st.kind == "ring" and s_a - slack <= st.value <= s_b + slack:
            lines.append(MarkingLine(f"mark_{st.name}", st.name, "ring", float(min(max(st.value, s_a), s_b)), (a, b)))
        elif st.kind == "stringer":
            angle = a + (st.value - a) % 360.0
            if angle <= b + 1e-9 or (b - a >= 360.0 - 1e-9):
                lines.append(MarkingLine(f"mark_{st.name}", st.name, "stringer", angle, (s_a, s_b)))
    return lines


def panel_assembly(panel: Panel, lines: list[MarkingLine], surface: TubeSurface) -> bd.Compound:
    """The panel solid (``panel_r0_s1``) and its ``marking_lines`` (``mark_ring_03``, ...),
    named for a STEP file."""
    from tubecad.stiffeners.assembly import WALL_COLOUR

    solid = bd.Solid(panel.solid.wrapped)
    solid.label, solid.color = panel.name, WALL_COLOUR
    children: list[bd.Shape] = [solid]
    if lines:
        marks = bd.Compound(children=[line.edge(surface) for line in lines])
        marks.label = "marking_lines"
        children.append(marks)
    return bd.Compound(label=panel.name, children=children)
