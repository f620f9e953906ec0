"""Where a tube's build time goes on general axes (issue 24): the stages of the full solid
build, axis included, beside the fastest peer sweep of the same centreline.

``python benchmarks/build_profile.py [--repeats 5] [--json FILE]``. For each case of
benchmarks/axes.py (the trefoil knot, the build123d spline edge, the pipe route) and a canal
surface (the nozzle's radius law on a straight axis), best of ``repeats`` after a warm-up:

- the full build: the axis made from its input (expressions, the edge, the route's points),
  the tube, ``build_tube_solid`` at tolerance 1e-9 (the tubecad row that meets the most
  accurate peer) with the benchmark's layout;
- its stages, by cProfile's cumulative time of the functions that make them (so the stages
  are each measured with the profiler's overhead; their shares are what is reported): the
  axis, the frame (or canal) fit, the surfaces and faces, the solid, and the share of all
  of it spent evaluating the axis' Chebyshev series;
- the fastest peer: MakePipeShell CorrectedFrenet (tolerance 1e-9) along the same
  centreline as an OCCT curve, built as benchmarks/peers.py builds it, the spine given.
"""

from __future__ import annotations

import argparse
import cProfile
import json
import math
import pstats
import time
from collections.abc import Callable
from pathlib import Path

#: stage -> the functions whose cumulative time makes it (file suffix, function name)
STAGES = {
    "axis": [
        ("curves/parametric.py", "__init__"),
        ("curves/route.py", "__init__"),
        ("curves/edge.py", "edge_axis"),
        ("curves/natural.py", "__init__"),
    ],
    "frame fit": [("fitting/frame_spline.py", "fit_frame"), ("fitting/canal_section.py", "fit_canal")],
    "surfaces": [
        ("fitting/exact_section.py", "exact_section_surface"),
        ("fitting/canal_section.py", "canal_section_surface"),
    ],
    "faces": [("brep/faces.py", "patch_faces")],
    "caps": [("brep/solids.py", "_end_cap")],
    "solid": [("brep/solids.py", "_solid")],
    "Chebyshev evaluation": [("curves/chebyshev.py", "__call__")],
}
TOLERANCE = 1e-9


def cases() -> dict[str, tuple[Callable[[], object], Callable[[], object] | None]]:
    """name -> (make the tube from its input, make the peer's spine edge or None)."""
    import build123d as bd
    from axes import ROUTE_BENDS, ROUTE_POINTS, SPLINE_POINTS, TREFOIL, route_wire

    from tubecad import (
        CurvatureLineTube,
        NaturalAxis,
        ParametricAxis,
        RouteAxis,
        edge_axis,
        expression_curve,
        tube_or_canal,
    )

    edge = bd.Spline(*SPLINE_POINTS)
    route_axis = RouteAxis(ROUTE_POINTS, ROUTE_BENDS)
    return {
        "trefoil (parametric)": (
            lambda: CurvatureLineTube(ParametricAxis(expression_curve(*TREFOIL), (0.0, 2.0 * math.pi)), 8.0),
            None,
        ),
        "spline edge": (lambda: CurvatureLineTube(edge_axis(edge), 6.0), lambda: edge),
        "route": (
            lambda: CurvatureLineTube(RouteAxis(ROUTE_POINTS, ROUTE_BENDS), 20.0),
            lambda: route_wire(route_axis),
        ),
        "canal (straight, r = 40 - 15 (s/300)^2)": (
            lambda: tube_or_canal(NaturalAxis("0", "0", (0.0, 300.0)), "40 - 15*(s/300)**2"),
            None,
        ),
    }


def build(make_tube: Callable[[], object]) -> object:
    from tubecad.brep import NetLayout, build_tube_solid

    tube = make_tube()
    rings = 3 if tube.axis.closed else 2  # type: ignore[attr-defined]
    return build_tube_solid(tube, NetLayout.equal(tube, rings, 1), TOLERANCE)


def best(call: Callable[[], object], repeats: int) -> float:
    call()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return min(times)


def stages(call: Callable[[], object]) -> dict[str, float]:
    """Each stage's share of the profiled build: the largest cumulative time of its functions
    (an edge's axis is a ParametricAxis: the two nest) over the build's."""
    profiler = cProfile.Profile()
    profiler.runcall(call)
    stats = pstats.Stats(profiler).stats  # type: ignore[attr-defined]
    total = max(v[3] for v in stats.values())
    shares = {}
    for stage, functions in STAGES.items():
        seconds = max(
            (v[3] for (file, _, name), v in stats.items() if any(file.endswith(f) and name == n for f, n in functions)),
            default=0.0,
        )
        shares[stage] = round(seconds / total, 3)
    return shares


def peer_seconds(make_tube: Callable[[], object], make_spine: Callable[[], object], repeats: int) -> float:
    """MakePipeShell CorrectedFrenet of the tube's circle along the spine (given, not timed)."""
    from peers import occt_pipe_shell

    tube, spine = make_tube(), make_spine()
    sweep = occt_pipe_shell("CorrectedFrenet")
    return best(lambda: sweep(tube, spine), repeats)


def run(repeats: int) -> dict:
    result = {}
    for name, (make_tube, make_spine) in cases().items():
        full = best(lambda make_tube=make_tube: build(make_tube), repeats)
        row = {"full_build_ms": round(1e3 * full, 1), "shares": stages(lambda make_tube=make_tube: build(make_tube))}
        if make_spine is not None:
            peer = peer_seconds(make_tube, make_spine, repeats)
            row["peer_corrected_frenet_ms"] = round(1e3 * peer, 1)
            row["ratio"] = round(full / peer, 1)
        result[name] = row
        print(name, json.dumps(row), flush=True)
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    result = run(args.repeats)
    if args.json:
        args.json.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
