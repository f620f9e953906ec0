"""A traced line of curvature as an edge on its host surface (issue 44; docs/MATH.md section 15).

The tracer gives, at each step's end, the line's parameters (u, v) and its arc length sigma
(:mod:`~tubecad.nets.trace`); the principal field gives there the line's exact direction
(u', v') = (du, dv)_k per unit length, and its derivative along the line (u'', v'') (the field
differenced along itself, central, over EPSILON of the face's size). Each piece between two
nodes is then the quintic that matches position, first and second derivatives at both ends
(Hermite; :meth:`scipy.interpolate.BPoly.from_derivatives`), a C2 curve whose Bezier poles are
the B-spline's (knots of multiplicity 5 inside): the edge's pcurve. The 3-D curve is the same
quintic Hermite interpolation of the surface's points X, X' = X_u u' + X_v v' and
X'' = X_uu u'^2 + 2 X_uv u' v' + X_vv v'^2 + X_u u'' + X_v v'', so both curves share the
parameter sigma, and the edge carries both (``BRep_Builder::UpdateEdge``). A closed line ends
exactly where it starts (a period along where it runs round a seam).

Nodes are the tracer's, which puts one on every line where the surface is less than C3 (a
B-spline's knot lines, the periodic seam): there the parameter direction jumps, so each piece
reads the field on its own side of the node and the pcurve is only C0 there (the 3-D curve
stays C1, its knot there of multiplicity 4: its tangent is geometric, the same from both sides). Its quality is measured where the interpolation is
least held, inside each piece: the angle between the 3-D curve's tangent and the principal
direction of its family at the surface point of its pcurve (``angle``, radians), and the
distance between the 3-D curve and that point (``gap``). Halving pieces does not lower the
angle below the tracer's tolerance over the piece's length (a node re-traced from one end
sits off the next by the step's error), so the tolerance, not the node count, sets it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.Geom import Geom_BSplineCurve
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Edge
from scipy.interpolate import BSpline

from tubecad.core.errors import TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.fitting.nurbs import occ_curve_2d, occ_curve_3d
from tubecad.nets.host import HostSurface, crossed_breaks
from tubecad.nets.principal import PointField, principal_field
from tubecad.nets.trace import CurvatureLine

FloatArray = np.ndarray
#: the step of the field's difference along the line, as a share of the face's size
EPSILON = 1e-6
#: the pieces' degree (quintic Hermite: position and two derivatives at both ends)
DEGREE = 5
#: points inside each piece where the edge is measured
CHECKS = 4


@dataclass(frozen=True)
class LineEdge:
    """A line of curvature as an ``edge`` carrying its 3-D ``curve`` and its ``pcurve`` on the
    host surface (both in the arc length), with ``angle``, the largest angle (radians) between
    the curve's tangent and its family's principal direction, and ``gap``, the largest distance
    between the 3-D curve and the surface point of the pcurve, inside the pieces."""

    edge: TopoDS_Edge
    curve: Geom_BSplineCurve
    pcurve: Geom2d_BSplineCurve
    angle: float
    gap: float


def line_edge(host: HostSurface, line: CurvatureLine) -> LineEdge:
    """The ``line`` (traced on ``host``) as an edge on the surface (module docstring).

    Args:
        host: the surface it was traced on.
        line: the traced line.

    Returns:
        The edge, its curves and how closely it follows the principal direction.
    """
    return _fitted(host, line)[0]


def _fitted(host: HostSurface, line: CurvatureLine) -> tuple[LineEdge, FloatArray, FloatArray]:
    """The edge through the line's nodes as they are, and each piece's largest angle and gap."""
    sigma, uv = line.sigma, line.uv.copy()
    ending, starting = line.offsets()
    if line.closed:  # ends where it starts (a period along round a seam)
        shift = np.zeros(2)
        for k, period in enumerate(host.periods):
            if period is not None:
                shift[k] = period * round((uv[-1, k] - uv[0, k]) / period)
        uv[-1] = uv[0] + shift
    points = host.points(*host.wrapped(uv[:, 0], uv[:, 1]))
    data = _Derivatives(host, line.family, float(np.ptp(points, axis=0).max()))
    pieces = len(sigma) - 1
    pcurve_poles = np.empty((pieces, 6, 2))
    curve_poles = np.empty((pieces, 6, 3))
    for i in range(pieces):
        way = points[i + 1] - points[i]
        h = sigma[i + 1] - sigma[i]
        start = data.at(uv[i] + starting[i], way)
        end = data.at(uv[i + 1] + ending[i + 1], way)
        pcurve_poles[i] = _bezier(uv[i], start[0], start[1], uv[i + 1], end[0], end[1], h)
        curve_poles[i] = _bezier(points[i], start[2], start[3], points[i + 1], end[2], end[3], h)
    knots = np.concatenate([[sigma[0]] * 6, np.repeat(sigma[1:-1], 5), [sigma[-1]] * 6])
    pcurve_spline = BSpline(knots, _joined(pcurve_poles), DEGREE)
    curve_spline = BSpline(knots, _joined(curve_poles), DEGREE)
    curve, pcurve = occ_curve_3d(curve_spline), occ_curve_2d(pcurve_spline)
    smooth = [i + 1 for i in range(1, pieces) if not (np.any(ending[i]) or np.any(starting[i]))]
    _to_c2(curve, smooth, EDGE_TOLERANCE * 1e-3)
    _to_c2(pcurve, smooth, 1e-12)
    _to_c1(curve, [i + 1 for i in range(1, pieces) if i + 1 not in smooth], C1_TOLERANCE)
    edge = BRepBuilderAPI_MakeEdge(curve).Edge()
    BRep_Builder().UpdateEdge(edge, pcurve, host.surface, TopLoc_Location(), EDGE_TOLERANCE)
    angles, gaps = _measured(host, line.family, sigma, curve_spline, pcurve_spline)
    return LineEdge(edge, curve, pcurve, float(angles.max()), float(gaps.max())), angles, gaps


#: how far (model units) the 3-D curve may move where a break node's knot is brought down to
#: C1: a tenth of the edges' tolerance (a tangent round-off of 1e-9 over a piece of 10 mm
#: moves it 1e-8)
C1_TOLERANCE = 0.1 * EDGE_TOLERANCE


def _to_c2(curve: Geom_BSplineCurve | Geom2d_BSplineCurve, knots: list[int], tolerance: float) -> None:
    """The Hermite pieces meet C2 at a node off the break lines (both take its data): their
    knot there brought down from multiplicity 5 to 3 (OCCT's ``RemoveKnot``, exact to
    ``tolerance``), two poles fewer a node. ``knots``: the 1-based knot indices."""
    for index in knots:
        curve.RemoveKnot(index, 3, tolerance)


def _to_c1(curve: Geom_BSplineCurve, knots: list[int], tolerance: float) -> None:
    """At a node on a break line the 3-D pieces share the line's unit tangent (geometric
    data: the same from both sides, to the principal direction's round-off, 1.4e-9 rad where
    the hull sample's curvatures come close) but not the second derivative (it takes the
    field's derivative on each side): their knot there brought down from multiplicity 5 to 4,
    a C1 curve (OCCT's ``RemoveKnot`` within ``tolerance``, C1_TOLERANCE; OCCT's pre-boolean
    check reports a C0 curve). A node where the tangents differ more stays C0."""
    for index in knots:
        curve.RemoveKnot(index, 4, tolerance)


def _bezier(
    p0: FloatArray, d0: FloatArray, dd0: FloatArray, p1: FloatArray, d1: FloatArray, dd1: FloatArray, h: float
) -> FloatArray:
    """The quintic Bezier poles on a piece of length h matching position, first and second
    derivatives at both ends (B'(0) = 5 (b1 - b0) / h, B''(0) = 20 (b2 - 2 b1 + b0) / h^2)."""
    return np.array(
        [
            p0,
            p0 + h * d0 / 5,
            p0 + 2 * h * d0 / 5 + h * h * dd0 / 20,
            p1 - 2 * h * d1 / 5 + h * h * dd1 / 20,
            p1 - h * d1 / 5,
            p1,
        ]
    )


def _joined(poles: FloatArray) -> FloatArray:
    """The pieces' Bezier poles (pieces, 6, dim) as one B-spline's (each join's pole once)."""
    return np.concatenate([poles[0, :1], poles[:, 1:].reshape(-1, poles.shape[2])])


class _Derivatives:
    """The line's direction and its derivative along itself at a parameter point, in the
    parameters and in 3-D: the field's direction turned the ``way`` the piece goes, its
    derivative by a difference along it over EPSILON of the face's ``size``: central, or
    one-sided (three points) where the central one would cross a break line of the surface."""

    def __init__(self, host: HostSurface, family: int, size: float) -> None:
        self.host, self.family = host, family
        self.field = PointField(host)
        self.eps = EPSILON * max(size, 1e-300)
        self.known: dict[tuple[float, float], tuple[FloatArray, FloatArray, FloatArray, FloatArray]] = {}

    def _direction(self, x: FloatArray, way: FloatArray) -> tuple[FloatArray, FloatArray]:
        u, v = self.host.wrapped(x[:1], x[1:])
        at = self.field.at(float(u[0]), float(v[0]), self.family)
        if at is None:
            raise TubecadError("a line of curvature reaches a degenerate point of its face's parameterisation")
        d, t = np.array(at[:2]), np.array(at[2:5])
        return (d, t) if float(t @ way) >= 0 else (-d, -t)

    def at(self, x: FloatArray, way: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """(uv', uv'', X', X'') at ``x`` for a piece going ``way`` (3-D); a node shared by two
        pieces is differenced once (turned round, the derivatives along the line are the same)."""
        key = (float(x[0]), float(x[1]))
        known = self.known.get(key)
        if known is None:
            known = self.known[key] = self._at(x, way)
        d, dd, t, tt = known
        return (d, dd, t, tt) if float(t @ way) >= 0 else (-d, dd, -t, tt)

    def _at(self, x: FloatArray, way: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        d, t = self._direction(x, way)
        e = self.eps
        if not crossed_breaks(self.host, x - 2 * e * d, x + 2 * e * d):
            (a, ta), (b, tb) = self._direction(x + e * d, t), self._direction(x - e * d, t)
            return d, (a - b) / (2 * e), t, (ta - tb) / (2 * e)
        side = 1.0 if not crossed_breaks(self.host, x, x + 2 * e * d) else -1.0
        (a, ta), (b, tb) = self._direction(x + side * e * d, t), self._direction(x + side * 2 * e * d, t)
        return d, side * (-3 * d + 4 * a - b) / (2 * e), t, side * (-3 * t + 4 * ta - tb) / (2 * e)


def _measured(
    host: HostSurface, family: int, sigma: FloatArray, curve: BSpline, pcurve: BSpline
) -> tuple[FloatArray, FloatArray]:
    """(each piece's largest angle, its largest gap) at CHECKS points inside each piece
    (module docstring)."""
    fractions = np.arange(1, CHECKS + 1) / (CHECKS + 1)
    at = (sigma[:-1, None] + fractions[None, :] * np.diff(sigma)[:, None]).ravel()
    uv, x, tangent = pcurve(at), curve(at), curve(at, 1)
    wu, wv = host.wrapped(uv[:, 0], uv[:, 1])
    field = principal_field(host, wu, wv)
    direction = field.d1 if family == 1 else field.d2
    cross = np.linalg.norm(np.cross(tangent, direction), axis=1)
    angle = np.arctan2(cross, np.abs(np.einsum("nk,nk->n", tangent, direction)))
    gap = np.linalg.norm(host.points(wu, wv) - x, axis=1)
    return angle.reshape(-1, CHECKS).max(axis=1), gap.reshape(-1, CHECKS).max(axis=1)
