"""Crosses, wyes and branches side by side (issue 43): two branches at one station (a cross:
opposite; a wye: symmetric about the main axis' plane) join into one valid solid; two whose
openings meet are refused naming the key, before any boolean. The clearance between two
openings is checked on the closed form of perpendicular cylinders: two branches of outer
radius r_o on the same generatrix of a straight main tube, at a1 < a2, leave openings whose
nearest points lie on that generatrix at s = a1 + r_o and a2 - r_o: clearance a2 - a1 - 2 r_o."""

from __future__ import annotations

import build123d as bd
import pytest

from tubecad import Branch, CurvatureJunction, NaturalAxis, ParameterError
from tubecad.junctions import branch_surface
from tubecad.junctions.placement import opening_clearance
from tubecad.junctions.saddle import saddle_curve
from tubecad.surface.canal import tube_or_canal

R_OUT, r_OUT = 52.0, 31.5


def test_the_clearance_between_two_openings_is_the_closed_form():
    main = tube_or_canal(
        NaturalAxis("0", "0", (0.0, 400.0), origin=(0, 0, 0), tangent=(1, 0, 0), normal=(0, 1, 0)), R_OUT
    )
    saddles = [saddle_curve(main, branch_surface(main, at, 150.0, r_OUT)) for at in (150.0, 230.0)]
    assert opening_clearance(main, *saddles) == pytest.approx(230.0 - 150.0 - 2 * r_OUT, abs=1e-9)  # measured 0
    touching = saddle_curve(main, branch_surface(main, 150.0 + 2 * r_OUT - 1.0, 150.0, r_OUT))
    assert opening_clearance(main, saddles[0], touching) == 0.0


def test_openings_that_meet_are_refused_naming_the_key():
    with pytest.raises(
        ParameterError, match=r"^branches: the openings of branches 0 and 1 meet .* overlap over"
    ) as info:
        CurvatureJunction(
            bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
            radius=50.0,
            thickness=4.0,
            normal=(0, 1, 0),
            rings=5,
            branches=[
                Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0),
                Branch(at=180.0, length=120.0, radius=30.0, thickness=3.0),
            ],
        )
    assert info.value.key == "branches"


@pytest.mark.slow
@pytest.mark.parametrize("arounds", [(90.0, 270.0), (60.0, 120.0)], ids=["cross", "wye"])
def test_a_cross_and_a_wye_are_one_valid_solid(arounds):
    tee = CurvatureJunction(
        bd.Edge.make_line((0, 0, 0), (300, 0, 0)),
        radius=50.0,
        thickness=4.0,
        normal=(0, 1, 0),
        rings=5,
        branches=[Branch(at=150.0, length=120.0, radius=20.0, thickness=3.0, around=a) for a in arounds],
    )
    report = tee.report
    assert tee.is_valid and len(tee.solids()) == 1 and report["valid"]
    assert set(report["saddles"]) == {"saddle_outer_0", "saddle_inner_0", "saddle_outer_1", "saddle_inner_1"}
    assert max(s["edges_deviation"] for s in report["saddles"].values()) < 1e-8


def test_a_pad_reaching_another_opening_is_refused_naming_its_width():
    """Openings 17 apart (a2 - a1 - 2 r_o, as above): a 20 wide pad round the first reaches
    the second's opening; a 5 wide one does not."""
    main_axis = bd.Edge.make_line((0, 0, 0), (400, 0, 0))

    def tee(width: float) -> CurvatureJunction:
        return CurvatureJunction(
            main_axis,
            radius=50.0,
            thickness=4.0,
            normal=(0, 1, 0),
            rings=5,
            branches=[
                Branch(at=150.0, length=120.0, radius=30.0, thickness=3.0, pad_thickness=4.0, pad_width=width),
                Branch(at=230.0, length=120.0, radius=30.0, thickness=3.0),
            ],
        )

    with pytest.raises(
        ParameterError, match=r"^pad\.width: the pad of branch 0 \(width 20\) reaches the opening of branch 1"
    ) as info:
        tee(20.0)
    assert info.value.key == "pad.width" and info.value.stage == "pads" and info.value.branch == 0
    assert tee(5.0).is_valid
