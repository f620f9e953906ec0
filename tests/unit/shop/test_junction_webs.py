"""The webs of a junction's stiffeners for the shop (issue 25), on the square tee whose outer
surfaces are main y^2 + z^2 = 52^2 along x and branch (x - 150)^2 + y^2 = 31.5^2 up z, with
flat bars 10 high and 2 thick standing outside: the ring through the branch's axis keeps the
arc 2 pi - (pi - 2 acos(31.5 / 52)) of its annulus between radii 52 and 62, so its web is that
sector (its area the cut frame's volume over its thickness, an independent measure: OCCT's
volume of the solid cut by the wedge); the stringer across the opening is the two rectangles
of its pieces, 118.5 and 218.5 long; a joint inside the arc splits the sector, and the pieces'
solids add up to the frame."""

from __future__ import annotations

import math

import pytest

from tubecad import NaturalAxis, ParameterError, tube_or_canal
from tubecad.brep.properties import is_valid
from tubecad.junctions import branch_surface, saddle_curve
from tubecad.shop.fabrication import Fabrication
from tubecad.shop.webs import piece_solids, ring_pieces, stringer_pieces
from tubecad.stiffeners.junction import Keepout, main_stiffeners
from tubecad.stiffeners.profiles import Profile

BAR = Profile("flat", 10.0, 2.0)
#: the opening's span round the main axis at x = 150, where the ring through the branch's axis stands
LOST = math.pi - 2 * math.acos(31.5 / 52.0)
#: a 3 x 1.5 m plate, kerf 2, no root gap
PLATE = Fabrication((3000.0, 1500.0), 2.0, 0.0)


@pytest.fixture(scope="module")
def stopped():
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, 400.0), normal=(0, 1, 0)), 50.0)
    outer = main.offset(2.0)
    saddle = saddle_curve(outer, branch_surface(main, 150.0, 150.0, 30.0).offset(1.5))
    (ring,) = main_stiffeners(outer, [(3, 150.0)], [], BAR, "outside", [Keepout(saddle=saddle)])
    stringers = main_stiffeners(outer, [], [(2, 90.0)], BAR, "outside", [Keepout(saddle=saddle)])
    return ring, stringers


def test_a_ring_cut_at_the_opening_develops_as_the_sector_of_its_arc(stopped):
    ring, _ = stopped
    a, b = ring.arc_deg
    assert math.radians(b - a) == pytest.approx(2 * math.pi - LOST, rel=1e-7)  # as the cut volume: 1e-7
    assert ring.length() == pytest.approx(52.0 * (2 * math.pi - LOST), rel=1e-7)
    (piece,) = ring_pieces(ring, PLATE)
    assert piece.span == (a, b) and piece.joints == (False, False)  # square ends on the opening: no butt joints
    r_in, r_out, angle = piece.pattern.sector
    assert (r_in, r_out) == (52.0, 62.0) and angle == pytest.approx(math.radians(b - a), rel=1e-15)
    assert piece.pattern.area == pytest.approx(0.5 * angle * (62.0**2 - 52.0**2), rel=1e-12)
    # the flat frame is its web times its thickness: OCCT's volume of the solid the wedge cut
    assert piece.pattern.area * BAR.thickness == pytest.approx(ring.solid.volume, rel=1e-9)


def test_a_joint_inside_the_arc_splits_it_and_the_pieces_make_the_frame(stopped):
    ring, _ = stopped
    a, b = ring.arc_deg
    joint = (a + 100.0) % 360.0
    fab = Fabrication((3000.0, 1500.0), 2.0, 0.0, joints={"ring_03": (joint,)})
    first, second = ring_pieces(ring, fab)
    assert (first.name, second.name) == ("ring_03_a", "ring_03_b")
    assert first.span == pytest.approx((a, a + 100.0), abs=1e-9) and second.span == pytest.approx((a + 100.0, b))
    assert (first.joints, second.joints) == ((False, True), (True, False))
    solids = piece_solids(ring, [first, second], 1e-8)
    assert all(is_valid(st.solid.wrapped) for st in solids)
    for st, piece in zip(solids, (first, second)):
        assert st.solid.volume == pytest.approx(piece.pattern.area * BAR.thickness, rel=1e-9)
    assert sum(st.solid.volume for st in solids) == pytest.approx(ring.solid.volume, rel=1e-9)
    outside = (a - 20.0) % 360.0  # in the opening
    with pytest.raises(ParameterError, match=r"joints\.ring_03: .* not on the ring"):
        ring_pieces(ring, Fabrication((3000.0, 1500.0), 2.0, 0.0, joints={"ring_03": (outside,)}))


def test_a_stopped_stringer_develops_as_the_rectangles_of_its_pieces(stopped):
    _, (before, after) = stopped
    for st, length in ((before, 150.0 - 31.5), (after, 400.0 - 150.0 - 31.5)):
        (piece,) = stringer_pieces(st, PLATE)
        assert piece.span == pytest.approx(st.base.span, abs=0.0) and piece.joints == (False, False)
        assert piece.pattern.base_length == pytest.approx(length, rel=1e-9)
        assert piece.pattern.area == pytest.approx(10.0 * length, rel=1e-9)


def test_a_cut_ring_is_bent_over_its_arc_only(stopped):
    """Its bending tables cover the kept arc, 52 (2 pi - lost) long, in the fewest arcs of at
    most 180 deg (two here)."""
    from tubecad.shop.package import bending_tables

    ring, _ = stopped
    tables = bending_tables([ring], {ring.name: ring_pieces(ring, PLATE)}, PLATE)
    assert [t.name for t in tables] == ["ring_03_arc1", "ring_03_arc2"]
    assert sum(t.length for t in tables) == pytest.approx(52.0 * (2 * math.pi - LOST), rel=1e-7)
    assert all(t.length <= 52.0 * math.pi for t in tables)
