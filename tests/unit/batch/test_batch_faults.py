"""Batches that resume and survive faults (issue 15), on this machine's worker processes:

- the manifest (batch.json) records each job's spec hash and its files' content hashes;
  a rerun builds only the jobs that are missing or changed (a changed spec, a deleted or
  altered file), ``--force`` builds them all;
- a batch interrupted with Ctrl-C (SIGINT to the command) keeps every finished job, leaves
  no partial file, and a rerun builds only the rest;
- a worker killed in the middle of a job costs only that job's retry;
- a job past ``--job-timeout`` is stopped, retried, then reported as failed, with no file;
- the same spec gives byte-identical STEP files but for the header's time stamp, which
  SOURCE_DATE_EPOCH fixes.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import ROOT, SMALL_BATCH_TUBE

from tubecad.batch.executors import ProcessExecutor, run_jobs
from tubecad.batch.jobs import JobResult, parse_sweep, plan_jobs, run_job
from tubecad.batch.manifest import content_hash, file_hash
from tubecad.cli.app import cli

# the same on both OCCT generations: CI runs it once; batches of worker processes: slow
pytestmark = [pytest.mark.once, pytest.mark.slow]

SMALL = SMALL_BATCH_TUBE
SWEEP = "tube.radius=4:6:6"  # six small tubes


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def manifest(out: Path) -> dict:
    return json.loads((out / "batch.json").read_text())


@pytest.fixture(scope="module")
def first_batch(tmp_path_factory):
    folder = tmp_path_factory.mktemp("resume")
    spec = folder / "t.toml"
    spec.write_text(SMALL)
    out = folder / "out"
    result = run("build", spec, "--sweep", SWEEP, "-d", out, "-j", 1)  # here: the executors are tested below
    assert result.exit_code == 0, result.output
    return spec, out


def test_the_manifest_records_the_hashes_of_every_file(first_batch):
    _, out = first_batch
    record = manifest(out)
    assert record["ok"] == 6 and record["skipped"] == 0
    for job in record["jobs"]:
        assert len(job["spec_hash"]) == 64 and job["attempts"] == 1
        assert set(job["hashes"]) == {f"{job['name']}.step", f"{job['name']}.report.json"}
        for name, digest in job["hashes"].items():  # recomputed here, from the bytes on disk
            assert content_hash((out / name).read_bytes(), name) == digest


def test_a_rerun_builds_only_what_is_missing_or_changed(first_batch, tmp_path):
    spec, out = first_batch
    names = [j["name"] for j in manifest(out)["jobs"]]
    again = run("build", spec, "--sweep", SWEEP, "-d", out, "-j", 1)
    assert again.exit_code == 0 and "(6 of 6 already built and unchanged: skipped)" in again.stderr
    assert manifest(out)["skipped"] == 6
    assert "6 jobs: 0 ok, 6 skipped (unchanged), 0 failed" in again.stderr.splitlines()[-1]  # each job once
    (out / f"{names[1]}.step").unlink()  # a deleted output
    with open(out / f"{names[2]}.step", "ab") as fh:  # a damaged one
        fh.write(b"\n")
    third = run("build", spec, "--sweep", SWEEP, "-d", out, "-j", 1)
    assert third.exit_code == 0 and "building 2 jobs" in third.stderr, third.stderr
    built = sorted(
        line.split("] ")[1].split(":")[0]
        for line in third.stderr.splitlines()
        if line.startswith("[2/2]") or line.startswith("[1/2]")
    )
    assert built == sorted(names[1:3])
    assert "6 jobs: 2 ok, 4 skipped (unchanged), 0 failed" in third.stderr.splitlines()[-1]
    assert all(
        file_hash(out / f"{n}.step") == manifest(out)["jobs"][i]["hashes"][f"{n}.step"] for i, n in enumerate(names)
    )
    forced = run("build", spec, "--sweep", SWEEP, "-d", out, "-j", 1, "--force")
    assert forced.exit_code == 0 and "building 6 jobs" in forced.stderr and manifest(out)["skipped"] == 0


def test_a_changed_spec_is_built_again(first_batch):
    spec, out = first_batch
    changed = spec.parent / "t.toml"
    changed.write_text(SMALL.replace("stringers = 2", "stringers = 3"))
    try:
        rerun = run("build", changed, "--sweep", SWEEP, "-d", out, "-j", 1)
        assert rerun.exit_code == 0 and "building 6 jobs" in rerun.stderr
    finally:
        spec.write_text(SMALL)


def test_ctrl_c_keeps_what_finished_and_a_rerun_builds_the_rest(tmp_path):
    spec = tmp_path / "t.toml"
    spec.write_text(SMALL)
    out = tmp_path / "out"
    command = [
        sys.executable,
        "-m",
        "tubecad.cli.console",
        "build",
        str(spec),
        "--sweep",
        "tube.radius=4:6:8",
        "-d",
        str(out),
        "-j",
        "2",
    ]
    proc = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    finished = 0
    for line in proc.stderr:
        finished += line.startswith("[")
        if finished == 3:
            proc.send_signal(signal.SIGINT)
            break
    rest = proc.stderr.read()
    assert proc.wait(60) == 130, rest
    record = manifest(out)
    done = record["ok"]
    assert 3 <= done < 8 and record["interrupted"]
    assert not list(out.glob(".*.part*"))  # no partial file
    files = {p.name for p in out.iterdir()} - {"batch.json"}
    assert files == {n for j in record["jobs"] if j["status"] == "ok" for n in j["hashes"]}
    again = subprocess.run(command, capture_output=True, text=True)
    assert again.returncode == 0, again.stderr
    assert (
        f"building {8 - done} jobs" in again.stderr
        and f"({done} of 8 already built and unchanged: skipped)" in again.stderr
    )
    assert manifest(out)["ok"] == 8


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


def test_a_job_past_the_timeout_is_stopped_retried_and_fails_without_files(tmp_path):
    spec = tmp_path / "slow.toml"
    spec.write_text(SMALL.replace("rings = 3", "rings = 60").replace("stringers = 2", "stringers = 16"))
    out = tmp_path / "out"
    start = time.monotonic()
    result = run("build", spec, "-d", out, "--job-timeout", 0.5, "--retries", 1)
    assert result.exit_code == 2, result.output
    lines = result.stderr.splitlines()
    assert any("timed out after 0.5 s (--job-timeout); retrying (attempt 2)" in line for line in lines), lines
    assert any("] slow: FAILED (attempt 2): timed out after 0.5 s" in line for line in lines), lines
    assert sorted(p.name for p in out.iterdir()) == ["batch.json"] and time.monotonic() - start < 60
    assert manifest(out)["jobs"][0]["attempts"] == 2


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
