"""Every public name documents its arguments (issue 42): the API page (docs/api.md, made by
mkdocstrings from the docstrings) shows each public class's and function's docstring, so
each of ``tubecad.__all__``'s classes and functions names every parameter of its signature
under a Google-style ``Args:`` section (in the class docstring or its ``__init__``'s), and a
function that returns something has ``Returns:`` (or ``Yields:``). Type aliases
(``AxisLike``, ``WallSide``, ...), the errors and protocols (never constructed) have no
arguments to document."""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable

import pytest

import tubecad
from tubecad.core.errors import TubecadError

#: names whose docstrings do not document every argument yet, each still expected to fail; take
#: a name out when its docstring is complete (the test then says so)
PENDING: set[str] = set()

#: a Google section's heading: ``Args:``, ``Returns:``, ... alone on its line
SECTION = re.compile(r"^(\s*)([A-Z][A-Za-z ]*):\s*$")
#: an entry of ``Args:``: ``name:``, ``name (type):``, ``*args, **kwargs:``
ENTRY = re.compile(r"^(\*{0,2}\w+(?:\s*,\s*\*{0,2}\w+)*)\s*(?:\([^)]*\))?\s*:")


def sections(doc: str) -> dict[str, list[str]]:
    """A docstring's Google sections: heading -> the lines under it indented deeper than the
    heading (blank lines kept), each dedented to the section's own indentation."""
    lines = inspect.cleandoc(doc).splitlines()
    out: dict[str, list[str]] = {}
    i = 0
    while i < len(lines):
        match = SECTION.match(lines[i])
        i += 1
        if not match:
            continue
        indent = len(match.group(1))
        body: list[str] = []
        while i < len(lines) and (not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > indent):
            body.append(lines[i])
            i += 1
        while body and not body[-1].strip():
            body.pop()
        out.setdefault(match.group(2), []).extend(body)
    return out


def documented_args(doc: str) -> set[str]:
    """The parameter names the ``Args:`` section(s) describe: its entries' names, those at the
    section's least indentation (an entry's wrapped description is indented deeper), ``*``
    stripped, several names on one entry each counted."""
    body = [line for line in sections(doc).get("Args", []) if line.strip()]
    if not body:
        return set()
    indent = min(len(line) - len(line.lstrip()) for line in body)
    names: set[str] = set()
    for line in body:
        if len(line) - len(line.lstrip()) == indent and (match := ENTRY.match(line.strip())):
            names |= {name.strip().lstrip("*") for name in match.group(1).split(",")}
    return names


def public_callables() -> dict[str, Callable]:
    """``tubecad.__all__``'s classes and functions, without the errors and the type aliases."""
    out: dict[str, Callable] = {}
    for name in tubecad.__all__:
        obj = getattr(tubecad, name)
        if inspect.isclass(obj) and issubclass(obj, TubecadError):
            continue
        if inspect.isclass(obj) or inspect.isfunction(obj):
            out[name] = obj
    return out


def problems(obj: Callable) -> list[str]:
    """What ``obj``'s docstring misses: undocumented parameters, a missing ``Returns:``."""
    if inspect.isclass(obj):
        if getattr(obj, "_is_protocol", False):
            return []  # a protocol is implemented, never constructed: it has no arguments
        init = obj.__dict__.get("__init__")
        signature = inspect.signature(init) if init is not None else inspect.signature(obj)
        docs = [inspect.getdoc(obj) or "", (init.__doc__ or "") if init is not None else ""]
        returns = False
    else:
        signature = inspect.signature(obj)
        docs = [inspect.getdoc(obj) or ""]
        returns = signature.return_annotation not in (inspect.Signature.empty, None, "None")
    named = set().union(*(documented_args(doc) for doc in docs))
    wanted = [p for p in signature.parameters if p not in ("self", "cls") and not p.startswith("_")]
    missing = [f"Args: {p}" for p in wanted if p not in named]
    if returns and not any({"Returns", "Yields"} & sections(doc).keys() for doc in docs):
        missing.append("Returns:")
    return missing


def test_the_public_names_are_found():
    """The walk sees the public classes and functions (and nothing else)."""
    found = public_callables()
    assert {"CurvatureWall", "NaturalAxis", "load_spec", "export_shape", "show", "NetLayout"} <= found.keys()
    assert not {"AxisLike", "WallSide", "SpecError", "TubecadError"} & found.keys()
    assert PENDING <= found.keys(), f"PENDING names no public class or function: {sorted(PENDING - found.keys())}"


@pytest.mark.parametrize("name", sorted(public_callables()))
def test_every_public_name_documents_its_arguments(name):
    missing = problems(public_callables()[name])
    if name in PENDING:
        assert missing, f"{name} is documented now: take it out of PENDING"
    else:
        assert not missing, f"{name}'s docstring misses: {', '.join(missing)}"


def test_the_section_parser():
    """The parser itself: entries with and without a type, wrapped descriptions (not entries),
    ``*args, **kwargs`` together, the section ending at the first line back at its indentation."""
    doc = """A thing.

    Some prose, with a colon: not a section.

    Args:
        a: the first, wrapped
            over two lines: still a's.
        b (float): the second.
        *items, **options: the rest.

    Returns:
        The result.

    c: not an argument.
    """
    assert documented_args(doc) == {"a", "b", "items", "options"}
    assert sections(doc)["Returns"] == ["    The result."]

    def f(a: int, b: float = 1.0) -> int:
        """F.

        Args:
            a: one.
        """
        return a

    assert problems(f) == ["Args: b", "Returns:"]
