"""Canal surfaces as OCCT B-reps (issue 12): exact-section NURBS, shells, capped solids and
walls with conical caps (docs/MATH.md section 8).

Expected values come from closed forms written here (a cone's equation, frustum volumes,
Pappus' theorem for a cone wall's rectangular section, a circle fitted to a Dupin
cyclide's stringers) or from the canal surface's own independent quadrature, and the B-rep
is measured by sampling its OCCT faces and edges, never from what the builder reports.
"""

import math

import numpy as np
import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepTools import BRepTools
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cone
from OCP.gp import gp_Pnt, gp_Vec

from tubecad import Helix, NaturalAxis, ParameterError, ParametricAxis
from tubecad.brep import NetLayout, build_tube_shell, build_tube_solid, build_wall_solid
from tubecad.brep import properties as props
from tubecad.brep.measure import tube_faces
from tubecad.brep.solids import exact_volume
from tubecad.fitting import TubeSurface, measure_surface
from tubecad.fitting.canal_section import (
    CanalSectionSurface,
    canal_functions,
    fit_canal,
)
from tubecad.surface import CanalSurface, CurvatureLineTube

#: BOPAlgo_ArgumentAnalyzer without its (slow) self-intersection mode
CHEAP_MODES = tuple(mode for mode in props.ANALYZER_MODES if mode != "SelfInterMode")


def face_samples(face, nu=6, nv=12):
    """Points, d/du, d/dv of a face's own surface on a grid inside its UV bounds (off knots),
    and the (u, v) of each sample."""
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    uv = [(u0 + (i + 0.37) * (u1 - u0) / nu, v0 + (j + 0.29) * (v1 - v0) / nv) for i in range(nu) for j in range(nv)]
    out = np.empty((3, len(uv), 3))
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    for k, (u, v) in enumerate(uv):
        surface.D1(u, v, p, du, dv)
        out[:, k] = [(p.X(), p.Y(), p.Z()), (du.X(), du.Y(), du.Z()), (dv.X(), dv.Y(), dv.Z())]
    return out[0], out[1], out[2], np.array(uv)


def abs_cos(a, b):
    return np.abs(np.einsum("ij,ij->i", a, b)) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))


def sphere_distance(canal, points, s_guess, offset=0.0):
    """The distance of ``points`` from the envelope of the spheres (c(s), r(s) + offset), as
    min over s of |p - c(s)| - r(s) - offset: Newton on its derivative from ``s_guess``
    (no stringer angle, no Moebius map: only the axis and the law)."""
    axis, law = canal.axis, canal.radius_law
    s0, s1 = canal.span

    def slope(s):
        d = points - axis.position(s)
        return -np.einsum("ij,ij->i", d, axis.rotation_minimising_frame(s)[0]) / np.linalg.norm(d, axis=1) - law.dr(s)

    s, h = np.asarray(s_guess, dtype=float).copy(), 1e-5
    for _ in range(8):
        g = slope(s)
        s = np.clip(s - g * 2 * h / (slope(np.clip(s + h, s0, s1)) - slope(np.clip(s - h, s0, s1))), s0, s1)
    return np.linalg.norm(points - axis.position(s), axis=1) - law.r(s) - offset


# --- a straight axis with r = r0 + m s: cones ---------------------------------------------------
R0, SLOPE, LENGTH = 2.0, 0.3, 40.0
Q = math.sqrt(1.0 - SLOPE**2)


@pytest.fixture(scope="module")
def cone():
    return CanalSurface(NaturalAxis("0", "0", (0.0, LENGTH)), f"{R0} + {SLOPE} * s")  # about the x axis


def frustum(r_a, r_b, h):
    return math.pi * h * (r_a * r_a + r_a * r_b + r_b * r_b) / 3.0


def test_the_cone_solid_lies_on_the_cone_and_holds_the_frustum(cone):
    build = build_tube_solid(cone, NetLayout.equal(cone, 4, 3))
    shape = build.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert isinstance(build.surfaces[0], CanalSectionSurface)
    # every face sample on the cone with apex x = -r0/m, half-angle a: sin a = m
    apex, sin_a = -R0 / SLOPE, SLOPE
    for face in tube_faces(shape):
        p, _, _, _ = face_samples(face)
        rho = np.hypot(p[:, 1], p[:, 2])
        assert np.abs(rho * Q - (p[:, 0] - apex) * sin_a).max() <= 1e-8
    # between the end circles (radius r q, in the planes x = s - r r'): the frustum
    r_end = R0 + SLOPE * LENGTH
    h = (LENGTH - r_end * SLOPE) - (0.0 - R0 * SLOPE)
    assert props.volume(shape) == pytest.approx(frustum(R0 * Q, r_end * Q, h), rel=1e-9)
    assert props.area(shape) == pytest.approx(
        math.pi * ((R0 * Q) ** 2 + (r_end * Q) ** 2 + Q * (R0 + r_end) * math.hypot(h, (r_end - R0) * Q)), rel=1e-9
    )
    assert props.analyzer_findings(shape, CHEAP_MODES) == {}


@pytest.mark.parametrize(
    "side, offsets", [("centered", (-0.25, 0.25)), ("inside", (-0.5, 0.0)), ("outside", (0.0, 0.5))]
)
def test_the_cone_wall_is_a_revolved_rectangle(cone, side, offsets):
    """The wall between the cones of r + d_in and r + d_out, capped by the cones of the sphere
    normals at the ends, is the revolution of a rectangle (the caps are normal to both
    surfaces): Pappus gives 2 pi x its area x its centroid's distance from the axis."""
    build = build_wall_solid(cone, 0.5, side, NetLayout.equal(cone, 3, 4))
    shape = build.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.analyzer_findings(shape, CHEAP_MODES) == {}
    r_end = R0 + SLOPE * LENGTH
    p0, p1 = np.array([-R0 * SLOPE, R0 * Q]), np.array([LENGTH - r_end * SLOPE, r_end * Q])  # (x, rho) on r
    centroid = 0.5 * (p0[1] + p1[1]) + 0.5 * sum(offsets) * Q  # the normal (-r', q) moves rho by q per unit
    pappus = 2 * math.pi * np.linalg.norm(p1 - p0) * (offsets[1] - offsets[0]) * centroid
    assert props.volume(shape) == pytest.approx(pappus, rel=1e-9)
    assert exact_volume(build, cone) == pytest.approx(pappus, rel=1e-9)
    # the same from the two offsets' own volumes (frustums, and CanalSurface.volume's quadrature)
    # with the cap frustums between their end circles: added at the end (r' > 0: the outer
    # end circle lies behind the inner one), cut off at the start
    d_in, d_out = offsets

    def cut(r):
        return frustum((r + d_in) * Q, (r + d_out) * Q, SLOPE * (d_out - d_in))

    ends = cut(r_end) - cut(R0)
    outer, inner = (cone.offset(d) for d in (d_out, d_in))
    assert outer.volume - inner.volume + ends == pytest.approx(pappus, rel=1e-9)
    assert [s.tube.radius_law.r(3.0) for s in build.surfaces] == pytest.approx([R0 + 0.9 + d_out, R0 + 0.9 + d_in])
    assert build.radii == pytest.approx([R0 + SLOPE * LENGTH / 2 + d for d in (d_out, d_in)], rel=1e-12)


def test_the_fit_of_a_table_law_keeps_its_knots():
    """A table law is C2 (r' only C1 at its rows): its knots are the spline's, of multiplicity
    degree - 1, and the fit holds across them."""
    canal = CanalSurface(NaturalAxis("0.02", "0.01", (0.0, 60.0)), [[0, 3], [20, 3.6], [45, 3.1], [60, 3.3]])
    fit = fit_canal(canal, (0.0,))
    knots = fit.spline.t
    for s in (20.0, 45.0):
        assert np.count_nonzero(knots == s) == fit.degree - 1
    assert fit.position_bound <= 0.5e-8 and fit.orthogonality_bound <= 0.5e-9
    # the fitted 21-vector reproduces the exact one between the samples
    s = np.linspace(0.0, 60.0, 997)
    assert np.abs(fit.spline(s) - canal_functions(canal, s)).max() < 1e-8


# --- the ring Dupin cyclide (open): all its curvature lines are circles ---------------------------
A, B, C, MU = 10.0, 8.0, 6.0, 8.0


def circle_fit(points):
    """(largest distance from the fitted circle, its radius): the plane by SVD, then the circle
    in the plane by linear least squares."""
    centre = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centre)
    off_plane = np.abs((points - centre) @ vt[2]).max()
    xy = (points - centre) @ vt[:2].T
    sol = np.linalg.lstsq(np.c_[2 * xy, np.ones(len(xy))], (xy**2).sum(axis=1), rcond=None)[0]
    radius = math.sqrt(sol[2] + sol[0] ** 2 + sol[1] ** 2)
    return max(off_plane, np.abs(np.linalg.norm(xy - sol[:2], axis=1) - radius).max()), radius


@pytest.mark.slow
def test_a_dupin_cyclide_wall_has_circles_for_stringer_edges():
    axis = ParametricAxis(lambda t: np.stack([A * np.cos(t), B * np.sin(t), 0.0 * t], axis=-1), (0.2, 5.8))
    # its ends come close (a tube of the largest radius 14 would self-intersect), not the cyclide
    cyclide = CanalSurface(axis, lambda s: MU - (C / A) * axis.position(s)[..., 0], allow_irregular=True)
    assert cyclide.regularity.locally_regular
    # at the default tolerance 1e-8 the stringers are circles to ~1.3e-10; 1e-9 gives ~4e-12
    build = build_wall_solid(cyclide, 0.4, "centered", NetLayout.equal(cyclide, 5, 6), tolerance=1e-9)
    shape = build.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.analyzer_findings(shape, CHEAP_MODES) == {}
    assert props.volume(shape) == pytest.approx(exact_volume(build, cyclide), rel=1e-9)
    for patches in build.patches:
        for column in patches.stringers:  # every stringer, all its edges: one circle
            points = np.concatenate([sample_edge(edge) for edge in column])
            residual, radius = circle_fit(points)
            assert residual <= 1e-10 and 0.1 < radius < 2 * A
            for edge in column:  # each edge on its own too (a short arc: a weaker fit)
                assert circle_fit(sample_edge(edge, 15))[0] <= 1e-10
        for ring in patches.rings:
            assert all(BRepAdaptor_Curve(edge).GetType().name.endswith("Circle") for edge in ring)
    for surface in build.surfaces:  # rational: every weight positive
        occ = surface.surface
        weights = [occ.Weight(i, j) for i in range(1, occ.NbUPoles() + 1) for j in range(1, occ.NbVPoles() + 1)]
        assert min(weights) > 0.0
    m = measure_surface(build.surfaces[0], 24, 400)
    assert m.max_deviation <= 1e-9 and m.max_orthogonality_error <= 1e-10


def sample_edge(edge, n=9):
    curve = BRepAdaptor_Curve(edge)
    ts = np.linspace(curve.FirstParameter(), curve.LastParameter(), n)
    return np.array([[curve.Value(t).X(), curve.Value(t).Y(), curve.Value(t).Z()] for t in ts])


# --- a tapered helix -----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def helical():
    return CanalSurface(Helix(0.02, 30.0, (0.0, 200.0)), "3 + 0.5*sin(s/20)")


@pytest.mark.slow
def test_a_tapered_helix_wall_is_accurate_and_orthogonal(helical):
    build = build_wall_solid(helical, 0.5, "centered", NetLayout.equal(helical, 6, 8))
    shape = build.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.analyzer_findings(shape, CHEAP_MODES) == {}
    assert props.volume(shape) == pytest.approx(exact_volume(build, helical), rel=1e-9)
    worst = {0.25: [0.0, 0.0], -0.25: [0.0, 0.0]}
    kinds = [(face.wrapped, BRepAdaptor_Surface(face.wrapped).GetType()) for face in shape.faces()]
    assert sum(kind == GeomAbs_Cone for _, kind in kinds) == 2  # the caps: r' = 0.025 and 0.025 cos 10 at the ends
    assert len(list(tube_faces(shape))) == 2 * 5 * 8  # the measure's tube faces: not the conical caps
    faces = [face for face, kind in kinds if kind == GeomAbs_BSplineSurface]
    assert len(faces) == 2 * 5 * 8
    for face in faces:
        p, du, dv, uv = face_samples(face, 8, 16)
        # the distance from the envelope of the spheres of r -+ d (nearest of the two)
        d = min(worst, key=lambda off: np.abs(np.median(sphere_distance(helical, p, uv[:, 1], off))))
        worst[d][0] = max(worst[d][0], np.abs(sphere_distance(helical, p, uv[:, 1], d)).max())
        worst[d][1] = max(worst[d][1], abs_cos(du, dv).max())
    for deviation, cos in worst.values():
        assert 0 < deviation <= 1e-8 and cos <= 1e-9
    # the rings are the exact characteristic circles, the faces' u-isolines the exact stringers
    for surface, patches in zip(build.surfaces, build.patches):
        exact = surface.tube
        for s, ring in zip(build.layout.s_rings, patches.rings):
            centre, radius, t = (x[0] for x in exact.circle(np.array([s])))
            points = np.concatenate([sample_edge(edge) for edge in ring])
            assert np.abs(np.linalg.norm(points - centre, axis=1) - radius).max() < 1e-12 * radius + 1e-13
            assert np.abs((points - centre) @ t).max() < 1e-12
        for angle, column in zip(build.layout.stringers_deg, patches.stringers):
            for edge in column:
                curve = BRepAdaptor_Curve(edge)
                s = np.linspace(curve.FirstParameter(), curve.LastParameter(), 7)
                exact_points = exact.points(math.radians(angle), s)
                assert np.abs(sample_edge(edge, 7) - exact_points).max() <= 1e-8


def test_a_tapered_helix_shell_and_solid(helical):
    layout = NetLayout.explicit(helical, [55.0, 130.0], [15.0, 100.0, 250.0])
    shell = build_tube_shell(helical, layout)
    assert props.is_valid(shell.shape) and props.free_edges(shell.shape) == 2 * 3  # the two end rings
    solid = build_tube_solid(helical, layout)
    assert props.is_valid(solid.shape) and props.free_edges(solid.shape) == 0
    swept = helical.measures()[1]  # the surface's volume with its end discs (quadrature)
    assert props.volume(solid.shape) == pytest.approx(swept, rel=1e-9)
    assert exact_volume(solid, helical) == pytest.approx(swept, rel=1e-15)
    m = measure_surface(solid.surfaces[0], 24, 1000)
    assert m.max_deviation <= 1e-8 and m.max_orthogonality_error <= 1e-9
    # radii: the arc-length mean of r = 3 + 0.5 sin(s / 20) over [0, 200]
    assert solid.radii == pytest.approx([3.0 + 0.05 * (1.0 - math.cos(10.0))], rel=1e-12)


# --- what stays the tube's, and what is refused ------------------------------------------------------
def test_a_constant_law_is_built_as_the_tube():
    axis = Helix(0.02, 30.0, (0.0, 100.0))
    layout = NetLayout.equal(CurvatureLineTube(axis, 3.0), 3, 4)
    canal, tube = (
        build_tube_solid(CanalSurface(axis, 3.0), layout),
        build_tube_solid(CurvatureLineTube(axis, 3.0), layout),
    )
    assert type(canal.surfaces[0]) is TubeSurface and canal.radii == tube.radii == [3.0]
    assert np.array_equal(canal.frame.spline.c, tube.frame.spline.c)
    assert props.volume(canal.shape) == props.volume(tube.shape)


def test_the_whole_ring_cyclide_is_a_closed_canal_solid():
    # round the whole ellipse the cyclide closes: a solid bounded by one closed shell, whose
    # volume is pi Int (r q)^2 (q^2 - r r'') ds (the characteristic discs swept round),
    # integrated here by quad in t from the ellipse and r = MU - C cos t by hand
    from scipy.integrate import quad

    axis = ParametricAxis(lambda t: np.stack([A * np.cos(t), B * np.sin(t), 0.0 * t], axis=-1), (0.0, 2 * math.pi))
    cyclide = CanalSurface(axis, lambda s: MU - (C / A) * axis.position(s)[..., 0])
    assert axis.closed

    def integrand(t: float) -> float:
        v = math.hypot(A * math.sin(t), B * math.cos(t))  # ds/dt
        dv = (A * A - B * B) * math.sin(t) * math.cos(t) / v
        r, dr = MU - C * math.cos(t), C * math.sin(t) / v  # dr/ds
        ddr = (C * math.cos(t) * v - C * math.sin(t) * dv) / v**3
        q2 = 1.0 - dr * dr
        return math.pi * r * r * q2 * (q2 - r * ddr) * v

    exact = quad(integrand, 0.0, 2 * math.pi, epsabs=0.0, epsrel=1e-13, limit=200)[0]
    solid = build_tube_solid(cyclide, NetLayout.equal(cyclide, 9, 4))
    assert props.is_valid(solid.shape) and props.free_edges(solid.shape) == 0
    assert props.volume(solid.shape) == pytest.approx(exact, rel=1e-10)


def test_a_wall_too_thick_for_the_smallest_radius_is_refused(helical):
    with pytest.raises(ParameterError, match=r"thickness must be < 5 .* smallest r is 2\.5"):
        build_wall_solid(helical, 5.2, "centered")
