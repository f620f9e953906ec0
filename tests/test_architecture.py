"""The layout as docs/ARCHITECTURE.md states it: the packages form layers, each importing
only from the layers below it, and no module imports itself back through another (every
import counts, also one inside a function). Read from the source, nothing is imported."""

from __future__ import annotations

import ast
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "tubecad"

#: low to high; a package may import its own modules and those of the layers below it
LAYERS = [
    {"core", "occ_compat"},
    {"curves"},
    {"surface"},
    {"fitting"},
    {"brep"},
    {"stiffeners"},
    {"export"},
    {"fem", "shop"},
    {"spec"},
    {"batch"},
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
#: private methods that other modules used to call on a surface (now public protocol members)
REMOVED_REACH_INS = {"_breaks"}


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


def private_reach_ins(modules: dict[str, ast.Module]) -> list[str]:
    """Calls ``x._m(...)`` of a method in :data:`REMOVED_REACH_INS` on anything but self or cls."""
    found = []
    for name, tree in modules.items():
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr in REMOVED_REACH_INS
            ):
                owner = node.func.value
                if not (isinstance(owner, ast.Name) and owner.id in {"self", "cls"}):
                    found.append(f"{name}:{node.lineno} .{node.func.attr}()")
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
    assert not found, "private methods called from another module:\n" + "\n".join(found)


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
