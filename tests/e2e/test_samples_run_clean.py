"""The showcase warns of nothing (issue 41): a sample shows the tool at its best, so every
sample spec, through the commands its tests run (``tubecad build`` of each, ``tubecad shop``
of those with a shop package), and ``tubecad paper`` print no warning and record none.

tubecad warns in one way: a line ``warning: ...`` on stderr (click's ``output`` holds both
streams) for what a written file records as a warning: flat.json's ``warnings`` (webs whose
flat pattern crosses itself), index.json's ``warnings`` (panels above ``max_strain``). Each
run here is the suite's one run of it (conftest: ``sample_build``, ``sample_shop``,
``paper_run``), so this adds no build."""

import json

import pytest
from conftest import SAMPLES

pytestmark = pytest.mark.slow

#: the samples `tubecad shop` runs on in the tests (tests/e2e/test_shop_cli.py)
SHOP_SAMPLES = ["shop_duct", "tee", "equal_tee"]


def said_warnings(output: str) -> list[str]:
    return [line for line in output.splitlines() if "warning" in line.lower()]


def test_the_paper_command_warns_of_nothing(paper_run):
    assert paper_run.exit_code == 0, paper_run.output
    assert said_warnings(paper_run.output) == []
    flat = json.loads((paper_run.folder / "flat" / "flat.json").read_text(encoding="utf-8"))
    assert flat["warnings"] == [] and not any(web["crosses_itself"] for web in flat["webs"])
    assert [w["name"] for w in flat["webs"] if w["name"].startswith("stringer_")] == ["stringer_00", "stringer_04"]


@pytest.mark.parametrize("spec", sorted(SAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_every_sample_builds_without_a_warning(sample_build, spec):
    result = sample_build(spec.stem)
    assert result.exit_code == 0, result.output
    assert said_warnings(result.output) == []


@pytest.mark.parametrize("name", SHOP_SAMPLES)
def test_the_shop_samples_warn_of_nothing(sample_shop, name):
    """shop_duct's panels stay under its max_strain = 0.04 (largest 0.033; the sample says why
    that limit), and no web piece or panel is flagged."""
    result = sample_shop(name)
    assert result.exit_code == 0, result.output
    assert said_warnings(result.output) == []
    index = json.loads((result.folder / "index.json").read_text(encoding="utf-8"))
    assert index["warnings"] == []
    limit = index["fabrication"]["max_strain"]
    assert all(not p["exceeds_max_strain"] and p["max_strain"] <= limit for p in index.get("panels") or [])
