"""A net's cells as one shell of curvature-line patches (issue 44, item 3), held to closed forms
none of which comes from tubecad: on the elliptical dome (the ellipse (r/500)^2 + (z/250)^2 = 1
revolved) every patch's isolines are its parallels (constant r and z) and meridians (in a plane
through the axis); the shell passes OCCT's checks (``BRepCheck_Analyzer``, the pre-boolean
``BOPAlgo_ArgumentAnalyzer``), has the split face's area (OCCT's ``BRepGProp``), and reads back
from STEP; a wall thickened from it has the host wall's volume."""

from __future__ import annotations

import numpy as np
import pytest
from shared.host_faces import DOME, SAMPLES

from tubecad.core.errors import ParameterError

pytestmark = pytest.mark.slow  # each cell traces its own grid of lines (about 1 s a cell)


def _face(name: str):
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import sub_shapes
    from tubecad.export.cad import import_shape

    return sub_shapes(import_shape(str(SAMPLES / name)), TopAbs_FACE)[0]


@pytest.fixture(scope="module")
def dome():
    from tubecad.nets import curvature_net
    from tubecad.nets.patch_shell import patch_shell

    net = curvature_net(_face("dome.step"), 3, 4)
    return net, patch_shell(net)


def test_every_inner_cell_of_the_dome_is_refitted_and_the_rest_kept_on_the_face(dome):
    net, shell = dome
    # 3 parallels (closed) and 4 meridians round the whole dome: (3 - 1) x 4 cells between
    # neighbouring lines; the cells against the rim and the crown opening are not four-sided
    assert len(shell.patches) == 2 * 4
    assert all(reason.startswith("not four-sided") for reason in shell.kept.values())
    report = shell.report()
    assert report["angle"] < 1e-6 and report["distance"] < 1e-8 * 1000.0  # the default target
    assert report["edge_tolerance"] < 1e-5


def test_the_patches_isolines_are_the_domes_parallels_and_meridians(dome):
    _, shell = dome
    worst_parallel = worst_meridian = worst_distance = 0.0
    for patch in shell.patches.values():
        u0, u1, v0, v1 = patch.surface.Bounds()
        for v in np.linspace(v0, v1, 5):  # v constant: a k1 line, a parallel
            p = np.array([patch.surface.Value(float(u), float(v)).Coord() for u in np.linspace(u0, u1, 41)])
            r = np.hypot(p[:, 0], p[:, 1])
            worst_parallel = max(worst_parallel, float(np.ptp(r)), float(np.ptp(p[:, 2])))
            # the distance from the ellipse of revolution: |f| / |grad f|, f = (r/a)^2 + (z/c)^2 - 1
            a, c = DOME["radius"], DOME["height"]
            f = (r / a) ** 2 + (p[:, 2] / c) ** 2 - 1
            worst_distance = max(worst_distance, float((np.abs(f) / np.hypot(2 * r / a**2, 2 * p[:, 2] / c**2)).max()))
        for u in np.linspace(u0, u1, 5):  # u constant: a k2 line, a meridian
            p = np.array([patch.surface.Value(float(u), float(v)).Coord() for v in np.linspace(v0, v1, 41)])
            normal = np.cross([0.0, 0.0, 1.0], p[0])
            worst_meridian = max(worst_meridian, float(np.abs(p @ (normal / np.linalg.norm(normal))).max()))
    # within the default target (1e-8 of the dome's size: 1e-5 mm; the patches' grids of 17 or
    # 33 lines a family)
    assert worst_distance < 3e-6  # measured 1.7e-6
    assert worst_parallel < 1e-5  # measured 4.9e-6 (r and z along a parallel)
    assert worst_meridian < 1e-11  # measured 4.1e-12


def test_the_shell_is_valid_fit_for_booleans_of_the_faces_area_and_reads_back(dome, tmp_path):
    import build123d as bd
    from OCP.BRepCheck import BRepCheck_Analyzer

    from tubecad.brep import properties as props
    from tubecad.brep.analyzer import analyzer_findings

    net, shell = dome
    assert BRepCheck_Analyzer(shell.shell).IsValid()
    assert analyzer_findings(shell.shell) == {}
    assert props.count(shell.shell, "face") == props.count(net.patches, "face")
    assert props.area(shell.shell) == pytest.approx(props.area(net.patches), rel=1e-9)
    bd.export_step(bd.Shell(bd.Shape.cast(shell.shell).faces()), tmp_path / "shell.step")
    back = bd.import_step(tmp_path / "shell.step")
    assert BRepCheck_Analyzer(back.wrapped).IsValid()
    assert len(back.faces()) == props.count(net.patches, "face")
    assert back.area == pytest.approx(props.area(net.patches), rel=1e-9)


def test_a_wall_thickened_from_the_patches_has_the_host_walls_volume(dome):
    from OCP.BRepCheck import BRepCheck_Analyzer

    from tubecad.brep import properties as props
    from tubecad.design.model import WallChoice
    from tubecad.design.net import thickened

    net, shell = dome
    on_host = thickened(net.patches, WallChoice(8.0, "inside"))
    on_patches = thickened(shell.shell, WallChoice(8.0, "inside"))
    assert BRepCheck_Analyzer(on_patches).IsValid()
    assert props.volume(on_patches) == pytest.approx(props.volume(on_host), rel=1e-7)  # measured 2.7e-8


def test_bad_arguments_are_refused_naming_them(dome):
    from tubecad.nets.patch_shell import patch_shell

    net, _ = dome
    for kwargs, key in (({"degree": 4}, "degree"), ({"samples": 3}, "samples"), ({"target": (0.0, 1e-6)}, "target")):
        with pytest.raises(ParameterError) as refused:
            patch_shell(net, **kwargs)
        assert refused.value.key == key


def _circle(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, float]:
    """The circle through three plane points: (centre, radius)."""
    d = 2 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    sa, sb, sc = a @ a, b @ b, c @ c
    centre = np.array(
        [
            (sa * (b[1] - c[1]) + sb * (c[1] - a[1]) + sc * (a[1] - b[1])) / d,
            (sa * (c[0] - b[0]) + sb * (a[0] - c[0]) + sc * (b[0] - a[0])) / d,
        ]
    )
    return centre, float(np.linalg.norm(a - centre))


def test_a_refitted_dome_panel_develops_its_meridian_straight_and_its_parallels_to_their_cones_circles(dome):
    """The development keeps the middle k2 line (a meridian: a geodesic, geodesic curvature 0)
    and every k1 line (a parallel) isometric: the meridian develops to a straight line, and a
    parallel of radius r to the circle its tangent cone unrolls to, of radius r / sin(g), g the
    angle between the meridian and the axis (r = a cos t, z = c sin t:
    sin g = a sin t / sqrt(a^2 sin^2 t + c^2 cos^2 t))."""
    from tubecad.nets.patch_surface import PatchSurface
    from tubecad.shop.panel_development import develop_cell

    _, shell = dome
    a, c = DOME["radius"], DOME["height"]
    worst_line = worst_circle = 0.0
    for patch in list(shell.patches.values())[:3]:
        base = PatchSurface(patch.surface)
        dev = develop_cell(base, base.u_range, base.span, "cell", (17, 9))
        middle = dev.grid[8]  # u = u_m: the middle meridian
        chord = (middle[-1] - middle[0]) / np.linalg.norm(middle[-1] - middle[0])
        off = middle - middle[0]
        worst_line = max(worst_line, float(np.abs(off[:, 0] * chord[1] - off[:, 1] * chord[0]).max()))
        for j, s in enumerate(dev.s):
            ring = dev.grid[:, j]
            centre, _ = _circle(ring[0], ring[8], ring[-1])
            x, y, _ = base.points(0.5 * sum(base.u_range), s)
            r = float(np.hypot(x, y))
            t = np.arccos(r / a)
            rho = r * np.hypot(a * np.sin(t), c * np.cos(t)) / (a * np.sin(t))
            worst_circle = max(worst_circle, float(np.abs(np.linalg.norm(ring - centre, axis=1) - rho).max()))
        assert dev.flat_area > dev.surface_area  # K > 0: the development stretches (Jacobi)
    assert worst_line < 1e-11  # measured 9e-13
    assert worst_circle < 5e-4  # measured 2.3e-4 mm on radii of 400 to 1000 mm (the patch's fit, 1e-6 mm)


def test_a_cones_refitted_panels_develop_without_strain_to_annular_sectors():
    """A cone is developable: its lines of curvature are its rulings and circles, and a cell
    between two of each develops to an annular sector (the apex its centre, the slant
    distances rho its radii, the angle theta sin(alpha) for theta round the axis): strain 0,
    the flat area the surface's, the corners' distances the sector's."""
    import math

    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_ConicalSurface
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt

    from tubecad.nets import curvature_net
    from tubecad.nets.patch_shell import patch_shell
    from tubecad.nets.patch_surface import PatchSurface
    from tubecad.shop.panel_development import develop_cell

    alpha, radius = math.radians(20.0), 100.0
    cone = Geom_ConicalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), alpha, radius)
    net = curvature_net(BRepBuilderAPI_MakeFace(cone, 0.0, math.pi, 50.0, 250.0, 1e-7).Face(), 3, 4)
    shell = patch_shell(net)
    assert len(shell.patches) == 2 * 3  # between 3 rulings and 4 circles, all inside the face
    apex = np.array([0.0, 0.0, -radius / math.tan(alpha)])
    for patch in shell.patches.values():
        base = PatchSurface(patch.surface)
        dev = develop_cell(base, base.u_range, base.span, "cell", (9, 9))
        assert dev.max_strain < 2e-6  # measured 6e-7: the patch's fit (the exact cone's is 0)
        assert dev.flat_area == pytest.approx(dev.surface_area, rel=1e-12)
        (u0, u1), (s0, s1) = base.u_range, base.span
        corners = [(u0, s0), (u1, s0), (u0, s1), (u1, s1)]
        developed = [dev.grid[i, j] for i, j in ((0, 0), (-1, 0), (0, -1), (-1, -1))]
        sector = []
        for u, s in corners:
            point = base.points(u, s)
            rho, theta = np.linalg.norm(point - apex), math.atan2(point[1], point[0])
            sector.append(rho * np.array([math.cos(theta * math.sin(alpha)), math.sin(theta * math.sin(alpha))]))
        for i in range(4):
            for j in range(i + 1, 4):
                flat = np.linalg.norm(developed[i] - developed[j])
                assert flat == pytest.approx(np.linalg.norm(sector[i] - sector[j]), abs=5e-6)  # measured 2e-6
