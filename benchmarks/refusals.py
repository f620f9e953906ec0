"""How long a bad spec waits for its refusal: every hostile case of the test suite, timed.

``python benchmarks/refusals.py`` runs each case of tests/e2e/test_bad_input.py (bad values,
unsafe expressions, hostile TOML, unwritable outputs, commands that a spec cannot feed) through
the installed ``tubecad`` console script in a fresh process, as a user would, best of
``--repeats``, and reports the slowest, the median and every case over ``--target`` seconds.
Each run must end with exit code 2 and write nothing. The peer is ``tubecad --help``, run side
by side: what any command costs before it reads a spec.

Results: benchmarks/results/refusals.json (``--out``).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONSOLE = Path(sys.executable).with_name("tubecad")
sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "e2e")]

import test_bad_input as hostile  # noqa: E402  (the test suite's hostile set)


def cases() -> dict[str, tuple[list[str], str]]:
    """name -> (command-line arguments after ``tubecad``, spec text)."""
    out: dict[str, tuple[list[str], str]] = {}
    build = ["build", "spec.toml", "-o", "out.step"]
    for name, (text, _) in hostile.BAD_VALUES.items():
        out[f"value/{name}"] = (build, text)
    for name, (expression, _) in hostile.BAD_EXPRESSIONS.items():
        out[f"expression/{name}"] = (build, hostile.custom(expression))
    for name, (text, _) in hostile.HOSTILE_TOML.items():
        if text != "\udcff":  # written as bytes by its test; the rest are text
            out[f"toml/{name}"] = (build, text)
    for name, (outputs, _) in hostile.BAD_OUTPUTS.items():
        args = ["build", "spec.toml"]
        for item in outputs:
            args += [item] if item.startswith("--") or args[-1:] == ["--report"] else ["-o", item]
        out[f"output/{name}"] = (args, hostile.BASE)
    for name, (args, text, _) in hostile.BAD_COMMANDS.items():
        out[f"command/{name}"] = (args, text)
    out["fit/tolerance_1e-30"] = (build, hostile.BASE + "\n[fit]\ntolerance = 1e-30\n")
    out["coil/long_tight_coil"] = (build, hostile.helix_on(20.0, 5.0, "[0.0, 50000.0]", 10.0))
    return out


def timed(args: list[str], text: str, repeats: int) -> tuple[float, int, list[str]]:
    """(best seconds, exit code, files left besides the spec) of ``tubecad ARGS`` on ``text``."""
    best, code, left = float("inf"), 0, []
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as folder:
            work = Path(folder)
            (work / "spec.toml").write_text(text)
            (work / "somefile.txt").write_text("a regular file")
            start = time.perf_counter()
            done = subprocess.run([str(CONSOLE), *args], cwd=work, capture_output=True, env=hostile.ENV)
            best = min(best, time.perf_counter() - start)
            code = done.returncode
            left = sorted(p.name for p in work.iterdir() if p.name not in ("spec.toml", "somefile.txt"))
    return best, code, left


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--target", type=float, default=1.0, help="seconds a refusal may take")
    parser.add_argument("--only", default="", help="run only the cases whose name contains this")
    parser.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "refusals.json")
    options = parser.parse_args()
    peer = timed(["--help"], "", options.repeats)[0]
    rows = []
    for name, (args, text) in cases().items():
        if options.only in name:
            seconds, code, left = timed(args, text, options.repeats)
            rows.append({"case": name, "seconds": round(seconds, 3), "exit_code": code, "left": left})
            flag = "" if code == 2 and not left and seconds <= options.target else "  <--"
            print(f"{seconds:6.2f} s  exit {code}  {name}{flag}", flush=True)
    times = [row["seconds"] for row in rows]
    slowest = max(rows, key=lambda row: row["seconds"])
    summary = {
        "cases": len(rows),
        "slowest": slowest,
        "median_seconds": statistics.median(times),
        "peer_tubecad_help_seconds": round(peer, 3),
        "over_target": [row["case"] for row in rows if row["seconds"] > options.target],
        "not_refused_cleanly": [row["case"] for row in rows if row["exit_code"] != 2 or row["left"]],
        "target_seconds": options.target,
    }
    print(json.dumps(summary, indent=2))
    if not options.only:
        options.out.write_text(json.dumps({"summary": summary, "rows": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
