"""[units] length and the JSON Schema of spec files (issue 5), from the command line.

- ``tubecad schema`` prints (or writes) the shipped schema, loading neither numpy nor OCCT.
- The spec's length unit is written into STEP, IGES, DXF, 3MF and glTF without rescaling the
  model: read back in millimetres, a file in metres is 1000 times the same numbers in mm.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import zipfile
from pathlib import Path
from types import SimpleNamespace

import pytest
from click.testing import CliRunner
from conftest import ROOT
from shared.schema_units import SMALL, STIFFENED, with_units

from tubecad.cli.app import cli
from tubecad.core.units import LENGTH_UNITS
from tubecad.spec.schema import schema_text, spec_schema

SHIPPED = ROOT / "samples" / "tubecad-spec.schema.json"


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_shipped_schema_is_what_tubecad_schema_prints(tmp_path):
    printed = run("schema")
    assert printed.exit_code == 0, printed.output
    assert printed.output == schema_text() == SHIPPED.read_text(encoding="utf-8")
    assert json.loads(printed.output) == spec_schema()
    written = run("schema", "-o", tmp_path / "s.json")
    assert written.exit_code == 0 and written.output.strip() == str(tmp_path / "s.json")
    assert (tmp_path / "s.json").read_text(encoding="utf-8") == schema_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.json"]  # no temporary left


def test_schema_to_a_missing_folder_exits_2_with_one_line(tmp_path):
    result = run("schema", "-o", tmp_path / "missing" / "s.json")
    assert result.exit_code == 2
    assert result.output.strip().count("\n") == 0 and "does not exist" in result.output
    assert not (tmp_path / "missing").exists()


def test_schema_command_loads_neither_numpy_nor_occt():
    code = (
        "import sys\nfrom tubecad.cli.app import cli\ntry:\n    cli.main(['schema'], standalone_mode=False)\n"
        "except SystemExit:\n    pass\n"
        "print('LOADED', sorted(m for m in ('numpy', 'OCP', 'build123d') if m in sys.modules))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout.rsplit("LOADED", 1)[0])["title"] == "tubecad spec"
    assert done.stdout.strip().splitlines()[-1] == "LOADED []"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The same numbers built in mm (no [units]), m and in: STEP, IGES, glTF, 3MF, polylines, report."""
    out = {}
    folder = tmp_path_factory.mktemp("units")
    for unit in ("mm", "m", "in"):
        spec = folder / f"{unit}.toml"
        spec.write_text(with_units(SMALL, None if unit == "mm" else unit))
        files = {ext: folder / f"{unit}.{ext}" for ext in ("step", "iges", "glb", "3mf", "json")}
        args = [
            "build",
            spec,
            *sum((["-o", p] for p in files.values()), []),
            "--report",
            folder / f"{unit}.report.json",
        ]
        result = run(*args)
        assert result.exit_code == 0, result.output
        out[unit] = SimpleNamespace(**files, report=json.loads((folder / f"{unit}.report.json").read_text()))
    return out


def box(shape) -> list[float]:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    b = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, b, False, False)  # the exact geometry's box (enlarged by OCCT's 1e-7)
    lo, hi = b.CornerMin(), b.CornerMax()
    return [hi.X() - lo.X(), hi.Y() - lo.Y(), hi.Z() - lo.Z()]


@pytest.mark.slow
def test_step_states_the_unit_and_keeps_the_numbers(built):
    from tubecad.brep import properties as props
    from tubecad.export.cad import import_shape

    units = {u: [ln for ln in b.step.read_text().splitlines() if "LENGTH_UNIT()" in ln] for u, b in built.items()}
    assert any("SI_UNIT(.MILLI.,.METRE.)" in ln for ln in units["mm"])
    assert any("SI_UNIT($,.METRE.)" in ln for ln in units["m"]) and not any(".MILLI." in ln for ln in units["m"])
    assert any("CONVERSION_BASED_UNIT('INCH'" in ln for ln in units["in"])
    text = "".join(built["in"].step.read_text().split())  # the writer wraps its lines anywhere
    factor = re.search(r"LENGTH_MEASURE_WITH_UNIT\((?:LENGTH_MEASURE\()?([-+0-9.E]+)[),]", text)
    assert factor and float(factor[1]) == 25.4
    mm = import_shape(built["mm"].step)
    for unit, factor in (("m", 1000.0), ("in", 25.4)):
        # read in millimetres (OCCT's default): the same numbers, 1000 (25.4) times larger
        assert box(import_shape(built[unit].step, "mm")) == pytest.approx([factor * x for x in box(mm)], rel=1e-8)
        assert props.volume(import_shape(built[unit].step)) == pytest.approx(factor**3 * props.volume(mm), rel=1e-9)
        # read in the model's own unit: the numbers as written (nothing was rescaled)
        assert box(import_shape(built[unit].step, unit)) == pytest.approx(box(mm), rel=1e-12)
    assert built["m"].report["exports"][str(built["m"].step)]["max_deviation"] < 1e-8  # read back in m, on the tube


@pytest.mark.slow
def test_build123d_reads_a_metre_step_in_millimetres(built):
    import build123d as bd

    size_mm, size_m = (bd.import_step(built[u].step).bounding_box().size for u in ("mm", "m"))
    assert size_m.X == pytest.approx(1000 * size_mm.X, rel=1e-6) and size_m.Z == pytest.approx(
        1000 * size_mm.Z, rel=1e-6
    )


def iges_global(path: Path) -> list[str]:
    """The IGES global section's parameters (delimiters ',' and ';', Hollerith strings decoded)."""
    text = "".join(ln[:72] for ln in path.read_text().splitlines() if len(ln) >= 73 and ln[72] == "G")
    params, i, current = [], 0, ""
    while i < len(text):
        m = re.match(r"(\d+)H", text[i:])
        if m and not current.strip():
            n = int(m.group(1))
            start = i + len(m.group(0))
            current, i = text[start : start + n], start + n
            continue
        if text[i] in ",;":
            params.append(current.strip())
            current = ""
            if text[i] == ";":
                break
        else:
            current += text[i]
        i += 1
    return params


@pytest.mark.slow
def test_iges_global_section_states_the_unit(built):
    from tubecad.export.cad import import_shape

    for unit, (flag, name) in {"mm": ("2", "MM"), "m": ("6", "M"), "in": ("1", "INCH")}.items():
        params = iges_global(built[unit].iges)
        assert (params[13], params[14]) == (flag, name), params[:20]  # parameters 14 and 15
        assert int(flag) == LENGTH_UNITS[unit].iges_flag
    mm = box(import_shape(built["mm"].iges))
    assert box(import_shape(built["m"].iges, "mm")) == pytest.approx([1000 * x for x in mm], rel=1e-7)
    assert box(import_shape(built["in"].iges, "in")) == pytest.approx(mm, rel=1e-7)


@pytest.mark.slow
def test_meshes_polylines_and_report_state_the_unit(built):
    import struct

    def glb_max(path: Path) -> float:  # glTF is in metres: the largest coordinate of its meshes
        data = path.read_bytes()
        length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20 : 20 + length])
        return max(abs(v) for a in doc["accessors"] if len(a.get("max", [])) == 3 for v in a["max"] + a["min"])

    assert glb_max(built["m"].glb) == pytest.approx(1000 * glb_max(built["mm"].glb), rel=1e-5)
    assert glb_max(built["in"].glb) == pytest.approx(25.4 * glb_max(built["mm"].glb), rel=1e-5)
    for unit, name in (("mm", "millimeter"), ("m", "meter"), ("in", "inch")):
        with zipfile.ZipFile(built[unit].__dict__["3mf"]) as archive:
            model = archive.read("3D/3dmodel.model").decode()
        assert re.search(r'<model[^>]* unit="(\w+)"', model).group(1) == name
        assert json.loads(built[unit].json.read_text())["units"] == unit
        report = built[unit].report
        assert report["units"] == {"length": unit}
        assert report["brep"]["volume"] == pytest.approx(built["mm"].report["brep"]["volume"], rel=1e-12)
        for info in report["exports"].values():  # every file read back in the model's unit, on the tube
            assert info.get("max_deviation", 0) < 1e-8 and info.get("max_vertex_deviation", 0) < info.get(
                "deflection", 1
            )


@pytest.mark.slow
def test_dxf_flat_patterns_state_the_unit(tmp_path):
    import ezdxf

    first = {}
    for unit, (insunits, measurement) in {"mm": (4, 1), "m": (6, 1), "in": (1, 0), "ft": (2, 0)}.items():
        spec = tmp_path / f"{unit}.toml"
        spec.write_text(with_units(STIFFENED.replace("rings = [1]", "rings = [1]\nstringers = [0]"), unit))
        result = run("flat", spec, "-o", tmp_path / unit)
        assert result.exit_code == 0, result.output
        doc = ezdxf.readfile(tmp_path / unit / "webs.dxf")
        assert doc.units == insunits == LENGTH_UNITS[unit].dxf
        assert (doc.header["$INSUNITS"], doc.header["$MEASUREMENT"]) == (insunits, measurement)
        assert json.loads((tmp_path / unit / "flat.json").read_text())["units"] == {"length": unit}
        first[unit] = [tuple(p) for e in doc.modelspace() if e.dxftype() == "CIRCLE" for p in [(e.dxf.radius,)]]
    assert first["m"] == first["mm"] == first["in"]  # the numbers as in the spec: nothing rescaled


def test_bad_units_exit_2_with_one_line_and_write_nothing(tmp_path):
    spec = tmp_path / "bad.toml"
    spec.write_text(with_units(SMALL, "km"))
    out = tmp_path / "out"
    out.mkdir()
    for args in (
        ["build", spec, "-o", out / "x.step", "--report", out / "r.json"],
        ["report", spec],
        ["flat", spec, "-o", out / "flat"],
    ):
        result = run(*args)
        assert result.exit_code == 2, result.output
        lines = result.output.strip().splitlines()
        assert len(lines) == 1, lines
        assert "[units] length must be one of mm, cm, m, in, ft, got 'km'" in lines[0]
    assert list(out.iterdir()) == []


@pytest.mark.slow
def test_a_batch_sweeps_the_unit(tmp_path):
    spec = tmp_path / "small.toml"
    spec.write_text(SMALL)
    out = tmp_path / "out"
    result = run("build", spec, "--sweep", 'units.length="mm","m"', "-d", out, "-f", "step", "-j", 1)
    assert result.exit_code == 0, result.output
    steps = {p.stem: p.read_text() for p in out.glob("*.step")}
    assert "SI_UNIT(.MILLI.,.METRE.)" in steps["small_length-mm"] and "SI_UNIT($,.METRE.)" in steps["small_length-m"]
    assert json.loads((out / "small_length-m.report.json").read_text())["units"] == {"length": "m"}
