"""The faces of a canal surface's wall panels (a radius law r(s); docs/MATH.md section 8),
for the one panel path :func:`tubecad.stiffeners.panels.split_into_panels`.

A canal panel between the rings s_a < s_b and the seam stringers chi_a -> chi_b
(counter-clockwise) is assembled from the wall build's own faces and edges, with new faces
that share them (nothing is sewn, nothing is cut):

- its outer and inner wall faces: the wall's patch faces between those rings and seams
  (:class:`~tubecad.brep.faces.PatchFaces`), as they are;
- a seam face per wall ring bay along each seam: the strip of surface normals from the
  inner to the outer surface along the stringer chi0 = const. The two stringer isolines
  are one B-spline in s of the canal spline with the same weights (the weights do not
  depend on the offset d), so the ruled surface between them, degree 1 across and
  parameterised by d - d_in, is exactly the strip of the fitted normals; its edges are the
  wall's two stringer edges and two straight radial segments (its isolines s = const);
- a cap at s_a and s_b: the piece of the normal cone through the inner and outer end
  circles (:func:`tubecad.brep.solids.normal_cone_face`; the plane where |r'| is below
  FLAT_CAP_SLOPE) between the wall's ring arcs and the two radial segments, which are
  generators of that cone.

Neighbouring panels share their seam faces and caps (one reversed), so the panels fit
together into the wall exactly. With a single seam a panel is its ring bay all round: the
wall's faces of those bays and two full normal-cone annuli. Round a closed axis the closing
ring is cut at the seams' start angles chi0 and at their end angles phi(chi0) (the Moebius
map's): the first bay's caps there run between start angles, the last bay's between end
angles, both on the closing circle as made at s0 (whose frame its shared edges use).
"""

from __future__ import annotations

import math

import build123d as bd
import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepGProp import BRepGProp_Face
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface, Geom_ConicalSurface
from OCP.Geom2d import Geom2d_Line
from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face, TopoDS_Vertex, TopoDS_Wire

from tubecad.brep import TubeBuild
from tubecad.brep import properties as props
from tubecad.brep.assembled import closed_solid, edge, plane_face
from tubecad.brep.faces import TOLERANCE
from tubecad.brep.solids import FLAT_CAP_SLOPE, normal_cone_face
from tubecad.core.errors import TubecadError
from tubecad.fitting.occ_arrays import integers, points_2d, reals, reals_2d
from tubecad.occ_compat import Array1OfPnt, as_face, downcast

#: points per radial segment at which its distance from the cap's cone is measured
RADIAL_GAP_SAMPLES = 9


class CanalWallEdges:
    """The seam faces, radial segments and cap pieces of a canal wall's panels, each made
    once (neighbouring panels share them): radial(k, j) from the inner to the outer
    surface at ring k on stringer j, seam_face(j, i) along stringer j between rings i and
    i + 1 (its normal towards stringer j + 1), cap(k, j_a, j_b) at ring k between stringers
    j_a -> j_b (its normal along +t)."""

    def __init__(self, build: TubeBuild):
        self.build = build
        self.outer, self.inner = build.patches
        # a canal wall's two surfaces, its thickness the distance of their levels (offsets d_out, d_in)
        self.outer_surface, self.inner_surface = build.surfaces
        self.thickness = float(self.outer_surface.level - self.inner_surface.level)
        self.n_s = len(build.layout.stringers_deg)
        # the face columns: the stringers and any C0 knot of the circle between them
        # (:func:`tubecad.brep.faces.face_columns`); stringer j is column self.column_of[j]
        columns_deg = self.outer.columns_deg or list(build.layout.stringers_deg)
        self.n_c = len(columns_deg)
        self.column_of = [columns_deg.index(float(a)) for a in build.layout.stringers_deg]
        self.last = len(build.layout.s_rings) - 1
        canal = self.outer_surface.tube
        # round a closed axis the closing ring (the first and the last, the same edges) is cut at
        # the stringers' start angles chi0 and at their end angles phi(chi0), the Moebius map's
        self._closing: dict[int, list[float]] = {}
        if canal.axis.closed and len(self.outer.rings[0]) > self.n_c:
            starts = np.radians(np.asarray(build.layout.stringers_deg, dtype=float))
            self._closing = {0: list(starts), self.last: list(np.asarray(canal.closing_angle(starts), dtype=float))}
        self._radial: dict[tuple[int, int], TopoDS_Edge] = {}
        self._seam: dict[tuple[int, int], TopoDS_Face] = {}
        self._cap: dict[tuple[int, int, int], TopoDS_Face] = {}
        self._annulus: dict[int, TopoDS_Face] = {}

    def panel(self, ia: int, ib: int, ja: int, jb: int) -> tuple[bd.Solid, float]:
        """The solid and outer area of the panel between the rings ia < ib and the stringers
        ja -> jb (ja < jb <= ja + n_s, indices past the last stringer wrap round; jb = ja + n_s:
        the ring bays all round, the wall's faces and two full normal-cone annuli)."""
        outer, inner, n_s = self.outer, self.inner, self.n_s
        if jb - ja == n_s:
            wall = [f for patches in (outer, inner) for row in patches.faces[ia:ib] for f in row]
            solid = closed_solid(wall + [as_face(self.annulus(ia).Reversed()), self.annulus(ib)])
            return bd.Solid(solid), props.faces_area([f for row in outer.faces[ia:ib] for f in row])
        columns = [c % self.n_c for c in range(self.column(ja), self.column(jb))]
        faces = [patches.faces[row][j] for patches in (outer, inner) for row in range(ia, ib) for j in columns]
        for row in range(ia, ib):
            faces += [self.seam_face(jb % n_s, row), as_face(self.seam_face(ja, row).Reversed())]
        faces += [as_face(self.cap(ia, ja, jb).Reversed()), self.cap(ib, ja, jb)]
        area = props.faces_area([outer.faces[row][j] for row in range(ia, ib) for j in columns])
        return bd.Solid(closed_solid(faces)), area

    def annulus(self, k: int) -> TopoDS_Face:
        """The whole normal cone (or plane) annulus at ring k between the inner and outer
        circles, its normal along +t."""
        if k not in self._annulus:
            s = self.ring_s(k)
            self._annulus[k] = normal_cone_face(
                s, self.inner_surface, self.inner.rings[k], self.outer_surface, self.outer.rings[k], outward=True
            )
        return self._annulus[k]

    def ring_s(self, k: int) -> float:
        """The s at which ring k's circle is made: its own, but s0 for the closing ring at either
        end of a closed axis, since its shared edges are parameterised in the frame at s0
        (r1(s0), not r1(s1), which the holonomy turns)."""
        return float(self.build.layout.s_rings[0 if k in self._closing else k])

    def column(self, j: int) -> int:
        """The face column where stringer j starts (j past the last stringer: a turn later)."""
        return self.column_of[j % self.n_s] + (j // self.n_s) * self.n_c

    def arc_index(self, k: int, j: int) -> int:
        """The index in ``rings[k]`` of the ring arc that starts at stringer j: j itself, but on
        the closing ring of a closed axis (cut at both the start and the end angles, in
        angular order) the arc starting at chi0_j on the first ring and at phi(chi0_j) on the
        last."""
        if k not in self._closing:
            return self.column(j)
        angle = self._closing[k][j] % (2.0 * math.pi)
        starts = [BRep_Tool.Range_s(e)[0] % (2.0 * math.pi) for e in self.outer.rings[k]]
        gaps = [abs(math.remainder(a - angle, 2.0 * math.pi)) for a in starts]
        best = int(np.argmin(gaps))
        if gaps[best] > 1e-7:
            raise TubecadError(
                f"no ring arc of the closing ring starts at stringer {j} ({math.degrees(angle):.6g} deg)"
            )
        return best

    def arcs(self, patches, k: int, ja: int, jb: int) -> tuple[list[TopoDS_Edge], list[float]]:
        """The ring arcs of ``patches`` at ring k from stringer ja to jb (jb > ja, indices past
        the last stringer wrap round), each with its lift: 2 pi where it comes after the
        circle's seam at u = 2 pi (its u = theta + 2 pi on the cap)."""
        ring = patches.rings[k]
        if k not in self._closing:
            columns = range(self.column(ja), self.column(jb))
            return [ring[c % self.n_c] for c in columns], [2.0 * math.pi if c >= self.n_c else 0.0 for c in columns]
        first, stop = self.arc_index(k, ja % self.n_s), self.arc_index(k, jb % self.n_s)
        count = (stop - first) % len(ring) or len(ring)
        indices = [first + i for i in range(count)]
        return [ring[i % len(ring)] for i in indices], [2.0 * math.pi if i >= len(ring) else 0.0 for i in indices]

    def vertex(self, patches, k: int, j: int) -> TopoDS_Vertex:
        """The wall's vertex on ring k and stringer j of ``patches``."""
        return TopExp.FirstVertex_s(patches.rings[k][self.arc_index(k, j)])

    def radial(self, k: int, j: int) -> TopoDS_Edge:
        """The straight segment from the inner to the outer vertex at ring k on stringer j,
        parameterised by d - d_in in [0, thickness] (the seam faces' isoline there)."""
        if (k, j) not in self._radial:
            v_in, v_out = self.vertex(self.inner, k, j), self.vertex(self.outer, k, j)
            p, q = BRep_Tool.Pnt_s(v_in), BRep_Tool.Pnt_s(v_out)
            poles = _points([p.Coord(), q.Coord()])
            line = Geom_BSplineCurve(poles, reals([0.0, self.thickness]), integers([2, 2]), 1)
            self._radial[k, j] = edge(line, v_in, v_out, 0.0, self.thickness)
        return self._radial[k, j]

    def seam_face(self, j: int, i: int) -> TopoDS_Face:
        """The ruled face along stringer j between rings i and i + 1, from the inner wall's
        stringer edge to the outer's: S(s, d - d_in), its normal S_s x S_d towards +chi."""
        if (j, i) not in self._seam:
            e_in, e_out = self.inner.stringers[j][i], self.outer.stringers[j][i]
            c_in = downcast(BRep_Tool.Curve_s(e_in, 0.0, 0.0), Geom_BSplineCurve)
            c_out = downcast(BRep_Tool.Curve_s(e_out, 0.0, 0.0), Geom_BSplineCurve)
            s0, s1 = BRep_Tool.Range_s(e_in)
            surface = _ruled(c_in, c_out, self.thickness)
            builder = BRep_Builder()
            face = TopoDS_Face()
            builder.MakeFace(face, surface, TOLERANCE)
            low, high = self.radial(i, j), self.radial(i + 1, j)
            builder.UpdateEdge(e_in, _line(0.0, 0.0, 1.0, 0.0), face, BRep_Tool.Tolerance_s(e_in))
            builder.UpdateEdge(e_out, _line(0.0, self.thickness, 1.0, 0.0), face, BRep_Tool.Tolerance_s(e_out))
            builder.UpdateEdge(low, _line(s0, 0.0, 0.0, 1.0), face, BRep_Tool.Tolerance_s(low))
            builder.UpdateEdge(high, _line(s1, 0.0, 0.0, 1.0), face, BRep_Tool.Tolerance_s(high))
            wire = TopoDS_Wire()
            builder.MakeWire(wire)  # counter-clockwise in (s, d)
            for e, orientation in (
                (e_in, TopAbs_FORWARD),
                (high, TopAbs_FORWARD),
                (e_out, TopAbs_REVERSED),
                (low, TopAbs_REVERSED),
            ):
                builder.Add(wire, e.Oriented(orientation))
            wire.Closed(True)
            builder.Add(face, wire)
            self._seam[j, i] = face
        return self._seam[j, i]

    def cap(self, k: int, ja: int, jb: int) -> TopoDS_Face:
        """The piece of the normal cone at ring k between the stringers ja -> jb (jb > ja,
        indices past the last stringer wrap round), its normal along +t."""
        if (k, ja, jb) not in self._cap:
            self._cap[k, ja, jb] = self._make_cap(k, ja, jb)
        return self._cap[k, ja, jb]

    def _make_cap(self, k: int, ja: int, jb: int) -> TopoDS_Face:
        s = self.ring_s(k)
        n_s = self.n_s
        arcs_in, lifts = self.arcs(self.inner, k, ja, jb)  # wrapped arcs: u = theta + 2 pi
        arcs_out, _ = self.arcs(self.outer, k, ja, jb)
        radial_a, radial_b = self.radial(k, ja), self.radial(k, jb % n_s)
        high, low = self.outer_surface, self.inner_surface
        centre, _, t, x_dir, _ = high.ring(s)
        dr = float(high.tube.radius_law.dr(np.array([s]))[0])
        if abs(dr) <= FLAT_CAP_SLOPE:  # the plane annulus' piece, counter-clockwise about +t
            loop = (
                [(e, True) for e in arcs_out]
                + [(radial_b, False)]
                + [(e, False) for e in arcs_in[::-1]]
                + [(radial_a, True)]
            )
            return plane_face(centre, t, x_dir, [loop])
        c_lo, radius_lo, _, _, _ = low.ring(s)
        q = math.sqrt(1.0 - dr * dr)
        sign = -math.copysign(1.0, dr)
        cone = Geom_ConicalSurface(
            gp_Ax3(gp_Pnt(*map(float, c_lo)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))),
            sign * math.atan2(q, abs(dr)),
            radius_lo,
        )
        v_high = sign * self.thickness  # the outer circle's v (distance along the generators from the inner)
        builder = BRep_Builder()
        face = TopoDS_Face()
        builder.MakeFace(face, cone, TOLERANCE)
        for arcs, v in ((arcs_in, 0.0), (arcs_out, v_high)):
            for e, lift in zip(arcs, lifts):
                builder.UpdateEdge(e, _line(lift, v, 1.0, 0.0), face, BRep_Tool.Tolerance_s(e))
        theta_a = BRep_Tool.Range_s(arcs_in[0])[0] + lifts[0]
        theta_b = BRep_Tool.Range_s(arcs_in[-1])[1] + lifts[-1]
        for e, theta in ((radial_a, theta_a), (radial_b, theta_b)):
            pcurve = _line(theta, 0.0, 0.0, sign)  # v = sign (d - d_in)
            builder.UpdateEdge(
                e, pcurve, face, max(BRep_Tool.Tolerance_s(e), _gap(e, cone, theta, sign, self.thickness))
            )
        # counter-clockwise in (u, v): the lower circle along +u, up the generator at b, back along the upper one
        (lower, upper), up = ((arcs_in, arcs_out), True) if v_high > 0 else ((arcs_out, arcs_in), False)
        wire = TopoDS_Wire()
        builder.MakeWire(wire)
        for e, orientation in (
            [(e, TopAbs_FORWARD) for e in lower]
            + [(radial_b, TopAbs_FORWARD if up else TopAbs_REVERSED)]
            + [(e, TopAbs_REVERSED) for e in upper[::-1]]
            + [(radial_a, TopAbs_REVERSED if up else TopAbs_FORWARD)]
        ):
            builder.Add(wire, e.Oriented(orientation))
        wire.Closed(True)
        builder.Add(face, wire)
        point, normal = gp_Pnt(), gp_Vec()
        BRepGProp_Face(face).Normal(0.5 * (theta_a + theta_b), 0.5 * v_high, point, normal)
        return face if normal.Dot(gp_Vec(*map(float, t))) > 0 else as_face(face.Reversed())


def _ruled(c_in: Geom_BSplineCurve, c_out: Geom_BSplineCurve, thickness: float) -> Geom_BSplineSurface:
    """The ruled surface S(s, d) from ``c_in`` (d = 0) to ``c_out`` (d = thickness): two
    rational curves on the same knots and weights, so degree 1 across with those weights."""
    n = c_in.NbPoles()
    if c_out.NbPoles() != n or c_in.NbKnots() != c_out.NbKnots():
        raise TubecadError(
            "the wall's inner and outer stringer curves differ in their knots: no seam face between them"
        )
    poles = np.array([[c_in.Pole(i).Coord(), c_out.Pole(i).Coord()] for i in range(1, n + 1)])
    weights = np.array([[c_in.Weight(i), c_out.Weight(i)] for i in range(1, n + 1)])
    if np.abs(weights[:, 0] - weights[:, 1]).max() > 1e-12 * weights.max():
        raise TubecadError(
            "the wall's inner and outer stringer curves differ in their weights: no seam face between them"
        )
    weights[:, 1] = weights[:, 0]
    knots = [c_in.Knot(i) for i in range(1, c_in.NbKnots() + 1)]
    mults = [c_in.Multiplicity(i) for i in range(1, c_in.NbKnots() + 1)]
    return Geom_BSplineSurface(
        points_2d(poles),
        reals_2d(weights),
        reals(knots),
        reals([0.0, thickness]),
        integers(mults),
        integers([2, 2]),
        c_in.Degree(),
        1,
    )


def _gap(e: TopoDS_Edge, cone: Geom_ConicalSurface, theta: float, sign: float, thickness: float) -> float:
    """Twice the largest distance of the radial segment ``e`` from the cone's generator at
    ``theta`` through its pcurve (v = sign x the parameter), at least TOLERANCE."""
    curve = BRep_Tool.Curve_s(e, 0.0, 0.0)
    gap = 0.0
    for x in np.linspace(0.0, thickness, RADIAL_GAP_SAMPLES):
        gap = max(gap, curve.Value(float(x)).Distance(cone.Value(theta, sign * float(x))))
    return max(TOLERANCE, 2.0 * gap)


def _points(points) -> Array1OfPnt:
    out = Array1OfPnt(1, len(points))
    for i, p in enumerate(points):
        out.SetValue(i + 1, gp_Pnt(*map(float, p)))
    return out


def _line(x: float, y: float, dx: float, dy: float) -> Geom2d_Line:
    return Geom2d_Line(gp_Pnt2d(x, y), gp_Dir2d(dx, dy))
