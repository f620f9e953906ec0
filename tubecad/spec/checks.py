"""The checks every spec key goes through: known keys, required keys, TOML types, choices
and finite numbers, each refused in one line naming ``[section] key`` (the spec checkers of
:mod:`tubecad.spec.parse` and :mod:`tubecad.spec.host` share them). Light: no numpy, no OCCT."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from tubecad.core.errors import SpecError
from tubecad.spec.keys import Key


def short(text: str, most: int = 80) -> str:
    """``text`` cut to ``most`` characters for a one-line message (a hostile spec can hold megabytes)."""
    return text if len(text) <= most else f"{text[:most]}... ({len(text)} characters)"


def check_keys(
    section: str, values: dict[str, Any], keys: dict[str, Key], fail: Callable[..., SpecError]
) -> dict[str, Any]:
    for key in values:
        if key not in keys:
            raise fail(f"unknown key [{section}] {short(key)}; allowed keys are {', '.join(keys)}", section)
    out: dict[str, Any] = {}
    for key, spec in keys.items():
        if key not in values:
            if spec.required:
                raise fail(f"[{section}] {key} is missing ({spec.help})", f"{section}.{key}")
            continue
        out[key] = check_type(section, key, values[key], spec, fail)
    return out


def check_type(section: str, key: str, value: Any, spec: Key, fail: Callable[..., SpecError]) -> Any:
    where = f"[{section}] {key}"

    def number(v: Any) -> bool:
        return isinstance(v, (int, float)) and not isinstance(v, bool)

    ok = {
        "number": number(value),
        "string": isinstance(value, str),
        "bool": isinstance(value, bool),
        "pair": isinstance(value, list) and len(value) == 2 and all(number(v) for v in value),
        "triple": isinstance(value, list) and len(value) == 3 and all(number(v) for v in value),
        "numbers": isinstance(value, list) and len(value) > 0 and all(number(v) for v in value),
        "number_or_numbers": number(value)
        or (isinstance(value, list) and len(value) > 0 and all(number(v) for v in value)),
        "integer": isinstance(value, int) and not isinstance(value, bool),
        "index_or_name": (isinstance(value, int) and not isinstance(value, bool)) or isinstance(value, str),
        "selection": value == "all"
        or (isinstance(value, list) and all(isinstance(v, int) and not isinstance(v, bool) for v in value)),
        "points": isinstance(value, list)
        and len(value) >= 3
        and all(isinstance(p, list) and len(p) == 3 and all(number(v) for v in p) for p in value),
        "joints": isinstance(value, dict)
        and all(isinstance(v, list) and v and all(number(x) for x in v) for v in value.values()),
        "table": isinstance(value, dict),
        "radius": number(value)
        or isinstance(value, str)
        or (
            isinstance(value, list)
            and len(value) >= 2
            and all(isinstance(p, list) and len(p) == 2 and all(number(v) for v in p) for p in value)
        ),
    }[spec.kind]
    if not ok:
        wanted = {
            "number": "a number",
            "string": "a string",
            "bool": "true or false",
            "integer": "a whole number",
            "index_or_name": "a whole-number index or a name",
            "pair": "a list of two numbers",
            "triple": "a list of three numbers",
            "numbers": "a non-empty list of numbers",
            "number_or_numbers": "a number or a non-empty list of numbers",
            "selection": 'a list of whole-number indices or "all"',
            "points": "a list of three or more [x, y, z] points",
            "joints": "a table of stiffener name = [positions]",
            "radius": "a number, an expression in s or a table of two or more [s, r] rows",
            "table": "an inline table { key = value, ... }",
        }[spec.kind]
        raise fail(f"{where} must be {wanted} ({spec.help}), got {toml_type(value)} {value!r:.80}", f"{section}.{key}")
    if spec.kind in ("number", "radius") and number(value) and not math.isfinite(value):
        raise fail(f"{where} must be finite ({spec.help}), got {value}", f"{section}.{key}")
    if spec.kind == "number_or_numbers" and not all(
        math.isfinite(v) for v in (value if isinstance(value, list) else [value])
    ):
        raise fail(f"{where} must be finite ({spec.help}), got {short(repr(value))}", f"{section}.{key}")
    if spec.choices and value not in spec.choices:
        raise fail(f"{where} must be one of {', '.join(spec.choices)}, got {short(repr(value))}", f"{section}.{key}")
    if spec.kind == "table":
        return check_keys(f"{section}.{key}", value, spec.keys, fail)
    return value


def toml_type(value: Any) -> str:
    return {
        bool: "a boolean",
        int: "an integer",
        float: "a float",
        str: "a string",
        list: "an array",
        dict: "a table",
    }.get(type(value), type(value).__name__)
