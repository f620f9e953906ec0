"""Flat patterns of stiffener webs on canal surfaces (docs/MATH.md sections 8 and 9).

Every expected value comes from a closed form written here (a cone's, a Dupin cyclide's focal
hyperbola, an annular sector's) or from a quadrature of the 3-D web measured on
CanalSurface.points / normal by finite differences, never from the flat-pattern code's output.
"""

import math

import numpy as np
import pytest
from conftest import fit_circle

from tubecad import CurvatureLineTube, Helix, NaturalAxis
from tubecad.curves.route import RouteAxis
from tubecad.spec.paper import paper_tube
from tubecad.spec.parse import load_spec
from tubecad.stiffeners.flat import (
    canal_ring_flat_pattern,
    canal_stringer_rates,
    polygon_area,
    ring_flat_pattern,
    stringer_flat_pattern,
    write_dxf,
    write_picture,
)
from tubecad.surface.canal import CanalSurface

SAMPLES = "samples"


def polyline(p):
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def edges(pattern):
    n = len(pattern.outline) // 2
    return pattern.outline[:n], pattern.outline[n:][::-1]


# --- (a) a cone: straight axis, r = r0 + a s ------------------------------------------------------
R0, SLOPE, LENGTH, HEIGHT = 2.0, 0.3, 40.0, 1.5


@pytest.fixture(scope="module")
def cone():
    return CanalSurface(NaturalAxis("0", "0", (0.0, LENGTH)), f"{R0} + {SLOPE} * s")


def cone_circle(s):
    """The cone's characteristic circle at s, from its geometry alone: the sphere of radius
    r = r0 + a s centred at x = s touches the cone of apex x = -r0 / a and half-angle beta,
    sin beta = a (r = (distance to the apex) sin beta), along the circle at axial distance
    d cos^2 beta from the apex (d = s + r0 / a), radius d cos beta sin beta."""
    beta = math.asin(SLOPE)
    d = s + R0 / SLOPE
    return -R0 / SLOPE + d * math.cos(beta) ** 2, d * math.cos(beta) * math.sin(beta)


@pytest.mark.parametrize("side", ["outside", "inside"])
def test_cone_stringer_web_is_a_rectangle(cone, side):
    """A stringer is a generatrix: its normals are parallel, so the web develops to a
    rectangle of length the slant distance between the end circles and height h."""
    (x0, rho0), (x1, rho1) = cone_circle(0.0), cone_circle(LENGTH)
    slant = math.hypot(x1 - x0, rho1 - rho0)  # = L cos(beta) = L sqrt(1 - a^2)
    assert slant == pytest.approx(LENGTH * math.sqrt(1 - SLOPE**2), rel=1e-15)
    pattern = stringer_flat_pattern(cone, 30.0, HEIGHT, side, samples=101)
    assert pattern.base_length == pytest.approx(slant, rel=5e-13)  # measured <= 1.4e-13
    assert pattern.top_length == pytest.approx(slant, rel=5e-13)
    assert pattern.area == pytest.approx(slant * HEIGHT, rel=5e-13)
    base, top = edges(pattern)
    assert np.abs(base[:, 1]).max() < 1e-12 * LENGTH  # zero curvature: a straight base edge
    assert np.abs(top[:, 1] - HEIGHT).max() < 1e-12 * LENGTH
    assert polygon_area(pattern.outline) == pytest.approx(slant * HEIGHT, rel=1e-12)


@pytest.mark.parametrize("side", ["outside", "inside"])
def test_cone_ring_web_is_a_sector_of_angle_2_pi_cos_beta(cone, side):
    """The normals along the circle at s meet in the sphere centre (x = s on the axis); the
    slant from there to the circle is r, the circle's radius r cos beta, so the normal cone
    has sin(half-angle) = cos beta = sqrt(1 - a^2) and develops to the angle 2 pi cos beta."""
    s = 25.0
    x, rho = cone_circle(s)
    slant = math.hypot(x - s, rho)
    assert slant == pytest.approx(R0 + SLOPE * s, rel=1e-15)
    angle = 2 * math.pi * rho / slant
    assert angle == pytest.approx(2 * math.pi * math.cos(math.asin(SLOPE)), rel=1e-15)
    pattern = canal_ring_flat_pattern(cone, s, HEIGHT, side)
    r_top = slant + (HEIGHT if side == "outside" else -HEIGHT)
    assert pattern.kind == "ring" and pattern.hole is None
    assert pattern.sector == pytest.approx((min(slant, r_top), max(slant, r_top), angle), rel=1e-14)
    assert pattern.base_length == pytest.approx(angle * slant, rel=1e-14)
    assert pattern.top_length == pytest.approx(angle * r_top, rel=1e-14)
    assert pattern.area == pytest.approx(angle / 2 * abs(r_top**2 - slant**2), rel=1e-14)
    # the outline: outer arc, radial edge, inner arc back, radial edge; its corners' angles
    # span the sector's angle, and the polygon's area converges to the sector's
    n = len(pattern.outline) // 2
    a = np.unwrap(np.arctan2(pattern.outline[:, 1], pattern.outline[:, 0]))
    assert a[n - 1] - a[0] == pytest.approx(angle, rel=1e-14) and a[n] - a[-1] == pytest.approx(angle, rel=1e-14)
    assert np.all(np.diff(a[:n]) > 0) and np.all(np.diff(a[n:]) < 0)  # round the outer arc, back on the inner
    radii = np.linalg.norm(pattern.outline, axis=1)
    assert radii[:n] == pytest.approx(max(slant, r_top), rel=1e-14)
    assert radii[n:] == pytest.approx(min(slant, r_top), rel=1e-14)
    # the polygon inscribed in the sector, n - 1 chords on each arc: its area in closed form
    chord = angle / (n - 1)
    inscribed = (n - 1) / 2 * math.sin(chord) * abs(r_top**2 - slant**2)
    assert polygon_area(pattern.outline) == pytest.approx(inscribed, rel=1e-12)


# --- (b) the ring Dupin cyclide of samples/dupin_cyclide.toml -------------------------------------
# spheres centred on the ellipse (a cos t, b sin t, 0), radius mu - c cos t, c^2 = a^2 - b^2
CA, CB, CC, CMU = 100.0, 80.0, 60.0, 80.0


@pytest.fixture(scope="module")
def cyclide():
    surface = load_spec(f"{SAMPLES}/dupin_cyclide.toml").tube
    assert isinstance(surface, CanalSurface)
    return surface


def focal_distance(surface, chi0):
    """The signed distance t, P = X + t n, from the stringer chi0 to the centre P of the second
    family's sphere touching the cyclide along it: P on the focal hyperbola x^2/c^2 - z^2/b^2 = 1,
    y = 0, P = (c sec v, 0, b tan v); |P - E(u)| = a sec v - c cos u for every ellipse point, so
    that sphere, of radius a sec v - mu, touches all the spheres mu - c cos u (from outside when
    a sec v > mu, round them when sec v < 0): t = a sec v - mu in both cases, and the stringer's
    normal curvature is 1 / t. P is found as the point nearest all the stringer's normal lines."""
    s = np.linspace(*surface.span, 41)
    x, n = surface.points(chi0, s), surface.normal(chi0, s)
    projector = np.eye(3) - n[:, :, None] * n[:, None, :]
    p = np.linalg.solve(projector.sum(axis=0), np.einsum("kij,kj->i", projector, x))
    miss = np.linalg.norm(np.einsum("kij,kj->ki", projector, p - x), axis=1).max()
    assert miss < 1e-9 * CA  # all the normals meet in P
    assert abs(p[1]) < 1e-9 * CA and p[0] ** 2 / CC**2 - p[2] ** 2 / CB**2 == pytest.approx(1.0, abs=1e-10)
    t = CA * p[0] / CC - CMU
    assert np.abs(np.linalg.norm(x - p, axis=1) - abs(t)).max() < 1e-9 * CA
    assert np.abs(p - x - t * n).max() < 1e-9 * CA  # P = X + t n, signed
    return t


@pytest.mark.parametrize("side", ["outside", "inside"])
@pytest.mark.parametrize("chi0_deg", [30.0, 100.0, 200.0, 250.0, 330.0])
def test_cyclide_stringer_web_develops_to_a_circular_arc(cyclide, chi0_deg, side):
    """The developed base edge is a circular arc of radius |t| (kappa_n = 1 / t constant),
    turning left for a web outside when t > 0; the top edge is the concentric arc of radius
    |t -+ h|, the area the annular sector's."""
    t = focal_distance(cyclide, math.radians(chi0_deg))
    h = 3.0
    pattern = stringer_flat_pattern(cyclide, chi0_deg, h, side, samples=401)
    base, top = edges(pattern)
    residual, radius, centre = fit_circle(base)
    assert residual < 2e-11 * abs(t)  # measured <= 7.4e-12 relative
    assert radius == pytest.approx(abs(t), rel=2e-11)  # measured <= 5.6e-12
    top_residual, top_radius, top_centre = fit_circle(top)
    sign = 1.0 if side == "outside" else -1.0
    assert top_residual < 2e-11 * abs(t) and top_radius == pytest.approx(abs(t - sign * h), rel=2e-11)
    assert np.linalg.norm(top_centre - centre) < 1e-13 * abs(t)  # measured <= 1e-14
    # the centre lies left of the base edge (the web's side) iff the line bends towards sign * n
    tangent = base[1] - base[0]
    left = tangent[0] * (centre[1] - base[0, 1]) - tangent[1] * (centre[0] - base[0, 0])
    assert np.sign(left) == np.sign(sign * t)
    # measures: arc lengths and the annular sector between radii |t| and |t -+ h|
    angle = pattern.base_length / abs(t)
    assert pattern.top_length == pytest.approx(angle * abs(t - sign * h), rel=1e-12)  # measured <= 2e-13
    assert pattern.area == pytest.approx(angle / 2 * abs(t**2 - (t - sign * h) ** 2), rel=1e-12)
    assert polyline(base) == pytest.approx(pattern.base_length, rel=2e-5)  # 400 chords: measured <= 1.1e-5


def test_cyclide_stringer_length_is_the_3d_circle_arc(cyclide):
    """The stringer itself is a circle in space: its arc length from the fitted circle's
    radius and the angle it subtends equals the developed base length."""
    chi0 = math.radians(100.0)
    x = cyclide.points(chi0, np.linspace(*cyclide.span, 401))
    centre = x.mean(axis=0)
    _, _, vt = np.linalg.svd(x - centre)
    xy = (x - centre) @ vt[:2].T
    residual, radius, mid = fit_circle(xy)
    assert residual < 1e-9 * radius
    a = np.unwrap(np.arctan2(xy[:, 1] - mid[1], xy[:, 0] - mid[0]))
    assert stringer_flat_pattern(cyclide, 100.0, 2.0).base_length == pytest.approx(radius * abs(a[-1] - a[0]), rel=1e-9)


# --- (c) a constant radius is today's tube ----------------------------------------------------------
@pytest.mark.parametrize("side, theta", [("outside", 37.0), ("inside", 200.0)])
def test_constant_radius_canal_gives_the_tube_pattern(side, theta):
    axis = paper_tube().axis.restricted((250.0, 900.0))
    tube, canal = CurvatureLineTube(axis, 15.0), CanalSurface(axis, 15.0)
    a, b = stringer_flat_pattern(tube, theta, 3.0, side), stringer_flat_pattern(canal, theta, 3.0, side)
    scale = np.abs(a.outline).max()
    assert np.abs(a.outline - b.outline).max() <= 1e-12 * scale  # measured 0 (bit for bit)
    for key in ("base_length", "top_length", "area"):
        assert getattr(b, key) == pytest.approx(getattr(a, key), rel=1e-12)
    ring, annulus = canal_ring_flat_pattern(canal, 500.0, 3.0, side), ring_flat_pattern(15.0, 3.0, side)
    assert ring.sector is None and ring.hole is not None
    assert np.array_equal(ring.outline, annulus.outline) and np.array_equal(ring.hole, annulus.hole)
    assert (ring.base_length, ring.top_length, ring.area) == (annulus.base_length, annulus.top_length, annulus.area)


# --- (d) the developed measures are the 3-D web's ------------------------------------------------------
def canal_cases():
    return {
        "smoothstep_straight": lambda: CanalSurface(
            NaturalAxis("0", "0", (0.0, 200.0)), "40 - 25 * (s / 200)**2 * (3 - 2 * s / 200)"
        ),
        "tapered_helix": lambda: load_spec(f"{SAMPLES}/tapered_helix.toml").tube,
        "table_on_helix": lambda: CanalSurface(
            Helix(0.01, 20.0, (0.0, 400.0)), [[0.0, 10.0], [100.0, 13.0], [250.0, 9.0], [400.0, 11.0]]
        ),
        "route": lambda: CanalSurface(
            RouteAxis([[0, 0, 0], [200, 0, 0], [200, 150, 60], [380, 150, 60]], 70.0), "18 - 0.012 * s"
        ),
        "cyclide": lambda: load_spec(f"{SAMPLES}/dupin_cyclide.toml").tube,
    }


CASES = canal_cases()


def derivative(f, s, step):
    """d f / ds by the 4th-order central difference."""
    return (8.0 * (f(s + step) - f(s - step)) - (f(s + 2 * step) - f(s - 2 * step))) / (12.0 * step)


def gauss_panels(breaks, panels, order=20):
    """(nodes, weights, the nodes' least distance from a panel's end)."""
    pieces = [np.linspace(a, b, panels + 1)[:-1] for a, b in zip(breaks[:-1], breaks[1:])]
    edges = np.concatenate(pieces + [breaks[-1:]])
    x, w = np.polynomial.legendre.leggauss(order)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel(), (1.0 - x[-1]) * half.min()


def web_3d(surface, chi0, height, sign):
    """(base length, top length, area) of the strip X + v n, v in [0, sign h], along the
    stringer chi0: Gauss-Legendre in s (panels between the axis' joints and the law's knots)
    and in v of |X_s|, |X_s + v n_s| and |(X_s + v n_s) x n|, with X_s and n_s central
    differences of CanalSurface.points and .normal."""
    s0, s1 = surface.span
    breaks = np.unique([s0, s1, *surface.radius_law.breaks, *(j for j, _ in surface.axis.joints)])
    s, ws, gap = gauss_panels(breaks, 24)
    step = gap / 3  # the differences stay inside the node's panel (no kink crossed)
    x_s = derivative(lambda u: surface.points(chi0, u), s, step)
    n = surface.normal(chi0, s)
    n_s = derivative(lambda u: surface.normal(chi0, u), s, step)
    v, wv = np.polynomial.legendre.leggauss(8)
    v, wv = 0.5 * sign * height * (v + 1.0), 0.5 * height * wv
    rulings = x_s[:, None, :] + v[None, :, None] * n_s[:, None, :]
    area = float(np.einsum("i,j,ij->", ws, wv, np.linalg.norm(np.cross(rulings, n[:, None, :]), axis=-1)))
    top = x_s + sign * height * n_s
    return float(ws @ np.linalg.norm(x_s, axis=1)), float(ws @ np.linalg.norm(top, axis=1)), area


@pytest.mark.slow
@pytest.mark.parametrize("side", ["outside", "inside"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_developed_web_measures_equal_the_3d_web(case, side):
    surface = CASES[case]()
    height = 0.15 * surface.radius_law.min_radius
    sign = 1.0 if side == "outside" else -1.0
    for chi0_deg in (40.0, 215.0):
        pattern = stringer_flat_pattern(surface, chi0_deg, height, side, samples=4001)
        base, top, area = web_3d(surface, math.radians(chi0_deg), height, sign)
        # measured <= 1.7e-12 relative (the route's 1.3e-11: its finite differences' small step)
        assert pattern.base_length == pytest.approx(base, rel=5e-11)
        assert pattern.top_length == pytest.approx(top, rel=5e-11)
        assert pattern.area == pytest.approx(area, rel=5e-11)
        # the outline drawn is the pattern measured: polyline lengths and shoelace area (4000
        # chords: measured <= 2.3e-7 and 9.1e-7)
        b, t = edges(pattern)
        assert polyline(b) == pytest.approx(base, rel=5e-7) and polyline(t) == pytest.approx(top, rel=5e-7)
        assert polygon_area(pattern.outline) == pytest.approx(area, rel=2e-6)


@pytest.mark.parametrize("case", sorted(CASES))
def test_stringer_rates_are_the_nets_forms(case):
    """turn = kappa_n sqrt(G) and speed = sqrt(G) of the closed form against N / G and G of
    CanalSurface.fundamental_forms (the evaluated net's derivative vectors)."""
    surface = CASES[case]()
    s0, s1 = surface.span
    s = np.linspace(s0, s1, 301)[1:-1]
    for chi0 in (0.3, 2.0, 4.5):
        turn, speed = canal_stringer_rates(surface, chi0)
        forms = surface.fundamental_forms(chi0, s)
        assert np.abs(speed(s) - np.sqrt(forms.G)).max() < 1e-14  # measured <= 6.7e-16
        assert np.abs(turn(s) / speed(s) - forms.N / forms.G).max() < 5e-14 / surface.radius_law.min_radius  # 6.4e-15


@pytest.mark.parametrize("side", ["outside", "inside"])
@pytest.mark.parametrize("case", ["cyclide", "tapered_helix", "route"])
def test_canal_ring_web_measures_equal_the_3d_cone_strip(case, side):
    """The ring web X + v n over the characteristic circle at s (v in [0, +-h]), where |r'| is
    largest: its area and edge lengths by the periodic trapezoid rule in chi0 (and
    Gauss-Legendre in v), with derivatives by central differences of CanalSurface.points and
    .normal, equal the sector's; the base edge is the circle of radius r q (CanalSurface.circle)."""
    surface = CASES[case]()
    s, h = surface.regularity.s_at_max_slope, 0.2 * surface.radius_law.min_radius
    sign = 1.0 if side == "outside" else -1.0
    chi0 = np.linspace(0.0, 2 * math.pi, 256, endpoint=False)
    step, weight = 1e-3, 2 * math.pi / len(chi0)
    x_u = derivative(lambda u: surface.points(u, s), chi0, step)
    n, n_u = surface.normal(chi0, s), derivative(lambda u: surface.normal(u, s), chi0, step)
    v, wv = np.polynomial.legendre.leggauss(8)
    v, wv = 0.5 * sign * h * (v + 1.0), 0.5 * h * wv
    rulings = x_u[:, None, :] + v[None, :, None] * n_u[:, None, :]
    area = float((np.linalg.norm(np.cross(rulings, n[:, None, :]), axis=-1) @ wv).sum() * weight)
    base = float(np.linalg.norm(x_u, axis=1).sum() * weight)
    top = float(np.linalg.norm(x_u + sign * h * n_u, axis=1).sum() * weight)
    _, radius, _ = surface.circle(s)
    pattern = canal_ring_flat_pattern(surface, s, h, side)
    assert base == pytest.approx(2 * math.pi * float(radius), rel=1e-12)
    # measured <= 1.6e-13 relative
    assert pattern.base_length == pytest.approx(base, rel=1e-12)
    assert pattern.top_length == pytest.approx(top, rel=1e-12)
    assert pattern.area == pytest.approx(area, rel=1e-12)
    assert pattern.sector[2] < 2 * math.pi * (1 - 1e-5)  # a sector, not an annulus


def test_dxf_and_picture_of_a_sector(tmp_path, cone):
    import ezdxf

    ring = canal_ring_flat_pattern(cone, 25.0, HEIGHT, "outside", "ring_00")
    stringer = stringer_flat_pattern(cone, 0.0, HEIGHT, "outside", "stringer_00")
    annulus = ring_flat_pattern(5.0, 1.0, "inside", "ring_01")
    doc = ezdxf.readfile(write_dxf([ring, stringer, annulus], tmp_path / "webs.dxf"))
    by_layer = {}
    for e in doc.modelspace():
        by_layer.setdefault(e.dxf.layer, []).append(e)
    (sector,) = by_layer["ring_00"]
    assert sector.dxftype() == "LWPOLYLINE" and sector.closed
    parts = list(sector.virtual_entities())
    arcs = [p for p in parts if p.dxftype() == "ARC"]
    lines = [p for p in parts if p.dxftype() == "LINE"]
    r_in, r_out, angle = ring.sector
    assert len(arcs) == 4 and len(lines) == 2
    assert sorted(a.dxf.radius for a in arcs) == pytest.approx([r_in, r_in, r_out, r_out], rel=1e-12)
    sweep = sum((a.dxf.end_angle - a.dxf.start_angle) % 360.0 for a in arcs)
    assert sweep == pytest.approx(2 * math.degrees(angle), rel=1e-12)
    assert all(line.dxf.start.distance(line.dxf.end) == pytest.approx(r_out - r_in, rel=1e-12) for line in lines)
    centres = {tuple(np.round(a.dxf.center, 9)) for a in arcs}
    assert len(centres) == 1  # concentric
    assert sorted(e.dxftype() for e in by_layer["ring_01"]) == ["CIRCLE", "CIRCLE"]
    assert [e.dxftype() for e in by_layer["stringer_00"]] == ["LWPOLYLINE"]
    paths = write_picture(ring, tmp_path)
    assert [p.suffix for p in paths] == [".svg", ".png"] and paths[1].read_bytes().startswith(b"\x89PNG")
