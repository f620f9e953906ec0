"""Run the benchmarks: ``python benchmarks/run.py [--quick] [--only compare|axes|canal|scaling|stiffened|startup] [--out DIR]``.

Prints the tables and writes DIR/benchmarks.json (every number) and DIR/benchmarks.md
(the tables, as pasted into docs/benchmarks.md). Default DIR: benchmarks/results (the published
numbers); with ``--quick`` (smaller sizes, well under a minute on 2 cores) the default is
benchmarks/results/quick (git-ignored), and a quick run never writes the published files.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

os.environ.setdefault("MPLBACKEND", "Agg")

import axes
import canal
import compare
import scaling
import startup
import stiffened

from tubecad.core.atomic import write_text

#: the published results (docs/benchmarks.md quotes them); --quick never writes here
PUBLISHED = Path(__file__).resolve().parent / "results"


def scaling_tables(result: dict) -> str:
    lines = [
        "**Grid evaluation** (paper tube, 64 points around x n along; OCCT: D0 of the fitted surface per point)",
        "",
        "| points | tubecad points/s | OCCT D0 points/s | tubecad / OCCT speed |",
        "|---|---|---|---|",
    ]
    for r in result["grid"]:
        occt = f"{r['occt_points_per_s']:.2g} | {r['ratio']:.0f}x" if "ratio" in r else "- | -"
        lines.append(f"| {r['points']:,} | {r['tubecad_points_per_s']:.2g} | {occt} |")
    lines += [
        "",
        "**Wall solid** (paper tube, thickness 2; N rings x M stringers; fresh process each)",
        "",
        "| N x M | faces | build s | peak MB | valid | BRepCheck s |",
        "|---|---|---|---|---|---|",
    ]
    for r in result["brep"]["walls"]:
        lines.append(
            f"| {r['rings']} x {r['stringers']} | {r['faces']:,} | {r['seconds']:.2f} | {r['peak_mb']:.0f} "
            f"| {'yes' if r['valid'] else 'NO'} | {r['check_s']:.2f} |"
        )
    lines += [
        "",
        "**One tube's shell: shared edges (tubecad) vs faces made one by one and sewn (OCCT)**",
        "",
        "| N x M | faces | tubecad s | sewing s | sewing / tubecad time | tubecad MB | sewing MB | free edges (tubecad, sewing) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    shells = result["brep"]["shells"]
    for ours, sewn in zip(shells[0::2], shells[1::2]):
        lines.append(
            f"| {ours['rings']} x {ours['stringers']} | {ours['faces']:,} | {ours['seconds']:.3f} | {sewn['seconds']:.3f} "
            f"| {sewn['seconds'] / ours['seconds']:.1f} | {ours['peak_mb']:.0f} | {sewn['peak_mb']:.0f} "
            f"| {ours['free_edges']}, {sewn['free_edges']} |"
        )
    lines += [
        "",
        "**Fit against tolerance** (paper tube; measured by dense sampling; peer: PointsToBSplineSurface on a 33 x 201 grid)",
        "",
        "| tolerance | tubecad ms | tubecad poles | tubecad deviation | tubecad \\|cos\\| | peer ms | peer poles | peer deviation | peer \\|cos\\| |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in result["fit"]:
        peer = (
            f"{r['peer_s'] * 1e3:.0f} | {r['peer_poles']:,} | {r['peer_deviation']:.1e} | {r['peer_orthogonality']:.1e}"
            if "peer_s" in r
            else "- | - | - | -"
        )
        lines.append(
            f"| {r['tolerance']:.0e} | {r['tubecad_s'] * 1e3:.0f} | {r['tubecad_poles']:,} | {r['tubecad_deviation']:.1e} "
            f"| {r['tubecad_orthogonality']:.1e} | {peer} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes and fewer samples (a smoke run)")
    parser.add_argument(
        "--only", choices=["compare", "axes", "canal", "scaling", "stiffened", "startup"], help="run one part only"
    )
    parser.add_argument(
        "--out",
        type=Path,
        default=None,
        help="folder for the results (default benchmarks/results; with --quick benchmarks/results/quick)",
    )
    args = parser.parse_args(argv)
    if args.out is None:
        args.out = PUBLISHED / "quick" if args.quick else PUBLISHED
    elif args.quick and args.out.resolve() == PUBLISHED:
        parser.error(f"--quick does not overwrite the published results in {PUBLISHED}; give another --out")
    args.out.mkdir(parents=True, exist_ok=True)
    log = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    result: dict = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()},
        "quick": args.quick,
    }
    started = time.perf_counter()
    tables = []
    if args.only in (None, "compare"):
        log("comparison with the peers:")
        result["compare"] = compare.run(
            samples=12_000 if args.quick else 60_000, repeats=1 if args.quick else 3, log=log
        )
        tables.append(compare.table(result["compare"]))
    if args.only in (None, "axes"):
        log("any axis (trefoil, spline edge, route) against the sweeps:")
        result["axes"] = axes.run(
            quick=args.quick, samples=12_000 if args.quick else 60_000, repeats=1 if args.quick else 3, log=log
        )
        tables.append(axes.table(result["axes"]))
    if args.only in (None, "canal"):
        log("canal surfaces (radius laws) against the sweeps with a radius law:")
        result["canal"] = canal.run(
            quick=args.quick, samples=12_000 if args.quick else 60_000, repeats=1 if args.quick else 3, log=log
        )
        tables.append(canal.table(result["canal"]))
    if args.only in (None, "scaling"):
        log("scaling:")
        result["scaling"] = {
            "grid": scaling.grid_throughput(scaling.GRID_SIZES[:3] if args.quick else scaling.GRID_SIZES, log=log),
            "brep": scaling.brep_scaling(scaling.WALL_LAYOUTS[:2], scaling.SEWING_LAYOUTS[:1], log=log)
            if args.quick
            else scaling.brep_scaling(log=log),
            "fit": scaling.fit_scaling((1e-4, 1e-8), (1e-4,), log=log) if args.quick else scaling.fit_scaling(log=log),
        }
        tables.append(scaling_tables(result["scaling"]))
    if args.only in (None, "stiffened"):
        log("stiffened wall against the plain wall:")
        result["stiffened"] = stiffened.run(repeats=1 if args.quick else 3, log=log)
        tables.append(stiffened.table(result["stiffened"]))
        log("stiffened canal wall (the nozzle) against the plain one:")
        result["stiffened_canal"] = stiffened.run(
            repeats=1 if args.quick else 3, log=log, spec=stiffened.ROOT / "samples" / "nozzle.toml"
        )
        tables.append(stiffened.table(result["stiffened_canal"]))
    if args.only in (None, "startup"):
        log("start-up times:")
        result["startup"] = startup.run(repeats=2 if args.quick else 5, log=log)
        tables.append(startup.table(result["startup"]))
    result["seconds"] = time.perf_counter() - started
    text = "\n\n".join(tables)
    write_text(args.out / "benchmarks.json", json.dumps(result, indent=2))
    write_text(args.out / "benchmarks.md", text + "\n")
    print(text)
    log(f"wrote {args.out / 'benchmarks.json'} and {args.out / 'benchmarks.md'} in {result['seconds']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
