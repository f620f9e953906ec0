"""Property-based tests (hypothesis): random valid tubes of every axis family keep the facts.

Each example draws an axis family and its parameters, an elevation angle beta, a span,
and a radius rho with rho * max|k| <= 0.8 (so the tube is locally regular); tubes that the
package's own regularity check refuses for a self-approach of the axis are filtered out.
For these tubes:

- the curvature-line net: F = 0 and M = 0 to round-off on a grid, G >= (1 - 0.8)^2;
- Pappus: the numerically integrated area is 2 pi rho L;
- the OCCT solids (3 rings x 4 stringers): the capped tube encloses pi rho^2 L and the wall
  pi (r_out^2 - r_in^2) L, both are valid closed solids, and a STEP round trip keeps the
  validity, the face count and the volume.

derandomize=True makes every run draw the same examples (reproducible CI).
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from tubecad import CircleInvolute, Clothoid, CurvatureLineTube, CustomCurvature, Helix, LogSpiral, RegularityError
from tubecad.brep import NetLayout, build_tube_solid, build_wall_solid
from tubecad.brep import properties as props
from tubecad.export.cad import import_shape
from tubecad.export.registry import export_shape
from tubecad.surface.checks import area_by_quadrature

#: the largest rho * max|k| drawn: a margin below the fold at 1
MAX_RHO_K = 0.8
ROUND_OFF = 1e-12
MIN_RHO = 0.2
#: volumes of the fitted B-rep through a STEP round trip (the file's against the solid's own):
#: the fit is within 1e-8 of the exact tube, rho >= MIN_RHO
VOLUME_REL = 1e-6
#: the fitted B-rep's volume against the closed form pi rho^2 L (pi (r_out^2 - r_in^2) L):
#: measured 5.6e-12 at most over the derandomized examples, 2.6e-10 on a thin wall hypothesis
#: found (thickness 0.05 rho: the fit's position error over a thin annulus); the fit reaches
#: about 1e-9 relative, as issue 42 asks the volumes to be checked at
EXACT_VOLUME_REL = 2e-9

FAST = settings(
    max_examples=40,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
OCCT = settings(FAST, max_examples=15)

finite = {"allow_nan": False, "allow_infinity": False}


@st.composite
def axes(draw):
    """(family, axis) with random parameters, beta and span."""
    family = draw(st.sampled_from(["log_spiral", "helix", "clothoid", "involute", "custom"]))
    beta = draw(st.floats(-70.0, 70.0, **finite))
    length = draw(st.floats(50.0, 1000.0, **finite))
    if family == "log_spiral":
        s0 = draw(st.floats(20.0, 500.0, **finite))
        return family, LogSpiral(draw(st.floats(0.5, 20.0, **finite)), beta, (s0, s0 + length))
    if family == "involute":
        s0 = draw(st.floats(5.0, 500.0, **finite))
        return family, CircleInvolute(draw(st.floats(1.0, 50.0, **finite)), beta, (s0, s0 + length))
    s0 = draw(st.floats(-500.0, 500.0, **finite))
    if family == "helix":
        k = draw(st.one_of(st.just(0.0), st.floats(-0.05, -1e-4, **finite), st.floats(1e-4, 0.05, **finite)))
        return family, Helix(k, beta, (s0, s0 + length))
    if family == "clothoid":
        return family, Clothoid(draw(st.floats(100.0, 600.0, **finite)), beta, (s0, s0 + length))
    c0 = draw(st.floats(-0.02, 0.02, **finite))
    c1 = draw(st.floats(0.0, 0.01, **finite))
    period = draw(st.floats(100.0, 1000.0, **finite))
    form = draw(
        st.sampled_from(
            [
                f"{c0!r} + {c1!r} * sin(2 * pi * s / {period!r})",
                f"{c0!r} + {c1 / 500!r} * s",
                f"{c0!r} * exp(-((s - {s0!r}) / {period!r}) ** 2) + {c1!r}",
            ]
        )
    )
    return family, CustomCurvature(form, beta, (s0, s0 + length))


def max_abs_curvature(axis) -> float:
    return float(np.abs(axis.curvature(np.linspace(*axis.span, 4001))).max())


def radius_for(axis, fraction: float) -> float:
    """rho = fraction * MAX_RHO_K / max|k|, and at most twice the length (for near-straight axes)."""
    k_max = max_abs_curvature(axis)
    return max(MIN_RHO, fraction * min(MAX_RHO_K / k_max if k_max > 0 else math.inf, 2 * axis.length))


@st.composite
def regular_tubes(draw, most: float = 1.0):
    """A tube the package accepts, with rho * max|k| <= most * 0.8."""
    family, axis = draw(axes())
    rho = radius_for(axis, draw(st.floats(0.05, most, **finite)))
    assume(rho * max_abs_curvature(axis) <= MAX_RHO_K)
    try:
        tube = CurvatureLineTube(axis, rho)
    except RegularityError:  # the axis comes back within 2 rho of itself
        assume(False)
    return tube


@FAST
@given(tube=regular_tubes())
def test_net_is_orthogonal_and_conjugate_to_round_off(tube):
    assert tube.regularity.ok and tube.regularity.max_rho_k <= MAX_RHO_K * (1 + 1e-9)
    u = np.linspace(0.0, 2.0 * math.pi, 48, endpoint=False)[:, None]
    s = np.linspace(*tube.span, 401)[None, :]
    forms = tube.fundamental_forms(u, s)
    assert forms.orthogonality_error.max() < ROUND_OFF  # F = 0
    assert forms.conjugacy_error.max() < ROUND_OFF  # M = 0
    assert np.allclose(forms.E, tube.radius**2, rtol=1e-12, atol=0)
    assert forms.G.min() >= (1.0 - MAX_RHO_K) ** 2 * (1 - 1e-9)  # regular: |S_s| >= 1 - rho |k|


@pytest.mark.slow
@FAST
@given(tube=regular_tubes())
def test_area_is_pappus(tube):
    assert area_by_quadrature(tube) == pytest.approx(2.0 * math.pi * tube.radius * tube.length, rel=1e-10)


def step_round_trip(shape, folder: Path):
    path = export_shape(shape, folder / "solid.step")
    back = import_shape(path)
    assert sorted(p.name for p in folder.iterdir()) == ["solid.step"]  # no temporary file left
    assert props.is_valid(back) and props.free_edges(back) == 0
    assert props.count(back, "solid") == 1
    assert props.count(back, "face") == props.count(shape, "face")
    assert props.volume(back) == pytest.approx(props.volume(shape), rel=VOLUME_REL)


@pytest.mark.slow
@OCCT
@given(tube=regular_tubes())
def test_capped_tube_solid_encloses_pi_rho2_L_and_survives_step(tube):
    build = build_tube_solid(tube, NetLayout.equal(tube, 3, 4))
    solid = build.shape
    assert props.is_valid(solid) and props.free_edges(solid) == 0
    assert props.count(solid, "face") == 2 * 4 + 2  # the patches and two end discs
    # measured 5.6e-12 (the largest of the 15 examples)
    assert props.volume(solid) == pytest.approx(math.pi * tube.radius**2 * tube.length, rel=EXACT_VOLUME_REL)
    with tempfile.TemporaryDirectory() as folder:
        step_round_trip(solid, Path(folder))


@pytest.mark.slow
@OCCT
@given(
    tube=regular_tubes(most=0.75),
    fraction=st.floats(0.05, 0.3, **finite),
    side=st.sampled_from(["centered", "inside", "outside"]),
)
def test_wall_solid_encloses_the_annulus_times_L_and_survives_step(tube, fraction, side):
    thickness = fraction * tube.radius
    try:
        build = build_wall_solid(tube, thickness, side, NetLayout.equal(tube, 3, 4))
    except RegularityError:  # the outer surface comes within 2 r_out of the axis elsewhere
        assume(False)
    r_out, r_in = build.radii
    assert r_out - r_in == pytest.approx(thickness, rel=1e-12)
    wall = build.shape
    assert props.is_valid(wall) and props.free_edges(wall) == 0
    assert props.count(wall, "face") == 2 * 2 * 4 + 2  # outer and inner patches, two annular caps
    # measured 2.9e-12 (the largest of the 15 examples), 2.6e-10 at worst (EXACT_VOLUME_REL)
    assert props.volume(wall) == pytest.approx(math.pi * (r_out**2 - r_in**2) * tube.length, rel=EXACT_VOLUME_REL)
    with tempfile.TemporaryDirectory() as folder:
        step_round_trip(wall, Path(folder))
