"""[units] length and the JSON Schema of spec files (issue 5).

- The schema (``tubecad schema``) is valid draft 2020-12, every sample and README spec
  validates, and the bad specs the checker refuses are refused by the schema too where a
  schema can say so; every range and choice the schema states is one the checker enforces.
- The spec's length unit: the stiffeners' density is per cubic unit, and a spec without
  [units] is in millimetres. The files written in that unit (STEP, IGES, DXF, 3MF, glTF) are
  checked from the command line in tests/e2e/test_cli_schema_units.py.
"""

from __future__ import annotations

import copy
import math
import re
import tomllib
from types import SimpleNamespace

import pytest
from conftest import ROOT
from jsonschema import Draft202012Validator
from shared.schema_units import SMALL, STIFFENED, with_units

from tubecad import SpecError
from tubecad.core.units import steel_density
from tubecad.spec.parse import ARRAY_SECTIONS, AXIS_COMMON, EXTRA_SECTIONS, FAMILY_KEYS, TUBE_KEYS, parse_spec
from tubecad.spec.schema import SCHEMA_DIALECT, spec_schema

SAMPLES = sorted((ROOT / "samples").glob("*.toml"))
VALIDATOR = Draft202012Validator(spec_schema())


def schema_errors(data: dict) -> list[str]:
    return [f"{list(e.absolute_path)}: {e.message}" for e in VALIDATOR.iter_errors(data)]


def readme_specs() -> list[dict]:
    """The spec blocks of the README and of the docs' pages."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    text = "\n".join(page.read_text(encoding="utf-8") for page in pages)
    return [tomllib.loads(block) for block in re.findall(r"^```toml\n(.*?)^```", text, re.S | re.M)]


# ---------------------------------------------------------------------------------------------
# the schema


def test_schema_is_valid_draft_2020_12():
    schema = spec_schema()
    Draft202012Validator.check_schema(schema)
    assert schema["$schema"] == SCHEMA_DIALECT == "https://json-schema.org/draft/2020-12/schema"
    assert schema["additionalProperties"] is False
    tube, host = schema["oneOf"]  # a tube ([axis] and [tube]) or a face the user has ([host])
    assert tube["required"] == ["axis", "tube"] and host["required"] == ["host"]
    sections = schema["properties"]
    assert set(sections) == {"axis", "tube", "host", *EXTRA_SECTIONS, *ARRAY_SECTIONS}
    # an array section ([[branches]]) is an array of such tables
    assert all((s.get("items") or s)["additionalProperties"] is False for s in sections.values())
    assert sections["branches"]["type"] == "array" and sections["branches"]["items"]["required"] == [
        "at",
        "length",
        "radius",
    ]
    # descriptions are the checker's help; the units key names its choices and default
    assert sections["tube"]["properties"]["radius"]["description"] == TUBE_KEYS["radius"].help
    assert sections["units"]["properties"]["length"]["enum"] == ["mm", "cm", "m", "in", "ft"]
    assert sections["units"]["properties"]["length"]["default"] == "mm"


@pytest.mark.parametrize("path", SAMPLES, ids=lambda p: p.stem)
def test_every_sample_validates_and_points_at_the_shipped_schema(path):
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    assert schema_errors(data) == []
    parse_spec(data, str(path), path.parent)  # and the checker takes it
    first = path.read_text(encoding="utf-8").splitlines()[0]
    assert first == "#:schema ./tubecad-spec.schema.json"  # taplo / Even Better TOML's directive
    assert (path.parent / first.split()[1]).is_file()


def test_readme_specs_validate():
    specs = readme_specs()
    assert specs and any("units" in s for s in specs)
    for data in specs:
        assert schema_errors(data) == []


# ---------------------------------------------------------------------------------------------
# bad specs: refused by the checker and by the schema


def sample_data(curve: str) -> dict:
    for path in SAMPLES:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        if data.get("axis", {}).get("curve") == curve:
            return data
    raise AssertionError(f"no sample of {curve}")


#: the docs' full spec (docs/spec-files.md): every section and key
FULL = next(s for s in readme_specs() if set(s) >= {"wall", "stiffeners", "panels", "units"})

FAKE_BUILD = SimpleNamespace(layout=SimpleNamespace(s_rings=list(range(11)), stringers_deg=list(range(8))))


def checker_message(data: dict) -> str:
    """The checker's one-line message for ``data``: the spec check and, for [stiffeners], the
    profile and density check of the build (run on a stand-in layout, nothing is built)."""
    from tubecad.spec.build import stiffener_selection

    with pytest.raises(SpecError) as caught:
        spec = parse_spec(data, "bad.toml")
        if "stiffeners" in spec.sections:
            stiffener_selection(spec, FAKE_BUILD)
    message = str(caught.value)
    assert "\n" not in message
    return message


def edit(base: dict, change) -> dict:
    data = copy.deepcopy(base)
    change(data)
    return data


BAD = {
    "unknown_section": (FULL, lambda d: d.update(colour={"name": "red"}), "unknown section [colour]"),
    "section_not_a_table": (FULL, lambda d: d.update(units="mm"), "[units] must be a table"),
    "missing_section": (FULL, lambda d: d.pop("tube"), "missing section [tube]"),
    "unknown_key": (FULL, lambda d: d["tube"].update(radus=1.0), "unknown key [tube] radus"),
    "unknown_units_key": (FULL, lambda d: d["units"].update(angle="deg"), "unknown key [units] angle"),
    "wrong_type": (FULL, lambda d: d["tube"].update(radius=True), "[tube] radius must be a number"),
    "bool_as_number": (
        FULL,
        lambda d: d["tube"].update(allow_irregular=1),
        "[tube] allow_irregular must be true or false",
    ),
    "three_numbers_for_a_pair": (FULL, lambda d: d["axis"].update(s=[1.0, 2.0, 3.0]), "[axis] s must be a list of two"),
    "selection_word": (FULL, lambda d: d["stiffeners"].update(rings="some"), "[stiffeners] rings must be a list"),
    "missing_required": (FULL, lambda d: d["tube"].pop("radius"), "[tube] radius is missing"),
    "missing_family_key": (FULL, lambda d: d["axis"].pop("a"), "[axis] a is missing"),
    "another_familys_key": (FULL, lambda d: d["axis"].update(A=3.0), "unknown key [axis] A"),
    "custom_k_as_number": (sample_data("custom"), lambda d: d["axis"].update(k=0.01), "[axis] k must be a string"),
    "helix_k_as_text": (sample_data("helix"), lambda d: d["axis"].update(k="0.01"), "[axis] k must be a number"),
    "bad_curve": (FULL, lambda d: d["axis"].update(curve="spiral"), "[axis] curve must be one of log_spiral | helix"),
    "bad_units": (
        FULL,
        lambda d: d["units"].update(length="km"),
        "[units] length must be one of mm, cm, m, in, ft, got 'km'",
    ),
    "units_as_number": (FULL, lambda d: d["units"].update(length=1000), "[units] length must be a string"),
    "units_in_capitals": (FULL, lambda d: d["units"].update(length="MM"), "[units] length must be one of mm, cm"),
    "wall_side": (
        FULL,
        lambda d: d["wall"].update(side="middle"),
        "[wall] side must be one of centered, inside, outside",
    ),
    "profile": (FULL, lambda d: d["stiffeners"].update(profile="I"), "[stiffeners] profile must be one of flat, T, L"),
    "stiffener_side": (
        FULL,
        lambda d: d["stiffeners"].update(side="under"),
        "[stiffeners] side must be one of outside, inside",
    ),
}


@pytest.mark.parametrize("name", BAD)
def test_bad_spec_is_refused_by_the_checker_and_the_schema(name):
    base, change, says = BAD[name]
    assert schema_errors(base) == []
    data = edit(base, change)
    assert says in checker_message(data)
    assert schema_errors(data), f"the schema accepts {name}"


def ranged_keys():
    """(section, key, Key, base spec) for every key the schema gives a range."""
    out = []
    for family, keys in FAMILY_KEYS.items():
        out += [
            ("axis", key, k, sample_data(family)) for key, k in keys.items() if k.low is not None or k.high is not None
        ]
    for section, keys in {"axis": AXIS_COMMON, "tube": TUBE_KEYS, **EXTRA_SECTIONS}.items():
        out += [(section, key, k, FULL) for key, k in keys.items() if k.low is not None or k.high is not None]
    return out


def outside(k) -> list[float]:
    """Values just outside the key's range: the open ends themselves, just past the closed ones."""
    step = 1 if k.kind == "integer" else None
    values = []
    if k.low is not None:
        values.append(
            k.low if k.low_open else (k.low - step if step else k.low * (1 - 1e-3) if k.low > 0 else k.low - 1e-3)
        )
    if k.high is not None:
        values.append(k.high if k.high_open else (k.high + step if step else k.high * (1 + 1e-3)))
    return values


@pytest.mark.parametrize("section, key, k, base", ranged_keys(), ids=lambda v: v if isinstance(v, str) else "")
def test_every_range_the_schema_states_is_one_the_checker_enforces(section, key, k, base):
    for value in outside(k):
        data = edit(base, lambda d: d[section].update({key: value}))
        message = checker_message(data)
        assert f"[{section}]" in message and key in message, message
        assert schema_errors(data), f"the schema accepts [{section}] {key} = {value}"


def test_the_schema_limits_are_the_rules_own():
    from tubecad.brep.layout import MAX_RINGS, MAX_STRINGERS
    from tubecad.core.tolerance import MIN_SIZE
    from tubecad.core.validation import MAX_LENGTH

    layout, tube = EXTRA_SECTIONS["layout"], TUBE_KEYS
    assert (layout["rings"].high, layout["stringers"].high) == (MAX_RINGS, MAX_STRINGERS)
    assert (tube["radius"].low, tube["radius"].high, EXTRA_SECTIONS["wall"]["thickness"].low) == (
        MIN_SIZE,
        MAX_LENGTH,
        MIN_SIZE,
    )
    # the values just inside are taken by both
    data = edit(
        FULL,
        lambda d: (
            d["layout"].update(rings=2, stringers=1000),
            d["stiffeners"].update(rings=[1]),
            d["panels"].update(rings=[0, 1]),
        ),
    )
    parse_spec(data)
    assert schema_errors(data) == []


# ---------------------------------------------------------------------------------------------
# units in the files


@pytest.mark.slow
def test_density_is_per_cubic_unit_and_the_default_steel_is_converted():
    from tubecad.spec.build import build_and_export

    reports = {u: build_and_export(parse_spec(tomllib.loads(with_units(STIFFENED, u)), u), []) for u in ("mm", "m")}
    mm, m = reports["mm"]["stiffeners"], reports["m"]["stiffeners"]
    assert (mm["density"], mm["density_unit"]) == (7.85e-6, "kg/mm^3")
    assert (m["density"], m["density_unit"]) == (7850.0, "kg/m^3")
    assert m["stiffeners"][0]["volume"] == pytest.approx(mm["stiffeners"][0]["volume"], rel=1e-12)  # same numbers
    assert m["total_stiffener_mass_kg"] == pytest.approx(1e9 * mm["total_stiffener_mass_kg"], rel=1e-12)
    assert steel_density("in") == pytest.approx(7850 * 0.0254**3, rel=1e-11)
    # a density given in the spec is taken as it is, per cubic unit
    given = build_and_export(parse_spec(tomllib.loads(with_units(STIFFENED + "density = 1000.0\n", "m"))), [])
    assert given["stiffeners"]["total_stiffener_mass_kg"] == pytest.approx(
        1000.0 * m["stiffeners"][0]["volume"], rel=1e-12
    )


def test_spec_without_units_is_in_millimetres():
    spec = parse_spec(tomllib.loads(SMALL))
    assert spec.length_unit == "mm" and "units" not in spec.sections
    assert math.isclose(steel_density(spec.length_unit), 7.85e-6, rel_tol=0)
