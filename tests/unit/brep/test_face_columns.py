"""A layout whose stringers leave an arc of the circle over 330 deg (one stringer, or all of
them within 30 deg) gets its faces split at the circle's C0 knot in that arc (issue 24): OCCT's
pre-boolean check, FreeCAD's, reports every face that runs over a C0 knot, and did on every
one-stringer tube and wall before. Checked against closed forms of straight cylinders and
cones: the split line is the curvature line diametrically opposite the stringers' middle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad import NaturalAxis
from tubecad.brep import NetLayout, build_tube_solid, build_wall_solid
from tubecad.brep.properties import analyzer_findings, is_valid, volume
from tubecad.stiffeners.panels import split_into_panels
from tubecad.surface.canal import tube_or_canal

MODES = ("ContinuityMode", "CurveOnSurfaceMode")
RHO, LENGTH = 10.0, 100.0


def cylinder():
    return tube_or_canal(NaturalAxis("0", "0", (0.0, LENGTH)), RHO)


def cone():
    return tube_or_canal(NaturalAxis("0", "0", (0.0, LENGTH)), "10 + 0.05 * s")


@pytest.mark.parametrize(
    ("stringers", "columns"),
    [([0.0], [0.0, 180.0]), ([0.0, 10.0], [0.0, 10.0, 185.0]), ([0.0, 90.0, 180.0, 270.0], None)],
)
def test_the_faces_end_at_every_c0_knot_of_the_circle(stringers, columns):
    tube = cylinder()
    build = build_tube_solid(tube, NetLayout.explicit(tube, [0.0, 50.0, LENGTH], stringers), 1e-9)
    patches = build.patches[0]
    assert is_valid(build.shape) and analyzer_findings(build.shape, MODES) == {}
    assert patches.columns_deg == columns  # None: the stringers are the columns
    n = len(columns or stringers)
    assert all(len(row) == n for row in patches.faces) and len(patches.stringers) == len(stringers)
    assert len(build.stringer_wires()) == len(stringers)  # the extra line is no named stringer
    assert volume(build.shape) == pytest.approx(math.pi * RHO**2 * LENGTH, rel=1e-12)
    if columns:
        # the split line is the surface's line u = const at the column's angle: on a straight
        # cylinder x = rho (cos a, sin a) in the frame of the first stringer, so its points lie
        # 2 rho sin((a - a_0) / 2) from the first stringer's at the same s
        extra = patches.columns[len(columns) - 1]
        first = patches.stringers[0]
        for e_extra, e_first in zip(extra, first):
            for t in (0.0, 0.5, 1.0):
                p, q = np.array(_point(e_extra, t)), np.array(_point(e_first, t))
                assert np.linalg.norm(p - q) == pytest.approx(
                    2 * RHO * math.sin(math.radians(columns[-1]) / 2), rel=1e-9
                )


def _point(edge, t: float) -> tuple[float, float, float]:
    import build123d as bd

    return tuple(bd.Edge(edge).position_at(t))


def test_a_one_stringer_wall_and_its_canal_twin_are_clean_and_panel_whole():
    """A wall of one stringer on a cylinder and on a cone (the canal surfaces' own faces and
    panels): clean, and its one seam's panels make up the wall's volume."""
    for tube, exact in (
        (cylinder(), math.pi * ((RHO + 0.5) ** 2 - (RHO - 0.5) ** 2) * LENGTH),
        # the cone's wall, capped by the normal cones of its end circles: in a meridian plane a
        # rectangle 1 wide (the normal offsets) and L cos(a) long (the normals at the ends pass
        # through the axis at s = 0 and L; sin a = r' = 0.05), centred on the characteristic circle
        # of s = L / 2, radius r q = 12.5 cos(a): Pappus, 2 pi 12.5 cos(a) L cos(a)
        (cone(), 2 * math.pi * 12.5 * LENGTH * (1 - 0.05**2)),
    ):
        build = build_wall_solid(tube, 1.0, "centered", NetLayout.explicit(tube, [0.0, 40.0, LENGTH], [0.0]))
        assert is_valid(build.shape) and analyzer_findings(build.shape, MODES) == {}
        assert all(len(row) == 2 for row in build.patches[0].faces)
        panels = split_into_panels(build, [0])
        assert len(panels) == 2 and all(analyzer_findings(p.solid, MODES) == {} for p in panels)
        total = sum(volume(p.solid) for p in panels)
        assert total == pytest.approx(volume(build.shape), rel=1e-9)
        assert total == pytest.approx(exact, rel=1e-9)
