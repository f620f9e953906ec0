"""tubecad's FE shell mesh beside gmsh meshing the same tube's STEP into quadrilaterals.

``python benchmarks/fem_mesh.py [--repeats N] [--json FILE]`` meshes a helix tube (Helix
k = 0.002, beta = 10 deg, s in [0, 2000], radius 100; layout 5 rings x 4 stringers) at two
sizes, about 2e4 and 1e5 elements:

- tubecad: ``shell_mesh`` with S4 elements, no stiffeners, no wall (the surface itself),
  size_along = size_around = h; the nodes are points of the exact surface;
- gmsh (its own OCCT): tubecad's tube shell (``build_tube_shell``, the same layout, no end
  caps) written to STEP, imported (``occ.importShapes``), meshed in 2-D with
  Frontal-Delaunay (``Mesh.Algorithm = 6``) and Blossom recombination into quadrilaterals
  (``Mesh.RecombineAll = 1``), ``Mesh.MeshSizeMin = MeshSizeMax`` tuned until its
  quadrilaterals are within 10 % of tubecad's element count. gmsh's Frontal-Delaunay for
  quads (``Mesh.Algorithm = 8``) leaves these faces' interiors unfilled (measured and kept in
  the result, ``algorithm_8``), so it is not the compared setting.

Both are timed alternately in one process, best of ``--repeats`` after one warm-up each
(tubecad: the ``shell_mesh`` call; gmsh: import + mesh, and the mesh generation alone).
The node-on-surface error of every node is computed here, independently of tubecad's
surface code: the nearest of dense axis samples ``tube.axis.position(s)``, then a golden-
section search of |X - c(s)| on the two sample intervals round it (to 1e-9 in s); the
error is |X - c(s*)| - radius. The result is printed as JSON and written to
``benchmarks/results/fem_mesh.json``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
RESULT = ROOT / "benchmarks" / "results" / "fem_mesh.json"
TARGETS = (20_000, 100_000)
#: gmsh's quadrilaterals within this fraction of tubecad's element count
MATCH = 0.10
#: axis samples per unit length for the nearest-sample start of the distance search
SAMPLES_PER_LENGTH = 10


def the_tube():
    from tubecad.brep.layout import NetLayout
    from tubecad.curves import Helix
    from tubecad.surface import CurvatureLineTube

    tube = CurvatureLineTube(Helix(0.002, 10.0, (0.0, 2000.0)), 100.0)
    return tube, NetLayout.equal(tube, 5, 4)


def surface_error(axis, radius: float, points: np.ndarray) -> tuple[float, float]:
    """(max |error|, RMS error) of ``points`` from the tube of ``radius`` round ``axis``:
    error = min over s of |X - c(s)| - radius, by golden section from the nearest sample."""
    from scipy.spatial import cKDTree

    lo, hi = axis.span
    samples = np.linspace(lo, hi, int(SAMPLES_PER_LENGTH * (hi - lo)) + 1)
    step = samples[1] - samples[0]
    nearest = samples[cKDTree(axis.position(samples)).query(points)[1]]
    a, b = np.clip(nearest - step, lo, hi), np.clip(nearest + step, lo, hi)
    f = lambda s: np.linalg.norm(points - axis.position(s), axis=1)  # noqa: E731
    g = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(int(math.ceil(math.log(2 * step / 1e-9) / -math.log(g)))):
        left = fc < fd  # the minimum is in [a, d]: d moves to c, a new c; else c to d, a new d
        a, b = np.where(left, a, c), np.where(left, d, b)
        x = np.where(left, b - g * (b - a), a + g * (b - a))
        fx = f(x)
        c, d = np.where(left, x, d), np.where(left, c, x)
        fc, fd = np.where(left, fx, fd), np.where(left, fc, fx)
    error = f(0.5 * (a + b)) - radius
    return float(np.abs(error).max()), float(np.sqrt(np.mean(error**2)))


def tubecad_mesh(tube, layout, h: float):
    from tubecad.fem import MeshSettings, shell_mesh

    return shell_mesh(tube, layout, settings=MeshSettings(element="S4", size_along=h, size_around=h))


def tubecad_size(tube, layout, target: int) -> float:
    """h with tubecad's element count nearest ``target`` (counts ~ area / h^2, rounded up per face)."""
    from tubecad.fem.grid import element_counts

    h = math.sqrt(tube.length * 2 * math.pi * tube.radius / target)
    best = None
    for scale in np.linspace(0.9, 1.2, 61):
        along, around = element_counts(tube, layout.s_rings, layout.stringers_deg, h * scale, h * scale)
        if best is None or abs(along * around - target) < abs(best[1] - target):
            best = (h * scale, along * around)
    return best[0]


def gmsh_mesh(step: Path, h: float, algorithm: int = 6) -> dict:
    """One gmsh run from the STEP file: seconds (import + mesh), mesh seconds, quadrilaterals,
    triangles, and the nodes (n, 3)."""
    import gmsh

    gmsh.clear()
    start = time.perf_counter()
    gmsh.model.occ.importShapes(str(step))
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMin", h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.Algorithm", algorithm)
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    meshing = time.perf_counter()
    gmsh.model.mesh.generate(2)
    end = time.perf_counter()
    counts = {"quadrilaterals": 0, "triangles": 0}
    for etype, tags in zip(*gmsh.model.mesh.getElements(2)[:2]):
        name = gmsh.model.mesh.getElementProperties(etype)[0]
        counts["quadrilaterals" if name.startswith("Quadrilateral") else "triangles"] += len(tags)
    _, xyz, _ = gmsh.model.mesh.getNodes()
    return {"seconds": end - start, "mesh_seconds": end - meshing, **counts, "nodes": np.asarray(xyz).reshape(-1, 3)}


def gmsh_size(step: Path, target: int, h: float, log) -> tuple[float, dict]:
    """h (starting from ``h``) giving gmsh quadrilaterals within MATCH of ``target``."""
    for _ in range(6):
        run = gmsh_mesh(step, h)
        log(
            f"    gmsh size {h:.4g}: {run['quadrilaterals']:,} quads, {run['triangles']} triangles, "
            f"{run['seconds']:.2f} s"
        )
        if abs(run["quadrilaterals"] - target) <= MATCH * target:
            return h, run
        h *= math.sqrt(run["quadrilaterals"] / target)
    raise RuntimeError(f"gmsh's element count did not come within {MATCH:.0%} of {target}")


def run(repeats: int = 3, log=print) -> dict:
    import gmsh

    from tubecad.brep import build_tube_shell
    from tubecad.export.registry import export_shape

    tube, layout = the_tube()
    result: dict = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()},
        "tube": {
            "axis": "Helix(k=0.002, beta_deg=10, s=[0, 2000])",
            "radius": tube.radius,
            "layout": {"rings": len(layout.s_rings), "stringers": len(layout.stringers_deg)},
        },
        "repeats": repeats,
        "tubecad": {"element": "S4", "surface": "the tube itself (no wall)"},
    }
    gmsh.initialize(readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        result["gmsh"] = {
            "version": gmsh.__version__,
            "algorithm": "6 (Frontal-Delaunay) + RecombineAll (Blossom)",
            "threads": gmsh.option.getNumber("General.NumThreads"),
        }
        with tempfile.TemporaryDirectory() as tmp:
            start = time.perf_counter()
            build = build_tube_shell(tube, layout)
            step = export_shape(build.shape, Path(tmp) / "tube.step")
            result["gmsh"]["step_seconds"] = time.perf_counter() - start  # tubecad's shell + STEP, gmsh's input
            result["gmsh"]["step_faces"] = len(layout.s_rings[1:]) * len(layout.stringers_deg)
            tubecad_mesh(tube, layout, 20.0)  # warm-up: imports, first calls
            gmsh_mesh(step, 40.0)
            result["sizes"] = []
            scale = 1.0  # gmsh's size over tubecad's for the same count, carried to the next target
            for target in TARGETS:
                h = tubecad_size(tube, layout, target)
                ours = tubecad_mesh(tube, layout, h)
                count = ours.element_count
                log(f"  target {target:,}: tubecad size {h:.4g}, {count:,} elements")
                gh, first = gmsh_size(step, count, h * scale, log)
                scale = gh / h
                t_runs, g_runs = [], [first]
                for _ in range(repeats):
                    start = time.perf_counter()
                    ours = tubecad_mesh(tube, layout, h)
                    t_runs.append(time.perf_counter() - start)
                    g_runs.append(gmsh_mesh(step, gh))
                theirs = min(g_runs[1:], key=lambda r: r["seconds"])
                t_best, g_best = min(t_runs), theirs["seconds"]
                t_err, g_err = (
                    surface_error(tube.axis, tube.radius, ours.nodes),
                    surface_error(tube.axis, tube.radius, theirs["nodes"]),
                )
                g_count = theirs["quadrilaterals"] + theirs["triangles"]
                row = {
                    "target": target,
                    "tubecad": {
                        "size": h,
                        "elements": count,
                        "nodes": len(ours.nodes),
                        "seconds": t_best,
                        "seconds_per_1e5_elements": t_best / count * 1e5,
                        "max_surface_error": t_err[0],
                        "rms_surface_error": t_err[1],
                    },
                    "gmsh": {
                        "size": gh,
                        "elements": g_count,
                        "quadrilaterals": theirs["quadrilaterals"],
                        "triangles": theirs["triangles"],
                        "nodes": len(theirs["nodes"]),
                        "seconds": g_best,
                        "mesh_seconds": theirs["mesh_seconds"],
                        "seconds_per_1e5_elements": g_best / g_count * 1e5,
                        "mesh_seconds_per_1e5_elements": theirs["mesh_seconds"] / g_count * 1e5,
                        "max_surface_error": g_err[0],
                        "rms_surface_error": g_err[1],
                    },
                }
                row["gmsh_over_tubecad_per_element"] = (
                    row["gmsh"]["seconds_per_1e5_elements"] / row["tubecad"]["seconds_per_1e5_elements"]
                )
                row["gmsh_mesh_only_over_tubecad_per_element"] = (
                    row["gmsh"]["mesh_seconds_per_1e5_elements"] / row["tubecad"]["seconds_per_1e5_elements"]
                )
                result["sizes"].append(row)
                log(
                    f"    tubecad {t_best:.3f} s, gmsh {g_best:.3f} s ({theirs['mesh_seconds']:.3f} s meshing): "
                    f"gmsh / tubecad per element {row['gmsh_over_tubecad_per_element']:.1f}; surface error max "
                    f"{t_err[0]:.2g} vs {g_err[0]:.2g}"
                )
            # the check of the distance search: the same nodes by tubecad's own Newton projection
            from tubecad.surface.checks import distance_to_axis

            nodes = tubecad_mesh(tube, layout, result["sizes"][0]["tubecad"]["size"]).nodes
            theirs = distance_to_axis(tube.axis, nodes)[0] - tube.radius
            result["tubecad_projection_max_surface_error"] = float(np.abs(theirs).max())
            # gmsh's Frontal-Delaunay for quads at the first gmsh size
            a8 = gmsh_mesh(step, result["sizes"][0]["gmsh"]["size"], algorithm=8)
            result["algorithm_8"] = {
                "size": result["sizes"][0]["gmsh"]["size"],
                "quadrilaterals": a8["quadrilaterals"],
                "triangles": a8["triangles"],
                "seconds": a8["seconds"],
            }
    finally:
        gmsh.finalize()
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json", type=Path, default=RESULT, help=f"write the numbers here (default {RESULT})")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    result = run(args.repeats, log=lambda line: print(line, file=sys.stderr))
    result["total_seconds"] = time.perf_counter() - start
    text = json.dumps(result, indent=2)
    print(text)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    from tubecad.core.atomic import write_text

    write_text(args.json, text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
