"""One place per policy (issue 22): the fit tolerance (tubecad.core.tolerance), the DXF writer
(tubecad.core.dxf), the output extensions (tubecad.export.formats), and pictures drawn on
matplotlib Figure objects, so that tubecad never switches the user's backend. The source
checks read the files; nothing of them is imported."""

from __future__ import annotations

import ast
import inspect
import json
import re
import subprocess
import sys

import pytest
from conftest import ROOT

PACKAGE = ROOT / "tubecad"


def sources() -> dict[str, ast.Module]:
    return {
        path.relative_to(PACKAGE.parent).as_posix(): ast.parse(path.read_text(encoding="utf-8"))
        for path in sorted(PACKAGE.rglob("*.py"))
    }


def imported(tree: ast.Module) -> set[str]:
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            names |= {node.module, *(f"{node.module}.{a.name}" for a in node.names)}
    return names


# --- matplotlib ------------------------------------------------------------------------------
DRAW = """
import json, sys
import matplotlib

matplotlib.use(sys.argv[1])
from pathlib import Path

import build123d as bd

from tubecad.spec.paper import paper_tube
from tubecad.export.plots import write_projections
from tubecad.export.render import render_shape_png
from tubecad.stiffeners.flat import ring_flat_pattern, write_picture

out = Path(sys.argv[2])
written = write_picture(ring_flat_pattern(14.0, 3.0, "inside", "ring_01"), out)
written += write_projections(paper_tube(), out, rings=5, stringers=4, subdivisions=2)
written.append(render_shape_png(bd.Box(3, 2, 1), out / "box.png", size_px=(200, 150)))
import tubecad.fem.plot, tubecad.shop.writer  # noqa: E401,F401  (every module that draws)

print(json.dumps([matplotlib.get_backend(), "matplotlib.pyplot" in sys.modules, [p.name for p in written]]))
"""


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["svg", "pdf"])
def test_drawing_a_picture_leaves_the_users_backend_alone(backend, tmp_path):
    proc = subprocess.run(
        [sys.executable, "-c", DRAW, backend, str(tmp_path)], capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    after, pyplot, names = json.loads(proc.stdout.strip().splitlines()[-1])
    assert after == backend and not pyplot  # not switched to Agg, and pyplot never loaded
    assert names == ["ring_01.svg", "ring_01.png", "projections.png", "projections.svg", "box.png"]
    assert all((tmp_path / n).stat().st_size > 0 for n in names)
    assert (tmp_path / "box.png").read_bytes().startswith(b"\x89PNG")


def test_no_module_switches_the_backend_or_uses_pyplot():
    for name, tree in sources().items():
        assert not {"matplotlib.pyplot", "pylab"} & imported(tree), f"{name} imports pyplot"
        calls = [
            n
            for n in ast.walk(tree)
            if isinstance(n, ast.Call)
            and isinstance(n.func, ast.Attribute)
            and n.func.attr == "use"
            and isinstance(n.func.value, ast.Name)
            and n.func.value.id == "matplotlib"
        ]
        assert not calls, f"{name} calls matplotlib.use"


# --- the fit tolerance --------------------------------------------------------------------------
def test_the_fit_defaults_are_named_once():
    from tubecad.core.tolerance import (
        DEFAULT_FIT_TOLERANCE,
        DEFAULT_ORTHOGONALITY,
        DEFAULT_TOLERANCE,
        orthogonality_for,
    )

    assert DEFAULT_FIT_TOLERANCE == 1e-8 and DEFAULT_TOLERANCE is DEFAULT_FIT_TOLERANCE  # the old name kept
    assert DEFAULT_ORTHOGONALITY == orthogonality_for(DEFAULT_FIT_TOLERANCE) == 1e-9


def test_every_tolerance_default_is_the_policys_name():
    """No function of tubecad writes its ``tolerance`` or ``orthogonality`` default as a number."""
    found = []
    for name, tree in sources().items():
        for node in ast.walk(tree):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            args = node.args
            positional = args.posonlyargs + args.args
            pairs = list(zip(positional[len(positional) - len(args.defaults) :], args.defaults))
            pairs += [(a, d) for a, d in zip(args.kwonlyargs, args.kw_defaults) if d is not None]
            found += [
                f"{name}:{node.lineno} {node.name}({a.arg}={ast.unparse(d)})"
                for a, d in pairs
                if a.arg in ("tolerance", "orthogonality")
                and isinstance(d, ast.Constant)
                and ast.literal_eval(d) in (1e-8, 1e-9)
            ]
    assert not found, found


def test_the_fits_and_builders_default_to_the_policy():
    from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE, DEFAULT_ORTHOGONALITY
    from tubecad.fitting.canal_section import fit_canal
    from tubecad.fitting.frame_spline import fit_frame
    from tubecad.fitting.route_frame import route_frame
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.solids import ring_stiffener, stringer_stiffener, web_face

    for function in (fit_frame, route_frame, fit_canal, ring_stiffener, stringer_stiffener, web_face, build_stiffeners):
        parameters = inspect.signature(function).parameters
        assert parameters["tolerance"].default == DEFAULT_FIT_TOLERANCE, function.__name__
        if "orthogonality" in parameters:
            assert parameters["orthogonality"].default == DEFAULT_ORTHOGONALITY, function.__name__


# --- DXF and extensions ----------------------------------------------------------------------
def test_one_module_writes_dxf():
    users = sorted(name for name, tree in sources().items() if "ezdxf" in {n.split(".")[0] for n in imported(tree)})
    assert users == ["tubecad/core/dxf.py"]


OUTPUT_EXTENSION = re.compile(r"\.(step|stp|iges|igs|brep|stl|3mf|gltf|glb|csv|json|dxf)", re.IGNORECASE)


def test_only_the_format_table_lists_output_extensions():
    """A string that is just an output extension ('.step') appears in tubecad/export/formats.py
    alone (file names such as 'paper.step' or f'{name}.dxf' are outputs, not the table)."""
    found = []
    for name, tree in sources().items():
        if name == "tubecad/export/formats.py":
            continue
        in_names = {id(v) for n in ast.walk(tree) if isinstance(n, ast.JoinedStr) for v in n.values}
        found += [
            f"{name}:{node.lineno} {node.value!r}"
            for node in ast.walk(tree)
            if isinstance(node, ast.Constant)
            and isinstance(node.value, str)
            and OUTPUT_EXTENSION.fullmatch(node.value)
            and id(node) not in in_names
        ]
    assert not found, found
