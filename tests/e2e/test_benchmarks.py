"""The benchmark's measurements are themselves checked: they must see the twist of a Frenet
sweep, and hold tubecad to the product targets (docs/benchmarks.md)."""

from __future__ import annotations

import sys

import pytest
from conftest import ROOT

sys.path.insert(0, str(ROOT / "benchmarks"))

from axes import CASES
from measure import measure
from peers import METHODS, SWEEPS, spine, spine_deviation

from tubecad.spec.paper import paper_tube


@pytest.fixture(scope="module")
def tube_and_spine():
    tube = paper_tube()
    return tube, spine(tube)


def test_tubecad_meets_the_targets_by_the_benchmark_measure(tube_and_spine, tmp_path):
    tube, path = tube_and_spine
    shape, solid = METHODS["tubecad"](tube, path)
    m = measure("tubecad", shape, tube, 0.0, samples=8_000, workdir=tmp_path)
    # one stringer: two faces, which end at the circle's C0 knot opposite it (OCCT's
    # pre-boolean check reports a face across one)
    assert m.valid and m.faces == 2
    assert m.max_deviation < 1e-8 and m.max_orthogonality < 1e-9
    assert m.max_curvature_angle_deg < 1e-6  # the isolines are the lines of curvature
    assert m.poles <= 2_000
    assert m.area_rel_error < 1e-9 and m.volume_rel_error < 1e-9
    assert m.step_bytes > 0


def test_the_measure_sees_the_twist_of_a_frenet_sweep(tube_and_spine, tmp_path):
    """A Frenet sweep is a good tube (close to the exact one) whose isolines are not lines
    of curvature: the torsion spins the Frenet frame away from the rotation-minimising one."""
    tube = tube_and_spine[0]
    path = spine(tube, 201)  # coarser than the benchmark's, to keep the test fast
    assert spine_deviation(tube, path) < 1e-3
    shape, solid = METHODS["build123d sweep, is_frenet=True"](tube, path)
    m = measure("frenet", shape, tube, 0.0, samples=8_000, workdir=tmp_path)
    assert m.valid and m.max_deviation < 1e-2
    assert m.max_curvature_angle_deg > 1.0 and m.max_orthogonality > 1e-2


@pytest.mark.parametrize("case", ["spline edge", "route"])
def test_the_any_axis_peers_sweep_the_axis_itself_and_tubecad_meets_the_targets(case, tmp_path):
    """benchmarks/axes.py: every spine the peers get is the tubecad axis' own curve (the
    refined edge too: knot insertion keeps the curve); tubecad meets the targets there by
    the benchmark measure; a CorrectedFrenet sweep of the same spine is the same tube."""
    tube, spines, _ = CASES[case](True)
    built: dict = {}
    for label, (make, _) in spines.items():
        built[label] = make(built)
        assert spine_deviation(tube, built[label]) < 1e-9
    shape, _ = METHODS["tubecad"](tube, None)
    m = measure("tubecad", shape, tube, 0.0, samples=6_000, workdir=tmp_path)
    assert m.valid and m.max_deviation < 1e-8 and m.max_orthogonality < 1e-9 and m.max_curvature_angle_deg < 1e-6
    shape, _ = SWEEPS["OCCT MakePipeShell CorrectedFrenet, tol 1e-9"](tube, next(iter(built.values())))
    peer = measure("corrected frenet", shape, tube, 0.0, samples=6_000, workdir=tmp_path)
    assert peer.valid and peer.max_deviation < 1e-8
