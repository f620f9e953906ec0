"""Every branch-to-main radius ratio r/R from 0.10 to 1.00 in steps of 0.01 (issue 43).

``python benchmarks/tee_ratios.py [--json FILE] [--step 0.01]``. Main: R 50 along x, 300 long,
wall 2; branch at x = 150, square, 150 long, wall 2, both centred. Per ratio:

- **saddle**: :func:`tubecad.junctions.fit_saddle` on the two centre surfaces, its time, and
  its points' distance from the closed form (each point's larger residual of the cylinders'
  equations y^2 + z^2 = R^2 and (x - 150)^2 + y^2 = r^2, and for r = R of the bisecting planes
  x - 150 = +-z);
- **Python API**: a :class:`tubecad.CurvatureJunction` (build123d part) built: time, valid,
  the saddle edges' largest distance from the exact saddle (the report's ``edges_deviation``);
- **spec**: the same tee as a TOML spec through :func:`tubecad.build_spec`: time and valid.

r = R is the equal tee: its saddle is two ellipse arcs through the crotch points, its wall is
refused naming the radius on both paths (the message is recorded).
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

import build123d as bd
import numpy as np

from tubecad import Branch, CurvatureJunction, NaturalAxis, ParameterError, TubecadError, build_spec, load_spec
from tubecad.junctions import branch_surface, fit_saddle
from tubecad.surface.canal import tube_or_canal

R, L, AT, H, T = 50.0, 300.0, 150.0, 150.0, 2.0
SPEC = """
[axis]
curve = "natural"
k = "0"
tau = "0"
s = [0.0, 300.0]
origin = [0.0, 0.0, 0.0]
tangent = [1.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
[tube]
radius = 50.0
[layout]
rings = 7
stringers = 8
[wall]
thickness = 2.0
[[branches]]
at = 150.0
length = 150.0
radius = {radius!r}
wall = {{ thickness = 2.0 }}
layout = {{ rings = 4, stringers = 8 }}
"""


def closed_form_error(points: np.ndarray, r: float) -> float:
    x, y, z = points[:, 0] - AT, points[:, 1], points[:, 2]
    error = np.maximum(np.abs(np.hypot(y, z) - R), np.abs(np.hypot(x, y) - r))
    if r == R:
        error = np.maximum(error, np.minimum(np.abs(x - z), np.abs(x + z)))
    return float(error.max())


def one(ratio: float) -> dict:
    r = round(ratio * R, 10)
    row: dict = {"ratio": ratio, "r": r}
    main = tube_or_canal(NaturalAxis("0", "0", (0.0, L), origin=(0, 0, 0), tangent=(1, 0, 0), normal=(0, 1, 0)), R)
    branch = branch_surface(main, AT, H, r)
    start = time.perf_counter()
    saddle = fit_saddle(main, branch)
    row["saddle_s"] = time.perf_counter() - start
    row["saddle_error"] = closed_form_error(saddle.saddle.points, r)
    row["saddle_curves"] = "ellipse arcs" if saddle.conic else f"B-spline, {saddle.poles} poles"
    start = time.perf_counter()
    try:
        part = CurvatureJunction(
            bd.Edge.make_line((0, 0, 0), (L, 0, 0)),
            radius=R,
            thickness=T,
            normal=(0, 1, 0),
            rings=7,
            branches=[Branch(at=AT, length=H, radius=r, thickness=T)],
        )
        row["part_s"] = time.perf_counter() - start
        row["part_valid"] = bool(part.is_valid)
        saddles = part.report["saddles"]
        row["edges_deviation"] = max(s["edges_deviation"] for s in saddles.values())
    except (ParameterError, TubecadError) as exc:
        row["part_refused"] = str(exc)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "tee.toml"
        path.write_text(SPEC.format(radius=r))
        start = time.perf_counter()
        try:
            result = build_spec(load_spec(path))
            row["spec_s"] = time.perf_counter() - start
            row["spec_valid"] = bool(
                bd.Shape.cast(result.shape.wrapped).is_valid
                if hasattr(result.shape, "wrapped")
                else result.shape.is_valid
            )
        except (ParameterError, TubecadError) as exc:
            row["spec_refused"] = str(exc)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path)
    parser.add_argument("--step", type=float, default=0.01)
    args = parser.parse_args()
    rows = []
    for ratio in np.round(np.arange(0.10, 1.0 + 1e-9, args.step), 2):
        row = one(float(ratio))
        rows.append(row)
        print(json.dumps(row), flush=True)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
