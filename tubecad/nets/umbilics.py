"""Umbilics of a host surface: found on the exact surface, typed, or reported as a region
(issue 44; docs/MATH.md section 15).

At an umbilic the trace-free part w = a + i b of the shape operator (in the tangent frame e1 =
X_u / |X_u|, e2 = n x e1: :mod:`~tubecad.nets.principal`) vanishes, and the k1 direction, at
the angle arg(w) / 2 from e1, turns by 2 pi times the umbilic's index as one goes round it:
+-1/2 for a generic umbilic, so w winds once (+-1) round a small loop. The search:

1. w on a grid over the face's parameter box, wrapped across a periodic seam (the last column
   is the first again), so an umbilic on the seam (two of an ellipsoid's four, on a NURBS sphere's
   image) lies inside a cell like any other;
2. every cell round which w winds (its angle's increments between the corners summed) holds
   one: Newton's method (MINPACK's hybrid, :func:`scipy.optimize.root`) on (a, b) = 0 from its
   centre, the result wrapped into the box; cells at a degenerate row of the parameterisation
   (a sphere's pole, |X_u x X_v| = 0, where the frame itself winds) are skipped;
3. the type from a small loop round it (radius RING_SHARE of the box, in a fixed frame of the
   tangent plane there): the index, the k1 direction's turn over 2 pi, and the separatrices,
   the rays from the umbilic along which the k1 or k2 direction is radial (the zeros of
   sin 2(psi - phi), psi the direction's angle and phi the ray's, half of them per family):
   index -1/2 a *star* (3 separatrices), +1/2 a *lemon* (1) or a *monstar* (3) (Darboux's
   D1, D2, D3; Berry & Hannay, J. Phys. A 10 (1977) 1809).

A face whose umbilic measure (k1 - k2) / 2 vanishes (to REGION of its largest curvature) at
every grid point is an umbilic region (a plane, a sphere): reported as such, not as points. A
part of a face where it vanishes (to PART) over whole grid cells (a hull's flat bottom) is an
umbilic part (:class:`UmbilicPart`): reported as a region (its type, centre, bounding box and
area to a grid cell), its cells left out of the search; lines of curvature stop on its border
(:func:`~tubecad.nets.trace.trace_line`'s ``flat``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.optimize import root

from tubecad.nets.host import HostSurface
from tubecad.nets.principal import principal_field

FloatArray = np.ndarray
UmbilicType = Literal["lemon", "monstar", "star"]
PartType = Literal["flat", "spherical"]

#: grid cells along each parameter of the search
GRID = 96
#: the typing loop's radius, as a share of the parameter box's smaller side
RING_SHARE = 1e-4
#: points on the typing loop
RING_POINTS = 720
#: a face is an umbilic region where (k1 - k2) / 2 is below this times its largest |k| everywhere
REGION = 1e-9
#: a part of the face is umbilic (a flat bottom, a spherical cap) where (k1 - k2) / 2 is below
#: this times the face's largest |k| over a whole cell of the search grid or more
PART = 1e-6
#: Newton's root is an umbilic where (a, b) / max |k| is below this
CONVERGED = 1e-12
#: the search grid's shift off the box's symmetric places, in cells
GOLDEN = 0.5 * (math.sqrt(5.0) - 1.0)
#: two umbilics found closer than this share of the face's size are one
SAME = 1e-7


@dataclass(frozen=True)
class Umbilic:
    """An umbilic at parameters (``u``, ``v``) and ``point`` (3,), its ``index`` (+-1/2),
    ``separatrices`` (per family) and ``type``; ``residual``: its umbilic measure
    (k1 - k2) / 2 there, over the face's largest |k| (round-off)."""

    u: float
    v: float
    point: FloatArray
    index: float
    separatrices: int
    type: UmbilicType
    residual: float


@dataclass(frozen=True)
class UmbilicPart:
    """A part of a face where (k1 - k2) / 2 vanishes (to PART of the face's largest |k|): a
    region, not points. ``type``: ``"flat"`` where the curvatures vanish too (a hull's flat
    side), ``"spherical"`` where they do not (a spherical cap)."""

    type: PartType
    #: the search grid's nodes inside it, (n, 3)
    points: FloatArray
    #: their parameters, (n, 2)
    uv: FloatArray
    #: its area: the search grid's cells with all four corners in it (so to about a cell)
    area: float

    @property
    def centre(self) -> FloatArray:
        """The mean of its grid nodes (3,)."""
        return self.points.mean(axis=0)

    def report(self) -> dict[str, object]:
        """``type``, ``centre``, ``box`` (its nodes' [[min x, y, z], [max x, y, z]]), ``area``."""
        return {
            "type": self.type,
            "centre": [float(c) for c in self.centre],
            "box": [[float(c) for c in self.points.min(axis=0)], [float(c) for c in self.points.max(axis=0)]],
            "area": self.area,
        }


@dataclass(frozen=True)
class Umbilics:
    """A face's umbilics: the isolated ``points`` (:class:`Umbilic`), or ``region`` True where
    the whole face is umbilic (a plane or a sphere: every direction is principal)."""

    points: list[Umbilic]
    region: bool
    #: parts of the face that are umbilic (a flat bottom, a spherical cap) where the rest is
    #: not (:class:`UmbilicPart`); the search finds no isolated umbilic there
    parts: tuple[UmbilicPart, ...] = ()
    #: the umbilic measure (k1 - k2) / 2 (1 / length) at or below which a point lies in a part
    #: (PART times the face's largest |k|); 0 without parts
    part_level: float = 0.0

    @property
    def index_sum(self) -> float:
        """The sum of the isolated umbilics' indices (2 on a closed surface of genus 0:
        Poincare-Hopf, the Euler characteristic)."""
        return float(sum(p.index for p in self.points))


def find_umbilics(host: HostSurface, grid: int = GRID) -> Umbilics:
    """The umbilics of ``host`` (module docstring).

    Args:
        host: the surface.
        grid: cells along each parameter of the search.

    Returns:
        The umbilics found and typed, or an umbilic region.
    """
    u0, u1, v0, v1 = host.bounds
    us, vs = (_nodes(lo, hi, closed, grid) for lo, hi, closed in ((u0, u1, host.closed[0]), (v0, v1, host.closed[1])))
    uu, vv = np.meshgrid(us, vs, indexing="ij")
    uu, vv = host.wrapped(uu, vv)
    field = principal_field(host, uu, vv)
    w = (field.a + 1j * field.b).reshape(uu.shape)
    k_max = float(np.nanmax(np.maximum(np.abs(field.k1), np.abs(field.k2))))
    measure = field.umbilic_measure
    if np.all(measure[np.isfinite(measure)] <= REGION * max(k_max, 1e-300)):
        return Umbilics([], True)
    degenerate = ~(field.area.reshape(uu.shape) > 1e-12 * np.nanmax(field.area))
    regular = np.abs(np.stack([field.k1, field.k2])).max(axis=0).reshape(uu.shape)[~degenerate]
    k_regular = float(np.nanmax(regular)) if regular.size else k_max  # not a pole row's
    flat = ~(measure.reshape(uu.shape) > PART * k_regular)  # (k1 - k2) / 2 this small: umbilic (or undefined)
    curvature = np.abs(np.stack([field.k1, field.k2])).max(axis=0).reshape(uu.shape)
    cell_area = np.outer(np.diff(us), np.diff(vs)) * _corners_mean(field.area.reshape(uu.shape))
    parts = _parts(flat & ~degenerate, host, uu, vv, curvature <= PART * k_regular, cell_area)
    degenerate |= flat
    with np.errstate(divide="ignore", invalid="ignore"):  # w = 0 in an umbilic part: its cells are skipped
        turn = np.angle(w[1:, :-1] / w[:-1, :-1]) + np.angle(w[1:, 1:] / w[1:, :-1])
        turn += np.angle(w[:-1, 1:] / w[1:, 1:]) + np.angle(w[:-1, :-1] / w[:-1, 1:])
        winding = np.rint(np.nan_to_num(turn) / (2 * math.pi))
    bad = degenerate[1:, :-1] | degenerate[:-1, :-1] | degenerate[1:, 1:] | degenerate[:-1, 1:]
    cells = np.argwhere((winding != 0) & ~bad)
    found: list[Umbilic] = []
    size = min(u1 - u0, v1 - v0)
    points = host.points(uu[::8, ::8], vv[::8, ::8])
    scale = float(np.ptp(points, axis=0).max())
    for i, j in cells:
        start = np.array([0.5 * (us[i] + us[i + 1]), 0.5 * (vs[j] + vs[j + 1])])
        start = np.concatenate(host.wrapped(start[:1], start[1:]))
        umbilic = _solved(host, start, k_max, size)
        if umbilic is None:
            continue
        if all(np.linalg.norm(umbilic.point - p.point) > SAME * scale for p in found):
            found.append(umbilic)
    return Umbilics(found, False, parts, PART * k_regular if parts else 0.0)


def _parts(
    flat: np.ndarray, host: HostSurface, uu: FloatArray, vv: FloatArray, plane: np.ndarray, cell_area: FloatArray
) -> tuple[UmbilicPart, ...]:
    """The umbilic parts of the face: the connected sets of search-grid nodes where
    (k1 - k2) / 2 <= PART max|k| (scipy's ``ndimage.label``, 4-connected) that hold a whole
    grid cell (its four corners: an area, not a line of flat points such as an inflection
    line along the boundary). An isolated umbilic, where the measure grows linearly from 0,
    puts no such cell on the grid. ``plane``: the nodes where the curvatures vanish too (a
    part all of them is flat); ``cell_area``: the grid cells' areas."""
    from scipy.ndimage import label

    labels, count = label(flat)
    cells = flat[:-1, :-1] & flat[1:, :-1] & flat[:-1, 1:] & flat[1:, 1:]
    out = []
    for k in sorted(set(labels[:-1, :-1][cells].tolist())):
        inside = labels == k
        kind: PartType = "flat" if bool(plane[inside].all()) else "spherical"
        mine = cells & inside[:-1, :-1]
        uv = np.stack([uu[inside], vv[inside]], axis=1)
        out.append(UmbilicPart(kind, host.jet(uu[inside], vv[inside]).X, uv, float(cell_area[mine].sum())))
    return tuple(out)


def _corners_mean(values: FloatArray) -> FloatArray:
    """The mean of a grid's values at each cell's four corners (one less each way)."""
    return 0.25 * (values[:-1, :-1] + values[1:, :-1] + values[:-1, 1:] + values[1:, 1:])


def _nodes(lo: float, hi: float, closed: bool, cells: int) -> FloatArray:
    """The search grid's nodes along one parameter: shifted off the box's symmetric places by
    the golden section of a cell (an umbilic on a grid line, u = pi on an ellipsoid, would sit
    on a cell's side), round the whole period where the direction is closed (the last node a
    period after the first, wrapped when evaluated), with the box's ends where it is not."""
    h = (hi - lo) / cells
    inner = lo + (np.arange(cells) + GOLDEN) * h
    if closed:
        return np.concatenate([inner, inner[:1] + (hi - lo)])
    return np.concatenate([[lo], inner, [hi]])


def _solved(host: HostSurface, start: FloatArray, k_max: float, size: float) -> Umbilic | None:
    """Newton from ``start`` on (a, b) = 0, typed; None where it does not converge in the box."""

    def residual(x: FloatArray) -> FloatArray:
        u, v = host.wrapped(x[:1], x[1:])
        f = principal_field(host, u, v)
        return np.array([f.a[0], f.b[0]]) / k_max

    solution = root(residual, start, method="hybr", options={"xtol": 1e-14})
    u, v = host.wrapped(solution.x[:1], solution.x[1:])
    # MINPACK may call a root at round-off "not making good progress": the residual decides
    left = float(np.abs(residual(np.array([u[0], v[0]]))).max())
    if not (host.inside(u, v)[0] and left <= CONVERGED):
        return None
    index, separatrices = _type(host, float(u[0]), float(v[0]), RING_SHARE * size)
    kind: UmbilicType = "star" if index < 0 else ("lemon" if separatrices == 1 else "monstar")
    point = host.jet(u, v).X[0]
    return Umbilic(float(u[0]), float(v[0]), point, index, separatrices, kind, left)


def _type(host: HostSurface, u: float, v: float, radius: float) -> tuple[float, int]:
    """(index, separatrices per family) from the loop of ``radius`` round (u, v) (module
    docstring): the k1 direction's angle psi and the ray's phi in a fixed tangent frame."""
    theta = np.linspace(0.0, 2 * math.pi, RING_POINTS + 1)
    centre = principal_field(host, np.array([u]), np.array([v]))
    t1, n = centre.e1[0], centre.n[0]
    t2 = np.cross(n, t1)
    lu, lv = host.wrapped(u + radius * np.cos(theta), v + radius * np.sin(theta))
    loop = principal_field(host, lu, lv)
    origin = host.jet(np.array([u]), np.array([v])).X[0]
    ray = host.jet(lu, lv).X - origin
    phi = np.arctan2(ray @ t2, ray @ t1)
    psi = np.arctan2(loop.d1 @ t2, loop.d1 @ t1)
    doubled = np.unwrap(2 * psi)
    index = float(np.rint((doubled[-1] - doubled[0]) / (2 * math.pi))) / 2
    g = np.sin(2 * (psi - phi))[:-1]
    changes = int(np.count_nonzero(np.signbit(g) != np.signbit(np.roll(g, -1))))
    return index, changes // 2
