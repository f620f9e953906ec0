"""Panel developments (tubecad.shop.panel_development): every expected value from a closed
form of the surface written here (cylinder, cone, torus), never from the code's output."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import CurvatureLineTube, NaturalAxis, ParameterError
from tubecad.shop.panel_development import develop_panel, write_panel_dxf, write_panel_picture
from tubecad.surface.canal import CanalSurface

# torus: the axis is the circle of radius A about (0, A, 0) in the xy-plane (k = 1 / A), r1 points
# to its centre, r2 = z; the tube of radius RT is the torus whose parallels (u = const) are the
# stringers and whose meridians (s = const) are the rings
A, RT = 100.0, 30.0
# cone: straight axis along x, r(s) = R0 + SLOPE s; its apex is at s = S_APEX
R0, SLOPE = 2.0, 0.3
S_APEX = -R0 / SLOPE
Q = math.sqrt(1.0 - SLOPE**2)


@pytest.fixture(scope="module")
def cylinder():
    return CurvatureLineTube(NaturalAxis("0", "0", (0.0, 100.0)), 10.0)


@pytest.fixture(scope="module")
def torus():
    return CurvatureLineTube(NaturalAxis("0.01", "0", (0.0, 300.0)), RT)


@pytest.fixture(scope="module")
def cone():
    return CanalSurface(NaturalAxis("0", "0", (0.0, 40.0)), "2.0 + 0.3 * s")


@pytest.fixture(scope="module")
def torus_panel(torus):
    return develop_panel(torus, (50.0, 150.0), (30.0, 90.0), name="torus_panel")


def pairwise(points: np.ndarray) -> np.ndarray:
    p = points.reshape(-1, 2)
    return np.linalg.norm(p[:, None, :] - p[None, :, :], axis=-1)


def signed_area(polygon: np.ndarray) -> float:
    x, y = polygon[:, 0], polygon[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def circle_through(p: np.ndarray) -> tuple[np.ndarray, float]:
    """Centre and radius of the circle through the first, middle and last of points ``p``."""
    a, b, c = p[0], p[len(p) // 2], p[-1]
    m = 2.0 * np.array([b - a, c - a])
    centre = np.linalg.solve(m, np.array([b @ b - a @ a, c @ c - a @ a]))
    return centre, float(np.linalg.norm(a - centre))


def arc_length(p: np.ndarray) -> float:
    """Length of the circular arc through points ``p`` (less than a half circle)."""
    _, radius = circle_through(p)
    return 2.0 * radius * math.asin(np.linalg.norm(p[-1] - p[0]) / (2.0 * radius))


# --- cylinder ----------------------------------------------------------------------------------
def test_cylinder_panel_is_an_exact_rectangle(cylinder):
    u_a, u_b, s_a, s_b, R = 20.0, 110.0, 10.0, 60.0, 10.0
    dev = develop_panel(cylinder, (s_a, s_b), (u_a, u_b), samples=(17, 33))
    assert dev.max_strain < 1e-14  # measured 5.3e-16
    # the documented placement: the middle stringer from the origin along +y, u to the right
    u = np.radians(np.linspace(u_a, u_b, 17))[:, None]
    s = np.linspace(s_a, s_b, 33)[None, :]
    expected = np.stack(np.broadcast_arrays(R * (u - math.radians(0.5 * (u_a + u_b))), s - s_a), axis=-1)
    assert np.abs(dev.grid - expected).max() < 2e-13  # measured 2.1e-14
    area = R * math.radians(u_b - u_a) * (s_b - s_a)
    assert dev.surface_area == pytest.approx(area, rel=1e-14)  # measured 5.6e-16
    assert dev.flat_area == pytest.approx(area, rel=1e-14)  # measured 6.7e-16
    corners = dev.outline()[[0, 16, 16 + 32, 2 * 16 + 32]]
    assert (
        np.abs(
            corners
            - [
                [-R * math.radians(45), 0],
                [R * math.radians(45), 0],
                [R * math.radians(45), 50],
                [-R * math.radians(45), 50],
            ]
        ).max()
        < 2e-13
    )


# --- cone ----------------------------------------------------------------------------------------
def test_cone_panel_develops_without_strain(cone):
    s_a, s_b, u_a, u_b = 5.0, 35.0, -30.0, 60.0
    dev = develop_panel(cone, (s_a, s_b), (u_a, u_b), samples=(17, 33))
    assert dev.max_strain < 5e-13  # measured 5.0e-14 (0.24 with the rings' kg of the wrong sign)
    # the cone's development: the point (chi0, s) lies at slant distance q (s - s_apex) from the
    # apex, at the polar angle r' chi0 (the circle of radius r q at slant l = q d spans r' of a turn)
    chi = np.radians(dev.angles_deg)[:, None]
    slant = Q * (dev.s - S_APEX)[None, :]
    flat = np.stack(np.broadcast_arrays(slant * np.cos(SLOPE * chi), slant * np.sin(SLOPE * chi)), axis=-1)
    assert np.abs(pairwise(dev.grid[::2, ::2]) - pairwise(flat[::2, ::2])).max() < 2e-12  # measured 1.4e-13
    sector = 0.5 * SLOPE * math.radians(u_b - u_a) * Q**2 * ((s_b - S_APEX) ** 2 - (s_a - S_APEX) ** 2)
    assert dev.surface_area == pytest.approx(sector, rel=1e-13)  # measured 5.0e-15
    assert dev.flat_area == pytest.approx(sector, rel=1e-13)  # measured 5.3e-15
    # rings are arcs of length r q (chi_b - chi_a); the middle stringer a straight generator
    for s in (s_a, 17.3, s_b):
        ring = dev.ring_line(s)
        assert arc_length(ring) == pytest.approx(
            (R0 + SLOPE * s) * Q * math.radians(u_b - u_a), rel=1e-13
        )  # measured 3.6e-15
        centre, radius = circle_through(ring)
        assert np.abs(np.linalg.norm(ring - centre, axis=1) - radius).max() < 1e-13  # measured 7.1e-15
    line = dev.stringer_line(15.0)
    assert np.linalg.norm(line[-1] - line[0]) == pytest.approx(Q * (s_b - s_a), rel=1e-14)  # measured 2.4e-15


# --- torus ---------------------------------------------------------------------------------------
def torus_development(u: np.ndarray, s: np.ndarray, u_m: float, s_a: float) -> tuple[np.ndarray, np.ndarray]:
    """(developed points, s-stretch) of the torus panel, from the torus alone: the parallel at u
    has radius rho(u) = A - RT cos u about the torus' axis. The middle parallel develops like
    its tangent cone (apex on the axis, slant rho_m / |sin u_m|): into the circular arc of that
    radius, s mapping to the polar angle |sin u_m| (s - s_a) / A; the meridians (geodesics, at
    right angles to it) into the cone's generators, the straight radial lines, along which rho
    grows at the rate sin u_m: the point at arc RT (u - u_m) from the parallel lies at slant
    (rho_m + RT (u - u_m) sin u_m) / |sin u_m|. Its parallel is stretched by that slant's
    circle over rho(u); the meridians keep their length."""
    rho = A - RT * np.cos(u)
    rho_m = A - RT * math.cos(u_m)
    reach = rho_m + RT * (u - u_m) * math.sin(u_m)
    slant = reach / abs(math.sin(u_m))
    psi = abs(math.sin(u_m)) * (s - s_a) / A
    points = np.stack(np.broadcast_arrays(slant * np.cos(psi), slant * np.sin(psi)), axis=-1)
    return points, reach / rho


def test_torus_panel_matches_the_tangent_cone_development(torus_panel):
    dev = torus_panel
    u_a, u_b, s_a, s_b = 30.0, 90.0, 50.0, 150.0
    u = np.radians(np.linspace(u_a, u_b, 33))[:, None]
    s = np.linspace(s_a, s_b, 65)[None, :]
    flat, stretch = torus_development(u, s, math.radians(60.0), s_a)
    # (with the stringers' kg of the wrong sign the distances are 26 off)
    assert np.abs(pairwise(dev.grid[::4, ::4]) - pairwise(flat[::4, ::4])).max() < 2e-12  # measured 9.9e-14
    strain = np.abs(stretch - 1.0) * np.ones((1, 65))
    assert np.abs(dev.strain - strain).max() < 2e-14  # measured 1.3e-15
    i = int(np.argmax(strain[:, 0]))
    assert dev.max_strain == pytest.approx(strain[i, 0], rel=1e-12)  # 0.0354331..., measured 2.2e-14 relative
    assert dev.max_strain_at[0] == pytest.approx(u_a + (u_b - u_a) * i / 32, abs=1e-12)
    assert dev.max_strain_at[1] == s_a  # the strain does not vary along the panel; ties go to the first node
    assert (
        np.abs(dev.max_strain_point - torus_point(math.radians(dev.max_strain_at[0]), s_a)).max() < 1e-12
    )  # measured 3.6e-14
    # areas: the patch Int Int RT (A - RT cos u) / A du ds, the flat annular sector
    area = (
        RT
        * (s_b - s_a)
        / A
        * (A * math.radians(u_b - u_a) - RT * (math.sin(math.radians(u_b)) - math.sin(math.radians(u_a))))
    )
    assert dev.surface_area == pytest.approx(area, rel=1e-14)  # measured 8.9e-16
    slants = torus_development(np.radians([u_a, u_b]), np.array([s_a]), math.radians(60.0), s_a)[0]
    ell = np.linalg.norm(slants, axis=-1)
    sector = 0.5 * math.sin(math.radians(60.0)) * (s_b - s_a) / A * (ell[1] ** 2 - ell[0] ** 2)
    assert dev.flat_area == pytest.approx(sector, rel=1e-13)  # measured 4.2e-15


def torus_point(u: float, s: float) -> np.ndarray:
    """The torus point at the stringer u, the meridian at arc s of the centre circle."""
    phi = s / A
    centre = np.array([A * math.sin(phi), A - A * math.cos(phi), 0.0])
    towards = np.array([-math.sin(phi), math.cos(phi), 0.0])  # r1: to the circle's centre
    return centre + RT * (math.cos(u) * towards + math.sin(u) * np.array([0.0, 0.0, 1.0]))


def test_torus_lengths_are_kept(torus_panel):
    dev = torus_panel
    for s in (50.0, 87.5, 150.0):  # meridians: straight, of length RT (u_b - u_a)
        ring = dev.ring_line(s)
        chord = ring[-1] - ring[0]
        assert np.linalg.norm(chord) == pytest.approx(RT * math.radians(60.0), rel=1e-14)  # measured 1.1e-15
        offsets = (ring - ring[0]) @ np.array([-chord[1], chord[0]]) / np.linalg.norm(chord)
        assert np.abs(offsets).max() < 1e-13  # measured 1.2e-14
    middle = dev.stringer_line(60.0)  # the middle parallel: an arc of the tangent cone's slant
    centre, radius = circle_through(middle)
    assert radius == pytest.approx(
        (A - RT * math.cos(math.radians(60.0))) / math.sin(math.radians(60.0)), rel=1e-13
    )  # 1.6e-15
    assert np.abs(np.linalg.norm(middle - centre, axis=1) - radius).max() < 2e-13  # measured 1.4e-14
    assert arc_length(middle) == pytest.approx(
        (A - RT * math.cos(math.radians(60.0))) * 100.0 / A, rel=1e-14
    )  # 5.6e-16


def test_small_torus_panel_strain_is_gaussian_curvature_times_half_distance_squared(torus):
    u_m, half = 40.0, 1.0  # degrees
    dev = develop_panel(torus, (100.0, 110.0), (u_m - half, u_m + half), samples=(9, 5))
    u_edge = math.radians(dev.max_strain_at[0])
    assert abs(dev.max_strain_at[0] - u_m) == pytest.approx(half)
    gauss = -math.cos(u_edge) / (RT * (A - RT * math.cos(u_edge)))  # K of the torus, in this u
    d = RT * math.radians(half)
    assert dev.max_strain == pytest.approx(
        abs(gauss) * d * d / 2.0, rel=0.01
    )  # measured 9.5e-3 (1.8e-2 at 2 deg: the d^3 term)


def test_outline_and_map(torus_panel):
    from shapely.geometry import Polygon

    dev = torus_panel
    outline = dev.outline()
    assert outline.shape == (2 * 33 + 2 * 65 - 4, 2)
    assert signed_area(outline) > 0.0
    assert Polygon(outline).is_valid
    assert signed_area(outline) == pytest.approx(dev.flat_area, rel=1e-4)  # the polygon's chords: measured 3.1e-5
    assert np.abs(dev.map(dev.angles_deg[:, None], dev.s[None, :]) - dev.grid).max() == 0.0  # the same evaluation
    assert dev.map(60.0, 50.0).shape == (2,)
    assert np.abs(dev.map(60.0, 50.0)).max() < 1e-12  # the middle stringer starts at the origin
    with pytest.raises(ParameterError, match="u_deg"):
        dev.map(95.0, 60.0)
    with pytest.raises(ParameterError, match="s must lie"):
        dev.map(60.0, 151.0)


# --- a canal surface on a curved, twisted axis -------------------------------------------------------
@pytest.fixture(scope="module")
def curved_canal():
    return CanalSurface(NaturalAxis("0.01", "0.003", (0.0, 100.0)), "6 + 0.03 * s")


def polyline_length(f, lo: float, hi: float, n: int = 2048) -> float:
    """Length of the curve f(t), t in [lo, hi], by Richardson extrapolation of two polylines."""

    def chords(m: int) -> float:
        p = f(np.linspace(lo, hi, m + 1))
        return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())

    return (4.0 * chords(2 * n) - chords(n)) / 3.0


@pytest.mark.slow
def test_canal_lengths_and_strain_against_finite_differences(curved_canal):
    base = curved_canal
    s_a, s_b, u_a, u_b = 20.0, 70.0, 10.0, 100.0
    dev = develop_panel(base, (s_a, s_b), (u_a, u_b), samples=(9, 11))
    # rings: the 3-D arc on the characteristic circle (centre c - r r' t, radius r q) between the seams
    for s in (s_a, 44.0, s_b):
        r, dr = 6.0 + 0.03 * s, 0.03
        t = base.axis.rotation_minimising_frame(s)[0]
        centre = base.axis.position(s) - r * dr * t
        a, b = base.points(math.radians(u_a), s) - centre, base.points(math.radians(u_b), s) - centre
        angle = math.atan2(float(np.cross(a, b) @ t), float(a @ b))
        angle = angle if angle > 0 else angle + 2 * math.pi
        assert arc_length(dev.ring_line(s)) == pytest.approx(
            r * math.sqrt(1 - dr * dr) * angle, rel=1e-13
        )  # measured 1.9e-15
    u_m = 0.5 * (u_a + u_b)
    length_3d = polyline_length(lambda s: base.points(math.radians(u_m), s), s_a, s_b)
    length_flat = polyline_length(lambda s: dev.map(u_m, s), s_a, s_b)
    assert length_flat == pytest.approx(length_3d, rel=1e-13)  # measured 1.6e-15
    # the developed metric against central differences of map(), the surface's against points()
    u = dev.angles_deg[1:-1, None]  # the grid's inner nodes
    s = dev.s[None, 1:-1]
    h_u, h_s = 1e-3, 1e-2

    def diff(f, du, ds):
        return (
            -f(u + 2 * du, s + 2 * ds) + 8 * f(u + du, s + ds) - 8 * f(u - du, s - ds) + f(u - 2 * du, s - 2 * ds)
        ) / 12.0

    surf = lambda ud, ss: base.points(np.radians(ud), ss)
    X_u, X_s = diff(surf, h_u, 0) / math.radians(h_u), diff(surf, 0, h_s) / h_s
    P_u, P_s = diff(dev.map, h_u, 0) / math.radians(h_u), diff(dev.map, 0, h_s) / h_s
    tangents = dev.tangents(u, s)
    assert np.abs(tangents[0] - P_u).max() < 1e-9 * np.abs(P_u).max()  # measured 3.3e-11 (the differences' error)
    assert np.abs(tangents[1] - P_s).max() < 1e-11  # measured 7.9e-13
    g = np.stack(
        [
            np.stack([(X_u * X_u).sum(-1), (X_u * X_s).sum(-1)], -1),
            np.stack([(X_u * X_s).sum(-1), (X_s * X_s).sum(-1)], -1),
        ],
        -2,
    )
    a = np.stack(
        [
            np.stack([(P_u * P_u).sum(-1), (P_u * P_s).sum(-1)], -1),
            np.stack([(P_u * P_s).sum(-1), (P_s * P_s).sum(-1)], -1),
        ],
        -2,
    )
    stretch = np.sqrt(np.linalg.eigvals(np.linalg.solve(g, a)).real)
    expected = np.abs(stretch - 1.0).max(axis=-1)
    assert expected.max() > 1e-3  # a doubly curved panel: measured 0.0122
    assert np.abs(dev.strain[1:-1, 1:-1] - expected).max() < 5e-10  # measured 2.7e-11


# --- files ---------------------------------------------------------------------------------------
def test_dxf_reads_back(torus_panel, tmp_path):
    import ezdxf

    dev = torus_panel
    marks = {"torus_panel": [("mark_ring_01", dev.ring_line(100.0)), ("mark_stringer_01", dev.stringer_line(60.0))]}
    (path,) = write_panel_dxf([dev], marks, tmp_path)
    assert path.name == "torus_panel_development.dxf"
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4  # mm
    assert {"OUTLINE", "MARKING", "TEXT", "STRAIN"} <= {layer.dxf.name for layer in doc.layers}
    space = doc.modelspace()
    (outline,) = space.query('LWPOLYLINE[layer=="OUTLINE"]')
    assert outline.closed
    assert np.abs(np.array(outline.get_points("xy")) - dev.outline()).max() < 1e-9
    marking = space.query('LWPOLYLINE[layer=="MARKING"]')
    assert len(marking) == 2 and not any(m.closed for m in marking)
    assert np.abs(np.array(marking[0].get_points("xy")) - dev.ring_line(100.0)).max() < 1e-9
    texts = {t.dxf.text for t in space.query('TEXT[layer=="TEXT"]')}
    assert {"torus_panel", "mark_ring_01", "mark_stringer_01"} <= texts
    (strain,) = space.query('TEXT[layer=="STRAIN"]')
    assert "max strain 3.543e-02" in strain.dxf.text and "u = 30 deg" in strain.dxf.text
    (metres,) = write_panel_dxf([dev], {}, tmp_path, length_unit="m")
    assert ezdxf.readfile(metres).header["$INSUNITS"] == 6
    assert not list(tmp_path.glob(".*part*"))


def test_picture(torus_panel, tmp_path):
    dev = torus_panel
    paths = write_panel_picture(dev, [("mark_ring_01", dev.ring_line(100.0))], tmp_path)
    assert sorted(p.name for p in paths) == ["torus_panel_development.png", "torus_panel_development.svg"]
    assert all(p.stat().st_size > 1000 for p in paths)


def test_bad_input(cylinder):
    with pytest.raises(ParameterError, match="s_range must lie within"):
        develop_panel(cylinder, (-5.0, 10.0), (0.0, 90.0))
    with pytest.raises(ParameterError, match="at most 360"):
        develop_panel(cylinder, (0.0, 10.0), (0.0, 400.0))
    with pytest.raises(ParameterError, match="angles_deg must be increasing"):
        develop_panel(cylinder, (0.0, 10.0), (90.0, 0.0))
    with pytest.raises(ParameterError, match="samples n_u"):
        develop_panel(cylinder, (0.0, 10.0), (0.0, 90.0), samples=(1, 5))
    with pytest.raises(ParameterError, match="name"):
        develop_panel(cylinder, (0.0, 10.0), (0.0, 90.0), name="a/b")
