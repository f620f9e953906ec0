"""`tubecad build` over many specs and parameter sweeps (tubecad.batch.jobs), from the command
line."""

import json
import math

import pytest
from click.testing import CliRunner

from tubecad.brep import properties as props
from tubecad.cli.app import cli
from tubecad.export.cad import import_shape

LENGTH = 300.0
SMALL = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, {length}]

[tube]
radius = {radius}

[layout]
rings = 3
stringers = 2
"""


def spec(folder, name, radius, length=LENGTH):
    path = folder / f"{name}.toml"
    path.write_text(SMALL.format(radius=radius, length=length))
    return path


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def step_volume(path):
    shape = import_shape(path)
    assert props.is_valid(shape) and props.count(shape, "solid") == 1
    return props.volume(shape)


@pytest.fixture(scope="module")
def pool_batch(tmp_path_factory):
    """Two good specs and a bad one, two worker processes, STEP and IGES."""
    folder = tmp_path_factory.mktemp("specs")
    specs = [spec(folder, "thin", 6.0), spec(folder, "bad", -1.0), spec(folder, "thick", 9.0)]
    out = folder / "out" / "new"
    result = run("build", *specs, "-d", out, "-j", 2, "-f", "step", "-f", "iges")
    return result, out


@pytest.mark.slow
def test_pool_batch_writes_each_good_spec_and_reports_the_bad_one(pool_batch):
    result, out = pool_batch
    assert result.exit_code == 2, result.output
    for name, radius in (("thin", 6.0), ("thick", 9.0)):
        # measured 2.8e-12
        assert step_volume(out / f"{name}.step") == pytest.approx(math.pi * radius**2 * LENGTH, rel=3e-11)
        report = json.loads((out / f"{name}.report.json").read_text())
        assert report["parameters"]["tube"]["radius"] == radius and report["brep"]["valid"]
        assert report["exports"][str(out / f"{name}.iges")]["valid"]
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["batch.json"] + [f"{n}.{e}" for n in ("thin", "thick") for e in ("step", "iges", "report.json")]
    )  # nothing from the bad job, no temporary files
    record = json.loads((out / "batch.json").read_text())
    assert (record["jobs_total"], record["ok"], record["failed"], record["workers"]) == (3, 2, 1, 2)
    jobs = {j["name"]: j for j in record["jobs"]}
    assert [j["name"] for j in record["jobs"]] == ["thin", "bad", "thick"]
    assert jobs["bad"]["status"] == "failed" and jobs["bad"]["outputs"] == []
    assert "[tube] radius must be in (0, inf), got -1" in jobs["bad"]["error"]
    assert jobs["thin"]["status"] == "ok" and jobs["thin"]["error"] is None and jobs["thin"]["seconds"] > 0
    assert jobs["thin"]["outputs"] == ["thin.step", "thin.iges", "thin.report.json"]


@pytest.mark.slow
def test_pool_batch_progress_lines(pool_batch):
    result, out = pool_batch
    lines = result.stderr.splitlines()
    done = sorted(
        line.split("] ", 1)[1].split(":")[0] for line in lines if line.startswith(("[1/3]", "[2/3]", "[3/3]"))
    )
    assert done == ["bad", "thick", "thin"]
    import re

    # what was built and how long it took, then the batch's rate and the time left (not after the last)
    assert any(
        re.search(r"\] thin: tube_solid 6 faces valid, 3 files, [\d.]+ s; [\d.e+-]+ jobs/s(, ~\d+ s left)?$", line)
        for line in lines
    ), lines
    assert (
        re.search(r"^\[1/3\] .*, ~\d+ s left$", lines[1])
        and "left" not in [l for l in lines if l.startswith("[3/3]")][0]
    )
    assert any("] bad: FAILED: " in line and "radius must be" in line for line in lines)
    assert "3 jobs: 2 ok, 1 failed" in lines[-1] and str(out / "batch.json") in lines[-1]
    assert "Traceback" not in result.output


@pytest.mark.slow
def test_sweep_over_the_radius_scales_the_volume_as_rho_squared(tmp_path):
    paper = spec(tmp_path, "paper", 5.0, length=200.0)
    out = tmp_path / "out"
    result = run("build", paper, "--sweep", "tube.radius=5,7.5,10", "-d", out, "-j", 1)
    assert result.exit_code == 0, result.output
    names = ["paper_radius-5", "paper_radius-7.5", "paper_radius-10"]
    volumes = {r: step_volume(out / f"{n}.step") for n, r in zip(names, (5.0, 7.5, 10.0))}
    for radius, volume in volumes.items():
        assert volume / volumes[5.0] == pytest.approx((radius / 5.0) ** 2, rel=1e-7)
    record = json.loads((out / "batch.json").read_text())
    assert [j["name"] for j in record["jobs"]] == names
    assert [j["source"] for j in record["jobs"]] == [f"{paper}[tube.radius={v}]" for v in ("5", "7.5", "10")]
    assert record["jobs"][1]["sweep"] == {"tube.radius": 7.5} and record["sweeps"] == ["tube.radius=5,7.5,10"]
    assert "3 jobs: 3 ok, 0 failed" in result.stderr


@pytest.mark.parametrize(
    "sweep, says",
    [
        ("tube.radus=1,2", "unknown key [tube] radus; allowed keys are radius, allow_irregular"),
        ("tubes.radius=1", "unknown section [tubes]"),
        ("radius=1", "the key must be SECTION.KEY"),
        ("tube.radius", "expected SECTION.KEY=VALUES"),
        ("tube.radius=abc", "the values must be TOML values"),
        ("tube.radius=1:3", "the values must be TOML values"),
        ("tube.radius=1:3:x", "a range is START:STOP:COUNT"),
        ("tube.radius=1:3:1", "a range is START:STOP:COUNT"),
    ],
)
def test_bad_sweeps_exit_2_naming_them_before_anything_is_built(tmp_path, sweep, says):
    out = tmp_path / "out"
    result = run("build", spec(tmp_path, "paper", 5.0), "--sweep", sweep, "-d", out)
    assert result.exit_code == 2, result.output
    assert says in result.output and repr(sweep) in result.output and "Traceback" not in result.output
    assert not out.exists()


def test_swept_values_the_spec_refuses_fail_their_jobs_naming_the_value(tmp_path):
    out = tmp_path / "out"
    result = run("build", spec(tmp_path, "paper", 5.0), "--sweep", 'tube.radius=-1,"big"', "-d", out, "-j", 1)
    assert result.exit_code == 2, result.output
    assert "paper.toml[tube.radius=-1]: [tube] radius must be in (0, inf)" in result.stderr
    assert "paper.toml[tube.radius=\"big\"]: [tube] radius: unknown name 'big'" in result.stderr
    record = json.loads((out / "batch.json").read_text())
    assert [j["status"] for j in record["jobs"]] == ["failed", "failed"]
    assert sorted(p.name for p in out.iterdir()) == ["batch.json"]


@pytest.mark.parametrize(
    "args, says",
    [
        (["two.toml", "-o", "x.step"], "-o/--output and --report are for one SPEC"),
        (["--report", "r.json", "--sweep", "tube.radius=1,2", "-d", "out"], "-o/--output and --report"),
        (["two.toml"], "batch mode (several SPECs) needs -d/--out-dir"),
        (
            ["-f", "iges", "-o", "x.step"],
            "-f/--format, -j/--jobs, --scheduler, --remote-dir and --job-timeout are for batch mode",
        ),
        ([], "Missing option '-o' / '--output'"),
        (["-d", "out", "-f", "obj"], "'obj' is not one of"),
    ],
)
def test_batch_option_errors(tmp_path, args, says, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = run("build", spec(tmp_path, "one", 5.0), *args)
    assert result.exit_code == 2 and says in result.output, result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["one.toml"]


def test_ctrl_c_cancels_the_rest_without_partial_files(tmp_path, monkeypatch):
    import tubecad.spec.build as build
    from tubecad.core.atomic import atomic_path, write_text

    def fake(spec, outputs, step_schema, report_path, written):
        if "radius=2" in spec.source:
            with atomic_path(outputs[0]) as tmp:
                tmp.write_text("half a file")
                raise KeyboardInterrupt  # Ctrl-C in the middle of a write
        for path in (*outputs, report_path):
            written.append(write_text(path, "{}"))
        return {"brep": {"kind": "tube_solid", "faces": 6, "valid": True}, "exports": {}}

    monkeypatch.setattr(build, "build_and_export", fake)
    out = tmp_path / "out"
    result = run("build", spec(tmp_path, "p", 5.0), "--sweep", "tube.radius=1,2,3", "-d", out, "-j", 1)
    assert result.exit_code == 130, result.output
    assert "interrupted: 2 of 3 jobs cancelled, 1 done" in result.stderr.splitlines()[-1]
    assert sorted(p.name for p in out.iterdir()) == ["batch.json", "p_radius-1.report.json", "p_radius-1.step"]
    record = json.loads((out / "batch.json").read_text())
    assert record["interrupted"] and [j["status"] for j in record["jobs"]] == ["ok", "cancelled", "cancelled"]
