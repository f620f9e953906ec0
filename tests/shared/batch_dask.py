"""Batches on a Dask distributed cluster (issue 15): tests/unit/batch/test_batch_dask.py and
tests/e2e/test_cli_batch_dask.py share the cluster, the spec and the sweep. Import this module
after ``pytest.importorskip("distributed")``."""

from __future__ import annotations

import os

import pytest
from conftest import SMALL_BATCH_TUBE

SWEEP = "tube.radius=4:6:8"


@pytest.fixture(scope="module", name="cluster")
def cluster_fixture():
    """A LocalCluster of 2 worker processes on 127.0.0.1, STEP headers stamped at a fixed time."""
    os.environ["SOURCE_DATE_EPOCH"] = "1700000000"  # the workers inherit it: stable STEP headers
    from distributed import LocalCluster

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address="127.0.0.1:0"
    ) as local:
        yield local
    del os.environ["SOURCE_DATE_EPOCH"]


@pytest.fixture(scope="module", name="spec")
def spec_fixture(tmp_path_factory):
    """SMALL_BATCH_TUBE written to a file."""
    path = tmp_path_factory.mktemp("dask") / "t.toml"
    path.write_text(SMALL_BATCH_TUBE)
    return path
