"""Stiffener solids built with no boolean, and the heights they may have (issue 9, items 1 and 7)."""

import math

import build123d as bd
import numpy as np
import pytest
from test_stiffeners import section_moments

from tubecad import CurvatureLineTube, ParameterError
from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.spec.paper import paper_tube
from tubecad.stiffeners.assembly import build_stiffeners
from tubecad.stiffeners.panels import split_into_panels
from tubecad.stiffeners.profiles import Profile
from tubecad.stiffeners.rings import ring_section
from tubecad.stiffeners.solids import ring_stiffener, stringer_stiffener

PROFILES = {
    "flat": lambda h: Profile("flat", h, 1.0),
    "T": lambda h: Profile("T", h, 1.0, 4.0, 0.8),
    "L": lambda h: Profile("L", h, 1.0, 4.0, 0.8),
}


def ring_volume(profile: Profile, s: float, R: float, side: str, span: tuple[float, float]) -> float:
    """The ring as rectangles in (s, r), web and flange, each clipped to the span: a tube of
    radius r between s_a and s_b encloses pi r^2 (s_b - s_a) (Pappus on a curved axis), so
    the ring holds sum pi |r_b^2 - r_a^2| (s_b - s_a)."""
    sign = 1.0 if side == "outside" else -1.0
    tw, h = profile.thickness, profile.height
    web_top = h if profile.kind == "flat" else h - profile.flange_thickness
    rects = [(s - tw / 2, s + tw / 2, 0.0, web_top)]
    if profile.kind == "T":
        rects.append((s - profile.flange_width / 2, s + profile.flange_width / 2, web_top, h))
    elif profile.kind == "L":
        rects.append((s - tw / 2, s - tw / 2 + profile.flange_width, web_top, h))
    total = 0.0
    for sa, sb, ha, hb in rects:
        sa, sb = max(sa, span[0]), min(sb, span[1])
        total += math.pi * abs((R + sign * hb) ** 2 - (R + sign * ha) ** 2) * max(sb - sa, 0.0)
    return total


def stringer_volume(tube: CurvatureLineTube, profile: Profile, side: str, theta: float, span) -> float:
    """V = Int [A - k (cos phi Mv - sin phi Mw)] ds, phi = theta - Int sigma ds (the Jacobian
    of C + v N + w E), by Gauss-Legendre; A, Mv, Mw: the cross-section's area and moments."""
    area, mv, mw = section_moments(profile, tube.radius, side)
    x, w = np.polynomial.legendre.leggauss(48)
    edges = np.linspace(*span, 9)
    s = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * x).ravel()
    phi = math.radians(theta) - tube.axis.twist(s)
    integrand = area - tube.axis.curvature(s) * (np.cos(phi) * mv - np.sin(phi) * mw)
    return float((integrand * np.tile(w, 8)).sum() * 0.5 * (edges[1] - edges[0]))


@pytest.mark.parametrize("kind", ["flat", "T", "L"])
@pytest.mark.parametrize("side, R", [("outside", 16.0), ("inside", 14.0)])
@pytest.mark.parametrize("s", [640.0, 200.4, 1199.9])  # the middle, clipped by the span's start and end
def test_ring_frame_is_one_solid_with_the_exact_volume(kind, side, R, s):
    tube = CurvatureLineTube(paper_tube().axis, R)
    profile = PROFILES[kind](3.5)  # (16 + 3.5) k(200) = 0.975 outside
    ring = ring_stiffener(tube, s, profile, side).solid
    assert isinstance(ring, bd.Solid) and props.is_valid(ring) and props.free_edges(ring) == 0
    assert props.count(ring, "solid") == 1
    exact = ring_volume(profile, s, R, side, tube.span)
    assert props.volume(ring) == pytest.approx(exact, rel=1e-9)  # measured: <= 1e-12
    # every constant-s side of the section is one planar annulus bounded by exact circles
    section = ring_section(profile, s, R, side, tube.span)
    annuli = sum(1 for a, b in zip(section, section[1:] + section[:1]) if a[0] == b[0])
    planes = [f for f in ring.faces() if f.geom_type == bd.GeomType.PLANE]
    assert len(planes) == annuli
    assert all(e.geom_type == bd.GeomType.CIRCLE for f in planes for e in f.edges())
    assert ring.edges().filter_by(bd.GeomType.CIRCLE)  # what CAD selectors find


@pytest.mark.slow
def test_stiffeners_pass_the_pre_boolean_check():
    """OCCT's BOPAlgo_ArgumentAnalyzer with every check on (FreeCAD's "BOP check")."""
    axis = paper_tube().axis
    ring = ring_stiffener(CurvatureLineTube(axis, 16.0), 640.0, PROFILES["T"](6.0), "outside").solid
    assert props.analyzer_findings(ring) == {}
    stringer = stringer_stiffener(
        CurvatureLineTube(axis, 14.0), 37.0, PROFILES["T"](13.9), "inside", span=(400.0, 450.0)
    )
    assert props.analyzer_findings(stringer.solid) == {}
    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 3, 8))
    panel = split_into_panels(build, [0, 3])[0]  # a 135 deg panel: cut where the circle is C0
    assert props.is_valid(panel.solid) and props.analyzer_findings(panel.solid) == {}


@pytest.mark.parametrize("kind", ["flat", "T"])
@pytest.mark.parametrize("height", [6.0, 10.0, 13.9])
def test_inside_stringers_up_to_the_wall_radius(kind, height):
    """Inside, a stringer reaches in to R - height and out to R: fitted to R, it builds up
    to height < R on the paper wall 14..16 (k(200) = 0.05; 20 k = 1 was refused)."""
    tube = CurvatureLineTube(paper_tube().axis, 14.0)
    profile = PROFILES[kind](height)
    span = (200.0, 320.0)
    stringer = stringer_stiffener(tube, 200.0, profile, "inside", span=span).solid
    assert props.is_valid(stringer) and props.free_edges(stringer) == 0
    assert props.volume(stringer) == pytest.approx(stringer_volume(tube, profile, "inside", 200.0, span), rel=1e-7)


@pytest.mark.filterwarnings("error")  # no divide-by-zero from the frame fit
def test_readme_stiffeners_build_inside():
    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, layout=NetLayout.equal(tube, rings=11, stringers=8))
    stiffeners = build_stiffeners(
        build, rings=[1, 2], stringers=[0, 4], profile=Profile("T", 6, 1, 4, 1), side="inside"
    )
    assert [s.name for s in stiffeners] == ["ring_01", "ring_02", "stringer_00", "stringer_04"]
    assert all(props.is_valid(s.solid) for s in stiffeners)
    s1 = build.layout.s_rings[1]
    assert props.volume(stiffeners[0].solid) == pytest.approx(
        ring_volume(Profile("T", 6, 1, 4, 1), s1, 14.0, "inside", tube.span), rel=1e-9
    )


def test_outside_stiffeners_beyond_the_limit_are_refused_before_fitting():
    axis = paper_tube().axis
    base = CurvatureLineTube(axis, 16.0)
    # a ring sees the curvature of its own span: k = 10 / 639.5 at its start, 1 / k - 16 = 47.95
    with pytest.raises(
        ParameterError,
        match=r"height must be < 47\.95 for side = 'outside' on this wall: "
        r"\(R \+ height\) max\|k\| must stay < 1 \(R = 16, max\|k\| = 0\.0156372 "
        r"at s = 639\.5\), got 48$",
    ):
        ring_stiffener(base, 640.0, Profile("flat", 48.0, 1.0), "outside")
    # a stringer's corners at w = +-0.5: sqrt((16 + h)^2 + 0.25) k(200) < 1, h < sqrt(400 - 0.25) - 16
    limit = math.sqrt(400 - 0.25) - 16
    with pytest.raises(
        ParameterError,
        match=rf"height must be < {limit:.6g} for side = 'outside' on this wall: .*"
        r"\(R = 16, max\|k\| = 0\.05 at s = 200\), got 4$",
    ):
        stringer_stiffener(base, 0.0, Profile("flat", 4.0, 1.0), "outside")
    with pytest.raises(ParameterError, match=r"height must be < R = 14 for side = 'inside'"):
        stringer_stiffener(CurvatureLineTube(axis, 14.0), 0.0, Profile("flat", 14.0, 1.0), "inside")
    # just below the limits (0.999 of it) they build: the ring's frame is fitted on a span
    # long enough for the orthogonality target (a 0.5-long one was not)
    ring = ring_stiffener(base, 200.0, Profile("flat", 3.98, 1.0), "outside").solid
    assert props.is_valid(ring) and props.volume(ring) == pytest.approx(math.pi * (19.98**2 - 16**2) * 0.5, rel=1e-9)
    stringer = stringer_stiffener(base, 0.0, Profile("flat", 0.999 * limit, 1.0), "outside", span=(200.0, 260.0)).solid
    assert props.is_valid(stringer)


def test_one_seam_gives_whole_bays():
    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 3, 4))
    panels = split_into_panels(build, [1])
    assert [p.angles_deg for p in panels] == [(90.0, 450.0)] * 2
    assert all(props.is_valid(p.solid) and props.free_edges(p.solid) == 0 for p in panels)
    assert sum(props.volume(p.solid) for p in panels) == pytest.approx(math.pi * (16**2 - 14**2) * 1000, rel=1e-9)
    assert panels[0].outer_area == pytest.approx(2 * math.pi * 16 * 500, rel=1e-9)


def test_a_ring_off_the_span_is_refused():
    tube = CurvatureLineTube(paper_tube().axis, 16.0)
    with pytest.raises(ParameterError, match=r"the ring at s = 100 lies outside the span \[200, 1200\]"):
        ring_stiffener(tube, 100.0, PROFILES["T"](3.0), "outside")
    # a flange reaching past the span's end is clipped there: half the ring at s = 200 is left
    ring = ring_stiffener(tube, 200.0, PROFILES["flat"](3.0), "outside").solid
    assert props.volume(ring) == pytest.approx(math.pi * (19**2 - 16**2) * 0.5, rel=1e-9)
