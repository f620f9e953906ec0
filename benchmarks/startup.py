"""Start-up times: what a command costs before it does anything (issue 10).

``python benchmarks/startup.py`` runs each command in a fresh process, best of N:
``tubecad --help`` (the command line, lazy: no numpy, no OCCT), ``import tubecad`` (the
package, lazy), ``import tubecad.surface`` (numpy/scipy), ``tubecad report`` on a sample
(the spec checked against the B-rep's size rules, from light modules: no OCCT) and ``from tubecad.brep import build_wall_solid``
(OCCT and build123d: what every build needs), each marked with whether it loads OCCT. The
peer is ``import build123d`` itself, run side by side.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

PYTHON = sys.executable
CONSOLE = Path(PYTHON).with_name("tubecad")

CASES = {
    "tubecad --help": [str(CONSOLE), "--help"],
    "import tubecad": [PYTHON, "-c", "import tubecad"],
    "import tubecad.surface (numpy, scipy)": [PYTHON, "-c", "import tubecad.surface"],
    "tubecad report samples/helix.toml": [
        str(CONSOLE),
        "report",
        str(Path(__file__).resolve().parent.parent / "samples" / "helix.toml"),
    ],
    "from tubecad.brep import build_wall_solid (tubecad build)": [
        PYTHON,
        "-c",
        "from tubecad.brep import build_wall_solid",
    ],
    "import build123d (peer)": [PYTHON, "-c", "import build123d"],
}


def best_seconds(command: list[str], repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        best = min(best, time.perf_counter() - start)
    return best


def loads_occt(command: list[str]) -> bool:
    """Does the command load OCCT (the OCP extension)? Checked with -X importtime."""
    if command[0] != PYTHON:
        probe = [
            PYTHON,
            "-X",
            "importtime",
            "-c",
            f"from tubecad.cli.app import cli\ntry:\n"
            f"    cli.main({command[1:]!r}, standalone_mode=False)\nexcept SystemExit:\n    pass",
        ]
    else:
        probe = [PYTHON, "-X", "importtime", *command[1:]]
    err = subprocess.run(probe, check=True, capture_output=True, text=True).stderr
    return "| OCP" in err or "OCP.OCP" in err


def run(repeats: int = 5, log=print) -> dict:
    out = {}
    for name, command in CASES.items():
        out[name] = {"seconds": best_seconds(command, repeats), "loads_occt": loads_occt(command)}
        log(f"  {name}: {out[name]['seconds']:.2f} s, OCCT loaded: {out[name]['loads_occt']}")
    return out


def table(result: dict) -> str:
    rows = ["**Start-up** (fresh process each, best of 5)", "", "| command | seconds | loads OCCT |", "|---|---|---|"]
    rows += [f"| `{name}` | {r['seconds']:.2f} | {'yes' if r['loads_occt'] else 'no'} |" for name, r in result.items()]
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args(argv)
    print(table(run(args.repeats, log=lambda t: print(t, file=sys.stderr))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
