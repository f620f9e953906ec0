"""Issue 22: the library without the command line. A script parses a spec into its typed
model, runs a batch and measures a file without importing tubecad.cli; the spec's sections
are parsed once (the typed model), errors carry their key."""

import dataclasses
import json
import os
import subprocess
import sys
import tomllib
from types import SimpleNamespace

import pytest
from conftest import ROOT

from tubecad.core.errors import ParameterError, SpecError, TubecadError
from tubecad.spec.keys import ARRAY_SECTIONS, EXTRA_SECTIONS, TUBE_KEYS
from tubecad.spec.model import SECTION_TYPES, BranchSection, SpecModel, StiffenersSection
from tubecad.spec.parse import parse_spec

SAMPLES = ROOT / "samples"

SMALL = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 300.0]

[tube]
radius = {radius}

[layout]
rings = 3
stringers = 2
"""

SCRIPT = """
import json, sys
from pathlib import Path

from tubecad.batch import BatchOptions, build_batch
from tubecad.export.readback import readback_report
from tubecad.export.cad import import_shape
from tubecad.spec import build_from_spec, load_spec

folder = Path(sys.argv[1])
spec = load_spec(folder / "small.toml")                       # parse a spec
assert spec.wall is None and spec.layout.rings == 3 and spec.fit.tolerance == 1e-8
lines = []
outcome = build_batch(                                         # run a batch
    [folder / "small.toml"],
    folder / "out",
    BatchOptions(sweeps=("tube.radius=5,6",), formats=("step",), jobs=1),
    lines.append,
)
step = folder / "out" / "small_radius-5.step"
build = build_from_spec(load_spec(folder / "small.toml"))      # measure a file against its build
measured = readback_report(step, import_shape(step), build, step)
print(json.dumps({
    "exit_code": outcome.exit_code,
    "ok": outcome.ok,
    "lines": lines,
    "valid": measured["valid"],
    "faces": measured["faces"],
    "cli": sorted(m for m in sys.modules if m == "tubecad.cli" or m.startswith("tubecad.cli.")),
}))
"""


@pytest.mark.slow
def test_a_script_parses_a_spec_runs_a_batch_and_measures_a_file_without_the_cli(tmp_path):
    (tmp_path / "small.toml").write_text(SMALL.format(radius=5.0))
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT, str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout.strip().splitlines()[-1])
    assert result["cli"] == []  # "tubecad.cli" not in sys.modules
    assert result["exit_code"] == 0 and result["ok"] == 2
    assert result["lines"][0].startswith("building 2 jobs with 1 process into")
    assert result["lines"][-1].startswith("2 jobs: 2 ok, 0 failed")
    assert result["valid"] and result["faces"] == 2 * 2 + 2
    record = json.loads((tmp_path / "out" / "batch.json").read_text())
    assert [j["status"] for j in record["jobs"]] == ["ok", "ok"]


def test_a_batch_resumes_and_reports_a_bad_job_by_its_outcome(tmp_path):
    from tubecad.batch import BatchOptions, build_batch

    spec = tmp_path / "p.toml"
    spec.write_text(SMALL.format(radius=5.0))
    options = BatchOptions(sweeps=("tube.radius=5,-1",), jobs=1, quiet=True)
    lines: list[str] = []
    first = build_batch([spec], tmp_path / "out", options, lines.append)
    assert (first.ok, first.failed, first.exit_code) == (1, 1, 2)
    assert lines == [first.summary()]  # quiet: the summary only
    again = build_batch([spec], tmp_path / "out", options)
    assert again.skipped == 1 and again.failed == 1  # the good job resumed, the bad one tried again


def test_batch_input_errors_carry_their_key(tmp_path):
    from tubecad.batch import BatchOptions, build_batch

    spec = tmp_path / "p.toml"
    spec.write_text(SMALL.format(radius=5.0))
    with pytest.raises(ParameterError) as caught:
        build_batch([spec], tmp_path / "out", BatchOptions(remote_dir="/x"))
    assert caught.value.key == "remote_dir" and not (tmp_path / "out").exists()
    with pytest.raises(ParameterError, match="--sweep 'nope'"):
        build_batch([spec], tmp_path / "out", BatchOptions(sweeps=("nope",)))


def test_help_and_schema_load_no_numpy_through_the_package_names():
    code = (
        "import sys\nimport tubecad.spec, tubecad.batch\nfrom tubecad.spec.schema import schema_text\n"
        "schema_text()\nprint(sorted(m for m in ('numpy', 'OCP', 'build123d') if m in sys.modules))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_every_section_has_its_dataclass_with_the_spec_keys_as_fields():
    tables = {"tube": TUBE_KEYS, **EXTRA_SECTIONS}
    assert set(SECTION_TYPES) == set(tables)
    for name, keys in tables.items():
        assert {f.name for f in dataclasses.fields(SECTION_TYPES[name])} == set(keys), name
    assert {f.name for f in dataclasses.fields(SpecModel)} == {"axis", *tables, *ARRAY_SECTIONS}
    # [[branches]]: a table each, of BranchSection's fields
    assert {f.name for f in dataclasses.fields(BranchSection)} == set(ARRAY_SECTIONS["branches"])


def test_the_model_is_typed_and_defaults_the_absent_keys():
    spec = parse_spec(tomllib.loads((SAMPLES / "helix_stiffened.toml").read_text()), "helix_stiffened.toml")
    assert spec.model.axis.curve == "helix" and spec.model.tube.radius == 12.0
    assert spec.wall is not None and spec.wall.side == "inside"
    assert spec.stiffeners.rings == (1, 2, 3, 4, 5) and spec.stiffeners.stringers == "all"
    assert spec.stiffeners.table()["rings"] == [1, 2, 3, 4, 5]
    assert spec.panels is None and spec.mesh is None and spec.units.length == "mm"
    assert spec.sections["wall"]["thickness"] == spec.wall.thickness  # the checked tables, kept for scripts


def test_the_paper_is_the_sample_spec():
    from tubecad.spec.paper import paper_spec

    sample = parse_spec(tomllib.loads((SAMPLES / "paper_log_spiral.toml").read_text()))
    paper = paper_spec()
    assert paper.model == sample.model
    assert paper.tube.axis.describe() == sample.tube.axis.describe() and paper.tube.radius == 15.0


def test_stiffener_indices_are_checked_when_the_spec_is_read():
    """[stiffeners] indices outside the layout: refused by parse_spec, before anything is built
    (the build's selection and the mesh take the checked spec), naming the section and key."""
    data = tomllib.loads(SMALL.format(radius=5.0))
    data["wall"] = {"thickness": 0.5}
    data["stiffeners"] = {"rings": [7], "height": 1.0, "thickness": 0.5, "side": "inside"}
    with pytest.raises(SpecError) as parsed:
        parse_spec(data, "bad.toml")
    assert str(parsed.value) == "bad.toml: [stiffeners] rings must be indices in [0, 2], got [7]"
    assert parsed.value.key == "stiffeners.rings"


@pytest.mark.parametrize(
    "change, key",
    [
        (lambda d: d["tube"].update(radius=-1.0), "tube.radius"),
        (lambda d: d["layout"].update(rings=1), "layout.rings"),
        (lambda d: d.update(wall={"thickness": "thick"}), "wall.thickness"),
        (lambda d: d.update(fit={"tolerance": 2.0}), "fit.tolerance"),
        (lambda d: d.update(nope={}), "nope"),
        (lambda d: d["axis"].pop("curve"), "axis.curve"),
        (lambda d: d.update(stiffeners={"height": 1.0}), "stiffeners.thickness"),
    ],
)
def test_spec_errors_carry_the_key(change, key):
    data = tomllib.loads(SMALL.format(radius=5.0))
    change(data)
    with pytest.raises(SpecError) as caught:
        parse_spec(data, "bad.toml")
    assert caught.value.key == key, str(caught.value)
    assert str(caught.value).startswith("bad.toml: ")


def test_errors_take_an_optional_key():
    assert TubecadError("x").key is None and str(ParameterError("x")) == "x"
    error = ParameterError("tolerance must be in (0, 1)", key="tolerance")
    assert error.key == "tolerance" and error.args == ("tolerance must be in (0, 1)",)
    import pickle

    assert pickle.loads(pickle.dumps(SpecError("s", key="wall.thickness"))).key == "wall.thickness"


def test_a_script_built_model_is_checked_by_the_build():
    """A model made in a script (not by parse_spec) with a bad [fit] tolerance: the build
    names [fit] by the error's key, not by its message."""
    from tubecad.spec.build import build_from_spec
    from tubecad.spec.model import FitSection

    spec = parse_spec(tomllib.loads(SMALL.format(radius=5.0)), "small.toml")
    bad = dataclasses.replace(spec, model=dataclasses.replace(spec.model, fit=FitSection(tolerance=5.0)))
    with pytest.raises(SpecError) as caught:
        build_from_spec(bad)
    assert str(caught.value).startswith("small.toml: [fit] ") and caught.value.key == "fit.tolerance"


def test_stiffeners_section_select_names_the_profile():
    section = StiffenersSection(height=1.0, thickness=0.5, profile="T")  # a T needs its flange
    layout = SimpleNamespace(s_rings=[0.0, 1.0], stringers_deg=[0.0])
    with pytest.raises(SpecError) as caught:
        section.select(layout, "s.toml")
    assert str(caught.value).startswith("s.toml: [stiffeners] ") and caught.value.key.startswith("stiffeners")


def test_cli_holds_no_library_logic():
    """tubecad/cli defines click commands and their glue, nothing a script would need."""
    source = (ROOT / "tubecad" / "cli" / "app.py").read_text()
    for name in ("def build_batch", "def write_patterns", "def render_step_picture", "def export_summary"):
        assert name not in source
