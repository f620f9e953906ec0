"""Seams and panels (issue 4): the wall split along chosen curvature lines.

A panel lies between two ring frames s_a < s_b and two seam stringers th_a -> th_b
(counter-clockwise). Its faces: the outer and inner wall surfaces between the seams
(exact-section patches), the two seam faces along the normal strip from r_in to r_out
(ruled, as exact as the wall), and two planar caps in the normal planes. Panels fit
together into the wall: their volumes add up to it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
from OCP.gp import gp_Pnt

from ..brep import TubeBuild
from ..brep import properties as props
from ..errors import ParameterError
from ..fitting import exact_section_surface
from ..surface import CurvatureLineTube
from .solids import ruled_surface, sew_solid


@dataclass
class Panel:
    name: str  # panel_r{ring bay}_s{seam bay}
    s_range: tuple[float, float]
    angles_deg: tuple[float, float]
    solid: bd.Solid
    outer_area: float

    def mass(self, density: float) -> float:
        return props.volume(self.solid) * density


def split_into_panels(build: TubeBuild, seams: list[int], rings: list[int] | None = None) -> list[Panel]:
    """Panels of the wall in ``build`` between its layout's rings (indices ``rings``, default
    all) and the seam stringers at layout indices ``seams`` (at least one)."""
    if len(build.radii) != 2:
        raise ParameterError("panels need a wall (build_wall_solid), not a tube solid")
    layout = build.layout
    n_s, n_r = len(layout.stringers_deg), len(layout.s_rings)
    if not seams or any(not 0 <= j < n_s for j in seams):
        raise ParameterError(f"seams must be one or more stringer indices in [0, {n_s - 1}], got {seams}")
    rings = sorted(set(range(n_r) if rings is None else rings) | {0, n_r - 1})
    if any(not 0 <= i < n_r for i in rings):
        raise ParameterError(f"rings must be ring indices in [0, {n_r - 1}], got {rings}")
    angles = sorted(layout.stringers_deg[j] for j in set(seams))
    bays = list(zip(angles, angles[1:] + [angles[0] + 360.0]))
    r_out, r_in = build.radii
    axis = build.surfaces[0].tube.axis
    panels = []
    for i, (ia, ib) in enumerate(zip(rings, rings[1:])):
        span = (layout.s_rings[ia], layout.s_rings[ib])
        for j, (a, b) in enumerate(bays):
            panels.append(panel(build, axis.restricted(span), r_in, r_out, a, b, f"panel_r{i}_s{j}"))
    return panels


def panel(build: TubeBuild, axis, r_in: float, r_out: float, a_deg: float, b_deg: float, name: str) -> Panel:
    """One panel over ``axis``'s span between the angles a_deg -> b_deg."""
    frame = build.frame
    s0, s1 = axis.span
    surfaces = [exact_section_surface(CurvatureLineTube(axis, r, allow_irregular=True), frame, origin_deg=a_deg)
                for r in (r_out, r_in)]  # fmt: skip
    u1 = float(surfaces[0].u_at(b_deg)) if (b_deg - a_deg) % 360 else 2 * math.pi
    faces = [BRepBuilderAPI_MakeFace(ts.surface, 0.0, u1, s0, s1, 1e-7).Face() for ts in surfaces]
    for angle in (a_deg, b_deg):
        faces.append(BRepBuilderAPI_MakeFace(ruled_surface(frame, math.radians(angle), (0.0, r_in), (0.0, r_out)),
                                             0.0, 1.0, s0, s1, 1e-7).Face())  # fmt: skip
    for s in (s0, s1):
        faces.append(_cap(surfaces, frame.spline(s), a_deg, b_deg, s, u1, r_in, r_out))
    solid = sew_solid(faces, name)
    return Panel(name, (s0, s1), (a_deg, b_deg), solid, props.area(bd.Face(faces[0])))


def _cap(surfaces, F: np.ndarray, a_deg: float, b_deg: float, s: float, u1: float, r_in: float, r_out: float):
    """Annular sector in the normal plane at s: outer arc, seam line, inner arc, seam line."""
    c, r1, r2 = F[:3], F[3:6], F[6:]

    def point(angle_deg: float, r: float) -> gp_Pnt:
        a = math.radians(angle_deg)
        return gp_Pnt(*map(float, c + r * (math.cos(a) * r1 + math.sin(a) * r2)))

    wire = BRepBuilderAPI_MakeWire()
    wire.Add(BRepBuilderAPI_MakeEdge(surfaces[0].surface.VIso(s), 0.0, u1).Edge())
    wire.Add(BRepBuilderAPI_MakeEdge(point(b_deg, r_out), point(b_deg, r_in)).Edge())
    wire.Add(BRepBuilderAPI_MakeEdge(surfaces[1].surface.VIso(s), 0.0, u1).Edge())
    wire.Add(BRepBuilderAPI_MakeEdge(point(a_deg, r_in), point(a_deg, r_out)).Edge())
    return BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()
