"""The branch's cutting template (issue 25): the saddle of perpendicular cylinders unrolled,
against its closed form y = sqrt(R^2 - r^2 sin^2(x / r)), read back from the DXF by ezdxf
and shapely; the strain of a curved branch's development; the refusal of a conical branch (and of
a conical main's strip: its opening is developed on a panel, test_hole_development.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import NaturalAxis, ParameterError, tube_or_canal
from tubecad.junctions import saddle_curve
from tubecad.shop.branch_template import branch_template

R, r = 50.0, 20.0


def line(origin, tangent, normal, length, radius):
    return tube_or_canal(NaturalAxis("0", "0", (0.0, length), origin=origin, tangent=tangent, normal=normal), radius)


MAIN = line((-100.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 200.0, R)
BRANCH = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)


def test_the_template_of_a_tee_is_the_closed_form_and_reads_back(tmp_path):
    import ezdxf
    from shapely.geometry import LineString, Polygon

    template = branch_template(BRANCH, saddle_curve(MAIN, BRANCH, 181), stringers=8)
    assert template.strain == 0.0 and template.girth == pytest.approx(2 * math.pi * r, rel=1e-15)
    path = template.save_dxf(tmp_path / "branch.dxf")
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4  # millimetres
    space = doc.modelspace()
    (saddle,) = space.query('LWPOLYLINE[layer=="saddle"]')
    xy = np.array([(x, y) for x, y, *_ in saddle.get_points()])
    assert np.abs(xy[:, 1] - np.sqrt(R**2 - r**2 * np.sin(xy[:, 0] / r) ** 2)).max() < 1e-12
    assert xy[0, 0] == 0.0 and xy[-1, 0] == pytest.approx(2 * math.pi * r, rel=1e-15)
    (outline,) = space.query('LWPOLYLINE[layer=="outline"]')
    strip = Polygon([(x, y) for x, y, *_ in outline.get_points()])
    assert strip.bounds == pytest.approx((0.0, 0.0, 2 * math.pi * r, 120.0), abs=1e-12)
    assert strip.contains(LineString(xy[1:-1]))  # the cut lies inside the strip
    marks = sorted(m.dxf.start[0] for m in space.query('LINE[layer=="girth_marks"]'))
    assert np.allclose(marks, 2 * math.pi * r * np.arange(8) / 8, rtol=0, atol=1e-12)
    assert sorted(t.dxf.text for t in space.query("TEXT")) == [f"stringer_{j:02d}" for j in range(8)]


def test_a_curved_branch_reports_the_strain_of_its_development():
    """A branch bent to radius 200 (k = 1/200, r = 20): the stringers stretch by
    |rho k cos(u - theta)| <= rho k = 0.1 along the saddle, and at least a part of that."""
    bent = tube_or_canal(
        NaturalAxis("1/200", "0", (0.0, 100.0), origin=(0, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), r
    )
    template = branch_template(bent, saddle_curve(MAIN, bent, 97))
    assert 0.05 < template.strain <= 20.0 / 200.0 + 1e-15


def test_a_conical_branch_is_refused_naming_its_radius():
    cone = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 100.0), origin=(0, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), "20 - 0.1 * s"
    )
    with pytest.raises(ParameterError, match="sector") as info:
        branch_template(cone, saddle_curve(MAIN, cone, 65))
    assert info.value.key == "branch.radius"  # the library's name; the spec adds [[branches]]


def test_a_conical_main_tubes_strip_is_refused_naming_its_key_and_the_panel():
    """The strip's template of a conical main tube's opening is refused, naming the main tube's
    radius under the caller's ``key`` (``main`` by default) and the panel's development that
    makes it (tests/unit/shop/test_hole_development.py; the shop package uses it)."""
    from tubecad.shop.branch_template import hole_template

    cone = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 200.0), origin=(-100.0, 0.0, 0.0), tangent=(1, 0, 0), normal=(0, 1, 0)),
        "55 - 0.05 * s",
    )
    saddle = saddle_curve(cone, BRANCH, 65)
    with pytest.raises(ParameterError, match="sector, not a strip; its opening is developed on a panel by") as info:
        hole_template(cone, saddle)
    assert info.value.key == "main.radius" and "hole_development.hole_development" in str(info.value)
    with pytest.raises(ParameterError, match="^vessel.radius: a main tube") as info:
        hole_template(cone, saddle, key="vessel")
    assert info.value.key == "vessel.radius"


def test_the_main_tubes_hole_template_is_the_closed_form_and_its_area(tmp_path):
    """The opening on the main tube unrolled to (R chi, s_A): chi = atan2(z, y) with
    y = r sin u, z = sqrt(R^2 - r^2 sin^2 u), s_A = 100 + r cos u; one closed line, whose
    area (shapely, read back from the DXF) is the developed hole's
    int R 2 sqrt(r^2 - R^2 cos^2 chi) dchi (scipy's quadrature)."""
    import ezdxf
    from scipy.integrate import quad
    from shapely.geometry import Polygon

    from tubecad.shop.branch_template import hole_template

    saddle = saddle_curve(MAIN, BRANCH, 721)
    template = hole_template(MAIN, saddle)
    u = saddle.branch_u
    chi = np.arctan2(np.sqrt(R**2 - r**2 * np.sin(u) ** 2), r * np.sin(u))
    assert np.abs(template.points - np.column_stack([R * chi, r * np.cos(u) + 100.0])).max() < 1e-11
    assert template.strain == 0.0 and template.girth == pytest.approx(2 * math.pi * R, rel=1e-15)

    doc = ezdxf.readfile(template.save_dxf(tmp_path / "hole.dxf"))
    (hole,) = doc.modelspace().query('LWPOLYLINE[layer=="saddle"]')
    assert hole.closed
    a = math.acos(r / R)
    exact, _ = quad(lambda c: R * 2 * math.sqrt(max(r**2 - R**2 * math.cos(c) ** 2, 0.0)), a, math.pi - a, limit=200)
    area = Polygon([(x, y) for x, y, *_ in hole.get_points()]).area
    assert area == pytest.approx(exact, rel=3e-5)  # the 720-sided polygon's chords: measured 1.3e-5


def test_the_dihedral_angle_of_a_tee_is_the_closed_form():
    """n_A = (0, y, z) / R, n_B = (x, y, 0) / r on the saddle: cos phi = y^2 / (R r) = r sin^2 u / R."""
    from tubecad.junctions import dihedral_angles

    saddle = saddle_curve(MAIN, BRANCH, 97)
    phi = dihedral_angles(MAIN, BRANCH, saddle)
    expected = np.degrees(np.arccos(r * np.sin(saddle.branch_u) ** 2 / R))
    assert np.abs(phi - expected).max() < 1e-12  # degrees; measured 1.3e-13
    assert phi.min() == pytest.approx(np.degrees(np.arccos(r / R)), abs=1e-10) and phi.max() == pytest.approx(90.0)


def test_the_equal_tees_templates_are_the_closed_forms(tmp_path):
    """r = R (issue 43): the branch's cut y = sqrt(R^2 - R^2 sin^2(x / R)) = R |cos(x / R)|,
    from crotch (y = 0) to crotch, two arches; the hole on the main unrolled to (R chi, s_A)
    with chi = atan2(R |cos u|, R sin u), its area int_0^pi 2 R^2 sin(chi) dchi = 4 R^2; the
    dihedral angle arccos(sin^2 u), 0 at the crotch where the tubes touch."""
    import ezdxf
    from shapely.geometry import Polygon

    from tubecad.junctions import dihedral_angles
    from tubecad.shop.branch_template import hole_template

    equal = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, R)
    saddle = saddle_curve(MAIN, equal, 721)
    template = branch_template(equal, saddle, stringers=8)
    xy = template.points
    assert np.abs(xy[:, 1] - R * np.abs(np.cos(xy[:, 0] / R))).max() < 1e-12 * R  # measured 1.2e-13 R
    assert np.abs(xy[list(saddle.corners), 1]).max() < 1e-12 * R  # the crotch points: height 0
    hole = hole_template(MAIN, saddle)
    u = saddle.branch_u
    chi = np.arctan2(R * np.abs(np.cos(u)), R * np.sin(u))
    # measured 1.02e-11 = 2e-13 R (round-off of the arc lengths R chi; below 1e-11 on earlier installs)
    assert np.abs(hole.points - np.column_stack([R * chi, R * np.cos(u) + 100.0])).max() < 2e-11
    doc = ezdxf.readfile(hole.save_dxf(tmp_path / "hole.dxf"))
    (outline,) = doc.modelspace().query('LWPOLYLINE[layer=="saddle"]')
    area = Polygon([(x, y) for x, y, *_ in outline.get_points()]).area
    assert area == pytest.approx(4 * R**2, rel=1e-5)  # the 720-sided polygon's chords: measured 6.3e-6
    phi = dihedral_angles(MAIN, equal, saddle)
    # arccos near 1 turns round-off e into sqrt(2 e): measured 2.4e-6 deg at the crotch
    assert np.abs(phi - np.degrees(np.arccos(np.sin(u) ** 2))).max() < 1e-5
