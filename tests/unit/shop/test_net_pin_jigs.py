"""Pin jigs of a net's panels (tubecad.shop.net_pin_jigs) on the dome (samples/dome.step, an
ellipse x = a cos t, z = b sin t of revolution, a = 500, b = 250): every pin touches the exact
surface ((x^2 + y^2) / a^2 + z^2 / b^2 = 1, or its offset at the distance asked), stands on its
grid point of the jig plane, on the panel (between the panel's two parallels and its two
meridians, read from the closed form: radius and azimuth), and no pin is below the clearance."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ROOT

A, B = 500.0, 250.0


@pytest.fixture(scope="module")
def dome_net():
    from tubecad.export.cad import read_faces
    from tubecad.nets import curvature_net
    from tubecad.occ_compat import as_face

    return curvature_net(as_face(read_faces(ROOT / "samples" / "dome.step")[0][1]), 4, 6)


def _on_the_panel(points: np.ndarray, jig, net) -> bool:
    """Whether the points lie between the panel's parallels (k1: radii) and meridians (k2:
    azimuths), the closed form's coordinates (the boundary, where the panel has no such line)."""
    radius = np.hypot(points[:, 0], points[:, 1])
    azimuth = np.arctan2(points[:, 1], points[:, 0])
    ok = np.ones(len(points), dtype=bool)
    parallels = sorted(float(np.hypot(*net.lines[n].points[0, :2])) for n in jig.lines if n.startswith("k1"))
    if len(parallels) == 2:
        ok &= (radius >= parallels[0] - 1e-9) & (radius <= parallels[1] + 1e-9)
    meridians = [
        float(np.arctan2(net.lines[n].points[0, 1], net.lines[n].points[0, 0])) for n in jig.lines if n.startswith("k2")
    ]
    if len(meridians) == 2:
        a, b = meridians
        span = (b - a) % (2 * np.pi)
        if span > np.pi:  # the shorter way round
            a, span = b, 2 * np.pi - span
        ok &= ((azimuth - a) % (2 * np.pi)) <= span + 1e-9
    return bool(ok.all())


def test_every_panels_pins_touch_the_dome_on_the_panel_above_the_plane(dome_net):
    from tubecad.shop.net_pin_jigs import net_pin_jigs

    warnings: list[str] = []
    jigs = net_pin_jigs(dome_net, (0.0, 0.0), "outside", 40.0, 5.0, warnings)
    assert not warnings and len(jigs) == 5 * 6  # 4 parallels: 5 rings from the opening to the equator, 6 meridians
    for jig in jigs:
        points = jig.points()
        surface = (points[:, 0] ** 2 + points[:, 1] ** 2) / A**2 + points[:, 2] ** 2 / B**2 - 1.0
        assert np.abs(surface).max() < 1e-12  # measured 2.4e-13
        plane = (points - jig.origin) @ np.stack([jig.x_dir, jig.y_dir]).T
        assert np.abs(plane - jig.xy).max() < 1e-9 * A  # each pin on its grid point
        assert np.allclose(jig.xy / jig.spacing, np.rint(jig.xy / jig.spacing), atol=1e-12)
        assert jig.heights.min() >= 5.0 - 1e-9  # the clearance
        assert _on_the_panel(points, jig, dome_net)
        assert len(jig.lines) >= 2  # a panel lies between lines (and the boundary)


def test_a_walls_pins_touch_its_outer_surface_as_a_trough(dome_net):
    """Stiffeners inside: the pins carry the outer surface (the wall's outer offset, here 3
    along the outward normal: the exact distance from the dome's surface), the panel a trough
    (up against the outward normal)."""
    from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
    from OCP.gp import gp_Pnt

    from tubecad.shop.net_pin_jigs import net_pin_jigs

    jigs = net_pin_jigs(dome_net, (-5.0, 3.0), "inside", 40.0, 0.0, [])
    jig = max(jigs, key=lambda j: len(j.heights))
    for point in jig.points():
        projection = GeomAPI_ProjectPointOnSurf(gp_Pnt(*point), dome_net.host.surface)
        assert projection.LowerDistance() == pytest.approx(3.0, abs=1e-9)
    middle = jig.points().mean(axis=0)
    outward = np.array([middle[0] / A**2, middle[1] / A**2, middle[2] / B**2])
    assert float(jig.up @ outward) < 0  # a trough


def test_a_cell_folding_over_its_plane_is_named_in_a_warning():
    """A net of one line a family on the dome makes panels half round it: no jig plane sees
    such a panel as a height field."""
    from tubecad.export.cad import read_faces
    from tubecad.nets import curvature_net
    from tubecad.occ_compat import as_face
    from tubecad.shop.net_pin_jigs import net_pin_jigs

    net = curvature_net(as_face(read_faces(ROOT / "samples" / "dome.step")[0][1]), 1, 2)
    warnings: list[str] = []
    jigs = net_pin_jigs(net, (0.0, 0.0), "outside", 50.0, 0.0, warnings)
    assert warnings and all("no pin jig" in w for w in warnings)
    assert len(jigs) + len(warnings) == 2 * 2
