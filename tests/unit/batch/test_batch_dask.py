"""Batches on a Dask distributed cluster (issue 15): a LocalCluster of 2 worker processes on
127.0.0.1, started here.

- the same 8-job sweep as the local pool gives the same files (byte for byte, the STEP
  time stamp fixed by SOURCE_DATE_EPOCH; hashes equal in both manifests);
- one worker killed in the middle of the batch: all 8 results present and valid;
- a batch interrupted after some jobs and run again builds only the rest.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

distributed = pytest.importorskip("distributed")

from conftest import SMALL_BATCH_TUBE

from tubecad.batch.dask_executor import DaskExecutor
from tubecad.batch.jobs import JobResult, parse_sweep, plan_jobs
from tubecad.batch.runner import run_batch
from tubecad.cli.app import cli

# the same on both OCCT generations: CI runs it once; clusters of worker processes: slow
pytestmark = [pytest.mark.once, pytest.mark.slow]

SMALL = SMALL_BATCH_TUBE
SWEEP = "tube.radius=4:6:8"


@pytest.fixture(scope="module")
def cluster():
    os.environ["SOURCE_DATE_EPOCH"] = "1700000000"  # the workers inherit it: stable STEP headers
    from distributed import LocalCluster

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address="127.0.0.1:0"
    ) as local:
        yield local
    del os.environ["SOURCE_DATE_EPOCH"]


@pytest.fixture(scope="module")
def spec(tmp_path_factory):
    path = tmp_path_factory.mktemp("dask") / "t.toml"
    path.write_text(SMALL)
    return path


def manifest(out: Path) -> dict:
    return json.loads((out / "batch.json").read_text())


def test_the_cluster_builds_the_same_files_as_the_local_pool(cluster, spec, tmp_path):
    runner = CliRunner()
    local = runner.invoke(cli, ["build", str(spec), "--sweep", SWEEP, "-d", str(tmp_path / "local"), "-j", "2"])
    assert local.exit_code == 0, local.output
    remote = runner.invoke(
        cli,
        ["build", str(spec), "--sweep", SWEEP, "-d", str(tmp_path / "dask"), "--scheduler", cluster.scheduler_address],
    )
    assert remote.exit_code == 0, remote.output
    first = remote.stderr.splitlines()[0]
    assert f"with Dask at {cluster.scheduler_address} (2 workers, 2 threads; dashboard http://127.0.0.1:" in first
    a, b = manifest(tmp_path / "local"), manifest(tmp_path / "dask")
    assert a["ok"] == b["ok"] == 8
    for ja, jb in zip(a["jobs"], b["jobs"]):
        step = f"{ja['name']}.step"
        assert ja["spec_hash"] == jb["spec_hash"] and ja["hashes"][step] == jb["hashes"][step]
        assert (tmp_path / "local" / step).read_bytes() == (tmp_path / "dask" / step).read_bytes()


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


def test_an_interrupted_cluster_batch_resumes(cluster, spec, tmp_path):
    out = tmp_path / "out"
    command = [
        sys.executable,
        "-m",
        "tubecad.cli.console",
        "build",
        str(spec),
        "--sweep",
        SWEEP,
        "-d",
        str(out),
        "--scheduler",
        cluster.scheduler_address,
    ]
    env = {**os.environ, "SOURCE_DATE_EPOCH": "1700000000"}
    proc = subprocess.Popen(command, stderr=subprocess.PIPE, text=True, env=env)
    finished = 0
    for line in proc.stderr:
        finished += line.startswith("[")
        if finished == 3:
            proc.send_signal(signal.SIGINT)
            break
    rest = proc.stderr.read()
    assert proc.wait(60) == 130, rest
    done = manifest(out)["ok"]
    assert 3 <= done < 8 and not list(out.glob(".*.part*"))
    again = subprocess.run(command, capture_output=True, text=True, env=env)
    assert again.returncode == 0, again.stderr
    assert (
        f"building {8 - done} jobs" in again.stderr
        and f"({done} of 8 already built and unchanged: skipped)" in again.stderr
    )
    assert manifest(out)["ok"] == 8


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


def test_workers_sharing_a_file_system_write_the_files_themselves(cluster, spec, tmp_path):
    """--remote-dir: the batch folder as the workers see it (here the same disk); the files
    are not sent back, and the manifest hashes them as this machine sees them."""
    out = tmp_path / "shared"
    result = CliRunner().invoke(
        cli,
        [
            "build",
            str(spec),
            "--sweep",
            "tube.radius=4:6:3",
            "-d",
            str(out),
            "--scheduler",
            cluster.scheduler_address,
            "--remote-dir",
            str(out),
        ],
    )
    assert result.exit_code == 0, result.output
    record = manifest(out)
    assert record["ok"] == 3
    for job in record["jobs"]:
        assert all((out / name).stat().st_size > 0 for name in job["hashes"]) and len(job["hashes"]) == 2


@pytest.mark.parametrize(
    "address, says",
    [
        ("tcp://127.0.0.1:1", "--scheduler tcp://127.0.0.1:1: cannot reach the Dask scheduler"),
        ("foo", "--scheduler 'foo': not a scheduler address such as tcp://HOST:PORT"),
    ],
)
def test_a_scheduler_that_cannot_be_reached_is_refused_before_anything_is_written(spec, tmp_path, address, says):
    result = CliRunner().invoke(cli, ["build", str(spec), "-d", str(tmp_path / "out"), "--scheduler", address])
    assert result.exit_code == 2 and says in result.output, result.output
    assert not (tmp_path / "out").exists()
