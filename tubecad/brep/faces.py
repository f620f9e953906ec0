"""Patch faces of a tube surface between ring frames and stringers, with shared edges.

Vertices and edges are built once and used by both neighbouring faces, so no sewing is
needed. A stringer edge's 3D curve is the surface's isoline u = const (the curvature line)
with the pcurve u = const, the same parameter by construction. A ring edge's 3D curve is a
true circle (Geom_Circle: centre c(s), plane normal t(s), radius rho, angle from the
stringer origin), so CAD selectors and OCCT's checks see circles; the fit is exact at
every ring (:func:`tubecad.fitting.frame_spline.refine_spline`'s rings), so the circle is
the faces' isoline s = const to round-off at any fit tolerance, and a STEP file (which
keeps no edge tolerance: its readers give each edge 1e-7) reads back with the rings on
their faces; its pcurve is
(u(theta), s), u(theta) the circle parametrisation's inverse as a quintic B-spline in
theta (:func:`ring_pcurve`, C1 like the circle, fitted once per stringer interval and
shared by every ring), and the edge tolerance covers what the fit deviates from the exact
circle. Each face lies on its own Segment()-ed copy of the surface, which keeps seams
out of multi-face tubes; a single face around the tube uses a seam edge instead.

On a canal surface (:class:`~tubecad.fitting.canal_section.CanalSectionSurface`) a ring is
its exact characteristic circle, angles counted from where the origin stringer crosses it;
the stringers cross it at angles that change with s (the Moebius map of docs/MATH.md
section 8), so each ring arc gets its own pcurve u(theta) (:func:`canal_ring`). On a closed
axis the stringers come back to the closing ring moved by a Moebius map of the circle (not
turned by the holonomy), and the closing ring's arcs get such pcurves on the first and the
last band alike (:func:`_canal_closing_ring`, :func:`canal_arc_pcurve`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.Geom import Geom_Circle, Geom_Curve
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Line
from OCP.gp import gp_Ax2, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec2d
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Vertex, TopoDS_Wire
from scipy.interpolate import BSpline, make_lsq_spline

from tubecad.brep.layout import stringer_parameters
from tubecad.core.errors import TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.fitting import TubeSurface
from tubecad.fitting.circle import CircleSpline
from tubecad.fitting.nurbs import occ_curve_2d
from tubecad.occ_compat import copy_of, downcast

#: edge and vertex tolerance: Precision::Confusion(); the geometry is far tighter
TOLERANCE = EDGE_TOLERANCE


@dataclass
class PatchFaces:
    """Faces [ring i][stringer j] and the edges they share, for one tube surface."""

    faces: list[list[TopoDS_Face]]  # faces[i][c]: between rings i, i+1 and columns c, c+1
    rings: list[list[TopoDS_Edge]]  # rings[i][c]: arc of ring i from column c to c+1, along +u
    stringers: list[list[TopoDS_Edge]]  # stringers[j][i]: stringer j from ring i to i+1, along +s
    #: a closed tube's closing ring (rings[0] and rings[-1] then hold its arcs): (theta_a,
    #: theta_b, arc) from the origin stringer, and the angle where each column ends on it
    closing_arcs: list[tuple[float, float, TopoDS_Edge]] = field(default_factory=list)
    closing_ends: list[float] = field(default_factory=list)
    #: the face columns' edges [c][i] and angles (degrees): the stringers and, where the
    #: stringers leave an arc of the circle over 330 deg, the circle's C0 knot inside it
    #: (:func:`face_columns`); None: the stringers themselves
    column_edges: list[list[TopoDS_Edge]] | None = None
    columns_deg: list[float] | None = None

    @property
    def columns(self) -> list[list[TopoDS_Edge]]:
        return self.stringers if self.column_edges is None else self.column_edges

    @property
    def seams(self) -> list[list[TopoDS_Edge]]:
        """The face columns that are not stringers, [k][i] as :attr:`stringers`: the curvature
        lines u = const through the circle's C0 knots (:func:`face_columns`), edges no one asked
        for, named ``seam_00``, ... (never ``stringer_..``); none where the columns are the
        stringers (at least two stringers no more than 330 deg apart)."""
        if self.column_edges is None:
            return []
        return [col for col in self.column_edges if not any(col[0].IsSame(st[0]) for st in self.stringers)]

    def all_faces(self) -> list[TopoDS_Face]:
        return [f for row in self.faces for f in row]


def patch_faces(
    tube_surface: TubeSurface,
    s_rings: Sequence[float],
    stringers_deg: Sequence[float],
    reverse: bool = False,
    closing: float | None = None,
) -> PatchFaces:
    """Faces of ``tube_surface`` between rings ``s_rings`` and the stringers at angles
    ``stringers_deg`` (increasing, the first at the surface's origin); ``reverse`` flips
    every face (for the inner wall of a solid). ``closing``: on a closed axis its holonomy
    (radians): the last ring is then the first one, reached by the stringers turned by it
    (see :func:`_closing_ring`)."""
    builder = BRep_Builder()
    surface = tube_surface.surface
    canal = tube_surface.canal
    columns_deg = face_columns(tube_surface, stringers_deg)
    named = [columns_deg.index(a) for a in stringers_deg]  # the stringers among the columns
    stringers_deg = columns_deg
    angles = [math.radians(a - tube_surface.origin_deg) for a in stringers_deg] + [2 * math.pi]
    u_cuts = stringer_parameters(stringers_deg, tube_surface.u_at)
    n_cuts = len(u_cuts)
    n_stringers = n_cuts - 1
    seam = n_stringers == 1
    own = len(s_rings) - (closing is not None)  # rings with edges of their own

    vertices = []
    rings = []
    bounds = []  # bounds[i][j]: the (edge, pcurve, tolerance) of ring i along face column j, in +u order
    if not canal:
        to_u = [ring_pcurve(tube_surface.circle, angles[j], angles[j + 1]) for j in range(n_stringers)]
    cuts: Sequence[float] | np.ndarray
    for i, s in enumerate(s_rings[:own]):
        if canal:  # the stringers cross each circle at angles that change with s (the Moebius map)
            circle, cuts, pcurves, tolerance = canal_ring(tube_surface, s, angles)
        else:
            circle, gap = ring_circle(tube_surface, s)
            tolerance = max(TOLERANCE, 2.0 * gap)
            cuts = angles
            pcurves = [downcast(to_u[j].Translated(gp_Vec2d(0.0, s)), Geom2d_BSplineCurve) for j in range(n_stringers)]
        # a vertex is the surface's point; the exact circle passes within the ring's gap of it,
        # so the vertex tolerance covers the gap as the edge's does (round-off: the fit is exact at rings)
        vertices.append([_vertex(builder, surface.Value(u_cuts[j], s), tolerance) for j in range(n_stringers)])
        rings.append(
            [
                _edge(
                    circle,
                    vertices[i][j],
                    vertices[i][(j + 1) % n_stringers],
                    cuts[j],
                    cuts[j + 1],
                )
                for j in range(n_stringers)
            ]
        )
        bounds.append([[(rings[i][j], pcurves[j], tolerance)] for j in range(n_stringers)])
    if closing is not None:
        arcs, first, last, ends = _closing_ring(tube_surface, s_rings[0], s_rings[-1], angles, vertices[0], closing)
        edges, end_vertices = [edge for _, _, edge in arcs], [v for _, v in ends]
        rings[0], bounds[0] = edges, first
        rings.append(edges)
        bounds.append(last)
        vertices.append(end_vertices)
    bands = []  # the surface between two rings, cut once: patches and stringer edges copy far fewer poles
    for s0, s1 in zip(s_rings[:-1], s_rings[1:]):
        band = copy_of(surface)
        band.Segment(u_cuts[0], u_cuts[-1], s0, s1)
        bands.append(band)
    stringers = [
        [
            _edge(band.UIso(u_cuts[j]), vertices[i][j], vertices[i + 1][j], s_rings[i], s_rings[i + 1])
            for i, band in enumerate(bands)
        ]
        for j in range(n_stringers)
    ]

    faces = []
    for i, band in enumerate(bands):
        row = []
        s0, s1 = s_rings[i], s_rings[i + 1]
        for j in range(n_stringers):
            u0, u1 = u_cuts[j], u_cuts[j + 1]
            piece = band if seam else copy_of(band)
            if not seam:
                piece.Segment(u0, u1, s0, s1)
            face = TopoDS_Face()
            builder.MakeFace(face, piece, TOLERANCE)
            bottom, top = bounds[i][j], bounds[i + 1][j]
            left, right = stringers[j][i], stringers[(j + 1) % n_stringers][i]
            for edge, pcurve, tolerance in bottom + top:
                builder.UpdateEdge(edge, pcurve, face, tolerance)
            if seam:  # one edge used twice: pcurve u = 2 pi for its forward use, u = 0 reversed
                builder.UpdateEdge(right, _line(u1, 0.0, 0, 1), _line(u0, 0.0, 0, 1), face, TOLERANCE)
            else:
                builder.UpdateEdge(right, _line(u1, 0.0, 0, 1), face, TOLERANCE)
                builder.UpdateEdge(left, _line(u0, 0.0, 0, 1), face, TOLERANCE)
            wire = TopoDS_Wire()
            builder.MakeWire(wire)  # counter-clockwise in (u, s): outward normal S_u x S_s
            for edge, orientation in (
                [(e, TopAbs_FORWARD) for e, _, _ in bottom]
                + [(right, TopAbs_FORWARD)]
                + [(e, TopAbs_REVERSED) for e, _, _ in top[::-1]]
                + [(left, TopAbs_REVERSED)]
            ):
                builder.Add(wire, edge.Oriented(orientation))
            wire.Closed(True)
            builder.Add(face, wire)
            row.append(TopoDS_Face.Reversed(face) if reverse else face)
        faces.append(row)
    extra = {} if len(named) == n_stringers else {"column_edges": stringers, "columns_deg": columns_deg}
    chosen = [stringers[j] for j in named]
    if closing is None:
        return PatchFaces(faces, rings, chosen, **extra)  # type: ignore[arg-type]
    return PatchFaces(faces, rings, chosen, arcs, [angle for angle, _ in ends], **extra)  # type: ignore[arg-type]


def face_columns(tube_surface: TubeSurface, stringers_deg: Sequence[float]) -> list[float]:
    """The angles (degrees) of the face columns: the stringers, and every C0 knot of the
    surface's circle between two of them (:mod:`tubecad.fitting.circle`: an arc over 330 deg,
    which one stringer always leaves, is split at its middle). OCCT's pre-boolean check reports
    a face that runs over a C0 knot, so the face is split there, along the curvature line
    u = const through the knot (a stringer no one asked for: an edge, not a named stringer)."""
    origin = float(stringers_deg[0])
    knots = [origin + math.degrees(b) for b in tube_surface.circle.breaks]
    columns = [float(a) for a in stringers_deg]
    for knot in knots:
        if all(abs((knot - a + 180.0) % 360.0 - 180.0) > 1e-9 for a in columns):
            columns.append(knot)
    return [columns[0], *sorted(columns[1:], key=lambda a: (a - origin) % 360.0)]


def seam_angles(tube_surface: TubeSurface, stringers_deg: Sequence[float]) -> list[float]:
    """The angles (degrees) of the face columns that are not stringers (:func:`face_columns`):
    the seams, in the order of :attr:`PatchFaces.seams` (round from the first stringer)."""
    stringers = {float(a) for a in stringers_deg}
    return [a for a in face_columns(tube_surface, stringers_deg) if a not in stringers]


#: on the closing ring, a stringer's end within this distance of a stringer's start shares its vertex
CLOSING_MERGE = 0.1 * TOLERANCE
#: an arc of the closing ring: (theta_a, theta_b, its edge)
Arc = tuple[float, float, TopoDS_Edge]
#: the closing ring: its arcs, the first and the last band's (edge, pcurve, tolerance) per
#: column, and each stringer's end (angle, vertex) on it
ClosingRing = tuple[
    list[Arc],
    list[list[tuple[TopoDS_Edge, Any, float]]],
    list[list[tuple[TopoDS_Edge, Any, float]]],
    list[tuple[float, TopoDS_Vertex]],
]


def _closing_ring(
    tube_surface: TubeSurface,
    s_first: float,
    s_last: float,
    angles: list[float],
    start_vertices: list[TopoDS_Vertex],
    holonomy: float,
) -> ClosingRing:
    """The ring where a closed tube closes: the circle at ``s_first`` (= the one at
    ``s_last``), cut where stringer j starts (angle a_j) and where it ends, turned by the
    holonomy: b_j = a_j + holonomy, since r1(L) = cos(h) r1(0) + sin(h) r2(0). Returns its
    arcs (theta_a, theta_b, edge) in +theta order from a_0, the (edge, pcurve, tolerance)
    lists of every face column of the first band (theta in [a_j, a_j+1]) and of the last
    band (theta in [b_j, b_j+1], with pcurves u(theta - h) at s_last), and the stringers'
    ends (angle b_j, vertex).
    The stringers stay true curvature lines: the faces meet the ring shifted, not twisted.

    On a canal surface (:func:`_canal_closing_ring`) the stringers come back moved by a
    Moebius map of the circle rather than turned: b_j = phi(a_j)."""
    if tube_surface.canal:
        return _canal_closing_ring(tube_surface, s_first, s_last, angles, start_vertices)
    two_pi = 2.0 * math.pi
    n = len(start_vertices)
    rho = tube_surface.tube.radius_law.constant_value  # a tube's radius
    circle, gap = ring_circle(tube_surface, s_first)
    theta = np.linspace(0.0, two_pi, 16, endpoint=False) + 0.1  # how far the s_last isoline is from that circle
    u_last = tube_surface.circle.u_of_theta(np.mod(theta - holonomy, two_pi))
    gap = max(
        [gap]
        + [
            circle.Value(float(th)).Distance(tube_surface.surface.Value(float(u), s_last))
            for th, u in zip(theta, u_last)
        ]
    )
    tolerance = max(TOLERANCE, 2.0 * gap)
    arcs, ends = _cut_closing_ring(
        circle, rho, angles[:n], [float(np.mod(a + holonomy, two_pi)) for a in angles[:n]], start_vertices
    )

    first, last = [], []
    for j in range(n):
        a0, a1 = angles[j], angles[j + 1]
        first.append(
            [
                (edge, ring_pcurve(tube_surface.circle, lo, hi).Translated(gp_Vec2d(0.0, s_first)), tolerance)
                for lo, hi, edge in _first_column(arcs, a0, a1)
            ]
        )
        b0 = ends[j][0]
        shift = b0 - a0  # theta on the ring = the last band's own angle + shift
        column = _last_column(arcs, b0, a1 - a0, j, holonomy)
        last.append(
            [
                (
                    edge,
                    ring_pcurve(
                        tube_surface.circle, start - shift, start - shift + _width(arcs, edge), moved=shift - lift
                    ).Translated(gp_Vec2d(0.0, s_last)),
                    tolerance,
                )
                for start, edge, lift in column
            ]
        )
    return arcs, first, last, ends


def _canal_closing_ring(
    tube_surface: TubeSurface,
    s_first: float,
    s_last: float,
    angles: list[float],
    start_vertices: list[TopoDS_Vertex],
) -> ClosingRing:
    """:func:`_closing_ring` of a canal surface on a closed axis (its law closes: the circle
    at ``s_last`` is the circle at ``s_first``). The ring's circle counts theta from the
    origin stringer's start; stringer j starts at a_j and ends at b_j = phi(o + a_j) - o
    (o the origin stringer's chi0, phi :meth:`CanalSurface.closing_angle`), in the same
    cyclic order (phi is a Moebius map of the circle). The last band's own angle (from the
    origin stringer's end, where it crosses the circle at s_last) is the ring's theta less
    phi(o) - o; its column j runs between the stringers' ends, as wide as the ring at
    s_last between them. Every arc's pcurve on the first and on the last band is fitted
    with the exact inverse Moebius map at s_first and at s_last (:func:`canal_arc_pcurve`),
    and the one edge tolerance covers the largest measured gap of either."""
    two_pi = 2.0 * math.pi
    n = len(start_vertices)
    exact = tube_surface.tube
    origin = math.radians(tube_surface.origin_deg)
    centre, radius, t, x_dir, chi_first = tube_surface.ring(s_first)
    circle = Geom_Circle(
        gp_Ax2(gp_Pnt(*map(float, centre)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))), radius
    )
    phi = exact.closing_angle(origin + np.asarray(angles[:n], dtype=float)) - origin
    arcs, ends = _cut_closing_ring(circle, radius, angles[:n], [float(b) for b in np.mod(phi, two_pi)], start_vertices)
    crossings = tube_surface.ring_angles(s_last, angles)  # the stringers' ends in the last band's own angle
    widths = np.diff(crossings)
    chi_last = tube_surface.ring(s_last)[4]
    m_first, m_last = exact.moebius_matrix(np.array([s_first, s_last]))

    first, last, gap = [], [], 0.0
    for j in range(n):
        column = []
        for lo, hi, edge in _first_column(arcs, angles[j], angles[j + 1]):
            pcurve, arc_gap = canal_arc_pcurve(tube_surface, s_first, angles, j, lo, hi, circle, chi_first, m_first)
            column.append((edge, pcurve))
            gap = max(gap, arc_gap)
        first.append(column)
        b0 = ends[j][0]
        shift = b0 - float(crossings[j])  # theta on the ring = the last band's own angle + shift
        column = []
        for start, edge, lift in _last_column(arcs, b0, float(widths[j]), j, None):
            lo, hi = start - lift, start - lift + _width(arcs, edge)  # the edge's own parameters
            pcurve, arc_gap = canal_arc_pcurve(
                tube_surface, s_last, angles, j, lo, hi, circle, chi_last, m_last, moved=shift - lift
            )
            column.append((edge, pcurve))
            gap = max(gap, arc_gap)
        last.append(column)
    tolerance = max(TOLERANCE, 2.0 * gap)
    return (
        arcs,
        [[(e, p, tolerance) for e, p in col] for col in first],
        [[(e, p, tolerance) for e, p in col] for col in last],
        ends,
    )


def _cut_closing_ring(
    circle: Geom_Circle,
    radius: float,
    starts: Sequence[float],
    ends_at: Sequence[float],
    start_vertices: list[TopoDS_Vertex],
) -> tuple[list[Arc], list[tuple[float, TopoDS_Vertex]]]:
    """The closing ring's arcs (theta_a, theta_b, edge) in +theta order, cut at the stringers'
    starts ``starts`` (with their vertices) and their ends ``ends_at`` (in [0, 2 pi)); an end
    within CLOSING_MERGE of a cut shares its vertex. Returns the arcs and each stringer's
    end (angle, vertex)."""
    two_pi = 2.0 * math.pi
    cuts = list(zip(starts, start_vertices))  # (angle, vertex) on the ring
    ends = []  # stringer j's end: (the angle of its vertex on the ring, the vertex)
    for b in ends_at:
        near = [(c, v) for c, v in cuts if radius * abs(math.remainder(b - c, two_pi)) <= CLOSING_MERGE]
        if not near:
            near = [(b, _vertex(BRep_Builder(), circle.Value(b)))]
            cuts.append(near[0])
        ends.append(near[0])
    cuts.sort(key=lambda cut: cut[0])
    stops = [c for c, _ in cuts] + [cuts[0][0] + two_pi]
    arcs = [
        (stops[k], stops[k + 1], _edge(circle, cuts[k][1], cuts[(k + 1) % len(cuts)][1], stops[k], stops[k + 1]))
        for k in range(len(cuts))
    ]
    return arcs, ends


def _first_column(arcs: list[Arc], a0: float, a1: float) -> list[Arc]:
    """The arcs (lo, hi, edge) of the closing ring between the angles a0 < a1 (the first band's column)."""
    return [(lo, hi, edge) for lo, hi, edge in arcs if a0 - 1e-12 <= lo and hi <= a1 + 1e-12]


def _last_column(
    arcs: list[Arc], b0: float, width: float, j: int, holonomy: float | None
) -> list[tuple[float, TopoDS_Edge, float]]:
    """The arcs of the closing ring covering [b0, b0 + width] (the last band's column j, where
    the stringers j and j + 1 end), each as (its start lifted into that range, edge, the
    lift: 0 or +- 2 pi), in +theta order."""
    two_pi = 2.0 * math.pi
    column = []
    for lo, hi, edge in arcs:
        for lift in (0.0, two_pi, -two_pi):
            if b0 - 1e-9 <= lo + lift and hi + lift <= b0 + width + 1e-9:
                column.append((lo + lift, edge, lift))
    column.sort(key=lambda c: c[0])
    covered = sum(hi - lo for lo, hi, edge in arcs if any(edge.IsSame(e) for _, e, _ in column))
    if abs(covered - width) > 1e-8 or not column:
        turned = "" if holonomy is None else f" (holonomy {holonomy:.6g} rad)"
        raise TubecadError(f"the closing ring could not be cut for stringer {j}{turned}")
    return column


def _width(arcs: list[Arc], edge: TopoDS_Edge) -> float:
    return next(hi - lo for lo, hi, e in arcs if e.IsSame(edge))


#: u(theta) is fitted to this (radians of u; x rho, far below the edge tolerance)
ANGLE_FIT_TOLERANCE = 1e-13
#: the pcurve's degree and its initial span (degree 9 over 15 deg fits u(theta) to ~1e-15)
ANGLE_FIT_DEGREE = 9
ANGLE_FIT_SPAN = math.radians(15.0)


def ring_pcurve(circle: CircleSpline, a: float, b: float, moved: float = 0.0) -> Geom2d_BSplineCurve:
    """The pcurve (u(theta), 0) of the ring arc theta in [a, b] (radians from the surface's
    origin) on a surface of ``circle``, parameterised by the angle like the arc's Geom_Circle;
    the arc at s uses it translated by (0, s). ``moved``: the curve (u(theta - moved), 0)
    over [a + moved, b + moved] instead, for an arc whose circle counts angles from
    elsewhere (the closing ring). Cached: every ring and surface shares them."""
    to_u = _angle_to_u(circle.breaks, float(a), float(b))
    if moved:
        to_u = BSpline(to_u.t + moved, to_u.c, to_u.k)
    return _ring_pcurve(to_u)


@functools.lru_cache(maxsize=1024)
def _angle_to_u(breaks: tuple[float, ...], a: float, b: float) -> BSpline:
    """u(theta) on [a, b] (radians from the origin) as a C1 B-spline: knots of multiplicity
    degree - 1 where the circle's sub-arcs join (u(theta) is only C1 there), spans of at
    most ANGLE_FIT_SPAN, halved until a least-squares fit on Chebyshev points is within
    ANGLE_FIT_TOLERANCE of the closed form."""
    circle = CircleSpline.with_breaks(breaks)
    joints = [arc.start for arc in circle.arcs if a + 1e-12 < arc.start < b - 1e-12]  # not at an end, to round-off
    return fit_angle_map(circle.u_of_theta, a, b, joints)


def fit_angle_map(to_u: Callable[[np.ndarray], np.ndarray], a: float, b: float, joints: Sequence[float]) -> BSpline:
    """The map ``to_u`` (theta -> u) on [a, b] as a degree ANGLE_FIT_DEGREE B-spline, C1 at
    ``joints`` (inside (a, b), increasing), spans of at most ANGLE_FIT_SPAN, halved until a
    least-squares fit on Chebyshev points is within ANGLE_FIT_TOLERANCE (or 8 halvings)."""
    degree = ANGLE_FIT_DEGREE
    segments = np.array([a, *joints, b])
    refine = 1
    while True:
        knots, samples = [a] * (degree + 1), []
        for k, (lo, hi) in enumerate(zip(segments[:-1], segments[1:])):
            spans = refine * math.ceil((hi - lo) / ANGLE_FIT_SPAN)
            knots += list(np.linspace(lo, hi, spans + 1)[1:-1]) + (
                [joints[k]] * (degree - 1) if k < len(joints) else []
            )
            samples.append(lo + (hi - lo) * 0.5 * (1 - np.cos(np.linspace(0, math.pi, 4 * spans + degree + 4))))
        knots += [b] * (degree + 1)
        x = np.unique(np.concatenate(samples))
        spline = make_lsq_spline(x, to_u(x), np.array(knots), k=degree)
        check = np.linspace(a, b, 200 * refine * len(segments))
        if np.abs(spline(check) - to_u(check)).max() <= ANGLE_FIT_TOLERANCE or refine >= 8:
            return spline
        refine *= 2


@functools.lru_cache(maxsize=1024)
def _ring_pcurve(to_u: BSpline) -> Geom2d_BSplineCurve:
    """The pcurve (u(theta), 0) of a ring arc, parameterised by the circle's angle (each
    ring's pcurve is this curve translated to s)."""
    return occ_curve_2d(_at_height(to_u, 0.0))


def _at_height(u_of_theta: BSpline, s: float) -> BSpline:
    """The plane curve (u(theta), s) of a scalar spline u(theta)."""
    c = np.column_stack([u_of_theta.c, np.full(len(u_of_theta.c), float(s))])
    return BSpline(u_of_theta.t, c, u_of_theta.k)


def ring_circle(tube_surface: TubeSurface, s: float, samples: int = 16) -> tuple[Geom_Circle, float]:
    """The ring at ``s`` as an exact circle (parameter: angle from the surface's origin) and
    its largest measured distance from the surface's isoline s = const."""
    tube = tube_surface.tube
    a = math.radians(tube_surface.origin_deg)
    (t,), (r1,), (r2,) = tube.axis.rotation_minimising_frame(np.array([s]))
    centre = tube.axis.position(np.array([s]))[0]
    x_dir = math.cos(a) * r1 + math.sin(a) * r2
    circle = Geom_Circle(
        gp_Ax2(gp_Pnt(*map(float, centre)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))),
        tube.radius_law.constant_value,  # a tube's radius
    )
    theta = np.linspace(0.0, 2 * math.pi, samples, endpoint=False) + 0.1
    gap = 0.0
    for th, u in zip(theta, tube_surface.circle.u_of_theta(theta)):
        gap = max(gap, circle.Value(float(th)).Distance(tube_surface.surface.Value(float(u), s)))
    return circle, gap


#: samples per ring arc at which a canal ring's circle is compared with the surface through its pcurve
CANAL_GAP_SAMPLES = 6


def canal_ring(
    tube_surface: TubeSurface, s: float, angles: list[float]
) -> tuple[Geom_Circle, np.ndarray, list[Geom2d_BSplineCurve], float]:
    """A canal surface's ring at ``s``: the exact characteristic circle (parameter: the angle
    from the origin stringer's point), the angles where the stringers ``angles`` (chi0 -
    origin, radians, the last 2 pi) cross it, the pcurve (u(theta), s) of each arc between
    them and the edge tolerance covering the largest measured distance of the circle from
    the surface through those pcurves. u(theta) composes the inverse Moebius map
    theta -> chi0 with the circle spline's u(chi0), fitted per arc (C1 where the spline's
    sub-arcs join)."""
    centre, radius, t, x_dir, chi_o = tube_surface.ring(s)
    circle = Geom_Circle(
        gp_Ax2(gp_Pnt(*map(float, centre)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))), radius
    )
    cuts = tube_surface.ring_angles(s, angles)
    pcurves, gap = [], 0.0
    moebius = tube_surface.tube.moebius_matrix(np.array([s]))[0]
    for j in range(len(angles) - 1):
        pcurve, arc_gap = canal_arc_pcurve(
            tube_surface, s, angles, j, float(cuts[j]), float(cuts[j + 1]), circle, chi_o, moebius
        )
        pcurves.append(pcurve)
        gap = max(gap, arc_gap)
    return circle, cuts, pcurves, max(TOLERANCE, 2.0 * gap)


def canal_arc_pcurve(
    tube_surface: TubeSurface,
    s: float,
    angles: Sequence[float],
    column: int,
    lo: float,
    hi: float,
    circle: Geom_Circle,
    chi_o: float,
    moebius: np.ndarray,
    moved: float = 0.0,
) -> tuple[Geom2d_BSplineCurve, float]:
    """The pcurve (u(theta), s) on ``tube_surface`` of the arc theta in [lo, hi] of ``circle``
    (its 3-D curve, parameterised by theta), which lies on the surface's ring at ``s`` in face
    column ``column`` (between the stringers ``angles[column]`` and ``angles[column + 1]``,
    chi0 - origin, radians), and the largest measured distance of the circle from the
    surface through it. The ring's own angle from the origin stringer at s (``chi_o`` its
    chi there, ``moebius`` Mb(s)) is theta - ``moved`` (0 on the ring's own circle; on a
    closed tube's closing ring, the shift between where the stringers start and end).
    u(theta) composes the exact inverse Moebius map theta -> chi0 (continued from the
    column's first stringer through the arc's middle) with the circle spline's u(chi0),
    fitted by :func:`fit_angle_map` (C1 where the spline's sub-arcs join)."""
    origin = math.radians(tube_surface.origin_deg)
    spline_circle, surface = tube_surface.circle, tube_surface.surface
    a0, a1 = angles[column], angles[column + 1]
    band_lo, band_mid = lo - moved, 0.5 * (lo + hi) - moved

    def to_u(theta: np.ndarray) -> np.ndarray:
        chi0 = tube_surface.ring_chi0(s, chi_o, origin + a0, theta - moved, band_mid, moebius)
        return spline_circle.u_of_theta(np.clip(chi0 - origin, a0, a1))

    starts = [arc.start for arc in spline_circle.arcs if a0 + 1e-12 < arc.start < a1 - 1e-12]
    if starts:  # where the sub-arcs join, in theta: the forward map of chi0
        chi = tube_surface.tube.stringer_angle(origin + np.array(starts), np.full(len(starts), s))
        joints = [
            float(x)
            for x in band_lo + np.mod(chi - chi_o - band_lo, 2.0 * math.pi) + moved
            if lo + 1e-12 < x < hi - 1e-12
        ]
    else:
        joints = []
    spline = fit_angle_map(to_u, lo, hi, joints)
    pcurve = occ_curve_2d(_at_height(spline, s))
    gap = max(
        circle.Value(float(theta)).Distance(surface.Value(float(spline(theta)), s))
        for theta in np.linspace(lo, hi, CANAL_GAP_SAMPLES + 2)
    )
    return pcurve, gap


def _vertex(builder: BRep_Builder, point: gp_Pnt, tolerance: float = TOLERANCE) -> TopoDS_Vertex:
    vertex = TopoDS_Vertex()
    builder.MakeVertex(vertex, point, tolerance)
    return vertex


def _edge(curve: Geom_Curve, v0: TopoDS_Vertex, v1: TopoDS_Vertex, t0: float, t1: float) -> TopoDS_Edge:
    maker = BRepBuilderAPI_MakeEdge(curve, v0, v1, t0, t1)
    if not maker.IsDone():
        raise TubecadError(f"OCCT could not make an edge on [{t0:g}, {t1:g}] (error {maker.Error()})")
    return maker.Edge()


def _line(x: float, y: float, dx: float, dy: float) -> Geom2d_Line:
    return Geom2d_Line(gp_Pnt2d(x, y), gp_Dir2d(dx, dy))
