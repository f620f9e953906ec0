"""Progress of a long `tubecad build` on stderr (tubecad.core.progress), and the batch's
line per job naming what was built. No assertion depends on how long anything takes: the
threshold is forced to 0 (TUBECAD_PROGRESS_AFTER) or the clock is a counter."""

import io
import os
import pty
import re
import subprocess
import sys

import pytest
from click.testing import CliRunner
from conftest import ROOT

from tubecad.batch.jobs import what_was_built
from tubecad.cli.app import cli
from tubecad.core.progress import AFTER_VARIABLE, Progress

SAMPLES = ROOT / "samples"
STIFFENERS = [
    "ring_01",
    "ring_02",
    "ring_03",
    "ring_04",
    "ring_05",
    "stringer_00",
    "stringer_01",
    "stringer_02",
    "stringer_03",
]
SMALL = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 200.0]

[tube]
radius = 6.0

[layout]
rings = 3
stringers = 2
"""


def run(*args, env=None):
    return CliRunner().invoke(cli, [str(a) for a in args], env=env)


class Clock:
    """A clock that moves only when told to."""

    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


# ---------------------------------------------------------------- the reporter


def test_nothing_is_shown_before_the_threshold_then_every_update():
    clock, out = Clock(), io.StringIO()
    progress = Progress(out, after=2.0, clock=clock)
    progress.step("building stiffeners")
    progress.update("ring_01", 1, 3)
    assert out.getvalue() == ""
    clock.now = 2.5
    progress.update("ring_02", 2, 3)  # the first shown: the state at that moment
    progress.update("ring_03", 3, 3)
    progress.step("writing and reading back files", 2)
    progress.advance(1, "wrote a.step")
    assert out.getvalue().splitlines() == [
        "tubecad: building stiffeners 2/3 (ring_02)",
        "tubecad: building stiffeners 3/3 (ring_03)",
        "tubecad: writing and reading back files 0/2",
        "tubecad: writing and reading back files 1/2 (wrote a.step)",
    ]


def test_a_long_stage_prints_about_every_5_percent_and_disabled_prints_nothing():
    out = io.StringIO()
    progress = Progress(out, after=0.0, clock=Clock())
    progress.step("building", 1000)
    for i in range(1, 1001):
        progress.update(f"item_{i}", i, 1000)
    lines = out.getvalue().splitlines()
    assert 20 <= len(lines) <= 22 and lines[-1] == "tubecad: building 1000/1000 (item_1000)"
    silent = io.StringIO()
    quiet = Progress(silent, after=0.0, enabled=False, clock=Clock())
    quiet.step("building", 3)
    quiet.update("x", 1, 3)
    quiet.close()
    assert silent.getvalue() == ""


def test_the_threshold_comes_from_the_environment(monkeypatch):
    monkeypatch.setenv(AFTER_VARIABLE, "0")
    assert Progress(io.StringIO()).after == 0.0
    monkeypatch.setenv(AFTER_VARIABLE, "soon")
    assert Progress(io.StringIO()).after == 2.0
    monkeypatch.delenv(AFTER_VARIABLE)
    assert Progress(io.StringIO()).after == 2.0


# ---------------------------------------------------------------- tubecad build


@pytest.fixture(scope="module")
def stiffened(tmp_path_factory):
    """`tubecad build helix_stiffened.toml -o x.brep` with the threshold forced to 0."""
    out = tmp_path_factory.mktemp("stiffened") / "x.brep"
    return run("build", SAMPLES / "helix_stiffened.toml", "-o", out, env={AFTER_VARIABLE: "0"}), out


@pytest.mark.slow
def test_plain_progress_lines_name_each_stiffener_on_stderr_only(stiffened):
    result, out = stiffened
    assert result.exit_code == 0, result.output
    lines = result.stderr.splitlines()
    assert all(line.startswith("tubecad: ") for line in lines), lines
    built = [line for line in lines if line.startswith("tubecad: building stiffeners ")]
    assert built[-len(STIFFENERS) :] == [
        f"tubecad: building stiffeners {i}/9 ({name})" for i, name in enumerate(STIFFENERS, start=1)
    ]
    assert "tubecad: building the wall 4/4 (solid)" in lines
    assert f"tubecad: writing and reading back files 2/2 (checked {out.name})" in lines
    assert "tubecad:" not in result.stdout and result.stdout.startswith("wall: ")  # stdout: the summary only


def test_quiet_shows_no_progress(tmp_path):
    spec = tmp_path / "small.toml"
    spec.write_text(SMALL)
    result = run("build", spec, "-o", tmp_path / "x.step", "-q", env={AFTER_VARIABLE: "0"})
    assert result.exit_code == 0 and result.stderr == "" and result.stdout.startswith("tube_solid: ")


def test_a_fast_build_shows_no_progress_with_the_default_threshold(tmp_path, monkeypatch):
    monkeypatch.delenv(AFTER_VARIABLE, raising=False)
    spec = tmp_path / "small.toml"
    spec.write_text(SMALL)
    result = run("build", spec, "-o", tmp_path / "x.step")
    assert result.exit_code == 0 and result.stderr == "", result.stderr


@pytest.mark.slow
def test_a_terminal_gets_one_redrawn_bar(tmp_path):
    """stderr a pseudo-terminal: the bar is redrawn with carriage returns and cleared at the end;
    stdout (a pipe) gets the summary and nothing of the bar."""
    spec = tmp_path / "small.toml"
    spec.write_text(SMALL)
    master, slave = pty.openpty()
    env = {**os.environ, AFTER_VARIABLE: "0"}
    process = subprocess.Popen(
        [sys.executable, "-m", "tubecad.cli.console", "build", str(spec), "-o", str(tmp_path / "x.step")],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=slave,
        env=env,
        cwd=tmp_path,
    )
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # the terminal closed with the process
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    stdout = process.stdout.read().decode()
    assert process.wait(timeout=300) == 0
    terminal = b"".join(chunks).decode()
    assert terminal.count("\r") >= 3 and "\n" not in terminal.replace("\r\n", "\n").strip("\n"), repr(terminal)
    assert re.search(r"\rtubecad: building the tube +\[#+-*\] +2/3 +surface", terminal.replace("\x1b[?25l", ""))
    assert "tubecad: writing and reading back files" in terminal and "x.step" in terminal
    assert terminal.endswith("\r\x1b[K\x1b[?25h"), repr(terminal[-40:])  # cleared, cursor shown again
    assert stdout.startswith("tube_solid: ") and "\r" not in stdout and "tubecad:" not in stdout


# ---------------------------------------------------------------- the batch's lines


@pytest.mark.slow
def test_batch_line_names_the_wall_and_its_stiffeners(tmp_path):
    out = tmp_path / "out"
    result = run("build", SAMPLES / "helix_stiffened.toml", "-d", out, "-j", "1")
    assert result.exit_code == 0, result.output
    line = next(line for line in result.stderr.splitlines() if line.startswith("[1/1] "))
    assert re.fullmatch(
        r"\[1/1\] helix_stiffened: wall 50 faces valid \+ 5 ring \+ 4 stringer stiffeners \(T\), "
        r"2 files, \d+\.\d s; [\d.e+-]+ jobs/s",
        line,
    ), line
    quiet = run("build", SAMPLES / "helix.toml", "-d", tmp_path / "quiet", "-j", "1", "-q")
    assert quiet.exit_code == 0 and quiet.stderr.splitlines()[0].startswith("1 jobs: 1 ok, 0 failed")


def test_what_was_built_reads_the_report():
    report = {
        "brep": {"kind": "wall", "faces": 88},
        "stiffeners": {"stiffeners": [{"kind": "ring", "profile": "flat"}, {"kind": "stringer", "profile": "L"}]},
        "panels": [{}, {}, {}],
    }
    assert what_was_built(report) == "wall 88 faces valid + 1 ring + 1 stringer stiffeners (flat, L) + 3 panels"
    assert what_was_built({"brep": {"kind": "tube_solid", "faces": 6}}, False) == "tube_solid 6 faces NOT VALID"
