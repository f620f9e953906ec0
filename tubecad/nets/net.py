"""A host face's curvature-line net: lines of both families seeded evenly, as edges, and the
face split into the net's patches (issue 44).

The family-1 lines are seeded along the family-2 line through ``seed`` (and the family-2 lines
along the family-1 line through it), evenly by arc length: ``count`` seeds at (i + 1/2) / count
of an open line's length, at i / count round a closed one. Each line is traced
(:func:`~tubecad.nets.trace.trace_line`, stopping near the umbilics :func:`~tubecad.nets.umbilics.find_umbilics`
finds), made an edge (:func:`~tubecad.nets.edges.line_edge`) and named ``k1_00``, ``k1_01``...,
``k2_00``...; the face is split by all of them (OCCT's General Fuse splitter: the edges lie on
it) into the net's patches, one shell, its validity checked. On a face with an umbilic part (a
flat bottom, :class:`~tubecad.nets.umbilics.UmbilicPart`) the lines stop on its border and the
default seed is the point nearest the box's centre off it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from OCP.BRepAlgoAPI import BRepAlgoAPI_Splitter
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape, TopoDS_Vertex

from tubecad.brep.operations import built
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.nets.edges import LineEdge, line_edge
from tubecad.nets.host import HostSurface
from tubecad.nets.trace import CurvatureLine, Family, trace_line
from tubecad.nets.umbilics import Umbilics, find_umbilics

#: lines stop this share of the face's size from an umbilic
UMBILIC_REACH = 1e-3
#: the step error of the guides (the lines the seeds are spread along), as a share of the
#: face's size: they place the seeds, each line then traced from its seed to ``tolerance``
#: (a seed 1e-9 of the size along its guide off is another line as exact); 3x fewer steps
GUIDE_SHARE = 1e-9
#: the most lines per family
MOST_LINES = 200


@dataclass(frozen=True)
class CurvatureNet:
    """A face's net: its ``host`` surface, its ``umbilics``, the traced ``lines`` and their
    ``edges`` by name (``k1_00``...), and ``patches``: the face split by them (one shell)."""

    host: HostSurface
    umbilics: Umbilics
    lines: dict[str, CurvatureLine]
    edges: dict[str, LineEdge]
    patches: TopoDS_Shape
    #: the lines that run along an edge the face already has (its seam or its boundary: a
    #: torus' meridian at u = 0): the face is not split there again
    on_face_edges: frozenset[str] = frozenset()

    @property
    def angle(self) -> float:
        """The largest angle (radians) between an edge's tangent and its principal direction."""
        return max((e.angle for e in self.edges.values()), default=0.0)

    @property
    def vertices(self) -> dict[str, TopoDS_Vertex]:
        """The umbilics as named vertices: ``umbilic_0``, ``umbilic_1``... (their types in
        :meth:`report`)."""
        from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
        from OCP.gp import gp_Pnt

        return {
            f"umbilic_{i}": BRepBuilderAPI_MakeVertex(gp_Pnt(*(float(c) for c in p.point))).Vertex()
            for i, p in enumerate(self.umbilics.points)
        }

    def report(self) -> dict[str, Any]:
        """The net's figures: ``umbilics`` [{"name", "point", "type", "index", "separatrices"}]
        (or ``umbilic_region``), ``umbilic_parts`` (:meth:`UmbilicPart.report`), per line its ``family``, ``length``, how it ``stopped`` and the
        edge's ``angle`` (radians) and ``gap``, and the largest angle over the net."""
        return {
            "umbilic_region": self.umbilics.region,
            "umbilic_parts": [part.report() for part in self.umbilics.parts],
            "umbilics": [
                {
                    "name": f"umbilic_{i}",
                    "point": [float(c) for c in p.point],
                    "type": p.type,
                    "index": p.index,
                    "separatrices": p.separatrices,
                }
                for i, p in enumerate(self.umbilics.points)
            ],
            "lines": {
                name: {
                    "family": line.family,
                    "length": float(line.sigma[-1] - line.sigma[0]),
                    "stopped": list(line.stopped),
                    "angle": self.edges[name].angle,
                    "gap": self.edges[name].gap,
                    "on_face_edge": name in self.on_face_edges,
                }
                for name, line in self.lines.items()
            },
            "angle": self.angle,
        }


def curvature_net(
    face: object,
    k1_lines: int,
    k2_lines: int,
    *,
    seed: tuple[float, float] | None = None,
    tolerance: float = 1e-10,
) -> CurvatureNet:
    """The curvature-line net of ``face`` (module docstring).

    Args:
        face: a build123d ``Face`` or an OCCT ``TopoDS_Face`` (split as it is), or a
            ``HostSurface`` (its face made over its box).
        k1_lines: lines of family 1 (along the k1 direction), 1 .. MOST_LINES.
        k2_lines: lines of family 2.
        seed: the parameters (u, v) the seeding lines pass through (default: the box's centre).
        tolerance: the tracer's step error (3-D length, relative to nothing: the model's unit).

    Returns:
        The net.

    Raises:
        ParameterError: (``k1_lines``, ``k2_lines``) counts out of range; (``face``) a face
            that is an umbilic region (a plane, a sphere: every direction is principal) or
            not a face; (``seed``) a seed outside the face or at an umbilic.
    """
    for key, count in (("k1_lines", k1_lines), ("k2_lines", k2_lines)):
        if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= MOST_LINES:
            raise ParameterError(f"{key} must be an integer in 1..{MOST_LINES}, got {count!r:.40}", key=key)
    host, shape = _host_and_face(face)
    umbilics = find_umbilics(host)
    if umbilics.region:
        raise ParameterError(
            "face: an umbilic region (a plane or a sphere): every direction is principal, it has no curvature-line net",
            key="face",
        )
    centre = seed if seed is not None else _centre(host, umbilics.part_level)
    stops = np.array([p.point for p in umbilics.points]).reshape(-1, 3)
    reach = UMBILIC_REACH * host.size

    def traced(start: tuple[float, float], family: Family, step_error: float = tolerance) -> CurvatureLine:
        return trace_line(host, start, family, tolerance=step_error, stops=stops, reach=reach, flat=umbilics.part_level)

    lines: dict[str, CurvatureLine] = {}
    plan: tuple[tuple[Family, int, Family], ...] = ((1, k1_lines, 2), (2, k2_lines, 1))
    for family, count, across in plan:
        guide = traced(centre, across, max(tolerance, GUIDE_SHARE * host.size))
        traced_lines = [traced(start, family) for start in _seeds(guide, count)]
        folds = _folds(guide, traced_lines, count)
        if folds is not None:  # the guide meets each line twice: seed along one half of it
            traced_lines = [traced(start, family) for start in _seeds(guide, count, folds)]
        for i, line in enumerate(traced_lines):
            lines[f"k{family}_{i:02d}"] = line
    edges = {name: line_edge(host, line) for name, line in lines.items()}
    on_edges = {name for name, line in lines.items() if _on_face_edges(shape, line.points)}
    patches = _split(shape, [e.edge for name, e in edges.items() if name not in on_edges])
    return CurvatureNet(host, umbilics, lines, edges, patches, frozenset(on_edges))


def _centre(host: HostSurface, level: float) -> tuple[float, float]:
    """The default seed: the parameter box's centre, or where that lies in an umbilic part
    (umbilic measure at most ``level``), the node of a 33 x 33 grid over the box nearest it
    whose measure is over 100 times ``level`` (well off the part's border)."""
    u0, u1, v0, v1 = host.bounds
    centre = (0.5 * (u0 + u1), 0.5 * (v0 + v1))
    if level == 0.0:
        return centre
    from tubecad.nets.principal import principal_field

    at = principal_field(host, np.array([centre[0]]), np.array([centre[1]]))
    if at.umbilic_measure[0] > 100.0 * level:
        return centre
    uu, vv = np.meshgrid(np.linspace(u0, u1, 35)[1:-1], np.linspace(v0, v1, 35)[1:-1], indexing="ij")
    field = principal_field(host, uu.ravel(), vv.ravel())
    good = np.flatnonzero(field.umbilic_measure > 100.0 * level)
    if not good.size:
        raise ParameterError(
            "face: it is umbilic (flat or spherical) nearly everywhere; it has no curvature-line net", key="face"
        )
    distance = np.hypot((uu.ravel()[good] - centre[0]) / (u1 - u0), (vv.ravel()[good] - centre[1]) / (v1 - v0))
    best = int(good[np.argmin(distance)])
    return float(uu.ravel()[best]), float(vv.ravel()[best])


def _host_and_face(face: object) -> tuple[HostSurface, TopoDS_Face]:
    if isinstance(face, HostSurface):
        u0, u1, v0, v1 = face.bounds
        return face, BRepBuilderAPI_MakeFace(face.surface, u0, u1, v0, v1, 1e-7).Face()
    host = HostSurface.of_face(face)
    assert host.face is not None  # of_face keeps the face (it refuses anything else)
    return host, host.face


def _seeds(guide: CurvatureLine, count: int, folds: tuple[float, float] | None = None) -> list[tuple[float, float]]:
    """``count`` parameter points evenly by arc length along ``guide`` (module docstring), or
    along its arc from ``folds[0]`` to ``folds[1]`` (arc lengths from a closed guide's start)
    as along an open line."""
    length = float(guide.sigma[-1] - guide.sigma[0])
    if folds is not None:
        span = (folds[1] - folds[0]) % length
        at = guide.sigma[0] + (folds[0] + (np.arange(count) + 0.5) / count * span) % length
    else:
        share = np.arange(count) / count if guide.closed else (np.arange(count) + 0.5) / count
        at = guide.sigma[0] + share * length
    u, v = np.interp(at, guide.sigma, guide.uv[:, 0]), np.interp(at, guide.sigma, guide.uv[:, 1])
    return [(float(a), float(b)) for a, b in zip(u, v)]


def _folds(guide: CurvatureLine, lines: list[CurvatureLine], count: int) -> tuple[float, float] | None:
    """Where a closed ``guide`` folds, if each closed line of the other family seeded on it
    crosses it twice (an ellipsoid's: its k2 loops cross the k1 loop at (x, +-y, 0)): seeds
    evenly round it would trace each line twice (two edges 1e-5 .. 1e-3 apart, and OCCT's
    splitter leaves invalid slivers between them). The crossings pair the guide's points
    (s, p(s)), an involution reversing the guide whose two fixed points are the folds (where
    the line ends at umbilics: an ellipsoid's umbilic arcs); a fold is taken as the middle of
    the shortest arc between a pair (the second on the other side of the first, or half the
    guide from it).

    Returns the folds' arc lengths from the guide's start (the arc from the first to the
    second, forward, meets each line once), or None: an open guide, or lines that cross it
    once (a torus' meridians) or end elsewhere than at umbilics and poles (a dome's at its
    rim), or more than twice."""
    if not guide.closed or count < 2:
        return None
    if any(not line.closed and not {"umbilic", "pole"}.issuperset(line.stopped) for line in lines):
        return None
    from scipy.spatial import cKDTree

    length = float(guide.sigma[-1] - guide.sigma[0])
    h = length / (40 * count)  # the crossings found to this arc length, far finer than the seeds

    def resampled(line: CurvatureLine) -> tuple[np.ndarray, np.ndarray]:
        at = np.arange(line.sigma[0], line.sigma[-1], h)
        return at - line.sigma[0], np.stack([np.interp(at, line.sigma, line.points[:, k]) for k in range(3)], axis=1)

    along, points = resampled(guide)
    tree = cKDTree(points)
    arcs: list[tuple[float, float]] = []  # (middle, length) of the shorter arc between a pair
    for line in lines:
        distance, nearest = tree.query(resampled(line)[1])
        if line.stopped == ("umbilic", "umbilic"):  # it crosses the guide at a fold
            arcs.append((float(along[nearest[np.argmin(distance)]]), 0.0))
            continue
        if not line.closed:  # stopped at a pole of the parameterisation: half a line
            continue
        near = distance < length / (4 * count)
        runs = np.flatnonzero(np.diff(np.concatenate([[0], near.astype(int), [0]])))
        starts, ends = runs[::2], runs[1::2]
        if len(starts) > 1 and near[0] and near[-1]:  # the last run goes on into the first
            starts, ends = starts[:-1], ends[:-1]
        crossings = [float(along[nearest[a + np.argmin(distance[a:b])]]) for a, b in zip(starts, ends)]
        if len(crossings) > 2:
            return None
        if len(crossings) < 2:  # once (or twice, merged near a fold)
            continue
        gap = (crossings[1] - crossings[0]) % length
        if gap > length / 2:
            crossings, gap = crossings[::-1], length - gap
        arcs.append(((crossings[0] + gap / 2) % length, gap))
    if all(short == 0.0 for _, short in arcs):  # no line met it twice
        return None
    arcs.sort(key=lambda arc: arc[1])
    first = arcs[0][0]
    others = [
        middle for middle, short in arcs if abs((first - middle + length / 2) % length - length / 2) > short / 2 + h
    ]
    second = others[0] if others else (first + length / 2) % length
    return (first, second) if first < second else (second, first)


def _on_face_edges(face: TopoDS_Face, points: np.ndarray) -> bool:
    """Whether the line's ``points`` all lie on the face's own edges (to EDGE_TOLERANCE; seven
    of them tried, ends and between)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_EDGE

    from tubecad.brep.properties import sub_shapes
    from tubecad.core.tolerance import EDGE_TOLERANCE

    edges = sub_shapes(face, TopAbs_EDGE)
    for point in points[np.linspace(0, len(points) - 1, 7).astype(int)]:
        vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*(float(c) for c in point))).Vertex()
        if min(BRepExtrema_DistShapeShape(vertex, edge).Value() for edge in edges) > 10 * EDGE_TOLERANCE:
            return False
    return True


def _split(face: TopoDS_Face, edges: list) -> TopoDS_Shape:
    """``face`` split by ``edges`` lying on it (OCCT's splitter), checked valid."""
    splitter = built(BRepAlgoAPI_Splitter(), [face], edges, parallel=True)
    if not splitter.IsDone() or not BRepCheck_Analyzer(splitter.Shape()).IsValid():
        raise TubecadError("OCCT could not split the face by its curvature lines into a valid shell", key="face")
    return splitter.Shape()
