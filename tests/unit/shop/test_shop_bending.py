"""Bending tables and inverse bending curves (tubecad/shop/bending.py).

Expected values come from closed forms written here (a circle's sagitta and chord, the paper's
eq. 7 for the tube on a slope-curve helix with its arc length in closed form, inverted here by
root finding) and from an independent bend back: the table alone rebuilt by a cubic spline
here and compared with the exact curve, never from the bending code's output.
"""

import csv
import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from tubecad import CurvatureLineTube, Helix, NaturalAxis
from tubecad.core.errors import ParameterError
from tubecad.shop.bending import (
    BendingTable,
    bending_table,
    ring_arcs,
    stringer_line,
    write_bending_csv,
    write_bending_picture,
)
from tubecad.surface.canal import CanalSurface


# --- ring arcs: circles --------------------------------------------------------------------------
def circle_table(radius, theta, arc_length):
    """(chord_x, offset_y) of the arc of ``radius`` and angle ``theta`` at ``arc_length``: with
    phi = sigma / R measured from the arc's start, the chord from phi = 0 to theta and y
    towards the arc's middle (its farthest point),
        x = R sin(phi - theta/2) + R sin(theta/2),  y = R cos(phi - theta/2) - R cos(theta/2)."""
    phi = arc_length / radius
    return (
        radius * np.sin(phi - theta / 2) + radius * math.sin(theta / 2),
        radius * np.cos(phi - theta / 2) - radius * math.cos(theta / 2),
    )


@pytest.mark.parametrize("pieces", [2, 3, 5])
def test_ring_arc_offsets_are_the_circles_sagitta(pieces):
    R, s = 500.0, 40.0
    tube = CurvatureLineTube(NaturalAxis("0", "0", (0.0, 100.0)), R)
    arcs = ring_arcs(tube, s, pieces=pieces, start_deg=10.0)
    theta = 2 * math.pi / pieces
    assert [length for _, length in arcs] == pytest.approx([R * theta] * pieces, rel=1e-15)
    for j, (position, length) in enumerate(arcs):
        sigma = np.linspace(0.0, length, 9)  # the arc is the tube's ring: S(u, s), u = 10 deg + j theta + sigma / R
        u = math.radians(10.0) + j * theta + sigma / R
        assert np.abs(position(sigma) - tube.points(u, np.full_like(u, s))).max() < 1e-14 * R  # measured 1.1e-16 R
        table = bending_table(position, length, f"ring_{j}", "ring base circle")
        x, y = circle_table(R, theta, table.arc_length)
        assert np.abs(table.offset_z).max() < 1e-14 * R  # planar; measured 0 (a straight axis: exact frame)
        assert np.abs(table.chord_x - x).max() < 1e-14 * R  # measured <= 1.4e-15 R
        assert np.abs(table.offset_y - y).max() < 1e-14 * R  # measured <= 1.1e-15 R
        assert np.array_equal(table.inverse_y, -table.offset_y)
        assert table.bend_back_error <= 0.1
    sagitta = R * (1 - math.cos(theta / 2))  # at the middle station (equal divisions: one is there)
    assert table.max_offset == pytest.approx(sagitta, rel=1e-14)  # measured <= 3e-15


def test_ring_arcs_on_a_cone_are_its_characteristic_circle():
    """The cone r = 2 + 0.3 s on the x axis: its sphere of radius r at x = s touches it along the
    circle at x = s - r r' of radius r q; the offset r + d has the circle of (r + d) q there."""
    cone = CanalSurface(NaturalAxis("0", "0", (0.0, 40.0)), "2.0 + 0.3 * s")
    s, d = 20.0, 1.5
    r, q = 2.0 + 0.3 * s + d, math.sqrt(1 - 0.09)
    arcs = ring_arcs(cone, s, level=d, pieces=4)
    for position, length in arcs:
        assert length == pytest.approx(2 * math.pi * r * q / 4, rel=1e-14)
        p = position(np.linspace(0.0, length, 33))
        assert np.abs(p[:, 0] - (s - r * 0.3)).max() < 1e-13  # measured 7e-15
        assert np.abs(np.hypot(p[:, 1], p[:, 2]) - r * q).max() < 1e-13  # measured 2e-14
        table = bending_table(position, length, "ring", "ring flange centre circle", max_error=1e-3)
        x, y = circle_table(r * q, math.pi / 2, table.arc_length)
        assert np.abs(table.chord_x - x).max() < 1e-13 and np.abs(table.offset_y - y).max() < 1e-13  # <= 1.8e-14
        assert np.abs(table.offset_z).max() < 1e-13  # measured 0


def test_given_spacing_and_the_largest_spacing_that_meets_max_error():
    R = 500.0
    position, length = ring_arcs(CurvatureLineTube(NaturalAxis("0", "0", (0.0, 100.0)), R), 50.0)[0]
    table = bending_table(position, length, "ring_a", "ring base circle", spacing=100.0)
    n = math.floor(length / 100.0)
    assert np.array_equal(table.arc_length, np.r_[np.arange(n + 1) * 100.0, length])  # every 100, and the end
    auto = bending_table(position, length, "ring_a", "ring base circle", max_error=0.1)
    assert auto.bend_back_error <= 0.1 and auto.spacing == pytest.approx(length / (len(auto.arc_length) - 1))
    # the next coarser candidate does not meet it
    coarser = {4: None, 6: 4, 8: 6, 12: 8, 16: 12, 24: 16, 32: 24, 48: 32, 64: 48}[len(auto.arc_length) - 1]
    with pytest.raises(ParameterError, match=r"^spacing: ring_a: the bend-back error .* exceeds max_error 0\.1"):
        bending_table(position, length, "ring_a", "ring base circle", spacing=length / coarser)


# --- a helix tube's stringer ------------------------------------------------------------------------
K, BETA, LENGTH, R, THETA = 0.01, 20.0, 600.0, 10.0, 30.0
B, U = math.radians(BETA), math.radians(THETA)
C = K * math.tan(B)  # the RMF's turn from the Frenet frame per unit s: w = psi sin b = c s


def helix_tube_points(s, rho):
    """Paper eq. 7: the tube of radius rho on the slope-curve helix k = const, psi = k s / cos b,
    phi = u - psi sin b (placed with c(0) = 0; a rigid motion does not change a table)."""
    psi = K * s / math.cos(B)
    phi = U - psi * math.sin(B)
    cb2k = math.cos(B) ** 2 / K  # cos b Int cos psi ds = cb2k sin psi
    return np.stack(
        [
            cb2k * np.sin(psi) - rho * (np.sin(psi) * np.cos(phi) + math.sin(B) * np.cos(psi) * np.sin(phi)),
            cb2k * (1 - np.cos(psi)) + rho * (np.cos(psi) * np.cos(phi) - math.sin(B) * np.sin(psi) * np.sin(phi)),
            s * math.sin(B) + rho * math.cos(B) * np.sin(phi),
        ],
        axis=-1,
    )


def helix_arc_length(s, rho):
    """Int_0^s (1 - rho k cos(u - c s)) ds = s - rho k (sin u - sin(u - c s)) / c."""
    return s - rho * K * (math.sin(U) - np.sin(U - C * s)) / C


def chord_frame(points_of_s, s_end):
    """The test's own chord frame: x along the chord, y towards the farthest point, found by
    dense sampling and the root of p . dp/ds, dp/ds by the complex step (exact to round-off)."""
    p0, p1 = points_of_s(np.array([0.0, s_end]))
    x = (p1 - p0) / np.linalg.norm(p1 - p0)

    def perp(s):
        d = points_of_s(s) - p0
        return d - np.multiply.outer(d @ x, x)

    def slope(s):
        p = perp(np.array([s + 1e-30j]))[0]
        return float(p.real @ (p.imag / 1e-30))

    grid = np.linspace(0.0, s_end, 20001)
    i = int(np.argmax((perp(grid) ** 2).sum(axis=1)))
    far = perp(np.array([brentq(slope, grid[i - 1], grid[i + 1], xtol=1e-13)]))[0].real
    y = far / np.linalg.norm(far)
    return p0, np.stack([x, y, np.cross(x, y)])


@pytest.fixture(scope="module")
def helix_tube():
    return CurvatureLineTube(Helix(K, BETA, (0.0, LENGTH)), R)


@pytest.mark.parametrize("level", [0.0, 3.8])
def test_helix_stringer_table_and_its_bend_back(helix_tube, level):
    rho = R + level
    position, length = stringer_line(helix_tube, THETA, level)
    assert length == pytest.approx(helix_arc_length(LENGTH, rho), rel=2e-15)  # measured 6e-16
    table = bending_table(position, length, "stringer_01", "web base on the wall" if level == 0 else "flange centre")
    assert table.bend_back_error <= 0.1

    # the stations' points in closed form: s_i from sigma(s_i) = arc_length_i
    s_i = np.array([brentq(lambda s: helix_arc_length(s, rho) - a, 0.0, LENGTH, xtol=1e-14) for a in table.arc_length])
    exact = helix_tube_points(s_i, rho)
    got = position(table.arc_length)  # the same points up to a rigid motion: equal distances
    pairs = np.linalg.norm(exact[:, None] - exact[None], axis=-1) - np.linalg.norm(got[:, None] - got[None], axis=-1)
    assert np.abs(pairs).max() < 2e-12  # measured 2.4e-13

    origin, frame = chord_frame(lambda s: helix_tube_points(s, rho), LENGTH)
    local = (exact - origin) @ frame.T
    assert np.abs(table.chord_x - local[:, 0]).max() < 1e-12  # measured <= 1.7e-13
    assert np.abs(table.offset_y - local[:, 1]).max() < 2e-8  # measured <= 3.4e-9 and, in z, 6.5e-9: the
    assert np.abs(table.offset_z - local[:, 2]).max() < 2e-8  # code's farthest point (central differences)
    assert table.max_offset > 100.0 and np.abs(table.offset_z).max() > 50.0  # a twisted piece

    # bend back from the table alone: the spline at sigma(s) against the exact point at s
    spline = CubicSpline(table.arc_length, np.c_[table.chord_x, table.offset_y, table.offset_z], axis=0)
    s = np.linspace(0.0, LENGTH, 40001)
    distance = np.linalg.norm(spline(helix_arc_length(s, rho)) - (helix_tube_points(s, rho) - origin) @ frame.T, axis=1)
    nodes, weights = np.polynomial.legendre.leggauss(10)
    a = table.arc_length
    mid, half = 0.5 * (a[1:] + a[:-1]), 0.5 * np.diff(a)
    speed = np.linalg.norm(spline(mid[:, None] + half[:, None] * nodes, 1), axis=-1)
    spline_length = float((speed * weights).sum(axis=1) @ half)
    measured = max(distance.max(), abs(spline_length - length))
    assert table.bend_back_error == pytest.approx(measured, rel=1e-4)  # measured 1.7e-5 (4097 vs 40001 samples)
    assert 0.05 < measured <= 0.1


def test_stringer_line_over_a_span_of_a_canal_wall():
    """On a canal surface the stringer chi0 over a sub-span is the same curve as over the whole
    span, cut: its points by arc length from the sub-span's start lie on the whole line."""
    canal = CanalSurface(NaturalAxis("0.01", "0", (0.0, 40.0)), "2.0 + 0.03 * s")
    whole, whole_length = stringer_line(canal, 40.0, 0.5)
    part, part_length = stringer_line(canal, 40.0, 0.5, span=(10.0, 30.0))
    top = canal.offset(0.5)
    chi0 = math.radians(40.0)
    ends = top.points(np.full(2, chi0), np.array([10.0, 30.0]))
    assert np.abs(part(np.array([0.0, part_length])) - ends).max() < 1e-13  # measured 8.4e-15

    def along(a):  # (P(a) - start) . tangent: 0 where the whole line passes the part's start
        p = whole(np.array([a - 1e-6, a, a + 1e-6]))
        return float((p[1] - ends[0]) @ (p[2] - p[0]))

    offset = brentq(along, 5.0, 15.0, xtol=1e-13)
    assert np.linalg.norm(whole(np.array([offset]))[0] - ends[0]) < 1e-13  # measured 0
    sigma = np.linspace(0.0, part_length, 11)
    assert np.abs(part(sigma) - whole(offset + sigma)).max() < 1e-13  # measured 8.9e-15
    assert whole_length > part_length > 0.45 * whole_length


# --- files and refusals ------------------------------------------------------------------------------
def test_csv_reads_back_and_the_picture_is_written(tmp_path, helix_tube):
    position, length = stringer_line(helix_tube, THETA)
    tables = [bending_table(position, length, "stringer_01_a", "web base on the wall")]
    arcs = ring_arcs(helix_tube, 300.0)
    tables += [bending_table(p, n, f"ring_02_{k}", "ring base circle") for k, (p, n) in zip("ab", arcs)]
    path = write_bending_csv(tables, tmp_path / "bending.csv", length_unit="mm")
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0].startswith("#") and "mm" in lines[0]
    rows = list(csv.DictReader(lines[1:]))
    assert list(rows[0]) == ["name", "line", "station", "arc_length", "chord_x", "offset_y", "offset_z", "inverse_y"]
    for table in tables:
        mine = [r for r in rows if r["name"] == table.name]
        assert [int(r["station"]) for r in mine] == list(range(len(table.arc_length)))
        assert {r["line"] for r in mine} == {table.line}
        for key in ("arc_length", "chord_x", "offset_y", "offset_z", "inverse_y"):
            assert np.array_equal(np.array([float(r[key]) for r in mine]), getattr(table, key))  # exact: repr
    assert sum(len(t.arc_length) for t in tables) == len(rows)
    paths = write_bending_picture(tables, tmp_path, stem="bending")
    assert sorted(p.name for p in paths) == ["bending.png", "bending.svg"]
    assert all(p.stat().st_size > 1000 for p in paths)
    assert "ring_02_b" in (tmp_path / "bending.svg").read_text(encoding="utf-8")
    assert not list(tmp_path.glob(".*part*"))  # atomic: no temporaries left


def test_refusals(helix_tube):
    position, length = stringer_line(helix_tube, THETA)
    with pytest.raises(ParameterError) as info:
        bending_table(position, length, "stringer_01", "web base on the wall", max_error=1e-12)
    message = str(info.value)
    assert message.startswith("max_error: stringer_01: the bend-back error is still ") and "\n" not in message
    assert "with 1024 intervals" in message
    for bad in (0.0, -5.0):
        with pytest.raises(ParameterError, match=r"^spacing must be > 0"):
            bending_table(position, length, "stringer_01", "web", spacing=bad)
    with pytest.raises(ParameterError, match=r"^max_error must be > 0"):
        bending_table(position, length, "stringer_01", "web", max_error=0.0)
    with pytest.raises(ParameterError, match=r"^pieces must be an integer >= 2"):
        ring_arcs(helix_tube, 100.0, pieces=1)

    def circle(sigma):  # a full circle of radius 10
        return np.stack([10 * np.cos(sigma / 10), 10 * np.sin(sigma / 10), 0 * sigma], axis=-1)

    with pytest.raises(ParameterError, match=r"^length: ring ends where it starts .* a closed curve has no chord"):
        bending_table(circle, 20 * math.pi, "ring", "ring base circle")
    assert isinstance(bending_table(circle, 10 * math.pi, "ring", "half"), BendingTable)
