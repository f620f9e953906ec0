"""Stiffeners standing on a host face's lines of curvature (issue 44): the solid of a flat-bar,
T or L stiffener whose web follows the face's normal along a net line, its web's flat
development and its flange's.

Along a line of curvature X(sigma) (arc length sigma) the normals n(sigma) rule a developable
strip (Rodrigues: dn/dsigma = -k dX/dsigma, k the line's principal curvature; docs/MATH.md
section 9), so the web X + w n, w from ``base`` to ``base`` +- ``height``, develops flat
without strain. Its development (:func:`tubecad.stiffeners.flat.developed_strip`) has
speed 1 and turn k(sigma) = the normal curvature along the line (the line's own principal
curvature), evaluated exactly on the host surface (:mod:`tubecad.nets.principal`).

The frame T (the tangent), n (the normal), b = T x n moves as dT/dsigma = k n + g b,
dn/dsigma = -k T, db/dsigma = -g T, with g = b . X'' the line's geodesic curvature towards b
(no b-component in dn: the geodesic torsion of a line of curvature is 0). So every point
X + w n + s b of the profile's cross-section moves along T at the rate 1 - w k - s g: the
stiffener is the profile's outline (:meth:`Profile.outline`, s across along b, w up along n)
carried along the line, each side of it a ruled surface, and its volume is

    V = Int (A - k(sigma) A_w - g(sigma) A_s) dsigma,   A_w = Int w dA,  A_s = Int s dA

(Pappus' theorem where the line is a circle round an axis). A T or L flange lies in the
tangent-plane strip X + d n + s b at its mid-thickness level d, developable (its rulings b
move along T): its edge s runs at the rate (1 - d k) - s g, so it develops
(:func:`tubecad.shop.net_shop.flange_pattern`) with speed 1 - d k and turn g. g is read from
the line's edge, b . X'' of its 3-D curve (quintic Hermite pieces whose nodes hold the
line's exact direction and its differenced derivative, :mod:`tubecad.nets.edges`).

The solid: each side of the outline is the ruled face between the curves of its two corners,
X + w n + s b, each interpolated through SAMPLES_PER_PIECE points per piece of the line
(scipy's C2 cubic); the two ends are planar (the outline at the line's ends). A flat web's
volume is the development's area times the thickness (Steiner: the strip is developable,
K = 0, and the sides are symmetric about it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepFill import BRepFill
from OCP.TopAbs import TopAbs_REVERSED
from OCP.TopoDS import TopoDS_Solid

from tubecad.core.errors import ParameterError, TubecadError
from tubecad.nets.edges import LineEdge
from tubecad.nets.host import HostSurface
from tubecad.nets.principal import principal_field
from tubecad.nets.trace import CurvatureLine
from tubecad.stiffeners.flat import FlatPattern, developed_strip
from tubecad.stiffeners.profiles import Profile, StiffenerSide

FloatArray = np.ndarray
#: points per piece of a line (between the tracer's nodes, each turning by at most
#: :data:`tubecad.nets.trace.TURN`) the web's curves are interpolated through: 2 hold the
#: solid's volume to 1e-11 of the development's area times the thickness (hull sample)
SAMPLES_PER_PIECE = 2


@dataclass(frozen=True)
class NetWeb:
    """A stiffener on the net's line ``line`` (its name): its ``solid`` (a TopoDS_Solid), its
    ``profile`` and ``side``, where its base stands (``base``: along the normal from the host
    face) and its web's developed flat ``pattern`` (a T or L profile's flange is developed by
    the shop: :func:`tubecad.shop.net_shop.flange_pattern`)."""

    line: str
    solid: TopoDS_Solid
    profile: Profile
    side: StiffenerSide
    base: float
    pattern: FlatPattern

    @property
    def name(self) -> str:
        """The stiffener's name: ``stiffener_k1_03``."""
        return f"stiffener_{self.line}"


def unit_normals(host: HostSurface, uv: FloatArray) -> FloatArray:
    """The face's unit normals (n, 3) at parameters ``uv`` (n, 2): Xu x Xv normalised, turned
    round where the face is reversed on its surface (the face's outside)."""
    jet = host.jet(uv[:, 0], uv[:, 1])
    normal = np.cross(jet.Xu, jet.Xv)
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    reversed_face = host.face is not None and host.face.Orientation() == TopAbs_REVERSED
    return -normal if reversed_face else normal


def line_curvature(host: HostSurface, edge: LineEdge, family: int, sigma: FloatArray) -> FloatArray:
    """The normal curvature along a line at arc lengths ``sigma`` (any shape): its family's
    (1 or 2) principal curvature at the points of its edge's pcurve (whose parameter is the
    arc length), signed for the face's outward normal (> 0 where the line bends towards it)."""
    at = np.asarray(sigma, dtype=float)
    uv = np.array([[p.X(), p.Y()] for p in (edge.pcurve.Value(float(x)) for x in at.ravel())]).reshape(-1, 2)
    field = principal_field(host, uv[:, 0], uv[:, 1])
    k = np.asarray(field.k1 if family == 1 else field.k2, dtype=float).reshape(at.shape)
    reversed_face = host.face is not None and host.face.Orientation() == TopAbs_REVERSED
    return -k if reversed_face else k


def net_web(
    host: HostSurface,
    name: str,
    line: CurvatureLine,
    edge: LineEdge,
    profile: Profile,
    side: StiffenerSide = "outside",
    base: float = 0.0,
) -> NetWeb:
    """The stiffener of ``profile`` (flat bar, T or L) on the net line ``name`` (module docstring).

    Args:
        host: the face's surface.
        name: the line's name (``k1_03``).
        line: the traced line.
        edge: its edge on the face.
        profile: its cross-section.
        side: ``outside`` (along the face's normal) or ``inside``.
        base: where the web's base stands, along the normal from the face (a wall's surface).

    Returns:
        The stiffener's solid and developments.

    Raises:
        ParameterError: (``side``) not outside or inside.
    """
    if side not in ("outside", "inside"):
        raise ParameterError(f"side must be one of outside, inside, got {side!r:.40}", key="side")
    sign = 1.0 if side == "outside" else -1.0
    outline = [(s, base + sign * w) for s, w in profile.outline()]
    solid = _stiffener_solid(host, line, edge, outline)
    pattern = web_pattern(host, name, line, edge, profile.web_height, side, base)
    return NetWeb(name, solid, profile, side, base, pattern)


def geodesic_curvature(host: HostSurface, edge: LineEdge, sigma: FloatArray) -> FloatArray:
    """g = b . X'' at arc lengths ``sigma`` (any shape) along the line's edge: its curvature
    towards b = T x n in the tangent plane (n the face's outward normal), from its 3-D curve's
    second derivative (the edge's parameter is the arc length)."""
    from OCP.gp import gp_Pnt, gp_Vec

    at = np.asarray(sigma, dtype=float)
    flat = at.ravel()
    uv = np.array([[p.X(), p.Y()] for p in (edge.pcurve.Value(float(x)) for x in flat)]).reshape(-1, 2)
    normals = unit_normals(host, uv)
    first, second = np.empty((len(flat), 3)), np.empty((len(flat), 3))
    p, d1, d2 = gp_Pnt(), gp_Vec(), gp_Vec()
    for i, x in enumerate(flat):
        edge.curve.D2(float(x), p, d1, d2)
        first[i], second[i] = d1.Coord(), d2.Coord()
    across = np.cross(first / np.linalg.norm(first, axis=1, keepdims=True), normals)
    return np.einsum("ij,ij->i", across, second).reshape(at.shape)


def line_kinks(line: CurvatureLine, a: float, b: float) -> FloatArray:
    """The span (0, b - a)'s ends and the nodes inside it where the line crosses a break of
    the surface (its curvatures kink there): the Chebyshev panels' ends."""
    ending, starting = line.offsets()
    kinks = line.sigma[np.any(ending != 0, axis=1) | np.any(starting != 0, axis=1)] - line.sigma[0] - a
    return np.unique(np.concatenate([[0.0, b - a], kinks[(kinks > 0) & (kinks < b - a)]]))


def web_pattern(
    host: HostSurface,
    name: str,
    line: CurvatureLine,
    edge: LineEdge,
    height: float,
    side: str,
    base: float = 0.0,
    span: tuple[float, float] | None = None,
) -> FlatPattern:
    """The development of the web of ``height`` on ``side`` of the line, its base ``base``
    along the normal from the face, over ``span`` (arc lengths from the line's start; None:
    all of it): along its base X + base n, whose speed is 1 - base k per unit arc length of the
    line (dn/dsigma = -k dX/dsigma), the rulings turning by k. The nodes where the line crosses
    a break of the surface (k kinks there) start Chebyshev panels.

    Args:
        host: the face's surface.
        name: the pattern's name.
        line: the traced line.
        edge: its edge (the pcurve in the arc length).
        height: the web's height.
        side: ``outside`` or ``inside``.
        base: the base's offset along the normal.
        span: (start, end) arc lengths from the line's start.

    Returns:
        The flat pattern (its base edge the developed base line).
    """
    s0 = edge.curve.FirstParameter()
    a, b = (0.0, edge.curve.LastParameter() - s0) if span is None else (float(span[0]), float(span[1]))

    def turn(s: FloatArray) -> FloatArray:
        return line_curvature(host, edge, line.family, s0 + a + np.asarray(s, dtype=float))

    def speed(s: FloatArray) -> FloatArray:
        return 1.0 - base * turn(s)

    # the turn resolved to round-off of a radian over the span (a nearly straight line's
    # curvature, 1e-6 of the face's, would else be resolved against its own round-off)
    return developed_strip(
        turn, speed, (0.0, b - a), height, side, name, breaks=line_kinks(line, a, b), turn_floor=1.0 / (b - a)
    )


def _stiffener_solid(host: HostSurface, line: CurvatureLine, edge: LineEdge, outline: list[tuple[float, float]]):
    """The profile's ``outline`` ((s, w) corners: s across along b = T x n, w along the normal
    from the face; a flat bar's four, a T's eight) carried along the line: each side the ruled
    face between its two corners' curves X + w n + s b (module docstring: every ruling moves
    along T), the ends planar (a closed line's stiffener is a ring: none); sewn, checked valid."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace as MakeFace
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakePolygon, BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing
    from OCP.gp import gp_Pnt

    from tubecad.occ_compat import as_shell

    nodes = line.sigma  # the edge's parameter is the arc length: its pieces turn by at most TURN
    t = np.concatenate(
        [np.ravel(np.linspace(nodes[:-1], nodes[1:], SAMPLES_PER_PIECE, endpoint=False), "F"), nodes[-1:]]
    )
    uv = np.array([[p.X(), p.Y()] for p in (edge.pcurve.Value(float(x)) for x in t)])
    points, tangents = _points_and_tangents(edge, t)
    normals = unit_normals(host, uv)
    across = np.cross(tangents, normals)
    across /= np.linalg.norm(across, axis=1, keepdims=True)
    closed = line.closed
    curves = [_fitted_edge(points + w * normals + s * across, t, closed) for s, w in outline]
    size = max(max(abs(w) for _, w in outline), max(abs(s) for s, _ in outline), 1.0)
    sewing = BRepBuilderAPI_Sewing(1e-6 * size)
    for i in range(len(outline)):  # each side, the base (last corner to first) included
        sewing.Add(BRepFill.Face_s(curves[i], curves[(i + 1) % len(outline)]))
    for end in () if closed else (0, -1):
        polygon = BRepBuilderAPI_MakePolygon()
        for s, w in outline:
            polygon.Add(gp_Pnt(*(float(x) for x in points[end] + w * normals[end] + s * across[end])))
        polygon.Close()
        sewing.Add(MakeFace(polygon.Wire(), True).Face())
    sewing.Perform()
    maker = BRepBuilderAPI_MakeSolid(as_shell(sewing.SewedShape()))
    solid = _outward(maker.Solid())
    if not BRepCheck_Analyzer(solid).IsValid():
        raise TubecadError("a stiffener's solid fails OCCT's validity check", key="height")
    return solid


def _points_and_tangents(edge: LineEdge, t: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The edge's points and unit tangents at its parameters ``t``."""
    from OCP.gp import gp_Pnt, gp_Vec

    points, tangents = np.empty((len(t), 3)), np.empty((len(t), 3))
    p, v = gp_Pnt(), gp_Vec()
    for i, x in enumerate(t):
        edge.curve.D1(float(x), p, v)
        points[i], tangents[i] = (p.X(), p.Y(), p.Z()), (v.X(), v.Y(), v.Z())
    return points, tangents / np.linalg.norm(tangents, axis=1, keepdims=True)


def _outward(solid):
    """``solid`` turned inside out if its volume is negative (its shell sewn inward)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(solid, props)
    if props.Mass() < 0:
        solid.Reverse()
    return solid


def _fitted_edge(points: FloatArray, t: FloatArray, closed: bool = False):
    """The edge through ``points`` at parameters ``t``: the C2 cubic interpolating spline
    (scipy's ``make_interp_spline``: not-a-knot, or periodic round a ``closed`` line, its last
    point its first) as an OCCT curve; its error between the points is O(h^4) in the pieces'
    turn."""
    from scipy.interpolate import make_interp_spline

    from tubecad.fitting.nurbs import occ_curve_3d

    if not closed:
        return BRepBuilderAPI_MakeEdge(occ_curve_3d(make_interp_spline(t, points, k=3))).Edge()
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt

    from tubecad.occ_compat import Array1OfInteger, Array1OfPnt, Array1OfReal

    points = points.copy()
    points[-1] = points[0]
    spline = make_interp_spline(t, points, k=3, bc_type="periodic")
    k, knots = spline.k, spline.t
    count = len(spline.c) - k  # scipy repeats the first k poles at the end
    poles, reals, mults = Array1OfPnt(1, count), Array1OfReal(1, count + 1), Array1OfInteger(1, count + 1)
    for i in range(count):
        poles.SetValue(i + 1, gp_Pnt(*(float(x) for x in spline.c[i])))
    for i in range(count + 1):
        reals.SetValue(i + 1, float(knots[k + i]))
        mults.SetValue(i + 1, 1)
    return BRepBuilderAPI_MakeEdge(Geom_BSplineCurve(poles, reals, mults, k, True)).Edge()
