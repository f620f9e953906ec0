"""A radius table's knot a sliver away from a route's line-bend joint (the last developer's
note: "a table knot within about 0.02 of a route joint makes the fit stall").

The joint is a C0 knot of the canal section spline, the table knot a C1 one; a sliver
between them used to be interpolated from its own values, whose rounding (about eps |c|)
the sliver's derivatives amplify by 1 / sliver: at 1e-3 the orthogonality stalled at
7.5e-10 (target 5e-10), at 1e-6 at 1.7e-7 (a knot 1e-3 before it: scipy refused duplicate
abscissae). The wall solid is built here from samples/tapered_bend.toml with the table row
moved to the joint, and measured: valid, and the fit's bounds within the targets.
"""

import numpy as np
import pytest
from conftest import ROOT

from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.fitting.canal_section import _insert_knot, _with_singular_parts, canal_functions, fit_canal
from tubecad.spec.parse import load_spec
from tubecad.surface.canal import tube_or_canal

SAMPLE = ROOT / "samples" / "tapered_bend.toml"
TOLERANCE = 1e-8
ORTHOGONALITY = 1e-9


@pytest.fixture(scope="module")
def axis():
    return load_spec(SAMPLE).tube.axis


def joint(axis, k=0):
    return float(axis.joints[k][0])


def sample_table(axis, gap, k=0):
    """The sample's table with the row nearest joint ``k`` moved to ``gap`` past it."""
    rows = [[0.0, 30.0], [100.0, 28.0], [300.0, 21.0], [540.0, 18.0]]
    rows[1 if k == 0 else 2][0] = joint(axis, k) + gap
    return rows


def knotted_table(axis, gap):
    """Six rows: the one at the joint a true knot (r''' jumps there, by about 1e-5)."""
    return [[0.0, 30.0], [60.0, 29.5], [joint(axis) + gap, 28.0], [220.0, 25.0], [300.0, 21.0], [540.0, 18.0]]


@pytest.mark.parametrize("gap", [0.02, -0.02, 1e-3, -1e-3, 1e-6, -1e-6, 0.0])
def test_wall_builds_with_a_table_knot_near_a_joint(axis, gap):
    canal = tube_or_canal(axis, sample_table(axis, gap))
    build = build_wall_solid(canal, 2.0, layout=NetLayout.equal(canal, 7, 8), tolerance=TOLERANCE)
    assert props.is_valid(build.shape.wrapped)
    fit = build.frame
    assert fit.position_bound <= 0.5 * TOLERANCE
    assert fit.orthogonality_bound <= 0.5 * ORTHOGONALITY
    # measured: about 1.2e-9 / 1.8e-10 at every gap, as with the row on the joint
    assert fit.position_bound < 2e-9 and fit.orthogonality_bound < 3e-10
    knots = np.unique(fit.spline.t)
    assert np.min(np.abs(knots - joint(axis))) == 0.0  # the joint stays a knot
    assert fit.spans <= 16


@pytest.mark.parametrize("gap", [0.02, 1e-3, -1e-3, 1e-6, -1e-6, 1e-9, 0.0])
@pytest.mark.parametrize("k", [0, 1])
def test_fit_with_a_table_knot_near_either_joint(axis, gap, k):
    canal = tube_or_canal(axis, sample_table(axis, gap, k))
    fit = fit_canal(canal, (1.0, -1.0), TOLERANCE, ORTHOGONALITY, rings=NetLayout.equal(canal, 7, 8).s_rings)
    assert fit.position_bound <= 0.5 * TOLERANCE and fit.orthogonality_bound <= 0.5 * ORTHOGONALITY
    t = fit.spline.t
    assert np.count_nonzero(t == joint(axis, k)) == fit.degree  # still C0 there


@pytest.mark.parametrize("gap", [0.02, -0.02, 1e-3, -1e-3, 1e-6, -1e-6, 0.0])
def test_fit_with_a_true_table_knot_near_a_joint(axis, gap):
    """A knot where r''' jumps: 1e-3 and 1e-6 away used to stall at 7.5e-10 and 2.5e-7."""
    canal = tube_or_canal(axis, knotted_table(axis, gap))
    b = joint(axis) + gap
    law = canal.radius_law
    assert abs(float(np.diff(law.dddr(np.array([b - 1.0, b + 1.0])))[0])) > 5e-6
    fit = fit_canal(canal, (1.0, -1.0), TOLERANCE, ORTHOGONALITY, rings=NetLayout.equal(canal, 7, 8).s_rings)
    assert fit.position_bound <= 0.5 * TOLERANCE and fit.orthogonality_bound <= 0.5 * ORTHOGONALITY
    # measured independently of the fit's own sampling: densely across the sliver
    s = np.union1d(
        np.linspace(joint(axis) - 0.05, joint(axis) + 0.05, 401),
        np.linspace(min(b, joint(axis)), max(b, joint(axis)), 41),
    )
    error = np.abs(fit.spline(s) - canal_functions(canal, s)).max()
    assert error < 1e-10  # about 3e-12 measured
    if 1e-4 < abs(gap):  # the knot kept, at multiplicity degree - 1 (r' is C1 there)
        assert np.count_nonzero(fit.spline.t == b) == fit.degree - 1
    assert np.count_nonzero(fit.spline.t == joint(axis)) == fit.degree


def test_singular_part_is_added_exactly():
    """Knot insertion keeps the function; the added K (s - b)_+^2 / 2 is exact."""
    from scipy.interpolate import BSpline

    rng = np.random.default_rng(1)
    k = 7
    t = np.concatenate([[0.0] * 8, [1.0] * 7, [2.0, 3.5], [5.0] * 8])
    S = BSpline(t, rng.normal(size=(len(t) - k - 1, 3)), k)
    s = np.linspace(0.0, 5.0, 1001)
    inserted = _insert_knot(S, 2.7, 6)
    assert np.abs(inserted(s) - S(s)).max() < 1e-12
    K = np.array([1.0, -2.0, 0.5])
    b = 1.0 + 1e-3
    total = _with_singular_parts(S, [(b, K)])
    assert np.count_nonzero(total.t == b) == k - 1
    s = np.union1d(s, np.linspace(1.0, 1.002, 41))
    expected = S(s) + 0.5 * np.maximum(s - b, 0.0)[:, None] ** 2 * K
    assert np.abs(total(s) - expected).max() < 1e-12
