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
