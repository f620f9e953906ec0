"""Robustness: every kind of bad input gets one clear line naming the key (spec files) or
the parameter (Python API) and what is allowed, exit code 2 and no traceback on the
command line, and no output file; Ctrl-C and SIGTERM end a run without partial files.

tests/e2e/test_spec_cli.py and tests/unit/surface/test_regularity.py hold the basic cases; these extend
them to ``build`` as well as ``report`` (nothing may be written), to non-finite values in
every numeric key, hostile TOML, unsafe expressions, unwritable outputs, unreachable
tolerances, densely coiled axes, the installed console script and interrupts.
"""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from tubecad import (
    CircleInvolute,
    Clothoid,
    CurvatureLineTube,
    CustomCurvature,
    ExpressionError,
    Helix,
    LogSpiral,
    ParameterError,
    RegularityError,
    TubecadError,
)
from tubecad.brep import NetLayout, tube_solid, wall_solid
from tubecad.cli.app import cli
from tubecad.fitting import FitError, fit_frame
from tubecad.spec.paper import paper_tube

CONSOLE = Path(sys.executable).parent / "tubecad"
ENV = {**os.environ, "MPLBACKEND": "Agg"}

#: the paper's tube with a small layout: what each case below edits
BASE = """\
[axis]
curve = "log_spiral"
a = 10.0
beta_deg = 10.0
s = [200.0, 1200.0]

[tube]
radius = 15.0

[layout]
rings = 3
stringers = 4
"""


def axis_spec(curve: str, params: str, s: str = "[200.0, 1200.0]", radius: str = "15.0", beta: str = "10.0") -> str:
    return f'[axis]\ncurve = "{curve}"\n{params}\nbeta_deg = {beta}\ns = {s}\n\n[tube]\nradius = {radius}\n'


def custom(expression: str, s: str = "[200.0, 1200.0]") -> str:
    return axis_spec("custom", f"k = {expression}", s, radius="5.0")


def helix_on(cylinder: float, pitch: float, s: str, radius: float) -> str:
    """The helix of Helix.from_radius_pitch(cylinder, pitch), as a spec."""
    beta = math.atan2(pitch, 2 * math.pi * cylinder)
    return axis_spec("helix", f"k = {math.cos(beta) ** 2 / cylinder!r}", s, repr(radius), repr(math.degrees(beta)))


def replace(old: str, new: str, text: str = BASE) -> str:
    assert old in text
    return text.replace(old, new)


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def temporaries(folder: Path) -> list[Path]:
    return [p for p in folder.rglob("*") if ".part" in p.name]


def assert_refused(result, says: tuple[str, ...]):
    """Exit code 2, one line, no traceback, naming what was asked for."""
    text = result.output
    assert result.exit_code == 2, text
    assert "Traceback" not in text and not (result.exception and not isinstance(result.exception, SystemExit))
    lines = [line for line in text.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("Error: "), text
    assert len(text) < 1200, f"message too long: {len(text)} characters"
    for part in says:
        assert part in text, f"{part!r} not in {text!r}"


def refuse_both_ways(tmp_path: Path, spec_text: str, says: tuple[str, ...], commands=("report", "build")):
    """``report SPEC`` and ``build SPEC -o OUT.step`` both refuse; nothing is written."""
    spec = tmp_path / "spec.toml"
    spec.write_text(spec_text)
    out = tmp_path / "out.step"
    for command in commands:
        start = time.perf_counter()
        result = run("report", spec, "--nu", 16, "--ns", 101) if command == "report" else run("build", spec, "-o", out)
        assert time.perf_counter() - start < 20.0, f"{command} took too long"
        assert_refused(result, says)
        assert sorted(p.name for p in tmp_path.iterdir()) == ["spec.toml"]  # no output, no temporary
    return result.output


# ---------------------------------------------------------------------------------------
# Spec files: the values
# ---------------------------------------------------------------------------------------

BAD_VALUES = {
    # rho k >= 1 somewhere: exactly at 1, beyond, and a clothoid that folds at its far end
    "rho_k_exactly_1": (
        replace("radius = 15.0", "radius = 20.0"),
        ("[tube] radius 20", "rho*k reaches 1 at s = 200", "must stay below 1", "allow_irregular"),
    ),
    "rho_k_above_1": (replace("radius = 15.0", "radius = 60.0"), ("[tube] radius 60", "rho*k reaches 3 at s = 200")),
    "clothoid_folds_at_end": (
        axis_spec("clothoid", "A = 100.0", "[-50.0, 1100.0]", "10.0"),
        ("[tube] radius 10", "rho*k reaches 1.1 at s = 1100", "for s in [1000, 1100]"),
    ),
    # the axis comes back closer than 2 rho
    "tight_helix": (
        helix_on(50.0, 20.0, "[0.0, 1000.0]", 15.0),
        ("[tube] radius 15", "comes back within", "2*rho = 30", "self-intersects"),
    ),
    "circle_run_round_1.5_times": (
        axis_spec("helix", "k = 0.05", "[0.0, 300.0]", "10.0", "0.0"),
        ("comes back within", "self-intersects"),
    ),
    # beta at and beyond +-90 deg
    "beta_-90": (replace("beta_deg = 10.0", "beta_deg = -90.0"), ("[axis] beta_deg must be in (-90, 90), got -90",)),
    "beta_above_90": (
        replace("beta_deg = 10.0", "beta_deg = 90.5"),
        ("[axis] beta_deg must be in (-90, 90), got 90.5",),
    ),
    "beta_far_below": (replace("beta_deg = 10.0", "beta_deg = -1e300"), ("[axis] beta_deg must be in (-90, 90)",)),
    # the span: empty, reversed, through s <= 0 where k is undefined, too short, too far
    "s_empty": (
        replace("[200.0, 1200.0]", "[700.0, 700.0]"),
        ("[axis] s must be increasing (start < end), got [700, 700]",),
    ),
    "s_reversed_involute": (
        axis_spec("involute", "a = 20.0", "[1200.0, 50.0]", "5.0"),
        ("[axis] s must be increasing",),
    ),
    "s_from_0_log_spiral": (replace("[200.0, 1200.0]", "[0.0, 1200.0]"), ("[axis] s must lie in s > 0", "got start 0")),
    "s_from_0_involute": (axis_spec("involute", "a = 20.0", "[0.0, 100.0]", "5.0"), ("[axis] s must lie in s > 0",)),
    "s_negative_involute": (
        axis_spec("involute", "a = 20.0", "[-10.0, 100.0]", "5.0"),
        ("[axis] s must lie in s > 0", "-10"),
    ),
    "s_too_short": (replace("[200.0, 1200.0]", "[1000.0, 1000.0000000001]"), ("[axis] s", "too short", "1e-09")),
    "s_too_far": (axis_spec("helix", "k = 0.0", "[0.0, 1e12]", "1.0"), ("[axis] s end must be at most 1e+09",)),
    "s_empty_array": (replace("[200.0, 1200.0]", "[]"), ("[axis] s must be a list of two numbers", "got an array []")),
    "s_three_numbers": (
        replace("[200.0, 1200.0]", "[200.0, 700.0, 1200.0]"),
        ("[axis] s must be a list of two numbers",),
    ),
    "s_with_a_boolean": (replace("[200.0, 1200.0]", "[200.0, true]"), ("[axis] s must be a list of two numbers",)),
    "s_a_string": (
        replace("[200.0, 1200.0]", '"200..1200"'),
        ("[axis] s must be a list of two numbers", "got a string"),
    ),
    # radius: negative, zero, too small or too large to build, wrong types
    "radius_negative": (replace("radius = 15.0", "radius = -0.5"), ("[tube] radius must be in (0, inf), got -0.5",)),
    "radius_minus_zero": (replace("radius = 15.0", "radius = -0.0"), ("[tube] radius must be in (0, inf)",)),
    "radius_too_small": (replace("radius = 15.0", "radius = 1e-300"), ("[tube] radius must be >= 1e-05",)),
    "radius_too_large": (replace("radius = 15.0", "radius = 1e200"), ("[tube] radius must be at most 1e+09",)),
    "radius_string": (
        replace("radius = 15.0", 'radius = "15 * t"'),
        ("[tube] radius: unknown name 't'", "allowed are s"),
    ),
    "radius_array": (replace("radius = 15.0", "radius = [15.0]"), ("[tube] radius must be a number", "got an array")),
    "radius_date": (replace("radius = 15.0", "radius = 1979-05-27"), ("[tube] radius must be a number",)),
    "beta_boolean": (
        replace("beta_deg = 10.0", "beta_deg = false"),
        ("[axis] beta_deg must be a number", "got a boolean"),
    ),
    "a_string": (replace("a = 10.0", 'a = "10"'), ("[axis] a must be a number",)),
    "allow_irregular_string": (
        replace("radius = 15.0", 'radius = 15.0\nallow_irregular = "yes"'),
        ("[tube] allow_irregular must be true or false",),
    ),
    # family parameters
    "helix_k_tiny": (axis_spec("helix", "k = 1e-300", "[0.0, 100.0]", "1.0"), ("[axis] k must be 0", "at least 1e-09")),
    "clothoid_A_huge": (axis_spec("clothoid", "A = 1e300", "[0.0, 100.0]", "1.0"), ("[axis] A must be at most 1e+09",)),
    "involute_a_zero": (
        axis_spec("involute", "a = 0.0", "[10.0, 100.0]", "1.0"),
        ("[axis] a must be in (0, inf), got 0",),
    ),
    "custom_origin_short": (
        custom('"0.001"').replace("beta_deg", "origin = [1.0, 2.0]\nbeta_deg"),
        ("[axis] origin must be a list of three numbers",),
    ),
    # unknown curve names
    "curve_capitalised": (
        replace('"log_spiral"', '"Log_Spiral"'),
        ("[axis] curve must be one of log_spiral | helix", "'Log_Spiral'"),
    ),
    "curve_empty": (replace('"log_spiral"', '""'), ("[axis] curve must be one of",)),
    "curve_number": (replace('"log_spiral"', "3"), ("[axis] curve must be one of", "got 3")),
    # layout, wall
    "rings_huge": (
        replace("rings = 3", "rings = 100000000"),
        ("[layout] rings must be a whole number >= 2 and <= 10000",),
    ),
    "stringers_huge": (
        replace("stringers = 4", "stringers = 100000000"),
        ("[layout] stringers must be a whole number >= 1 and <= 1000",),
    ),
    "too_many_faces": (
        replace("stringers = 4", "stringers = 1000").replace("rings = 3", "rings = 10000"),
        ("[layout]", "faces; at most 100000 are allowed"),
    ),
    "rings_string": (replace("rings = 3", 'rings = "3"'), ("[layout] rings must be a whole number",)),
    "wall_zero": (BASE + "\n[wall]\nthickness = 0.0\n", ("[wall] thickness must be in (0, inf), got 0",)),
    "wall_negative": (BASE + "\n[wall]\nthickness = -2.0\n", ("[wall] thickness must be in (0, inf), got -2",)),
    "wall_too_thin": (BASE + "\n[wall]\nthickness = 1e-9\n", ("[wall] thickness must be >= 1e-05",)),
    "wall_as_thick_as_diameter": (
        BASE + "\n[wall]\nthickness = 30.0\n",
        ("[wall] thickness must be < 30 for side = 'centered' (radius 15",),
    ),
    "wall_thicker_than_radius_inside": (
        BASE + '\n[wall]\nthickness = 15.5\nside = "inside"\n',
        ("[wall] thickness must be < 15 for side = 'inside'",),
    ),
    "wall_outside_makes_it_fold": (
        BASE + '\n[wall]\nthickness = 10.0\nside = "outside"\n',
        ("[wall] the wall's outer surface is not regular", "radius 25", "rho*k reaches 1.25"),
    ),
    "wall_side_number": (BASE + "\n[wall]\nthickness = 1.0\nside = 1\n", ("[wall] side must be a string",)),
    # fit tolerance too loose or meaningless
    "tolerance_one": (BASE + "\n[fit]\ntolerance = 1.0\n", ("[fit] fit tolerance must be in (0, 1)", "got 1.0")),
    "tolerance_huge": (BASE + "\n[fit]\ntolerance = 1e6\n", ("[fit] fit tolerance must be in (0, 1)",)),
    "tolerance_zero": (BASE + "\n[fit]\ntolerance = 0.0\n", ("[fit] fit tolerance must be in (0, 1)", "got 0.0")),
    "tolerance_negative": (BASE + "\n[fit]\ntolerance = -1e-8\n", ("[fit] fit tolerance must be in (0, 1)",)),
    "tolerance_string": (BASE + '\n[fit]\ntolerance = "1e-8"\n', ("[fit] tolerance must be a number",)),
}


@pytest.mark.parametrize("spec_text, says", list(BAD_VALUES.values()), ids=list(BAD_VALUES))
def test_bad_values_are_refused_by_report_and_build_writing_nothing(tmp_path, spec_text, says):
    refuse_both_ways(tmp_path, spec_text, says)


#: (section, key, spec with that key) for every numeric key a spec can hold
NUMERIC_KEYS = [
    ("axis", "a", BASE, "a = 10.0"),
    ("axis", "beta_deg", BASE, "beta_deg = 10.0"),
    ("axis", "s start", BASE, "s = [200.0, 1200.0]"),
    ("axis", "s end", BASE, "s = [200.0, 1200.0]"),
    ("axis", "k", axis_spec("helix", "k = 0.01", "[0.0, 500.0]"), "k = 0.01"),
    ("axis", "A", axis_spec("clothoid", "A = 400.0", "[0.0, 500.0]", "5.0"), "A = 400.0"),
    ("axis", "psi0_deg", custom('"0.001"').replace("beta_deg", "psi0_deg = 0.0\nbeta_deg"), "psi0_deg = 0.0"),
    (
        "axis",
        "origin[1]",
        custom('"0.001"').replace("beta_deg", "origin = [0.0, 0.0, 0.0]\nbeta_deg"),
        "origin = [0.0, 0.0, 0.0]",
    ),
    ("tube", "radius", BASE, "radius = 15.0"),
    ("layout", "s_rings", BASE.replace("rings = 3", "s_rings = [700.0]"), "s_rings = [700.0]"),
    (
        "layout",
        "u_stringers_deg",
        BASE.replace("stringers = 4", "u_stringers_deg = [0.0, 90.0]"),
        "u_stringers_deg = [0.0, 90.0]",
    ),
    ("wall", "thickness", BASE + "\n[wall]\nthickness = 2.0\n", "thickness = 2.0"),
    ("fit", "tolerance", BASE + "\n[fit]\ntolerance = 1e-6\n", "tolerance = 1e-6"),
    (
        "stiffeners",
        "height",
        BASE + "\n[wall]\nthickness = 2.0\n[stiffeners]\nrings = [1]\nheight = 6.0\nthickness = 1.0\n",
        "height = 6.0",
    ),
]


def with_value(text: str, line: str, key: str, value: str) -> str:
    name, _, old = line.partition(" = ")
    if key == "s start":
        new = f"{name} = [{value}, 1200.0]"
    elif key == "s end":
        new = f"{name} = [200.0, {value}]"
    elif key == "origin[1]":
        new = f"{name} = [0.0, {value}, 0.0]"
    elif old.startswith("["):
        new = f"{name} = [{value}]"
    else:
        new = f"{name} = {value}"
    return replace(line, new, text)


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
@pytest.mark.parametrize("section, key, text, line", NUMERIC_KEYS, ids=[f"{s}.{k}" for s, k, _, _ in NUMERIC_KEYS])
def test_nan_and_inf_in_any_numeric_key_name_the_key(tmp_path, section, key, text, line, value):
    output = refuse_both_ways(tmp_path, with_value(text, line, key, value), (f"[{section}] {key}",))
    assert "finite" in output


# ---------------------------------------------------------------------------------------
# Spec files: custom expressions
# ---------------------------------------------------------------------------------------

BAD_EXPRESSIONS = {
    "import": (
        "\"__import__('os').system('touch pwned')\"",
        ("[axis] k: function", "__import__", "is not allowed; use one of sin"),
    ),
    "import_only": ("\"__import__('os')\"", ("[axis] k: function '__import__' is not allowed",)),
    "dunder_attribute": ('"s.__class__.__bases__"', ("[axis] k: attribute access", "is not allowed")),
    "tuple_attribute": ('"().__class__"', ("[axis] k: attribute access (().__class__) is not allowed",)),
    "lambda_call": ('"(lambda: 1)()"', ("[axis] k: function", "is not allowed")),
    "lambda": ('"lambda s: s"', ("[axis] k: Lambda", "is not allowed in an expression")),
    "subscript": ('"s[0] * 0.001"', ("[axis] k: Subscript", "is not allowed")),
    "open_file": ("\"open('/etc/passwd')\"", ("[axis] k: function 'open' is not allowed",)),
    "huge_exponent": ('"s ** 10 ** 10"', ("[axis] k: nested powers (a ** b ** c) are not allowed",)),
    "tower": ('"9 ** 9 ** 9"', ("[axis] k: nested powers",)),
    "literal_exponent": ('"s ** 1e10"', ("[axis] k: exponent", "is out of range [-64, 64]")),
    "huge_integer": ('"' + "9" * 500 + '"', ("[axis] k: number 999", "out of range", "finite")),
    "huge_float": ('"1e999 * s"', ("[axis] k: number 1e999 is out of range",)),
    "very_long": (
        '"' + "+".join(["0.001"] * 300) + '"',
        ("[axis] k is 1799 characters long; at most 1000 are allowed",),
    ),
    "too_many_nodes": ('"' + "-" * 600 + '0.001"', ("[axis] k has", "syntax nodes; at most 400")),
    "empty": ('""', ("[axis] k = '' is not a valid expression",)),
    "number_not_string": ("0.001", ("[axis] k must be a string", "got a float")),
    # valid expressions that are not finite (or not smooth) somewhere in the span
    "log_of_negative": ('"log(s - 500)"', ("[axis] k(s) is not finite at s = 200", "got nan")),
    "pole_inside": (
        '"1 / (s - 300)"',
        ("[axis] k(s) could not be resolved", "must be smooth and finite", "near s = 300"),
    ),
    "pole_at_start": ('"1 / (s - 200)"', ("[axis] k(s) is not finite at s = 200", "got inf")),
    "sqrt_of_negative": ('"0.001 * sqrt(s - 1000)"', ("[axis] k(s) is not finite at s = 200",)),
    "overflow": ('"exp(s)"', ("[axis] k(s) is not finite at s = ",)),
}


@pytest.mark.parametrize("expression, says", list(BAD_EXPRESSIONS.values()), ids=list(BAD_EXPRESSIONS))
def test_unsafe_or_non_finite_expressions_are_refused(tmp_path, monkeypatch, expression, says):
    monkeypatch.chdir(tmp_path)
    refuse_both_ways(tmp_path, custom(expression), says)
    assert not (tmp_path / "pwned").exists()


# ---------------------------------------------------------------------------------------
# Spec files: malformed and hostile TOML
# ---------------------------------------------------------------------------------------

HOSTILE_TOML = {
    "unclosed_header": (replace("[tube]", "[tube"), ("not valid TOML", "line 7")),
    "unclosed_string": (replace('"log_spiral"', '"log_spiral'), ("not valid TOML",)),
    "two_dots": (replace("radius = 15.0", "radius = 15.0.0"), ("not valid TOML",)),
    "no_key": (replace("radius = 15.0", "= 15.0"), ("not valid TOML",)),
    "deep_inline_tables": (
        BASE + "deep = " + "{a = " * 3000 + "1" + "}" * 3000 + "\n",
        ("not valid TOML: nested too deeply",),
    ),
    "deep_arrays": (BASE + "[fit]\nx = " + "[" * 50000 + "]" * 50000 + "\n", ("not valid TOML: nested too deeply",)),
    "deep_table_headers": ("[" + ".".join(["a"] * 5000) + "]\nx = 1\n" + BASE, ("unknown section [a]",)),
    "duplicate_key": (replace("a = 10.0", "a = 10.0\na = 20.0"), ("not valid TOML: Cannot overwrite a value",)),
    "duplicate_table": (BASE + "\n[tube]\nradius = 3.0\n", ("not valid TOML", "twice")),
    "array_of_tables": (replace("[axis]", "[[axis]]"), ("[axis] must be a table", "got an array")),
    "huge_file": ("# " + "x" * 1_100_000 + "\n" + BASE, ("larger than 1000000 bytes",)),
    "huge_string_value": (
        replace('"log_spiral"', '"' + "x" * 900_000 + '"'),
        ("[axis] curve must be one of", "... (900002 characters)"),
    ),
    "huge_unknown_key": (
        replace("a = 10.0", "a = 10.0\n" + "k" * 500_000 + " = 1"),
        ("unknown key [axis] kkk", "characters)"),
    ),
    "empty_file": ("", ("missing section [axis]",)),
    "not_utf8": ("\udcff", ("not UTF-8",)),
}


@pytest.mark.parametrize("spec_text, says", list(HOSTILE_TOML.values()), ids=list(HOSTILE_TOML))
def test_malformed_and_hostile_toml_is_refused(tmp_path, spec_text, says):
    if spec_text == "\udcff":
        (tmp_path / "spec.toml").write_bytes(b"\xff\xfe[axis]\n")
        spec_text = None
    if spec_text is not None:
        (tmp_path / "spec.toml").write_text(spec_text)
    out = tmp_path / "out.step"
    for args in (("report", tmp_path / "spec.toml"), ("build", tmp_path / "spec.toml", "-o", out)):
        start = time.perf_counter()
        assert_refused(run(*args), says)
        assert time.perf_counter() - start < 20.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["spec.toml"]


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
def test_an_endless_spec_file_is_not_read_to_the_end():
    assert_refused(run("report", "/dev/zero"), ("/dev/zero: spec file is larger than 1000000 bytes",))


# ---------------------------------------------------------------------------------------
# Outputs that cannot be written
# ---------------------------------------------------------------------------------------


#: -o outputs and what their refusal says, each refused before anything is built (timed, with
#: every other hostile case here, by benchmarks/refusals.py)
BAD_OUTPUTS = {
    "missing_folder": (["missing/out.step"], ("output folder", "missing' does not exist")),
    "under_a_file": (["somefile.txt/out.step"], ("output folder", "somefile.txt' is not a folder")),
    "proc_subfolder": (["/proc/tubecad-test/out.step"], ("output '/proc/tubecad-test/out.step'",)),
    "proc": (["/proc/out.step"], ("output '/proc/out.step': cannot write to '/proc'",)),
    "unknown_extension": (
        ["out.obj"],
        ("unknown extension '.obj'; use one of .step, .stp, .iges, .igs, .brep, .stl, .3mf, .gltf, .glb, .csv, .json",),
    ),
    "no_extension": (["out"], ("output 'out': no extension; use one of .step",)),
    # nothing written, not even out.step
    "second_output_bad": (["out.step", "missing/out.iges"], ("missing' does not exist",)),
    "polylines_bad": (["out.step", "somefile.txt/lines.csv"], ("is not a folder",)),
    "report_bad": (["out.step", "--report", "somefile.txt/r.json"], ("r.json': output folder",)),
}


@pytest.mark.parametrize("outputs, says", list(BAD_OUTPUTS.values()), ids=list(BAD_OUTPUTS))
def test_unwritable_outputs_are_refused_before_building(tmp_path, monkeypatch, outputs, says):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.toml").write_text(BASE)
    (tmp_path / "somefile.txt").write_text("a regular file")
    args = []
    for item in outputs:
        args += [item] if item.startswith("--") or args[-1:] == ["--report"] else ["-o", item]
    start = time.perf_counter()
    assert_refused(run("build", "spec.toml", *args), says)
    assert time.perf_counter() - start < 10.0  # refused up front, nothing built
    assert sorted(p.name for p in tmp_path.iterdir()) == ["somefile.txt", "spec.toml"]
    assert (tmp_path / "somefile.txt").read_text() == "a regular file"


WALL = BASE + "\n[wall]\nthickness = 2.0\n"

#: a command, its spec and options, and what its refusal says: what the spec and the command
#: decide alone (indices against the layout, sections a command needs, its program, its
#: folder), each refused before OCCT loads (timed by benchmarks/refusals.py)
BAD_COMMANDS = {
    "stiffener_ring_index": (
        ["build", "spec.toml", "-o", "out.step"],
        WALL + "[stiffeners]\nrings = [7]\nheight = 6.0\nthickness = 1.0\n",
        ("[stiffeners] rings must be indices in [0, 2], got [7]",),
    ),
    "stiffener_stringer_index": (
        ["build", "spec.toml", "-o", "out.step"],
        WALL + "[stiffeners]\nstringers = [0, 4]\nheight = 6.0\nthickness = 1.0\n",
        ("[stiffeners] stringers must be indices in [0, 3], got [4]",),
    ),
    "panel_seam_index": (
        ["build", "spec.toml", "-o", "out.step"],
        WALL + "[panels]\nseams = [9]\n",
        ("[panels] seams must be one or more stringer indices in [0, 3], got [9]",),
    ),
    "panel_ring_index": (
        ["build", "spec.toml", "-o", "out.step"],
        WALL + "[panels]\nseams = [0]\nrings = [5]\n",
        ("[panels] rings must be ring indices in [0, 2], got [5]",),
    ),
    "analyse_without_analysis": (
        ["analyse", "spec.toml", "-o", "fe"],
        WALL,
        ("has no [analysis] section",),
    ),
    "analyse_without_wall": (
        ["analyse", "spec.toml", "-o", "fe"],
        BASE + "[analysis]\npressure = 0.1\n",
        ("an analysis needs the wall's thickness: add a [wall] section",),
    ),
    "shop_without_stiffeners": (
        ["shop", "spec.toml", "-o", "shop"],
        WALL,
        ("has neither [stiffeners] nor [panels]",),
    ),
    "shop_folder_under_a_file": (
        ["shop", "spec.toml", "-o", "somefile.txt/shop"],
        WALL + "[panels]\nseams = [0]\n",
        ("output folder 'somefile.txt/shop' cannot be made: 'somefile.txt' is a file",),
    ),
    "flat_without_stiffeners": (
        ["flat", "spec.toml", "-o", "flat"],
        WALL,
        ("has no [stiffeners] section",),
    ),
    "mesh_unknown_format": (
        ["mesh", "spec.toml", "-o", "model.obj"],
        WALL,
        ("a mesh is written as", "got '.obj'"),
    ),
}


@pytest.mark.parametrize("args, spec_text, says", list(BAD_COMMANDS.values()), ids=list(BAD_COMMANDS))
def test_what_a_spec_and_its_command_decide_is_refused_before_occt_loads(tmp_path, monkeypatch, args, spec_text, says):
    """Refused by the checks that run before the CAD kernel is imported (tubecad.spec.preflight,
    tubecad.spec.parse): a process that runs them imports neither OCP nor build123d."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.toml").write_text(spec_text)
    (tmp_path / "somefile.txt").write_text("a regular file")
    code = (
        "import sys\nfrom tubecad.cli.app import cli\n"
        f"try:\n    cli.main({args!r}, standalone_mode=True)\n"
        "finally:\n    print('OCCT loaded' if 'OCP' in sys.modules or 'build123d' in sys.modules else 'no OCCT', file=sys.stderr)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=ENV, timeout=120)
    assert done.returncode == 2, done.stderr
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert lines[-1] == "no OCCT" and len(lines) == 2 and lines[0].startswith("Error: "), done.stderr
    for part in says:
        assert part in lines[0], f"{part!r} not in {lines[0]!r}"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["somefile.txt", "spec.toml"]


def test_analyse_without_calculix_is_refused_before_occt_loads(tmp_path, monkeypatch):
    """The spec is fine; ccx is not on PATH (an empty folder is)."""
    (tmp_path / "spec.toml").write_text(WALL + "[analysis]\npressure = 0.1\n")
    (tmp_path / "bin").mkdir()
    code = (
        "import sys\nfrom tubecad.cli.app import cli\n"
        "try:\n    cli.main(['analyse', 'spec.toml', '-o', 'fe'], standalone_mode=True)\n"
        "finally:\n    print('OCCT loaded' if 'OCP' in sys.modules else 'no OCCT', file=sys.stderr)\n"
    )
    env = {**ENV, "PATH": str(tmp_path / "bin")}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120
    )
    assert done.returncode == 2, done.stderr
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert lines == [lines[0], "no OCCT"] and "CalculiX (ccx) is not installed" in lines[0], done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bin", "spec.toml"]


def test_output_that_is_a_folder_is_a_usage_error(tmp_path):
    (tmp_path / "spec.toml").write_text(BASE)
    result = run("build", tmp_path / "spec.toml", "-o", tmp_path)
    assert result.exit_code == 2 and "is a directory" in result.output and "Traceback" not in result.output


# ---------------------------------------------------------------------------------------
# Tolerances, sizes and coils that could make a run hang or exhaust memory
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("tolerance", ["1e-15", "1e-30"])
def test_tolerance_below_double_precision_is_refused_before_fitting(tmp_path, tolerance):
    """The paper's wall reaches at most 210 + 15 + 2 from the origin: 8 eps x 227 ~ 4e-13 is
    the floor (tubecad.core.tolerance.smallest_tolerance), so nothing is fitted."""
    spec = tmp_path / "spec.toml"
    spec.write_text(BASE + f"\n[wall]\nthickness = 2.0\n\n[fit]\ntolerance = {tolerance}\n")
    result = run("report", spec)
    assert_refused(result, (f"[fit] fit tolerance {tolerance}", "below what double precision can reach", "4e-13"))
    size = float(result.output.split("coordinates up to ")[1].split(":")[0])
    axis = paper_tube().axis
    exact = np.abs(axis.position(np.linspace(*axis.span, 20001))).max() + 15.0 + 2.0
    assert abs(size - exact) < 1e-3 * exact


def test_unreachable_tolerance_ends_quickly_saying_the_best_reached(tmp_path):
    """Above the floor but below what the fit reaches (2.4e-12 at best on the paper's tube)."""
    spec = tmp_path / "spec.toml"
    spec.write_text(BASE + "\n[wall]\nthickness = 2.0\n\n[fit]\ntolerance = 1e-12\n")
    start = time.perf_counter()
    result = run("build", spec, "-o", tmp_path / "out.step")
    assert time.perf_counter() - start < 20.0
    assert_refused(
        result,
        (
            "[fit] fit tolerance 1e-12",
            "not reached",
            "the best reached was",
            "stopped decreasing",
            "try a looser tolerance",
        ),
    )
    best = [float(x) for x in result.output.split("the best reached was ")[1].split(" (")[0].split(" / ")]
    assert 1e-12 < best[0] < 1e-8  # the fit went as far as double precision allows
    assert sorted(p.name for p in tmp_path.iterdir()) == ["spec.toml"]


def test_fit_says_whether_it_stalled_or_ran_out_of_spans():
    axis = paper_tube().axis
    start = time.perf_counter()
    with pytest.raises(FitError, match="stopped decreasing under refinement"):
        fit_frame(axis, 15.0, tolerance=1e-15, orthogonality=1e-15)
    assert time.perf_counter() - start < 20.0
    with pytest.raises(FitError, match="still decreasing: try a looser tolerance or split the span"):
        fit_frame(axis, 15.0, tolerance=1e-10, orthogonality=1e-10, max_spans=16)


@pytest.mark.slow
def test_densely_coiled_axis_is_refused_quickly_within_bounded_memory():
    """A circle run round 125 times: every axis sample is within 3 rho of every other
    (2e8 pairs at full sampling). Checked in a subprocess limited to 2 GB."""
    code = (
        "import resource; resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))\n"
        "from tubecad import CurvatureLineTube, Helix, RegularityError\n"
        "try:\n"
        "    CurvatureLineTube(Helix(0.08, 0.0, (0.0, 1e4)), 10.0)\n"
        "except RegularityError as exc:\n"
        "    print(exc)\n"
    )
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
        env={**ENV, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"},
    )
    assert time.perf_counter() - start < 30.0
    assert done.returncode == 0, done.stderr[-2000:]
    assert "comes back within" in done.stdout and "self-intersects" in done.stdout


def test_long_tight_coil_spec_is_refused_quickly(tmp_path):
    refuse_both_ways(
        tmp_path,
        helix_on(20.0, 5.0, "[0.0, 50000.0]", 10.0),
        ("[tube] radius 10", "comes back within", "self-intersects"),
        commands=("report",),
    )


# ---------------------------------------------------------------------------------------
# The Python API: ParameterError / RegularityError naming the parameter
# ---------------------------------------------------------------------------------------

TUBE = paper_tube()
API_CASES = {
    "log_spiral_a_bool": (
        lambda: LogSpiral(True, 10.0, (200, 1200)),
        ParameterError,
        "a must be a real number, got True",
    ),
    "log_spiral_span_through_0": (lambda: LogSpiral(10.0, 10.0, (0.0, 1200)), ParameterError, "span must lie in s > 0"),
    "log_spiral_beta_90": (lambda: LogSpiral(10.0, 90.0, (200, 1200)), ParameterError, "beta_deg must be in (-90, 90)"),
    "log_spiral_span_none": (lambda: LogSpiral(10.0, 10.0, None), ParameterError, "span must be a pair [start, end]"),
    "involute_span_negative": (
        lambda: CircleInvolute(20.0, 10.0, (-5.0, 100)),
        ParameterError,
        "span must lie in s > 0",
    ),
    "involute_a_huge": (lambda: CircleInvolute(1e300, 10.0, (5.0, 100)), ParameterError, "a must be at most 1e+09"),
    "helix_k_string": (lambda: Helix("0.01", 10.0, (0, 100)), ParameterError, "k must be a real number"),
    "helix_k_tiny": (
        lambda: Helix(1e-300, 10.0, (0, 100)),
        ParameterError,
        "k must be 0 (a straight axis) or at least 1e-09",
    ),
    "helix_radius_huge": (
        lambda: Helix.from_radius_pitch(1e12, 1.0, (0, 100)),
        ParameterError,
        "radius must be at most 1e+09",
    ),
    "helix_span_inf": (lambda: Helix(0.01, 10.0, (0, math.inf)), ParameterError, "span end must be finite"),
    "clothoid_A_inf": (lambda: Clothoid(math.inf, 10.0, (0, 100)), ParameterError, "A must be finite"),
    "clothoid_A_huge": (lambda: Clothoid(1e300, 10.0, (0, 100)), ParameterError, "A must be at most 1e+09"),
    "custom_k_none": (
        lambda: CustomCurvature(None, 10.0, (0, 100)),
        ParameterError,
        "k must be a callable k(s) or an expression",
    ),
    "custom_k_raises": (
        lambda: CustomCurvature(lambda s: 1 / 0, 10.0, (0, 100)),
        ParameterError,
        "k(s) raised ZeroDivisionError",
    ),
    "custom_k_wrong_shape": (
        lambda: CustomCurvature(lambda s: np.zeros(3), 10.0, (0, 100)),
        ParameterError,
        "k(s) must return an array shaped like s",
    ),
    "custom_k_complex": (
        lambda: CustomCurvature(lambda s: 0.001j * s, 10.0, (0, 100)),
        ParameterError,
        "k(s) must return real numbers",
    ),
    "custom_k_nan": (
        lambda: CustomCurvature(lambda s: np.sqrt(s - 50.0), 10.0, (0, 100)),
        ParameterError,
        "k(s) is not finite at s = 0",
    ),
    "custom_expression_huge_number": (
        lambda: CustomCurvature("9" * 400, 10.0, (0, 100)),
        ExpressionError,
        "k: number 999",
    ),
    "custom_origin_none": (
        lambda: CustomCurvature("0.001", 10.0, (0, 100), origin=None),
        ParameterError,
        "origin must be three coordinates [x, y, z], got None",
    ),
    "custom_origin_string": (
        lambda: CustomCurvature("0.001", 10.0, (0, 100), origin="xyz"),
        ParameterError,
        "origin must be three coordinates",
    ),
    "custom_turns_too_often": (
        lambda: CustomCurvature("0.01", 89.99, (0, 5000)),
        ParameterError,
        "turns 4.559e+04 times over the span",
    ),
    "tube_axis_none": (lambda: CurvatureLineTube(None, 15.0), ParameterError, "axis must be a tubecad Axis"),
    "tube_radius_nan": (lambda: CurvatureLineTube(TUBE.axis, math.nan), ParameterError, "radius must be finite"),
    "tube_radius_huge": (lambda: CurvatureLineTube(TUBE.axis, 1e200), ParameterError, "radius must be at most 1e+09"),
    "tube_allow_irregular_string": (
        lambda: CurvatureLineTube(TUBE.axis, 20.0, allow_irregular="no"),
        ParameterError,
        "allow_irregular must be True or False, got 'no'",
    ),
    "tube_rho_k_1": (lambda: CurvatureLineTube(TUBE.axis, 20.0), RegularityError, "rho*k reaches 1 at s = 200"),
    "tube_circle_twice": (
        lambda: CurvatureLineTube(Helix(0.05, 0.0, (0.0, 300.0)), 10.0),
        RegularityError,
        "self-intersects",
    ),
    "wall_tube_none": (
        lambda: wall_solid(None, 2.0),
        ParameterError,
        "tube must be a CurvatureLineTube or a CanalSurface, got NoneType",
    ),
    "wall_thickness_string": (lambda: wall_solid(TUBE, "2"), ParameterError, "thickness must be a real number"),
    "wall_thickness_zero": (lambda: wall_solid(TUBE, 0.0), ParameterError, "thickness must be in (0, inf), got 0"),
    "wall_thickness_tiny": (lambda: wall_solid(TUBE, 1e-9), ParameterError, "thickness must be >= 1e-05"),
    "wall_thicker_than_radius": (
        lambda: wall_solid(TUBE, 16.0, "inside"),
        ParameterError,
        "thickness must be < 15 for side = 'inside'",
    ),
    "wall_outside_folds": (
        lambda: wall_solid(TUBE, 10.0, "outside"),
        RegularityError,
        "thickness 10 (side = 'outside') gives a wall between radii 15 and 25",
    ),
    "wall_side_none": (
        lambda: wall_solid(TUBE, 2.0, None),
        ParameterError,
        "side must be one of centered, inside, outside",
    ),
    "wall_layout_string": (lambda: wall_solid(TUBE, 2.0, layout="11x8"), ParameterError, "layout must be a NetLayout"),
    "wall_layout_of_another_tube": (
        lambda: wall_solid(
            TUBE, 2.0, layout=NetLayout.equal(CurvatureLineTube(LogSpiral(10.0, 10.0, (300, 900)), 15.0))
        ),
        ParameterError,
        "layout rings must run from the tube's span start 200",
    ),
    "wall_tolerance_nan": (
        lambda: wall_solid(TUBE, 2.0, tolerance=math.nan),
        ParameterError,
        "fit tolerance must be in (0, 1) model units, got nan",
    ),
    "wall_tolerance_bool": (
        lambda: wall_solid(TUBE, 2.0, tolerance=True),
        ParameterError,
        "fit tolerance must be in (0, 1)",
    ),
    "tube_solid_radius_tiny": (
        lambda: tube_solid(CurvatureLineTube(Helix(0.01, 10.0, (0, 50)), 1e-300)),
        ParameterError,
        "radius must be >= 1e-05 model units for a B-rep",
    ),
    "layout_rings_huge": (
        lambda: NetLayout.equal(TUBE, 10**9, 4),
        ParameterError,
        "rings must be a whole number >= 2 and <= 10000",
    ),
    "layout_s_rings_strings": (
        lambda: NetLayout.explicit(TUBE, ["a"], [0.0]),
        ParameterError,
        "s_rings must be a non-empty list of finite arc lengths in [200, 1200]",
    ),
    "layout_angles_none": (
        lambda: NetLayout.explicit(TUBE, [500.0], None),
        ParameterError,
        "u_stringers_deg must be a non-empty list of finite angles",
    ),
}


@pytest.mark.parametrize("make, error, says", list(API_CASES.values()), ids=list(API_CASES))
def test_api_errors_name_the_parameter_and_range(make, error, says):
    start = time.perf_counter()
    with pytest.raises(error) as info:
        make()
    assert time.perf_counter() - start < 20.0
    assert isinstance(info.value, TubecadError)
    message = str(info.value)
    assert says in message and "\n" not in message and len(message) < 1000


# ---------------------------------------------------------------------------------------
# The installed console script, in subprocesses
# ---------------------------------------------------------------------------------------


def console(*args, cwd=None) -> subprocess.Popen:
    return subprocess.Popen(
        [str(CONSOLE), *map(str, args)], cwd=cwd, env=ENV, text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )


@pytest.mark.slow
@pytest.mark.skipif(not CONSOLE.exists(), reason="the tubecad console script is not installed")
def test_console_script_refuses_bad_input_with_one_line_and_exit_2(tmp_path):
    bad_radius = tmp_path / "radius.toml"
    bad_radius.write_text(replace("radius = 15.0", "radius = nan"))
    unsafe = tmp_path / "unsafe.toml"
    unsafe.write_text(custom("\"__import__('os')\""))
    good = tmp_path / "good.toml"
    good.write_text(BASE)
    runs = {  # started together: each pays the import of OCCT
        "report": (console("report", bad_radius, cwd=tmp_path), "[tube] radius must be finite"),
        "unsafe": (
            console("build", unsafe, "-o", "out.step", cwd=tmp_path),
            "[axis] k: function '__import__' is not allowed",
        ),
        "proc": (console("build", good, "-o", "/proc/out.step", cwd=tmp_path), "cannot write to '/proc'"),
    }
    for name, (process, says) in runs.items():
        out, err = process.communicate(timeout=180)
        assert process.returncode == 2, (name, err)
        assert out == "" and "Traceback" not in err
        assert err.strip().startswith("Error: ") and len(err.strip().splitlines()) == 1 and says in err, (name, err)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["good.toml", "radius.toml", "unsafe.toml"]


# ---------------------------------------------------------------------------------------
# Interrupts: Ctrl-C and SIGTERM leave no partial files and no traceback
# ---------------------------------------------------------------------------------------


def wait_for(process: subprocess.Popen, ready, timeout: float = 180.0) -> bool:
    """Poll until ``ready()`` (True) or the process ends (False)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if process.poll() is not None:
            return False
        if ready():
            return True
        time.sleep(0.002)
    process.kill()
    pytest.fail("timed out waiting for the process")


def assert_interrupted(process: subprocess.Popen):
    out, err = process.communicate(timeout=120)
    assert process.returncode == 130, (process.returncode, err[-3000:])
    assert "Traceback" not in err and "Error" not in err, err[-3000:]
    # the last line says so; before it only progress lines (a build shows them after 2 s)
    lines = [line for line in err.splitlines() if line.strip()]
    assert lines[-1] == "interrupted" and all(line.startswith("tubecad: ") for line in lines[:-1]), err[-3000:]
    return out


@pytest.mark.slow
@pytest.mark.skipif(not CONSOLE.exists() or sys.platform != "linux", reason="needs the console script and Linux")
def test_ctrl_c_while_writing_leaves_no_partial_file(tmp_path):
    """SIGINT as soon as a temporary output file exists, i.e. while OCCT writes it."""
    from tubecad.brep import properties as props
    from tubecad.export.cad import import_shape

    spec = tmp_path / "spec.toml"
    spec.write_text(
        replace("rings = 3", "rings = 21").replace("stringers = 4", "stringers = 8") + "\n[wall]\nthickness = 2.0\n"
    )
    targets = [tmp_path / name for name in ("a.step", "b.iges", "c.brep", "d.step")]
    process = console("build", spec, *[x for t in targets for x in ("-o", t)])
    seen = []

    def writing() -> bool:  # a temporary that lasts (the up-front write check's one lasts microseconds)
        parts = temporaries(tmp_path)
        if parts and seen and set(parts) & set(seen):
            return True
        seen[:] = parts
        return False

    assert wait_for(process, writing), "the build ended before any output was being written"
    process.send_signal(signal.SIGINT)
    assert_interrupted(process)
    assert temporaries(tmp_path) == []
    for target in targets:  # absent, or complete and valid
        if target.exists():
            shape = import_shape(target)
            assert props.is_valid(shape) and props.count(shape, "face") == 2 * 20 * 8 + 2
    assert any(not t.exists() for t in targets)  # the run really was cut short


@pytest.mark.slow
@pytest.mark.skipif(not CONSOLE.exists() or sys.platform != "linux", reason="needs the console script and Linux")
def test_sigterm_during_paper_leaves_only_complete_files(tmp_path):
    from tubecad.brep import properties as props
    from tubecad.export.cad import import_shape

    out = tmp_path / "paper"
    process = console("paper", "-o", out, "--nu", 32, "--ns", 201)
    assert wait_for(process, lambda: (out / "paper.step").exists()), "paper ended before paper.step was written"
    process.send_signal(signal.SIGTERM)
    assert_interrupted(process)
    assert temporaries(out) == []
    assert not (out / "report.json").exists()  # written last: the run was cut short
    shape = import_shape(out / "paper.step")
    assert props.is_valid(shape) and props.count(shape, "face") == 162


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/maps").exists() or not CONSOLE.exists(), reason="needs Linux /proc")
def test_ctrl_c_while_the_cad_libraries_load_is_clean(tmp_path):
    """An interrupt during the seconds the OCCT import takes: no traceback either."""
    (tmp_path / "spec.toml").write_text(BASE)
    process = console("build", tmp_path / "spec.toml", "-o", tmp_path / "out.step")

    def loading_occt() -> bool:
        try:
            return "/OCP/" in Path(f"/proc/{process.pid}/maps").read_text()
        except OSError:
            return False

    assert wait_for(process, loading_occt)
    process.send_signal(signal.SIGINT)
    assert_interrupted(process)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["spec.toml"]
