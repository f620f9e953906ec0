"""Canal surfaces on closed axes: the radius law closes (a periodic law; a table whose last
r repeats the first is the periodic cubic spline), the stringers come back to the closing
ring moved by a Moebius map of the circle, phi(chi0) = chi(chi0, s1) + h, and the shell,
solid and wall are valid closed B-reps (no caps, the wall's inner shell its cavity).

Independent facts: the volume a closed canal surface encloses is that of its
characteristic discs swept round the loop, pi Int (r q)^2 (q^2 - r r'') ds, integrated here
by scipy's quad from the closed-form law (for a constant r it is pi r^2 L, the torus'
2 pi^2 R r^2 on a circle); the stringers' ends come from integrating their own equation
d chi / ds = (r' / q) (k2 cos chi - k1 sin chi) by scipy's solve_ivp (not the code's
Moebius matrix); a periodic table is compared with scipy's periodic CubicSpline.
"""

import math

import build123d as bd
import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.interpolate import CubicSpline
from shared.closed_canal import CLOSED_TREFOIL
from shared.closed_tubes import TWO_PI, trefoil

from tubecad.brep import NetLayout, build_tube_shell, build_tube_solid, build_wall_solid
from tubecad.brep import properties as props
from tubecad.brep.solids import exact_volume
from tubecad.curves.parametric import ParametricAxis
from tubecad.surface import CanalSurface, CurvatureLineTube, tube_or_canal
from tubecad.surface.checks import envelope_distance

#: every check of OCCT's pre-boolean analyzer but the self-intersection one (minutes on the
#: trefoil's walls; the torus-like wall below gets every check)
CHECKS = tuple(mode for mode in props.ANALYZER_MODES if mode != "SelfInterMode")
R_TORUS, R0, AMPLITUDE = 10.0, 2.0, 0.5  # circle axis; r = R0 + AMPLITUDE cos(2 pi s / L)
T_R0, T_AMPLITUDE = 0.3, 0.05  # the trefoil's law


def circle(t: np.ndarray) -> np.ndarray:
    return np.stack([R_TORUS * np.cos(t), R_TORUS * np.sin(t), 0.0 * t], axis=-1)


def cosine_law(r0: float, a: float, length: float):
    """r, r', r'' of r0 + a cos(2 pi s / L), by hand."""
    w = TWO_PI / length
    return (
        lambda s: r0 + a * math.cos(w * s),
        lambda s: -a * w * math.sin(w * s),
        lambda s: -a * w * w * math.cos(w * s),
    )


def swept_volume(r, dr, ddr, length: float, offset: float = 0.0) -> float:
    """pi Int (R q)^2 (q^2 - R r'') ds round the loop, R = r + offset, by adaptive quadrature."""

    def integrand(s: float) -> float:
        big, q2 = r(s) + offset, 1.0 - dr(s) ** 2
        return math.pi * big * big * q2 * (q2 - big * ddr(s))

    return quad(integrand, 0.0, length, limit=400, epsabs=0.0, epsrel=1e-13)[0]


def stringer_ends(canal: CanalSurface, dr, chi0: np.ndarray) -> np.ndarray:
    """chi(s1) of the stringers that start at chi0, by solve_ivp on their own equation."""
    axis = canal.axis

    def rhs(s: float, chi: np.ndarray) -> np.ndarray:
        k1, k2 = (float(np.asarray(k).ravel()[0]) for k in axis.normal_development(np.array([s])))
        slope = dr(s)
        return slope / math.sqrt(1.0 - slope * slope) * (k2 * np.cos(chi) - k1 * np.sin(chi))

    sol = solve_ivp(rhs, axis.span, chi0, method="DOP853", rtol=1e-12, atol=1e-13)
    assert sol.success
    return sol.y[:, -1]


@pytest.fixture(scope="module")
def torus_canal() -> CanalSurface:
    axis = ParametricAxis(circle, (0.0, TWO_PI))
    assert axis.closed and abs(axis.holonomy) < 1e-12
    return CanalSurface(axis, f"{R0!r} + {AMPLITUDE!r} * cos(2 * pi * s / {axis.length!r})")


@pytest.fixture(scope="module")
def trefoil_canal() -> CanalSurface:
    axis = ParametricAxis(trefoil, (0.0, TWO_PI))
    assert axis.closed and abs(axis.holonomy) > 1.0
    return CanalSurface(axis, f"{T_R0!r} + {T_AMPLITUDE!r} * cos(2 * pi * s / {axis.length!r})")


def test_a_closed_law_and_a_periodic_table(torus_canal):
    axis = torus_canal.axis
    L = axis.length
    law = torus_canal.radius_law
    assert law.periodic and "periodic" in law.describe()
    rows = [[0.0, 2.0], [0.2 * L, 2.6], [0.5 * L, 1.7], [0.8 * L, 2.2], [L, 2.0]]
    table = tube_or_canal(axis, rows)
    assert isinstance(table, CanalSurface) and "periodic cubic spline" in table.radius_law.describe()["interpolation"]
    reference = CubicSpline(np.array(rows)[:, 0], np.array(rows)[:, 1], bc_type="periodic")
    s = np.linspace(0.0, L, 101)
    for n, got in enumerate((table.radius_law.r, table.radius_law.dr, table.radius_law.ddr)):
        assert np.abs(got(s) - reference(s, n)).max() < 1e-12
        ends = got(np.array([0.0, L]))
        assert abs(ends[1] - ends[0]) < 1e-12  # C2 round the loop
    # the periodic table's closed solid: valid, watertight, its volume the discs' swept volume
    solid = build_tube_solid(table, NetLayout.equal(table, 7, 4))
    assert props.is_valid(solid.shape) and props.free_edges(solid.shape) == 0
    expected = swept_volume(
        lambda x: float(reference(x)), lambda x: float(reference(x, 1)), lambda x: float(reference(x, 2)), L
    )
    assert props.volume(solid.shape) == pytest.approx(expected, rel=1e-9)
    # a constant radius on a closed axis stays today's tube
    assert isinstance(tube_or_canal(axis, 2.0), CurvatureLineTube)


def test_the_closing_map(trefoil_canal):
    """phi(chi0) = chi(chi0, s1) + h: chi0 + h for a constant law; otherwise from the
    stringers' own equation, and increasing (the stringers' ends keep their order)."""
    axis = trefoil_canal.axis
    chi0 = np.linspace(0.0, TWO_PI, 12, endpoint=False)
    constant = CanalSurface(axis, 0.3)
    assert np.abs(constant.closing_angle(chi0) - (chi0 + axis.holonomy)).max() < 1e-15
    _, dr, _ = cosine_law(T_R0, T_AMPLITUDE, axis.length)
    phi = trefoil_canal.closing_angle(chi0)
    assert np.abs(phi - (stringer_ends(trefoil_canal, dr, chi0) + axis.holonomy)).max() < 1e-9
    assert np.abs(phi - chi0 - axis.holonomy).max() > 1e-3  # moved, not only turned
    dense = np.linspace(0.0, TWO_PI, 721)
    assert np.all(np.diff(trefoil_canal.closing_angle(dense)) > 0)


@pytest.mark.slow
def test_the_torus_like_canal_wall(torus_canal):
    """(a) A circle axis, r = 2 + 0.5 cos(2 pi s / L): the closed shell, solid and wall."""
    L = torus_canal.length
    r, dr, ddr = cosine_law(R0, AMPLITUDE, L)
    assert swept_volume(lambda s: R0, lambda s: 0.0, lambda s: 0.0, L) == pytest.approx(
        2 * math.pi**2 * R_TORUS * R0**2, rel=1e-13
    )
    layout = NetLayout.equal(torus_canal, 8, 4)
    shell = build_tube_shell(torus_canal, layout).shape
    assert props.is_valid(shell) and props.free_edges(shell) == 0 and shell.wrapped.Closed()
    solid = build_tube_solid(torus_canal, layout)
    assert props.is_valid(solid.shape) and props.free_edges(solid.shape) == 0
    assert props.count(solid.shape, "face") == 8 * 4  # no caps
    assert props.volume(solid.shape) == pytest.approx(swept_volume(r, dr, ddr, L), rel=1e-9)
    thickness = 0.2
    wall = build_wall_solid(torus_canal, thickness, "centered", layout)
    shape = wall.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.analyzer_findings(shape) == {}
    expected = swept_volume(r, dr, ddr, L, 0.1) - swept_volume(r, dr, ddr, L, -0.1)
    assert props.volume(shape) == pytest.approx(expected, rel=1e-9)
    assert exact_volume(wall, torus_canal) == pytest.approx(expected, rel=1e-11)


@pytest.mark.slow
def test_the_trefoil_canal_wall(trefoil_canal):
    """(b) The whole trefoil knot with a periodic law: valid and watertight, every stringer
    ends on the closing ring at phi(a_j) (the exact circle point there, phi from the
    stringers' own equation), and the faces within the fit tolerance of the envelope."""
    axis = trefoil_canal.axis
    L, h = axis.length, axis.holonomy
    r, dr, ddr = cosine_law(T_R0, T_AMPLITUDE, L)
    rings, stringers, thickness = 8, 4, 0.04  # eight distinct rings round the loop
    layout = NetLayout.equal(trefoil_canal, rings, stringers)
    wall = build_wall_solid(trefoil_canal, thickness, "centered", layout)
    shape = wall.shape
    assert props.is_valid(shape) and props.free_edges(shape) == 0
    assert props.analyzer_findings(shape, CHECKS) == {}
    # the closing ring is cut at the stringers' starts and their (moved) ends, on both surfaces
    assert props.count(shape, "vertex") == 2 * ((rings - 1) * stringers + 2 * stringers)
    expected = swept_volume(r, dr, ddr, L, 0.02) - swept_volume(r, dr, ddr, L, -0.02)
    assert props.volume(shape) == pytest.approx(expected, rel=1e-9)

    start = axis.at(np.array([0.0]))
    c0, t0, r1, r2 = start.position[0], start.t[0], start.r1[0], start.r2[0]
    chi0 = np.radians(layout.stringers_deg)
    ends = stringer_ends(trefoil_canal, dr, chi0) + h
    for surface, offset in enumerate((0.02, -0.02)):
        radius, slope = r(0.0) + offset, dr(0.0)
        centre, size = c0 - radius * slope * t0, radius * math.sqrt(1.0 - slope * slope)
        for wire, phi in zip(wall.stringer_wires(surface), ends):
            end = np.array(tuple(wire.edges()[-1].position_at(1.0)))
            exact = centre + size * (math.cos(phi) * r1 + math.sin(phi) * r2)
            assert np.linalg.norm(end - exact) < 1e-8
    # the fit: measured bound and the faces' points on the exact envelopes
    assert wall.frame.position_bound <= 0.5 * wall.tolerance
    for surface, offset in enumerate((0.02, -0.02)):
        exact = trefoil_canal.offset(offset)
        points = np.array(
            [
                tuple(face.position_at(u, v))
                for face in [f for row in wall.face_grid(surface) for f in row]
                for u in (0.1, 0.5, 0.9)
                for v in (0.1, 0.5, 0.9)
            ]
        )
        distance, _ = envelope_distance(exact, points)
        assert np.abs(distance).max() < wall.tolerance


@pytest.mark.slow
@pytest.mark.parametrize("seams", [[0], [0, 2], [0, 1, 2, 3]])
def test_panels_of_a_closed_canal_wall_fit_together_into_it(tmp_path, seams):
    """The closed trefoil's canal wall (r = 8 + 0.02 x) split into panels: the last ring bay's
    panels end on the closing ring at the seams' end angles (the Moebius map's), the first
    bay's start there at their start angles; every panel a valid solid passing the quick
    pre-boolean checks, their volumes adding up to the wall's and their outer areas to its
    outer surface's, ring bay by ring bay to the bay all round (one seam)."""
    from tubecad.spec.parse import load_spec
    from tubecad.stiffeners.panels import split_into_panels

    spec = tmp_path / "spec.toml"
    spec.write_text(CLOSED_TREFOIL.format(radius='"8 + 0.02 * x"'))
    canal = load_spec(spec).tube
    wall = build_wall_solid(canal, 1.0, layout=NetLayout.equal(canal, 4, 4))
    panels = split_into_panels(wall, seams)
    assert len(panels) == 4 * len(seams)
    assert all(p.solid.is_valid and props.analyzer_findings(p.solid, CHECKS) == {} for p in panels)
    volumes = [props.volume(p.solid) for p in panels]
    assert sum(volumes) == pytest.approx(props.volume(wall.shape), rel=2e-11)  # measured 6.6e-12
    outer = props.faces_area(wall.patches[0].all_faces())
    assert sum(p.outer_area for p in panels) == pytest.approx(outer, rel=1e-13)  # measured 1.1e-16
    bays = [props.volume(p.solid) for p in split_into_panels(wall, [0])] if len(seams) > 1 else volumes
    for i, bay in enumerate(bays):
        assert sum(volumes[i * len(seams) : (i + 1) * len(seams)]) == pytest.approx(bay, rel=2e-12)  # measured 6.5e-13


@pytest.mark.slow
def test_a_stringer_round_a_closed_canal_wall_ends_where_its_equation_takes_it(tmp_path):
    """A stringer all round the closed trefoil's canal wall (r = 8 + 0.02 x): one valid solid,
    fit for booleans, whose end cap stands on the closing circle at chi(s1) + h, chi(s1) from
    solve_ivp on d chi / ds = (r' / q) (k2 cos chi - k1 sin chi) (r' = 0.02 t_x) and h the
    holonomy, while its start cap is at chi0: the Moebius map moves it by -126.9 deg."""
    from tubecad.spec.parse import load_spec
    from tubecad.stiffeners.profiles import Profile
    from tubecad.stiffeners.solids import stringer_stiffener

    spec = tmp_path / "spec.toml"
    spec.write_text(CLOSED_TREFOIL.format(radius='"8 + 0.02 * x"'))
    canal = load_spec(spec).tube
    axis, chi0 = canal.axis, math.radians(30.0)
    stringer = stringer_stiffener(canal, 30.0, Profile("flat", 3.0, 1.0), tolerance=1e-8, name="stringer_00")
    assert stringer.solid.is_valid and props.analyzer_findings(stringer.solid, CHECKS) == {}
    caps = [f for f in stringer.solid.faces() if f.geom_type == bd.GeomType.PLANE]
    assert len(caps) == 2
    centre = np.ravel(canal.circle(np.array(axis.span[0]))[0])
    _, r1, r2 = (np.ravel(v) for v in axis.rotation_minimising_frame(np.array(axis.span[0])))
    angles = sorted(
        math.atan2((np.array(list(f.center())) - centre) @ r2, (np.array(list(f.center())) - centre) @ r1) for f in caps
    )
    end = stringer_ends(
        canal, lambda s: 0.02 * float(np.ravel(axis.rotation_minimising_frame(np.array([s]))[0])[0]), np.array([chi0])
    )[0]
    expected = math.remainder(end + axis.holonomy, TWO_PI)
    assert min(abs(math.remainder(a - chi0, TWO_PI)) for a in angles) < 1e-9  # measured 1.6e-14
    assert min(abs(math.remainder(a - expected, TWO_PI)) for a in angles) < 1e-9  # measured 1.9e-11


def saddle(start: float) -> CanalSurface:
    """The sample's saddle loop (x = 60 cos t, y = 60 sin t, z = 12 sin 2t) and its law
    r = 10 + 0.05 x, the loop started at t = ``start``."""

    def curve(t: np.ndarray) -> np.ndarray:
        return np.stack([60 * np.cos(t), 60 * np.sin(t), 12 * np.sin(2 * t)], axis=-1)

    axis = ParametricAxis(curve, (start, start + TWO_PI), closed=True)
    return tube_or_canal(axis, "10 + 0.05 * x")


@pytest.mark.slow
def test_the_closing_ring_frame_of_a_canal_wall_is_the_ring_built_whole_elsewhere():
    """The ring frame at the closing (t = 0) is built as two halves, one at each end of the
    span, fused: one valid solid, fit for booleans, of the volume of the same ring built in
    one piece on the loop started at t = pi / 2 (where t = 0 is 3/4 of the way round: the
    speed sqrt(3600 + 576 cos^2 2t) has period pi / 2), and of the Pappus volume
    2 pi (R + h / 2) h w of its section (r' = 0 at t = 0, so the web stands in the plane of
    the circle of radius R = 13 there; the axis' curvature 1/60 moves it by less than 0.2 %)."""
    from tubecad.stiffeners.profiles import Profile
    from tubecad.stiffeners.solids import ring_stiffener

    profile = Profile("flat", height=2.0, thickness=0.5)
    closed = saddle(0.0)
    closing = ring_stiffener(closed, closed.span[0], profile, tolerance=1e-8, name="ring_00")
    assert closing.solid.is_valid and props.analyzer_findings(closing.solid) == {}
    shifted = saddle(0.5 * math.pi)
    s0, s1 = shifted.span
    whole = ring_stiffener(shifted, s0 + 0.75 * (s1 - s0), profile, tolerance=1e-8)
    assert len(whole.solid.solids()) == 1
    volume = props.volume(closing.solid)
    assert volume == pytest.approx(props.volume(whole.solid), rel=1e-11)  # measured 2.7e-14
    pappus = TWO_PI * (13.0 + 1.0) * 2.0 * 0.5
    assert volume == pytest.approx(pappus, rel=1e-3)  # measured 7.3e-4
