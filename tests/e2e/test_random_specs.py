"""A seeded slice of the random-spec run (benchmarks/random_specs.py, issue 24): the first 12
cases of seed 2026, one of every axis kind, each generated with its own independent
geometry and judged from outside (the STEP file read back by OCCT and measured against the
exact surface, or a one-line refusal naming its key and leaving no file). The nightly-size
run is ``python benchmarks/random_specs.py --cases 1000``; its table is docs/benchmarks.md's."""

from __future__ import annotations

import sys

import pytest
from conftest import ROOT

sys.path.insert(0, str(ROOT / "benchmarks"))

import random_specs

SEED, SLICE = 2026, range(12)


def test_the_slice_covers_every_axis_kind(tmp_path):
    kinds = {random_specs.make_case(SEED, i, tmp_path).kind for i in SLICE}
    assert kinds == set(random_specs.KINDS)


@pytest.mark.slow
@pytest.mark.parametrize("index", SLICE)
def test_a_random_spec_builds_rightly_or_is_refused_rightly(index, tmp_path):
    case = random_specs.make_case(SEED, index, tmp_path)
    row = random_specs.run_case(case, tmp_path)
    assert row["outcome"] in ("built", "refused")
    assert not row["problems"], f"case {index} ({case.kind}, expected {case.expect}: {case.why}): {row['problems']}"
    if case.expect != "either":
        assert row["outcome"] == {"build": "built", "refuse": "refused"}[case.expect]
