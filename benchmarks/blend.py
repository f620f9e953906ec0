"""The crotch blend beside OCCT's fillet on the same tee (issue 43).

``python benchmarks/blend.py [--json FILE]``. The tee: main R 50 along x, 300 long, wall 4;
branch r 30 square at x = 150, 150 long, wall 3 (outer cylinders 52 and 31.5); a rolling ball
of radius rb = 5 (and 2, 10) along the outer saddle. Each way is timed (best of 3) and measured:

- **OCCT**: the wall from exact cylinders, ``(Cylinder(52) + Cylinder(31.5)) - (Cylinder(48)
  + Cylinder(30))``, then build123d's ``fillet`` (``BRepFilletAPI_MakeFillet``) on the edges
  that lie on both outer cylinders;
- **tubecad**: :func:`tubecad.junctions.build_branched_wall` with ``blend`` (nets 7 x 8, 4 x 8).

For each: made or not, BRepCheck validity, OCCT's pre-boolean check, and the blend's largest
distance from the exact rolling-ball surface: points on the blend's faces (OCCT: the faces the
fillet made; tubecad: its blend rings and edges), each one's distance from the ball's centre
curve (the exact centres, :meth:`tubecad.junctions.blend.RollingBall.contact_points`, refined
by golden-section search in u_B) less rb.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import build123d as bd
import numpy as np
from scipy.spatial import cKDTree

from tubecad import NaturalAxis, tube_or_canal
from tubecad.brep import NetLayout
from tubecad.brep.properties import analyzer_findings, is_valid
from tubecad.junctions import BranchWall, branch_surface, build_branched_wall
from tubecad.junctions.blend import rolling_ball

R, r, T_MAIN, T_BRANCH, L, H = 50.0, 30.0, 4.0, 3.0, 300.0, 150.0
R_OUT, r_OUT = R + T_MAIN / 2, r + T_BRANCH / 2


def occt_wall() -> bd.Part:
    def cylinder(radius: float, length: float, along: str) -> bd.Part:
        if along == "x":
            return bd.Pos(L / 2, 0, 0) * bd.Rot(0, 90, 0) * bd.Cylinder(radius, length)
        return bd.Pos(150.0, 0, length / 2) * bd.Cylinder(radius, length)

    outside = cylinder(R_OUT, L, "x") + cylinder(r_OUT, H, "z")
    bore = cylinder(R - T_MAIN / 2, L + 2, "x") + cylinder(r - T_BRANCH / 2, H + 2, "z")
    return outside - bore


def saddle_edges(part: bd.Part) -> list[bd.Edge]:
    """The edges on both outer cylinders (the outer saddle)."""
    out = []
    for edge in part.edges():
        p = np.array([tuple(edge.position_at(t)) for t in np.linspace(0, 1, 7)])
        on_main = np.abs(np.hypot(p[:, 1], p[:, 2]) - R_OUT).max() < 1e-6
        on_branch = np.abs(np.hypot(p[:, 0] - 150.0, p[:, 1]) - r_OUT).max() < 1e-6
        if on_main and on_branch:
            out.append(edge)
    return out


def ball_distance(ball, points: np.ndarray) -> np.ndarray:
    """|P - C(u*)| - rb, C the ball's exact centre curve, u* where (P - C(u)) . C'(u) = 0 by
    Newton's method from the nearest of 4097 centres (C' and C'' by central differences of the
    exact centres), all points at once."""
    u = np.linspace(0.0, 2 * math.pi, 4097)
    centres = ball.contact_points(u)[0]
    _, nearest = cKDTree(centres).query(points)
    t = u[nearest]
    h = 1e-4
    for _ in range(12):
        c0, cp, cm = (ball.contact_points(t + d)[0] for d in (0.0, h, -h))
        d1, d2 = (cp - cm) / (2 * h), (cp - 2 * c0 + cm) / h**2
        gap = points - c0
        g = -np.einsum("pk,pk->p", gap, d1)
        dg = np.einsum("pk,pk->p", d1, d1) - np.einsum("pk,pk->p", gap, d2)
        step = -g / dg
        t = t + np.clip(step, -0.01, 0.01)
        if np.abs(step).max() < 1e-12:
            break
    return np.linalg.norm(points - ball.contact_points(t)[0], axis=1) - ball.radius


def face_points(faces, n: int = 7) -> np.ndarray:
    return np.array(
        [
            tuple(f.position_at(a, b))
            for f in faces
            for a in np.linspace(0.05, 0.95, n)
            for b in np.linspace(0.05, 0.95, n)
        ]
    )


def one(rb: float) -> dict:
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, L), origin=(0, 0, 0), tangent=(1, 0, 0), normal=(0, 1, 0)), R)
    branch = branch_surface(main, 150.0, H, r)
    ball = rolling_ball(main.offset(T_MAIN / 2), branch.offset(T_BRANCH / 2), rb, 1e-8)
    row: dict = {"rb": rb}
    wall = occt_wall()
    edges = saddle_edges(wall)
    best = math.inf
    filleted = None
    for _ in range(3):
        start = time.perf_counter()
        try:
            filleted = wall.fillet(rb, edges)
        except Exception as exc:  # OCCT's fillet raises on failure (StdFail_NotDone)
            row["occt"] = {"made": False, "error": f"{type(exc).__name__}: {exc}"[:200]}
            break
        best = min(best, time.perf_counter() - start)
    if filleted is not None and "occt" not in row:
        new_faces = [f for f in filleted.faces() if f.geom_type.name not in ("CYLINDER", "PLANE")]
        deviation = np.abs(ball_distance(ball, face_points(new_faces)))
        row["occt"] = {
            "made": True,
            "seconds": best,
            "valid": bool(is_valid(filleted.wrapped)),
            "pre_boolean_check": analyzer_findings(filleted.wrapped),
            "fillet_faces": len(new_faces),
            "deviation": float(deviation.max()),
        }
    best = math.inf
    for _ in range(3):
        start = time.perf_counter()
        junction = build_branched_wall(
            main, T_MAIN, [BranchWall(branch, T_BRANCH, blend=rb)], main_layout=NetLayout.equal(main, 7, 8)
        )
        best = min(best, time.perf_counter() - start)
    blend_edges = [e for name, es in junction.edges.items() if name.startswith("blend") for e in es]
    points = np.array([tuple(e.position_at(t)) for e in blend_edges for t in np.linspace(0, 1, 9)])
    row["tubecad"] = {
        "seconds": best,
        "valid": bool(is_valid(junction.shape.wrapped)),
        "pre_boolean_check": analyzer_findings(junction.shape.wrapped),
        "blend_edges": len(blend_edges),
        "deviation": float(np.abs(ball_distance(junction.blends[0], points)).max()),
    }
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    rows = []
    for rb in (2.0, 5.0, 10.0):
        row = one(rb)
        rows.append(row)
        print(json.dumps(row), flush=True)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
