"""tubecad side by side with the tools an engineer would otherwise use (see peers.py),
in one run, on the paper example, a clothoid and a helix; every method measured the same
way (measure.py). Ratios are tubecad / best peer: below 1 tubecad is better.
"""

from __future__ import annotations

import time
from pathlib import Path

from measure import Measured, measure
from peers import METHODS, PEERS, SPINE_POINTS, spine, spine_deviation

from tubecad.spec.parse import load_spec

ROOT = Path(__file__).resolve().parent.parent
SPECS = {
    "paper (log spiral)": ROOT / "samples" / "paper_log_spiral.toml",
    "clothoid": ROOT / "samples" / "clothoid.toml",
    "helix": ROOT / "samples" / "helix.toml",
}
#: lower is better for each; the ratio columns of the table
RATIO_METRICS = (
    "build_s",
    "export_s",
    "poles",
    "max_deviation",
    "max_orthogonality",
    "max_curvature_angle_deg",
    "area_rel_error",
    "step_bytes",
)


def timed_build(make, tube, path, repeats: int) -> tuple[object, bool, float]:
    """Build ``repeats`` times (once if the first takes over a second); the shape and best time."""
    best = float("inf")
    for attempt in range(repeats):
        start = time.perf_counter()
        shape, solid = make(tube, path)
        best = min(best, time.perf_counter() - start)
        if best > 1.0:
            break
    return shape, solid, best


def run_methods(name: str, tube, runs, samples: int, repeats: int, log=print) -> list[Measured]:
    """Build (best of ``repeats``) and measure each (method, builder, spine) of ``runs`` on ``tube``."""
    results: list[Measured] = []
    for method, make, path in runs:
        shape, solid, build_s = timed_build(make, tube, path, repeats)
        results.append(measure(method, shape, tube, build_s, samples, solid=solid))
        log(f"  {name}: {method}: {results[-1].max_deviation:.2e} deviation, {build_s * 1e3:.0f} ms")
    return results


def ratios(ours: Measured, peers: list[Measured], metrics: tuple[str, ...] = RATIO_METRICS) -> dict:
    """Per column of ``metrics``: the best of ``peers`` and tubecad / it."""
    out = {}
    for metric in metrics:
        best = min(peers, key=lambda m: getattr(m, metric))
        value = getattr(best, metric)
        out[metric] = {
            "best_peer": best.method,
            "best_peer_value": value,
            "tubecad": getattr(ours, metric),
            "ratio": getattr(ours, metric) / value if value else None,
        }
    return out


def compare_spec(name: str, spec: Path, samples: int, repeats: int, log=print) -> dict:
    tube = load_spec(spec).tube
    path = spine(tube)
    results = run_methods(name, tube, [(method, make, path) for method, make in METHODS.items()], samples, repeats, log)
    return {
        "spec": str(spec.relative_to(ROOT)),
        "length": tube.length,
        "radius": tube.radius,
        "spine_points": SPINE_POINTS,
        "spine_deviation": spine_deviation(tube, path),
        "methods": [m.as_dict() for m in results],
        "ratios": ratios(results[0], results[1:]),
    }


def run(samples: int = 60_000, repeats: int = 3, log=print) -> dict:
    out = {"peers": PEERS, "spine_points": SPINE_POINTS, "samples_per_method": samples, "specs": {}}
    for name, spec in SPECS.items():
        out["specs"][name] = compare_spec(name, spec, samples, repeats, log)
    return out


def method_table(methods: list[dict], ratio_rows: list[tuple[str, dict]]) -> list[str]:
    """One Markdown table: a row per measured method, then one row per (label, ratios)."""
    lines = [
        "| method | build ms | STEP ms | poles | max deviation | max \\|cos\\| | curvature-line angle (deg) "
        "| area error | STEP KB | valid |",
        "|" + "---|" * 10,
    ]
    for m in methods:
        lines.append(
            f"| {m['method']} | {m['build_s'] * 1e3:.0f} | {m['export_s'] * 1e3:.0f} | {m['poles']:,} "
            f"| {m['max_deviation']:.1e} | {m['max_orthogonality']:.1e} | {m['max_curvature_angle_deg']:.1e} "
            f"| {m['area_rel_error']:.1e} | {m['step_bytes'] / 1024:.0f} | {'yes' if m['valid'] else 'NO'} |"
        )
    for label, r in ratio_rows:
        cells = ["-" if r[metric]["ratio"] is None else f"{r[metric]['ratio']:.2g}" for metric in RATIO_METRICS]
        lines.append(f"| *{label}* | " + " | ".join(cells) + " | |")
    return lines


def table(result: dict) -> str:
    """The comparison as a Markdown table (one block per spec), with the ratio row."""
    lines = []
    for name, spec in result["specs"].items():
        lines += [
            f"**{name}** (`{spec['spec']}`, L = {spec['length']:g}, rho = {spec['radius']:g}; "
            f"sweep spine {spec['spine_points']} points, {spec['spine_deviation']:.1e} from the axis)",
            "",
        ]
        lines += method_table(spec["methods"], [("tubecad / best peer", spec["ratios"])])
        lines.append("")
    return "\n".join(lines)


def case_main(argv: list[str] | None, doc: str, run, table, quick_help: str) -> int:
    """The command line of a benchmark of cases (axes.py, canal.py): ``--quick`` (fewer samples,
    one build each), ``--json FILE``; the progress goes to stderr, the table to stdout."""
    import argparse
    import json
    import sys

    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help=quick_help)
    parser.add_argument("--json", type=str, default=None, help="also write the numbers to this file")
    args = parser.parse_args(argv)
    log = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    result = run(args.quick, samples=12_000 if args.quick else 60_000, repeats=1 if args.quick else 3, log=log)
    if args.json:
        with open(args.json, "w") as handle:
            json.dump(result, handle, indent=2)
    print(table(result))
    return 0
