"""Batches on a Dask distributed cluster (issue 15) from the command line: a LocalCluster of 2
worker processes on 127.0.0.1, started here.

- `tubecad build --scheduler`: the same 8-job sweep as the local pool gives the same files
  (byte for byte, the STEP time stamp fixed by SOURCE_DATE_EPOCH; hashes equal in both
  manifests);
- a batch interrupted after some jobs and run again builds only the rest;
- --remote-dir; a scheduler that cannot be reached is refused before anything is written.
"""

from __future__ import annotations

import os

import pytest
from click.testing import CliRunner
from shared.batch import assert_a_rerun_builds_the_rest, build_command, interrupted, manifest

distributed = pytest.importorskip("distributed")

from shared.batch_dask import SWEEP
from shared.batch_dask import cluster_fixture as cluster_fixture  # the fixture cluster; `as`: imported for pytest
from shared.batch_dask import spec_fixture as spec_fixture  # the fixture spec; `as`: imported for pytest

from tubecad.cli.app import cli

# the same on both OCCT generations: CI runs it once; clusters of worker processes: slow
pytestmark = [pytest.mark.once, pytest.mark.slow]


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


def test_an_interrupted_cluster_batch_resumes(cluster, spec, tmp_path):
    out = tmp_path / "out"
    command = build_command(spec, SWEEP, out, "--scheduler", cluster.scheduler_address)
    env = {**os.environ, "SOURCE_DATE_EPOCH": "1700000000"}
    code, rest = interrupted(command, 3, env)
    assert code == 130, rest
    done = manifest(out)["ok"]
    assert 3 <= done < 8 and not list(out.glob(".*.part*"))
    assert_a_rerun_builds_the_rest(command, out, done, env)


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
