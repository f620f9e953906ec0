"""The opening on a main tube whose radius varies (a nozzle on a conical head), developed on
the panel of the main round it: on a cone against the cone's exact development (a point at
slant distance rho from the apex, angle theta round the axis, goes to the polar point
(rho, theta sin a)), its area against the quadrature of the hole on the cone, read back from
the DXF by ezdxf and shapely; on a cylinder against the strip's template; the panel's bounds
and the refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.distance import pdist

from tubecad import NaturalAxis, ParameterError, tube_or_canal
from tubecad.junctions import saddle_curve
from tubecad.shop.hole_development import HolePanel, hole_bounds, hole_development

SLOPE, R0, r = 0.05, 55.0, 20.0  # the cone's spheres r(s) = 55 - 0.05 s about the x axis from x = -100
CONE = tube_or_canal(
    NaturalAxis("0", "0", (0.0, 200.0), origin=(-100.0, 0.0, 0.0), tangent=(1, 0, 0), normal=(0, 1, 0)),
    f"{R0} - {SLOPE} * s",
)
BRANCH = tube_or_canal(NaturalAxis("0", "0", (0.0, 120.0), origin=(0, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), r)
#: the apex, where the spheres' radius is 0 (s = R0 / SLOPE), and the half-angle a, sin a = |r'|
APEX = np.array([-100.0 + R0 / SLOPE, 0.0, 0.0])
COS_A = math.sqrt(1.0 - SLOPE**2)


@pytest.fixture(scope="module")
def saddle():
    return saddle_curve(CONE, BRANCH, 721)


def cone_development(points: np.ndarray) -> np.ndarray:
    """The cone's exact development of 3-D points on it: polar (rho, theta sin a)."""
    rho = np.linalg.norm(points - APEX, axis=1)
    theta = np.unwrap(np.arctan2(points[:, 2], points[:, 1]))
    return np.column_stack([rho * np.cos(theta * SLOPE), rho * np.sin(theta * SLOPE)])


def test_the_hole_on_a_cone_is_its_exact_development(saddle):
    """Pairwise distances are blind to a rigid motion (or a reflection): the developed saddle's
    agree with those of the exact development of its 3-D points, and the panel has no strain."""
    development, line = hole_development(CONE, saddle, 2.0, "hole")
    assert line.shape == (721, 2) and np.array_equal(line[0], line[-1])  # closed as the saddle is
    # the saddle's points are on the cone of half-angle a: their distance from the axis is rho sin a
    slant, across = np.linalg.norm(saddle.points - APEX, axis=1), np.hypot(*saddle.points[:, 1:].T)
    assert np.abs(slant * SLOPE - across).max() < 2e-12  # measured 1.5e-13
    exact = cone_development(saddle.points)
    got, want = pdist(line[:-1]), pdist(exact[:-1])
    assert np.abs(got - want).max() < 1e-13 * want.max()  # measured 9.8e-15 (4.1e-13 absolute)
    assert development.max_strain < 5e-14  # measured 5.2e-15
    assert development.flat_area == pytest.approx(development.surface_area, rel=1e-13)  # measured 6.2e-15


def test_the_developed_holes_area_is_the_holes_area_on_the_cone(saddle):
    """The hole on the cone, x^2 + y^2 < r^2 with the cone's radius rho(x) = (x_apex - x) tan a
    round the x axis: at each x the angle 2 asin(sqrt(r^2 - x^2) / rho(x)) of a ring of radius
    rho, the area element rho dx dtheta / cos a (scipy's quadrature); the developed polygon
    (shapely) falls short of it by its 720 chords only, and matches the exact development's."""
    from scipy.integrate import quad
    from shapely.geometry import Polygon

    _, line = hole_development(CONE, saddle, 2.0, "hole")
    tan_a = SLOPE / COS_A

    def across(x: float) -> float:
        rho = (APEX[0] - x) * tan_a
        return rho / COS_A * 2.0 * math.asin(math.sqrt(max(r * r - x * x, 0.0)) / rho)

    exact, _ = quad(across, -r, r, limit=200, epsabs=1e-12)
    polygon = Polygon(line[:-1])
    assert polygon.is_valid and polygon.area == pytest.approx(exact, rel=3e-5)  # measured 1.27e-5 (the chords)
    assert polygon.area == pytest.approx(Polygon(cone_development(saddle.points)[:-1]).area, rel=1e-12)  # 1e-15


def test_the_panel_is_the_margin_beyond_the_saddle_at_the_smallest_ring(saddle):
    """Rings the margin beyond the saddle's s extent; stringers margin / (r q) beyond its angles,
    r q the ring's radius (q = cos a) at the panel's narrow end s_b; clipped to the span."""
    (s_lo, s_hi), (u_lo, u_hi) = saddle.extent(saddle.main_s), saddle.extent(saddle.main_u)
    (s_a, s_b), (u_a, u_b) = hole_bounds(CONE, saddle, 2.0)
    assert (s_a, s_b) == pytest.approx((s_lo - 2.0, s_hi + 2.0), abs=1e-12)
    ring = (R0 - SLOPE * s_b) * COS_A
    assert (u_a, u_b) == pytest.approx((math.degrees(u_lo - 2.0 / ring), math.degrees(u_hi + 2.0 / ring)), rel=1e-12)
    (s_a, s_b), _ = hole_bounds(CONE, saddle, 150.0)
    assert (s_a, s_b) == (0.0, 200.0)
    development, line = hole_development(CONE, saddle, 2.0, "hole")
    from shapely.geometry import Polygon

    assert Polygon(development.outline()).contains(Polygon(line[:-1]))


def test_on_a_cylinder_the_panel_is_the_strip_template_moved(saddle):
    """On a straight cylinder both developments are exact: the panel's hole is the strip's
    (R u, s) hole up to a rigid motion."""
    from tubecad.shop.branch_template import hole_template

    cylinder = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 200.0), origin=(-100.0, 0.0, 0.0), tangent=(1, 0, 0), normal=(0, 1, 0)), 50.0
    )
    on_cylinder = saddle_curve(cylinder, BRANCH, 361)
    development, line = hole_development(cylinder, on_cylinder, 2.0, "hole")
    strip = hole_template(cylinder, on_cylinder).points
    got, want = pdist(line), pdist(strip)
    assert np.abs(got - want).max() < 2e-14 * want.max()  # measured 1.6e-15
    assert development.max_strain < 1e-14  # measured 3.8e-16


@pytest.mark.parametrize("margin", [0.0, -1.0, math.inf, math.nan, "2", True])
def test_a_margin_not_a_positive_length_is_refused(saddle, margin):
    with pytest.raises(ParameterError, match="margin") as info:
        hole_development(CONE, saddle, margin, "hole")
    assert info.value.key == "margin"


def test_the_drawing_reads_back_with_the_closed_hole_and_the_stringer_marks(saddle, tmp_path):
    import ezdxf

    development, line = hole_development(CONE, saddle, 2.0, "branch_0_hole")
    marks = {f"stringer_{j:02d}": 45.0 * j for j in range(8)}  # only stringer_02 (90 deg) crosses it
    path = HolePanel(development, line, marks).save_dxf(tmp_path / "branch_0_hole.dxf")
    assert path.name == "branch_0_hole.dxf"
    space = ezdxf.readfile(path).modelspace()
    (hole,) = space.query('LWPOLYLINE[layer=="saddle"]')
    assert hole.closed
    assert np.abs(np.array([p[:2] for p in hole.get_points()]) - line[:-1]).max() < 1e-12
    (outline,) = space.query('LWPOLYLINE[layer=="outline"]')
    assert outline.closed
    assert [t.dxf.text for t in space.query('TEXT[layer=="girth_marks"]')] == ["stringer_02"]
    (mark,) = space.query('LINE[layer=="girth_marks"]')
    foot = development.map(90.0, development.s_range[0])
    assert np.allclose((mark.dxf.start.x, mark.dxf.start.y), foot, rtol=0, atol=1e-12 * R0)
