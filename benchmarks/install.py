"""Install size and time (issue 10): what ``pip install`` costs a user, before and now.

``python benchmarks/install.py [--out FILE]`` makes fresh virtual environments in a temporary
folder and, for each case, times the install, measures the environment's size on disk
(``du``: site-packages and scripts), counts the distributions and checks ``pip check``:

- before: the dependencies tubecad declared up to issue 9 (build123d 0.12 pinned, CadQuery,
  both OCP wheels, ocp-vscode) with tubecad itself;
- ``pip install .``: today's default install (the newest build123d and its OCP);
- ``pip install '.[cadquery]'``: the CadQuery extra (build123d 0.12, OCP 7.9, CadQuery 2.8);
- build123d 0.13 installed first, then ``pip install .``: build123d and OCP must be kept;
- build123d 0.13 alone: what any build123d plugin costs at least.

By default every case runs with pip's cache as it is on the machine (run the script twice
for a warm cache): the times compare installs, not download speeds. ``--cold`` passes
``--no-cache-dir``, so every wheel is downloaded again: what a first-time user waits. The
peer is the "before" install, run side by side.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PYTHON = "python3.11"

#: the [project] dependencies of tubecad 0.1.0 up to issue 9 (git 52f2bb5)
BEFORE = [
    "numpy>=1.26",
    "scipy>=1.11",
    "matplotlib>=3.8",
    "click>=8.1",
    "build123d>=0.12,<0.13",
    "cadquery>=2.8,<2.9",
    "cadquery-ocp>=7.9.3,<7.10",
    "cadquery-ocp-novtk>=7.9.3,<7.10",
    "ocp-vscode>=2.6",
]

#: case -> (what is installed first, not timed; the timed pip install steps)
CASES: dict[str, tuple[list[list[str]], list[list[str]]]] = {
    "before (issue 9: CadQuery, two OCP wheels, ocp-vscode)": ([], [BEFORE, ["--no-deps", str(ROOT)]]),
    "pip install .": ([], [[str(ROOT)]]),
    "pip install '.[cadquery]'": ([], [[f"{ROOT}[cadquery]"]]),
    "build123d 0.13 first, then pip install .": ([["build123d==0.13.0"]], [[str(ROOT)]]),
    "build123d 0.13 alone (the floor of any build123d plugin)": ([], [["build123d==0.13.0"]]),
}


def run_case(first: list[list[str]], steps: list[list[str]], folder: Path, cold: bool = False) -> dict:
    subprocess.run([PYTHON, "-m", "venv", str(folder)], check=True)
    pip = [
        str(folder / "bin" / "python"),
        "-m",
        "pip",
        "install",
        "-q",
        "--disable-pip-version-check",
        *(["--no-cache-dir"] if cold else []),
    ]
    for step in first:
        subprocess.run(pip + step, check=True)
    seconds = 0.0
    for step in steps:
        start = time.perf_counter()
        subprocess.run(pip + step, check=True)
        seconds += time.perf_counter() - start
    du = subprocess.run(["du", "-sm", str(folder)], check=True, capture_output=True, text=True).stdout
    listing = subprocess.run(
        [str(folder / "bin" / "python"), "-m", "pip", "list", "--format", "json"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    versions = {p["name"].lower(): p["version"] for p in json.loads(listing)}
    check = subprocess.run([str(folder / "bin" / "python"), "-m", "pip", "check"], capture_output=True, text=True)
    return {
        "seconds": seconds,
        "megabytes": int(du.split()[0]),
        "distributions": len(versions),
        "build123d": versions.get("build123d"),
        "ocp": versions.get("cadquery-ocp-novtk") or versions.get("cadquery-ocp"),
        "ocp_distributions": sorted(d for d in versions if d.startswith("cadquery-ocp")),
        "cadquery": versions.get("cadquery"),
        "pip_check": check.returncode == 0,
    }


def table(result: dict) -> str:
    lines = [
        "| install | seconds | MB on disk | distributions | build123d | OCP wheels | pip check |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, r in result.items():
        wheels = ", ".join(f"{d} {r['ocp']}" for d in r["ocp_distributions"])
        lines.append(
            f"| {name} | {r['seconds']:.0f} | {r['megabytes']:,} | {r['distributions']} | {r['build123d']} "
            f"| {wheels} | {'ok' if r['pip_check'] else 'FAILS'} |"
        )
    return "\n".join(lines)


def run(cold: bool = False, log=print) -> dict:
    out = {}
    with tempfile.TemporaryDirectory(prefix="tubecad-install-") as tmp:
        for i, (name, (first, steps)) in enumerate(CASES.items()):
            out[name] = run_case(first, steps, Path(tmp) / f"venv{i}", cold)
            log(
                f"  {name}: {out[name]['seconds']:.0f} s, {out[name]['megabytes']:,} MB, build123d {out[name]['build123d']}"
            )
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cold", action="store_true", help="pip --no-cache-dir: download every wheel again")
    parser.add_argument(
        "--out", type=Path, default=None, help="JSON file [default: benchmarks/results/install[-cold].json]"
    )
    args = parser.parse_args()
    out = args.out or ROOT / "benchmarks" / "results" / f"install{'-cold' * args.cold}.json"
    result = run(args.cold)
    print(table(result))
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"python": sys.version.split()[0], "cold": args.cold, "cases": result}, indent=2) + "\n")


if __name__ == "__main__":
    main()
