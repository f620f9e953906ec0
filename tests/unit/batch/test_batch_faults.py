"""Batches that resume and survive faults (issue 15), on this machine's worker processes:

- a worker killed in the middle of a job costs only that job's retry;
- the same spec gives byte-identical STEP files but for the header's time stamp, which
  SOURCE_DATE_EPOCH fixes;
- a job shipped to a cluster worker builds without the submitter's files;
- a result that ended as Ctrl-C came is kept.

The manifest, reruns, Ctrl-C and --job-timeout of `tubecad build` are checked from the
command line in tests/e2e/test_cli_batch_faults.py.
"""

from __future__ import annotations

import json
import os
import signal
import time
from pathlib import Path

import pytest
from conftest import ROOT, SMALL_BATCH_TUBE

from tubecad.batch.executors import ProcessExecutor, run_jobs
from tubecad.batch.jobs import JobResult, parse_sweep, plan_jobs, run_job
from tubecad.batch.manifest import content_hash

# the same on both OCCT generations: CI runs it once; batches of worker processes: slow
pytestmark = [pytest.mark.once, pytest.mark.slow]

SMALL = SMALL_BATCH_TUBE


def test_a_worker_killed_mid_job_costs_only_that_jobs_retry(tmp_path):
    spec = tmp_path / "t.toml"
    spec.write_text(SMALL)
    jobs = plan_jobs([spec], [parse_sweep("tube.radius=4:6:4")], tmp_path, ["step"])
    executor = ProcessExecutor(2)
    results: dict[int, JobResult] = {}
    retried = []
    killed = []

    def finished(i, result):
        results[i] = result
        if not killed:  # the other worker is busy with a job: kill it there
            busy = [w for w in executor._workers if w.index is not None]
            if busy:
                os.kill(busy[0].process.pid, signal.SIGKILL)
                killed.append(busy[0].index)

    try:
        interrupted = run_jobs(
            jobs,
            executor,
            finished,
            retries=1,
            lost=lambda i, m: JobResult(jobs[i].name, "failed", m),
            retrying=lambda i, m, a: retried.append((i, m, a)),
        )
    finally:
        executor.close()
    assert not interrupted and killed and [r[0] for r in retried] == killed
    assert "its worker process died" in retried[0][1] and retried[0][2] == 2
    assert sorted(results) == [0, 1, 2, 3] and all(r.status == "ok" and r.valid for r in results.values())
    assert all(Path(p).exists() for job in jobs for p in job.outputs)


def test_the_same_spec_gives_the_same_step_bytes(tmp_path, monkeypatch):
    spec = tmp_path / "t.toml"
    spec.write_text(SMALL)
    job = plan_jobs([spec], [], tmp_path / "a", ["step"])[0]
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    assert run_job(job).status == "ok"
    other = plan_jobs([spec], [], tmp_path / "b", ["step"])[0]
    time.sleep(1.1)  # another second on the clock: only the time stamp may differ
    assert run_job(other).status == "ok"
    a, b = (Path(j.outputs[0]).read_bytes() for j in (job, other))
    assert a != b and content_hash(a, "t.step") == content_hash(b, "t.step")
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    for j in (job, other):
        assert run_job(j).status == "ok"
    a, b = (Path(j.outputs[0]).read_bytes() for j in (job, other))
    assert a == b and b"'2023-11-14T22:13:20'" in a


def test_a_shipped_job_builds_without_the_submitters_files(tmp_path):
    """What a cluster worker gets: the resolved spec and the bytes of the file it refers to
    (here a STEP centreline), built with the originals gone, the files' bytes sent back."""
    from tubecad.batch.dask_executor import remote_job, shipped

    root = ROOT / "samples"
    spec = tmp_path / "edge.toml"
    spec.write_text((root / "edge.toml").read_text())
    (tmp_path / "centreline.step").write_bytes((root / "centreline.step").read_bytes())
    job = plan_jobs([spec], [parse_sweep("tube.radius=1.5,2")], tmp_path / "out", ["step"])[1]
    task = shipped(job)
    spec.unlink(), (tmp_path / "centreline.step").unlink()
    result, files = remote_job(task)
    assert result.status == "ok" and result.valid, result.error
    assert sorted(files) == [f"{job.name}.report.json", f"{job.name}.step"]
    assert json.loads(files[f"{job.name}.report.json"])["parameters"]["tube"]["radius"] == 2
    assert not (tmp_path / "out").exists()  # nothing written here: the bytes came back


def test_a_result_that_ended_as_ctrl_c_came_is_kept_and_its_worker_ends_at_once():
    """The race of Ctrl-C with a job's end: the result is in the pipe, its files written,
    when the stop comes. The stop hands it over (the batch records it) and the worker, now
    between jobs, ends on SIGTERM without the 10 s grace."""
    executor = ProcessExecutor(1, run="json.dumps")  # any picklable job in, a result out
    try:
        executor.submit(0, [1, 2])
        (worker,) = executor._workers
        assert worker.conn.poll(60)  # the job has ended; its result waits to be read
        start = time.monotonic()
        assert executor.stop() == [(0, "[1, 2]")]
        assert time.monotonic() - start < 5.0 and worker.process.exitcode == 0
    finally:
        executor.close()
