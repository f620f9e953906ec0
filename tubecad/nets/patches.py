"""A cell of a curvature-line net refitted as a B-spline surface in curvature-line coordinates
(issue 44, item 3; docs/MATH.md section 15).

A four-sided cell of a net (:func:`~tubecad.nets.net.curvature_net`) lies between two lines of
family 1, ``k1 = (i, i')``, and two of family 2, ``k2 = (j, j')``. Its patch is the surface
X(u, v) whose u-isolines (u constant) are lines of family 2 and whose v-isolines are lines of
family 1: X_u runs along the k1 direction, X_v along k2, so F = X_u . X_v = 0 and
M = X_uv . n = 0 (the curvature-line parameterisation: the shape operator diagonal; do Carmo,
*Differential Geometry of Curves and Surfaces*, section 3-3). It is built as follows.

1. **Corners.** The four lines' pcurves (the net's edges', quintic Hermite in the arc length)
   are intersected pairwise in the host's parameters: their polygons of traced nodes crossed
   segment by segment (shifted by whole periods round a closed seam), each crossing then
   refined by Newton's method on P(s) - Q(t) = 0 (2 x 2, the pcurves' derivatives the
   Jacobian's columns). C00 = k1[0] x k2[0] (the one nearest ``near`` where the lines cross
   more than once), C10 = k1[0] x k2[1], C01 = k2[0] x k1[1], C11 = k1[1] x k2[1], each the
   crossing nearest, along the line they share, the corner found before it.
2. **The grid.** ``n`` lines of family 2 (the cell's two and n - 2 between) seeded on the
   side k1[0] at equal shares of its arc length between C00 and C10, and ``m`` lines of
   family 1 seeded on the side k2[0] between C00 and C01, traced on the host
   (:func:`~tubecad.nets.trace.trace_line`, the net's tolerance, each way at most 1.5 times
   the cell's longest side) and made edges (:func:`~tubecad.nets.edges.line_edge`). Their
   m x n crossings (step 1's Newton, each the one nearest along its family-2 line the grid
   point before it) are the grid points G_ab on the host, at the surface parameters
   u_a = a / (n - 1) L_u, v_b = b / (m - 1) L_v, L_u and L_v the arc lengths of the sides
   k1[0] and k2[0]: both sides are parameterised by their arc length.
3. **The surface.** The tensor-product cubic interpolant of G (scipy's
   :func:`~scipy.interpolate.make_interp_spline`, not-a-knot ends, first along v for each
   column, then along u through the columns' poles; de Boor, *A Practical Guide to Splines*,
   chapter XVII): a bicubic ``Geom_BSplineSurface`` of n x m poles. Its isolines through the
   grid interpolate points of the traced lines; between them the surface interpolates the
   smooth family of lines, so its distance from the host and from the lines falls as h^4 and
   the angle of its isolines' tangents to the principal directions as h^3 (h the grid's step).
4. **The face.** Bounded by the net's own lines between the corners: four new edges on the
   net's edges' 3-D curves (the same ``Geom_BSplineCurve``, trimmed at the corners' arc
   lengths), each given a pcurve on the patch (its grid points' (u, v) interpolated against
   their arc length on the edge: on the sides k1[0] and k2[0] exactly the affine map of
   step 2) with the tolerance the edge's curve keeps from the patch (``edge_gap``, measured,
   at least OCCT's 1e-7 confusion); the face is oriented with the host's normal and checked
   valid (``BRepCheck_Analyzer``).

**Measured** (:class:`CurvaturePatch`) on a grid four times finer than the lines' (at the
grid's lines, and at 1/4, 1/2 and 3/4 of every step between them): the largest distance from
the host (each point projected with OCCT's ``GeomAPI_ProjectPointOnSurf``), the largest angle
between the isolines' tangents X_u, X_v and the host's principal directions d1, d2 at the
projected points, |F| / sqrt(E G) and |M| / (sqrt(E G) max(|k1|, |k2|)) on the patch (its own
forms and curvatures: the cosine of the isolines' angle and the shape operator's cross term
relative to the larger curvature), and the pole count.

Without ``samples`` the grid is chosen by the ``target`` distance and angle: 9, 17, 33 lines a
family (the coarser grids' lines traced once), the first whose measures meet it; the finer
grids are not tried where even the finest, at the interpolant's ideal rate (the angle falling
as h^degree, the distance as h^(degree + 1)), would leave it off the target (a cell across a
host's C2 knot line, where the curvature-line map is only C1 and the error falls as h).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeVertex,
    BRepBuilderAPI_MakeWire,
)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Vertex
from scipy.interpolate import BSpline, make_interp_spline

from tubecad.core.errors import ParameterError, TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.fitting.nurbs import occ_curve_2d
from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals
from tubecad.nets.edges import line_edge
from tubecad.nets.host import HostSurface
from tubecad.nets.net import UMBILIC_REACH, CurvatureNet
from tubecad.nets.principal import field_of, principal_field
from tubecad.nets.trace import Family, trace_line
from tubecad.occ_compat import as_edge, as_face

FloatArray = np.ndarray
#: the grids tried without ``samples`` (lines a family, the cell's own included): each the
#: last's lines and one between each two
GRIDS = (9, 17, 33)
#: the default target: distance from the host (share of the face's size) and angle (radians)
TARGET = (1e-6, 1e-6)
#: the traced lines run each way at most this many times the cell's longest side
REACH = 1.5
#: measuring points inside each step of the grid (besides its lines)
CHECKS = (0.25, 0.5, 0.75)
#: Newton on two pcurves' crossing stops when a step is below this (parameters)
NEWTON_STEP = 1e-14
#: two crossings of the same two lines closer than this share of the face's size are one
SAME = 1e-9


@dataclass(frozen=True)
class CurvaturePatch:
    """A cell of a net as a bicubic B-spline ``surface`` in curvature-line coordinates and its
    ``face`` bounded by the net's lines (module docstring), with its measures.

    The surface's u runs along family 1 (its v-isolines are k1 lines), v along family 2, over
    [0, L_u] x [0, L_v] (the sides k1[0] and k2[0]'s arc lengths)."""

    surface: Geom_BSplineSurface
    #: None where the patch was made without its face (``bounded=False``)
    face: TopoDS_Face | None
    #: (lines of family 1, lines of family 2) in the grid, the cell's own included
    samples: tuple[int, int]
    #: the grid points on the host (n, m, 3): [a, b] on the a-th family-2 line and b-th family-1
    grid: FloatArray
    #: the host's parameters of the grid points (n, m, 2), unwrapped across a periodic seam
    grid_uv: FloatArray
    #: the largest distance from the host (model units)
    distance: float
    #: the largest angle (radians) between an isoline's tangent and its principal direction
    angle: float
    #: the largest |F| / sqrt(E G) on the patch (the cosine of its isolines' angle)
    F: float
    #: the largest |M| / (sqrt(E G) max(|k1|, |k2|)) on the patch
    M: float
    #: the largest distance between the boundary edges' 3-D curves and the patch (along their
    #: pcurves): the edges' tolerance on the patch is the larger of twice it and 1e-7 (0 without
    #: the face)
    edge_gap: float
    #: the surface's poles (along u, along v)
    poles: tuple[int, int]
    #: the face's normal agrees with the host's (else the face is reversed on its surface)
    same_sense: bool
    #: seconds taken (tracing, crossings, fit, measure)
    seconds: float
    #: the face size the relative figures are measured against
    size: float
    #: the coarser grids tried first (without ``samples``): their report()s
    tried: tuple[dict[str, Any], ...] = ()

    def report(self) -> dict[str, Any]:
        """The patch's figures (plain floats and ints): ``samples``, ``poles``, ``distance``
        (and over the face's size), ``angle``, ``F``, ``M``, ``edge_gap``, ``seconds``."""
        return {
            "samples": list(self.samples),
            "poles": list(self.poles),
            "distance": self.distance,
            "distance_share": self.distance / self.size,
            "angle": self.angle,
            "F": self.F,
            "M": self.M,
            "edge_gap": self.edge_gap,
            "seconds": self.seconds,
        }


@dataclass(frozen=True)
class _Line:
    """A line of the grid: its traced nodes' parameters and arc lengths, its pcurve (scipy,
    in the arc length) and its 3-D curve (OCCT, the same parameter)."""

    uv: FloatArray
    sigma: FloatArray
    pcurve: BSpline
    curve: Geom_BSplineCurve
    #: a closed line's length (its arc length then counts round it), else None
    period: float | None = None

    def at(self, s: Any) -> FloatArray:
        """The pcurve at arc lengths ``s``, taken round a closed line."""
        if self.period is not None:
            s = self.sigma[0] + np.mod(np.asarray(s, dtype=float) - self.sigma[0], self.period)
        return self.pcurve(s)

    def apart(self, a: Any, b: Any) -> Any:
        """a - b along the line: the shorter way round a closed one."""
        d = np.asarray(a, dtype=float) - b
        return d if self.period is None else (d + 0.5 * self.period) % self.period - 0.5 * self.period


def curvature_patch(
    net: CurvatureNet,
    k1: tuple[str, str],
    k2: tuple[str, str],
    samples: tuple[int, int] | None = None,
    *,
    target: tuple[float, float] = TARGET,
    degree: int = 3,
    tolerance: float = 1e-10,
    near: tuple[float, float] | None = None,
    bounded: bool = True,
) -> CurvaturePatch:
    """The cell of ``net`` between the lines ``k1`` and ``k2`` as a patch in curvature-line
    coordinates (module docstring).

    Args:
        net: the net.
        k1: two lines of family 1 by name (``("k1_02", "k1_03")``): the sides v = 0 and v = L_v.
        k2: two lines of family 2: the sides u = 0 and u = L_u.
        samples: (lines of family 1, lines of family 2) in the grid, each 4 .. 200 (the cell's
            own included); None: chosen by ``target`` among GRIDS.
        target: (distance as a share of the face's size, angle in radians) the automatic
            grid must meet; the finest of GRIDS is returned where none does.
        degree: the surface's degree both ways (odd, 3 .. 7): 3, bicubic; 5 for a finer fit
            on a smooth host (its error falls as h^(degree + 1)).
        tolerance: the tracer's step error for the grid's lines (3-D length; the net's is
            1e-10 unless it was made otherwise).
        near: host parameters (u, v) near the corner k1[0] x k2[0], where those lines cross
            more than once (closed lines); default the crossing first along k1[0].
        bounded: make the face on the patch bounded by the cell's lines (step 4); False: the
            surface and its measures only (:mod:`~tubecad.nets.patch_shell` puts the net's
            own edges on it).

    Returns:
        The patch.

    Raises:
        ParameterError: (``k1``, ``k2``) names not lines of that family of the net;
            (``samples``) counts out of range; (``net``) lines that do not cross as a cell, or
            a grid line that ends inside the cell (an umbilic, the face's boundary).
    """
    for key, names, family in (("k1", k1, 1), ("k2", k2, 2)):
        if len(names) != 2 or names[0] == names[1] or any(net.lines.get(n) is None for n in names):
            raise ParameterError(f"{key} must name two lines of the net, got {names!r:.60}", key=key)
        if any(net.lines[n].family != family for n in names):
            raise ParameterError(f"{key} must name lines of family {family}, got {names!r:.60}", key=key)
    if degree not in (3, 5, 7):
        raise ParameterError(f"degree must be 3, 5 or 7, got {degree!r:.20}", key="degree")
    if samples is not None and not all(isinstance(s, int) and degree + 1 <= s <= 200 for s in samples):
        raise ParameterError(f"samples must be two integers in {degree + 1}..200, got {samples!r:.60}", key="samples")
    start = time.perf_counter()
    cell = _Cell(net, k1, k2, tolerance, near, degree)
    if samples is not None:
        return cell.patch(samples, start, bounded=bounded)
    tried: list[dict[str, Any]] = []
    patch = None
    for count in GRIDS:
        if count <= degree:
            continue
        patch = cell.patch((count, count), start, tuple(tried), bounded)
        if patch.distance <= target[0] * cell.size and patch.angle <= target[1]:
            break
        tried.append(patch.report())
        # each finer grid halves the step: at best the angle falls by 2^degree a grid (the
        # distance by 2^(degree + 1)); where even the finest left would miss the target, no
        # finer grid's lines are traced
        finer = (GRIDS[-1] - 1) / (count - 1)  # the finest grid's step is this many times smaller
        if patch.angle > target[1] * finer**degree or patch.distance > target[0] * cell.size * finer ** (degree + 1):
            break
    assert patch is not None
    return patch


def _line_of(line: Any, edge: Any) -> _Line:
    """A traced line (:class:`~tubecad.nets.trace.CurvatureLine`) and its edge as a grid line."""
    period = float(line.sigma[-1] - line.sigma[0]) if line.closed else None
    return _Line(line.uv, line.sigma, _spline_of(edge.pcurve), edge.curve, period)


def _spline_of(pcurve: Geom2d_BSplineCurve) -> BSpline:
    """An OCCT 2-D B-spline curve (non-rational) as scipy's."""
    poles = np.array([[pcurve.Pole(i).X(), pcurve.Pole(i).Y()] for i in range(1, pcurve.NbPoles() + 1)])
    knots = np.repeat(
        [pcurve.Knot(i) for i in range(1, pcurve.NbKnots() + 1)],
        [pcurve.Multiplicity(i) for i in range(1, pcurve.NbKnots() + 1)],
    )
    return BSpline(knots, poles, pcurve.Degree())


class _Cell:
    """The cell's host, its four lines and corners, and the grid's lines traced so far (by
    family and share of the side they are seeded on)."""

    def __init__(
        self,
        net: CurvatureNet,
        k1: tuple[str, str],
        k2: tuple[str, str],
        tolerance: float,
        near: tuple[float, float] | None,
        degree: int = 3,
    ) -> None:
        self.host, self.tolerance, self.degree = net.host, tolerance, degree
        self.size = self.host.size
        self.stops = np.array([p.point for p in net.umbilics.points]).reshape(-1, 3)
        self.reach = UMBILIC_REACH * self.size
        self.flat = net.umbilics.part_level
        sides = {name: _line_of(net.lines[name], net.edges[name]) for name in (*k1, *k2)}
        self.bottom, self.top = sides[k1[0]], sides[k1[1]]
        self.left, self.right = sides[k2[0]], sides[k2[1]]
        # the corners, as (arc length on the family-1 line, on the family-2 line)
        first = self._crossings(self.bottom, self.left)
        if not len(first):
            raise ParameterError(f"the lines {k1[0]} and {k2[0]} do not cross", key="net")
        if near is not None and len(first) > 1:
            at = np.array([self.bottom.at(s) for s in first[:, 0]])
            first = first[[int(np.argmin(np.linalg.norm(self._wrap(at - np.asarray(near, dtype=float)), axis=1)))]]
        c00 = first[0]
        # each corner's arc length on the line it shares with the one before counted from that
        # one's (the shorter way round a closed line): the sides' spans are then differences
        c10 = self._nearest(self._crossings(self.bottom, self.right), 0, c00[0], (k1[0], k2[1]), self.bottom)
        c01 = self._nearest(self._crossings(self.top, self.left), 1, c00[1], (k1[1], k2[0]), self.left)
        c11 = self._nearest(self._crossings(self.top, self.right), 0, c01[0], (k1[1], k2[1]), self.top)
        c10[0] = c00[0] + self.bottom.apart(c10[0], c00[0])
        c01[1] = c00[1] + self.left.apart(c01[1], c00[1])
        self.corners = {"00": c00, "10": c10, "01": c01, "11": c11}
        self.length_u, self.length_v = abs(c10[0] - c00[0]), abs(c01[1] - c00[1])
        longest = max(
            self.length_u, self.length_v, abs(self.top.apart(c11[0], c01[0])), abs(self.right.apart(c11[1], c10[1]))
        )
        self.max_length = REACH * longest
        self.traced: dict[tuple[int, float], _Line] = {}

    def _wrap(self, d: FloatArray) -> FloatArray:
        """Parameter differences brought into (-period/2, period/2] along a closed direction."""
        d = np.array(d, dtype=float)
        for k in (0, 1):
            period = self.host.periods[k]
            if self.host.closed[k] and period is not None:
                d[..., k] -= period * np.round(d[..., k] / period)
        return d

    def _nearest(self, found: FloatArray, k: int, value: float, names: tuple[str, str], line: _Line) -> FloatArray:
        """The crossing in ``found`` whose arc length ``k`` is nearest ``value`` along ``line``."""
        if not len(found):
            raise ParameterError(f"the lines {names[0]} and {names[1]} do not cross: no four-sided cell", key="net")
        return found[int(np.argmin(np.abs(line.apart(found[:, k], value))))].copy()

    def _crossings(self, p: _Line, q: _Line) -> FloatArray:
        """Every crossing of the lines p and q, (k, 2): the arc length on each (module
        docstring, step 1)."""
        a, b = p.uv, q.uv
        shifts = [np.zeros(2)]
        for k in (0, 1):
            period = self.host.periods[k]
            if self.host.closed[k] and period is not None:
                low = math.floor((a[:, k].min() - b[:, k].max()) / period)
                high = math.ceil((a[:, k].max() - b[:, k].min()) / period)
                turns = [period * t for t in range(low, high + 1)]
                shifts = [s + np.eye(2)[k] * t for s in shifts for t in turns]
        d, e = np.diff(a, axis=0), np.diff(b, axis=0)
        found = []
        for shift in shifts:
            w = (b[None, :-1, :] + shift) - a[:-1, None, :]
            den = d[:, None, 0] * e[None, :, 1] - d[:, None, 1] * e[None, :, 0]
            with np.errstate(invalid="ignore", divide="ignore"):
                alpha = (w[..., 0] * e[None, :, 1] - w[..., 1] * e[None, :, 0]) / den
                beta = (w[..., 0] * d[:, None, 1] - w[..., 1] * d[:, None, 0]) / den
            slack = 1e-9
            hit = (den != 0) & (alpha >= -slack) & (alpha <= 1 + slack) & (beta >= -slack) & (beta <= 1 + slack)
            i, j = np.nonzero(hit)
            if not len(i):
                continue
            s = p.sigma[i] + alpha[i, j] * np.diff(p.sigma)[i]
            t = q.sigma[j] + beta[i, j] * np.diff(q.sigma)[j]
            s, t, ok = _newton(p.pcurve, q.pcurve, s, t, shift)
            found += [(x, y) for x, y, good in zip(s, t, ok) if good]
        out: list[tuple[float, float]] = []
        for x, y in sorted(found):
            if not out or abs(x - out[-1][0]) > SAME * self.size or abs(y - out[-1][1]) > SAME * self.size:
                out.append((x, y))
        return np.array(out).reshape(-1, 2)

    def _line(self, family: Family, share: float) -> _Line:
        """The grid's line of ``family`` seeded at ``share`` of its side (k1[0] for family 2,
        k2[0] for family 1) between the corners; the cell's own at shares 0 and 1."""
        if share in (0.0, 1.0):
            return (self.left, self.right)[int(share)] if family == 2 else (self.bottom, self.top)[int(share)]
        key = (family, round(share, 12))
        if key not in self.traced:
            side, k = (self.bottom, 0) if family == 2 else (self.left, 1)
            at = self.corners["00"][k] + share * (
                (self.corners["10"] if family == 2 else self.corners["01"])[k] - self.corners["00"][k]
            )
            seed = side.at(at)
            line = trace_line(
                self.host,
                (float(seed[0]), float(seed[1])),
                family,
                tolerance=self.tolerance,
                stops=self.stops,
                reach=self.reach,
                max_length=self.max_length,
                flat=self.flat,
            )
            self.traced[key] = _line_of(line, line_edge(self.host, line))
        return self.traced[key]

    def grid(self, rows: int, columns: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The grid's crossings: (s, t) (columns, rows, 2): the arc length on the family-2
        line (column) and on the family-1 line (row), and their host parameters (columns,
        rows, 2), unwrapped across a seam; and the seeds' shares (u's, v's)."""
        shares_u, shares_v = np.linspace(0.0, 1.0, columns), np.linspace(0.0, 1.0, rows)
        cols = [self._line(2, float(x)) for x in shares_u]
        lines = [self._line(1, float(x)) for x in shares_v]
        st = np.empty((columns, rows, 2))
        for a, col in enumerate(cols):
            # along the column from the bottom: its crossing with k1[0] nearest its seed
            reference = self.corners["00"][1] if a == 0 else None
            if a == columns - 1:
                reference = self.corners["10"][1]
            for b, row in enumerate(lines):
                found = self._crossings(row, col)  # (on the row, on the column)
                if not len(found):
                    raise ParameterError(
                        f"a grid line of the cell ends inside it (column {a}, row {b}): an umbilic or the "
                        "face's boundary in the cell; no four-sided patch",
                        key="net",
                    )
                if reference is None:  # an interior column at the bottom: its seed on k1[0]
                    seed_s = self.corners["00"][0] + shares_u[a] * (self.corners["10"][0] - self.corners["00"][0])
                    pick = int(np.argmin(np.abs(row.apart(found[:, 0], seed_s))))
                else:
                    pick = int(np.argmin(np.abs(col.apart(found[:, 1], reference))))
                st[a, b] = found[pick, 1], found[pick, 0]
                reference = st[a, b, 0]
        uv = np.array([[cols[a].at(st[a, b, 0]) for b in range(rows)] for a in range(columns)])
        # one unwrapping across a closed seam: along the first column, then along each row
        for k in (0, 1):
            period = self.host.periods[k]
            if self.host.closed[k] and period is not None:
                uv[0, :, k] = np.unwrap(uv[0, :, k], period=period)
                uv[:, :, k] = np.unwrap(uv[:, :, k], period=period, axis=0)
        return st, uv, shares_u, shares_v

    def patch(
        self, samples: tuple[int, int], start: float, tried: tuple[dict[str, Any], ...] = (), bounded: bool = True
    ) -> CurvaturePatch:
        """The patch on a grid of ``samples`` = (family-1 lines, family-2 lines)."""
        rows, columns = samples
        st, uv, shares_u, shares_v = self.grid(rows, columns)
        host = self.host
        grid = host.points(*host.wrapped(uv[..., 0].ravel(), uv[..., 1].ravel())).reshape(columns, rows, 3)
        us, vs = shares_u * self.length_u, shares_v * self.length_v
        k = self.degree
        along_v = make_interp_spline(vs, grid, k=k, axis=1)  # c: (rows' poles, columns, 3)
        along_u = make_interp_spline(us, along_v.c, k=k, axis=1)  # c: (columns' poles, rows' poles, 3)
        poles = np.asarray(along_u.c, dtype=float)
        u_knots, u_mults = knots_and_multiplicities(along_u.t)
        v_knots, v_mults = knots_and_multiplicities(along_v.t)
        surface = Geom_BSplineSurface(
            points_2d(poles), reals(u_knots), reals(v_knots), integers(u_mults), integers(v_mults), k, k
        )
        distance, angle, f, m, same = self._measured(surface, us, vs, uv)
        face, gap = self._face(surface, st, us, vs, grid, same) if bounded else (None, 0.0)
        return CurvaturePatch(
            surface,
            face,
            (rows, columns),
            grid,
            uv,
            distance,
            angle,
            f,
            m,
            gap,
            (poles.shape[0], poles.shape[1]),
            same,
            time.perf_counter() - start,
            self.size,
            tried,
        )

    def _measured(
        self, surface: Geom_BSplineSurface, us: FloatArray, vs: FloatArray, uv: FloatArray
    ) -> tuple[float, float, float, float, bool]:
        """(distance, angle, F, M, whether the patch's normal agrees with the host's) on the
        measuring grid (module docstring)."""
        fractions = np.array((0.0, *CHECKS))

        def finer(x: FloatArray) -> FloatArray:
            return np.append((x[:-1, None] + fractions[None, :] * np.diff(x)[:, None]).ravel(), x[-1])

        fu, fv = np.meshgrid(finer(us), finer(vs), indexing="ij")
        patch = HostSurface.of_surface(surface)
        jet = patch.jet(fu.ravel(), fv.ravel())
        own = field_of(jet)
        # the host's parameters as a first guess: the grid's interpolated likewise
        guess_v = make_interp_spline(vs, uv, k=self.degree, axis=1)  # c: (rows' poles, columns, 2)
        guess_u = make_interp_spline(us, guess_v.c, k=self.degree, axis=1)  # c: (columns' poles, rows' poles, 2)
        across = guess_u(fu[:, 0])  # (rows' poles, fine u's, 2): the spline's axis is 1
        hint = BSpline(guess_v.t, across, self.degree)(fv[0]).swapaxes(0, 1).reshape(-1, 2)
        # a box of a grid step round the guess (unclamped along a closed direction)
        step = np.maximum(np.abs(np.diff(uv, axis=0)).max(axis=(0, 1)), np.abs(np.diff(uv, axis=1)).max(axis=(0, 1)))
        low, high = np.array(self.host.bounds[0::2]), np.array(self.host.bounds[1::2])
        projector = GeomAPI_ProjectPointOnSurf()
        feet = np.empty((len(hint), 2))
        distances = np.empty(len(hint))
        for i, (point, guess) in enumerate(zip(jet.X.tolist(), self._wrapped(hint))):
            box = [guess - step, guess + step]
            for k in (0, 1):
                if not self.host.closed[k]:
                    box[0][k], box[1][k] = max(box[0][k], low[k]), min(box[1][k], high[k])
            projector.Init(self.host.surface, box[0][0], box[1][0], box[0][1], box[1][1])
            projector.Perform(gp_Pnt(*point))
            if not projector.NbPoints():
                raise TubecadError("a point of the curvature patch could not be projected onto its host")
            distances[i] = projector.LowerDistance()
            feet[i] = projector.LowerDistanceParameters()
        field = principal_field(self.host, feet[:, 0], feet[:, 1])
        angle = max(float(_angle(jet.Xu, field.d1).max()), float(_angle(jet.Xv, field.d2).max()))
        lu, lv = np.linalg.norm(jet.Xu, axis=1), np.linalg.norm(jet.Xv, axis=1)
        f = np.abs(np.einsum("nk,nk->n", jet.Xu, jet.Xv)) / (lu * lv)
        m = np.abs(np.einsum("nk,nk->n", jet.Xuv, own.n)) / (lu * lv * np.maximum(np.abs(own.k1), np.abs(own.k2)))
        same = float(np.einsum("nk,nk->n", own.n, field.n).mean()) > 0
        return float(distances.max()), angle, float(f.max()), float(m.max()), same

    def _wrapped(self, uv: FloatArray) -> FloatArray:
        u, v = self.host.wrapped(uv[:, 0], uv[:, 1])
        return np.stack([u, v], axis=1)

    def _face(
        self, surface: Geom_BSplineSurface, st: FloatArray, us: FloatArray, vs: FloatArray, grid: FloatArray, same: bool
    ) -> tuple[TopoDS_Face, float]:
        """The face on ``surface`` bounded by the cell's four lines (module docstring, step
        4) and the largest gap between their curves and the patch."""
        corners = {
            key: BRepBuilderAPI_MakeVertex(gp_Pnt(*(float(c) for c in grid[a, b]))).Vertex()
            for key, (a, b) in {"00": (0, 0), "10": (-1, 0), "01": (0, -1), "11": (-1, -1)}.items()
        }
        n_u, n_v = len(us), len(vs)
        sides = [  # (line, its arc lengths at the grid points, their (u, v), from, to)
            (self.bottom, st[:, 0, 1], np.stack([us, np.zeros(n_u)], axis=1), "00", "10"),
            (self.right, st[-1, :, 0], np.stack([np.full(n_v, us[-1]), vs], axis=1), "10", "11"),
            (self.top, st[::-1, -1, 1], np.stack([us[::-1], np.full(n_u, vs[-1])], axis=1), "11", "01"),
            (self.left, st[0, ::-1, 0], np.stack([np.zeros(n_v), vs[::-1]], axis=1), "01", "00"),
        ]
        worst = 0.0
        edges: list[TopoDS_Edge] = []
        for line, sigma, params, first, last in sides:
            edge, gap = _side(line.curve, sigma, params, corners[first], corners[last], surface)
            edges.append(edge)
            worst = max(worst, gap)
        tolerance = max(EDGE_TOLERANCE, 2.0 * worst)
        builder = BRep_Builder()
        for edge in edges:
            builder.UpdateEdge(edge, tolerance)
        for vertex in corners.values():
            builder.UpdateVertex(vertex, tolerance)
        wire = BRepBuilderAPI_MakeWire()
        for edge in edges:
            wire.Add(edge)
        if not wire.IsDone():
            raise TubecadError("the cell's four lines do not make a closed wire on its patch")
        face = BRepBuilderAPI_MakeFace(surface, wire.Wire(), True).Face()
        if not same:
            face = as_face(face.Reversed())
        if not BRepCheck_Analyzer(face).IsValid():
            raise TubecadError("the curvature patch's face is not valid")
        return face, worst


def _side(
    curve: Geom_BSplineCurve,
    sigma: FloatArray,
    params: FloatArray,
    first: TopoDS_Vertex,
    last: TopoDS_Vertex,
    surface: Geom_BSplineSurface,
) -> tuple[TopoDS_Edge, float]:
    """An edge on ``curve`` from the vertex ``first`` (at sigma[0]) to ``last`` (sigma[-1]),
    with the pcurve on ``surface`` interpolating ``params`` against ``sigma``; and the largest
    distance between the curve and the surface along that pcurve."""
    order = np.argsort(sigma)
    pcurve = make_interp_spline(sigma[order], params[order], k=3)
    low, high = float(sigma[order[0]]), float(sigma[order[-1]])
    forward = sigma[-1] > sigma[0]
    start, end = (first, last) if forward else (last, first)
    maker = BRepBuilderAPI_MakeEdge(curve, start, end, low, high)
    if not maker.IsDone():
        raise TubecadError("an edge of the curvature patch could not be made on its line")
    edge = maker.Edge()
    BRep_Builder().UpdateEdge(edge, occ_curve_2d(pcurve), surface, TopLoc_Location(), EDGE_TOLERANCE)
    at = np.linspace(low, high, 8 * len(sigma) + 1)
    on_patch = pcurve(at)
    gap = max(
        curve.Value(float(x)).Distance(surface.Value(float(p), float(q))) for x, (p, q) in zip(at, on_patch.tolist())
    )
    return (edge if forward else as_edge(edge.Reversed())), gap


def _newton(
    p: BSpline, q: BSpline, s: FloatArray, t: FloatArray, shift: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Newton's method on p(s) - q(t) - shift = 0 (each a pcurve in its arc length) from
    (s, t), vectorised; (s, t, converged inside both domains)."""
    (s_lo, s_hi), (t_lo, t_hi) = (p.t[p.k], p.t[-p.k - 1]), (q.t[q.k], q.t[-q.k - 1])
    for _ in range(30):
        r = p(s) - q(t) - shift
        dp, dq = p(s, 1), q(t, 1)
        det = -dp[:, 0] * dq[:, 1] + dp[:, 1] * dq[:, 0]
        with np.errstate(invalid="ignore", divide="ignore"):
            ds = (-r[:, 0] * dq[:, 1] + r[:, 1] * dq[:, 0]) / det
            dt = (dp[:, 0] * r[:, 1] - dp[:, 1] * r[:, 0]) / det
        s, t = np.clip(s - ds, s_lo, s_hi), np.clip(t - dt, t_lo, t_hi)
        if np.all(np.abs(ds) + np.abs(dt) < NEWTON_STEP * max(1.0, float(np.abs(s).max()))):
            break
    r = np.linalg.norm(p(s) - q(t) - shift, axis=1)
    scale = max(float(np.abs(p.c).max()), 1.0)
    return s, t, np.isfinite(r) & (r < 1e-9 * scale)


def _angle(d: FloatArray, t: FloatArray) -> FloatArray:
    """The angle between lines (either sense), accurate near 0."""
    return np.arctan2(np.linalg.norm(np.cross(d, t), axis=1), np.abs(np.einsum("nk,nk->n", d, t)))
