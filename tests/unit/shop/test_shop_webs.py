"""Cuttable web pieces and their nesting on plates (issue 13).

The expected values are measured independently: the 3-D web is the strip of normals along
the line, which on a tube is the family of tubes of radius rho between R and R -+ h at the
same angle (docs/MATH.md section 9), so its base length and area are quadratures of
polylines of CurvatureLineTube.points; overlaps and distances are shapely's, on the DXF as
ezdxf reads it back.
"""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from shapely.geometry import Point, Polygon, box

from tubecad import CurvatureLineTube
from tubecad.brep import build_wall_solid
from tubecad.brep.properties import analyzer_findings, is_valid, volume
from tubecad.core.errors import ParameterError
from tubecad.shop.drawings import write_plate_dxf, write_plate_svg
from tubecad.shop.fabrication import fabrication_settings
from tubecad.shop.nesting import check_nesting, nest
from tubecad.shop.webs import piece_names, piece_solids, ring_pieces, stringer_pieces
from tubecad.spec.paper import PAPER_LAYOUT, PAPER_STRINGER_PROFILE, PAPER_WALL_THICKNESS, paper_stiffeners, paper_tube
from tubecad.stiffeners.assembly import build_stiffeners
from tubecad.stiffeners.flat import stringer_flat_pattern
from tubecad.stiffeners.profiles import Profile


@pytest.fixture(scope="module")
def paper():
    tube = paper_tube()
    build = build_wall_solid(tube, PAPER_WALL_THICKNESS, "centered", PAPER_LAYOUT(tube))
    # the paper's stiffeners (stringers at 0 and 180 deg) and the same stringers at 90 and 270
    # deg, whose webs cross themselves flat (issue 41: why `tubecad paper` leaves them out)
    crossing = build_stiffeners(build, [], [2, 6], Profile(*PAPER_STRINGER_PROFILE), "inside")
    return build, {st.name: st for st in paper_stiffeners(build) + crossing}


def web_measures(st, span, points=200_001):
    """(base length, area) of the 3-D web of stringer ``st`` over ``span``: the polyline
    length of the line at radius rho is linear in rho (|S_s| = 1 - rho kappa_u), so the area
    between rho = R and R -+ h is h times the mean of the two lengths."""
    s = np.linspace(*span, points)
    theta = math.radians(st.value)
    sign = 1.0 if st.side == "outside" else -1.0

    def length(rho):
        p = CurvatureLineTube(st.base.axis, rho, allow_irregular=True).points(theta, s)
        return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())

    base, top = length(st.base.radius), length(st.base.radius + sign * st.profile.height)
    return base, st.profile.height * (base + top) / 2


@pytest.mark.parametrize("name", ["stringer_02", "stringer_06"])
def test_paper_webs_that_cross_themselves_are_split_into_simple_pieces(paper, name):
    """The issue's finding: the whole webs of stringer_02 and _06 are not simple polygons;
    split, every piece is, and the pieces' areas and base lengths are the 3-D web's."""
    _, stiffeners = paper
    st = stiffeners[name]
    whole = stringer_flat_pattern(st.base, st.value, st.profile.height, st.side, st.name, samples=4001)
    assert not Polygon(whole.outline).is_valid
    pieces = stringer_pieces(st, fabrication_settings({"joint_gap": 0.0}))
    assert [p.name for p in pieces] == piece_names(name, len(pieces)) and len(pieces) >= 2
    assert pieces[0].span[0] == st.base.span[0] and pieces[-1].span[1] == st.base.span[1]
    for a, b in zip(pieces, pieces[1:]):
        assert a.span[1] == pytest.approx(b.span[0], abs=1e-9)  # no gap: they meet
    for piece in pieces:
        polygon = Polygon(piece.pattern.outline)
        assert polygon.is_valid and polygon.area == pytest.approx(piece.area, rel=1e-5)  # polygon of 1001 + 1001 points
        base, area = web_measures(st, piece.span)
        assert piece.pattern.base_length == pytest.approx(base, rel=1e-9)  # measured 9.4e-11 (the polyline's error)
        assert piece.area == pytest.approx(area, rel=1e-9)  # measured 9.4e-11
    assert sum(p.area for p in pieces) == pytest.approx(whole.area, rel=1e-12)


def test_joint_gap_is_laid_off_along_the_base_line(paper):
    _, stiffeners = paper
    st = stiffeners["stringer_02"]
    gap = 1.5
    pieces = stringer_pieces(st, fabrication_settings({"joint_gap": gap}))
    whole, _ = web_measures(st, st.base.span)
    total = sum(p.pattern.base_length for p in pieces)
    assert total + gap * (len(pieces) - 1) == pytest.approx(whole, rel=1e-9)
    for a, b in zip(pieces, pieces[1:]):
        between, _ = web_measures(st, (a.span[1], b.span[0]), 2001)
        assert between == pytest.approx(gap, rel=1e-9)
        assert a.joints[1] and b.joints[0]
    assert not pieces[0].joints[0] and not pieces[-1].joints[1]


@pytest.mark.slow
def test_chosen_joints_come_first_and_the_solids_are_split_there(paper):
    build, stiffeners = paper
    st = stiffeners["stringer_00"]
    fab = fabrication_settings({"joints": {"stringer_00": [640.0]}})
    pieces = stringer_pieces(st, fab)
    assert [p.name for p in pieces] == ["stringer_00_a", "stringer_00_b"]
    assert pieces[0].span == (200.0, pytest.approx(640.0, abs=1e-9)) and pieces[1].span[0] == pytest.approx(
        640.0, abs=1e-9
    )
    solids = piece_solids(st, pieces, build.tolerance)
    assert [s.name for s in solids] == ["stringer_00_a", "stringer_00_b"]
    for s in solids:
        assert is_valid(s.solid) and analyzer_findings(s.solid) == {}
    assert sum(volume(s.solid) for s in solids) == pytest.approx(volume(st.solid), rel=1e-9)


@pytest.mark.slow
def test_a_ring_too_large_for_the_plate_is_cut_into_sectors_in_2d_and_3d(paper):
    build, stiffeners = paper
    st = stiffeners["ring_03"]
    fab = fabrication_settings({"plate_size": [30.0, 20.0], "kerf": 0.5})  # the annulus is 28 across
    pieces = ring_pieces(st, fab, tuple(build.layout.stringers_deg))
    assert len(pieces) == 2 and all(p.joints == (True, True) for p in pieces)
    r_out, r_in = st.base.radius, st.base.radius - st.profile.height
    assert sum(p.area for p in pieces) == pytest.approx(math.pi * (r_out**2 - r_in**2), rel=1e-14)
    for p in pieces:
        assert Polygon(p.pattern.outline).is_valid
        assert p.span[1] - p.span[0] == pytest.approx(180.0, rel=1e-14)
    solids = piece_solids(st, pieces, build.tolerance)
    assert all(is_valid(s.solid) and analyzer_findings(s.solid) == {} for s in solids)
    assert sum(volume(s.solid) for s in solids) == pytest.approx(volume(st.solid), rel=1e-9)


def test_a_t_rings_web_plate_is_cut_up_to_its_flange(paper):
    """A T profile is two plates: the web up to the flange (h - tf) and the flange on it. The
    ring's web plate is the annulus from the wall's radius R to R - (h - tf) (inside), not to
    R - h, where it would overlap the flange plate by tf all round."""
    build, _ = paper
    h, tw, bf, tf = 6.0, 0.8, 4.0, 1.0
    (st,) = build_stiffeners(build, [3], [], Profile("T", h, tw, bf, tf), "inside")
    pieces = ring_pieces(st, fabrication_settings({}), tuple(build.layout.stringers_deg))
    r_out = st.base.radius
    r_in = r_out - (h - tf)
    assert sum(p.area for p in pieces) == pytest.approx(math.pi * (r_out**2 - r_in**2), rel=1e-14)


def dxf_parts(path):
    """The PARTS layer of a plate DXF as shapely polygons (circles as 720-gons), by ezdxf."""
    import ezdxf
    from ezdxf.path import make_path

    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    polygons = [
        Polygon([tuple(p)[:2] for p in make_path(e).flattening(1e-4)]) for e in msp.query('LWPOLYLINE[layer=="PARTS"]')
    ]
    circles = [
        Point(e.dxf.center.x, e.dxf.center.y).buffer(e.dxf.radius, 180) for e in msp.query('CIRCLE[layer=="PARTS"]')
    ]
    circles.sort(key=lambda c: (round(c.centroid.x, 6), round(c.centroid.y, 6), -c.area))
    for outer, inner in zip(circles[::2], circles[1::2]):  # each annulus: its two concentric circles
        polygons.append(outer.difference(inner))
    plate = next(iter(msp.query('LWPOLYLINE[layer=="PLATE"]')))
    return doc, polygons, Polygon([tuple(p)[:2] for p in plate.get_points()])


@pytest.mark.slow
def test_every_web_of_the_paper_nested_without_overlap(paper, tmp_path):
    _, stiffeners = paper
    fab = fabrication_settings({"plate_size": [700.0, 420.0], "kerf": 1.0})
    pieces = [
        p
        for st in stiffeners.values()
        for p in (stringer_pieces(st, fab) if st.kind == "stringer" else ring_pieces(st, fab))
    ]
    plates = nest(pieces, fab)
    report = check_nesting(plates, fab)
    assert report["valid"] and report["pieces"] == len(pieces)
    placed_area = 0.0
    for plate in plates:
        doc, polygons, sheet = dxf_parts(write_plate_dxf(plate, fab, tmp_path / f"{plate.name}.dxf"))
        assert doc.header["$INSUNITS"] == 4  # millimetres
        assert sheet.equals(box(0, 0, 700, 420))
        assert len(polygons) == len(plate.pieces)
        for i, polygon in enumerate(polygons):
            assert polygon.is_valid and sheet.contains(polygon)
            assert polygon.exterior.distance(sheet.exterior) >= fab.kerf - 1e-9
            for other in polygons[i + 1 :]:
                assert polygon.distance(other) >= 2 * fab.kerf - 1e-9  # measured: exactly 2 kerf where shelves touch
        placed_area += sum(p.area for p in polygons)
    assert placed_area / (len(plates) * 700 * 420) == pytest.approx(report["plate_utilisation"], rel=1e-4)
    used = sum(plate.used_size[0] * plate.used_size[1] for plate in plates)  # a plate less its offcut strip
    assert placed_area / used == pytest.approx(report["utilisation"], rel=1e-4)
    assert report["plate_utilisation"] <= report["utilisation"] <= 1.0


def test_the_svg_is_1_to_1_in_millimetres_without_axes(paper, tmp_path):
    _, stiffeners = paper
    fab = fabrication_settings({"plate_size": [700.0, 420.0], "kerf": 1.0, "joint_gap": 1.0})
    plates = nest(stringer_pieces(stiffeners["stringer_06"], fab), fab)
    root = ET.parse(write_plate_svg(plates[0], fab, tmp_path / "plate.svg")).getroot()
    ns = {"svg": "http://www.w3.org/2000/svg"}
    width = float(root.get("width").removesuffix("mm"))
    assert root.get("width").endswith("mm") and root.get("viewBox").split()[2] == f"{width:.6g}"
    groups = {g.get("id"): g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("id")}
    assert {"PLATE", "PARTS", "CUT", "JOINTS", "TEXT"} <= set(groups)
    names = [t.text for t in groups["TEXT"].findall("svg:text", ns)]
    assert {"stringer_06_a", "stringer_06_b"} <= set(names)
    plate_path = (
        groups["PLATE"].find("svg:path", ns).get("d").replace("M", "").replace("L", "").replace("Z", "").split()
    )
    xy = np.array(plate_path, dtype=float).reshape(-1, 2)
    assert np.ptp(xy, axis=0) == pytest.approx([700.0, 420.0], rel=1e-12)  # in the mm user units, scaled by 1
    joints = sum(sum(placed.piece.joints) for placed in plates[0].pieces)  # the butt-joint ends on this plate
    assert joints >= 1 and len(groups["JOINTS"].findall("svg:path", ns)) == joints


def test_a_plate_too_small_for_the_web_height_is_refused_naming_the_key(paper):
    _, stiffeners = paper
    with pytest.raises(ParameterError, match=r"^plate_size .* too small for stringer_00's web") as info:
        stringer_pieces(stiffeners["stringer_00"], fabrication_settings({"plate_size": [100.0, 2.1], "kerf": 0.1}))
    assert info.value.key == "plate_size"  # the library's own name; the spec adds [fabrication]
    with pytest.raises(ParameterError, match=r"joints.stringer_00: 100 is outside the stringer"):
        stringer_pieces(stiffeners["stringer_00"], fabrication_settings({"joints": {"stringer_00": [100.0]}}))
    with pytest.raises(ParameterError, match=r"joints.ring_03: 400 is outside the ring's angles"):
        ring_pieces(stiffeners["ring_03"], fabrication_settings({"joints": {"ring_03": [400.0]}}))


@pytest.mark.parametrize(
    "section, says, key",
    [
        ({"kerf": -1.0}, "kerf must be a finite number >= 0", "kerf"),
        ({"kerf": math.nan}, "kerf must be a finite number >= 0", "kerf"),
        ({"joint_gap": math.inf}, "joint_gap must be a finite number >= 0", "joint_gap"),
        ({"max_strain": 0.0}, "max_strain must be a finite number > 0", "max_strain"),
        ({"pin_spacing": -5.0}, "pin_spacing must be a finite number > 0", "pin_spacing"),
        ({"plate_size": [10.0, 3.0], "kerf": 2.0}, "plate_size [10.0, 3.0] leaves no room", "plate_size"),
    ],
)
def test_bad_settings_name_the_key(section, says, key):
    """Python terms in the library (the spec's [fabrication] adds its name: tests/e2e/test_shop_cli.py)."""
    with pytest.raises(ParameterError) as caught:
        fabrication_settings(section)
    assert str(caught.value).startswith(says) and "\n" not in str(caught.value) and caught.value.key == key
