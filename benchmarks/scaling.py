"""How tubecad scales, each curve beside a peer run in the same process or the same way:

- grid evaluation: points per second of ``CurvatureLineTube.grid`` from 1e3 to 1e7 points,
  beside OCCT evaluating the fitted surface point by point (``Geom_BSplineSurface.D0``,
  the fastest way to get points of a CAD surface from Python);
- B-rep size: the wall solid with N rings x M stringers (up to about 10,000 faces): time
  and peak memory against N*M; beside it, the same patch faces made one by one
  (``BRepBuilderAPI_MakeFace``) and joined by ``BRepBuilderAPI_Sewing``, the usual way to
  turn patches into a shell, against tubecad's shell of the same faces (shared edges, no sewing);
- fit: time, poles and measured deviation against the tolerance, 1e-3 to 1e-9, beside
  ``GeomAPI_PointsToBSplineSurface`` on a 33 x 201 exact grid asked for the same tolerance.

Each B-rep case runs in a fresh process ("spawn"); its peak memory is the peak resident
size during the build above the resident size before it (Linux VmHWM after clear_refs).
"""

from __future__ import annotations

import concurrent.futures
import math
import multiprocessing
import resource
import time

import numpy as np

GRID_SIZES = (1_000, 10_000, 100_000, 1_000_000, 10_000_000)
OCCT_GRID_LIMIT = 100_000  # the per-point peer above this would take minutes and says nothing new
WALL_LAYOUTS = ((3, 4), (6, 8), (11, 16), (26, 20), (51, 40), (101, 50))  # rings, stringers
SEWING_LAYOUTS = ((3, 4), (6, 8), (11, 16), (26, 20), (51, 20))  # one tube's shell
TOLERANCES = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
PEER_TOLERANCES = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)


def _best_of(func, repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        best = min(best, time.perf_counter() - start)
    return best


def grid_throughput(sizes=GRID_SIZES, log=print) -> list[dict]:
    from OCP.gp import gp_Pnt

    from tubecad.brep import NetLayout, build_tube_shell
    from tubecad.spec.paper import paper_tube

    tube = paper_tube()
    build = build_tube_shell(tube, NetLayout.equal(tube, 2, 1))
    surface, ts = build.surfaces[0].surface, build.surfaces[0]
    rows = []
    for n in sizes:
        nu = 64
        ns = max(n // nu, 2)
        u = np.linspace(0.0, 2.0 * math.pi, nu, endpoint=False)
        s = np.linspace(*tube.span, ns)
        seconds = _best_of(lambda: tube.grid(u, s), 3 if n <= 1_000_000 else 1)
        row = {"points": nu * ns, "tubecad_s": seconds, "tubecad_points_per_s": nu * ns / seconds}
        if n <= OCCT_GRID_LIMIT:
            uu = ts.u_at(np.degrees(u))
            point = gp_Pnt()

            def occt() -> None:
                for a in uu:
                    for b in s:
                        surface.D0(float(a), float(b), point)

            occt_s = _best_of(occt, 1)
            row.update(occt_s=occt_s, occt_points_per_s=nu * ns / occt_s, ratio=occt_s / seconds)
        rows.append(row)
        log(
            f"  grid {nu * ns:>10,} points: {row['tubecad_points_per_s']:.3g} points/s"
            + (f", OCCT D0 {row['occt_points_per_s']:.3g} points/s" if "occt_s" in row else "")
        )
    return rows


def _reset_peak() -> int:
    """Reset the process's peak resident size (Linux: clear_refs 5) and return the current
    resident size in kB, so that a later :func:`_peak_mb_since` measures only what follows."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        with open("/proc/self/status") as f:
            return next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))
    except OSError:  # elsewhere: the peak since the start, above the level after imports
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def _peak_mb_since(baseline_kb: int) -> float:
    try:
        with open("/proc/self/status") as f:
            peak = next(int(line.split()[1]) for line in f if line.startswith("VmHWM:"))
    except OSError:
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return (peak - baseline_kb) / 1024.0


def wall_case(rings: int, stringers: int) -> dict:
    """In a fresh process: build the paper wall with this layout; time, peak memory, checks."""
    from tubecad.brep import NetLayout, build_wall_solid, properties
    from tubecad.spec.paper import paper_tube

    tube = paper_tube()
    layout = NetLayout.equal(tube, rings, stringers)
    baseline = _reset_peak()
    start = time.perf_counter()
    build = build_wall_solid(tube, 2.0, "centered", layout)
    seconds = time.perf_counter() - start
    peak = _peak_mb_since(baseline)
    start = time.perf_counter()
    valid = properties.is_valid(build.shape)
    check_s = time.perf_counter() - start
    return {
        "rings": rings,
        "stringers": stringers,
        "faces": properties.count(build.shape, "face"),
        "seconds": seconds,
        "peak_mb": peak,
        "valid": valid,
        "check_s": check_s,
        "free_edges": properties.free_edges(build.shape),
    }


def shell_case(rings: int, stringers: int, sew: bool) -> dict:
    """In a fresh process: one tube's patch faces as a shell, tubecad's way or by sewing."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_Sewing

    from tubecad.brep import NetLayout, build_tube_shell, properties
    from tubecad.brep.layout import stringer_parameters
    from tubecad.spec.paper import paper_tube

    tube = paper_tube()
    layout = NetLayout.equal(tube, rings, stringers)
    baseline = _reset_peak()
    start = time.perf_counter()
    if sew:  # the same fitted surface, the faces made one by one, then sewn
        ts = build_tube_shell(tube, NetLayout.equal(tube, 2, 1)).surfaces[0]
        cuts = stringer_parameters(layout.stringers_deg, ts.u_at)
        sewing = BRepBuilderAPI_Sewing(1e-6)
        for s0, s1 in zip(layout.s_rings[:-1], layout.s_rings[1:]):
            for u0, u1 in zip(cuts[:-1], cuts[1:]):
                sewing.Add(BRepBuilderAPI_MakeFace(ts.surface, u0, u1, s0, s1, 1e-7).Face())
        sewing.Perform()
        shape = sewing.SewedShape()
    else:
        shape = build_tube_shell(tube, layout).shape
    seconds = time.perf_counter() - start
    peak = _peak_mb_since(baseline)
    return {
        "rings": rings,
        "stringers": stringers,
        "method": "sewing" if sew else "tubecad",
        "faces": properties.count(shape, "face"),
        "seconds": seconds,
        "peak_mb": peak,
        "free_edges": properties.free_edges(shape),
        "valid": properties.is_valid(shape),
    }


def _in_fresh_processes(calls, log) -> list[dict]:
    context = multiprocessing.get_context("spawn")
    rows = []
    for func, args in calls:
        with concurrent.futures.ProcessPoolExecutor(1, mp_context=context) as pool:
            rows.append(pool.submit(func, *args).result())
        log("  " + ", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in rows[-1].items()))
    return rows


def brep_scaling(wall_layouts=WALL_LAYOUTS, sewing_layouts=SEWING_LAYOUTS, log=print) -> dict:
    walls = _in_fresh_processes([(wall_case, layout) for layout in wall_layouts], log)
    shells = _in_fresh_processes(
        [(shell_case, (*layout, sew)) for layout in sewing_layouts for sew in (False, True)], log
    )
    return {"walls": walls, "shells": shells}


def fit_scaling(tolerances=TOLERANCES, peer_tolerances=PEER_TOLERANCES, log=print) -> list[dict]:
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace

    from tubecad.brep.measure import net_against_tube, sample_face
    from tubecad.brep.solids import orthogonality_for
    from tubecad.fitting import exact_section_surface, fit_frame, measure_surface
    from tubecad.fitting.generic import grid_surface
    from tubecad.spec.paper import paper_tube

    tube = paper_tube()
    rows = []
    for tol in tolerances:
        start = time.perf_counter()
        frame = fit_frame(tube.axis, tube.radius, tol, orthogonality_for(tol))
        ts = exact_section_surface(tube, frame)
        seconds = time.perf_counter() - start
        measured = measure_surface(ts)
        nu, nv = ts.pole_count
        row = {
            "tolerance": tol,
            "tubecad_s": seconds,
            "tubecad_poles": nu * nv,
            "tubecad_deviation": measured.max_deviation,
            "tubecad_orthogonality": measured.max_orthogonality_error,
        }
        if tol in peer_tolerances:
            start = time.perf_counter()
            fit = grid_surface(tube, 33, 201, tol)
            peer_s = time.perf_counter() - start
            face = BRepBuilderAPI_MakeFace(fit.surface, 1e-6).Face()
            deviation, orthogonality, _ = net_against_tube(tube, *sample_face(face, 48, 1500))
            nu, nv = fit.pole_count
            row.update(peer_s=peer_s, peer_poles=nu * nv, peer_deviation=deviation, peer_orthogonality=orthogonality)
        rows.append(row)
        log("  " + ", ".join(f"{k} {v:.3g}" for k, v in row.items()))
    return rows
