"""Batches over many specs and parameter sweeps (tubecad.batch.jobs): sweeps parsed, jobs named,
progress lines. `tubecad build` in batch mode is run in tests/e2e/test_cli_batch.py."""

import pytest

from tubecad import ParameterError
from tubecad.batch.jobs import parse_sweep, plan_jobs


def test_parse_sweep_values_and_ranges():
    assert parse_sweep("tube.radius=10,12,15").values == (10, 12, 15)
    assert parse_sweep("axis.beta_deg=0:30:4").values == (0, 10, 20, 30)
    assert parse_sweep("axis.beta_deg=0.0:1.0:3").values == (0.0, 0.5, 1.0)
    assert parse_sweep("axis.beta_deg=-5:5:3").values == (-5, 0, 5)
    assert parse_sweep('axis.curve="helix", "clothoid"').values == ("helix", "clothoid")
    assert parse_sweep("axis.s=[0, 300],[0, 400]").values == ([0, 300], [0, 400])
    assert parse_sweep("axis.A=400").label == "axis.A"  # any family's [axis] key
    for text in ("tube.radius=__import__('os')", "tube.radius=1\nx = 2", "tube.radius=1], w = [2"):
        with pytest.raises(ParameterError):
            parse_sweep(text)


def test_job_names_are_unique_and_safe(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    sweeps = [parse_sweep("tube.radius=10,12.5"), parse_sweep("axis.beta_deg=0:30:2")]
    jobs = plan_jobs([tmp_path / "a" / "p q.toml", tmp_path / "b" / "p q.toml"], sweeps, tmp_path, ["STEP", "step"])
    assert [j.name for j in jobs][:4] == [
        "p_q_radius-10_beta_deg-0",
        "p_q_radius-10_beta_deg-30",
        "p_q_radius-12.5_beta_deg-0",
        "p_q_radius-12.5_beta_deg-30",
    ]
    assert [j.name for j in jobs][4:] == [j.name + "_2" for j in jobs[:4]]
    assert jobs[0].outputs == (str(tmp_path / "p_q_radius-10_beta_deg-0.step"),)
    assert jobs[3].source.endswith("p q.toml[tube.radius=12.5, axis.beta_deg=30]")
    assert jobs[3].overrides == (("tube", "radius", 12.5), ("axis", "beta_deg", 30))
    assert plan_jobs([tmp_path / "batch.toml"], [], tmp_path, ["json"])[0].name == "batch_2"  # batch.json is taken


def test_a_failed_jobs_line_holds_its_whole_message():
    """The end of a message often holds the fix (allow_irregular): the line is never cut."""
    from tubecad.batch.jobs import JobResult
    from tubecad.batch.runner import progress_line

    error = "[tube] radius 40: the tube is irregular: " + "the circle at s = 1 crosses the axis; " * 12
    error += "set allow_irregular = true to build it anyway"
    line = progress_line(JobResult("t_radius-40", "failed", error), 3, 6)
    assert len(error) > 400 and line == f"[3/6] t_radius-40: FAILED: {error}"
