"""Seams and panels (issue 4): the wall split along chosen curvature lines.

A panel lies between two ring frames s_a < s_b and two seam stringers a -> b
(counter-clockwise). Its faces: the outer and inner wall surfaces between the seams, the
two seam faces along the normal strip from the inner to the outer surface (ruled, as exact
as the wall), and two caps at s_a and s_b, sharing their edges (nothing is sewn). Panels fit
together into the wall: their volumes add up to it. With a single seam a panel is its bay
all round (a full turn, the seam one of its edges).

One path for every wall (:func:`split_into_panels`: the checks, the ring and seam bays, the
names and the order); only the faces come from the surface. The tube (r = const, its fast
path) refits exact-section patches between the seams with planar caps in the normal
planes (:func:`panel`); a canal surface's wall (a radius law) is assembled from the wall
build's own faces, with ruled seam faces along the normals and pieces of the normal cones
as caps (:class:`tubecad.stiffeners.canal_panels.CanalWallEdges`).
"""

from __future__ import annotations

import math

import build123d as bd

from tubecad.brep import TubeBuild
from tubecad.brep import properties as props
from tubecad.brep.assembled import Strip, c0_knots, strip_solid
from tubecad.core.errors import ParameterError
from tubecad.fitting import exact_section_surface
from tubecad.stiffeners.canal_panels import CanalWallEdges
from tubecad.stiffeners.panel import Panel
from tubecad.stiffeners.rings import swept_section
from tubecad.stiffeners.solids import cap_plane, ruled_surface, surface_part
from tubecad.surface import CurvatureLineTube


def split_into_panels(build: TubeBuild, seams: list[int], rings: list[int] | None = None) -> list[Panel]:
    """Panels of the wall in ``build`` between its layout's rings (indices ``rings``, default
    all) and the seam stringers at layout indices ``seams`` (at least one): ring bay by ring
    bay, seam bays from the first seam counter-clockwise, named ``panel_r{i}_s{j}``."""
    if len(build.radii) != 2:
        raise ParameterError("panels need a wall (build_wall_solid), not a tube solid")
    layout = build.layout
    n_s = len(layout.stringers_deg)
    ordered, rings = layout.panel_bounds(seams, rings)
    surface = build.surfaces[0].tube
    # the layout's angles increase with the index: seam bays j_a -> j_b, j_b past n_s wrapping round
    bays = list(zip(ordered, ordered[1:] + [ordered[0] + n_s]))

    def angle(j: int) -> float:
        return layout.stringers_deg[j] if j < n_s else layout.stringers_deg[j - n_s] + 360.0

    if surface.constant_radius:  # the fast path: exact-section patches refitted between the seams
        r_out, r_in = build.radii
        axis = surface.axis

        def solid_and_area(ia: int, ib: int, ja: int, jb: int) -> tuple[bd.Solid, float]:
            span = (layout.s_rings[ia], layout.s_rings[ib])
            return tube_panel(build, axis.restricted(span), r_in, r_out, angle(ja), angle(jb))

    else:  # the wall build's own faces, ruled seam faces and normal-cone caps
        solid_and_area = CanalWallEdges(build).panel

    panels = []
    for i, (ia, ib) in enumerate(zip(rings, rings[1:])):
        for j, (ja, jb) in enumerate(bays):
            solid, area = solid_and_area(ia, ib, ja, jb)
            span = (layout.s_rings[ia], layout.s_rings[ib])
            panels.append(Panel(f"panel_r{i}_s{j}", span, (angle(ja), angle(jb)), solid, area))
    return panels


def panel(build: TubeBuild, axis, r_in: float, r_out: float, a_deg: float, b_deg: float, name: str) -> Panel:
    """One panel of a tube's wall over ``axis``'s span between the angles a_deg -> b_deg
    (:func:`tube_panel`)."""
    solid, area = tube_panel(build, axis, r_in, r_out, a_deg, b_deg)
    return Panel(name, axis.span, (a_deg, b_deg), solid, area)


def tube_panel(build: TubeBuild, axis, r_in: float, r_out: float, a_deg: float, b_deg: float) -> tuple[bd.Solid, float]:
    """The solid and outer area of a tube's panel over ``axis``'s span between the angles
    a_deg -> b_deg: outer patch a -> b, seam b (r_out -> r_in), inner patch b -> a, seam a
    (r_in -> r_out), counter-clockwise about +t, with shared edges and planar caps
    (:func:`tubecad.brep.assembled.strip_solid`)."""
    frame = build.section_frame  # a tube's build: its frame fit
    if frame is None:
        raise ParameterError("tube_panel: the build is a canal surface's (a radius law): split it with canal_panel")
    s0, s1 = axis.span
    if not (b_deg - a_deg) % 360:  # one seam: the bay all round, the seam an edge of it
        section = [(s0, r_in), (s1, r_in), (s1, r_out), (s0, r_out)]
        solid, tube_faces = swept_section(axis, section, build.tolerance, origin_deg=a_deg)
        return bd.Solid(solid), props.faces_area(tube_faces[r_out])
    outer, inner = (
        exact_section_surface(CurvatureLineTube(axis, r, allow_irregular=True), frame, origin_deg=a_deg)
        for r in (r_out, r_in)
    )
    u1 = float(outer.u_at(b_deg))
    # the wall patches in pieces between the surfaces' C0 knots (each piece its own face)
    cuts = [0.0] + [u for u in c0_knots(outer.surface) if 1e-12 < u < u1 - 1e-12] + [u1]
    pieces = list(zip(cuts[:-1], cuts[1:]))
    strips = [Strip(surface_part(outer.surface, p, q), p, q) for p, q in pieces]
    strips.append(Strip(ruled_surface(frame, math.radians(b_deg), (0.0, r_in), (0.0, r_out)), 1.0, 0.0))
    strips += [Strip(surface_part(inner.surface, p, q), q, p) for p, q in pieces[::-1]]
    strips.append(Strip(ruled_surface(frame, math.radians(a_deg), (0.0, r_in), (0.0, r_out)), 0.0, 1.0))
    # faces end where the frame is only C0 (a route's rational frame: at its joints and rings)
    cuts = [v for v in c0_knots(outer.surface, "v") if s0 + 1e-9 * (s1 - s0) < v < s1 - 1e-9 * (s1 - s0)]
    solid, faces = strip_solid(strips, s0, s1, (cap_plane(frame, s0), cap_plane(frame, s1)), True, cuts)
    outer_faces = faces[: len(pieces) * (len(cuts) + 1)]  # strip by strip, each cut at the joints
    return bd.Solid(solid), props.faces_area(outer_faces)
