"""Pin-jig tables (tubecad.shop.pin_jig): every touching point checked against the closed form
of the surface written here, every height against an independent line-surface intersection."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from tubecad import CurvatureLineTube, NaturalAxis, ParameterError
from tubecad.shop.pin_jig import pin_jig, write_pin_jig_csv, write_pin_jig_picture
from tubecad.surface.canal import CanalSurface

R = 10.0  # cylinder about the x axis (r1 = y, r2 = z: u = atan2(z, y), s = x)
A, RT = 100.0, 30.0  # torus: centre circle of radius A about (0, A, 0) in the xy-plane, tube radius RT
CYLINDER_PANEL = dict(s_range=(10.0, 60.0), angles_deg=(20.0, 110.0))
TORUS_PANEL = dict(s_range=(50.0, 150.0), angles_deg=(150.0, 210.0))


@pytest.fixture(scope="module")
def cylinder():
    return CurvatureLineTube(NaturalAxis("0", "0", (0.0, 100.0)), R)


@pytest.fixture(scope="module")
def torus():
    return CurvatureLineTube(NaturalAxis("0.01", "0", (0.0, 300.0)), RT)


@pytest.fixture(scope="module")
def cylinder_jig(cylinder):
    return pin_jig(cylinder, spacing=2.5, clearance=2.0, name="cyl_panel", **CYLINDER_PANEL)


@pytest.fixture(scope="module", params=[1.0, -1.0], ids=["dome", "trough"])
def torus_jig(torus, request):
    return pin_jig(torus, spacing=4.0, up_sign=request.param, clearance=0.5, name="torus_panel", **TORUS_PANEL)


def inside(u: float, s: float, panel: dict, slack: float = 1e-9) -> bool:
    (s_a, s_b), (u_a, u_b) = panel["s_range"], panel["angles_deg"]
    u = (u - u_a) % 360.0 + u_a  # the angle's turn that falls in [u_a, u_a + 360)
    return u_a - slack <= u <= u_b + slack and s_a - slack <= s <= s_b + slack


def cylinder_hits(foot: np.ndarray, up: np.ndarray) -> list[tuple[float, float, float]]:
    """(t, u_deg, s) where the line foot + t up meets y^2 + z^2 = R^2 (a quadratic in t)."""
    a = up[1] ** 2 + up[2] ** 2
    b = 2.0 * (foot[1] * up[1] + foot[2] * up[2])
    c = foot[1] ** 2 + foot[2] ** 2 - R * R
    disc = b * b - 4.0 * a * c
    if disc < 0:
        return []
    out = []
    for t in ((-b - math.sqrt(disc)) / (2 * a), (-b + math.sqrt(disc)) / (2 * a)):
        p = foot + t * up
        out.append((t, math.degrees(math.atan2(p[2], p[1])), float(p[0])))
    return out


def torus_angles(p: np.ndarray) -> tuple[float, float]:
    """(u_deg, s) of a torus point: s = A phi, phi its angle round the torus' axis from the
    start of the centre circle; u from rho = A - RT cos u, z = RT sin u."""
    phi = math.atan2(p[0], A - p[1])
    rho = math.hypot(p[0], p[1] - A)
    return math.degrees(math.atan2(p[2], A - rho)), A * phi


def torus_hits(foot: np.ndarray, up: np.ndarray) -> list[tuple[float, float, float]]:
    """(t, u_deg, s) where foot + t up meets (|q|^2 + A^2 - RT^2)^2 = 4 A^2 (qx^2 + qy^2),
    q = p - (0, A, 0): a quartic in t, solved with numpy.roots and polished by Newton."""
    q0 = foot - np.array([0.0, A, 0.0])
    norm2 = np.array([up @ up, 2.0 * q0 @ up, q0 @ q0 + A * A - RT * RT])
    planar = (
        4.0
        * A
        * A
        * np.array([up[0] ** 2 + up[1] ** 2, 2.0 * (q0[0] * up[0] + q0[1] * up[1]), q0[0] ** 2 + q0[1] ** 2])
    )
    quartic = np.polysub(np.polymul(norm2, norm2), planar)
    out = []
    for root in np.roots(quartic):
        if abs(root.imag) > 1e-6 * max(1.0, abs(root)):
            continue
        t = root.real
        for _ in range(4):
            t -= np.polyval(quartic, t) / np.polyval(np.polyder(quartic), t)
        out.append((t, *torus_angles(foot + t * up)))
    return out


def check_table(jig, surface, panel: dict, hits, on_surface, clearance: float) -> None:
    # the plane's frame
    frame = np.stack([jig.x_dir, jig.y_dir, jig.up])
    assert np.abs(frame @ frame.T - np.eye(3)).max() < 1e-14
    assert np.linalg.det(frame) == pytest.approx(1.0, abs=1e-14)
    # pins on the regular grid, i, j >= 0, each once
    ij = jig.xy / jig.spacing
    assert np.abs(ij - np.rint(ij)).max() < 1e-12
    assert ij.min() > -1e-12 and ij.min(axis=0).max() < 1e-12
    assert len({tuple(x) for x in jig.indices}) == len(jig.xy)
    # touching points: on the exact surface, above their pins, no lower than the clearance
    points = jig.points()
    assert on_surface(points).max() < 1e-11  # measured 1.1e-13 (torus), 1.2e-14 (cylinder)
    touching = surface.points(np.radians(jig.angles_deg), jig.s)
    assert np.abs(touching - points).max() < 1e-11  # measured 4.3e-14
    plane = (touching - jig.origin) @ np.stack([jig.x_dir, jig.y_dir]).T
    assert np.abs(plane - jig.xy).max() < 1e-11  # measured 4.3e-14
    assert jig.heights.min() >= clearance - 1e-12
    assert all(inside(u, s, panel) for u, s in zip(jig.angles_deg, jig.s))
    # an independent intersection of each pin's vertical line with the surface
    for k, (x, y) in enumerate(jig.xy):
        foot = jig.origin + x * jig.x_dir + y * jig.y_dir
        found = [hit for hit in hits(foot, jig.up) if inside(hit[1], hit[2], panel)]
        assert len(found) == 1
        t, u, s = found[0]
        assert t == pytest.approx(jig.heights[k], abs=1e-11)  # measured 1.7e-13
        assert np.linalg.norm(foot + t * jig.up - points[k]) < 1e-11
    # and every grid point whose line meets the panel is a pin
    i_max, j_max = jig.indices.max(axis=0)
    table = {tuple(x) for x in jig.indices}
    for i in range(-2, i_max + 3):
        for j in range(-2, j_max + 3):
            foot = jig.origin + i * jig.spacing * jig.x_dir + j * jig.spacing * jig.y_dir
            meets = any(inside(u, s, panel, slack=-1e-7) for _, u, s in hits(foot, jig.up))
            assert meets <= ((i, j) in table)


def test_cylinder_jig(cylinder, cylinder_jig):
    jig = cylinder_jig
    # the area-weighted mean outward normal of the panel: (0, cos 65, sin 65); x along the axis
    assert np.abs(jig.up - [0.0, math.cos(math.radians(65.0)), math.sin(math.radians(65.0))]).max() < 1e-14
    assert np.abs(jig.x_dir - [1.0, 0.0, 0.0]).max() < 1e-14
    # the lowest points are the seams, at R cos 45 along up; the plane 2 below them
    assert float(jig.origin @ jig.up) == pytest.approx(R * math.cos(math.radians(45.0)) - 2.0, abs=1e-12)
    check_table(jig, cylinder, CYLINDER_PANEL, cylinder_hits, lambda p: np.abs(np.hypot(p[:, 1], p[:, 2]) - R), 2.0)
    assert len(jig.heights) == 21 * 5  # x: 50 / 2.5 + 1 columns; y within +-R sin 45 = +-7.07: 0, +-2.5, +-5


def test_torus_jig(torus, torus_jig):
    jig = torus_jig

    def off(p: np.ndarray) -> np.ndarray:  # the distance to the torus
        return np.abs(np.hypot(np.hypot(p[:, 0], p[:, 1] - A) - A, p[:, 2]) - RT)

    check_table(jig, torus, TORUS_PANEL, torus_hits, off, 0.5)
    assert len(jig.heights) > 100


def test_cone_touching_points():
    cone = CanalSurface(NaturalAxis("0", "0", (0.0, 40.0)), "2.0 + 0.3 * s")
    jig = pin_jig(cone, (5.0, 35.0), (-30.0, 60.0), 2.0)
    p = jig.points()
    # the cone r = 0.3 (s - s0) enveloped: rho = 0.3 / q (x - s0), s0 = -2 / 0.3 its apex
    slope = 0.3 / math.sqrt(1 - 0.09)
    assert np.abs(np.hypot(p[:, 1], p[:, 2]) - slope * (p[:, 0] + 2.0 / 0.3)).max() < 1e-9
    assert len(jig.heights) > 30


def test_csv_reads_back(cylinder_jig, tmp_path):
    jig = cylinder_jig
    path = write_pin_jig_csv(jig, tmp_path / "cyl_panel_pin_jig.csv")
    with open(path, newline="", encoding="utf-8") as f:
        assert f.readline() == "# units: mm\n"
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == ["pin", "i", "j", "x", "y", "height", "u_deg", "s"]
    assert [int(r["pin"]) for r in rows] == list(range(1, len(jig.heights) + 1))
    assert np.array_equal([[int(r["i"]), int(r["j"])] for r in rows], jig.indices)
    for key, values in (
        ("x", jig.xy[:, 0]),
        ("y", jig.xy[:, 1]),
        ("height", jig.heights),
        ("u_deg", jig.angles_deg),
        ("s", jig.s),
    ):
        assert np.array_equal([float(r[key]) for r in rows], values)  # repr: exact
    with open(write_pin_jig_csv(jig, tmp_path / "m.csv", length_unit="m"), encoding="utf-8") as f:
        assert f.readline() == "# units: m\n"


def test_picture(torus, tmp_path):
    jig = pin_jig(torus, spacing=8.0, name="torus_panel", **TORUS_PANEL)
    paths = write_pin_jig_picture(jig, tmp_path)
    assert sorted(p.name for p in paths) == ["torus_panel_pin_jig.png", "torus_panel_pin_jig.svg"]
    assert all(p.stat().st_size > 1000 for p in paths)


def test_bad_input(cylinder):
    for spacing in (0.0, -1.0, math.nan, math.inf, "5"):
        with pytest.raises(ParameterError, match="pin_spacing must be > 0"):
            pin_jig(cylinder, spacing=spacing, **CYLINDER_PANEL)
    with pytest.raises(ParameterError, match="up_sign"):
        pin_jig(cylinder, spacing=1.0, up_sign=0.5, **CYLINDER_PANEL)
    with pytest.raises(ParameterError, match="clearance"):
        pin_jig(cylinder, spacing=1.0, clearance=-1.0, **CYLINDER_PANEL)
    with pytest.raises(ParameterError, match="not a graph"):
        pin_jig(cylinder, (10.0, 60.0), (0.0, 200.0), 1.0)
    # a spacing larger than the panel still gives the pin under the middle point
    jig = pin_jig(cylinder, spacing=1e4, **CYLINDER_PANEL)
    assert len(jig.heights) == 1 and jig.angles_deg[0] == pytest.approx(65.0) and jig.s[0] == pytest.approx(35.0)
