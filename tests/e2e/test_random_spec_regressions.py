"""Regressions found by the random-spec run (benchmarks/random_specs.py, issue 24): each spec
here is a case the run generated, named by its index (seed 2026), that a regular tube once
failed. Judged as the run judges: the file written by ``export_build``, read back by OCCT's
own STEP reader and checked by BRepCheck, or a refusal that names its key in one line and
leaves no file."""

import re

import build123d as bd
import pytest

from tubecad.spec import build_spec, export_build, parse_spec

#: case 852: a log spiral ~1.2e6 from the origin (radius 8.3e4); STEP holds its coordinates
#: to 6e-7, more than the 1e-7 edge tolerance, and the file once read back invalid
FAR_SPIRAL = {
    "axis": {"curve": "log_spiral", "a": 13.096241759632093, "beta_deg": 33.21264078914237,
             "s": [1456286.9709085613, 2071668.0097897588]},
    "tube": {"radius": 82719.48268952969},
    "layout": {"rings": 17, "stringers": 3},
    "fit": {"tolerance": 1.4151498825510724e-05},
}  # fmt: skip


#: case 160: a custom-k axis out to 2.4e6 with T stiffeners; the wall read back with
#: curves off their faces by more than STEP's 13 digits let the reader heal
FAR_STIFFENED = {
    "axis": {"curve": "custom", "k": "-1.2541116169954406e-07 + 1.2492576298813113e-06 * sin(s / 304161.14033246425)",
             "beta_deg": -24.979192854947158, "s": [0.0, 2426418.5475701806]},
    "tube": {"radius": 288051.3763843929},
    "layout": {"rings": 2, "stringers": 2},
    "wall": {"thickness": 41.83670415555127, "side": "outside"},
    "fit": {"tolerance": 4.269143820261901e-09},
    "stiffeners": {"profile": "T", "height": 104988.69636893456, "thickness": 10065.175406129943, "side": "inside",
                   "rings": [0, 1], "stringers": [0], "flange_width": 37135.846107815894,
                   "flange_thickness": 17736.676877079335},
}  # fmt: skip


def read_step(path):
    """The file as OCCT's plain STEP reader (what FreeCAD's importer calls) gives it."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    return reader.OneShape()


def declared_uncertainty(path) -> float:
    """The file's UNCERTAINTY_MEASURE_WITH_UNIT, the precision its reader heals to."""
    text = "".join(path.read_text().split())
    found = re.search(r"UNCERTAINTY_MEASURE_WITH_UNIT\(LENGTH_MEASURE\(([-+0-9.eE]+)\)", text)
    assert found, "the file declares no uncertainty"
    return float(found.group(1))


def written_poles(shape) -> list:
    """Every B-spline face's poles, in the order the faces come."""
    from OCP.BRep import BRep_Tool

    out = []
    for face in bd.Shape.cast(shape).faces():
        surface = BRep_Tool.Surface_s(face.wrapped)
        if hasattr(surface, "NbUPoles"):
            out.append(
                [
                    surface.Pole(i, j).Coord()
                    for i in range(1, surface.NbUPoles() + 1)
                    for j in range(1, surface.NbVPoles() + 1)
                ]
            )
    return out


def test_a_tube_a_million_units_from_the_origin_reads_back_valid_and_to_the_bit(tmp_path):
    """Coordinates of 1.2e6, written with 17 digits (tubecad.export.cad.FILE_REAL): every pole
    reads back as the double that was built, so the reader heals nothing and the solid is
    valid at OCCT's default uncertainty. With 13 digits the file held them to 6e-7 and the
    solid read back failed BRepCheck unless the file declared a larger uncertainty."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    out = tmp_path / "far.step"
    built = build_spec(parse_spec(FAR_SPIRAL, base=tmp_path))
    export_build(built, [out])
    shape = read_step(out)
    assert len(bd.Shape.cast(shape).solids()) == 1 and BRepCheck_Analyzer(shape).IsValid()
    largest = max(abs(c) for v in bd.Shape.cast(shape).vertices() for c in tuple(v))
    assert largest > 1e6 and declared_uncertainty(out) == pytest.approx(1e-7)
    assert sorted(written_poles(shape)) == sorted(written_poles(built.build.shape.wrapped))


def test_a_stiffened_wall_far_from_the_origin_is_written_and_reads_back_valid(tmp_path):
    """Case 160 (coordinates of 2.4e6): refused by STEP's 13 digits once (the curves read
    back off their faces); 17 digits write it as built, every solid valid."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    out = tmp_path / "out.step"
    export_build(build_spec(parse_spec(FAR_STIFFENED, base=tmp_path)), [out])
    solids = bd.Shape.cast(read_step(out)).solids()
    assert len(solids) == 1 + 3 and all(BRepCheck_Analyzer(s.wrapped).IsValid() for s in solids)


def test_a_tolerance_13_digits_could_not_hold_is_held(tmp_path):
    """Case 372's spiral, 1.4e6 from the origin, asked to 8.9e-9: 13 digits held it to ~3e-7
    and the file was refused; 17 digits hold it, measured on the file read back."""
    spec = {
        "axis": {"curve": "log_spiral", "a": 6.630459677303902, "beta_deg": 34.449492404917436,
                 "s": [1406282.1490043416, 1867264.7302146365]},
        "tube": {"radius": 33380.51919559474},
        "layout": {"rings": 3, "stringers": 4},
        "wall": {"thickness": 9.10813946402632, "side": "inside"},
        "fit": {"tolerance": 8.864490417342323e-09},
    }  # fmt: skip
    out = tmp_path / "out.step"
    info = export_build(build_spec(parse_spec(spec, base=tmp_path)), [out])[str(out)]
    assert info["valid"] and info["max_deviation"] <= spec["fit"]["tolerance"]
    assert info["max_orthogonality_error"] <= info["orthogonality_target"]


def test_a_ring_frame_far_from_the_origin_is_a_valid_solid(tmp_path):
    """A spiral ~4e7 from its pole at tolerance 1.8e-5: the ring frame's circle lies up to a
    few 1e-7 off the fitted face, more than the default vertex tolerance, and OCCT refused
    the frame's edge (DifferentsPointAndParameter); its vertices now cover that gap."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    s0, s1 = 9785567.727725346, 41276674.0684289
    spec = {
        "axis": {"curve": "log_spiral", "a": 13.689946032501954, "beta_deg": 17.578421444392987, "s": [s0, s1]},
        "tube": {"radius": 450445.781643199},
        "layout": {"s_rings": [s0 + 40 / 58 * (s1 - s0)], "stringers": 2},
        "wall": {"thickness": 3505.0227688947143, "side": "outside"},
        "fit": {"tolerance": 1.847546133665053e-05},
        "stiffeners": {"profile": "flat", "height": 176084.95829032845, "thickness": 6528.60816126214,
                       "side": "outside", "rings": [1]},
    }  # fmt: skip
    built = build_spec(parse_spec(spec, base=tmp_path))
    solids = bd.Shape.cast(built.shape.wrapped if hasattr(built.shape, "wrapped") else built.shape).solids()
    assert len(solids) == 2 and all(BRepCheck_Analyzer(s.wrapped).IsValid() for s in solids)


#: case 13 of the run with the file checks (issue 24, cases 0-159): a helix canal wall fitted
#: to 7.7e-6; its ring circles lay up to ~the fit tolerance from the fitted faces, which the
#: STEP file does not carry (the reader gives 1e-7); the fit is now exact at the rings
COARSE_CANAL = {
    "axis": {"curve": "helix", "k": -0.0005695901138823759, "beta_deg": -18.72905333378926,
             "s": [0.0, 2885.354474665675]},
    "tube": {"radius": "143.94783385865816 * (1 + 0.10002080918590711 * sin(2 * pi * s / 4550.408715790109"
                       " + 5.963011042274367))"},
    "layout": {"rings": 5, "stringers": 11},
    "wall": {"thickness": 3.5298741152742754, "side": "inside"},
    "fit": {"tolerance": 7.709762775632542e-06},
}  # fmt: skip


def test_a_coarse_canal_wall_reads_back_clean_by_the_pre_boolean_check(tmp_path):
    from tubecad.brep.properties import analyzer_findings

    out = tmp_path / "canal.step"
    export_build(build_spec(parse_spec(COARSE_CANAL, base=tmp_path)), [out])
    found = {}
    for solid in bd.Shape.cast(read_step(out)).solids():
        found.update(analyzer_findings(solid.wrapped, ("CurveOnSurfaceMode",)))
    assert found == {}
