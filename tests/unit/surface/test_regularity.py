"""Regularity (docs/MATH.md section 5): folded or self-intersecting tubes are refused, saying where."""

import math
import re

import numpy as np
import pytest

from tubecad import Clothoid, CurvatureLineTube, Helix, LogSpiral, ParameterError, RegularityError


def test_rho_k_at_or_above_one_is_refused_naming_the_s_interval():
    # k = 10/s, rho = 15: rho k >= 1 for s <= 150.
    with pytest.raises(RegularityError) as info:
        CurvatureLineTube(LogSpiral(10.0, 10.0, (100.0, 1200.0)), 15.0)
    msg = str(info.value)
    assert "rho*k reaches 1.5 at s = 100" in msg
    lo, hi = map(float, re.search(r"for s in \[([\d.e+-]+), ([\d.e+-]+)\]", msg).groups())
    assert lo == 100.0 and hi == pytest.approx(150.0, rel=1e-9)


def test_fold_inside_the_span_is_found_between_samples():
    # Clothoid k = s / A^2 with rho = 10: rho|k| >= 1 for |s| >= 1000 (both ends here).
    with pytest.raises(RegularityError) as info:
        CurvatureLineTube(Clothoid(100.0, 0.0, (-1200.0, 1100.0)), 10.0, allow_irregular=False)
    where = re.search(r"for s in (.*?)\)", str(info.value)).group(1)
    intervals = re.findall(r"\[([-\d.e+]+), ([-\d.e+]+)\]", where)
    assert [(float(a), float(b)) for a, b in intervals] == [
        pytest.approx((-1200.0, -1000.0)),
        pytest.approx((1000.0, 1100.0)),
    ]


def test_coiling_axis_closer_than_two_rho_is_refused_with_closest_approach():
    helix = Helix.from_radius_pitch(50.0, 25.0, (0.0, 1000.0))  # coils 25 apart
    with pytest.raises(RegularityError) as info:
        CurvatureLineTube(helix, 15.0)
    msg = str(info.value)
    d = float(re.search(r"comes back within ([\d.]+)", msg).group(1))
    assert d == pytest.approx(25.0, rel=1e-2)  # successive coils: a little under one pitch apart
    assert "self-intersects" in msg
    s1, s2 = map(float, re.search(r"between s = ([\d.]+) and s = ([\d.]+)", msg).groups())
    one_turn = 2 * math.pi * 50 / math.cos(helix.beta)
    assert abs(s2 - s1) == pytest.approx(one_turn, rel=0.02)


def test_irregular_tube_can_be_allowed_explicitly_and_reports_why():
    tube = CurvatureLineTube(Helix.from_radius_pitch(50.0, 25.0, (0.0, 1000.0)), 15.0, allow_irregular=True)
    assert not tube.regularity.ok and tube.regularity.self_intersecting
    assert tube.points(0.0, 10.0).shape == (3,)


def test_partial_torus_whose_ends_come_close_is_not_refused():
    """0.9 of a torus: the two ends come within 10 of each other across the gap (< 2 rho),
    but the surface is part of a regular torus and no normal discs meet."""
    tube = CurvatureLineTube(Helix(1 / 15.5, 0.0, (0.0, 2 * math.pi * 15.5 * 0.9)), 15.0)
    assert tube.regularity.ok
    assert tube.regularity.closest_approach < 10.0


def test_regular_tubes_are_not_refused_at_the_schur_bound():
    # A circle (torus) of radius just above rho: arc pi*rho apart is still >= 2 rho apart.
    tube = CurvatureLineTube(Helix(1 / 15.5, 0.0, (0.0, 2 * math.pi * 15.5 * 0.9)), 15.0)
    assert tube.regularity.ok and tube.regularity.max_rho_k == pytest.approx(15 / 15.5)


def test_paper_tube_is_regular_with_the_documented_margins():
    tube = CurvatureLineTube(LogSpiral(10.0, 10.0, (200.0, 1200.0)), 15.0)
    assert tube.regularity.max_rho_k == pytest.approx(0.75)
    assert 30.0 < tube.regularity.closest_approach < 34.0


@pytest.mark.parametrize(
    "make, says",
    [
        (lambda: LogSpiral(10.0, 90.0, (200, 1200)), "beta_deg must be in (-90, 90), got 90"),
        (lambda: LogSpiral(10.0, -95.0, (200, 1200)), "beta_deg must be in (-90, 90), got -95"),
        (lambda: LogSpiral(10.0, 10.0, (1200, 200)), "span must be increasing"),
        (lambda: LogSpiral(10.0, 10.0, (300, 300)), "span must be increasing"),
        (lambda: LogSpiral(10.0, 10.0, (-5, 1200)), "span must lie in s > 0"),
        (lambda: LogSpiral(-1.0, 10.0, (200, 1200)), "a must be in (0, inf), got -1"),
        (lambda: LogSpiral(float("nan"), 10.0, (200, 1200)), "a must be finite"),
        (lambda: LogSpiral(10.0, 10.0, (200, float("inf"))), "span end must be finite"),
        (lambda: Clothoid(0.0, 10.0, (0, 10)), "A must be in (0, inf), got 0"),
        (lambda: CurvatureLineTube(LogSpiral(10.0, 10.0, (200, 1200)), 0.0), "radius must be in (0, inf), got 0"),
        (lambda: CurvatureLineTube(LogSpiral(10.0, 10.0, (200, 1200)), -3), "radius must be in (0, inf), got -3"),
        (lambda: CurvatureLineTube(LogSpiral(10.0, 10.0, (200, 1200)), "15"), "radius must be a real number"),
    ],
)
def test_bad_parameters_name_the_parameter_and_range(make, says):
    with pytest.raises(ParameterError) as info:
        make()
    assert says in str(info.value)


def test_numpy_scalars_are_accepted():
    tube = CurvatureLineTube(LogSpiral(np.float64(10), np.float32(10), (np.int64(200), 1200.0)), np.float64(15))
    assert tube.radius == 15.0
