"""Stiffeners on canal surfaces (issue 12): ring frames on the normal cones of the
characteristic circles, stringers square to the curvature lines, checked against closed
forms (a cone is a surface of revolution: Pappus) and the exact sphere envelope."""

from __future__ import annotations

import math

import build123d as bd
import numpy as np
import pytest

from tubecad import NaturalAxis, tube_or_canal
from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.brep.measure import sample_face
from tubecad.spec.parse import load_spec
from tubecad.stiffeners.assembly import build_stiffeners
from tubecad.stiffeners.canal import (
    along_wall,
    canal_ring_solid,
    canal_stringer_solid,
    stringer_frame,
    wall_points_across,
)
from tubecad.stiffeners.profiles import Profile
from tubecad.stiffeners.rings import ring_section
from tubecad.surface.checks import envelope_distance

PROFILES = [Profile("flat", 6, 1), Profile("T", 6, 1, 4, 1), Profile("L", 6, 1, 4, 1)]
SLOPE = 0.1  # the cone r = 30 - 0.1 s


@pytest.fixture(scope="module")
def cone():
    return tube_or_canal(NaturalAxis("0", "0", (0.0, 200.0)), f"30 - {SLOPE} * s")


@pytest.fixture(scope="module")
def nozzle():
    return load_spec("samples/nozzle.toml").tube


def meridian(point_s: float, d: float, slope: float, r0: float) -> tuple[float, float]:
    """The cone's point (axial z, radius) of the circle of r + d at s: the sphere of radius
    r + d about (s, 0) touches the surface at z = s - (r + d) r', rho = (r + d) q."""
    r = r0 - slope * point_s
    q = math.sqrt(1.0 - slope**2)
    return point_s + (r + d) * slope, (r + d) * q  # r' = -slope


def pappus(polygon: list[tuple[float, float]]) -> float:
    """The volume of the polygon (z, rho) revolved about the z axis: 2 pi Int Int rho dA."""
    total = 0.0
    for (z1, p1), (z2, p2) in zip(polygon, polygon[1:] + polygon[:1]):
        total += (z1 * p2 - z2 * p1) * (p1 + p2)
    return 2.0 * math.pi * abs(total) / 6.0


@pytest.mark.parametrize("side", ["outside", "inside"])
@pytest.mark.parametrize("profile", PROFILES, ids=lambda p: p.kind)
def test_ring_on_a_cone_is_the_solid_of_revolution_of_its_section(cone, profile, side):
    # every face of a ring on a cone is a cone or a plane of revolution about the axis, so the
    # meridian section is a straight-sided polygon and Pappus gives the exact volume
    s = 80.0
    section = ring_section(profile, s, 0.0, side, cone.span, along=lambda w: along_wall(cone, s, w))
    solid = bd.Solid(canal_ring_solid(cone, section, 1e-8))
    assert props.is_valid(solid.wrapped)
    exact = pappus([meridian(x, d, SLOPE, 30.0) for x, d in section])
    assert abs(props.volume(solid) - exact) < 1e-12 * exact


def test_ring_web_on_a_cone_is_its_thickness_wide_along_the_wall(cone):
    # on a cone the circles advance along the generator at q per unit s: the web's two
    # normal cones cut the wall t apart along it
    s, t = 80.0, 1.0
    a, b = along_wall(cone, s, -t / 2), along_wall(cone, s, t / 2)
    (za, pa), (zb, pb) = meridian(a, 0.0, SLOPE, 30.0), meridian(b, 0.0, SLOPE, 30.0)
    assert math.hypot(zb - za, pb - pa) == pytest.approx(t, rel=1e-13)


@pytest.mark.slow
def test_ring_frames_on_a_curved_axis_pass_the_pre_boolean_check():
    canal = load_spec("samples/tapered_helix.toml").tube
    s = 300.0
    section = ring_section(
        Profile("T", 4, 1, 3, 0.8), s, 0.0, "outside", canal.span, along=lambda w: along_wall(canal, s, w)
    )
    solid = bd.Solid(canal_ring_solid(canal, section, 1e-8))
    assert props.is_valid(solid.wrapped) and props.analyzer_findings(solid) == {}
    # its base faces lie on the sphere envelope (distance 0), its top faces at height 4
    levels = []
    for face in solid.faces():
        points = sample_face(face.wrapped, 3, 3)[0]
        dist, _ = envelope_distance(canal, points)
        levels.append(float(np.median(dist)))
    assert min(abs(v) for v in levels) < 1e-8 and min(abs(v - 4.0) for v in levels) < 1e-8


@pytest.mark.slow
@pytest.mark.parametrize("sample", ["nozzle", "tapered_helix", "dupin_cyclide"])
def test_stringer_base_lies_on_the_wall_and_its_web_stands_normal_to_it(sample):
    canal = load_spec(f"samples/{sample}.toml").tube
    profile = Profile("flat", 5.0, 1.0)
    chi0 = math.radians(30.0)
    solid, (a, b), bound = canal_stringer_solid(canal, chi0, profile, "outside", canal.span, 1e-8)
    shape = bd.Solid(solid)
    assert props.is_valid(solid) and props.analyzer_findings(shape) == {}
    assert bound < 5e-9
    # the square ends stop short of a slanted end circle: the circle of radius r q leaves the
    # section plane (normal m = q t + r' e) by r' w^2 / (2 r q) at w across, which the wall
    # makes up at the stringer speed sqrt(G) >= min_speed
    law = canal.radius_law
    for end, station in zip(canal.span, (a, b)):
        dr, r = float(law.dr(end)), float(law.r(end))
        assert (
            abs(station - end)
            <= 1.05 * 0.25 * abs(dr) / (2 * r * math.sqrt(1 - dr * dr)) / canal.regularity.min_speed + 1e-12
        )
    # the base face (the one nearest the wall) lies on the exact sphere envelope
    distances = []
    for face in shape.faces():
        points = sample_face(face.wrapped, 5, 9)[0]
        dist, _ = envelope_distance(canal, points)
        distances.append(np.abs(dist).max())
    assert min(distances) < 1e-8
    # the web's side corners: the wall's point in the section plane at +-t/2 across, then
    # straight up along the normal: 5 high, t apart
    s = np.linspace(a, b, 7)
    wall, _ = wall_points_across(canal, chi0, s, np.array([-0.5, 0.5]))
    X, n, ebar, m = stringer_frame(canal, chi0, s)
    assert np.abs(np.einsum("ijk,ik->ij", wall - X[:, None], ebar) - [-0.5, 0.5]).max() < 1e-11  # t apart across
    assert np.abs(np.einsum("ijk,ik->ij", wall - X[:, None], m)).max() < 1e-11  # in the section plane
    assert np.abs(envelope_distance(canal, wall.reshape(-1, 3))[0]).max() < 1e-10  # on the exact wall
    assert np.abs(np.einsum("ij,ij->i", n, m)).max() < 1e-14 and np.abs(np.einsum("ij,ij->i", ebar, m)).max() < 1e-14


def test_stringer_on_a_cone_has_the_volume_of_its_parallel_sections(cone):
    # a stringer of a cone runs along a generator: its section planes are parallel, so its
    # volume is the integral of the section areas along it (Cavalieri); each section is the
    # profile over the cone's own trace across (dense points of the exact surface)
    profile, chi0 = Profile("T", 6, 1, 4, 1), 0.3
    solid, (a, b), _ = canal_stringer_solid(cone, chi0, profile, "outside", (20.0, 150.0), 1e-8)
    shape = bd.Solid(solid)
    assert props.is_valid(solid)
    caps = [f for f in shape.faces() if f.geom_type == bd.GeomType.PLANE]
    assert len(caps) == 2
    assert abs(abs(np.array(tuple(caps[0].normal_at())) @ np.array(tuple(caps[1].normal_at()))) - 1.0) < 1e-12
    x, w = np.polynomial.legendre.leggauss(8)
    stations = 0.5 * (a + b) + 0.5 * (b - a) * x
    X, n, ebar, m = stringer_frame(cone, chi0, stations)
    across = np.linspace(-0.5, 0.5, 4001)
    wall = wall_points_across(cone, chi0, stations, across)[0]
    top = np.array([(p, h) for p, h in profile.outline() if h != 0.0])
    areas = []
    for k in range(len(stations)):
        base = np.stack([(wall[k] - X[k]) @ ebar[k], (wall[k] - X[k]) @ n[k]], axis=1)
        ring = np.vstack([base[-1:], top, base])  # +t/2 on the wall, round the profile, back across the wall
        areas.append(0.5 * abs(ring[:, 0] @ np.roll(ring[:, 1], -1) - ring[:, 1] @ np.roll(ring[:, 0], -1)))
    length = float(
        np.linalg.norm(stringer_frame(cone, chi0, np.array([b]))[0] - stringer_frame(cone, chi0, np.array([a]))[0])
    )
    assert props.volume(shape) == pytest.approx(0.5 * length * float(np.dot(w, areas)), rel=1e-8)


def test_stiffened_nozzle_wall_from_its_build(nozzle):
    layout = NetLayout.equal(nozzle, 5, 4)
    build = build_wall_solid(nozzle, 2.0, "centered", layout)
    stiffeners = build_stiffeners(build, [1, 3], [0, 2], Profile("flat", 4, 1), "inside")
    assert [st.name for st in stiffeners] == ["ring_01", "ring_03", "stringer_00", "stringer_02"]
    for st in stiffeners:
        assert props.is_valid(st.solid.wrapped), st.name
    # the ring's circle: r q of the inner wall at its s; its length 2 pi r q
    ring = stiffeners[0]
    inner = build.surfaces[1].tube
    r, dr = float(inner.radius_law.r(ring.value)), float(inner.radius_law.dr(ring.value))
    assert ring.base_radius == pytest.approx(r * math.sqrt(1 - dr * dr), rel=1e-14)
    assert ring.length() == pytest.approx(2 * math.pi * ring.base_radius, rel=1e-14)
    # a stringer's length: Int |X_s| ds on the exact surface, by the trapezoid rule on a fine grid
    s = np.linspace(*nozzle.span, 20001)
    x = inner.points(np.radians(stiffeners[2].value), s)
    assert stiffeners[2].length() == pytest.approx(np.linalg.norm(np.diff(x, axis=0), axis=1).sum(), rel=1e-8)


def test_a_stiffener_that_folds_its_own_surface_is_refused_before_fitting():
    canal = load_spec("samples/tapered_helix.toml").tube  # k = 0.02 * cos^2(20 deg)
    with pytest.raises(Exception, match="height: a test stringer reaches the canal surface of r \\+60"):
        from tubecad.stiffeners.canal import checked_levels

        checked_levels(canal, [60.0], "a test stringer")
