"""The area-replacement figures (UG-37 style) of a branch opening: d measured from the bore's
saddle (2 r square, 2 r / sin a oblique), and a hand-worked set-on nozzle with and without a pad."""

from __future__ import annotations

import math

import pytest

from tubecad import NaturalAxis, ParameterError, tube_or_canal
from tubecad.junctions import area_replacement, saddle_curve


def line(origin, tangent, normal, length, radius):
    return tube_or_canal(NaturalAxis("0", "0", (0.0, length), origin=origin, tangent=tangent, normal=normal), radius)


#: the main wall's inner surface (R_in = 48) and the branch's bore (r_in = 20)
MAIN_INNER = line((-100.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 200.0, 48.0)
BORE = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, 20.0)
FIGURES = dict(
    shell_radius=48.0, shell_thickness=4.0, nozzle_radius=20.0, nozzle_thickness=2.0, pressure=2.0, stress=100.0
)


def test_a_square_nozzle_by_hand():
    """By hand: t_r = 2 x 48 / 98.8 = 0.971660, t_rn = 2 x 20 / 98.8 = 0.404858, d = 40,
    A = 38.8664, A1 = 40 x 3.028340 = 121.1336, A2 = min(5 x 1.595142 x 4, 2 x 1.595142 x 5) = 15.9514."""
    result = area_replacement(saddle_curve(MAIN_INNER, BORE, 129), **FIGURES)
    assert result.d == pytest.approx(40.0, abs=1e-11)
    assert (result.t_r, result.t_rn) == pytest.approx((0.971660, 0.404858), abs=1e-6)
    assert (result.required, result.shell, result.nozzle, result.pad) == pytest.approx(
        (38.8664, 121.1336, 15.9514, 0.0), abs=1e-4
    )
    assert result.adequate and "not a code certification" in result.as_dict()["note"]


def test_a_pad_adds_its_area_within_the_limit():
    """Pad D_p = 80, t_e = 4: the limit is 2 max(40, 20 + 2 + 4) = 80, A5 = (80 - 40 - 4) x 4 = 144;
    A2 = min(31.9028, 2 x 1.595142 x 9 = 28.7126); a wider pad adds nothing past the limit."""
    saddle = saddle_curve(MAIN_INNER, BORE, 129)
    result = area_replacement(saddle, **FIGURES, pad_diameter=80.0, pad_thickness=4.0)
    assert (result.nozzle, result.pad) == pytest.approx((28.7126, 144.0), abs=1e-4)
    assert area_replacement(saddle, **FIGURES, pad_diameter=120.0, pad_thickness=4.0).pad == pytest.approx(
        144.0, abs=1e-9
    )


def test_an_oblique_opening_is_longer_by_one_over_sin_a():
    """A bore at 60 deg to the main axis opens 2 r / sin 60 along it (its generators at y = 0
    meet the main surface at x = R cot a -+ r / sin a)."""
    a = math.radians(60.0)
    bore = line((0.0, 0.0, 0.0), (math.cos(a), 0, math.sin(a)), (0, 1, 0), 120.0, 20.0)
    result = area_replacement(saddle_curve(MAIN_INNER, bore, 257), **FIGURES)
    assert result.d == pytest.approx(40.0 / math.sin(a), abs=1e-11)


def test_bad_figures_are_refused_by_key():
    saddle = saddle_curve(MAIN_INNER, BORE, 33)
    with pytest.raises(ParameterError) as info:
        area_replacement(saddle, **{**FIGURES, "shell_thickness": 0.0})
    assert info.value.key == "branches.shell_thickness"
    with pytest.raises(ParameterError) as info:
        area_replacement(saddle, **{**FIGURES, "pressure": 200.0})
    assert info.value.key == "branches.pressure"
