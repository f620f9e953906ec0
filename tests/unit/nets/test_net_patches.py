"""A net's four-sided cell refitted in curvature-line coordinates (issue 44, item 3), held to
closed forms none of which comes from tubecad: the elliptical dome's ellipse of revolution,
its meridians (constant polar angle) and parallels (constant z), and the bicubic hull panel
against OCCT's own principal directions (``GeomLProp_SLProps``)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shared.host_faces import DOME, SAMPLES

from tubecad.core.errors import ParameterError
from tubecad.nets import curvature_net
from tubecad.nets.patches import CurvaturePatch, curvature_patch
from tubecad.occ_compat import as_edge


def _face(name: str):
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import sub_shapes
    from tubecad.export.cad import import_shape

    return sub_shapes(import_shape(str(SAMPLES / name)), TopAbs_FACE)[0]


def _angle(d: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The angle between lines (either sense), accurate near 0."""
    return np.arctan2(np.linalg.norm(np.cross(d, t), axis=1), np.abs(np.einsum("nk,nk->n", d, t)))


def _sampled(patch: CurvaturePatch, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(points, X_u, X_v) of the patch's surface on a count x count grid of its parameters,
    each (count, count, 3), by OCCT's D1."""
    from OCP.gp import gp_Pnt, gp_Vec

    u0, u1, v0, v1 = patch.surface.Bounds()
    out = np.empty((3, count, count, 3))
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    for i, u in enumerate(np.linspace(u0, u1, count)):
        for j, v in enumerate(np.linspace(v0, v1, count)):
            patch.surface.D1(float(u), float(v), p, du, dv)
            out[:, i, j] = p.Coord(), du.Coord(), dv.Coord()
    return out[0], out[1], out[2]


def _valid(shape) -> bool:
    from OCP.BRepCheck import BRepCheck_Analyzer

    return BRepCheck_Analyzer(shape).IsValid()


# --- the dome: the ellipse (r/500)^2 + (z/250)^2 = 1 revolved -----------------------------------


@pytest.fixture(scope="module")
def dome_net():
    return curvature_net(_face("dome.step"), 6, 6)


@pytest.fixture(scope="module")
def dome_patch(dome_net) -> CurvaturePatch:
    # between the parallels k1_02, k1_03 and the meridians k2_01, k2_02 (60 degrees apart)
    return curvature_patch(dome_net, ("k1_02", "k1_03"), ("k2_01", "k2_02"), (17, 17))


def test_the_dome_patch_lies_on_the_ellipse_of_revolution(dome_patch):
    a, b = DOME["radius"], DOME["height"]
    p, _, _ = _sampled(dome_patch, 65)
    p = p.reshape(-1, 3)
    f = (p[:, 0] ** 2 + p[:, 1] ** 2) / a**2 + p[:, 2] ** 2 / b**2 - 1.0
    gradient = 2.0 * p / np.array([a * a, a * a, b * b])
    distance = np.abs(f) / np.linalg.norm(gradient, axis=1)  # to first order: f / |grad f|
    print(f"dome patch: {distance.max():.2e} from the ellipsoid, its own measure {dome_patch.distance:.2e}")
    assert distance.max() < 2e-4  # measured 9.2e-5 (h^4: 1.5e-3 on 9 lines, 5.8e-6 on 33)
    assert dome_patch.distance < 2e-4 and dome_patch.distance == pytest.approx(distance.max(), rel=0.1)


def test_the_dome_patchs_isolines_are_meridians_and_parallels(dome_patch):
    p, xu, xv = _sampled(dome_patch, 65)
    r, z = np.hypot(p[..., 0], p[..., 1]), p[..., 2]
    polar = np.unwrap(np.arctan2(p[..., 1], p[..., 0]), axis=1)
    # u = const (family 2): a meridian, constant polar angle; its off-plane distance r dphi
    meridian = (np.ptp(polar, axis=1) * r.max(axis=1)).max()
    # v = const (family 1): a parallel, constant z
    parallel = np.ptp(z, axis=0).max()
    print(f"dome patch: meridians off their planes by {meridian:.2e}, parallels off theirs by {parallel:.2e}")
    # exact but for round-off: a row's points share one z and a column's one polar angle, and
    # the interpolant of equal values is that value (the patch's error is across the isolines)
    assert meridian < 1e-11 and parallel < 1e-11  # measured 1.9e-12, 7.1e-13
    # their tangents against the exact meridian and parallel directions
    a, b = DOME["radius"], DOME["height"]
    q = p.reshape(-1, 3)
    along_parallel = np.stack([-q[:, 1], q[:, 0], np.zeros(len(q))], axis=1)
    along_meridian = np.cross(q / np.array([a * a, a * a, b * b]), along_parallel)
    angle_u = _angle(xu.reshape(-1, 3), along_parallel).max()
    angle_v = _angle(xv.reshape(-1, 3), along_meridian).max()
    print(f"dome patch: isolines {angle_u:.2e}, {angle_v:.2e} rad off, its own measure {dome_patch.angle:.2e}")
    assert angle_u < 1e-4 and angle_v < 1e-5  # measured 5.0e-5, 3.1e-6 rad (h^3)
    assert dome_patch.angle == pytest.approx(max(angle_u, angle_v), rel=0.1)
    assert dome_patch.F < 1e-4 and dome_patch.M < 1e-10  # measured 4.7e-5, 3.1e-12


def test_the_dome_patchs_face_is_bounded_by_the_nets_lines(dome_net, dome_patch):
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_EDGE

    from tubecad.brep.properties import sub_shapes

    assert _valid(dome_patch.face)
    assert dome_patch.same_sense and dome_patch.poles == (17, 17)
    edges = sub_shapes(dome_patch.face, TopAbs_EDGE)
    assert len(edges) == 4
    nets = [dome_net.edges[name].curve for name in ("k1_02", "k1_03", "k2_01", "k2_02")]
    for edge in edges:  # each on one of the net's curves, in its arc length, untouched
        first, last = BRep_Tool.Range_s(as_edge(edge))
        curve = BRep_Tool.Curve_s(as_edge(edge), first, last)
        at = np.linspace(first, last, 5).tolist()
        same = [max(curve.Value(t).Distance(net.Value(t)) for t in at) for net in nets]
        assert sorted(same)[0] == 0.0 and sorted(same)[1] > 1.0
    assert dome_patch.edge_gap < 4e-4  # measured 2.0e-4: the lines' own curves, within it of the patch
    assert max(BRep_Tool.Tolerance_s(as_edge(e)) for e in edges) == pytest.approx(2 * dome_patch.edge_gap)


def test_a_quintic_dome_patch_is_finer(dome_net):
    patch = curvature_patch(dome_net, ("k1_02", "k1_03"), ("k2_01", "k2_02"), (9, 9), degree=5)
    print(patch.report())
    assert patch.distance < 3e-5 and patch.angle < 1e-5  # measured 1.2e-5, 3.7e-6 (h^6, h^5)
    assert _valid(patch.face)


@pytest.mark.slow
def test_the_dome_patchs_error_falls_as_h4():
    net = curvature_net(_face("dome.step"), 6, 6)
    patch = curvature_patch(net, ("k1_02", "k1_03"), ("k2_01", "k2_02"), target=(1e-8, 1e-5))
    table = [*patch.tried, patch.report()]
    for row in table:
        print(row)
    assert [row["samples"] for row in table] == [[9, 9], [17, 17], [33, 33]]
    distances, angles = [row["distance"] for row in table], [row["angle"] for row in table]
    for coarse, fine in zip(distances, distances[1:]):
        assert 14 < coarse / fine < 18  # measured 15.9, 16.0: cubic, h^4
    for coarse, fine in zip(angles, angles[1:]):
        assert 7 < coarse / fine < 9  # measured 7.9, 8.0: the tangents, h^3
    assert patch.distance < 1e-5 and patch.angle < 1e-5  # measured 5.8e-6, 6.3e-6


# --- the hull panel: against OCCT's principal directions ------------------------------------


@pytest.fixture(scope="module")
def hull_net():
    return curvature_net(_face("hull_panel.step"), 6, 6)


@pytest.fixture(scope="module")
def hull_patch(hull_net) -> CurvaturePatch:
    return curvature_patch(hull_net, ("k1_02", "k1_03"), ("k2_00", "k2_01"), (17, 17))


def test_the_hull_patch_follows_occts_principal_directions(hull_net, hull_patch):
    from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
    from OCP.GeomLProp import GeomLProp_SLProps
    from OCP.gp import gp_Dir, gp_Pnt

    surface = hull_net.host.surface
    p, xu, xv = _sampled(hull_patch, 41)
    distance, straight, crossed = 0.0, 0.0, 0.0
    for point, du, dv in zip(p.reshape(-1, 3), xu.reshape(-1, 3), xv.reshape(-1, 3)):
        projection = GeomAPI_ProjectPointOnSurf(gp_Pnt(*point), surface)
        distance = max(distance, projection.LowerDistance())
        u, v = projection.LowerDistanceParameters()
        props = GeomLProp_SLProps(surface, u, v, 2, 1e-12)
        d1, d2 = gp_Dir(), gp_Dir()
        props.CurvatureDirections(d1, d2)
        first, second = np.array([d1.Coord()]), np.array([d2.Coord()])
        # OCCT's max and min directions (by its normal's sign): the isolines along them, one
        # way round for every point (the two are at right angles)
        straight = max(straight, _angle(du[None], first)[0], _angle(dv[None], second)[0])
        crossed = max(crossed, _angle(du[None], second)[0], _angle(dv[None], first)[0])
    angle = min(straight, crossed)
    print(f"hull patch: {distance:.2e} from the host, isolines {angle:.2e} rad off OCCT's directions")
    print(hull_patch.report())
    # the host is only C2 across its knot line v = 0.5, which crosses the cell: the lines'
    # geodesic curvature and the net's spacing jump there, which no tensor product follows
    assert distance < 2.5e-3  # measured 2.0e-3 (5.1e-7 of the panel's 4000)
    assert angle < 6e-4  # measured 5.0e-4 rad
    # its own measure (on 4 points a step, the host projected too) agrees
    assert hull_patch.distance == pytest.approx(distance, rel=0.1)  # measured 1.9e-3
    assert hull_patch.angle < 6e-4  # measured 5.3e-4


def test_the_hull_patchs_face_is_valid(hull_patch):
    assert _valid(hull_patch.face)
    assert hull_patch.edge_gap < 6e-3  # measured 5.6e-3


def test_a_cell_of_lines_that_do_not_cross_is_refused(hull_net):
    with pytest.raises(ParameterError, match="do not cross"):
        curvature_patch(hull_net, ("k1_04", "k1_05"), ("k2_03", "k2_04"), (5, 5))
    with pytest.raises(ParameterError, match="family 1"):
        curvature_patch(hull_net, ("k2_00", "k2_01"), ("k2_00", "k2_01"), (5, 5))
    with pytest.raises(ParameterError, match="samples"):
        curvature_patch(hull_net, ("k1_02", "k1_03"), ("k2_00", "k2_01"), (3, 5))


def test_the_dome_patch_is_sixty_degrees_wide(dome_patch):
    """The sides k1_02 (u from 0 to L_u) and k2_01 (v from 0 to L_v) are parameterised by arc
    length: L_u is the parallel's 60 degree arc, r pi / 3."""
    u0, u1, v0, v1 = dome_patch.surface.Bounds()
    r = float(np.hypot(*dome_patch.grid[0, 0, :2]))
    assert (u0, v0) == (0.0, 0.0)
    assert u1 == pytest.approx(r * math.pi / 3, rel=1e-10)
