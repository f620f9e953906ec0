"""The one mechanism for tests that need an external program (tests/conftest.py: the
``requires`` marker and function): on a machine without the program the test is skipped with a
one-line reason (the README's quick start passes on a fresh machine), and with CI set the same
test fails (CI installs the programs: a green CI cannot hide a missing install step).

Proved on a tiny test file run by pytest in a subprocess whose PATH holds only this Python's
folder, so that ccx cannot be found."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import TESTS

TINY = """
import pytest
from conftest import requires


@pytest.mark.requires("ccx")
def test_marked():
    raise AssertionError("ran without ccx")


def test_called():
    requires("ccx")
    raise AssertionError("ran without ccx")


def test_needs_nothing():
    pass
"""


def run_tiny(tmp_path: Path, ci: str | None) -> subprocess.CompletedProcess:
    (tmp_path / "test_tiny.py").write_text(TINY)
    env = {k: v for k, v in os.environ.items() if k not in ("CI", "PYTEST_ADDOPTS", "PYTEST_XDIST_WORKER")}
    env["PATH"] = str(Path(sys.executable).parent)  # no ccx here
    env["PYTEST_DISABLE_PLUGIN_AUTOLOAD"] = "1"  # only what the tiny run needs: a quicker start
    env["PYTHONPATH"] = os.pathsep.join([str(TESTS), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    if ci is not None:
        env["CI"] = ci
    return subprocess.run(
        [sys.executable, "-m", "pytest", *"-p conftest -p no:cacheprovider -p no:xdist -rsfE test_tiny.py".split()],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_a_missing_program_skips_with_a_one_line_reason(tmp_path):
    done = run_tiny(tmp_path, ci=None)
    assert done.returncode == 0, done.stdout + done.stderr
    assert re.search(r"\b1 passed, 2 skipped\b", done.stdout), done.stdout
    reasons = [ln for ln in done.stdout.splitlines() if ln.startswith("SKIPPED")]
    assert len(reasons) == 2, done.stdout
    for line in reasons:
        assert "needs ccx (CalculiX): not on PATH; apt-get install calculix-ccx" in line, line


@pytest.mark.parametrize("ci", ["true", "1"])
def test_in_ci_a_missing_program_fails(tmp_path, ci):
    done = run_tiny(tmp_path, ci=ci)
    assert done.returncode == 1, done.stdout + done.stderr
    # the mark fails the test's setup (an error), the call its body (a failure); none is skipped
    summary = done.stdout.strip().splitlines()[-1]
    assert re.search(r"\b1 failed, 1 passed, 1 error\b", summary) and "skipped" not in summary, done.stdout
    assert "ran without ccx" not in done.stdout  # failed before the test's body ran on
    said = [ln for ln in done.stdout.splitlines() if ln.startswith(("FAILED", "ERROR"))]
    assert len(said) == 2, done.stdout
    assert all(f"CI={ci}: needs ccx (CalculiX): not on PATH; apt-get install calculix-ccx" in ln for ln in said)
