"""Lazy package exports (PEP 562): a package names what it offers and the module defining
each name, and the module is imported on first use. So importing one light submodule (the
spec checker's size rules, say) does not load OCCT through its package's ``__init__``, and
``tubecad --help`` starts in a fraction of a second."""

from __future__ import annotations

from collections.abc import Callable
from importlib import import_module
from typing import Any


def lazy_exports(
    package: str, exports: dict[str, str], namespace: dict[str, Any]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` for ``package``: ``exports`` maps a public name to its module
    (relative, e.g. ``".solids"``); a name, once imported, is stored in ``namespace`` (the
    package's globals), so the lookup runs once."""

    def __getattr__(name: str) -> Any:
        if name in exports:
            value = getattr(import_module(exports[name], package), name)
            namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(exports))

    return __getattr__, __dir__
