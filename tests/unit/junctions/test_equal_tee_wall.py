"""The equal tee's wall (issue 43) against closed forms that do not come from tubecad: main
y^2 + z^2 = R^2 along x (300 long), branch x^2 + y^2 = R^2 up z (120 long), both walls 4
centred, so the outer surfaces (52) touch each other at (0, +-52, 0) and the bores (48) at
(0, +-48, 0). Each union's volume is |A| + |B| less half the Steinmetz solid, 8 a^3 / 3 (the
branch from the main axis up), its saddle the half-ellipses in x = +-z; the crotch points
are vertices; OCCT's checks, and the STEP file read back."""

from __future__ import annotations

import math

import numpy as np
import pytest
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.GeomAbs import GeomAbs_Ellipse

from tubecad import NaturalAxis
from tubecad.brep import NetLayout
from tubecad.brep.properties import analyzer_findings, is_valid, volume
from tubecad.junctions import branch_surface, build_junction_wall
from tubecad.surface.canal import tube_or_canal

R, T, L, H = 50.0, 4.0, 300.0, 120.0
R_OUT, R_IN = R + T / 2, R - T / 2


def line(origin, tangent, normal, length, radius):
    return tube_or_canal(NaturalAxis("0", "0", (0.0, length), origin=origin, tangent=tangent, normal=normal), radius)


MAIN = line((-L / 2, 0.0, 0.0), (1, 0, 0), (0, 1, 0), L, R)
BRANCH = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), H, R)


def union_volume(a: float) -> float:
    return math.pi * a**2 * (L + H) - 8 * a**3 / 3


WALL_VOLUME = union_volume(R_OUT) - union_volume(R_IN)


def build(main_net=(4, 6), branch_net=(3, 6)):
    return build_junction_wall(
        MAIN,
        BRANCH,
        T,
        T,
        main_layout=NetLayout.equal(MAIN, *main_net),
        branch_layout=NetLayout.equal(BRANCH, *branch_net),
    )


@pytest.fixture(scope="module")
def tee():
    return build()


def saddle_points(tee, name: str) -> np.ndarray:
    return np.array([tuple(e.position_at(t)) for e in tee.edges[name] for t in np.linspace(0, 1, 51)])


def test_the_equal_tee_is_one_valid_solid_of_the_closed_form_volume(tee):
    assert len(tee.shape.solids()) == 1 and is_valid(tee.shape.wrapped)
    assert volume(tee.shape.wrapped) == pytest.approx(WALL_VOLUME, rel=1e-12)  # measured 2.3e-14


@pytest.mark.parametrize(("name", "a"), [("saddle_outer", R_OUT), ("saddle_inner", R_IN)])
def test_the_saddle_edges_are_the_half_ellipses_through_the_crotch_vertices(tee, name, a):
    p = saddle_points(tee, name)
    # measured 9.2e-14 and 1.1e-13 (the edges are the ellipse arcs themselves)
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - a).max() < 1e-12 * a
    assert np.abs(np.hypot(p[:, 0], p[:, 1]) - a).max() < 1e-12 * a
    assert np.minimum(np.abs(p[:, 0] - p[:, 2]), np.abs(p[:, 0] + p[:, 2])).max() < 1e-12 * a
    assert p[:, 2].min() > -1e-12 * a
    assert all(BRepAdaptor_Curve(e.wrapped).GetType() == GeomAbs_Ellipse for e in tee.edges[name])
    ends = np.array([tuple(v) for e in tee.edges[name] for v in (e.position_at(0), e.position_at(1))])
    for crotch in ([0.0, a, 0.0], [0.0, -a, 0.0]):
        assert np.linalg.norm(ends - crotch, axis=1).min() < 1e-12 * a  # measured 8.1e-14
    assert tee.deviation[name] < 1e-12 * a and tee.coverage[name] == pytest.approx(1.0, abs=1e-12)
    assert tee.saddles[name].kind == "2 ellipse arcs"


def test_the_nets_stay_named_round_the_opening(tee):
    """The main's end ring whole; its ring at x = -50 cut where the branch's outer cylinder
    holds it, |y| < sqrt(52^2 - 50^2), z > 0; its stringer at 60 deg (y = 26) cut where
    x^2 < 52^2 - 26^2; the branch's end ring whole (every piece through the splits and the
    sewing named)."""
    length = {name: sum(e.length for e in edges) for name, edges in tee.edges.items()}
    assert length["main_ring_00"] == pytest.approx(2 * math.pi * R_OUT, rel=1e-12)
    cut = 2 * R_OUT * math.asin(math.sqrt(R_OUT**2 - 50.0**2) / R_OUT)
    assert length["main_ring_01"] == pytest.approx(2 * math.pi * R_OUT - cut, rel=1e-12)
    assert length["main_stringer_01"] == pytest.approx(L - 2 * R_OUT * math.cos(math.radians(30)), rel=1e-9)
    assert length["branch_ring_02"] == pytest.approx(2 * math.pi * R_OUT, rel=1e-12)
    assert min(e.length for e in tee.shape.edges()) > 1.0


@pytest.mark.slow
def test_the_equal_tee_is_clean_and_reads_back_from_step_and_gmsh(tee, tmp_path):
    from conftest import gmsh_initialized
    from shared.step_read_back import step_read_back

    assert analyzer_findings(tee.shape.wrapped) == {}
    path = tmp_path / "equal_tee.step"
    back = step_read_back(tee.shape, path)
    assert len(back.solids()) == 1 and is_valid(back.wrapped)
    # the reader gives every edge 1e-7: OCCT's own section edges at the crotch failed that (8
    # InvalidCurveOnSurface), the edges on the exact saddle hold it
    assert analyzer_findings(back.solids()[0].wrapped) == {}
    assert volume(back.wrapped) == pytest.approx(WALL_VOLUME, rel=1e-12)
    with gmsh_initialized() as g:
        g.model.occ.importShapes(str(path))
        g.model.occ.synchronize()
        volumes = g.model.getEntities(3)
        assert len(volumes) == 1
        assert g.model.occ.getMass(*volumes[0]) == pytest.approx(WALL_VOLUME, rel=1e-9)


@pytest.mark.slow
def test_a_main_ring_and_stringer_through_the_crotch_points(tee):
    """5 rings (one at x = 0) and 8 stringers (one at y = R): the crotch points are vertices of
    the main's net already (OCCT's extrema on a trimmed ellipse missed them at its end: 104 off)."""
    wall = build((5, 8), (3, 8))
    assert is_valid(wall.shape.wrapped) and analyzer_findings(wall.shape.wrapped) == {}
    assert volume(wall.shape.wrapped) == pytest.approx(WALL_VOLUME, rel=1e-12)  # measured 1.5e-13
    p = saddle_points(wall, "saddle_outer")
    assert np.minimum(np.abs(p[:, 0] - p[:, 2]), np.abs(p[:, 0] + p[:, 2])).max() < 1e-12 * R_OUT


@pytest.mark.slow
@pytest.mark.parametrize("angle", [60.0, 45.0])
def test_an_equal_lateral_meets_in_the_bisecting_planes(angle):
    """The branch at 60 / 45 deg: the saddles in the planes through the axes' crossing normal to
    t -+ d; one valid, analyzer-clean solid."""
    main = line((0.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 300.0, R)
    wall = build_junction_wall(main, branch_surface(main, 150.0, 150.0, R, angle=angle), T, T)
    assert is_valid(wall.shape.wrapped) and analyzer_findings(wall.shape.wrapped) == {}
    d = np.array([math.cos(math.radians(angle)), 0.0, math.sin(math.radians(angle))])
    for name in ("saddle_outer", "saddle_inner"):
        p = saddle_points(wall, name) - [150.0, 0.0, 0.0]
        planes = np.abs(np.stack([p @ ([1.0, 0, 0] - d), p @ ([1.0, 0, 0] + d)], axis=1)).min(axis=1)
        assert planes.max() < 1e-11 * R  # measured 3e-13
        assert wall.saddles[name].kind == "2 ellipse arcs"


@pytest.mark.slow
def test_only_the_bores_touching():
    """r = 49 with a 2 mm wall on R = 50 with 4: the bores (48) touch, the outer surfaces (50 in
    52) cross: one saddle a periodic B-spline, the other two ellipse arcs."""
    main = line((0.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 300.0, R)
    wall = build_junction_wall(main, branch_surface(main, 150.0, 150.0, 49.0), T, 2.0)
    assert is_valid(wall.shape.wrapped) and analyzer_findings(wall.shape.wrapped) == {}
    assert wall.saddles["saddle_outer"].kind == "periodic B-spline"
    assert wall.saddles["saddle_inner"].kind == "2 ellipse arcs"
    p = saddle_points(wall, "saddle_inner") - [150.0, 0.0, 0.0]
    assert np.minimum(np.abs(p[:, 0] - p[:, 2]), np.abs(p[:, 0] + p[:, 2])).max() < 1e-12 * R_IN
