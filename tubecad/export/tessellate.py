"""Triangles for a tube or wall on its own curvature-line grid, to a linear tolerance.

The rings (s = const) and stringers (u = const) are lines of curvature: F = M = 0, so over a
grid cell du x ds the surface leaves the plane of a triangle by at most, to second order,

    (|L| du^2 + |N| ds^2) / 8,   L = -rho,   N = kappa (1 - rho kappa),  |kappa| <= k(s)

(docs/index.md, "What is computed"). Each term gets :data:`SHARE` of the tolerance: around the tube
the exact circle's sag rho (1 - cos(du / 2)), along it k (1 + rho k) ds^2 / 8, with k the
largest axis curvature over the ring bay; the rest covers higher-order terms. The angular
tolerance bounds the turn of the normal between neighbouring triangles: du, and k ds.

OCCT's own mesher (BRepMesh) places points isotropically in the parameter plane, so on these
long B-spline faces it makes several times more triangles and still leaves a few beyond the
deflection; the grid here is anisotropic, and its bound is checked on every file read back
(tubecad.export.readback). The triangulations are attached to the build's faces, with
the polygons of their edges, so the STL, 3MF and glTF writers use them as they are; caps are
triangulated between the same ring points, so the mesh is closed.

A closed tube has no caps: its ring at s = L is its ring at s = 0, reached by the grid column
at angle c at c + h, h the holonomy (the rotation-minimising frame comes back turned by it).
The closing ring's nodes are the columns and the columns + h (among them the B-rep's cuts
there, a_j and b_j = a_j + h), their points computed once per surface; the first band's
bottom row and the last band's top row are those very points (the last band's at its own
angles, theta - h), each joined to its regular neighbour row by fans: the mesh closes there
too, with a triangle more per extra node.

A canal surface (a radius law r(s)) is meshed on its own grid (:func:`canal_grid`): its
rings are the characteristic circles, of radius r q varying along s, and its stringers
chi0 = const are spaced round them by the Moebius map, so no closed bound like the tube's
holds; the columns and rows are spaced where the second fundamental form asks, and then
measured on the exact surfaces (chord midpoints along the normal, the normal's turn) and
refined until they hold. A wall's caps, pieces of the normal cone through its end circles
(planar where r' = 0), are strips between the outer and inner end circles' nodes, which
lie on the cone's generators; a tube solid's end discs are strips across their circle.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.GeomAbs import GeomAbs_Cone, GeomAbs_Plane
from OCP.gp import gp_Pnt, gp_Pnt2d
from OCP.Poly import Poly_PolygonOnTriangulation, Poly_Triangle, Poly_Triangulation
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location

from tubecad.brep.faces import CLOSING_MERGE
from tubecad.brep.layout import stringer_parameters
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.occ_compat import as_edge, as_face

if TYPE_CHECKING:
    from OCP.TopoDS import TopoDS_Edge, TopoDS_Face

    from tubecad.brep import TubeBuild
    from tubecad.brep.faces import PatchFaces
    from tubecad.curves import Axis
    from tubecad.fitting.exact_section import TubeSurface
    from tubecad.surface.protocol import CurvatureLineSurface

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


def grid_arcs(
    axis: Axis, s_rings: Sequence[float], radius: float, tolerance: float, angular: float
) -> list[np.ndarray]:
    """Per ring bay: the arc lengths (both ends) of its grid rows, equally spaced. The bay's
    curvature is sampled up to its ends from inside: at a route's line-bend joint k jumps,
    and the bend's k must not refine the straight bay beside it."""
    rows = []
    for s0, s1 in zip(s_rings[:-1], s_rings[1:]):
        samples = np.linspace(s0, s1, CURVATURE_SAMPLES)
        samples[[0, -1]] += np.array([1.0, -1.0]) * 1e-9 * (s1 - s0)
        k = float(np.max(np.abs(axis.curvature(samples))))
        count = (s1 - s0) / arc_step(k, radius, tolerance, angular)
        rows.append(np.linspace(s0, s1, max(1, math.ceil(count)) + 1))
    return rows


def _columns_deg(build: TubeBuild) -> list[float]:
    """The angles of the build's face columns (:attr:`~tubecad.brep.faces.PatchFaces.columns_deg`)."""
    return build.patches[0].columns_deg or list(build.layout.stringers_deg)


def triangulate_build(build: TubeBuild, tolerance: float, angular: float) -> int:
    """Attach a triangulation to every face of ``build.shape`` (a TubeBuild's tube or wall):
    its tube faces on the curvature-line grid, its planar caps between the end rings (a
    closed axis has none: its first and last bands share the closing ring's nodes).
    Returns the number of triangles; refuses (ParameterError) more than MAX_TRIANGLES.
    Remove them with ``BRepTools.Clean_s``."""
    axis = build.surfaces[0].tube.axis
    if not build.surfaces[0].tube.constant_radius:  # a canal surface: steps measured on the exact surfaces
        angles, arcs = canal_grid(build, tolerance, angular)
    else:
        radius = max(build.radii)  # the outer tube needs the finest angle step; the inner one shares it
        # the face columns: the stringers and any C0 knot of the circle between them
        angles = grid_angles(_columns_deg(build), angle_step(radius, tolerance, angular))
        arcs = grid_arcs(axis, build.layout.s_rings, radius, tolerance, angular)
    # every node once per surface, so that neighbouring faces and the caps share them bit for bit
    columns = np.radians(np.concatenate([a[:-1] for a in angles]))
    first_column = np.cumsum([0] + [len(a) - 1 for a in angles])
    rows = np.concatenate([s[:-1] for s in arcs] + [arcs[-1][-1:]])
    first_row = np.cumsum([0] + [len(s) - 1 for s in arcs])
    # a closed axis: the closing ring's nodes on each surface (angles from the origin stringer)
    rings = [closing_angles(columns - columns[0], axis.holonomy, rho) for rho in build.radii] if axis.closed else []
    total = 2 * sum(len(a) - 1 for a in angles) * sum(len(s) - 1 for s in arcs) * len(build.surfaces)
    total += sum(2 * (len(ring) - len(columns)) for ring, _ in rings)  # a fan triangle per extra node, in both bands
    if total > MAX_TRIANGLES:
        raise ParameterError(
            f"a mesh tolerance of {tolerance:g} needs {total:,} triangles for this "
            f"{'wall' if len(build.surfaces) > 1 else 'tube'}; at most {MAX_TRIANGLES:,} are "
            f"allowed: use a larger tolerance"
        )
    builder = BRep_Builder()
    grids = []
    for k, (surface, patches) in enumerate(zip(build.surfaces, build.patches)):
        grid = surface.tube.points(columns[:, None], rows[None, :])
        grid = np.concatenate([grid, grid[:1]])  # the first column again: the last sector closes on it
        grids.append(grid)
        u_cuts = stringer_parameters(_columns_deg(build), surface.u_at)
        closing = (
            _ClosingRing(surface, patches, grid, rows[0], columns, first_column, build.radii[k], *rings[k])
            if rings
            else None
        )
        last = len(patches.faces) - 1
        for i, row in enumerate(patches.faces):
            for j, face in enumerate(row):
                block = grid[first_column[j] : first_column[j + 1] + 1, first_row[i] : first_row[i + 1] + 1]
                bottom = closing.first(j) if closing is not None and i == 0 else None
                top = closing.last(j) if closing is not None and i == last else None
                _tube_face(
                    builder, surface, patches, face, (i, j), block, angles[j], arcs[i], u_cuts, tolerance, bottom, top
                )
    for face, end, cone in _caps(build):
        cap_rings = [grid[:-1, 0 if end == 0 else -1] for grid in grids]
        cap = _cone_cap_face if cone else _cap_face
        total += cap(builder, build, face, end, cap_rings, first_column, tolerance)
    return total


#: a canal grid's cell diagonal (the sum of its two directions' errors) may reach this
#: fraction of the tolerance; the rest is left for the file's rounding
DIAGONAL_SHARE = 0.95
#: samples of the second fundamental form per sector (around) and per ring bay (along), for
#: a canal grid's first steps and their spacing
FORM_SAMPLES = (17, 17)
#: passes of a canal grid's measure-and-refine loop (the first may also coarsen)
CANAL_PASSES = 6


def canal_grid(build: TubeBuild, tolerance: float, angular: float) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The grid of a canal surface's build (its surfaces' ``tube`` CanalSurfaces, the exact
    r + d): per sector its columns' angles chi0 (degrees, both ends), per ring bay its rows'
    s (both ends), as :func:`grid_angles` and :func:`grid_arcs` give a tube's.

    Nothing of a tube's bound carries over (the circles' radius r q and the Moebius map's
    spacing of the stringers vary along s, the stringers' normal curvature with r'' too), so
    the steps are measured. The second fundamental form sampled over each sector and bay
    gives the intervals needed per unit chi0 and s (|L| du^2 / 8 and |N| ds^2 / 8 within
    SHARE x ``tolerance``, the normal's turn |L| du / sqrt(E), |N| ds / sqrt(G) within
    ``angular``), the largest over the other direction; the columns and rows are spaced
    where those densities ask (equal shares of their integrals), a first count from the
    integrals. Then on the grid itself, on every surface, the chord midpoints' distance from
    the exact surface along its normal (rings, stringers and the cells' diagonals) and the
    turn of the exact normals between neighbouring nodes are measured, and each sector and
    bay refined (the first pass also coarsened) by the square root of its excess, until
    every one holds."""
    exact = [surface.tube for surface in build.surfaces]
    columns = _columns_deg(build)
    ends = np.array([*map(float, columns), float(columns[0]) + 360.0])
    s_rings = np.asarray(build.layout.s_rings, dtype=float)
    (chi0, around), (s, along_need) = _canal_densities(exact, np.radians(ends), s_rings, tolerance, angular)
    n_u = np.maximum(1, np.ceil(_integrals(chi0, around))).astype(int)
    n_s = np.maximum(1, np.ceil(_integrals(s, along_need))).astype(int)
    for attempt in range(CANAL_PASSES):
        angles = [np.degrees(_spaced(x, d, n)) for x, d, n in zip(chi0, around, n_u)]
        arcs = [_spaced(x, d, n) for x, d, n in zip(s, along_need, n_s)]
        for a, b, grid in ((ends[:-1], ends[1:], angles), (s_rings[:-1], s_rings[1:], arcs)):
            for k, row in enumerate(grid):  # the ends exactly
                row[0], row[-1] = a[k], b[k]
        ring, along, diagonal = _canal_errors(exact, angles, arcs, tolerance, angular)
        if ring.max() <= 1.0 and along.max() <= 1.0 and diagonal.max() <= 1.0:
            return angles, arcs
        # a cell whose diagonal alone is too far: both its directions share the excess
        ring = np.maximum(ring, diagonal.max(axis=0))
        along = np.maximum(along, diagonal.max(axis=1))
        grow_u, grow_s = np.sqrt(np.maximum(ring, 0.0)) * 1.02, np.sqrt(np.maximum(along, 0.0)) * 1.02
        if attempt > 0:
            grow_u, grow_s = np.maximum(grow_u, 1.0), np.maximum(grow_s, 1.0)
        n_u = np.maximum(1, np.ceil(n_u * grow_u - 1e-9)).astype(int)
        n_s = np.maximum(1, np.ceil(n_s * grow_s - 1e-9)).astype(int)
    raise TubecadError(
        f"the canal surface's mesh grid does not reach the mesh tolerance {tolerance:g} in {CANAL_PASSES} passes"
    )


def _integrals(x: np.ndarray, density: np.ndarray) -> np.ndarray:
    """Per row of samples ``x`` the trapezoid integral of ``density``."""
    return (0.5 * (density[:, 1:] + density[:, :-1]) * np.diff(x, axis=1)).sum(axis=1)


def _spaced(x: np.ndarray, density: np.ndarray, count: int) -> np.ndarray:
    """``count`` + 1 points from x[0] to x[-1] that cut the integral of ``density`` (sampled at
    ``x``, piecewise linear; floored at a tenth of its mean, so no interval grows far past the
    equal one) into equal shares."""
    d = np.maximum(density, 0.1 * density.mean() + 1e-300)
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (d[1:] + d[:-1]) * np.diff(x))])
    return np.interp(np.linspace(0.0, cumulative[-1], count + 1), cumulative, x)


def _canal_densities(
    exact: list, ends: np.ndarray, s_rings: np.ndarray, tolerance: float, angular: float
) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """The grid intervals a canal surface needs per unit chi0 over each sector (``ends``,
    radians) and per unit s over each bay (``s_rings``), from |L|, |N| (and E, G) sampled on
    every surface, each the largest over the other direction (see :func:`canal_grid`):
    ((chi0 samples, density) per sector, (s samples, density) per bay), rows of samples."""
    per_u, per_s = FORM_SAMPLES
    frac_u, frac_s = np.linspace(0.0, 1.0, per_u), np.linspace(1e-9, 1.0 - 1e-9, per_s)
    chi0 = ends[:-1, None] + np.diff(ends)[:, None] * frac_u
    s = s_rings[:-1, None] + np.diff(s_rings)[:, None] * frac_s
    around = np.zeros(chi0.size)
    along = np.zeros(s.size)
    sag = 8.0 * SHARE * tolerance
    for surface in exact:
        forms = surface.fundamental_forms(chi0.reshape(-1, 1), s.reshape(1, -1))
        L, N = np.abs(forms.L), np.abs(forms.N)
        around = np.maximum(around, np.maximum(np.sqrt(L / sag), L / (np.sqrt(forms.E) * angular)).max(axis=1))
        along = np.maximum(along, np.maximum(np.sqrt(N / sag), N / (np.sqrt(forms.G) * angular)).max(axis=0))
    s[:, 0], s[:, -1] = s_rings[:-1], s_rings[1:]
    return (chi0, around.reshape(chi0.shape)), (s, along.reshape(s.shape))


def _canal_errors(
    exact: list, angles: list[np.ndarray], arcs: list[np.ndarray], tolerance: float, angular: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """On the grid of ``angles`` (degrees) x ``arcs``, over every surface of ``exact``: per
    sector the largest error around (the ring chords' midpoints' distance from the surface
    over SHARE x ``tolerance``, or the normal's turn between neighbouring columns over
    ``angular``), per bay the largest along (the stringer chords', the turn between rows), per
    cell (bay x sector) its diagonal's midpoint's distance over DIAGONAL_SHARE x ``tolerance``:
    each at most 1 where the grid holds. The distance is measured along the exact normal at
    the chord's middle parameters (the chord leaves the surface along it, to higher order)."""
    columns = np.radians(np.concatenate([a[:-1] for a in angles] + [angles[-1][-1:]]))
    rows = np.concatenate([s[:-1] for s in arcs] + [arcs[-1][-1:]])
    sector = np.repeat(np.arange(len(angles)), [len(a) - 1 for a in angles])  # of each column interval
    bay = np.repeat(np.arange(len(arcs)), [len(s) - 1 for s in arcs])  # of each row interval
    mid_c, mid_r = 0.5 * (columns[:-1] + columns[1:]), 0.5 * (rows[:-1] + rows[1:])
    ring, along = np.zeros(len(angles)), np.zeros(len(arcs))
    diagonal = np.zeros((len(arcs), len(angles)))

    # X = c + r n: the sphere's normal
    def normal(surface: CurvatureLineSurface, x: np.ndarray, s: np.ndarray) -> np.ndarray:
        return (x - surface.axis.position(s)[None]) / surface.radius_law.r(s)[None, :, None]

    def off(chord: np.ndarray, chi0: np.ndarray, s: np.ndarray, surface: CurvatureLineSurface) -> np.ndarray:
        x = surface.points(chi0[:, None], s[None, :])
        return np.abs(np.einsum("...i,...i", chord - x, normal(surface, x, s)))

    def turn(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return 2.0 * np.arcsin(np.clip(0.5 * np.linalg.norm(a - b, axis=-1), 0.0, 1.0))

    for surface in exact:
        p = surface.points(columns[:, None], rows[None, :])
        n = normal(surface, p, rows)
        around = np.maximum(
            off(0.5 * (p[:-1] + p[1:]), mid_c, rows, surface) / (SHARE * tolerance), turn(n[:-1], n[1:]) / angular
        ).max(axis=1)
        np.maximum.at(ring, sector, around)
        up = np.maximum(
            off(0.5 * (p[:, :-1] + p[:, 1:]), columns, mid_r, surface) / (SHARE * tolerance),
            turn(n[:, :-1], n[:, 1:]) / angular,
        ).max(axis=0)
        np.maximum.at(along, bay, up)
        cell = off(0.5 * (p[:-1, :-1] + p[1:, 1:]), mid_c, mid_r, surface) / (DIAGONAL_SHARE * tolerance)
        np.maximum.at(diagonal, (bay[None, :], sector[:, None]), cell)
    return ring, along, diagonal


def closing_angles(columns: np.ndarray, holonomy: float, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """The nodes of a closed tube's closing ring: the grid ``columns`` (radians from the origin
    stringer, increasing in [0, 2 pi)), where they start, and the same + ``holonomy`` mod 2 pi,
    where they end; an added angle within CLOSING_MERGE / ``radius`` of a column is dropped
    (the B-rep merges a stringer's end onto a stringer's start as near). Returns (the angles,
    increasing in [0, 2 pi); the column of each, -1 for an added one)."""
    two_pi = 2.0 * math.pi
    added = np.mod(columns + holonomy, two_pi)
    added[added >= two_pi] = 0.0
    at = np.searchsorted(columns, added)
    gap = np.minimum(
        *(np.abs(np.remainder(added - columns[k] + math.pi, two_pi) - math.pi) for k in (at - 1, at % len(columns)))
    )
    added = added[radius * gap > CLOSING_MERGE]
    ring = np.concatenate([columns, added])
    order = np.argsort(ring, kind="stable")
    return ring[order], np.concatenate([np.arange(len(columns)), np.full(len(added), -1)])[order]


@dataclass
class _Row:
    """A face's row of nodes on the closing ring, in +u order: their points, u, angles on the
    ring (from the origin stringer, lifted to increase), and the row node of each of the
    face's regular columns."""

    points: np.ndarray
    u: np.ndarray
    ring: np.ndarray
    match: np.ndarray


class _ClosingRing:
    """The closing ring of one surface of a closed tube: its nodes (:func:`closing_angles`),
    their points computed once (a grid column's at s0 bit for bit, the others the exact tube
    point at s0), and the rows they make on the first band's faces (at the ring's angles,
    s0) and on the last band's (at the faces' own angles theta - (b_j - a_j), s = L)."""

    def __init__(
        self,
        surface: TubeSurface,
        patches: PatchFaces,
        grid: np.ndarray,
        s0: float,
        columns: np.ndarray,
        first_column: np.ndarray,
        rho: float,
        angles: np.ndarray,
        column: np.ndarray,
    ) -> None:
        self.surface, self.patches, self.first_column, self.angles = surface, patches, first_column, angles
        self.columns = np.append(columns - columns[0], 2.0 * math.pi)  # from the origin; the last sector ends at 2 pi
        own = column >= 0
        self.points = np.empty((len(angles), 3))
        self.points[own] = grid[column[own], 0]
        if not own.all():
            self.points[~own] = surface.tube.points((angles[~own] + columns[0])[:, None], np.array([[s0]]))[:, 0]
        self.node = np.empty(len(columns), dtype=int)  # the ring node of each column
        self.node[column[own]] = np.flatnonzero(own)
        self.rho = float(rho)

    def first(self, j: int) -> _Row:
        """Face j of the first band: the nodes from stringer j's start a_j to a_j+1."""
        c0, c1 = self.first_column[j], self.first_column[j + 1]
        nodes, ring = self._run(self.node[c0], self.node[c1 % len(self.node)])
        return self._row(j, nodes, ring, ring)

    def last(self, j: int) -> _Row:
        """Face j of the last band: the nodes from stringer j's end b_j to stringer j+1's end
        (round the whole ring for a seam), at the face's own angles theta - (b_j - a_j)."""
        ends = self.patches.closing_ends
        b = float(ends[j])
        nodes, ring = self._run(self._nearest(b), self._nearest(float(ends[(j + 1) % len(ends)])))
        own = self.columns[self.first_column[j]] + (ring - ring[0]) + math.remainder(ring[0] - b, 2.0 * math.pi)
        return self._row(j, nodes, ring, own)

    def _nearest(self, theta: float) -> int:
        return int(np.argmin(np.abs(np.remainder(self.angles - theta + math.pi, 2.0 * math.pi) - math.pi)))

    def _run(self, start: int, stop: int) -> tuple[np.ndarray, np.ndarray]:
        """The ring nodes from ``start`` to ``stop`` in +theta order (once round when they are
        the same), and their angles lifted to increase from the start's."""
        count = len(self.angles)
        k = np.arange(start, stop + (count if stop <= start else 0) + 1)
        return k % count, self.angles[k % count] + 2.0 * math.pi * (k // count)

    def _row(self, j: int, nodes: np.ndarray, ring: np.ndarray, own: np.ndarray) -> _Row:
        regular = self.columns[self.first_column[j] : self.first_column[j + 1] + 1]
        match = np.abs(own[None, :] - regular[:, None]).argmin(axis=1)
        off = np.abs(own[match] - regular).max()  # round-off, or a stringer's end merged onto a start
        ordered = match[0] == 0 and match[-1] == len(own) - 1 and np.all(np.diff(match) > 0)
        if not ordered or off > 2.0 * CLOSING_MERGE / self.rho + 1e-9:
            raise TubecadError(
                f"the closing ring's mesh nodes do not match the grid columns of face {j} (off by {off:.3g} rad)"
            )
        u = np.asarray(self.surface.circle.u_of_theta(np.clip(own, regular[0], regular[-1])), dtype=float)
        return _Row(self.points[nodes], u, ring, match)


def _tube_face(
    builder: BRep_Builder,
    surface: TubeSurface,
    patches: PatchFaces,
    face: TopoDS_Face,
    where: tuple[int, int],
    points: np.ndarray,
    angles: np.ndarray,
    arcs: np.ndarray,
    u_cuts: list[float],
    tolerance: float,
    bottom: _Row | None = None,
    top: _Row | None = None,
) -> None:
    """Face [i][j] = ``where``: its ``points`` (angles x arcs x 3), nodes (a, b) -> 1 + a m + b,
    UV (u, s), two triangles per grid cell. On a closed tube the first band's ``bottom`` row
    and the last band's ``top`` row are the closing ring's (a superset of the columns), joined
    to their neighbour rows by fans."""
    if bottom is not None or top is not None:
        return _closing_face(
            builder, surface, patches, face, where, points, angles, arcs, u_cuts, tolerance, bottom, top
        )
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
    n_stringers = len(patches.columns)
    lower, upper = patches.rings[i][j], patches.rings[i + 1][j]
    left, right = patches.columns[j][i], patches.columns[(j + 1) % n_stringers][i]
    _polygon(builder, lower, [index[:, 0]], tri)
    _polygon(builder, upper, [index[:, -1]], tri)
    if n_stringers == 1:  # one seam edge: its forward use is u = 2 pi, the reversed one u = 0
        _polygon(builder, right, [index[-1, :], index[0, :]], tri)
    else:
        _polygon(builder, left, [index[0, :]], tri)
        _polygon(builder, right, [index[-1, :]], tri)


def _closing_face(
    builder: BRep_Builder,
    surface: TubeSurface,
    patches: PatchFaces,
    face: TopoDS_Face,
    where: tuple[int, int],
    points: np.ndarray,
    angles: np.ndarray,
    arcs: np.ndarray,
    u_cuts: list[float],
    tolerance: float,
    bottom: _Row | None,
    top: _Row | None,
) -> None:
    """:func:`_tube_face` for a face on the closing ring: the regular rows' nodes first
    (column-major), then the ``bottom`` and ``top`` rows'. Each regular interval [c_k, c_k+1]
    of an irregular row with its nodes p_0 = c_k, ..., p_m = c_k+1 is joined to the regular
    row's nodes R_k, R_k+1 by the triangles (p_t, p_t+1, R_k) and (p_m, R_k+1, R_k) below it,
    (R_k, p_t+1, p_t) and (R_k, R_k+1, p_m) above it: counter-clockwise in (u, s)."""
    i, j = where
    n, m = len(angles), len(arcs)
    lo, hi = int(bottom is not None), m - int(top is not None)  # the regular rows lo .. hi - 1
    if hi <= lo:
        raise TubecadError(f"face [{i}][{j}] would have no regular grid row between its closing rows")
    u = np.asarray(surface.u_at(angles), dtype=float)
    u[0], u[-1] = u_cuts[j], u_cuts[j + 1]
    index = np.zeros((n, m), dtype=int)
    index[:, lo:hi] = np.arange(1, n * (hi - lo) + 1).reshape(n, hi - lo)
    nodes = [points[:, lo:hi].reshape(-1, 3)]
    uv = [np.stack(np.broadcast_arrays(u[:, None], arcs[None, lo:hi]), axis=-1).reshape(-1, 2)]
    p, q, r, t = index[:-1, lo : hi - 1], index[1:, lo : hi - 1], index[1:, lo + 1 : hi], index[:-1, lo + 1 : hi]
    triangles = [np.stack([p, q, r], -1).reshape(-1, 3), np.stack([p, r, t], -1).reshape(-1, 3)]
    count = n * (hi - lo)
    rows = {}
    for b, row in ((0, bottom), (m - 1, top)):
        if row is None:
            continue
        ids = np.arange(count + 1, count + 1 + len(row.points))
        count += len(row.points)
        row_u = row.u.copy()
        row_u[row.match] = u  # the columns' own u, exact at the stringers
        nodes.append(row.points)
        uv.append(np.stack([row_u, np.full(len(row_u), arcs[b])], axis=-1))
        triangles.append(_fans(ids, row.match, index[:, 1 if b == 0 else m - 2], below=b == 0))
        index[:, b] = ids[row.match]
        rows[b] = (ids, row)
    tri = _triangulation(np.concatenate(nodes), np.concatenate(uv), np.concatenate(triangles), tolerance)
    builder.UpdateFace(as_face(face), tri)
    n_stringers = len(patches.columns)
    for b, ring in ((0, i), (m - 1, i + 1)):
        if b in rows:
            _closing_polygons(builder, patches.closing_arcs, *rows[b], tri)
        else:
            _polygon(builder, patches.rings[ring][j], [index[:, b]], tri)
    left, right = patches.columns[j][i], patches.columns[(j + 1) % n_stringers][i]
    if n_stringers == 1:
        _polygon(builder, right, [index[-1, :], index[0, :]], tri)
    else:
        _polygon(builder, left, [index[0, :]], tri)
        _polygon(builder, right, [index[-1, :]], tri)


def _fans(row: np.ndarray, match: np.ndarray, regular: np.ndarray, below: bool) -> np.ndarray:
    """The triangles between an irregular row's nodes ``row`` (``match``: where the regular
    columns are among them) and the regular row's ``regular`` nodes, the irregular row
    ``below`` it or above."""
    triangles = []
    for k in range(len(regular) - 1):
        a, b, r0, r1 = match[k], match[k + 1], regular[k], regular[k + 1]
        if below:
            triangles += [(row[t], row[t + 1], r0) for t in range(a, b)] + [(row[b], r1, r0)]
        else:
            triangles += [(r0, row[t + 1], row[t]) for t in range(a, b)] + [(r0, r1, row[b])]
    return np.array(triangles, dtype=int).reshape(-1, 3)


def _closing_polygons(
    builder: BRep_Builder,
    arcs: list[tuple[float, float, TopoDS_Edge]],
    ids: np.ndarray,
    row: _Row,
    tri: Poly_Triangulation,
) -> None:
    """The polygon of each closing arc on a face's closing row: the row's nodes between the
    arc's ends (the arcs whose middle, lifted by 2 pi k, falls within the row)."""
    two_pi = 2.0 * math.pi
    x0, x1 = row.ring[0], row.ring[-1]
    mine = []
    for a, b, edge in arcs:
        lift = x0 + (0.5 * (a + b) - x0) % two_pi - 0.5 * (a + b)
        if 0.5 * (a + b) + lift < x1:
            mine.append((a + lift, b + lift, edge))
    at = 0
    for a, b, edge in sorted(mine, key=lambda arc: arc[0]):
        start, stop = (int(np.argmin(np.abs(row.ring - x))) for x in (a, b))
        if start != at or stop <= start:
            break
        _polygon(builder, edge, [ids[start : stop + 1]], tri)
        at = stop
    if at != len(ids) - 1 or not mine:
        raise TubecadError("the closing ring's arcs do not match its mesh nodes")


def _caps(build: TubeBuild) -> Iterator[tuple[TopoDS_Face, int, bool]]:
    """(face, end, conical) of each end cap of the solid, end 0 at the start of the span and 1
    at its end (none on an open shell): planar, or a canal wall's piece of the normal cone."""
    span = build.layout.s_rings[0], build.layout.s_rings[-1]
    ends = build.surfaces[0].tube.axis.position(np.array(span))
    explorer = TopExp_Explorer(build.shape.wrapped, TopAbs_FACE)
    while explorer.More():
        face = as_face(explorer.Current())
        adaptor = BRepAdaptor_Surface(face, False)
        kind = adaptor.GetType()
        if kind in (GeomAbs_Plane, GeomAbs_Cone):
            origin = (adaptor.Plane() if kind == GeomAbs_Plane else adaptor.Cone()).Location()
            end = int(np.argmin(np.linalg.norm(ends - [origin.X(), origin.Y(), origin.Z()], axis=1)))
            yield face, end, kind == GeomAbs_Cone
        explorer.Next()


def _cap_face(
    builder: BRep_Builder,
    build: TubeBuild,
    face: TopoDS_Face,
    end: int,
    rings: list[np.ndarray],
    first_column: np.ndarray,
    tolerance: float,
) -> int:
    """The planar cap at ``end`` of the span: a strip between the outer and inner ``rings``
    (a wall), or a fan from the centre (a tube); UV in the plane's own axes. Returns its
    triangle count."""
    count = len(rings[0])
    plane = BRepAdaptor_Surface(face, False).Plane().Position()
    origin, x_dir, y_dir = (
        np.array([v.X(), v.Y(), v.Z()]) for v in (plane.Location(), plane.XDirection(), plane.YDirection())
    )
    a = np.arange(count)
    b = (a + 1) % count
    if len(rings) > 1:  # outer ring nodes 1..count, inner count+1..2 count
        points = np.concatenate(rings)
        triangles = np.concatenate([np.stack([a, b, b + count], -1), np.stack([a, b + count, a + count], -1)]) + 1
    elif not build.surfaces[0].tube.constant_radius:
        # a canal surface's end circle: a strip zigzagging across it, no node off the circle
        # (its centre c - r r' t is off the axis, where a mesh's measure would take it for
        # the surface's); each triangle turned counter-clockwise below
        points = rings[0]
        order = np.empty(count, dtype=int)
        order[0::2], order[1::2] = np.arange((count + 1) // 2), count - 1 - np.arange(count // 2)
        triangles = np.stack([order[:-2], order[1:-1], order[2:]], -1) + 1
    else:  # the centre is the last node
        s = build.layout.s_rings[0 if end == 0 else -1]
        points = np.concatenate([rings[0], build.surfaces[0].tube.axis.position(np.array([s]))])
        triangles = np.stack([a, b, np.full(count, count)], -1) + 1
    uv = np.stack([(points - origin) @ x_dir, (points - origin) @ y_dir], -1)
    p, q, r = (uv[triangles[:, k] - 1] for k in range(3))
    clockwise = (q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0]) < 0
    triangles[clockwise] = triangles[clockwise, ::-1]  # counter-clockwise about the normal
    tri = _triangulation(points, uv, triangles, tolerance)
    builder.UpdateFace(face, tri)
    ring = 0 if end == 0 else len(build.layout.s_rings) - 1
    for k, patches in enumerate(build.patches):
        for j, edge in enumerate(patches.rings[ring]):
            nodes = (np.arange(first_column[j], first_column[j + 1] + 1) % count) + 1 + k * count
            _polygon(builder, edge, [nodes], tri)
    return len(triangles)


def _cone_cap_face(
    builder: BRep_Builder,
    build: TubeBuild,
    face: TopoDS_Face,
    end: int,
    rings: list[np.ndarray],
    first_column: np.ndarray,
    tolerance: float,
) -> int:
    """A canal wall's cap at ``end``, the piece of the normal cone through its outer and inner
    end circles (tubecad.brep.solids.normal_cone_face): the strip between the ``rings``' nodes.
    A node and its partner on the other ring lie on one generator (the stringers of r + d
    share chi(chi0, s)), so each quad is planar, on the cone up to the circles' own chords.
    The seam (the generator u = 0, through the first column) has its nodes twice, at u = 0
    and u = 2 pi; UV is the cone's own (u about +t, v along the generator). Returns its
    triangle count."""
    from OCP.BRep import BRep_Tool
    from OCP.ElSLib import ElSLib
    from OCP.TopAbs import TopAbs_EDGE

    count = len(rings[0])
    cone = BRepAdaptor_Surface(face, False).Cone()
    points = np.concatenate([np.concatenate([ring, ring[:1]]) for ring in rings])  # outer 0..count, inner after
    uv = np.array([ElSLib.Parameters_s(cone, gp_Pnt(*p)) for p in points.tolist()]).reshape(-1, 2)
    for k in range(2):  # u from the seam: about 0 at the first column, increasing round to 2 pi at its copy
        block = slice(k * (count + 1), (k + 1) * (count + 1))
        u = np.unwrap(uv[block, 0])
        u -= 2.0 * math.pi * round(u[0] / (2.0 * math.pi))
        u[-1] = u[0] + 2.0 * math.pi
        uv[block, 0] = u
    a = np.arange(count)
    o, i = a, a + count + 1  # outer and inner nodes (0-based) of each column
    triangles = np.concatenate([np.stack([o, o + 1, i + 1], -1), np.stack([o, i + 1, i], -1)]) + 1
    p, q, r = uv[triangles[0] - 1]
    if (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]) < 0:  # counter-clockwise in the cone's UV
        triangles = triangles[:, ::-1]
    tri = _triangulation(points, uv, triangles, tolerance)
    builder.UpdateFace(face, tri)
    ring = 0 if end == 0 else len(build.layout.s_rings) - 1
    for k, patches in enumerate(build.patches):
        for j, edge in enumerate(patches.rings[ring]):
            _polygon(builder, edge, [np.arange(first_column[j], first_column[j + 1] + 1) + 1 + k * (count + 1)], tri)
    # the seam, from the ring of the lower v to the other: its forward use at u = 2 pi, the reversed at u = 0
    lower, upper = (0, count + 1) if uv[0, 1] < uv[count + 1, 1] else (count + 1, 0)
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        edge = as_edge(explorer.Current())
        if BRep_Tool.IsClosed_s(edge, face):
            _polygon(builder, edge, [np.array([lower + count, upper + count]) + 1, np.array([lower, upper]) + 1], tri)
            break
        explorer.Next()
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


def _polygon(builder: BRep_Builder, edge: TopoDS_Edge, node_lists: list[np.ndarray], tri: Poly_Triangulation) -> None:
    """The edge's nodes on ``tri`` (two lists for a seam edge), in the edge's direction."""
    polygons = []
    for nodes in node_lists:
        polygon = Poly_PolygonOnTriangulation(len(nodes), False)
        for i, node in enumerate(nodes.tolist(), 1):
            polygon.SetNode(i, node)
        polygons.append(polygon)
    if len(polygons) == 2:  # a seam edge: its forward use, then its reversed one
        builder.UpdateEdge(edge, polygons[0], polygons[1], tri, TopLoc_Location())
    else:
        (polygon,) = polygons
        builder.UpdateEdge(edge, polygon, tri, TopLoc_Location())


def mesh_deviation(
    axis: Axis,
    radii: Sequence[float] | np.ndarray,
    vertices: np.ndarray,
    triangles: np.ndarray,
    level: Callable[..., tuple[np.ndarray, np.ndarray]] | None = None,
    scale: float | None = None,
) -> tuple[float, float]:
    """(max vertex deviation, max triangle deviation) of a mesh of tubes of ``radii`` about
    ``axis``: how far its vertices, and its triangles, lie from the exact tube each triangle
    belongs to. A triangle is sampled at its edge midpoints, where a chord of a surface whose
    second fundamental form is diagonal on the grid leaves it farthest (its centroid lies
    8/9 as far). End caps (every vertex at the same end of the span) are not measured.
    ``level`` and ``scale``: a canal surface's measure (tubecad.brep.measure.surface_levels,
    ``radii`` then its levels) and its smallest radius."""
    from tubecad.surface.checks import distance_to_axis

    if level is None:
        level = lambda p, g=None, iters=12: distance_to_axis(axis, p, g, iters)  # noqa: E731
    radii = np.asarray(radii, dtype=float)
    dist, s = level(vertices)
    ends = np.array(axis.span)
    at_end = np.abs(s[:, None] - ends[None, :]) <= 1e-3 * (radii.min() if scale is None else scale)  # (n, 2)
    cap = (at_end[triangles].all(axis=1)).any(axis=1)
    tube = triangles[~cap]
    if not len(tube):
        return 0.0, 0.0
    # the tube triangles' vertices (a canal wall's conical caps have nodes between the tubes)
    vertex = float(np.min(np.abs(dist[np.unique(tube)][:, None] - radii[None, :]), axis=1).max())
    which = np.argmin(np.abs(dist[tube].mean(axis=1)[:, None] - radii[None, :]), axis=1)
    a, b = tube.reshape(-1), np.roll(tube, -1, axis=1).reshape(-1)  # the three edges (a_k, b_k) of each triangle
    # an edge shared by two triangles of one tube once: a closed mesh's midpoints halved
    key = (np.minimum(a, b) * len(vertices) + np.maximum(a, b)) * len(radii) + np.repeat(which, 3)
    _, first = np.unique(key, return_index=True)
    a, b, radius = a[first], b[first], radii[np.repeat(which, 3)[first]]
    midpoints = 0.5 * (vertices[a] + vertices[b])
    step = s[b] - s[a]
    if axis.closed:  # an edge across the closing ring: its ends are near s0 and s1, its middle at either
        step = np.where(np.abs(step) > 0.5 * axis.length, step - np.sign(step) * axis.length, step)
    guess = s[a] + 0.5 * step
    if axis.closed:
        guess = axis.span[0] + np.mod(guess - axis.span[0], axis.length)
    guess = np.clip(guess, *axis.span)
    d, _ = level(midpoints, guess, 4)  # from a close guess
    return vertex, float(np.abs(d - radius).max())
