"""A stiffened wall beside the same wall without stiffeners, in one process (issue 9).

``python benchmarks/stiffened.py [--spec SPEC.toml] [--repeats N] [--json FILE]`` runs what
``tubecad build SPEC.toml -o OUT.step`` runs (tubecad.spec.build.build_and_export:
build, report, named STEP, read back and check) for a stiffened sample (default
``samples/helix_stiffened.toml``; ``samples/nozzle.toml`` is a canal wall) and for the same
spec without its [stiffeners] section (the plain wall), alternately, after one warm-up
build, and prints for each the best wall-clock and CPU time and the peak resident memory
above the level before the build (Linux VmHWM after clear_refs), and their ratios (target:
stiffened / plain time <= 1.6). The stiffener solids alone are timed too.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
import tomllib
from pathlib import Path

from scaling import _peak_mb_since, _reset_peak

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "samples" / "helix_stiffened.toml"
TARGET_RATIO = 1.6


def specs(path: Path = SPEC) -> dict[str, object]:
    """The plain wall (the sample without [stiffeners]) and the stiffened sample, checked."""
    from tubecad.spec.parse import parse_spec

    data = tomllib.loads(path.read_text())
    plain = {key: value for key, value in data.items() if key != "stiffeners"}
    return {"plain": parse_spec(plain, f"{path.name} without [stiffeners]"), "stiffened": parse_spec(data, path.name)}


def one_build(spec, out: Path) -> dict[str, float]:
    """build_and_export to STEP: wall-clock and CPU seconds, peak MB above the start."""
    from tubecad.spec.build import build_and_export

    baseline = _reset_peak()
    wall, cpu = time.perf_counter(), time.process_time()
    build_and_export(spec, [out])
    return {
        "seconds": time.perf_counter() - wall,
        "cpu_seconds": time.process_time() - cpu,
        "peak_mb": _peak_mb_since(baseline),
        "step_bytes": out.stat().st_size,
    }


def stiffeners_only(spec) -> float:
    """Seconds to make the [stiffeners] solids on an already built wall."""
    from tubecad.spec.build import build_from_spec, stiffeners_from_spec

    build = build_from_spec(spec)
    start = time.perf_counter()
    stiffeners_from_spec(spec, build)
    return time.perf_counter() - start


def run(repeats: int = 3, log=print, spec: Path = SPEC) -> dict:
    cases = specs(spec)
    result: dict = {"spec": str(spec.resolve().relative_to(ROOT)), "repeats": repeats, "target_ratio": TARGET_RATIO}
    with tempfile.TemporaryDirectory() as tmp:
        one_build(cases["plain"], Path(tmp) / "warm-up.step")  # imports, OCCT's first-use set-up
        runs: dict[str, list[dict]] = {name: [] for name in cases}
        for _ in range(repeats):
            for name, spec in cases.items():
                runs[name].append(one_build(spec, Path(tmp) / f"{name}.step"))
    for name, rows in runs.items():
        result[name] = {key: min(row[key] for row in rows) for key in rows[0]}
        # the allocator reuses what the warm-up freed, so the first build of each shows its peak best
        result[name]["peak_mb"] = max(row["peak_mb"] for row in rows)
        r = result[name]
        log(
            f"  {name:9s}: {r['seconds']:.2f} s ({r['cpu_seconds']:.2f} s CPU), peak {r['peak_mb']:.0f} MB, "
            f"STEP {r['step_bytes'] / 1e6:.2f} MB"
        )
    plain, stiffened = result["plain"], result["stiffened"]
    result["time_ratio"] = stiffened["seconds"] / plain["seconds"]
    result["cpu_ratio"] = stiffened["cpu_seconds"] / plain["cpu_seconds"]
    result["memory_ratio"] = stiffened["peak_mb"] / plain["peak_mb"] if plain["peak_mb"] >= 1.0 else float("nan")
    result["stiffeners_seconds"] = min(stiffeners_only(cases["stiffened"]) for _ in range(repeats))
    log(
        f"  stiffened / plain: time {result['time_ratio']:.2f} (CPU {result['cpu_ratio']:.2f}; target <= {TARGET_RATIO}), "
        f"peak memory {result['memory_ratio']:.2f}; the stiffener solids alone {result['stiffeners_seconds']:.2f} s"
    )
    return result


def table(result: dict) -> str:
    """The markdown table of :func:`run`'s result."""
    rows = [
        f"**Stiffened wall** (`{result['spec']}`; `tubecad build -o x.step` in one process, best of "
        f"{result['repeats']})",
        "",
        "| build | seconds | CPU seconds | peak MB | STEP MB |",
        "|---|---|---|---|---|",
    ]
    for name in ("plain", "stiffened"):
        r = result[name]
        rows.append(
            f"| {name} | {r['seconds']:.2f} | {r['cpu_seconds']:.2f} | {r['peak_mb']:.0f} | {r['step_bytes'] / 1e6:.2f} |"
        )
    rows.append(
        f"| *stiffened / plain* | {result['time_ratio']:.2f} | {result['cpu_ratio']:.2f} | "
        f"{result['memory_ratio']:.2f} | |"
    )
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spec", type=Path, default=SPEC, help="a sample with a [stiffeners] section")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json", type=Path, help="also write the numbers here")
    args = parser.parse_args(argv)
    result = run(args.repeats, spec=args.spec)
    print(table(result))
    if args.json:
        args.json.write_text(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
