"""Batches from the command line (issue 15): tests/e2e/test_cli_batch_faults.py and
tests/e2e/test_cli_batch_dask.py read the manifest, interrupt a running batch with Ctrl-C and
run it again."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
from pathlib import Path


def build_command(spec: Path, sweep: str, out: Path, *options: str) -> list[str]:
    """``tubecad build SPEC --sweep SWEEP -d OUT OPTIONS`` as a command line for this Python."""
    return [sys.executable, "-m", "tubecad.cli.console", "build", str(spec), "--sweep", sweep, "-d", str(out), *options]


def manifest(out: Path) -> dict:
    return json.loads((out / "batch.json").read_text())


def interrupted(command: list[str], after: int, env: dict | None = None) -> tuple[int, str]:
    """Run ``command`` (a batch) and send it SIGINT (Ctrl-C) once ``after`` jobs have finished
    (lines on stderr starting with "["): its exit code and the rest of its stderr."""
    proc = subprocess.Popen(command, stderr=subprocess.PIPE, text=True, env=env)
    finished = 0
    for line in proc.stderr:
        finished += line.startswith("[")
        if finished == after:
            proc.send_signal(signal.SIGINT)
            break
    rest = proc.stderr.read()
    return proc.wait(60), rest


def assert_a_rerun_builds_the_rest(command: list[str], out: Path, done: int, env: dict | None = None) -> None:
    """``command`` run again builds only the 8 - ``done`` jobs left, skipping the others, and
    completes the batch in ``out``."""
    again = subprocess.run(command, capture_output=True, text=True, env=env)
    assert again.returncode == 0, again.stderr
    assert (
        f"building {8 - done} jobs" in again.stderr
        and f"({done} of 8 already built and unchanged: skipped)" in again.stderr
    )
    assert manifest(out)["ok"] == 8
