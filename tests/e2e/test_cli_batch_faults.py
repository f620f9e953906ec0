"""Batches that resume and survive faults (issue 15), from the command line, on this machine's
worker processes:

- the manifest (batch.json) records each job's spec hash and its files' content hashes;
  a rerun builds only the jobs that are missing or changed (a changed spec, a deleted or
  altered file), ``--force`` builds them all;
- a batch interrupted with Ctrl-C (SIGINT to the command) keeps every finished job, leaves
  no partial file, and a rerun builds only the rest;
- a job past ``--job-timeout`` is stopped, retried, then reported as failed, with no file.
"""

from __future__ import annotations

import time

import pytest
from click.testing import CliRunner
from conftest import SMALL_BATCH_TUBE
from shared.batch import assert_a_rerun_builds_the_rest, build_command, interrupted, manifest

from tubecad.batch.manifest import content_hash, file_hash
from tubecad.cli.app import cli

# the same on both OCCT generations: CI runs it once; batches of worker processes: slow
pytestmark = [pytest.mark.once, pytest.mark.slow]

SMALL = SMALL_BATCH_TUBE
SWEEP = "tube.radius=4:6:6"  # six small tubes


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


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
    command = build_command(spec, "tube.radius=4:6:8", out, "-j", "2")
    code, rest = interrupted(command, 3)
    assert code == 130, rest
    record = manifest(out)
    done = record["ok"]
    assert 3 <= done < 8 and record["interrupted"]
    assert not list(out.glob(".*.part*"))  # no partial file
    files = {p.name for p in out.iterdir()} - {"batch.json"}
    assert files == {n for j in record["jobs"] if j["status"] == "ok" for n in j["hashes"]}
    assert_a_rerun_builds_the_rest(command, out, done)


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
