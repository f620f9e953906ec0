"""The frame fit's last step (tubecad.fitting.frame_spline.redistributed_breaks): the breaks the
halving left redistributed by each span's measured error (de Boor's knot placement), kept
only if the fit on them meets the targets. Checked against the halving alone and, on the
B-rep, by the exact tube the surface module evaluates."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import CurvatureLineTube, ParametricAxis, expression_curve
from tubecad.brep import NetLayout, build_tube_shell
from tubecad.core.tolerance import orthogonality_for
from tubecad.fitting import fit_frame, frame_spline, measure_surface

TREFOIL = ("40*(sin(t)+2*sin(2*t))", "40*(cos(t)-2*cos(2*t))", "-40*sin(3*t)")


@pytest.fixture(scope="module")
def knot():
    return CurvatureLineTube(ParametricAxis(expression_curve(*TREFOIL), (0.0, math.pi)), 8.0)


def _spans(fit) -> int:
    return len(np.unique(fit.spline.t)) - 1


@pytest.mark.parametrize("tolerance", [1e-5, 1e-8])
def test_redistribution_keeps_fewer_spans_within_the_targets(knot, tolerance, monkeypatch):
    orthogonality = orthogonality_for(tolerance)
    redistributed = fit_frame(knot.axis, knot.radius, tolerance, orthogonality)
    with monkeypatch.context() as patch:
        patch.setattr(frame_spline, "REDISTRIBUTE_GAIN", 0.0)  # never worth trying: the halving alone
        halved = fit_frame(knot.axis, knot.radius, tolerance, orthogonality)
    # measured on this half knot: 66 -> 53 spans at 1e-5, 145 -> 124 at 1e-8
    assert _spans(redistributed) <= 0.9 * _spans(halved)
    assert redistributed.position_bound <= 0.5 * tolerance
    assert redistributed.orthogonality_bound <= 0.5 * orthogonality


def test_the_redistributed_surface_is_within_the_tolerance_and_its_rings_are_knots(knot):
    tolerance = 1e-5
    layout = NetLayout.equal(knot, 4, 3)
    build = build_tube_shell(knot, layout, tolerance)
    m = measure_surface(build.surfaces[0], 48, 6000)  # the OCCT surface against the exact tube
    assert m.max_deviation <= tolerance
    assert m.max_orthogonality_error <= orthogonality_for(tolerance)
    knots = build.frame.spline.t
    for ring in layout.s_rings[1:-1]:  # each inner ring a knot of multiplicity p: the fit exact there
        assert np.count_nonzero(np.abs(knots - ring) <= 1e-12 * knot.length) == build.frame.degree
