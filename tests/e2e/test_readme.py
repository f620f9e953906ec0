"""Every code block of README.md and of every page of the documentation site (docs/*.md)
runs (or is checked) here, so a snippet cannot silently break.

The blocks are read from the pages when the tests are collected, so an edit is picked up by
the next run. One test per block, named by its page, index, language and first line
(``-k python``, ``-k fem`` or ``-k README-05`` picks blocks):

- ```python blocks run each on its own, as a user pastes one: in a fresh namespace and an
  empty working directory, with README_ENVIRONMENT (MPLBACKEND=Agg, and OCP_VSCODE_PYTEST=1
  so that tubecad.show needs no viewer). Tracebacks point at the page's own lines. A block
  that imports CadQuery is skipped where the extra is not installed (CI runs it in the
  CadQuery environment). Files a snippet names (``"wall.step"``) must exist afterwards and read back;
  ``# ~3e-16`` and ``# (64, 1001, 3)`` comments are checked against the value printed or
  assigned on that line; other comments that state something are checked by CLAIMS below, and
  a comment stating a number that no rule checks fails the test.
- ```toml blocks are checked by the project's spec loader, their commented-out alternatives
  and ``a | b | c`` choices too; a complete spec is run through ``tubecad report`` and
  ``tubecad build -o x.step``.
- ```bash blocks: the quick start (between the ci:quickstart markers) is what .ci/run runs;
  the test checks that .ci/run extracts exactly these lines. Every command line shown in the
  README (fenced, indented or inline) must name a subcommand, options and choices that
  ``tubecad SUB --help`` lists; python/pip lines name files, modules and extras that exist.
- Indented blocks: command lines as above, directory listings must name existing folders.
- Anything else fails unless NOT_RUNNABLE lists it, with the reason.
"""

from __future__ import annotations

import ast
import builtins
import contextlib
import csv
import io
import json
import math
import os
import re
import shlex
import subprocess
import sys
import tokenize
import tomllib
import traceback
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from conftest import ROOT, requires

README = ROOT / "README.md"
DOCS = ROOT / "docs"
#: every page whose blocks run: the README, then the site's pages
PAGES = [README, *sorted(DOCS.glob("*.md"))]
#: pages whose indented blocks are equations, not code (tests/unit/surface/test_symbolic.py proves them)
EQUATION_PAGES = {ROOT / "docs/MATH.md"}
CI_RUN = ROOT / ".ci" / "run"
PACKAGE = ROOT / "tubecad"
QUICKSTART_BEGIN, QUICKSTART_END = "<!-- ci:quickstart:begin -->", "<!-- ci:quickstart:end -->"

#: blocks that are not code, keyed by their first line, with the reason
NOT_RUNNABLE = {
    "S(u, s) = c(s) + rho (cos u r1(s) + sin u r2(s))": "an equation, not code: tests/unit/surface/test_symbolic.py proves its forms with sympy",
    "c(s) = (cos b Int cos psi ds, cos b Int sin psi ds, s sin b)": "equations, not code: tests/unit/surface/test_symbolic.py proves them with sympy",
}

#: a python block whose code names one of these needs that external program: where it is
#: missing the block's test is skipped with a one-line reason (a failure in CI), by the
#: ``requires`` of tests/conftest.py, so that the quick start passes on a fresh machine
NEEDS_PROGRAM = {
    "tubecad.fem.analysis": "ccx",
    "tubecad.fem.calculix": "ccx",
    "import gmsh": "gmsh",
    "tubecad.fem.junction": "gmsh",
    ".shell_model(": "gmsh",
}


# ---------------------------------------------------------------------------------------------
# the blocks


@dataclass(frozen=True)
class Block:
    index: int  # 1-based, in page order
    lang: str  # the fence's language ("" if none), or "indented"
    line: int  # the page's line number of the block's first line of code
    text: str
    page: Path = README

    @property
    def first_line(self) -> str:
        return next((ln.strip() for ln in self.text.splitlines() if ln.strip()), "")

    @property
    def id(self) -> str:
        slug = re.sub(r"\W+", "_", self.first_line).strip("_")[:40]
        # CI's CadQuery environment selects these blocks by `-k cadquery`, whatever their first line
        extra = "-cadquery" if self.needs_cadquery and "cadquery" not in slug else ""
        return f"{self.page.stem}-{self.index:02d}-{self.lang or 'plain'}-{slug}{extra}"

    @property
    def needs_cadquery(self) -> bool:
        return self.lang == "python" and re.search(r"^import cadquery|^from cadquery", self.text, re.M) is not None

    @property
    def name(self) -> str:
        return str(self.page.relative_to(ROOT))

    def where(self) -> str:
        return (
            f"{self.name} block {self.index} ({self.lang or 'no language'}, line {self.line}: {self.first_line[:60]!r})"
        )


def readme_blocks(text: str, page: Path = README) -> list[Block]:
    """Fenced blocks (``` or ~~~) and indented (4 spaces, after a blank line) blocks, in order."""
    lines = text.splitlines()
    found: list[tuple[str, int, str]] = []
    i = 0
    while i < len(lines):
        fence = re.match(r"^(`{3,}|~{3,})\s*([\w+-]*)", lines[i])
        if fence:
            mark, lang = fence.group(1), fence.group(2)
            start = i + 1
            i += 1
            while i < len(lines) and not lines[i].startswith(mark):
                i += 1
            assert i < len(lines), f"{page.name} line {start}: the fence {mark}{lang} is never closed"
            found.append((lang, start + 1, "\n".join(lines[start:i]) + "\n"))
            i += 1
            continue
        if lines[i].startswith("    ") and lines[i].strip() and (i == 0 or not lines[i - 1].strip()):
            start = i
            while i < len(lines) and (lines[i].startswith("    ") or not lines[i].strip()):
                i += 1
            body = [ln[4:] for ln in lines[start:i]]
            while body and not body[-1].strip():
                body.pop()
            found.append(("indented", start + 1, "\n".join(body) + "\n"))
            continue
        i += 1
    return [Block(n, lang, line, body, page) for n, (lang, line, body) in enumerate(found, start=1)]


BLOCKS = [b for page in PAGES for b in readme_blocks(page.read_text(encoding="utf-8"), page)]
README_BLOCKS = [b for b in BLOCKS if b.page == README]
PYTHON_BLOCKS = [b for b in BLOCKS if b.lang == "python"]


def quickstart_lines() -> tuple[int, int]:
    """README line numbers of the quick-start markers."""
    lines = README.read_text(encoding="utf-8").splitlines()
    begin = [n for n, ln in enumerate(lines, 1) if ln.strip() == QUICKSTART_BEGIN]
    end = [n for n, ln in enumerate(lines, 1) if ln.strip() == QUICKSTART_END]
    assert len(begin) == 1 and len(end) == 1 and begin[0] < end[0], (
        f"README.md must hold one {QUICKSTART_BEGIN} ... {QUICKSTART_END} pair, in that order"
    )
    return begin[0], end[0]


#: set while a snippet runs: no plot windows; tubecad.show records what it would send to
#: OCP CAD Viewer instead of needing a running one (tests/unit/integrations/test_viewer.py runs a real viewer)
README_ENVIRONMENT = {"MPLBACKEND": "Agg", "OCP_VSCODE_PYTEST": "1"}


@contextlib.contextmanager
def readme_environment(workdir: Path):
    """chdir into ``workdir`` with README_ENVIRONMENT set, restoring all afterwards."""
    old_cwd, old_env = os.getcwd(), {name: os.environ.get(name) for name in README_ENVIRONMENT}
    os.environ.update(README_ENVIRONMENT)
    os.chdir(workdir)
    try:
        yield
    finally:
        os.chdir(old_cwd)
        for name, value in old_env.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value


# ---------------------------------------------------------------------------------------------
# python blocks: each on its own


@dataclass
class PythonRun:
    block: Block
    tree: ast.Module
    ns: dict[str, Any] = field(default_factory=dict)
    prints: dict[int, list[tuple]] = field(default_factory=dict)  # page line -> args of each print there
    warnings: list[warnings.WarningMessage] = field(default_factory=list)
    error: BaseException | None = None
    traceback: str = ""


def run_python_block(block: Block, workdir: Path) -> PythonRun:
    """Run ``block`` as a user who pastes it alone: a fresh namespace, ``workdir`` (empty) as
    the working directory; what it prints is recorded by line, its errors and warnings kept."""
    tree = ast.parse(block.text, filename=str(block.page))
    ast.increment_lineno(tree, block.line - 1)  # tracebacks name the page's own lines
    result = PythonRun(block, tree)

    def record_print(*args, **kwargs) -> None:
        frame = sys._getframe(1)
        if frame.f_code.co_filename == str(block.page):
            result.prints.setdefault(frame.f_lineno, []).append(args)
        builtins.print(*args, **kwargs)

    result.ns = {"__name__": "__main__", "print": record_print}
    with readme_environment(workdir), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            exec(compile(tree, str(block.page), "exec"), result.ns)
        except Exception as exc:  # reported by the block's test
            result.error = exc  # the traceback from the page's line on (this file's frame left out)
            result.traceback = "".join(traceback.format_exception(type(exc), exc, exc.__traceback__.tb_next))
    result.warnings = [w for w in caught if _ours(w.filename)]
    return result


def _ours(filename: str) -> bool:
    """A warning raised by the snippet itself or by tubecad's code (not a third-party library's)."""
    return filename in {str(page) for page in PAGES} or Path(filename).resolve().is_relative_to(PACKAGE)


# what the python comments state ----------------------------------------------------------------

NUMBER = r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
APPROX = re.compile(rf"~\s*({NUMBER})")
SHAPE = re.compile(r"^\(\s*(\d+(?:\s*,\s*\d+)+)\s*,?\s*\)")
STATES_A_NUMBER = re.compile(r"~\s*\d|\d(?:\.\d+)?[eE][-+]?\d|\(\s*\d+\s*,\s*\d+")
FILE_NAME = re.compile(r"^[\w.-]+\.(step|stp|iges|igs|brep|csv|json|dxf|svg|png)$", re.IGNORECASE)


def _statement_at(tree: ast.Module, line: int) -> ast.stmt | None:
    return next((s for s in tree.body if s.lineno <= line <= (s.end_lineno or s.lineno)), None)


def _comments(block: Block) -> list[tuple[int, str]]:
    """(page line, comment text) of every comment in the block."""
    tokens = tokenize.generate_tokens(io.StringIO(block.text).readline)
    return [(block.line - 1 + t.start[0], t.string.lstrip("#").strip()) for t in tokens if t.type == tokenize.COMMENT]


def _subject(run: PythonRun, ns: dict[str, Any], line: int) -> tuple[bool, Any]:
    """The value a comment on ``line`` talks about: what the print there printed (first
    argument), or what the assignment there bound. (False, None) if neither."""
    stmt = _statement_at(run.tree, line)
    if (
        isinstance(stmt, ast.Expr)
        and isinstance(stmt.value, ast.Call)
        and isinstance(stmt.value.func, ast.Name)
        and stmt.value.func.id == "print"
    ):
        printed = run.prints.get(stmt.lineno)
        assert printed, f"line {line}: the print there printed nothing"
        return True, printed[-1][0]
    if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
        return True, ns[stmt.targets[0].id]
    return False, None


def check_comment(run: PythonRun, ns: dict[str, Any], line: int, comment: str) -> bool:
    """Check the ``~NUMBER`` and ``(a, b, c)`` statements of a comment; True if there was one."""
    approx, shape = APPROX.search(comment), SHAPE.match(comment)
    if not (approx or shape):
        return False
    found, value = _subject(run, ns, line)
    assert found, (
        f"{run.block.name} line {line}: the comment {comment!r} states a value, but the line neither prints "
        f"nor assigns one name; add a rule for it to CLAIMS in tests/e2e/test_readme.py"
    )
    if approx:
        stated, actual = float(approx.group(1)), abs(float(np.max(value)))
        assert stated != 0 and actual != 0 and abs(math.log10(actual / abs(stated))) <= 1, (
            f"{run.block.name} line {line}: the comment says ~{approx.group(1)}, the snippet gives {actual:.3g}"
        )
    if shape:
        stated_shape = tuple(int(n) for n in shape.group(1).split(","))
        assert np.shape(value) == stated_shape, (
            f"{run.block.name} line {line}: the comment says shape {stated_shape}, the snippet gives {np.shape(value)}"
        )
    return True


# comments checked by hand: (text on the code line, what it states, the check) -------------------


def _refuses_irregular(ns, workdir):
    from tubecad.core.errors import RegularityError

    with pytest.raises(RegularityError, match=r"s = \d"):  # the message says where
        ns["CurvatureLineTube"](ns["axis"], radius=25.0)


def _forms_arrays(ns, workdir):
    forms, grid = ns["forms"], (len(ns["u"]), len(ns["s"]))
    for name in "EFGLMN":
        assert np.shape(getattr(forms, name)) == grid, f"forms.{name}"


def _axis_frame(ns, workdir):
    frame = ns["frame"]
    for name in ("position", "t", "n", "bn"):
        assert np.shape(getattr(frame, name)) == (len(ns["s"]), 3), f"frame.{name}"
    for name in ("psi", "k", "torsion"):
        assert np.shape(getattr(frame, name)) == (len(ns["s"]),), f"frame.{name}"


def _custom_any_k(ns, workdir):
    """The numeric axis of k = 10/s is the log spiral up to a rigid motion (README: ~1e-12 over L = 1000)."""
    s = ns["s"]
    exact, numeric = ns["axis"].evaluate(s), ns["numeric"].evaluate(s)
    chord = lambda f: np.linalg.norm(f.position - f.position[0], axis=1)
    assert np.abs(chord(numeric) - chord(exact)).max() < 1e-10
    assert np.ptp(numeric.psi - exact.psi) < 1e-10 and np.abs(numeric.k - exact.k).max() < 1e-12


def _layout_explicit(ns, workdir):
    layout = ns["NetLayout"].explicit(ns["tube"], [300.0, 650.0], [0.0, 90.0])
    assert list(layout.stringers_deg) == [0.0, 90.0]
    rings = list(layout.s_rings)
    assert rings[0] == ns["tube"].span[0] and rings[-1] == ns["tube"].span[1] and len(rings) == 4


def _is_build123d_solid(ns, workdir):
    import build123d as bd

    assert isinstance(ns["wall"], bd.Solid) and ns["wall"].is_valid


def _export_formats(ns, workdir):
    from tubecad.brep import properties as props
    from tubecad.export.cad import import_shape
    from tubecad.export.registry import cad_format, export_shape

    assert {cad_format(f"x{ext}") for ext in (".step", ".stp")} == {"step"}
    assert {cad_format(f"x{ext}") for ext in (".iges", ".igs")} == {"iges"} and cad_format("x.brep") == "brep"
    assert "AUTOMOTIVE_DESIGN" in (workdir / "wall.step").read_text(errors="replace")[:5000]  # AP214, the default
    wall = import_shape(workdir / "wall.step")
    assert props.count(wall, "face") == props.count(ns["wall"], "face")
    assert props.volume(wall) == pytest.approx(props.volume(ns["wall"]), rel=1e-9)
    ap242 = export_shape(ns["wall"], workdir / "wall_ap242.stp", step_schema="AP242")
    assert "AP242" in ap242.read_text(errors="replace")[:5000]


def _build_parts(ns, workdir):
    build, layout = ns["build"], ns["layout"]
    assert build.layout is layout and len(build.surfaces) == 2


def _wires_and_faces(ns, workdir):
    import build123d as bd

    build = ns["build"]
    assert all(isinstance(w, bd.Wire) for w in build.ring_wires(0) + build.stringer_wires(1))
    assert all(isinstance(f, bd.Face) for row in build.face_grid(0) for f in row)


def _inner_lines(ns, workdir):
    lines, layout = ns["lines"], ns["build"].layout
    assert sorted(line.kind for line in lines) == sorted(
        ["ring"] * len(layout.s_rings) + ["stringer"] * len(layout.stringers_deg)
    )
    assert {line.radius for line in lines} == {ns["build"].radii[1]} == {ns["tube"].radius - 1.0}  # the inner wall


def _csv_points(ns, workdir):
    with open(workdir / "lines.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    vec = lambda names: np.array([[float(r[n]) for n in names] for r in rows])
    position, tangent, normal = vec("xyz"), vec(["tx", "ty", "tz"]), vec(["nx", "ny", "nz"])
    assert np.isfinite(position).all() and len(rows) > 100
    assert np.abs(np.linalg.norm(tangent, axis=1) - 1).max() < 1e-9
    assert np.abs(np.linalg.norm(normal, axis=1) - 1).max() < 1e-9
    assert np.abs(np.einsum("ij,ij->i", tangent, normal)).max() < 1e-9
    assert {r["line"] for r in rows} == {line.name for line in ns["lines"]}


def _stiffeners(ns, workdir):
    stiffeners = ns["stiffeners"]
    assert [st.name for st in stiffeners] == ["ring_01", "ring_02", "stringer_00", "stringer_04"]
    assert all(st.solid.is_valid for st in stiffeners)


def _panels(ns, workdir):
    from tubecad.brep import properties as props

    panels, wall = ns["panels"], ns["build"].shape
    assert [p.name for p in panels[:2]] == ["panel_r0_s0", "panel_r0_s1"]
    assert len(panels) == 2 * (len(ns["build"].layout.s_rings) - 1)
    assert sum(props.volume(p.solid) for p in panels) == pytest.approx(props.volume(wall), rel=1e-9)


def _named_assembly(ns, workdir):
    import build123d as bd

    top = bd.import_step(workdir / "assembly.step")
    names = [c.label for c in top.children]
    assert names[:5] == ["wall", "ring_01", "ring_02", "stringer_00", "stringer_04"], names
    wall = top.children[0]
    assert [c.label for c in wall.children] == [p.name for p in ns["panels"]]


CLAIMS: list[tuple[str, str, Callable[[dict, Path], None]]] = [
    ("CurvatureLineTube(axis, radius=15.0)", "refuses irregular tubes, saying where", _refuses_irregular),
    ("tube.fundamental_forms(", "E, F, G, L, M, N arrays", _forms_arrays),
    ("axis.evaluate(s)", "position, t, n, bn, psi, k, torsion", _axis_frame),
    ("CustomCurvature(lambda s: 10.0 / s", "any k(s) (here the log spiral's)", _custom_any_k),
    ("NetLayout.equal(tube", "or NetLayout.explicit(tube, s_rings, angles_deg)", _layout_explicit),
    ("wall = wall_solid(", "a build123d Solid", _is_build123d_solid),
    ('export_shape(wall, "wall.step")', ".step/.stp (AP214 or AP242), .iges/.igs, .brep", _export_formats),
    ("build = build_wall_solid(tube, 2.0, layout=layout)", "the solid and what it was built from", _build_parts),
    ("build.ring_wires(0)", "build123d Wires and Faces", _wires_and_faces),
    ("lines = net_lines(build.surfaces[1]", "rings and stringers on the inner wall", _inner_lines),
    ('polylines_csv(lines, "lines.csv")', "per point: position, unit tangent, unit normal", _csv_points),
    ("stiffeners = build_stiffeners(", "the named stiffeners, valid", _stiffeners),
    ("panels = split_into_panels(", "panel_r0_s0, panel_r0_s1, ...; volumes add up to the wall", _panels),
    ("export_named_step(named_assembly(", "names read back", _named_assembly),
]


def _read_back(path: Path) -> None:
    """A file a snippet wrote: present, and readable as what its extension says."""
    assert path.is_file() and path.stat().st_size > 0, f"the snippet should have written {path.name}"
    ext = path.suffix.lower()
    if ext in (".step", ".stp", ".iges", ".igs", ".brep"):
        from tubecad.brep import properties as props
        from tubecad.export.cad import import_shape

        shape = import_shape(path)
        assert props.is_valid(shape) and props.count(shape, "solid") >= 1, f"{path.name} does not read back valid"
    elif ext == ".csv":
        with open(path, newline="") as file:
            rows = list(csv.reader(file))
        assert len(rows) >= 2 and all(len(r) == len(rows[0]) for r in rows), f"{path.name} is not a table"
    elif ext == ".json":
        json.loads(path.read_text())
    elif ext == ".dxf":
        import ezdxf

        assert len(ezdxf.readfile(path).modelspace()) > 0
    elif ext == ".png":
        assert path.read_bytes().startswith(b"\x89PNG")
    elif ext == ".svg":
        assert "<svg" in path.read_text()[:2000]


def check_python_block(block: Block, workdir: Path) -> None:
    run = run_python_block(block, workdir)
    if run.error is not None:
        pytest.fail(f"{block.where()} raised (run on its own, as pasted):\n{run.traceback}", pytrace=False)
    assert not run.warnings, f"{block.where()} warns: " + "; ".join(
        f"{w.category.__name__}: {w.message} ({Path(w.filename).name}:{w.lineno})" for w in run.warnings
    )
    ns = run.ns
    # files the snippet names
    for node in ast.walk(run.tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and FILE_NAME.match(node.value):
            _read_back(workdir / node.value)
    # what the comments state
    code_lines = block.text.splitlines()
    for line, comment in _comments(block):
        code = code_lines[line - block.line]
        claims = [c for c in CLAIMS if c[0] in code]
        with readme_environment(workdir):
            for _, _, check in claims:
                check(ns, workdir)
        checked = check_comment(run, ns, line, comment)
        if not (checked or claims) and STATES_A_NUMBER.search(comment):
            pytest.fail(
                f"{block.name} line {line}: the comment {comment!r} states a number no rule checks; "
                f"make it ~VALUE or (shape), or add a rule to CLAIMS in tests/e2e/test_readme.py"
            )
    # claims on lines without a comment
    commented = {line for line, _ in _comments(block)}
    for n, code in enumerate(code_lines, start=block.line):
        if n not in commented:
            with readme_environment(workdir):
                for key, _, check in CLAIMS:
                    if key in code:
                        check(ns, workdir)


def test_every_claim_rule_matches_a_readme_line():
    code = "".join(b.text for b in PYTHON_BLOCKS)
    stale = [key for key, _, _ in CLAIMS if key not in code]
    assert not stale, f"CLAIMS rules whose code is no longer on any page: {stale}"


# ---------------------------------------------------------------------------------------------
# toml blocks: the spec loader


def _spec_keys() -> dict[str, dict[str, Any]]:
    from tubecad.spec import parse as spec

    axis = dict(spec.AXIS_COMMON)
    for keys in spec.FAMILY_KEYS.values():
        axis.update(keys)
    return {"axis": axis, "tube": spec.TUBE_KEYS, **spec.EXTRA_SECTIONS}


#: a commented-out key that replaces another (the loader refuses both at once)
REPLACES = {"s_rings": "rings", "u_stringers_deg": "stringers"}


def _toml_sections(text: str) -> dict[str, list[str]]:
    """Section name -> its lines (comments included)."""
    out: dict[str, list[str]] = {"": []}
    current = ""
    for line in text.splitlines():
        header = re.match(r"^\[([\w.]+)\]", line)
        if header:
            current = header.group(1)
            out[current] = []
        out[current].append(line)
    return out


def check_toml_block(block: Block, workdir: Path) -> None:
    from tubecad.spec.parse import parse_spec

    data = tomllib.loads(block.text)
    parse_spec(
        data, block.where(), ROOT / "samples" if "host" in data else None
    )  # a [host] block names a sample's face
    keys = _spec_keys()
    sections = _toml_sections(block.text)
    for section, lines in sections.items():
        for line in lines:
            # "# log_spiral | helix | ..." lists the same choices as the loader's help
            assignment = re.match(r'^(\w+)\s*=\s*"[^"]*"\s*#\s*(.*)$', line)
            if assignment:
                key, comment = assignment.groups()
                stated = re.match(r"([\w]+(?:\s*\|\s*[\w]+)+)", comment)
                if stated:
                    loader = re.search(r"\w+(?:\s*\|\s*\w+)+", keys[section][key].help)
                    assert loader, f"{block.where()}: [{section}] {key}: the loader's help lists no choices"
                    said, allowed = (set(re.split(r"\s*\|\s*", m.group(0))) for m in (stated, loader))
                    assert said == allowed, (
                        f"{block.where()}: [{section}] {key} choices {said}, the loader allows {allowed}"
                    )
            # "# key = value" (an alternative) is accepted by the loader when uncommented
            alternative = re.match(r"^#\s*(\w+)\s*=\s*([^#]+?)\s*(?:#.*)?$", line)
            if alternative and section:
                key, value = alternative.groups()
                assert key in keys[section], (
                    f"{block.where()}: commented-out key [{section}] {key} is unknown to the loader"
                )
                changed = json.loads(json.dumps(data))
                changed[section][key] = tomllib.loads(f"v = {value}")["v"]
                changed[section].pop(REPLACES.get(key, ""), None)
                parse_spec(changed, f"{block.where()} with [{section}] {key} = {value}")
    if "axis" in data and "tube" in data and set(spec_sections()) <= set(data):  # the full example: every key
        for section in data:
            text = "\n".join(sections[section])
            missing = [k for k in keys[section] if not re.search(rf"\b{re.escape(k)}\b", text)]
            assert not missing, f"{block.where()}: [{section}] does not mention the loader's keys {missing}"
    if "axis" in data and "tube" in data:
        run_spec_through_cli(block, data, workdir)

    if "branches" in data:  # a [[branches]] example documents every key of a branch table
        from tubecad.spec.keys import BRANCH_KEYS

        text = "\n".join(line for lines in sections.values() for line in lines)
        missing = [k for k in BRANCH_KEYS if not re.search(rf"^\s*{k}\s*=", text, re.M)]
        assert not missing, f"{block.where()}: [[branches]] does not mention the loader's keys {missing}"


def spec_sections() -> list[str]:
    """The optional sections ([layout], [wall], ...): the full example holds them all."""
    from tubecad.spec.keys import EXTRA_SECTIONS

    return list(EXTRA_SECTIONS)


def tubecad_command() -> list[str]:
    script = Path(sys.executable).parent / "tubecad"
    return [str(script)] if script.is_file() else [sys.executable, "-m", "tubecad.cli.console"]


def run_spec_through_cli(block: Block, data: dict, workdir: Path) -> None:
    """``tubecad report SPEC`` and ``tubecad build SPEC -o x.step`` (run side by side), checked."""
    import build123d as bd

    from tubecad.brep import properties as props
    from tubecad.spec.layout import layout_from_section
    from tubecad.spec.parse import parse_spec

    spec = workdir / f"block{block.index}.toml"
    spec.write_text(block.text)
    env = {**os.environ, "MPLBACKEND": "Agg"}
    start = lambda *args: subprocess.Popen(
        [*tubecad_command(), *args],
        cwd=workdir,
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    report, build = start("report", spec.name), start("build", spec.name, "-o", "x.step")
    (report_out, report_err), (build_out, build_err) = report.communicate(timeout=600), build.communicate(timeout=600)
    assert report.returncode == 0, f"tubecad report of {block.where()} failed: {report_err}"
    measured = json.loads(report_out)
    assert measured["max_orthogonality_error"] < 1e-14 and measured["max_M_error"] < 1e-14
    assert build.returncode == 0, f"tubecad build of {block.where()} failed: {build_err}"
    assert "valid=True" in build_out, build_out
    top = bd.import_step(workdir / "x.step")
    assert props.is_valid(top), f"x.step built from {block.where()} does not read back valid"
    stiffeners, panels = data.get("stiffeners"), data.get("panels")
    if stiffeners or panels:  # a named assembly: the wall (or its panels) and the stiffeners by name
        layout = layout_from_section(parse_spec(data).tube, data.get("layout", {}))
        names = [c.label for c in top.children]
        assert names[0] == "wall", names
        if stiffeners:

            def chosen(key, count):
                value = stiffeners.get(key, [])
                return list(range(count)) if value == "all" else value

            expected = [f"ring_{i:02d}" for i in chosen("rings", len(layout.s_rings))]
            expected += [f"stringer_{j:02d}" for j in chosen("stringers", len(layout.stringers_deg))]
            # on a junction a stringer crossing an opening is in pieces, stringer_02_a and stringer_02_b
            whole = list(dict.fromkeys(re.sub(r"(stringer_\d+)_[a-z]$", r"\1", name) for name in names[1:]))
            assert whole[: len(expected)] == expected, names
        if panels:
            labels = [c.label for c in top.children[0].children]
            assert labels and all(re.fullmatch(r"panel_r\d+_s\d+", label) for label in labels), labels


# ---------------------------------------------------------------------------------------------
# command lines: tubecad options against --help, python and pip lines against the repository


@dataclass(frozen=True)
class Option:
    takes_value: bool
    choices: tuple[str, ...] = ()


_HELP: dict[str, str] = {}


def tubecad_help(*args: str) -> str:
    """``tubecad ARGS --help``, from the command-line entry point's own click group (in process:
    the same text as the console script prints, without a second start of OCCT)."""
    if args not in _HELP:
        from click.testing import CliRunner

        from tubecad.cli.app import cli

        result = CliRunner().invoke(cli, [*args, "--help"], prog_name="tubecad")
        assert result.exit_code == 0, f"tubecad {' '.join(args)} --help failed: {result.output}"
        _HELP[args] = result.output
    return _HELP[args]


def subcommands() -> set[str]:
    text = tubecad_help().split("Commands:", 1)[1]
    return {m.group(1) for m in re.finditer(r"^  (\S+)", text, re.M)}


def help_options(sub: str) -> tuple[dict[str, Option], tuple[int, float]]:
    """The options of ``tubecad SUB --help`` and its number of positional arguments (min, max)."""
    text = tubecad_help(sub)
    usage = re.search(rf"Usage: tubecad {sub}(.*)", text).group(1).replace("[OPTIONS]", "")
    words = usage.split()
    required = sum(1 for w in words if not w.startswith("[") and "..." not in w)
    optional = sum(1 for w in words if w.startswith("[") and "..." not in w)
    most = math.inf if "..." in usage else required + optional
    options: dict[str, Option] = {}
    body = text.split("Options:", 1)[1]
    head = re.compile(r"^  (-[\w-]+(?:, -[\w-]+)*)(?: ((?:\S| (?=\S))+))?(?:\s{2,}|$)")
    for line in body.splitlines():
        m = head.match(line)
        if not m:
            continue
        metavar = m.group(2) or ""
        choice = re.fullmatch(r"\[([^\]]+)\]", metavar)
        option = Option(bool(metavar), tuple(choice.group(1).split("|")) if choice else ())
        for name in m.group(1).split(", "):
            options[name] = option
    return options, (required, most)


def check_tubecad(args: list[str], where: str) -> None:
    assert args, f"{where}: 'tubecad' without a subcommand"
    if args in (["--help"], ["-h"], ["--version"]):  # the group's own options
        return
    sub, rest = args[0], args[1:]
    assert sub in subcommands(), f"{where}: tubecad has no subcommand {sub!r} (it has {sorted(subcommands())})"
    options, (least, most) = help_options(sub)
    positional = []
    i = 0
    while i < len(rest):
        token = rest[i]
        if token.startswith("-") and len(token) > 1:
            name, eq, inline = token.partition("=")
            assert name in options, f"{where}: tubecad {sub} --help lists no option {name} (it has {sorted(options)})"
            option = options[name]
            if option.takes_value:
                if not eq:
                    i += 1
                    assert i < len(rest) and not rest[i].startswith("-"), f"{where}: {name} needs a value"
                    inline = rest[i]
                if option.choices:
                    wrong = [v for v in inline.split("|") if v.lower() not in {c.lower() for c in option.choices}]
                    assert not wrong, f"{where}: {name} {inline}: {wrong} not among {option.choices}"
                if name == "--sweep" and not inline.partition("=")[0].isupper():  # not the SECTION.KEY placeholder
                    from tubecad.batch.jobs import parse_sweep

                    parse_sweep(inline)
            else:
                assert not eq, f"{where}: {name} takes no value"
        else:
            positional.append(token)
        i += 1
    assert least <= len(positional) <= most, (
        f"{where}: tubecad {sub} takes {least} to {most} arguments, the README gives {positional}"
    )


def check_python_command(argv: list[str], comment: str, where: str) -> None:
    from packaging.specifiers import SpecifierSet

    version = re.fullmatch(r"python(\d+\.\d+)?", Path(argv[0]).name)
    assert version, f"{where}: not a python command: {argv[0]}"
    if version.group(1):
        requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
        assert version.group(1) in SpecifierSet(requires), f"{where}: {argv[0]} but the project requires {requires}"
    if argv[1] == "-m":
        import importlib.util

        assert importlib.util.find_spec(argv[2]) is not None, f"{where}: no module {argv[2]}"
        return
    script = ROOT / argv[1]
    assert script.is_file(), f"{where}: {argv[1]} does not exist"
    used = [a.partition("=")[0] for a in argv[2:] if a.startswith("-")] + re.findall(r"(?<![\w-])--[\w-]+", comment)
    if used:
        done = subprocess.run(
            [sys.executable, str(script), "--help"], cwd=ROOT, capture_output=True, text=True, timeout=300
        )
        assert done.returncode == 0, f"{where}: {argv[1]} --help failed: {done.stderr}"
        listed = set(re.findall(r"(?<![\w-])(--?[\w][\w-]*)", done.stdout))
        assert set(used) <= listed, f"{where}: {argv[1]} --help lists no {sorted(set(used) - listed)}"


def check_pip_command(argv: list[str], where: str) -> None:
    assert argv[1:2] == ["install"], f"{where}: only 'pip install' of this project is expected, got {argv}"
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"].get("optional-dependencies", {})
    targets = [a for a in argv[2:] if not a.startswith("-")]
    assert targets, f"{where}: pip install of nothing"
    for target in targets:
        m = re.fullmatch(r"\.(?:\[([\w,-]+)\])?", target)
        assert m, f"{where}: pip install {target}: only this project ('.' or '.[extra]') is expected"
        missing = [e for e in (m.group(1) or "").split(",") if e and e not in extras]
        assert not missing, f"{where}: pyproject.toml has no extra {missing}"


def _unbracket(token: str) -> str:
    """A usage word without the brackets of an optional part: ``[-o`` -> ``-o``, ``N]`` -> ``N``
    (``.[test]`` keeps its own)."""
    token = token[1:] if token.startswith("[") else token
    while token.endswith("]") and token.count("]") > token.count("["):
        token = token[:-1]
    return token


def check_command_line(line: str, where: str, described: bool = False) -> int:
    """Check every command of one shell line; ``described``: text after 2+ spaces is a description.
    Returns the number of commands checked."""
    code, _, comment = line.partition(" #")
    if described:
        code = re.split(r"\s{2,}", code.strip())[0]
    count = 0
    for segment in re.split(r"&&|\|\||;| \| ", code):
        argv = [t for t in map(_unbracket, shlex.split(segment)) if t and t != "..."]
        if not argv:
            continue
        name = Path(argv[0]).name
        if name == "tubecad":
            check_tubecad(argv[1:], where)
        elif name.startswith("python"):
            check_python_command(argv, comment, where)
        elif name == "pip":
            check_pip_command(argv, where)
        else:
            pytest.fail(
                f"{where}: the README shows the command {argv[0]!r}, which tests/e2e/test_readme.py does not check"
            )
        count += 1
    return count


def check_commands(block: Block, described: bool) -> int:
    return sum(
        check_command_line(line, f"{block.where()}, line {block.line + n}", described)
        for n, line in enumerate(block.text.splitlines())
        if line.strip()
    )


def check_bash_block(block: Block) -> None:
    begin, end = quickstart_lines()
    if block.page != README or not begin < block.line < end:
        assert block.first_line in NOT_RUNNABLE, (
            f"{block.where()}: a bash block outside the quick start, which nothing runs; list it in NOT_RUNNABLE"
        )
        check_commands(block, described=False)
        return
    # the quick start: .ci/run extracts exactly these lines and runs them
    ci = CI_RUN.read_text()
    extract = re.search(r"^commands=\$\((.*)\)\s*$", ci, re.M)
    assert extract, ".ci/run no longer extracts the quick start as commands=$(...)"
    assert re.search(r'^bash -euo pipefail -c "\$commands"', ci, re.M), ".ci/run no longer runs the extracted commands"
    done = subprocess.run(
        ["bash", "-c", f"set -euo pipefail; {extract.group(1)}"], cwd=ROOT, capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == block.text.splitlines(), (
        f".ci/run extracts\n{done.stdout}\nbut the quick-start block is\n{block.text}"
    )
    assert check_commands(block, described=False) >= 2


def check_indented_block(block: Block) -> None:
    lines = [ln for ln in block.text.splitlines() if ln.strip()]
    if any(re.match(r"^(tubecad|\S*python\S*|\S*pip) ", ln) for ln in lines):
        assert all(re.match(r"^(tubecad|\S*python\S*|\S*pip) ", ln) for ln in lines), (
            f"{block.where()}: mixes command lines with other text"
        )
        check_commands(block, described=True)
    elif all(re.match(r"^[\w./-]+/\s", ln) for ln in lines):  # a listing of folders
        missing = [ln.split()[0] for ln in lines if not (ROOT / ln.split()[0]).is_dir()]
        assert not missing, f"{block.where()}: no such folders: {missing}"
    else:
        assert block.first_line in NOT_RUNNABLE, f"{block.where()}: neither runnable nor listed in NOT_RUNNABLE"


# ---------------------------------------------------------------------------------------------
# the tests


@pytest.mark.parametrize(
    "block",
    # python and spec blocks build solids: slow (`-m "not slow"` still checks the others)
    [pytest.param(b, id=b.id, marks=[pytest.mark.slow] if b.lang in ("python", "toml") else []) for b in BLOCKS],
)
def test_readme_block(block: Block, tmp_path: Path) -> None:
    if block.lang == "python":
        assert block.first_line not in NOT_RUNNABLE, f"{block.where()}: python blocks must run"
        requires(*sorted({program for code, program in NEEDS_PROGRAM.items() if code in block.text}))
        if block.needs_cadquery:
            pytest.importorskip("cadquery", reason="CadQuery is the extra tubecad[cadquery]")
        check_python_block(block, tmp_path)
    elif block.lang == "toml":
        assert block.first_line not in NOT_RUNNABLE, f"{block.where()}: spec blocks must load"
        check_toml_block(block, tmp_path)
    elif block.lang == "bash":
        check_bash_block(block)
    elif block.lang == "indented" and block.page in EQUATION_PAGES:
        assert not re.match(r"^(tubecad|\S*python\S*|\S*pip) ", block.first_line), f"{block.where()}: a command"
    elif block.lang == "indented":
        check_indented_block(block)
    else:
        assert block.first_line in NOT_RUNNABLE, (
            f"{block.where()}: blocks of this language are not run; make it python, toml or bash, "
            f"or list it in NOT_RUNNABLE in tests/e2e/test_readme.py with the reason"
        )


def test_readme_has_the_blocks_it_should():
    langs = [b.lang for b in BLOCKS]
    assert langs.count("python") >= 3 and "toml" in langs and "bash" in langs
    assert [b.lang for b in README_BLOCKS].count("python") >= 2, "the README shows build123d and CadQuery"
    assert len(README.read_text(encoding="utf-8").splitlines()) <= 300, "the README is the front door: 300 lines"
    begin, end = quickstart_lines()
    inside = [b for b in README_BLOCKS if begin < b.line < end]
    assert len(inside) == 1 and inside[0].lang == "bash", "the quick start must be one ```bash block"
    stale = set(NOT_RUNNABLE) - {b.first_line for b in BLOCKS}
    assert not stale, f"NOT_RUNNABLE lists blocks no longer on any page: {stale}"


def _inline_spans() -> list[tuple[str, int, str]]:
    """(page name, line, text) of inline `code` outside the blocks, on every page."""
    spans = []
    for page in PAGES:
        in_block = set()
        for b in BLOCKS:
            if b.page == page:
                first = b.line - (0 if b.lang == "indented" else 1)
                in_block.update(range(first, b.line + len(b.text.splitlines()) + 1))
        name = str(page.relative_to(ROOT))
        for n, line in enumerate(page.read_text(encoding="utf-8").splitlines(), start=1):
            if n not in in_block:
                spans += [(name, n, m.group(1)) for m in re.finditer(r"`([^`]+)`", line)]
    return spans


def test_inline_commands_and_options_exist():
    """`tubecad ...` in the text names a real command line; `-x VALUE` spans name real options."""
    options: dict[str, Option] = {}
    for sub in subcommands():
        options.update(help_options(sub)[0])
    checked = 0
    for page, line, span in _inline_spans():
        where = f"{page} line {line}: `{span}`"
        if span.startswith("tubecad "):
            check_command_line(span, where)
            checked += 1
        elif re.match(r"^--?[a-z]", span):
            name, _, value = span.partition(" ")
            assert name in options, f"{where}: no tubecad subcommand has the option {name}"
            assert bool(value) <= options[name].takes_value, f"{where}: {name} takes no value"
            if name == "--sweep" and value:
                from tubecad.batch.jobs import parse_sweep

                sweep = parse_sweep(value)
                span = re.fullmatch(rf".*=({NUMBER}):({NUMBER}):(\d+)", value)
                if span:  # START:STOP:COUNT, both ends included
                    start, stop, count = float(span.group(1)), float(span.group(2)), int(span.group(3))
                    assert len(sweep.values) == count and sweep.values[0] == start and sweep.values[-1] == stop, (
                        f"{where}: gives {sweep.values}"
                    )
            checked += 1
    assert checked >= 5


def test_files_and_names_the_text_points_at_exist():
    """Pictures, repository paths and Python names quoted in the text (outside the blocks)."""
    import importlib

    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for picture in re.findall(r"!\[[^\]]*\]\(([^)\s]+)\)", text):
            assert (page.parent / picture).is_file(), f"{page.name} shows {picture}, which does not exist"
        for link in re.findall(r"(?<!!)\[[^\]]*\]\(([^)\s#]+)(?:#[^)]*)?\)", text):
            if not re.match(r"https?://", link):
                assert (page.parent / link).exists(), f"{page.name} links to {link}, which does not exist"
    checked = 0
    for page, line, span in _inline_spans():
        where = f"{page} line {line}: `{span}`"
        if re.fullmatch(r"(samples|tests|docs|benchmarks|tubecad)/[\w./-]*", span):
            assert (ROOT / span).exists(), f"{where}: no such file or folder"
        elif m := re.fullmatch(r"import ([\w.]+)", span):
            try:
                importlib.import_module(m.group(1))
            except ImportError as exc:  # the CadQuery plugin without the extra: it must say how to get it
                assert "cadquery" in m.group(1) and "pip install 'tubecad[cadquery]'" in str(exc), f"{where}: {exc}"
                continue
        elif m := re.fullmatch(r"(tubecad(?:\.\w+)+)((?:/\w+)*)", span):  # tubecad.brep.properties.volume/area
            module, _, name = m.group(1).rpartition(".")
            try:  # a submodule (tubecad.stiffeners.rings) is an attribute only once imported
                importlib.import_module(m.group(1))
            except ModuleNotFoundError:
                pass  # not a module: an attribute, checked below
            except ImportError as exc:  # the CadQuery plugin without the extra: it must say how to get it
                assert "pip install 'tubecad[cadquery]'" in str(exc), f"{where}: {exc}"
                continue
            for attr in [name, *m.group(2).split("/")[1:]]:
                assert hasattr(importlib.import_module(module), attr), f"{where}: {module} has no {attr}"
        elif m := re.fullmatch(r"Workplane\.(\w+)", span):  # added by the CadQuery plugin imported above
            try:
                import cadquery as cq
            except ImportError:  # the extra tubecad[cadquery] is not installed here
                continue

            assert hasattr(cq.Workplane, m.group(1)), f"{where}: cadquery.Workplane has no {m.group(1)}"
        else:
            continue
        checked += 1
    assert checked >= 5
