"""Pin-jig tables of a host face's net panels (issue 44): the heights of the vertical pins each
cell of the net (a plate between two lines of each family, or between lines and the face's
boundary) is set on.

The same table as a tube panel's (:mod:`tubecad.shop.pin_jig`), on any face: the pins carry
the plating's surface opposite its stiffeners, S = X + d n (the face offset along its outward
normal n by ``level``: OCCT's ``Geom_OffsetSurface``, exact; the face itself at 0), over the
cell (the split face's patch, classified in the host's parameters by OCCT's
``IntTools_FClass2d``).

- up = up_sign * m / |m|, m = Int Int S_u x S_v du dv over the cell (the area-weighted mean
  outward normal, summed on a grid of the cell's parameter box, the points off the cell left
  out); up_sign = +1 sets the panel outward side up (dome up), -1 as a trough;
- x_dir = the host's k1 direction at the cell's middle sample, made orthogonal to up;
  y_dir = up x x_dir (right-handed);
- the plane lies ``clearance`` below the cell's lowest point (the lowest sample, refined by
  bounded L-BFGS-B while it stays on the cell, or the lowest of its boundary's points, 129 an
  edge), so every height is >= clearance;
- the pin grid (spacing h) passes through the projection of the middle sample, so there is
  always a pin; its (0, 0) (the table's ``origin``, on the plane) is the grid point of the
  smallest i and j among the pins, so i, j >= 0 and x = i h, y = j h;
- a grid point is a pin when its vertical line meets the cell: proj(S(u, v)) = (x, y) is
  solved by Newton from the nearest sample (scipy.spatial.cKDTree), to 1e-12 of the cell's
  size, and kept when (u, v) lies on the cell; its height is (S(u, v) - origin) . up.

A cell that folds over the plane (the projected Jacobian changes sign on it: a vertical line
would meet it twice) has no table: a ParameterError says so (the shop package warns).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from OCP.TopoDS import TopoDS_Face

from tubecad.core.atomic import write_text
from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.core.units import length_unit as length_unit_of
from tubecad.nets.host import HostSurface, face_classifier
from tubecad.nets.principal import principal_field
from tubecad.shop.pin_jig import round_spacing

if TYPE_CHECKING:
    from tubecad.nets import CurvatureNet

FloatArray = np.ndarray
#: samples of the cell's parameter box along each direction (at least, at most)
MIN_SAMPLES, MAX_SAMPLES = 33, 129
#: Newton iterations at most
MAX_ITERATIONS = 40


@dataclass(frozen=True)
class CellPinJig:
    """A net panel's pin-jig table: the plane (``origin``, ``x_dir``, ``y_dir``, ``up``) and,
    per pin, its grid position ``xy`` in the plane, its height along ``up``, where it touches
    the surface (``uv``: the host's parameters) and the panel's ``outline`` projected."""

    name: str
    spacing: float
    origin: FloatArray
    x_dir: FloatArray
    y_dir: FloatArray
    up: FloatArray
    xy: FloatArray  # (n, 2) i * spacing, j * spacing
    heights: FloatArray  # (n,)
    uv: FloatArray  # (n, 2)
    outline: FloatArray  # (m, 2)
    lines: tuple[str, ...] = ()  # the net's lines bounding the panel

    @property
    def indices(self) -> FloatArray:
        """(n, 2) the pins' grid indices (i, j)."""
        return np.rint(self.xy / self.spacing).astype(int)

    def points(self) -> FloatArray:
        """(n, 3) the touching points origin + x x_dir + y y_dir + h up."""
        return self.origin + self.xy[:, :1] * self.x_dir + self.xy[:, 1:] * self.y_dir + self.heights[:, None] * self.up


class _Surface:
    """The host offset by ``level`` along the face's outward normal: points and first
    derivatives (OCCT's ``D1`` on the surface or its ``Geom_OffsetSurface``)."""

    def __init__(self, host: HostSurface, level: float) -> None:
        from OCP.Geom import Geom_OffsetSurface
        from OCP.TopAbs import TopAbs_REVERSED

        reversed_face = host.face is not None and host.face.Orientation() == TopAbs_REVERSED
        self.sign = -1.0 if reversed_face else 1.0  # the surface's normal X_u x X_v against the face's outward one
        self.surface = host.surface if level == 0.0 else Geom_OffsetSurface(host.surface, self.sign * level)

    def d1(self, u: FloatArray, v: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        from OCP.gp import gp_Pnt, gp_Vec

        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        out = np.empty((3, u.size, 3))
        p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
        d1 = self.surface.D1
        for i, (a, b) in enumerate(zip(u.ravel().tolist(), v.ravel().tolist())):
            d1(a, b, p, du, dv)
            out[0, i], out[1, i], out[2, i] = p.Coord(), du.Coord(), dv.Coord()
        return out[0].reshape(*u.shape, 3), out[1].reshape(*u.shape, 3), out[2].reshape(*u.shape, 3)


def cell_pin_jig(
    host: HostSurface,
    cell: TopoDS_Face,
    spacing: float,
    level: float = 0.0,
    up_sign: float = 1.0,
    clearance: float = 0.0,
    name: str = "panel",
    lines: tuple[str, ...] = (),
) -> CellPinJig:
    """The pin-jig table of the net's ``cell`` (module docstring).

    Args:
        host: the face's surface.
        cell: a patch of the split face (on ``host``'s surface).
        spacing: the pin grid's spacing (> 0).
        level: the surface the pins carry, along the outward normal from the face.
        up_sign: +1 the outward side up, -1 as a trough.
        clearance: the cell's lowest point above the plane (>= 0).
        name: the table's name.
        lines: the net's lines bounding the cell (recorded).

    Returns:
        The table.

    Raises:
        ParameterError: (``pin_spacing``) not > 0; (``panel``) the cell folds over the plane or
            has no mean normal.
    """
    from OCP.BRepTools import BRepTools
    from scipy.spatial import cKDTree

    if not (isinstance(spacing, (int, float)) and math.isfinite(spacing) and spacing > 0):
        raise ParameterError(f"pin_spacing must be > 0, got {spacing!r:.40}", key="pin_spacing")
    h = float(spacing)
    surface = _Surface(host, level)
    inside = face_classifier(cell)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(cell)
    # samples of the parameter box, those on the cell kept
    X, Xu, Xv = surface.d1(np.array([u0, u1, u0, u1]), np.array([v0, v0, v1, v1]))
    box = float(np.ptp(X, axis=0).max())
    n = int(np.clip(math.ceil(4.0 * box / h) + 1, MIN_SAMPLES, MAX_SAMPLES))
    us, vs = np.meshgrid(np.linspace(u0, u1, n), np.linspace(v0, v1, n), indexing="ij")
    on = inside(us.ravel(), vs.ravel())
    if on.sum() < 4:
        raise ParameterError(f"panel {name}: too small for its samples", key="panel")
    us, vs = us.ravel()[on], vs.ravel()[on]
    S, Su, Sv = surface.d1(us, vs)
    normal = surface.sign * np.cross(Su, Sv)
    mean = normal.sum(axis=0)
    if np.linalg.norm(mean) < 1e-6 * np.linalg.norm(normal, axis=1).sum():
        raise ParameterError(f"panel {name}: it has no mean normal (it goes round the face)", key="panel")
    up = float(up_sign) * mean / np.linalg.norm(mean)
    middle = int(np.argmin(np.linalg.norm(S - S.mean(axis=0), axis=1)))
    field = principal_field(host, us[middle : middle + 1], vs[middle : middle + 1])
    t = np.asarray(field.d1, dtype=float).reshape(3)
    x_dir = t - float(t @ up) * up
    x_dir /= np.linalg.norm(x_dir)
    y_dir = np.cross(up, x_dir)
    ref = S[middle]
    local = (S - ref) @ np.stack([x_dir, y_dir, up]).T
    jac = (Su @ x_dir) * (Sv @ y_dir) - (Sv @ x_dir) * (Su @ y_dir)
    if not (np.all(jac > 0) or np.all(jac < 0)):
        raise ParameterError(
            f"panel {name}: it is not a graph over its jig plane (a vertical pin would meet it twice); "
            "a finer net makes smaller panels",
            key="panel",
        )
    low = _lowest(surface, up, ref, local[:, 2], us, vs, (u0, u1, v0, v1), inside)
    size = float(np.ptp(local[:, :2], axis=0).max())
    lo, hi = local[:, :2].min(axis=0), local[:, :2].max(axis=0)
    ii, jj = (
        a.ravel()
        for a in np.meshgrid(
            np.arange(math.floor(lo[0] / h) - 1, math.ceil(hi[0] / h) + 2),
            np.arange(math.floor(lo[1] / h) - 1, math.ceil(hi[1] / h) + 2),
            indexing="ij",
        )
    )
    targets = np.stack([ii * h, jj * h], axis=1).astype(float)
    step = max((u1 - u0), (v1 - v0)) / (n - 1)
    reach = 2.0 * step * float(np.linalg.norm(np.stack([Su, Sv]), axis=2).max())
    dist, nearest = cKDTree(local[:, :2]).query(targets)
    near = dist <= reach
    targets, ii, jj, nearest = targets[near], ii[near], jj[near], nearest[near]
    u, v, ok = _project(surface, ref, x_dir, y_dir, targets, us[nearest], vs[nearest], 1e-12 * max(size, h))
    keep = ok & inside(u, v)
    ii, jj, u, v = ii[keep], jj[keep], u[keep], v[keep]
    order = np.lexsort((ii, jj))
    ii, jj, u, v = ii[order], jj[order], u[order], v[order]
    i0, j0 = int(ii.min()), int(jj.min())  # the middle sample's pin is always there
    touching, boundary = surface.d1(u, v)[0], _outline(surface, cell)
    # the lowest point: inside (the samples, refined) or on the boundary (its edges sampled
    # finely); the pins themselves never below it
    low = min(low, float(((boundary - ref) @ up).min()), float(((touching - ref) @ up).min()))
    origin = ref + (i0 * h) * x_dir + (j0 * h) * y_dir + (low - clearance) * up
    heights = (touching - origin) @ up
    outline = (boundary - origin) @ np.stack([x_dir, y_dir]).T
    xy = np.stack([(ii - i0) * h, (jj - j0) * h], axis=1).astype(float)
    return CellPinJig(name, h, origin, x_dir, y_dir, up, xy, heights, np.stack([u, v], axis=1), outline, lines)


def _lowest(surface: _Surface, up, ref, height, us, vs, bounds, inside) -> float:
    """min (S - ref) . up over the cell: the lowest sample, refined by bounded L-BFGS-B where
    the refined point stays on the cell."""
    from scipy.optimize import minimize

    k = int(np.argmin(height))
    u0, u1, v0, v1 = bounds

    def f(x: FloatArray) -> tuple[float, FloatArray]:
        S, Su, Sv = surface.d1(x[:1], x[1:])
        return float((S[0] - ref) @ up), np.array([float(Su[0] @ up), float(Sv[0] @ up)])

    result = minimize(f, np.array([us[k], vs[k]]), jac=True, method="L-BFGS-B", bounds=[(u0, u1), (v0, v1)])
    if result.fun < height[k] and inside(result.x[:1], result.x[1:])[0]:
        return float(result.fun)
    return float(height[k])


def _project(surface: _Surface, ref, x_dir, y_dir, targets, u, v, tolerance: float):
    """Newton on ((S(u, v) - ref) . x_dir, . y_dir) = targets from (u, v): (u, v, converged)."""
    u, v = u.astype(float).copy(), v.astype(float).copy()
    ok = np.zeros(len(u), dtype=bool)
    for _ in range(MAX_ITERATIONS):
        S, Su, Sv = surface.d1(u, v)
        rx, ry = (S - ref) @ x_dir - targets[:, 0], (S - ref) @ y_dir - targets[:, 1]
        ok = np.hypot(rx, ry) <= tolerance
        if ok.all():
            break
        a, b, c, d = Su @ x_dir, Sv @ x_dir, Su @ y_dir, Sv @ y_dir
        det = a * d - b * c
        with np.errstate(divide="ignore", invalid="ignore"):
            du, dv = (d * rx - b * ry) / det, (a * ry - c * rx) / det
        moving = ~ok & np.isfinite(du) & np.isfinite(dv)
        u[moving] -= du[moving]
        v[moving] -= dv[moving]
    return u, v, ok


def _outline(surface: _Surface, cell: TopoDS_Face, per_edge: int = 129) -> FloatArray:
    """The cell's boundary on the surface, (m, 3): each edge's pcurve sampled, in the wire's order."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools_WireExplorer
    from OCP.TopAbs import TopAbs_REVERSED, TopAbs_WIRE
    from OCP.TopExp import TopExp_Explorer

    from tubecad.occ_compat import as_wire

    points = []
    wires = TopExp_Explorer(cell, TopAbs_WIRE)
    while wires.More():
        walk = BRepTools_WireExplorer(as_wire(wires.Current()), cell)
        while walk.More():
            edge = walk.Current()
            pcurve = BRep_Tool.CurveOnSurface_s(edge, cell, 0.0, 0.0)
            first, last = BRep_Tool.Range_s(edge, cell)
            ts = np.linspace(first, last, per_edge)[:-1]
            if edge.Orientation() == TopAbs_REVERSED:
                ts = np.linspace(last, first, per_edge)[:-1]
            uv = np.array([[q.X(), q.Y()] for q in (pcurve.Value(float(t)) for t in ts)])
            points.append(surface.d1(uv[:, 0], uv[:, 1])[0])
            walk.Next()
        break  # the outer wire
    return np.concatenate(points)


def write_cell_pin_jig_csv(jig: CellPinJig, path: str | Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> Path:
    """The table as CSV: a comment line ``# units: mm``, a comment naming the bounding lines,
    the header pin, i, j, x, y, height, px, py, pz (the touching point in the model) and one
    row per pin (numbered from 1), floats as repr (round-trip exact); written atomically."""
    unit = length_unit_of(length_unit)
    lines = [f"# units: {unit.name}", f"# panel {jig.name} between {', '.join(jig.lines) or 'the boundary'}"]
    lines.append("pin,i,j,x,y,height,px,py,pz")
    for k, ((i, j), (x, y), height, p) in enumerate(zip(jig.indices, jig.xy, jig.heights, jig.points())):
        lines.append(",".join([str(k + 1), str(i), str(j)] + [repr(float(v)) for v in (x, y, height, *p)]))
    return write_text(path, "\n".join(lines) + "\n")


def net_pin_jigs(
    net: CurvatureNet,
    levels: tuple[float, float],
    side: str,
    spacing: float | None,
    clearance: float,
    warnings: list[str],
) -> list[CellPinJig]:
    """A pin jig per cell of ``net`` (``panel_01``... in the split face's order), on the
    plating's surface opposite its stiffeners (``levels`` = the wall's (inner, outer) offsets
    from the face; stiffeners ``side`` outside: the inner one, the panel dome-up; inside: the
    outer one, a trough), pins every ``spacing`` (None: a round value giving about 6 pins
    across each panel); a cell with no table is named in ``warnings``.

    Args:
        net: the face's net (its ``patches``: the cells).
        levels: the wall's inner and outer offsets along the outward normal (0, 0 without one).
        side: the stiffeners' side (``outside`` without stiffeners).
        spacing: the pin grid's spacing, or None.
        clearance: the panels' lowest points above their planes.
        warnings: collects the cells with no table.

    Returns:
        The tables.
    """
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer

    from tubecad.occ_compat import as_face

    level, up_sign = (levels[0], 1.0) if side == "outside" else (levels[1], -1.0)
    cells = []
    walk = TopExp_Explorer(net.patches, TopAbs_FACE)
    while walk.More():
        cells.append(as_face(walk.Current()))
        walk.Next()
    size = float(np.ptp(np.concatenate([line.points for line in net.lines.values()]), axis=0).max())
    out = []
    for k, cell in enumerate(cells, 1):
        name = f"panel_{k:02d}"
        try:
            h = spacing if spacing is not None else _round_spacing(cell)
            lines = bounding_lines(net, cell, 1e-6 * size)
            out.append(cell_pin_jig(net.host, cell, h, level, up_sign, clearance, name, lines))
        except ParameterError as exc:
            warnings.append(f"{name}: no pin jig ({exc})")
    return out


def _round_spacing(cell: TopoDS_Face) -> float:
    """A round spacing (1, 2 or 5 x 10^k) giving about 6 pins across the cell's narrower
    extent (the middle one of its bounding box's sides)."""
    from tubecad.occ_compat import box_corners

    corners = box_corners(cell)
    assert corners is not None  # a cell of the split face is not empty
    return round_spacing(sorted(np.subtract(corners[1], corners[0]).tolist())[1])


def bounding_lines(net: CurvatureNet, cell: TopoDS_Face, reach: float) -> tuple[str, ...]:
    """The names of the net's lines a cell's edges lie on (each edge's middle within ``reach``
    of the line's curve; OCCT's ``GeomAPI_ProjectPointOnCurve``), sorted."""
    from OCP.BRep import BRep_Tool
    from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer

    from tubecad.occ_compat import as_edge

    names: set[str] = set()
    walk = TopExp_Explorer(cell, TopAbs_EDGE)
    while walk.More():
        edge = as_edge(walk.Current())
        walk.Next()
        if BRep_Tool.Degenerated_s(edge):
            continue
        curve = BRep_Tool.Curve_s(edge, 0.0, 1.0)
        first, last = BRep_Tool.Range_s(edge)
        middle = curve.Value(0.5 * (first + last))
        for name, line_edge in net.edges.items():
            projection = GeomAPI_ProjectPointOnCurve(middle, line_edge.curve)
            if projection.NbPoints() and projection.LowerDistance() <= reach:
                names.add(name)
                break
    return tuple(sorted(names))
