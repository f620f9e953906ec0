"""A tee as a build123d user makes it today, beside tubecad's junction wall (issue 25).

``python benchmarks/tee.py [--json FILE]``. The same tee: main tube R 50 along x, 300 long,
wall 4; branch r 30 up z from the main axis, 120 long, wall 3 (d/D = 0.6), both centred on
their radius. Each way is timed (best of 3), then checked in one process:

- **build123d, primitives**: ``(Cylinder(R_o) + Cylinder(r_o)) - (Cylinder(R_i) + Cylinder(r_i))``
  (the usual recipe: exact OCCT cylinders, fused and bored);
- **build123d, sweeps**: the same with each tube a ``sweep`` of its circle along its axis line
  (what a user does once the axis is not straight);
- **tubecad**: :func:`tubecad.junctions.build_junction_wall` (both tubes' rings and stringers
  as edges, 7 x 8 on the main, 4 x 8 on the branch).

For each: the time, BRepCheck validity, OCCT's pre-boolean check (every check on), the volume
against the closed form (the walls less the cylinders' overlap by quadrature), whether the
saddle is a set of edges and whether they carry a name, how many named curvature lines the
solid has, and a 1 mm fillet along the outer saddle (build123d's ``fillet`` on the edges
that lie on both outer cylinders): made, valid, and its time.

A second case puts a nozzle on a bend (samples/nozzle_on_torus.toml: a quarter torus of axis
radius 300, R 60 wall 5, a nozzle r 15 wall 3 on its crown): the build123d user sweeps the
circles along the arc and fuses a cylinder on (no closed-form volume: the tubecad and
build123d volumes are compared with each other); tubecad builds the spec's junction.

A third times samples/tee.toml whole (the junction, its pad and its 16 stiffeners), the case
of the issue's target (a valid, analyzer-clean stiffened tee with named saddles in under 2 s).
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import build123d as bd
import numpy as np
from scipy.integrate import quad

from tubecad import NaturalAxis, tube_or_canal
from tubecad.brep import NetLayout
from tubecad.brep.properties import analyzer_findings, is_valid, volume
from tubecad.junctions import build_junction_wall

R, r, T_MAIN, T_BRANCH, L, H = 50.0, 30.0, 4.0, 3.0, 300.0, 120.0
R_OUT, R_IN, r_OUT, r_IN = R + T_MAIN / 2, R - T_MAIN / 2, r + T_BRANCH / 2, r - T_BRANCH / 2
FILLET = 1.0


def exact_volume() -> float:
    def overlap(big: float, small: float) -> float:
        return quad(lambda y: 2 * math.sqrt(small**2 - y**2) * math.sqrt(big**2 - y**2), -small, small, epsrel=1e-13)[0]

    outer = math.pi * R_OUT**2 * L + math.pi * r_OUT**2 * H - overlap(R_OUT, r_OUT)
    inner = math.pi * R_IN**2 * L + math.pi * r_IN**2 * H - overlap(R_IN, r_IN)
    return outer - inner


def primitives() -> bd.Shape:
    along_x = bd.Pos(-L / 2, 0, 0) * bd.Rot(0, 90, 0)
    main = [
        along_x * bd.Cylinder(radius, L, align=(bd.Align.CENTER, bd.Align.CENTER, bd.Align.MIN))
        for radius in (R_OUT, R_IN)
    ]
    branch = [
        bd.Cylinder(radius, H, align=(bd.Align.CENTER, bd.Align.CENTER, bd.Align.MIN)) for radius in (r_OUT, r_IN)
    ]
    return (main[0] + branch[0]) - (main[1] + branch[1])


def sweeps() -> bd.Shape:
    def swept(start: tuple, end: tuple, radius: float) -> bd.Solid:
        path = bd.Edge.make_line(start, end)
        circle = bd.Wire([bd.Edge.make_circle(radius, bd.Plane(origin=start, z_dir=path.tangent_at(0)))])
        return bd.Solid(bd.sweep(bd.Face(circle), path).wrapped)

    main = [swept((-L / 2, 0, 0), (L / 2, 0, 0), radius) for radius in (R_OUT, R_IN)]
    branch = [swept((0, 0, 0), (0, 0, H), radius) for radius in (r_OUT, r_IN)]
    return (main[0] + branch[0]) - (main[1] + branch[1])


def tubecad_tee():
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, L), origin=(-L / 2, 0, 0), tangent=(1, 0, 0), normal=(0, 1, 0)), R)
    branch = tube_or_canal(NaturalAxis("0", "0", (0.0, H), origin=(0, 0, 0), tangent=(0, 0, 1), normal=(1, 0, 0)), r)
    return build_junction_wall(
        main,
        branch,
        T_MAIN,
        T_BRANCH,
        main_layout=NetLayout.equal(main, 7, 8),
        branch_layout=NetLayout.equal(branch, 4, 8),
    )


def outer_saddle(shape: bd.Shape) -> list[bd.Edge]:
    """The edges on both outer cylinders (y^2 + z^2 = R_o^2 and x^2 + y^2 = r_o^2)."""
    found = []
    for edge in shape.edges():
        p = np.array([tuple(edge.position_at(t)) for t in np.linspace(0, 1, 9)])
        if (
            np.abs(np.hypot(p[:, 1], p[:, 2]) - R_OUT).max() < 1e-5
            and np.abs(np.hypot(p[:, 0], p[:, 1]) - r_OUT).max() < 1e-5
        ):
            found.append(edge)
    return found


def timed(make, repeats: int = 3):
    best, value = math.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        value = make()
        best = min(best, time.perf_counter() - start)
    return value, best


def fillet(shape: bd.Shape, edges: list[bd.Edge]) -> dict:
    start = time.perf_counter()
    try:
        rounded = shape.fillet(FILLET, edges)
        ok = is_valid(rounded.wrapped)
        return {"made": True, "valid": ok, "seconds": round(time.perf_counter() - start, 2)}
    except Exception as exc:  # a failed fillet is the result
        return {
            "made": False,
            "error": f"{type(exc).__name__}: {exc}"[:160],
            "seconds": round(time.perf_counter() - start, 2),
        }


def bend_sweeps() -> bd.Shape:
    """The nozzle on the bend as a build123d user makes it: circles swept along the arc, cylinders fused."""
    arc = bd.Edge.make_circle(300.0, bd.Plane.XY, start_angle=0.0, end_angle=90.0)
    start, tangent = arc.position_at(0), arc.tangent_at(0)

    def swept(radius: float) -> bd.Solid:
        circle = bd.Wire([bd.Edge.make_circle(radius, bd.Plane(origin=start, z_dir=tangent))])
        return bd.Solid(bd.sweep(bd.Face(circle), arc).wrapped)

    crown = arc.position_at(0.5)
    nozzle = [
        bd.Pos(crown.X, crown.Y, 0) * bd.Cylinder(radius, 100.0, align=(bd.Align.CENTER, bd.Align.CENTER, bd.Align.MIN))
        for radius in (16.5, 13.5)
    ]
    return (swept(62.5) + nozzle[0]) - (swept(57.5) + nozzle[1])


def bend_tubecad():
    from tubecad.spec import load_spec
    from tubecad.spec.junction import build_junction

    return build_junction(load_spec(Path(__file__).resolve().parent.parent / "samples" / "nozzle_on_torus.toml"))


def bend_saddle(shape: bd.Shape) -> list[bd.Edge]:
    """The edges on the bend's outer torus (distance 62.5 from its axis circle) and the nozzle's cylinder."""
    found = []
    centre = np.array([300.0 * math.cos(math.pi / 4), 300.0 * math.sin(math.pi / 4)])
    for edge in shape.edges():
        p = np.array([tuple(edge.position_at(t)) for t in np.linspace(0, 1, 9)])
        torus = np.abs(np.hypot(np.hypot(p[:, 0], p[:, 1]) - 300.0, p[:, 2]) - 62.5).max()
        cylinder = np.abs(np.hypot(p[:, 0] - centre[0], p[:, 1] - centre[1]) - 16.5).max()
        if torus < 1e-5 and cylinder < 1e-5:
            found.append(edge)
    return found


CASES = {
    "tee": (
        [("build123d, primitives", primitives), ("build123d, sweeps", sweeps), ("tubecad", tubecad_tee)],
        outer_saddle,
    ),
    "nozzle on a bend": ([("build123d, sweeps", bend_sweeps), ("tubecad", bend_tubecad)], bend_saddle),
}


def run() -> dict:
    rows = {case: run_case(makers, saddle_of, case == "tee") for case, (makers, saddle_of) in CASES.items()}
    rows["stiffened tee sample"] = stiffened_sample()
    return rows


def stiffened_sample() -> dict:
    """samples/tee.toml as ``tubecad build`` makes it (the junction, its pad, its 16 stiffeners
    stopped on the saddle and the pad's edge), best of 3, each part timed, then every solid
    checked: valid, and OCCT's pre-boolean check with every check on."""
    from tubecad.spec.junction import branch_walls, build_junction, build_junction_stiffeners, build_pads
    from tubecad.spec.parse import load_spec

    spec = load_spec(Path(__file__).resolve().parent.parent / "samples" / "tee.toml")
    best: dict[str, float] = {}
    for _ in range(3):
        times = {}
        start = time.perf_counter()
        walls = branch_walls(spec)
        junction = build_junction(spec, walls)
        times["junction"] = time.perf_counter() - start
        pads = build_pads(spec, junction, walls)
        times["pad"] = time.perf_counter() - start - times["junction"]
        stiffeners = build_junction_stiffeners(spec, walls, junction)
        times["total"] = time.perf_counter() - start
        times["stiffeners"] = times["total"] - times["junction"] - times["pad"]
        best = {k: min(v, best.get(k, math.inf)) for k, v in times.items()}
    solids = [junction.shape, *(p.solid for p in pads.values()), *(st.solid for st in stiffeners)]
    start = time.perf_counter()
    findings = [analyzer_findings(solid.wrapped) for solid in solids]
    row = {
        "seconds": {k: round(v, 2) for k, v in best.items()},
        "solids": len(solids),
        "valid": all(is_valid(solid.wrapped) for solid in solids),
        "analyzer": {k: v for found in findings for k, v in found.items()},
        "analyzer_seconds": round(time.perf_counter() - start, 2),
        "saddle_deviation": junction.deviation,
    }
    print("stiffened tee sample", json.dumps(row, default=str), flush=True)
    return row


def run_case(makers, saddle_of, closed_form: bool) -> dict:
    expected = exact_volume() if closed_form else None
    rows = {}
    for name, make in makers:
        built, seconds = timed(make)
        shape = built.shape if name == "tubecad" else built
        if expected is None:
            expected = volume(shape.wrapped)  # the first way's: the others are compared with it
        solids = shape.solids()
        saddle = built.edges["saddle_outer"] if name == "tubecad" else saddle_of(shape)
        row = {
            "seconds": round(seconds, 2),
            "solids": len(solids),
            "valid": is_valid(shape.wrapped),
            "faces": len(shape.faces()),
            "volume_error": float(volume(shape.wrapped) / expected - 1),
            "outer_saddle_edges": len(saddle),
            "saddle_named": all(e.label == "saddle_outer" for e in saddle) and bool(saddle),
            "named_curvature_lines": 0,
        }
        if name == "tubecad":
            row["named_curvature_lines"] = sum(1 for name in built.edges if not name.startswith("saddle"))
            row["saddle_deviation"] = built.deviation
        start = time.perf_counter()
        row["analyzer"] = analyzer_findings(shape.wrapped)
        row["analyzer_seconds"] = round(time.perf_counter() - start, 2)
        row["fillet"] = fillet(shape, saddle)
        rows[name] = row
        print(name, json.dumps(row, default=str), flush=True)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    rows = run()
    if args.json:
        args.json.write_text(json.dumps(rows, indent=2, default=str) + "\n")


if __name__ == "__main__":
    main()
