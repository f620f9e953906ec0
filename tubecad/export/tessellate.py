"""Triangles for a tube or wall on its own curvature-line grid, to a linear tolerance.

The rings (s = const) and stringers (u = const) are lines of curvature: F = M = 0, so over a
grid cell du x ds the surface leaves the plane of a triangle by at most, to second order,

    (|L| du^2 + |N| ds^2) / 8,   L = -rho,   N = kappa (1 - rho kappa),  |kappa| <= k(s)

(README, "What is computed"). Each term gets :data:`SHARE` of the tolerance: around the tube
the exact circle's sag rho (1 - cos(du / 2)), along it k (1 + rho k) ds^2 / 8, with k the
largest axis curvature over the ring bay; the rest covers higher-order terms. The angular
tolerance bounds the turn of the normal between neighbouring triangles: du, and k ds.

OCCT's own mesher (BRepMesh) places points isotropically in the parameter plane, so on these
long B-spline faces it makes several times more triangles and still leaves a few beyond the
deflection; the grid here is anisotropic, and its bound is checked on every file read back
(tubecad.interfaces.readback). The triangulations are attached to the build's faces, with
the polygons of their edges, so the STL, 3MF and glTF writers use them as they are; caps are
triangulated between the same ring points, so the mesh is closed.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.GeomAbs import GeomAbs_Plane
from OCP.gp import gp_Pnt, gp_Pnt2d
from OCP.Poly import Poly_PolygonOnTriangulation, Poly_Triangle, Poly_Triangulation
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location

from ..brep.layout import stringer_parameters
from ..errors import ParameterError
from ..occ_compat import as_face

#: the share of the linear tolerance given to each grid direction (around, along)
SHARE = 0.45
#: the most triangles a tube mesh may have (a finer tolerance is refused before meshing)
MAX_TRIANGLES = 4_000_000
#: axis curvature samples per ring bay, for the bay's largest k
CURVATURE_SAMPLES = 65


def angle_step(radius: float, tolerance: float, angular: float) -> float:
    """The largest angle step (radians) around a circle of ``radius`` whose chords stay
    within SHARE x ``tolerance`` of it, and at most ``angular``."""
    sag = min(SHARE * tolerance / radius, 1.0)
    return min(2.0 * math.acos(1.0 - sag), angular)


def arc_step(k: float, radius: float, tolerance: float, angular: float) -> float:
    """The largest s step along a tube of ``radius`` whose axis curvature is at most ``k``:
    |N| ds^2 / 8 <= SHARE x ``tolerance`` with |N| <= k (1 + rho k), and k ds <= ``angular``;
    inf where the axis is straight."""
    if k <= 0.0:
        return math.inf
    return min(math.sqrt(8.0 * SHARE * tolerance / (k * (1.0 + radius * k))), angular / k)


def grid_angles(stringers_deg: Sequence[float], step: float) -> list[np.ndarray]:
    """Per sector between consecutive stringers (the last one round to the first + 360):
    the angles (degrees, both ends) of its grid columns, equally spaced, at most ``step``
    (radians) apart."""
    ends = [*map(float, stringers_deg), float(stringers_deg[0]) + 360.0]
    return [np.linspace(a, b, max(1, math.ceil(math.radians(b - a) / step)) + 1) for a, b in zip(ends[:-1], ends[1:])]


def grid_arcs(axis, s_rings: Sequence[float], radius: float, tolerance: float, angular: float) -> list[np.ndarray]:
    """Per ring bay: the arc lengths (both ends) of its grid rows, equally spaced."""
    rows = []
    for s0, s1 in zip(s_rings[:-1], s_rings[1:]):
        k = float(np.max(np.abs(axis.curvature(np.linspace(s0, s1, CURVATURE_SAMPLES)))))
        count = (s1 - s0) / arc_step(k, radius, tolerance, angular)
        rows.append(np.linspace(s0, s1, max(1, math.ceil(count)) + 1))
    return rows


def triangulate_build(build, tolerance: float, angular: float) -> int:
    """Attach a triangulation to every face of ``build.shape`` (a TubeBuild's tube or wall):
    its tube faces on the curvature-line grid, its planar caps between the end rings.
    Returns the number of triangles; refuses (ParameterError) more than MAX_TRIANGLES.
    Remove them with ``BRepTools.Clean_s``."""
    radius = max(build.radii)  # the outer tube needs the finest angle step; the inner one shares it
    angles = grid_angles(build.layout.stringers_deg, angle_step(radius, tolerance, angular))
    arcs = grid_arcs(build.surfaces[0].tube.axis, build.layout.s_rings, radius, tolerance, angular)
    total = 2 * sum(len(a) - 1 for a in angles) * sum(len(s) - 1 for s in arcs) * len(build.surfaces)
    if total > MAX_TRIANGLES:
        raise ParameterError(f"a mesh tolerance of {tolerance:g} needs {total:,} triangles for this "
                             f"{'wall' if len(build.surfaces) > 1 else 'tube'}; at most {MAX_TRIANGLES:,} are "
                             f"allowed: use a larger tolerance")  # fmt: skip
    # every node once per surface, so that neighbouring faces and the caps share them bit for bit
    columns = np.radians(np.concatenate([a[:-1] for a in angles]))
    first_column = np.cumsum([0] + [len(a) - 1 for a in angles])
    rows = np.concatenate([s[:-1] for s in arcs] + [arcs[-1][-1:]])
    first_row = np.cumsum([0] + [len(s) - 1 for s in arcs])
    builder = BRep_Builder()
    grids = []
    for surface, patches in zip(build.surfaces, build.patches):
        grid = surface.tube.points(columns[:, None], rows[None, :])
        grid = np.concatenate([grid, grid[:1]])  # the first column again: the last sector closes on it
        grids.append(grid)
        u_cuts = stringer_parameters(build.layout.stringers_deg, surface.u_at)
        for i, row in enumerate(patches.faces):
            for j, face in enumerate(row):
                block = grid[first_column[j] : first_column[j + 1] + 1, first_row[i] : first_row[i + 1] + 1]
                _tube_face(builder, surface, patches, face, (i, j), block, angles[j], arcs[i], u_cuts, tolerance)
    for face, end in _caps(build):
        rings = [grid[:-1, 0 if end == 0 else -1] for grid in grids]
        total += _cap_face(builder, build, face, end, rings, first_column, tolerance)
    return total


def _tube_face(builder, surface, patches, face, where: tuple[int, int], points: np.ndarray, angles: np.ndarray,
               arcs: np.ndarray, u_cuts: list[float], tolerance: float) -> None:  # fmt: skip
    """Face [i][j] = ``where``: its ``points`` (angles x arcs x 3), nodes (a, b) -> 1 + a m + b,
    UV (u, s), two triangles per grid cell."""
    i, j = where
    n, m = len(angles), len(arcs)
    u = np.asarray(surface.u_at(angles), dtype=float)
    u[0], u[-1] = u_cuts[j], u_cuts[j + 1]  # exact at the stringers (u_at wraps 2 pi to 0)
    uv = np.stack(np.broadcast_arrays(u[:, None], arcs[None, :]), axis=-1).reshape(-1, 2)
    index = np.arange(1, n * m + 1).reshape(n, m)
    p, q, r, t = index[:-1, :-1], index[1:, :-1], index[1:, 1:], index[:-1, 1:]
    triangles = np.concatenate([np.stack([p, q, r], -1).reshape(-1, 3), np.stack([p, r, t], -1).reshape(-1, 3)])
    tri = _triangulation(points.reshape(-1, 3), uv, triangles, tolerance)
    builder.UpdateFace(as_face(face), tri)
    n_stringers = len(patches.stringers)
    bottom, top = patches.rings[i][j], patches.rings[i + 1][j]
    left, right = patches.stringers[j][i], patches.stringers[(j + 1) % n_stringers][i]
    _polygon(builder, bottom, [index[:, 0]], tri)
    _polygon(builder, top, [index[:, -1]], tri)
    if n_stringers == 1:  # one seam edge: its forward use is u = 2 pi, the reversed one u = 0
        _polygon(builder, right, [index[-1, :], index[0, :]], tri)
    else:
        _polygon(builder, left, [index[0, :]], tri)
        _polygon(builder, right, [index[-1, :]], tri)


def _caps(build):
    """(face, end) of each planar end cap of the solid, end 0 at the start of the span and 1
    at its end (none on an open shell)."""
    span = build.layout.s_rings[0], build.layout.s_rings[-1]
    ends = build.surfaces[0].tube.axis.position(np.array(span))
    explorer = TopExp_Explorer(build.shape.wrapped, TopAbs_FACE)
    while explorer.More():
        face = as_face(explorer.Current())
        adaptor = BRepAdaptor_Surface(face, False)
        if adaptor.GetType() == GeomAbs_Plane:
            origin = adaptor.Plane().Location()
            yield face, int(np.argmin(np.linalg.norm(ends - [origin.X(), origin.Y(), origin.Z()], axis=1)))
        explorer.Next()


def _cap_face(builder, build, face, end: int, rings: list[np.ndarray], first_column: np.ndarray,
              tolerance: float) -> int:  # fmt: skip
    """The planar cap at ``end`` of the span: a strip between the outer and inner ``rings``
    (a wall), or a fan from the centre (a tube); UV in the plane's own axes. Returns its
    triangle count."""
    count = len(rings[0])
    plane = BRepAdaptor_Surface(face, False).Plane().Position()
    origin, x_dir, y_dir = (np.array([v.X(), v.Y(), v.Z()]) for v in (plane.Location(), plane.XDirection(), plane.YDirection()))
    a = np.arange(count)
    b = (a + 1) % count
    if len(rings) > 1:  # outer ring nodes 1..count, inner count+1..2 count
        points = np.concatenate(rings)
        triangles = np.concatenate([np.stack([a, b, b + count], -1), np.stack([a, b + count, a + count], -1)]) + 1
    else:  # the centre is the last node
        s = build.layout.s_rings[0 if end == 0 else -1]
        points = np.concatenate([rings[0], build.surfaces[0].tube.axis.position(np.array([s]))])
        triangles = np.stack([a, b, np.full(count, count)], -1) + 1
    uv = np.stack([(points - origin) @ x_dir, (points - origin) @ y_dir], -1)
    p, q, r = uv[triangles[0] - 1]
    if (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]) < 0:  # counter-clockwise about the normal
        triangles = triangles[:, ::-1]
    tri = _triangulation(points, uv, triangles, tolerance)
    builder.UpdateFace(face, tri)
    ring = 0 if end == 0 else len(build.layout.s_rings) - 1
    for k, patches in enumerate(build.patches):
        for j, edge in enumerate(patches.rings[ring]):
            nodes = (np.arange(first_column[j], first_column[j + 1] + 1) % count) + 1 + k * count
            _polygon(builder, edge, [nodes], tri)
    return len(triangles)


def _triangulation(points: np.ndarray, uv: np.ndarray, triangles: np.ndarray, tolerance: float) -> Poly_Triangulation:
    """A Poly_Triangulation with UV nodes; 1-based triangle indices; its deflection ``tolerance``."""
    tri = Poly_Triangulation(len(points), len(triangles), True)
    for i, ((x, y, z), (u, v)) in enumerate(zip(points.tolist(), uv.tolist()), 1):
        tri.SetNode(i, gp_Pnt(x, y, z))
        tri.SetUVNode(i, gp_Pnt2d(u, v))
    for i, (a, b, c) in enumerate(triangles.tolist(), 1):
        tri.SetTriangle(i, Poly_Triangle(a, b, c))
    tri.Deflection(tolerance)
    return tri


def _polygon(builder, edge, node_lists: list[np.ndarray], tri: Poly_Triangulation) -> None:
    """The edge's nodes on ``tri`` (two lists for a seam edge), in the edge's direction."""
    polygons = []
    for nodes in node_lists:
        polygon = Poly_PolygonOnTriangulation(len(nodes), False)
        for i, node in enumerate(nodes.tolist(), 1):
            polygon.SetNode(i, node)
        polygons.append(polygon)
    builder.UpdateEdge(edge, *polygons, tri, TopLoc_Location())


def mesh_deviation(axis, radii: Sequence[float], vertices: np.ndarray, triangles: np.ndarray) -> tuple[float, float]:
    """(max vertex deviation, max triangle deviation) of a mesh of tubes of ``radii`` about
    ``axis``: how far its vertices, and its triangles, lie from the exact tube each triangle
    belongs to. A triangle is sampled at its edge midpoints, where a chord of a surface whose
    second fundamental form is diagonal on the grid leaves it farthest (its centroid lies
    8/9 as far). Planar end caps (every vertex at the same end of the span) are not measured."""
    from ..surface.checks import distance_to_axis

    radii = np.asarray(radii, dtype=float)
    dist, s = distance_to_axis(axis, vertices)
    vertex = float(np.min(np.abs(dist[:, None] - radii[None, :]), axis=1).max())
    ends = np.array(axis.span)
    at_end = np.abs(s[:, None] - ends[None, :]) <= 1e-3 * radii.min()  # (n, 2)
    cap = (at_end[triangles].all(axis=1)).any(axis=1)
    tube = triangles[~cap]
    if not len(tube):
        return vertex, 0.0
    radius = radii[np.argmin(np.abs(dist[tube].mean(axis=1)[:, None] - radii[None, :]), axis=1)]
    a, b = tube, np.roll(tube, -1, axis=1)  # the three edges (a_k, b_k) of each triangle
    midpoints = 0.5 * (vertices[a] + vertices[b]).reshape(-1, 3)
    step = s[b] - s[a]
    if axis.closed:  # an edge across the closing ring: its ends are near s0 and s1, its middle at either
        step = np.where(np.abs(step) > 0.5 * axis.length, step - np.sign(step) * axis.length, step)
    guess = s[a] + 0.5 * step
    if axis.closed:
        guess = axis.span[0] + np.mod(guess - axis.span[0], axis.length)
    guess = np.clip(guess, *axis.span).reshape(-1)
    d, _ = distance_to_axis(axis, midpoints, guess, iters=4)  # from a close guess
    return vertex, float(np.abs(d - np.repeat(radius, 3)).max())
