"""The faces' cells: point sets whose convex hulls hold a face, for proving face pairs apart
(tubecad.brep.analyzer, issue 24).

- A B-spline (or Bezier) face lies on its surface over the parameter box of its pcurves (the box
  of a B-spline pcurve's poles, a line's end points, a circle's square: each contains the curve).
- The surface, its inner knots raised to the degree (exact), is a grid of Bezier patches, each in
  the convex hull of its poles (a rational one too: its weights are checked positive); halving a
  patch by de Casteljau's construction (exact, on the homogeneous poles) makes the hulls as tight
  as needed; a plane face lies in the rectangle of its parameter box; other surfaces prove nothing.
- Two hulls are apart by at least the gap between their projections on any direction (a
  separating axis, computed on the poles themselves: 13-sided boxes, the patches' normals, the
  line of their centres).

Each cell keeps its Bezier patch (homogeneous poles), parameter box and corner poles, which the
contact proofs of touching faces take (tubecad.brep.contact).
"""

from __future__ import annotations

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.Geom import Geom_BSplineSurface, Geom_Plane, Geom_RectangularTrimmedSurface
from OCP.TopAbs import TopAbs_EDGE, TopAbs_VERTEX
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS_Edge, TopoDS_Shape

from tubecad.fitting.nurbs import SurfaceArrays
from tubecad.occ_compat import as_edge, as_face, as_vertex, copy_of, downcast


def sub_shapes(shape: TopoDS_Shape, kind) -> list[TopoDS_Shape]:
    """The sub-shapes of ``kind`` (TopAbs_FACE, ...) of ``shape``, in TopExp_Explorer's order
    (a shared one once per use)."""
    explorer, out = TopExp_Explorer(shape, kind), []
    while explorer.More():
        out.append(explorer.Current())
        explorer.Next()
    return out


def _spans(knots: np.ndarray, degree: int, count: int, low: float, high: float) -> np.ndarray:
    """The knot spans (index k: [knots[k], knots[k+1]]) of nonzero length meeting [low, high]."""
    k = np.arange(degree, count)
    slack = 1e-12 * max(1.0, abs(knots[-1] - knots[0]))
    keep = (knots[k + 1] > knots[k]) & (knots[k + 1] > low - slack) & (knots[k] < high + slack)
    return k[keep]


#: the directions of the cells' 13-sided boxes (k-DOPs): the axes, the face and body diagonals
_DIRECTIONS = np.array(
    [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1], [0, 1, 1], [0, 1, -1]]
    + [[1, 1, 1], [1, 1, -1], [1, -1, 1], [-1, 1, 1]],
    dtype=float,
)
_DIRECTIONS /= np.linalg.norm(_DIRECTIONS, axis=1, keepdims=True)


class Cells:
    """Point sets whose convex hulls hold a face, a grid of Bezier patches (u major): their poles,
    boxes, centres, normals, the spans' middles (to find a refined cell's parent)."""

    def __init__(self, points: np.ndarray, u_mid: np.ndarray, v_mid: np.ndarray, u_low: np.ndarray, v_low: np.ndarray):
        self.points = points  # (cells, points, 3)
        self.low, self.high = points.min(axis=1), points.max(axis=1)
        on = points @ _DIRECTIONS.T  # (cells, points, 13)
        self.dop_low, self.dop_high = on.min(axis=1), on.max(axis=1)
        self.centre = points.mean(axis=1)
        self.normal = np.zeros_like(self.centre)
        self.u_mid, self.v_mid, self.u_low, self.v_low = u_mid, v_mid, u_low, v_low
        self.extent_u = self.extent_v = 0.0
        # each cell's Bezier patch (homogeneous grid) and parameter box: for the contact proofs
        self.grids: np.ndarray | None = None
        self.boxes = np.zeros((len(points), 4))  # u low, u high, v low, v high
        self.corners = np.full((len(points), 4, 3), np.nan)  # the patches' corner poles (none: NaN)

    def parents(self, coarser: Cells) -> np.ndarray:
        """Each cell's parent among the cells of ``coarser`` (the span holding its middle)."""
        pu = np.clip(np.searchsorted(coarser.u_low, self.u_mid, side="right") - 1, 0, len(coarser.u_low) - 1)
        pv = np.clip(np.searchsorted(coarser.v_low, self.v_mid, side="right") - 1, 0, len(coarser.v_low) - 1)
        return (pu[:, None] * len(coarser.v_low) + pv[None, :]).ravel()


class FaceCells:
    """A face's cells at each refinement level (none: the face's extent cannot be bounded)."""

    def __init__(self, face) -> None:
        self.levels: list[Cells] = []
        self.children: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self.spline: tuple | None = None  # (Bezier patches, their u and v ranges)
        # each edge with points whose hull holds its pcurve, and the box of them all (None: some
        # pcurve cannot be bounded)
        self.pcurves = _pcurve_hulls(as_face(face))
        self.box = _box(self.pcurves)
        self.radius = BRep_Tool.Tolerance_s(face)
        for edge in sub_shapes(face, TopAbs_EDGE):
            self.radius = max(self.radius, BRep_Tool.Tolerance_s(as_edge(edge)))
        for vertex in sub_shapes(face, TopAbs_VERTEX):
            self.radius = max(self.radius, BRep_Tool.Tolerance_s(as_vertex(vertex)))
        # a vertex lies within its tolerance of its edges' ends, which lie within theirs of the surface
        self.radius *= 3.0
        cells = _first_cells(self, as_face(face))
        if cells is not None:
            self.levels.append(cells)

    @property
    def bounded(self) -> bool:
        return bool(self.levels)

    def cells(self, level: int) -> Cells:
        """The cells after ``level`` rounds of halving (the last ones when no more can come)."""
        while len(self.levels) <= level:
            if self.spline is None:
                return self.levels[-1]
            finer = _refine(self)
            order = np.argsort(finer.parents(self.levels[-1]), kind="stable")
            count = np.bincount(finer.parents(self.levels[-1]), minlength=len(self.levels[-1].points))
            self.children.append((order, np.cumsum(count) - count, count))
            self.levels.append(finer)
        return self.levels[level]

    def kids(self, level: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(children sorted by parent, each parent's first position in it, its count) from
        ``level`` to ``level + 1``."""
        self.cells(level + 1)
        if len(self.children) <= level:  # a plane: each cell its own child
            n = len(self.levels[-1].points)
            return np.arange(n), np.arange(n), np.ones(n, dtype=int)
        return self.children[level]


def _pcurve_hulls(face) -> list[tuple[TopoDS_Edge, list[tuple[float, float]]]] | None:
    """Each edge of the face with points whose convex hull holds its pcurve (None: some pcurve
    cannot be bounded, or the face has no edge)."""
    out = []
    for shape in sub_shapes(face, TopAbs_EDGE):
        edge = as_edge(shape)
        curve = BRep_Tool.CurveOnSurface_s(edge, face, 0.0, 0.0)
        found = None if curve is None else _pcurve_points(curve, *BRep_Tool.Range_s(edge, face))
        if not found:
            return None
        out.append((edge, found))
    return out or None


def _box(
    pcurves: list[tuple[TopoDS_Edge, list[tuple[float, float]]]] | None,
) -> tuple[float, float, float, float] | None:
    """The box of the pcurves' hull points: it holds the face's parameters."""
    if pcurves is None:
        return None
    us = [p[0] for _, points in pcurves for p in points]
    vs = [p[1] for _, points in pcurves for p in points]
    return min(us), max(us), min(vs), max(vs)


def _pcurve_points(curve, first: float, last: float) -> list[tuple[float, float]] | None:
    """Points whose convex hull holds the 2D curve over [first, last]."""
    name = curve.DynamicType().Name()
    if name == "Geom2d_TrimmedCurve":
        return _pcurve_points(curve.BasisCurve(), first, last)
    if name == "Geom2d_Line":
        return [curve.Value(first).Coord(), curve.Value(last).Coord()]
    if name in ("Geom2d_Circle", "Geom2d_Ellipse"):
        x, y = curve.Location().Coord()
        r = curve.Radius() if name == "Geom2d_Circle" else curve.MajorRadius()
        return [(x - r, y - r), (x + r, y + r)]
    if name == "Geom2d_BezierCurve":
        if curve.IsRational() and min(curve.Weight(i) for i in range(1, curve.NbPoles() + 1)) <= 0:
            return None
        return [curve.Pole(i).Coord() for i in range(1, curve.NbPoles() + 1)]
    if name == "Geom2d_BSplineCurve" and not curve.IsPeriodic():
        n, p = curve.NbPoles(), curve.Degree()
        if curve.IsRational() and min(curve.Weight(i) for i in range(1, n + 1)) <= 0:
            return None
        knots = np.repeat(
            [curve.Knot(i) for i in range(1, curve.NbKnots() + 1)],
            [curve.Multiplicity(i) for i in range(1, curve.NbKnots() + 1)],
        )
        spans = _spans(knots, p, n, min(first, last), max(first, last))
        if not len(spans):
            return None
        return [curve.Pole(i + 1).Coord() for i in range(int(spans[0]) - p, int(spans[-1]) + 1)]
    return None


def _first_cells(owner: FaceCells, face) -> Cells | None:
    surface = BRep_Tool.Surface_s(face)
    name = surface.DynamicType().Name()
    if name == "Geom_RectangularTrimmedSurface":
        surface = downcast(surface, Geom_RectangularTrimmedSurface).BasisSurface()
        name = surface.DynamicType().Name()
    box = owner.box
    if name == "Geom_Plane":
        if box is None:
            return None
        u1, u2, v1, v2 = box
        plane = downcast(surface, Geom_Plane)
        corners = [plane.Value(u, v).Coord() for u in (u1, u2) for v in (v1, v2)]
        zero = np.zeros(1)
        cells = Cells(np.array([corners], dtype=float), zero, zero, zero, zero)
        cells.normal = np.array([plane.Axis().Direction().Coord()], dtype=float)
        cells.corners = cells.points.copy()  # (u1, v1), (u1, v2), (u2, v1), (u2, v2)
        return cells
    if name not in ("Geom_BSplineSurface", "Geom_BezierSurface"):
        return None
    from OCP.GeomConvert import GeomConvert

    # a copy, as Bezier patches: every inner knot raised to the degree (OCCT does this exactly)
    spline = (
        GeomConvert.SurfaceToBSplineSurface_s(surface)
        if name == "Geom_BezierSurface"
        else copy_of(downcast(surface, Geom_BSplineSurface))
    )
    if spline.IsUPeriodic():
        spline.SetUNotPeriodic()
    if spline.IsVPeriodic():
        spline.SetVNotPeriodic()
    p, q = spline.UDegree(), spline.VDegree()
    if spline.NbUKnots() > 2:
        spline.IncreaseUMultiplicity(2, spline.NbUKnots() - 1, p)
    if spline.NbVKnots() > 2:
        spline.IncreaseVMultiplicity(2, spline.NbVKnots() - 1, q)
    arrays = SurfaceArrays.from_occ(spline)  # poles, weights, flat knots (it is not periodic now)
    nu, nv = arrays.weights.shape
    if arrays.weights.min() <= 0:
        return None
    ctrl = np.concatenate([arrays.poles * arrays.weights[..., None], arrays.weights[..., None]], axis=-1)
    uk, vk = np.unique(arrays.u_knots), np.unique(arrays.v_knots)
    if (nu - 1) != p * (len(uk) - 1) or (nv - 1) != q * (len(vk) - 1):
        return None  # not in Bezier form (an unexpected knot structure): nothing proven
    u0, u1, v0, v1 = spline.Bounds()
    if box is not None:  # the face's parameters, within the surface's
        u0, u1, v0, v1 = max(u0, box[0]), min(u1, box[1]), max(v0, box[2]), min(v1, box[3])
    su = np.nonzero((uk[1:] >= u0) & (uk[:-1] <= u1))[0]
    sv = np.nonzero((vk[1:] >= v0) & (vk[:-1] <= v1))[0]
    if not len(su) or not len(sv):
        return None
    patches = np.stack(
        [np.stack([ctrl[a * p : a * p + p + 1, b * q : b * q + q + 1] for b in sv]) for a in su]
    )  # (patches in u, in v, p+1, q+1, 4)
    owner.spline = (patches, uk[su], uk[su + 1], vk[sv], vk[sv + 1])
    return _patch_cells(owner.spline)


def _patch_cells(spline: tuple) -> Cells:
    patches, u_low, u_high, v_low, v_high = spline
    nu, nv, p1, q1, _ = patches.shape
    points = patches[..., :3] / patches[..., 3:]
    cells = Cells(points.reshape(nu * nv, p1 * q1, 3), (u_low + u_high) / 2, (v_low + v_high) / 2, u_low, v_low)
    cells.grids = patches.reshape(nu * nv, p1, q1, 4)
    # the corner poles (0, 0), (0, q), (p, 0), (p, q)
    cells.corners = points[:, :, [0, 0, -1, -1], [0, -1, 0, -1]].reshape(nu * nv, 4, 3)
    cells.boxes = np.stack(
        [np.repeat(u_low, nv), np.repeat(u_high, nv), np.tile(v_low, nu), np.tile(v_high, nu)], axis=1
    )
    du = (points[:, :, -1, :, :] - points[:, :, 0, :, :]).mean(axis=2)
    dv = (points[:, :, :, -1, :] - points[:, :, :, 0, :]).mean(axis=2)
    normal = np.cross(du, dv).reshape(-1, 3)
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    cells.normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    cells.extent_u = float(np.linalg.norm(du, axis=-1).mean())
    cells.extent_v = float(np.linalg.norm(dv, axis=-1).mean())
    return cells


def _halve(patches: np.ndarray, axis: int) -> np.ndarray:
    """Each Bezier patch cut at its middle along ``axis`` (0: u, 1: v) by de Casteljau's
    construction on the homogeneous poles: two patches holding the same surface."""
    moved = np.moveaxis(patches, axis + 2, -2)  # (..., degree+1, 4)
    left, right, row = [moved[..., 0, :]], [moved[..., -1, :]], moved
    for _ in range(moved.shape[-2] - 1):
        row = 0.5 * (row[..., :-1, :] + row[..., 1:, :])
        left.append(row[..., 0, :])
        right.append(row[..., -1, :])
    halves = [np.moveaxis(np.stack(side, axis=-2), -2, axis + 2) for side in (left, right[::-1])]
    both = np.stack(halves, axis=axis + 1)  # (.., 2, ..) next to the patch axis
    shape = list(patches.shape)
    shape[axis] *= 2
    return both.reshape(shape)


def _refine(owner: FaceCells) -> Cells:
    """Every patch halved in the face's longer direction(s)."""
    assert owner.spline is not None
    patches, u_low, u_high, v_low, v_high = owner.spline
    last = owner.levels[-1]
    longest = max(last.extent_u, last.extent_v)
    if 2 * last.extent_u >= longest:
        patches, middle = _halve(patches, 0), (u_low + u_high) / 2
        u_low, u_high = np.stack([u_low, middle], axis=1).ravel(), np.stack([middle, u_high], axis=1).ravel()
    if 2 * last.extent_v >= longest:
        patches, middle = _halve(patches, 1), (v_low + v_high) / 2
        v_low, v_high = np.stack([v_low, middle], axis=1).ravel(), np.stack([middle, v_high], axis=1).ravel()
    owner.spline = (patches, u_low, u_high, v_low, v_high)
    return _patch_cells(owner.spline)


class CellStack:
    """The cells of several faces at one level, end to end (each cell's points padded to the
    longest by repeating its last: the same hull)."""

    def __init__(self, owners: list[FaceCells], faces: list[int], level: int) -> None:
        parts = [owners[f].cells(level) for f in faces]
        sizes = [len(c.points) for c in parts]
        self.offset = dict(zip(faces, np.cumsum([0, *sizes[:-1]]).tolist()))
        self.face = np.repeat(np.array(faces, dtype=int), sizes)
        width = max(c.points.shape[1] for c in parts)
        self.points = np.concatenate(
            [np.pad(c.points, ((0, 0), (0, width - c.points.shape[1]), (0, 0)), mode="edge") for c in parts]
        )
        self.dop_low = np.concatenate([c.dop_low for c in parts])
        self.dop_high = np.concatenate([c.dop_high for c in parts])
        self.centre = np.concatenate([c.centre for c in parts])
        self.normal = np.concatenate([c.normal for c in parts])
        self.corners = np.concatenate([c.corners for c in parts])


def unresolved(a: CellStack, ia: np.ndarray, ib: np.ndarray, need: np.ndarray) -> np.ndarray:
    """Which cell pairs (ia[k], ib[k]) are not proven farther apart than need[k]: neither their
    13-sided boxes nor their projections on their normals and on the line of their centres are."""
    gap = np.maximum(a.dop_low[ib] - a.dop_high[ia], a.dop_low[ia] - a.dop_high[ib]).max(axis=1)
    left = np.nonzero(gap <= need)[0]
    if not len(left):
        return left
    ja, jb = ia[left], ib[left]
    line = a.centre[jb] - a.centre[ja]
    length = np.linalg.norm(line, axis=1, keepdims=True)
    line = np.divide(line, length, out=np.zeros_like(line), where=length > 0)
    axes = np.stack([a.normal[ja], a.normal[jb], line], axis=2)  # (pairs, 3, 3); a zero axis proves nothing
    on_a, on_b = a.points[ja] @ axes, a.points[jb] @ axes  # (pairs, points, 3)
    separation = np.maximum(on_b.min(axis=1) - on_a.max(axis=1), on_a.min(axis=1) - on_b.max(axis=1)).max(axis=1)
    return left[separation <= need[left]]
