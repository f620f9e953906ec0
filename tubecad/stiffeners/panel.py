"""A panel: the piece of a wall between two ring frames and two seam stringers, as a solid
with its name (``panel_r{ring bay}_s{seam bay}``), its span and angles, and the area of its
outer face (for the mass and the shop's plate sizes)."""

from __future__ import annotations

from dataclasses import dataclass

import build123d as bd

from tubecad.brep import properties as props


@dataclass
class Panel:
    name: str  # panel_r{ring bay}_s{seam bay}
    s_range: tuple[float, float]
    angles_deg: tuple[float, float]
    solid: bd.Solid
    outer_area: float

    def mass(self, density: float) -> float:
        return props.volume(self.solid) * density
