"""Stiffeners on curvature lines (issue 4): curves and polylines, stiffener solids."""

import csv
import json
import math

import build123d as bd
import numpy as np
import pytest
from conftest import edges_of
from OCP.BRepAdaptor import BRepAdaptor_Curve

from tubecad import CurvatureLineTube, ParameterError
from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.export.cad import import_shape
from tubecad.export.registry import export_shape
from tubecad.occ_compat import as_edge
from tubecad.spec.paper import paper_tube
from tubecad.stiffeners import lines_compound, net_lines, polylines_csv, polylines_json
from tubecad.stiffeners.profiles import Profile
from tubecad.stiffeners.solids import ring_stiffener, stringer_stiffener
from tubecad.surface.checks import distance_to_axis


@pytest.fixture(scope="module")
def wall():
    tube = paper_tube()
    return build_wall_solid(tube, 2.0, "centered", NetLayout.explicit(tube, [450.0, 900.0], [0.0, 72.0, 190.0]))


def test_lines_lie_on_the_surfaces_and_export_as_curves(tmp_path, wall):
    lines = net_lines(wall.surfaces[0], wall.layout) + net_lines(wall.surfaces[1], wall.layout, "_inner")
    assert [ln.name for ln in lines[:5]] == [
        "line_ring_00",
        "line_ring_01",
        "line_ring_02",
        "line_ring_03",
        "line_stringer_00",
    ]
    for line in lines:
        curve = BRepAdaptor_Curve(line.edge().wrapped)
        tube = line.surface.tube
        for p in np.linspace(curve.FirstParameter(), curve.LastParameter(), 25):
            q = curve.Value(p)
            # a ring is a Geom_Circle whose parameter is the angle from the surface's origin
            th, s = (
                (p + math.radians(line.surface.origin_deg), line.value)
                if line.kind == "ring"
                else (math.radians(line.value), p)
            )
            assert np.linalg.norm(np.array([q.X(), q.Y(), q.Z()]) - tube.points(th, s)) < 1e-8
    compound = lines_compound(lines)
    step = import_shape(export_shape(compound, tmp_path / "lines.step"))
    assert props.count(step, "edge") == len(lines)
    iges = import_shape(export_shape(compound, tmp_path / "lines.iges"))
    total = sum(bd.Edge(e).length for e in edges_of(iges))
    assert total == pytest.approx(sum(ln.edge().length for ln in lines), rel=1e-7)  # IGES keeps ~1e-8


def test_polylines_carry_position_tangent_and_normal(tmp_path, wall):
    lines = net_lines(wall.surfaces[1], wall.layout, "_inner")
    rows = list(csv.DictReader(open(polylines_csv(lines, tmp_path / "l.csv", 40))))
    assert len(rows) == 40 * len(lines)
    data = json.loads(polylines_json(lines, tmp_path / "l.json", 300).read_text())
    assert data["units"] == "mm" and len(data["lines"]) == len(lines)
    axis = paper_tube().axis
    for line in data["lines"]:
        p, t, n = (np.array(line[k]) for k in ("position", "tangent", "normal"))
        dist, s_star = distance_to_axis(axis, p, np.array(line["s"]))
        assert np.abs(dist - 14.0).max() < 1e-9 and np.abs(s_star - np.array(line["s"])).max() < 1e-7
        assert np.allclose(np.linalg.norm(t, axis=1), 1) and np.allclose(np.linalg.norm(n, axis=1), 1)
        assert np.abs(np.einsum("ij,ij->i", t, n)).max() < 1e-12
        chords = np.diff(p, axis=0)
        mid = t[:-1] + t[1:]
        cos = np.einsum(
            "ij,ij->i",
            chords / np.linalg.norm(chords, axis=1, keepdims=True),
            mid / np.linalg.norm(mid, axis=1, keepdims=True),
        )
        assert cos.min() > 0.999  # the tangent points along the line
    first = rows[0]
    assert first["line"] == "line_ring_00_inner" and float(first["surface_radius"]) == 14.0


def unique_edges(shape):
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp

    from tubecad.occ_compat import IndexedMapOfShape

    found = IndexedMapOfShape()
    TopExp.MapShapes_s(props.topods(shape), TopAbs_EDGE, found)
    return [as_edge(found.FindKey(i)) for i in range(1, found.Extent() + 1)]


def section_moments(profile: Profile, R: float, side: str):
    """Area and first moments (int v dA, int w dA) of the stiffener's cross-section in the
    (w, v) plane, v measured from the axis: the outline polygon closed by its chord, minus
    (outside) or plus (inside) the circular segment between the chord and the wall's arc."""
    sign = 1.0 if side == "outside" else -1.0
    delta = math.asin(profile.thickness / (2 * R))
    pts = [(w, R * math.cos(delta) if h == 0 else R + sign * h) for w, h in profile.outline()]
    area = mv = mw = 0.0
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
        cross = x0 * y1 - x1 * y0
        area += cross / 2
        mw += (x0 + x1) * cross / 6
        mv += (y0 + y1) * cross / 6
    flip = 1.0 if area > 0 else -1.0
    area, mv, mw = area * flip, mv * flip, mw * flip
    seg_area, seg_mv = R**2 * (2 * delta - math.sin(2 * delta)) / 2, 2 / 3 * R**3 * math.sin(delta) ** 3
    return area - sign * seg_area, mv - sign * seg_mv, mw


@pytest.mark.parametrize("kind", ["flat", "T", "L"])
@pytest.mark.parametrize("side", ["outside", "inside"])
def test_stringer_stiffener_volume_is_exact_and_it_stands_on_the_wall(kind, side):
    tube = CurvatureLineTube(paper_tube().axis, 16.0 if side == "outside" else 14.0)
    profile = Profile(kind, 8.0, 1.2, 5.0 if kind != "flat" else 0.0, 1.0 if kind != "flat" else 0.0)
    theta = 37.0
    stiffener = stringer_stiffener(tube, theta, profile, side, span=(300.0, 800.0))
    solid = stiffener.solid
    assert isinstance(solid, bd.Solid) and props.is_valid(solid) and props.free_edges(solid) == 0
    # V = Int [A - k (cos phi Mv - sin phi Mw)] ds, phi = theta - Int sigma ds (Jacobian of C + v N + w E)
    area, mv, mw = section_moments(profile, tube.radius, side)
    x, w = np.polynomial.legendre.leggauss(48)
    edges = np.linspace(300.0, 800.0, 21)
    s = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * x).ravel()
    phi = math.radians(theta) - tube.axis.twist(s)
    integrand = area - tube.axis.curvature(s) * (np.cos(phi) * mv - np.sin(phi) * mw)
    exact = float((integrand * np.tile(w, 20)).sum() * 0.5 * (edges[1] - edges[0]))
    assert props.volume(solid) == pytest.approx(exact, rel=2e-10)  # measured 1.9e-11 (inside)
    # the edges it stands on lie on the wall: at distance R from the axis (no gap)
    on_wall = 0
    for edge in unique_edges(solid):
        pts = bd.Edge(edge).positions(np.linspace(0, 1, 15))
        p = np.array([[q.X, q.Y, q.Z] for q in pts])
        dist, _ = distance_to_axis(tube.axis, p)
        if np.abs(dist - tube.radius).max() < 1e-8:
            on_wall += 1
    assert on_wall == 4  # two long base edges (web sides meet the wall) and two end arcs


@pytest.mark.parametrize("kind", ["flat", "T"])
def test_ring_frame_is_a_planar_ring_on_the_wall(kind):
    tube = CurvatureLineTube(paper_tube().axis, 16.0)
    profile = Profile(kind, 6.0, 1.0, 4.0 if kind == "T" else 0.0, 0.8 if kind == "T" else 0.0)
    ring = ring_stiffener(tube, 640.0, profile, "outside").solid
    assert props.is_valid(ring) and props.free_edges(ring) == 0
    web = math.pi * ((16 + 6 - (0.8 if kind == "T" else 0)) ** 2 - 16**2) * 1.0
    flange = math.pi * (22**2 - 21.2**2) * 4.0 if kind == "T" else 0.0
    assert props.volume(ring) == pytest.approx(web + flange, rel=2e-12)  # measured 1.3e-13
    planes = [f for f in ring.faces() if f.geom_type == bd.GeomType.PLANE]
    assert len(planes) >= 2  # side faces are annuli in normal planes


def test_stiffener_input_errors():
    tube = CurvatureLineTube(paper_tube().axis, 16.0)
    with pytest.raises(ParameterError, match="profile must be one of flat, T, L"):
        Profile("I", 5, 1)
    with pytest.raises(ParameterError, match="flange_width must be > thickness"):
        Profile("T", 5, 1, 0.5, 0.5)
    with pytest.raises(ParameterError, match="side must be one of outside, inside"):
        stringer_stiffener(tube, 0.0, Profile(), "middle")
    with pytest.raises(ParameterError, match="height must be < R"):
        stringer_stiffener(tube, 0.0, Profile("flat", 20.0, 1.0), "inside")
    with pytest.raises(ParameterError, match="span must lie within"):
        stringer_stiffener(tube, 0.0, Profile(), span=(100.0, 300.0))


def test_named_step_assembly_keeps_names_colours_and_solids(tmp_path):
    from tubecad.export.cad import export_named_step
    from tubecad.stiffeners import net_lines
    from tubecad.stiffeners.assembly import build_stiffeners, named_assembly

    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 4, 4))
    stiffeners = build_stiffeners(build, [1, 2], [0, 2], Profile("flat", 3.0, 1.0), side="inside")
    lines = net_lines(build.surfaces[1], build.layout, "_inner")
    path = export_named_step(named_assembly(build, stiffeners, lines), tmp_path / "asm.step")
    back = bd.import_step(path)
    names = [c.label for c in back.children]
    assert names == ["wall", "ring_01", "ring_02", "stringer_00", "stringer_02", "curvature_lines"]
    wall, ring = back.children[0], back.children[1]
    assert props.is_valid(wall)
    assert props.volume(wall) == pytest.approx(math.pi * (16**2 - 14**2) * 1000, rel=3e-11)  # measured 2.3e-12
    assert props.volume(ring) == pytest.approx(math.pi * (14**2 - 11**2) * 1.0, rel=5e-13)  # measured 4.5e-14
    assert ring.color is not None and tuple(round(c, 2) for c in tuple(ring.color)[:3]) == (0.85, 0.45, 0.2)
    assert [c.label for c in back.children[-1].children][:2] == ["line_ring_00_inner", "line_ring_01_inner"]
    with pytest.raises(ParameterError, match=r"stiffener rings must be indices in \[0, 3\], got \[7\]"):
        build_stiffeners(build, [7], [], Profile())


@pytest.mark.parametrize("side, theta", [("outside", 30.0), ("inside", 200.0)])
def test_stringer_flat_pattern_matches_the_3d_web(side, theta):
    """Flat pattern vs the 3D web measured by OCCT: area and both edge lengths to 1e-6; and
    the developed outline itself (shoelace, polyline lengths) against the exact values."""
    from tubecad.stiffeners.flat import polygon_area, stringer_flat_pattern
    from tubecad.stiffeners.solids import web_face

    base = CurvatureLineTube(paper_tube().axis.restricted((250.0, 900.0)), 16.0 if side == "outside" else 14.0)
    height = 3.0
    pattern = stringer_flat_pattern(base, theta, height, side, samples=20001)
    web = web_face(base, theta, height, side)
    assert props.area(web) == pytest.approx(pattern.area, rel=1e-6)
    lengths = sorted(bd.Edge(e).length for e in unique_edges(web) if bd.Edge(e).length > 10 * height)
    assert lengths == pytest.approx(sorted([pattern.base_length, pattern.top_length]), rel=1e-6)
    n = len(pattern.outline) // 2
    assert polygon_area(pattern.outline) == pytest.approx(pattern.area, rel=1e-6)
    polyline = lambda p: float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())
    assert polyline(pattern.outline[:n]) == pytest.approx(pattern.base_length, rel=1e-6)
    assert polyline(pattern.outline[n:]) == pytest.approx(pattern.top_length, rel=1e-6)


def test_ring_flat_pattern_is_the_annulus_of_the_ring_web(tmp_path):
    import ezdxf

    from tubecad.stiffeners.flat import ring_flat_pattern, stringer_flat_pattern, write_dxf, write_picture

    ring = ring_flat_pattern(14.0, 3.0, "inside", "ring_01")
    assert ring.area == pytest.approx(math.pi * (14**2 - 11**2)) and ring.base_length == pytest.approx(2 * math.pi * 14)
    stringer = stringer_flat_pattern(CurvatureLineTube(paper_tube().axis, 14.0), 90.0, 2.0, "inside", "stringer_02")
    doc = ezdxf.readfile(write_dxf([ring, stringer], tmp_path / "webs.dxf"))
    entities = list(doc.modelspace())
    assert sorted(e.dxftype() for e in entities) == ["CIRCLE", "CIRCLE", "LWPOLYLINE"]
    assert sorted(e.dxf.radius for e in entities if e.dxftype() == "CIRCLE") == pytest.approx([11.0, 14.0])
    poly = next(e for e in entities if e.dxftype() == "LWPOLYLINE")
    pts = np.array([p[:2] for p in poly.get_points()])
    from tubecad.stiffeners.flat import polygon_area

    assert poly.closed and polygon_area(pts) == pytest.approx(stringer.area, rel=1e-5)
    paths = write_picture(stringer, tmp_path)
    assert [p.suffix for p in paths] == [".svg", ".png"] and paths[1].read_bytes().startswith(b"\x89PNG")


@pytest.mark.slow
def test_stiffeners_fuse_into_the_wall():
    from tubecad.stiffeners.assembly import build_stiffeners, named_assembly

    tube = CurvatureLineTube(paper_tube().axis.restricted((400.0, 600.0)), 15.0)
    build = build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 3, 4))
    stiffeners = build_stiffeners(build, [1], [1], Profile("flat", 3.0, 1.0), side="outside")
    fused = named_assembly(build, stiffeners, fuse=True).children[0]
    assert fused.label == "wall" and props.is_valid(fused) and props.count(fused, "solid") == 1
    separate = props.volume(build.shape) + sum(props.volume(s.solid) for s in stiffeners)
    ring, stringer = stiffeners
    overlap = sum(props.volume(p) for p in ring.solid.intersect(stringer.solid))  # where the stringer crosses the ring
    assert props.volume(fused) == pytest.approx(separate - overlap, rel=1e-6)


def test_ring_lines_are_true_circles_and_pass_the_continuity_check():
    """FreeCAD's BOP check flagged every line_ring_* (a C0-knotted B-spline); now circles."""
    import build123d as bd

    from tubecad.brep import NetLayout, build_wall_solid
    from tubecad.brep.properties import analyzer_findings
    from tubecad.spec.paper import paper_tube
    from tubecad.stiffeners import net_lines

    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, layout=NetLayout.equal(tube, 5, 4))
    rings = [line for line in net_lines(build.surfaces[1], build.layout, "_inner") if line.kind == "ring"]
    for line in rings:
        edge = line.edge()
        assert edge.geom_type == bd.GeomType.CIRCLE and edge.radius == pytest.approx(14.0, rel=1e-15)
        assert edge.length == pytest.approx(2 * math.pi * 14.0, rel=1e-14)
        assert analyzer_findings(edge.wrapped, ("ContinuityMode",)) == {}
