"""Stiffeners on a junction (issue 25), on the square tee whose outer surfaces are main
y^2 + z^2 = 52^2 along x and branch (x - 150)^2 + y^2 = 31.5^2 up z: a flat bar (10 high,
2 thick) stringer crossing the opening stops where its base meets the saddle, x = 150 -+ 31.5
on top, each piece a prism of the full stringer's section; the ring through the branch's axis
loses the angle the opening spans there, pi - 2 acos(31.5 / 52), and its ends lie in planes
through the main axis (square ends); a pad's edge stops them instead; a branch ring too near
its saddle is refused naming the key."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import NaturalAxis, ParameterError, tube_or_canal
from tubecad.brep.properties import is_valid
from tubecad.junctions import branch_surface, saddle_curve
from tubecad.stiffeners.junction import Keepout, branch_stiffeners, main_stiffeners
from tubecad.stiffeners.profiles import Profile

BAR = Profile("flat", 10.0, 2.0)


@pytest.fixture(scope="module")
def tee():
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, 400.0), normal=(0, 1, 0)), 50.0)
    branch = branch_surface(main, 150.0, 150.0, 30.0)
    outer, branch_outer = main.offset(2.0), branch.offset(1.5)
    return outer, branch_outer, saddle_curve(outer, branch_outer)


def test_a_stringer_across_the_opening_stops_on_the_saddle(tee):
    outer, _, saddle = tee
    (full,) = main_stiffeners(outer, [], [(0, 0.0)], BAR, "outside", [Keepout(saddle=saddle)])
    a, b = main_stiffeners(outer, [], [(2, 90.0)], BAR, "outside", [Keepout(saddle=saddle)])
    assert (full.name, a.name, b.name) == ("stringer_00", "stringer_02_a", "stringer_02_b")
    assert all(is_valid(s.solid.wrapped) for s in (full, a, b))
    xs = [(s.solid.bounding_box().min.X, s.solid.bounding_box().max.X) for s in (a, b)]
    assert xs[0] == pytest.approx((0.0, 150.0 - 31.5), abs=1e-6)
    assert xs[1] == pytest.approx((150.0 + 31.5, 400.0), abs=1e-6)
    per_length = full.solid.volume / 400.0  # a prism: the pieces are its section times their lengths
    assert a.solid.volume == pytest.approx(per_length * 118.5, rel=1e-9)
    assert b.solid.volume == pytest.approx(per_length * (400.0 - 181.5), rel=1e-9)


def test_a_ring_through_the_opening_loses_its_angle_with_square_ends(tee):
    outer, _, saddle = tee
    (whole,) = main_stiffeners(outer, [(1, 100.0)], [], BAR, "outside", [Keepout(saddle=saddle)])
    (cut,) = main_stiffeners(outer, [(3, 150.0)], [], BAR, "outside", [Keepout(saddle=saddle)])
    assert is_valid(cut.solid.wrapped)
    lost = math.pi - 2 * math.acos(31.5 / 52.0)  # the opening's span round the axis at x = 150
    assert cut.solid.volume == pytest.approx(whole.solid.volume * (1 - lost / (2 * math.pi)), rel=1e-7)
    ends = [f for f in cut.solid.faces() if f.geom_type.name == "PLANE" and abs(f.normal_at().X) < 1e-9]
    assert len(ends) == 2  # the two ends, in planes through the main axis (the x axis): square to the ring
    for face in ends:
        n, p = face.normal_at(), face.center()
        assert abs(n.Y * p.Y + n.Z * p.Z) < 1e-6  # the plane holds the axis
        angle = math.degrees(math.atan2(p.Z, p.Y))
        flank = math.degrees(math.acos(31.5 / 52.0))  # where the opening's edge crosses the ring, 52.7 deg
        assert min(abs(angle - flank), abs(angle - (180.0 - flank))) < 1e-6


def test_a_pad_stops_them_on_its_edge(tee):
    outer, _, _ = tee
    pad = Keepout(s_range=(100.0, 200.0), angles_deg=(40.0, 140.0))
    a, b = main_stiffeners(outer, [], [(2, 90.0)], BAR, "outside", [pad])
    assert a.solid.bounding_box().max.X == pytest.approx(100.0, abs=1e-6)
    assert b.solid.bounding_box().min.X == pytest.approx(200.0, abs=1e-6)
    (whole,) = main_stiffeners(outer, [(1, 50.0)], [], BAR, "outside", [pad])
    (cut,) = main_stiffeners(outer, [(2, 150.0)], [], BAR, "outside", [pad])
    assert cut.solid.volume == pytest.approx(whole.solid.volume * (1 - 100.0 / 360.0), rel=1e-7)


def test_the_branch_s_stiffeners_start_beyond_its_saddle(tee):
    _, branch_outer, saddle = tee
    top = float(saddle.branch_s.max())  # the saddle's highest point up the branch: the crest, y = 0, z = 52
    assert top == pytest.approx(52.0, abs=1e-9)
    ring, stringer = branch_stiffeners(branch_outer, saddle, [(2, 100.0)], [(0, 0.0)], BAR, "outside", 10.0)
    assert ring.name == "branch_ring_02" and stringer.name == "branch_stringer_00"
    # branch stringer 0 stands at x = 181.5, y = 0, where the saddle crosses the main's crest, z = 52: the
    # highest point under its base (+-1 across), so the stringer starts square in the plane z = 52
    assert stringer.solid.bounding_box().min.Z == pytest.approx(52.0, abs=1e-6)
    with pytest.raises(ParameterError, match="within 10 of its saddle") as info:
        branch_stiffeners(branch_outer, saddle, [(1, 58.0)], [], BAR, "outside", 10.0)
    assert info.value.key == "branches.stiffeners.rings"


def test_a_stringer_inside_the_opening_over_its_length_is_refused(tee):
    outer, _, _ = tee
    everywhere = Keepout(s_range=(-1.0, 401.0), angles_deg=(80.0, 100.0))
    with pytest.raises(ParameterError, match="cannot stop on it") as info:
        main_stiffeners(outer, [], [(2, 90.0)], BAR, "outside", [everywhere])
    assert info.value.key == "stiffeners.stringers"
    assert np.isfinite(outer.length)


@pytest.fixture(scope="module")
def cone_tee():
    """Issue 43: the main a cone, r(s) = 60 - 0.05 s (outer surface 61.5 - 0.05 s), the branch
    r 20 (outer 21) square at s = 150."""
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, 300.0), normal=(0, 1, 0)), "60 - 0.05 * s")
    branch = branch_surface(main, 150.0, 150.0, 20.0)
    outer, branch_outer = main.offset(1.5), branch.offset(1.0)
    return outer, branch_outer, saddle_curve(outer, branch_outer)


def ring_plane_s(x: float) -> float:
    """The ring whose plane is x on the cone's outer surface: a canal ring at s lies in the plane
    x = s - r r' = s + 0.05 (61.5 - 0.05 s)."""
    return (x - 0.05 * 61.5) / (1 - 0.05**2)


def test_on_a_conical_main_a_stringer_stops_on_the_branch_cylinder(cone_tee):
    """The top stringer's pieces end square in the ring planes where the branch's outer cylinder
    (x - 150)^2 + y^2 = 21^2 crosses the top, x = 150 -+ 21, at their base; their webs stand
    on the cone's normal, which leans 0.05 (its slope) along x: the first piece's top edge
    reaches 10 x 0.05 beyond its base, the second's starts there."""
    outer, _, saddle = cone_tee
    a, b = main_stiffeners(outer, [], [(2, 90.0)], BAR, "outside", [Keepout(saddle=saddle)])
    assert is_valid(a.solid.wrapped) and is_valid(b.solid.wrapped)
    assert a.solid.bounding_box().max.X == pytest.approx(150.0 - 21.0 + 10.0 * 0.05, abs=1e-6)
    # measured 4.7e-4 short: its base corners, a half thickness either side of the stringer, lie
    # (w / 2)^2 |r'| / (2 rho) inside the ring plane on the cone
    assert b.solid.bounding_box().min.X == pytest.approx(150.0 + 21.0, abs=1e-3)


def test_on_a_conical_main_a_ring_loses_the_openings_angle(cone_tee):
    """The ring frame whose base band (2 wide) holds the plane x = 150 loses the widest angle the
    opening spans over that band: in the ring plane x (radius rho(x) = r sqrt(1 - r'^2)) the
    branch cylinder holds |y| < sqrt(21^2 - (x - 150)^2), the angle pi - 2 acos(sqrt(21^2 -
    (x - 150)^2) / rho(x)), widest at x = 150.4 as the cone narrows (sampled here, 20001
    planes); its ends lie in planes through the axis."""
    outer, _, saddle = cone_tee
    s = ring_plane_s(150.0)
    (whole,) = main_stiffeners(outer, [(3, s)], [], BAR, "outside", [])
    (cut,) = main_stiffeners(outer, [(3, s)], [], BAR, "outside", [Keepout(saddle=saddle)])
    assert is_valid(cut.solid.wrapped)
    x = np.linspace(ring_plane_s(149.0), ring_plane_s(151.0), 20001) * (1 - 0.05**2) + 0.05 * 61.5
    rho = (61.5 - 0.05 * ring_plane_s(x)) * math.sqrt(1 - 0.05**2)
    lost = float((math.pi - 2 * np.arccos(np.sqrt(21.0**2 - (x - 150.0) ** 2) / rho)).max())
    # measured 2.0e-6: the widest angle is taken from the saddle's 257 samples in the band, O(h^2)
    # short of the exact extreme (1e-5 rad: the frame's ends reach 5e-4 into the opening)
    assert cut.solid.volume == pytest.approx(whole.solid.volume * (1 - lost / (2 * math.pi)), rel=1e-5)
    ends = [f for f in cut.solid.faces() if f.geom_type.name == "PLANE" and abs(f.normal_at().X) < 1e-9]
    assert len(ends) == 2
    for face in ends:
        n, p = face.normal_at(), face.center()
        assert abs(n.Y * p.Y + n.Z * p.Z) < 1e-6  # the plane holds the axis
