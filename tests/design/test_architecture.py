"""The layout as docs/ARCHITECTURE.md states it: the packages form layers, each importing
only from the layers below it, and no module imports itself back through another (every
import counts, also one inside a function or for type checkers only). Read from the source,
nothing is imported."""

from __future__ import annotations

import ast
import sys
from pathlib import Path

from conftest import ROOT

PACKAGE = ROOT / "tubecad"

#: low to high; a package may import its own modules and those of the layers below it
LAYERS = [
    {"core", "occ_compat"},
    {"curves"},
    {"surface"},
    {"fitting"},
    {"brep"},
    {"junctions", "nets"},
    {"stiffeners"},
    {"export"},
    {"fem", "shop"},
    {"design"},
    {"spec"},
    {"batch"},
    {"parts"},
    {"integrations"},
    {"cli"},
]
RANK = {name: i for i, names in enumerate(LAYERS) for name in names}


def import_graph() -> dict[str, set[str]]:
    """module -> the tubecad modules it imports (a package's ``__init__`` as the package)."""
    modules: dict[str, Path] = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        modules[name] = path
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join(up + ([base] if base else []))
                targets = [base, *(f"{base}.{a.name}" for a in node.names)]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            else:
                continue
            graph[name] |= {t for t in targets if t in modules and t != name and not name.startswith(t + ".")}
    return graph


def layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None  # tubecad/__init__ (the lazy public names) sits above all


def test_every_package_has_a_layer():
    packages = {layer(m) for m in import_graph()} - {None}
    assert packages <= set(RANK), f"packages missing from LAYERS (and docs/ARCHITECTURE.md): {packages - set(RANK)}"


def upward_imports(graph: dict[str, set[str]]) -> list[str]:
    return sorted(
        f"{a} -> {b}"
        for a, targets in graph.items()
        for b in targets
        if layer(a) is not None and layer(b) is not None and RANK[layer(b)] > RANK[layer(a)]
    )


def import_circles(graph: dict[str, set[str]]) -> list[list[str]]:
    state: dict[str, int] = {}  # 1: on the path, 2: done
    cycles: list[list[str]] = []

    def visit(node: str, path: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycles.append(path[path.index(nxt) :] + [nxt])
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = 2

    for start in sorted(graph):
        if start not in state:
            visit(start, [start])
    return cycles


def test_no_upward_import():
    upward = upward_imports(import_graph())
    assert not upward, "imports from a higher layer:\n" + "\n".join(upward)


def test_no_import_circle():
    cycles = import_circles(import_graph())
    assert not cycles, "import circles:\n" + "\n".join(" -> ".join(c) for c in cycles)


def test_the_checker_sees_a_circle_and_an_upward_import(tmp_path, monkeypatch):
    """The walk itself, on a package made here: a module of core importing one of cli inside
    a function, which imports it back with a relative import."""
    pkg = tmp_path / "tubecad"
    for folder in (pkg / "core", pkg / "cli"):
        folder.mkdir(parents=True)
        (folder / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "core" / "a.py").write_text("def f():\n    from tubecad.cli import b\n")
    (pkg / "cli" / "b.py").write_text("from ..core import a\n")
    monkeypatch.setattr(sys.modules[__name__], "PACKAGE", pkg)
    graph = import_graph()
    assert graph["tubecad.core.a"] == {"tubecad.cli", "tubecad.cli.b"}
    assert graph["tubecad.cli.b"] == {"tubecad.core", "tubecad.core.a"}
    assert upward_imports(graph) == ["tubecad.core.a -> tubecad.cli", "tubecad.core.a -> tubecad.cli.b"]
    assert ["tubecad.cli.b", "tubecad.core.a", "tubecad.cli.b"] in import_circles(graph)


# --- dispatch by the surface protocol, not by the concrete class -----------------------------------
#: concrete classes named outside the curves' Axis tree: the two surfaces and the canal fit's
CONCRETE = {
    "CurvatureLineTube": "tubecad.surface.tube",
    "CanalSurface": "tubecad.surface.canal",
    "CanalSpline": "tubecad.fitting.canal_section",
    "CanalSectionSurface": "tubecad.fitting.canal_section",
}
#: private methods that other modules used to call on a surface or an axis (now public protocol
#: members: ``s_breaks``, ``inside``); flagged on anything but self or cls, wherever defined
REMOVED_REACH_INS = {"_breaks", "_inside"}
#: underscored names that are public API elsewhere (a namedtuple's)
PUBLIC_UNDERSCORED = {"_replace", "_asdict", "_make"}


def _modules() -> dict[str, ast.Module]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = ast.parse(path.read_text(encoding="utf-8"))
    return out


def concrete_classes(modules: dict[str, ast.Module]) -> dict[str, str]:
    """class name -> its module: :data:`CONCRETE` and every subclass of Axis in tubecad.curves
    (RouteAxis, SlopeCurve, Helix, ...), found from the class statements' bases."""
    bases: dict[str, tuple[str, set[str]]] = {}
    for name, tree in modules.items():
        if name.startswith("tubecad.curves"):
            for node in ast.walk(tree):
                if isinstance(node, ast.ClassDef):
                    names = {b.id if isinstance(b, ast.Name) else getattr(b, "attr", "") for b in node.bases}
                    bases[node.name] = (name, names)
    axes = {"Axis"}
    while True:
        more = {c for c, (_, b) in bases.items() if b & axes} - axes
        if not more:
            break
        axes |= more
    return {**CONCRETE, **{c: bases[c][0] for c in axes - {"Axis"}}}


def concrete_dispatch(modules: dict[str, ast.Module]) -> list[str]:
    """``isinstance(x, C)`` with C a concrete class, outside C's own module, as "module:line C"."""
    classes = concrete_classes(modules)
    found = []
    for name, tree in modules.items():
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "isinstance"):
                continue
            if len(node.args) < 2:
                continue
            kinds = node.args[1].elts if isinstance(node.args[1], ast.Tuple) else [node.args[1]]
            for kind in kinds:
                cls = kind.id if isinstance(kind, ast.Name) else getattr(kind, "attr", None)
                if cls in classes and classes[cls] != name:
                    found.append(f"{name}:{node.lineno} {cls}")
    return sorted(found)


def _defined_names(tree: ast.Module) -> set[str]:
    """The names a module defines anywhere in it: its functions and methods, its classes,
    and names assigned (a class-level alias ``_inside = inside``)."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names |= {t.id for t in targets if isinstance(t, ast.Name)}
    return names


def _foreign_modules(tree: ast.Module) -> set[str]:
    """The names a module binds to modules or objects imported from outside tubecad (``os``
    of ``import os``): their underscored members are that library's business."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {(a.asname or a.name).split(".")[0] for a in node.names if not a.name.startswith("tubecad")}
        elif isinstance(node, ast.ImportFrom) and not node.level and not (node.module or "").startswith("tubecad"):
            names |= {a.asname or a.name for a in node.names}
    return names


def private_reach_ins(modules: dict[str, ast.Module]) -> list[str]:
    """Calls ``x._m(...)`` on anything but self or cls of a private method ``_m`` that the
    calling module does not define itself (another module's private method: a reach-in),
    and of a method in :data:`REMOVED_REACH_INS` wherever it is defined. A call on a module
    imported from outside tubecad (``os._exit``) and a namedtuple's ``_replace`` are not ours."""
    found = []
    for name, tree in modules.items():
        defined, foreign = _defined_names(tree), _foreign_modules(tree)
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                continue
            attr, owner = node.func.attr, node.func.value
            if not attr.startswith("_") or attr.startswith("__") or attr in PUBLIC_UNDERSCORED:
                continue
            if isinstance(owner, ast.Name) and owner.id in {"self", "cls"}:
                continue
            if attr in REMOVED_REACH_INS or not (
                attr in defined or (isinstance(owner, ast.Name) and owner.id in foreign)
            ):
                found.append(f"{name}:{node.lineno} .{attr}()")
    return sorted(found)


def test_the_concrete_classes_include_every_axis():
    classes = concrete_classes(_modules())
    for cls in ("RouteAxis", "SlopeCurve", "Helix", "LogSpiral", "Clothoid", "NaturalAxis", "ParametricAxis"):
        assert cls in classes, cls
    assert "Axis" not in classes and "RadiusLaw" not in classes


def test_no_isinstance_on_a_concrete_surface_or_axis():
    found = concrete_dispatch(_modules())
    assert not found, "isinstance on a concrete class outside its module (use the surface protocol):\n" + "\n".join(
        found
    )


def test_no_private_reach_in_on_a_surface():
    found = private_reach_ins(_modules())
    assert not found, "private methods called from another module (make them public):\n" + "\n".join(found)


def test_the_dispatch_checker_sees_an_isinstance_and_a_reach_in():
    """The checks themselves, on modules made here: the defining module may use isinstance,
    another may not (a bare name, a dotted one, in a tuple), nor call ``_breaks`` on an object."""
    own = ast.parse(
        "class CanalSurface:\n    def f(self, x):\n        return isinstance(x, CanalSurface) and self._breaks()\n"
    )
    other = ast.parse(
        "import tubecad.surface as ts\n"
        "def g(x, y):\n"
        "    return isinstance(x, (int, ts.CanalSurface)) or isinstance(y, Helix) or x._breaks()\n"
    )
    curves = ast.parse("class Axis:\n    pass\nclass SlopeCurve(Axis):\n    pass\nclass Helix(SlopeCurve):\n    pass\n")
    modules = {"tubecad.surface.canal": own, "tubecad.shop.x": other, "tubecad.curves.families": curves}
    assert concrete_dispatch(modules) == ["tubecad.shop.x:3 CanalSurface", "tubecad.shop.x:3 Helix"]
    assert private_reach_ins(modules) == ["tubecad.shop.x:3 ._breaks()"]


def test_the_reach_in_checker_sees_another_modules_private_method():
    """``x._m()`` is a reach-in unless x is self or cls, or ``_m`` is the calling module's own
    (a method of one of its classes on another instance), or x a library outside tubecad;
    ``_inside`` and ``_breaks`` are reach-ins even where the module defines them."""
    own = ast.parse(
        "class CanalSurface:\n"
        "    def _solve(self):\n"
        "        return 1\n"
        "    def _inside(self, s):\n"
        "        return self.axis._inside(s)\n"
        "    def restricted(self):\n"
        "        piece = CanalSurface()\n"
        "        return piece._solve()\n"
    )
    other = ast.parse(
        "import os\n"
        "from collections import namedtuple\n"
        "def f(base, canal, row):\n"
        "    base.axis._inside(0.0)\n"
        "    canal._solve()\n"
        "    row._replace(a=1)\n"
        "    os._exit(0)\n"
        "    return _helper() + base.inside(0.0)\n"
        "def _helper():\n"
        "    return 0\n"
    )
    modules = {"tubecad.surface.canal": own, "tubecad.shop.x": other}
    assert private_reach_ins(modules) == [
        "tubecad.shop.x:4 ._inside()",
        "tubecad.shop.x:5 ._solve()",
        "tubecad.surface.canal:5 ._inside()",
    ]


# --- no downcast: what a caller needs is a protocol member, never typing.cast -----------------------
#: casts allowed, as (module, the type named): none since issue 42 (the last two, a tube build's frame
#: and a busy worker's index, became TubeBuild.section_frame and a narrowing comprehension)
PENDING_CASTS: set[tuple[str, str]] = set()


def typing_casts(modules: dict[str, ast.Module]) -> list[tuple[str, int, str]]:
    """Every call of ``typing.cast`` as (module, line, the type named): ``cast(T, x)`` (also
    imported under another name) and ``typing.cast(T, x)`` (also ``import typing as t``).
    build123d's ``Shape.cast`` (``bd.Shape.cast``: a TopoDS shape as its build123d class, a
    conversion at run time) is not typing's and is not counted."""
    found = []
    for name, tree in modules.items():
        functions, namespaces = {"cast"}, {"typing"}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module == "typing":
                functions |= {a.asname or a.name for a in node.names if a.name == "cast"}
            elif isinstance(node, ast.Import):
                namespaces |= {a.asname or a.name for a in node.names if a.name == "typing"}
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and node.args):
                continue
            func = node.func
            if (isinstance(func, ast.Name) and func.id in functions) or (
                isinstance(func, ast.Attribute)
                and func.attr == "cast"
                and isinstance(func.value, ast.Name)
                and func.value.id in namespaces
            ):
                kind = node.args[0]
                named = (
                    kind.value if isinstance(kind, ast.Constant) and isinstance(kind.value, str) else ast.unparse(kind)
                )
                found.append((name, node.lineno, named))
    return sorted(found)


def test_no_cast():
    """docs/ARCHITECTURE.md: no stage asks which concrete kind a surface, a fit or an axis is;
    it asks the protocol (a member, or the surface's double dispatch), so no value is cast to
    a class it was not declared as (nor to any other type: a function returns what it says)."""
    found = typing_casts(_modules())
    new = [f"{m}:{line} cast({kind}, ...)" for m, line, kind in found if (m, kind) not in PENDING_CASTS]
    assert not new, "typing.cast (add the protocol member the caller needs instead):\n" + "\n".join(new)
    gone = sorted(PENDING_CASTS - {(m, kind) for m, _, kind in found})
    assert not gone, f"casts removed: take them out of PENDING_CASTS too: {gone}"


def test_the_cast_checker_sees_typing_casts_only():
    """The check itself: ``cast``, an alias of it and ``typing.cast`` (also through an alias of
    typing) are found, with the type as written; build123d's ``bd.Shape.cast`` is not."""
    module = ast.parse(
        "import typing\n"
        "import typing as t\n"
        "import build123d as bd\n"
        "from typing import cast, cast as as_\n"
        "def f(x):\n"
        "    a = cast(CanalSurface, x)\n"
        "    b = typing.cast('list[CanalSectionSurface]', x)\n"
        "    c = t.cast(int, x)\n"
        "    d = as_(CurvatureLineTube, x)\n"
        "    return bd.Shape.cast(x), Shape.cast(x), a, b, c, d\n"
    )
    assert typing_casts({"tubecad.brep.x": module}) == [
        ("tubecad.brep.x", 6, "CanalSurface"),
        ("tubecad.brep.x", 7, "list[CanalSectionSurface]"),
        ("tubecad.brep.x", 8, "int"),
        ("tubecad.brep.x", 9, "CurvatureLineTube"),
    ]


# --- one staging recipe: output folders are staged by tubecad.core.atomic only -------------------
def temporary_folders(modules: dict[str, ast.Module]) -> list[str]:
    """Calls of ``mkdtemp`` (``tempfile.mkdtemp``, or imported by name) outside tubecad.core, as
    "module:line": a folder of outputs is staged by :func:`tubecad.core.atomic.staged_folder`,
    the one recipe (a scratch folder for an external program is ``TemporaryDirectory``)."""
    found = []
    for name, tree in modules.items():
        if name.startswith("tubecad.core"):
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                func = node.func
                called = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
                if called == "mkdtemp":
                    found.append(f"{name}:{node.lineno}")
    return sorted(found)


def test_output_folders_are_staged_in_one_place():
    found = temporary_folders(_modules())
    assert not found, "mkdtemp outside tubecad.core (use tubecad.core.atomic.staged_folder):\n" + "\n".join(found)


def test_the_staging_checker_sees_mkdtemp():
    module = ast.parse("import tempfile\nfrom tempfile import mkdtemp\na = tempfile.mkdtemp()\nb = mkdtemp()\n")
    assert temporary_folders({"tubecad.shop.x": module, "tubecad.core.atomic": module}) == [
        "tubecad.shop.x:3",
        "tubecad.shop.x:4",
    ]
