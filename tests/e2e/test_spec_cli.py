"""Spec files and the command line: what users type, and what they get back."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import PAPER_SPEC, ROOT

from tubecad import SpecError
from tubecad.cli.app import cli
from tubecad.spec.parse import load_spec

SAMPLES = ROOT / "samples"
#: the tube samples ([axis] and [tube]; a face's net, [host], has no tube to report: test_cli_host_nets.py)
SAMPLE_SPECS = sorted(p for p in SAMPLES.glob("*.toml") if "[host]" not in p.read_text())

GOOD = PAPER_SPEC


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.mark.slow
def test_every_family_has_a_sample_spec():
    curves = {load_spec(p).axis.family for p in SAMPLE_SPECS}
    assert curves == {
        "log_spiral",
        "helix",
        "clothoid",
        "involute",
        "custom",
        "natural",
        "parametric",
        "points",
        "edge",
        "route",
    }


@pytest.mark.slow
@pytest.mark.parametrize("spec", SAMPLE_SPECS, ids=lambda p: p.stem)
def test_report_of_each_sample_measures_a_curvature_line_net(spec):
    result = run("report", spec, "--nu", 48, "--ns", 301)
    assert result.exit_code == 0, result.output
    report = json.loads(result.output)
    tube = load_spec(spec).tube
    assert report["length"] == pytest.approx(tube.length)
    assert report["grid"] == {"nu": 48, "ns": 301, "points": 48 * 301}
    if report.get("surface") == "canal":  # a radius law: area and volume two ways, the net to 1e-10
        assert report["area_relative_error"] < 1e-10 and report["volume_relative_error"] < 1e-10
        assert report["max_orthogonality_error"] < 1e-10 and report["max_M_error"] < 1e-10
        assert report["regular"] is True and 0 < report["regularity"]["max_fold"] < 1
        return
    assert report["area_exact"] == pytest.approx(2 * math.pi * tube.radius * tube.length)
    assert report["volume_exact"] == pytest.approx(
        math.pi * tube.radius**2 * tube.length, rel=1e-15
    )  # measured 0: the same closed form
    assert report["area_numeric"] == pytest.approx(report["area_exact"], rel=1e-12)
    assert report["max_orthogonality_error"] < 1e-13
    assert report["max_M_error"] < 1e-13
    assert 0 <= report["max_rho_k"] < 1 and report["regular"] is True  # 0: a straight main tube (lateral)
    assert report["grid"] == {"nu": 48, "ns": 301, "points": 48 * 301}
    assert report["parameters"]["tube"]["radius"] == tube.radius


@pytest.mark.slow
def test_paper_command_writes_report_and_pictures(paper_run):
    result = paper_run  # `tubecad paper -o ROOT/new/out --nu 64 --ns 501`, the suite's one paper run
    out = result.folder
    assert result.exit_code == 0, result.output
    report = json.loads((out / "report.json").read_text())
    assert report["parameters"]["axis"] == {"curve": "log_spiral", "a": 10.0, "beta_deg": 10.0, "s": [200.0, 1200.0]}
    assert report["parameters"]["tube"] == {"radius": 15.0}
    assert report["length"] == 1000.0
    assert report["max_rho_k"] == pytest.approx(0.75)
    assert 30 < report["closest_axis_return"] < 34
    assert report["max_orthogonality_error"] < 1e-13 and report["max_M_error"] < 1e-13
    png = (out / "projections.png").read_bytes()
    assert png.startswith(b"\x89PNG") and len(png) > 50_000
    svg = (out / "projections.svg").read_text(encoding="utf-8")
    # the shaded surface as an embedded image, the net's 11 + 8 lines as vector paths in both views
    assert "<svg" in svg and "<image" in svg and svg.count("<path") > 2 * (11 + 8)
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporary files left
    mask = os.umask(0)
    os.umask(mask)
    assert (out / "report.json").stat().st_mode & 0o777 == 0o666 & ~mask


@pytest.mark.slow
def test_paper_command_writes_webs_that_do_not_cross_themselves(paper_run):
    """issue 41: the paper's stringer webs are those at 0 and 180 deg (stringer_00, _04), whose
    flat outlines (read back from webs.dxf with ezdxf, judged by shapely) are simple, and the
    command warns of none (the webs at 90 and 270 deg cross themselves flat:
    tests/unit/shop/test_shop_webs.py)."""
    import ezdxf
    from shapely.geometry import Polygon

    outlines: dict[str, list] = {}
    for entity in ezdxf.readfile(paper_run.folder / "flat" / "webs.dxf").modelspace().query("LWPOLYLINE"):
        outlines.setdefault(entity.dxf.layer, []).extend((x, y) for x, y, *_ in entity.get_points())
    assert sorted(n for n in outlines if n.startswith("stringer_")) == ["stringer_00", "stringer_04"]
    assert all(Polygon(points).is_valid for points in outlines.values())
    assert "crosses itself" not in paper_run.output and "warning" not in paper_run.output, paper_run.output


def write(tmp_path, text, name="spec.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    "edit, says",
    [
        (lambda t: t.replace("a = 10.0", "a = -10.0"), "[axis] a must be in (0, inf), got -10"),
        (lambda t: t.replace("a = 10.0", "a = 'ten'"), "[axis] a must be a number"),
        (lambda t: t.replace("a = 10.0\n", ""), "[axis] a is missing"),
        (
            lambda t: t.replace("a = 10.0", "a = 10.0\nb = 3"),
            "unknown key [axis] b; allowed keys are curve, a, beta_deg, s",
        ),
        (lambda t: t.replace("log_spiral", "spiral"), "[axis] curve must be one of log_spiral | helix"),
        (lambda t: t.replace("beta_deg = 10.0", "beta_deg = 90"), "[axis] beta_deg must be in (-90, 90), got 90"),
        (lambda t: t.replace("beta_deg = 10.0", "beta_deg = nan"), "[axis] beta_deg must be finite"),
        (lambda t: t.replace("[200.0, 1200.0]", "[1200.0, 200.0]"), "[axis] s must be increasing"),
        (lambda t: t.replace("[200.0, 1200.0]", "[-1.0, 200.0]"), "[axis] s must lie in s > 0"),
        (lambda t: t.replace("[200.0, 1200.0]", "[200.0]"), "[axis] s must be a list of two numbers"),
        (lambda t: t.replace("radius = 15.0", "radius = 0"), "[tube] radius must be in (0, inf), got 0"),
        (lambda t: t.replace("radius = 15.0", "radius = true"), "[tube] radius must be a number"),
        (lambda t: t.replace("radius = 15.0", ""), "[tube] radius is missing"),
        (lambda t: t.replace("[tube]", "[tubes]"), "unknown section [tubes]"),
        (lambda t: t.replace("[200.0, 1200.0]", "[100.0, 1200.0]"), "rho*k reaches 1.5 at s = 100"),
        (lambda t: t + "\n[axis.extra]\nx = 1\n", "unknown key [axis] extra"),
        (lambda t: t.replace("[tube]", "tube = 3\n[tubex]"), "unknown section [tubex]"),
        (
            lambda t: t.replace('"log_spiral"', '"custom"').replace("a = 10.0", "k = \"__import__('os')\""),
            "function '__import__' is not allowed",
        ),
        (lambda t: t.replace('"log_spiral"', '"custom"').replace("a = 10.0", 'k = "s.real"'), "attribute access"),
        (lambda t: t.replace('"log_spiral"', '"custom"').replace("a = 10.0", 'k = "9**9**9"'), "nested powers"),
        (lambda t: t.replace("[axis]", "[axis"), "not valid TOML"),
        (lambda t: "x = [" * 5000, "not valid TOML"),
    ],
)
def test_bad_specs_exit_2_naming_the_key_without_traceback(tmp_path, edit, says):
    path = write(tmp_path, edit(GOOD))
    result = run("report", path)
    assert result.exit_code == 2, result.output
    assert says in result.output
    assert "Traceback" not in result.output
    with pytest.raises(SpecError):
        load_spec(path)


def test_irregular_spec_can_be_allowed(tmp_path):
    text = GOOD.replace("[200.0, 1200.0]", "[100.0, 1200.0]").replace(
        "radius = 15.0", "radius = 15.0\nallow_irregular = true"
    )
    report = json.loads(run("report", write(tmp_path, text), "--nu", 16, "--ns", 101).output)
    assert report["regular"] is False and report["max_rho_k"] == pytest.approx(1.5)


def test_missing_or_binary_spec_files(tmp_path):
    assert run("report", tmp_path / "nope.toml").exit_code == 2
    binary = tmp_path / "bin.toml"
    binary.write_bytes(b"\xff\xfe\x00garbage")
    result = run("report", binary)
    assert result.exit_code == 2 and "not UTF-8" in result.output


def test_unwritable_output_folder_is_a_clear_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    result = run("paper", "-o", blocker / "sub")
    assert result.exit_code == 2 and "cannot create output folder" in result.output


def test_console_script_is_installed_and_runs():
    """The `tubecad` entry point of a real install, in a subprocess."""
    exe = Path(sys.executable).parent / "tubecad"
    command = [str(exe)] if exe.exists() else [sys.executable, "-m", "tubecad.cli.app"]
    done = subprocess.run(
        command + ["report", str(SAMPLES / "helix.toml"), "--nu", "16", "--ns", "101"],
        capture_output=True,
        text=True,
        env={**os.environ, "MPLBACKEND": "Agg"},
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["parameters"]["axis"]["curve"] == "helix"


@pytest.mark.parametrize(
    "args", [["--help"], ["build", "--help"], ["paper", "--help"], ["report", "SAMPLE"], ["report", "STIFFENED"]]
)
def test_help_loads_no_occt(args):
    """`tubecad --help` and `tubecad report` start without OCCT, build123d or matplotlib (lazy
    imports): the report's spec check (sizes, layout, wall, stiffener heights) uses light modules."""
    import subprocess
    import sys

    samples = {"SAMPLE": str(SAMPLES / "helix.toml"), "STIFFENED": str(SAMPLES / "helix_stiffened.toml")}
    args = [samples.get(a, a) for a in args]
    code = (
        "import sys\nfrom tubecad.cli.app import cli\ntry:\n    cli.main(%r, standalone_mode=False)\n"
        "except SystemExit:\n    pass\nprint('LOADED', sorted(m for m in ('OCP', 'build123d', 'matplotlib') if m in sys.modules))"
        % (args,)
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-1] == "LOADED []"


def test_a_spec_mistake_is_refused_before_occt_and_numpy_load(tmp_path):
    """`build`, `shop`, `mesh` and `report` check the spec before the CAD kernel (and the
    maths) load: a misspelt key is refused with its one-line message and exit code 2, and
    neither OCCT, build123d nor numpy was imported for it (issue 23: under 1 s)."""
    import subprocess
    import sys

    bad = tmp_path / "bad.toml"
    bad.write_text((SAMPLES / "helix.toml").read_text().replace("radius =", "radiuss =", 1))
    code = (
        "import sys\nfrom tubecad.cli.app import cli\nfor args in %r:\n"
        "    try:\n        cli.main(args, standalone_mode=False)\n"
        "    except Exception as exc:\n        print('REFUSED', getattr(exc, 'exit_code', None), exc)\n"
        "print('LOADED', sorted(m for m in ('OCP', 'build123d', 'numpy') if m in sys.modules))"
        % (
            [
                ["build", str(bad), "-o", str(tmp_path / "x.step")],
                ["shop", str(bad), "-o", str(tmp_path / "shop")],
                ["mesh", str(bad), "-o", str(tmp_path / "x.inp")],
                ["report", str(bad)],
            ],
        )
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    lines = done.stdout.strip().splitlines()
    assert lines[-1] == "LOADED []", done.stdout + done.stderr
    refusals = [line for line in lines if line.startswith("REFUSED")]
    assert len(refusals) == 4 and all(
        r.startswith("REFUSED 2 ") and "unknown key [tube] radiuss" in r for r in refusals
    )
    assert not list(tmp_path.glob("x.*")) and not (tmp_path / "shop").exists()
