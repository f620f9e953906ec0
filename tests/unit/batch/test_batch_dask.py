"""Batches on a Dask distributed cluster (issue 15): a LocalCluster of 2 worker processes on
127.0.0.1, started here.

- one worker killed in the middle of the batch: all 8 results present and valid;
- a job past the timeout is stopped, retried and fails without files.

`tubecad build --scheduler` (the same files as the local pool, an interrupted batch resumed)
is run in tests/e2e/test_cli_batch_dask.py.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")

from conftest import SMALL_BATCH_TUBE
from shared.batch_dask import SWEEP
from shared.batch_dask import cluster_fixture as cluster_fixture  # the fixture cluster; `as`: imported for pytest
from shared.batch_dask import spec_fixture as spec_fixture  # the fixture spec; `as`: imported for pytest

from tubecad.batch.dask_executor import DaskExecutor
from tubecad.batch.jobs import JobResult, parse_sweep, plan_jobs
from tubecad.batch.runner import run_batch

# the same on both OCCT generations: CI runs it once; clusters of worker processes: slow
pytestmark = [pytest.mark.once, pytest.mark.slow]

SMALL = SMALL_BATCH_TUBE


def test_a_worker_killed_mid_batch_loses_no_result(cluster, spec, tmp_path):
    from distributed import Client

    jobs = plan_jobs([spec], [parse_sweep(SWEEP)], tmp_path, ["step"])
    executor = DaskExecutor(cluster.scheduler_address, out_dir=tmp_path)
    killed = []

    def on_result(i: int, result: JobResult) -> None:
        if killed:
            return
        with Client(cluster.scheduler_address) as client:
            pids = client.run(os.getpid)
            busy = [w for w, keys in client.processing().items() if keys]
        if busy:
            os.kill(pids[busy[0]], signal.SIGKILL)  # its nanny starts another; its task runs elsewhere
            killed.append(busy[0])

    try:
        results, interrupted = run_batch(jobs, 2, lambda line: None, executor=executor, retries=2, on_result=on_result)
    finally:
        executor.close()
    assert killed and not interrupted
    assert all(r is not None and r.status == "ok" and r.valid for r in results)
    assert all(Path(p).stat().st_size > 0 for job in jobs for p in job.outputs)
    assert not list(tmp_path.glob(".*.part*"))


def test_a_hung_cluster_job_is_stopped_retried_and_fails_without_files(cluster, tmp_path):
    """A job past --job-timeout is cancelled and the worker running it restarted (its nanny
    starts a new one), so it holds no worker; after its retries it fails, writing nothing."""
    spec = tmp_path / "slow.toml"
    spec.write_text(SMALL.replace("rings = 3", "rings = 60").replace("stringers = 2", "stringers = 16"))
    jobs = plan_jobs([spec], [], tmp_path / "out", ["step"])
    (tmp_path / "out").mkdir()
    executor = DaskExecutor(cluster.scheduler_address, out_dir=tmp_path / "out")
    lines = []
    try:
        results, interrupted = run_batch(jobs, 1, lines.append, executor=executor, retries=1, timeout=1.0)
    finally:
        executor.close()
    assert not interrupted and results[0].status == "failed" and results[0].attempts == 2
    assert "timed out after 1 s (--job-timeout); retrying (attempt 2)" in lines[0]
    assert list((tmp_path / "out").iterdir()) == []
