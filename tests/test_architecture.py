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
