"""The JSON Schema (draft 2020-12) of spec files, for editors: ``tubecad schema``.

Made from the spec checker's own key tables (:mod:`tubecad.spec.keys`), so the
two cannot drift: every section and key, its type, whether it is required, its range or
choices, and its help as the description; unknown keys are refused (``additionalProperties:
false``). The [axis] keys depend on ``curve``: every family's keys are listed (so an editor
completes them all), and one ``if``/``then`` per family requires that family's keys and
allows no other family's.

The schema checks what a schema can: the spec checker stays the authority and also checks
what depends on the geometry (regularity, the wall's outer surface, stiffener heights,
indices into the layout, start < end of the span, explicit rings inside the span).

Light on purpose: no numpy, no OCCT.
"""

from __future__ import annotations

import json
from typing import Any

from tubecad.spec.keys import (
    ARRAY_SECTIONS,
    AXIS_COMMON,
    EXTRA_SECTIONS,
    FAMILY_KEYS,
    HOST_KEYS,
    HOST_SECTIONS,
    SECTION_HELP,
    TUBE_KEYS,
    Key,
)

SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"

_NUMBER = {"type": "number"}
_KINDS: dict[str, dict[str, Any]] = {
    "number": _NUMBER,
    "string": {"type": "string"},
    "bool": {"type": "boolean"},
    "integer": {"type": "integer"},
    "index_or_name": {"anyOf": [{"type": "integer", "minimum": 0}, {"type": "string"}]},
    "pair": {"type": "array", "items": _NUMBER, "minItems": 2, "maxItems": 2},
    "triple": {"type": "array", "items": _NUMBER, "minItems": 3, "maxItems": 3},
    "numbers": {"type": "array", "items": _NUMBER, "minItems": 1},
    "number_or_numbers": {"anyOf": [_NUMBER, {"type": "array", "items": _NUMBER, "minItems": 1}]},
    "selection": {"anyOf": [{"const": "all"}, {"type": "array", "items": {"type": "integer"}}]},
    "points": {
        "type": "array",
        "items": {"type": "array", "items": _NUMBER, "minItems": 3, "maxItems": 3},
        "minItems": 3,
    },
    "joints": {"type": "object", "additionalProperties": {"type": "array", "items": _NUMBER, "minItems": 1}},
    "table": {"type": "object"},
    "radius": {
        "anyOf": [
            _NUMBER,
            {"type": "string"},
            {
                "type": "array",
                "items": {"type": "array", "items": _NUMBER, "minItems": 2, "maxItems": 2},
                "minItems": 2,
            },
        ]
    },
}


def key_schema(key: Key) -> dict[str, Any]:
    """One key: its type, choices, range and default, described by its help."""
    out: dict[str, Any] = {"description": key.help, **json.loads(json.dumps(_KINDS[key.kind]))}
    if key.kind == "table":  # an inline table: exactly its own keys
        out.update(section_schema("", key.keys))
        out["description"] = key.help
    if key.choices:
        out["enum"] = list(key.choices)
    if key.low is not None:
        out["exclusiveMinimum" if key.low_open else "minimum"] = key.low
    if key.high is not None:
        out["exclusiveMaximum" if key.high_open else "maximum"] = key.high
    if key.default is not None:
        out["default"] = key.default
    return out


def section_schema(name: str, keys: dict[str, Key]) -> dict[str, Any]:
    """A section: a table of exactly these keys."""
    out: dict[str, Any] = {
        "description": SECTION_HELP.get(name, ""),
        "type": "object",
        "properties": {key: key_schema(k) for key, k in keys.items()},
        "additionalProperties": False,
    }
    required = [key for key, k in keys.items() if k.required]
    if required:
        out["required"] = required
    return out


def axis_schema() -> dict[str, Any]:
    """[axis]: the common keys, every family's keys, and per family (``if`` curve is it)
    its required keys and no other family's."""
    properties: dict[str, Any] = {key: key_schema(k) for key, k in AXIS_COMMON.items()}
    for family, keys in FAMILY_KEYS.items():
        for key, k in keys.items():
            if key in properties:  # a name several families use (a, k): any of their types
                merged = properties[key]
                merged["description"] += f"; {family}: {k.help}"
                if key_schema(k)["type"] not in _types(merged):
                    merged["type"] = [*_types(merged), key_schema(k)["type"]]
                for bound in ("exclusiveMinimum", "minimum", "exclusiveMaximum", "maximum"):
                    if merged.get(bound) != key_schema(k).get(bound):
                        merged.pop(bound, None)  # the family's own range is in its branch below
            else:
                properties[key] = key_schema(k)
                properties[key]["description"] = f"{family}: {k.help}"
    branches = []
    for family, keys in FAMILY_KEYS.items():
        allowed = [*AXIS_COMMON, *keys]
        branches.append(
            {
                "if": {"properties": {"curve": {"const": family}}, "required": ["curve"]},
                "then": {
                    "properties": {key: key_schema(k) for key, k in keys.items()},
                    "required": [key for key, k in {**AXIS_COMMON, **keys}.items() if k.required],
                    "propertyNames": {"enum": allowed},
                },
            }
        )
    return {
        "description": SECTION_HELP["axis"],
        "type": "object",
        "properties": properties,
        "required": [key for key, k in AXIS_COMMON.items() if k.required],
        "additionalProperties": False,
        "allOf": branches,
    }


def _types(schema: dict[str, Any]) -> list[str]:
    kind = schema["type"]
    return list(kind) if isinstance(kind, list) else [kind]


def spec_schema() -> dict[str, Any]:
    """The JSON Schema of a spec file (as TOML parses it)."""
    sections = {
        "axis": axis_schema(),
        "tube": section_schema("tube", TUBE_KEYS),
        "host": section_schema("host", HOST_KEYS),
    }
    sections.update({name: section_schema(name, keys) for name, keys in EXTRA_SECTIONS.items()})
    for name, keys in ARRAY_SECTIONS.items():  # [[name]]: an array of tables of these keys
        sections[name] = {
            "description": SECTION_HELP.get(name, ""),
            "type": "array",
            "items": section_schema(name, keys),
            "minItems": 1,
        }
    return {
        "$schema": SCHEMA_DIALECT,
        "title": "tubecad spec",
        "description": "A tube parameterised by its lines of curvature (tubecad's spec files, "
        "docs/spec-files.md). Made by `tubecad schema` from the spec checker's key tables.",
        "type": "object",
        "properties": sections,
        "additionalProperties": False,
        "oneOf": [  # a tube ([axis] and [tube]), or a face the user has ([host] and its sections)
            {"required": ["axis", "tube"], "not": {"required": ["host"]}},
            {
                "required": ["host"],
                "propertyNames": {"enum": ["host", *HOST_SECTIONS]},
            },
        ],
    }


def schema_text() -> str:
    """The schema as ``tubecad schema`` prints it: indented JSON, one trailing newline."""
    return json.dumps(spec_schema(), indent=2) + "\n"
