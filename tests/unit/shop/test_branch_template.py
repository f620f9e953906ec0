"""The branch's cutting template (issue 25): the saddle of perpendicular cylinders unrolled,
against its closed form y = sqrt(R^2 - r^2 sin^2(x / r)), read back from the DXF by ezdxf
and shapely; the strain of a curved branch's development; the refusal of a cone."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import NaturalAxis, ParameterError, saddle_curve, tube_or_canal
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
    assert info.value.key == "branches.radius"
