"""The reinforcement pad round a branch (issue 25), against an independent quadrature: on a
straight main tube (outer radius R along x) the pad between R and R + t over the rings
s_a..s_b and the angles a..b, with the branch's outer cylinder (x - x0)^2 + y^2 = r^2 cut out,
has the volume (b - a) / 2 ((R + t)^2 - R^2) (s_b - s_a) less
int_{-r}^{r} 2 sqrt(r^2 - y^2) (sqrt((R + t)^2 - y^2) - sqrt(R^2 - y^2)) dy; it develops with
no strain (a cylinder); a pad too wide is refused naming its key."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from tubecad import NaturalAxis, ParameterError
from tubecad.brep.properties import is_valid, volume
from tubecad.junctions import saddle_curve
from tubecad.shop.panel_development import develop_panel
from tubecad.stiffeners.pad import reinforcement_pad
from tubecad.surface.canal import tube_or_canal

R, r, L = 52.0, 31.5, 400.0  # the main's and the branch's outer radii
MAIN = tube_or_canal(NaturalAxis("0", "0", (0.0, L), normal=(0, 1, 0)), R)  # along x from 0; r1 = y, r2 = z
BRANCH = tube_or_canal(NaturalAxis("0", "0", (0.0, 150.0), origin=(150, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), r)
SADDLE = saddle_curve(MAIN, BRANCH, 257)


@pytest.fixture(scope="module")
def pad():
    return reinforcement_pad(MAIN, BRANCH, SADDLE, 6.0, 25.0)


def test_the_pad_spans_the_saddle_plus_its_width_between_curvature_lines(pad):
    """The saddle runs x = 150 +- r, angle 90 deg +- asin(r / R): the pad 25 beyond it."""
    assert pad.s_range == pytest.approx((150 - r - 25, 150 + r + 25), abs=1e-9)
    half = math.degrees(math.asin(r / R) + 25 / R)
    assert pad.angles_deg == pytest.approx((90 - half, 90 + half), abs=1e-9)
    assert pad.diameter == pytest.approx(2 * (r + 25), abs=1e-9)


def test_the_pad_s_volume_is_the_sector_less_the_branch(pad):
    t = pad.thickness
    (a, b), (s_a, s_b) = np.radians(pad.angles_deg), pad.s_range
    sector = (b - a) / 2 * ((R + t) ** 2 - R**2) * (s_b - s_a)
    hole, _ = quad(
        lambda y: 2 * math.sqrt(r**2 - y**2) * (math.sqrt((R + t) ** 2 - y**2) - math.sqrt(R**2 - y**2)),
        -r,
        r,
        epsabs=1e-12,
        epsrel=1e-13,
    )
    assert is_valid(pad.solid.wrapped) and len(pad.solid.solids()) == 1
    # measured 2.7e-10
    assert volume(pad.solid.wrapped) == pytest.approx(sector - hole, rel=1e-8)


def test_the_pad_develops_without_strain_on_a_cylinder(pad):
    development = develop_panel(pad.surface, pad.s_range, pad.angles_deg, "pad")
    assert development.max_strain < 1e-12  # measured 8.6e-16
    assert development.flat_area == pytest.approx(R * np.radians(np.ptp(pad.angles_deg)) * np.ptp(pad.s_range))


@pytest.mark.parametrize(
    ("length", "width", "says"),
    [
        (1000.0, 140.0, "all round the main tube"),  # 2 (asin(r / R) + w / R) > 2 pi from w = 129.5
        (300.0, 130.0, "past the main tube's span"),
        (L, 0.0, "must be > 0"),
    ],
)
def test_a_pad_too_wide_is_refused_naming_its_key(length, width, says):
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, length), origin=(150 - length / 2, 0, 0), normal=(0, 1, 0)), R)
    with pytest.raises(ParameterError, match=says) as info:
        reinforcement_pad(main, BRANCH, saddle_curve(main, BRANCH, 65), 6.0, width)
    assert info.value.key == "pad.width" and "\n" not in str(info.value)  # the spec adds [[branches]]


def test_a_pad_on_a_conical_main_is_the_cone_shells_sector_less_the_branch():
    """Issue 43: the main a cone, its outer surface the envelope of spheres of radius
    r(s) = 61.5 - 0.05 s about the x axis (half-angle phi, sin phi = 0.05), a branch of outer
    radius 21 up z at x = 150. In a meridian half-plane the pad's section is a rectangle, the
    meridian between its rings (their points at x = s - r r', radius r cos phi) by the
    thickness t along the normal (sin phi, cos phi): Pappus gives the sector's volume
    angle x length x t x (its centroid's radius); less the branch's hole,
    int int [sqrt(rho_t(x)^2 - y^2) - sqrt(rho(x)^2 - y^2)] over (x - 150)^2 + y^2 < 21^2,
    rho(x) = (61.5 - 0.05 x) / cos phi the cone's radius at x (scipy's quadrature). It is
    bounded by the saddle's extent plus the width, round the axis at the smallest radius."""
    from scipy.integrate import dblquad

    cone = tube_or_canal(NaturalAxis("0", "0", (0.0, 300.0), normal=(0, 1, 0)), "61.5 - 0.05 * s")
    branch = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 150.0), origin=(150, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), 21.0
    )
    saddle = saddle_curve(cone, branch, 257)
    t, width = 4.0, 15.0
    pad = reinforcement_pad(cone, branch, saddle, t, width)
    assert is_valid(pad.solid.wrapped)
    (s_lo, s_hi), (u_lo, u_hi) = saddle.extent(saddle.main_s), saddle.extent(saddle.main_u)
    s_a, s_b = pad.s_range
    assert (s_a, s_b) == pytest.approx((s_lo - width, s_hi + width), abs=1e-12)
    smallest = 61.5 - 0.05 * s_b
    assert pad.angles_deg == pytest.approx(
        (math.degrees(u_lo - width / smallest), math.degrees(u_hi + width / smallest)), rel=1e-6
    )
    cos_phi = math.sqrt(1 - 0.05**2)

    def ring_point(s: float) -> tuple[float, float]:  # (x, radius) of the outer ring at s
        r = 61.5 - 0.05 * s
        return s + 0.05 * r, r * cos_phi

    (xa, ra), (xb, rb) = ring_point(s_a), ring_point(s_b)
    length = math.hypot(xb - xa, rb - ra)
    angle = math.radians(pad.angles_deg[1] - pad.angles_deg[0])
    sector = angle * length * t * (0.5 * (ra + rb) + 0.5 * t * cos_phi)

    def rho(x: float, d: float) -> float:
        return (61.5 + d - 0.05 * x) / cos_phi

    hole, _ = dblquad(
        lambda y, x: math.sqrt(rho(x, t) ** 2 - y**2) - math.sqrt(rho(x, 0.0) ** 2 - y**2),
        150.0 - 21.0,
        150.0 + 21.0,
        lambda x: -math.sqrt(max(21.0**2 - (x - 150.0) ** 2, 0.0)),
        lambda x: math.sqrt(max(21.0**2 - (x - 150.0) ** 2, 0.0)),
        epsabs=1e-10,
        epsrel=1e-12,
    )
    assert volume(pad.solid.wrapped) == pytest.approx(sector - hole, rel=1e-12)  # measured 2.0e-15
