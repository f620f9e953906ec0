"""tubecad against the sweeps on axes that are not slope curves (issue 11), by the same
measure as compare.py (measure.py): each face's own OCCT surface sampled densely against
the exact tube; twist = the angle of the isolines from the curvature directions; poles,
build and STEP time, validity. Ratios are tubecad / best peer: below 1 tubecad is better.

``python benchmarks/axes.py [--quick]`` (also ``benchmarks/run.py --only axes``). Cases:

- trefoil: ParametricAxis of expression_curve("40*(sin(t)+2*sin(2*t))",
  "40*(cos(t)-2*cos(2*t))", "-40*sin(3*t)") for t in [0, 5.5], rho 8 (samples/trefoil.toml):
  an open piece of the knot, as the closed loop is not supported yet (--quick: t in [0, 2]);
- spline edge: edge_axis of the build123d Spline through (0,0,0), (60,25,10), (120,10,45),
  (180,-30,40), (230,-20,0), rho 6 (samples/build123d_spline_wall.py's centreline);
- route: RouteAxis through (0,0,0), (300,0,0), (300,250,0), (300,250,200), (450,400,200)
  with bend radii 60, 60, 80, rho 20 (samples/route.toml): legs joined by bends in three planes.

The peers (build123d sweep with is_frenet True and False, MakePipeShell CorrectedFrenet and
DiscreteTrihedron: peers.SWEEPS) sweep the circle along an OCCT curve of the same
centreline and are measured against the exact axis, tubecad's. The spines, each measured
against it too:

- spline edge: the edge itself, and the same edge with 9 knots inserted in every span;
- route: its lines and arcs as a wire (the same curve exactly);
- trefoil: a cubic through 2001 points with exact tangents at arc-length parameters
  (peers.spine, compare.py's recipe; --quick 501), a degree-8 B-spline approximating 1001
  exact points to 1e-11 (GeomAPI_PointsToBSpline), and that B-spline with 9 knots inserted
  in every span.

Knot insertion leaves the curve as it is; it is there for DiscreteTrihedron, which samples
its frame at 10 points per knot span (GeomFill_DiscreteTrihedron::Init), turns it by the
smallest rotation between them and reports zero derivatives: its tube changes with the
knots of the same curve, from on the tube to far off it, either way round.

tubecad is fitted at its default tolerance (1e-8) and at 1e-5 and 1e-9, so that each peer
can be met at equal accuracy: the tubecad row with the fewest poles that is at least as
accurate. A peer counts for the ratios only if it made the tube (valid, within 1e-3 rho of
it). Beside them tubecad's own: F and M on the exact grid (256 x 2001) and the time to make
its axis and tube; the peers' spines are timed too (neither is in the build time).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from typing import Callable

import build123d as bd
import numpy as np
from compare import method_table, ratios, run_methods
from measure import Measured
from peers import DEFAULT_TOLERANCE, SWEEPS, spine, spine_deviation, tubecad_at, tubecad_solid

from tubecad import CurvatureLineTube, ParametricAxis, edge_axis, expression_curve
from tubecad.curves.route import RouteAxis
from tubecad.surface.checks import net_errors

TREFOIL = ("40*(sin(t)+2*sin(2*t))", "40*(cos(t)-2*cos(2*t))", "-40*sin(3*t)")
SPLINE_POINTS = ((0, 0, 0), (60, 25, 10), (120, 10, 45), (180, -30, 40), (230, -20, 0))
ROUTE_POINTS = ((0, 0, 0), (300, 0, 0), (300, 250, 0), (300, 250, 200), (450, 400, 200))
ROUTE_BENDS = (60.0, 60.0, 80.0)
#: tubecad is also fitted to these tolerances (besides its default 1e-8), to compare at equal accuracy
TUBECAD_TOLERANCES = (1e-5, 1e-9)
#: knots inserted per span (DiscreteTrihedron samples 10 frames per span)
REFINE = 10
#: a peer's tube this far from the exact tube (relative to rho) is a failure, not a result
FAILED = 1e-3
#: a spine further than this from the exact axis is refused (a failed approximation, not a spine)
SPINE_LIMIT = 1e-6


def timed(make: Callable, *args):
    """make(*args) and the seconds it took."""
    start = time.perf_counter()
    value = make(*args)
    return value, time.perf_counter() - start


def edge_of(curve) -> bd.Edge:
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge

    return bd.Edge(BRepBuilderAPI_MakeEdge(curve).Edge())


def approximated_spine(tube: CurvatureLineTube, points: int = 1001, degree: int = 8, tolerance: float = 1e-11) -> bd.Edge:
    """A smooth B-spline (degree <= ``degree``, C3) within ``tolerance`` of ``points`` exact
    axis points at their arc lengths (GeomAPI_PointsToBSpline)."""
    from OCP.GeomAbs import GeomAbs_C3
    from OCP.GeomAPI import GeomAPI_PointsToBSpline
    from OCP.gp import gp_Pnt

    from tubecad.occ_compat import Array1OfPnt, Array1OfReal

    s = np.linspace(*tube.span, points)
    xyz = tube.axis.position(s)
    pts, params = Array1OfPnt(1, points), Array1OfReal(1, points)
    for i in range(points):
        pts.SetValue(i + 1, gp_Pnt(*xyz[i]))
        params.SetValue(i + 1, float(s[i]))
    return edge_of(GeomAPI_PointsToBSpline(pts, params, 3, degree, GeomAbs_C3, tolerance).Curve())


def refined(edge: bd.Edge, per_span: int = REFINE) -> bd.Edge:
    """The same B-spline curve (a copy) with ``per_span - 1`` knots inserted in every span."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GeomConvert import GeomConvert

    from tubecad.occ_compat import Array1OfReal

    curve = GeomConvert.CurveToBSplineCurve_s(BRepAdaptor_Curve(edge.wrapped).BSpline())
    knots = Array1OfReal(1, curve.NbKnots())
    curve.Knots(knots)
    k = [knots.Value(i) for i in range(1, curve.NbKnots() + 1)]
    for a, b in zip(k[:-1], k[1:]):
        for j in range(1, per_span):
            curve.InsertKnot(a + (b - a) * j / per_span, 1, 1e-12 * (k[-1] - k[0]))
    return edge_of(curve)


def route_wire(axis: RouteAxis) -> bd.Wire:
    """The route's lines and circular arcs as an OCCT wire: the same curve exactly."""
    edges = []
    for piece in axis.pieces:
        a, m, b = axis.position(np.array([piece.s0, 0.5 * (piece.s0 + piece.s1), piece.s1]))
        ends = (bd.Vector(*a), bd.Vector(*b))
        edges.append(bd.Edge.make_line(*ends) if piece.kind == "line" else bd.Edge.make_three_point_arc(ends[0], bd.Vector(*m), ends[1]))
    return bd.Wire(edges)


def trefoil(quick: bool):
    """The trefoil-knot piece (t in [0, 5.5]; --quick [0, 2]) and its three spines."""
    t1 = 2.0 if quick else 5.5
    axis = ParametricAxis(expression_curve(*TREFOIL), (0.0, t1))
    tube = CurvatureLineTube(axis, 8.0)
    cubic = 501 if quick else 2001
    spines = {f"cubic {cubic}": (lambda built: spine(tube, cubic),
                                 f"cubic through {cubic} points with exact tangents at arc-length parameters"),
              "degree 8": (lambda built: approximated_spine(tube), "degree 8, C3, within 1e-11 of 1001 points (PointsToBSpline)"),
              "degree 8 refined": (lambda built: refined(built["degree 8"]),
                                   f"the degree-8 spine with {REFINE - 1} knots inserted per span")}  # fmt: skip
    return tube, spines, (f"ParametricAxis x(t) = {TREFOIL[0]}, y(t) = {TREFOIL[1]}, z(t) = {TREFOIL[2]}, t in [0, {t1:g}]"
                          " (an open piece: the closed knot is not supported yet)")  # fmt: skip


def spline_edge(quick: bool):
    """The axis along a build123d Spline edge; the spines: that edge, and it refined."""
    edge = bd.Spline(*SPLINE_POINTS)
    tube = CurvatureLineTube(edge_axis(edge), 6.0)
    spines = {"the edge": (lambda built: edge, "the build123d Spline edge itself"),
              "the edge refined": (lambda built: refined(edge), f"the same edge with {REFINE - 1} knots inserted per span")}  # fmt: skip
    return tube, spines, f"edge_axis of the build123d Spline through {', '.join(map(str, SPLINE_POINTS))}"


def route(quick: bool):
    """The pipe route of samples/route.toml; the spine: its lines and arcs."""
    axis = RouteAxis(ROUTE_POINTS, ROUTE_BENDS)
    tube = CurvatureLineTube(axis, 20.0)
    return tube, {"lines and arcs": (lambda built: route_wire(axis), "the route's lines and arcs as a wire")}, (
        f"RouteAxis through {len(ROUTE_POINTS)} points, bend radii {', '.join(f'{r:g}' for r in ROUTE_BENDS)}: "
        f"{sum(p.kind == 'line' for p in axis.pieces)} legs, {sum(p.kind == 'bend' for p in axis.pieces)} bends in three planes")  # fmt: skip


#: case name -> (quick) -> (tube, {spine label: (make(spines built so far), description)}, description)
CASES: dict[str, Callable] = {"trefoil (parametric)": trefoil, "spline edge": spline_edge, "route": route}


def at_equal_accuracy(variants: list[Measured], peer: Measured) -> tuple[Measured, bool]:
    """The tubecad variant with the fewest poles that is at least as accurate as ``peer``
    (and True), or the most accurate variant if none is (and False)."""
    good = [m for m in variants if m.max_deviation <= peer.max_deviation]
    if good:
        return min(good, key=lambda m: (m.poles, m.build_s)), True
    return min(variants, key=lambda m: m.max_deviation), False


def run_case(name: str, setup: Callable, quick: bool, samples: int, repeats: int, log=print) -> dict:
    (tube, spines, description), axis_s = timed(setup, quick)
    grid = net_errors(tube, *((64, 501) if quick else (256, 2001)))
    paths: dict = {}
    spine_info = {}
    for label, (make, text) in spines.items():
        paths[label], seconds = timed(make, paths)
        deviation = spine_deviation(tube, paths[label], 20_000)
        if not deviation < SPINE_LIMIT:
            raise RuntimeError(f"{name}: the spine '{label}' is {deviation:.2g} from the axis (limit {SPINE_LIMIT:g})")
        spine_info[label] = {"description": text, "deviation": deviation, "seconds": seconds}
    named = (lambda sweep, label: f"{sweep} [{label}]") if len(paths) > 1 else (lambda sweep, label: sweep)
    runs = [("tubecad", tubecad_solid, None)] + [(f"tubecad, tol {t:.0e}".replace("e-0", "e-"), tubecad_at(t), None)
                                             for t in TUBECAD_TOLERANCES]  # fmt: skip
    runs += [(named(sweep, label), make, path) for label, path in paths.items() for sweep, make in SWEEPS.items()]
    results = run_methods(name, tube, runs, samples, repeats, log)
    variants, peers = results[: 1 + len(TUBECAD_TOLERANCES)], results[1 + len(TUBECAD_TOLERANCES) :]
    made = [m.valid and m.max_deviation < FAILED * tube.radius for m in peers]
    counted = [m for m, ok in zip(peers, made) if ok]
    equal = []
    for peer in counted:
        ours, matched = at_equal_accuracy(variants, peer)
        equal.append({"peer": peer.method, "peer_deviation": peer.max_deviation, "tubecad": ours.method,
                      "tubecad_deviation": ours.max_deviation, "matched": matched,
                      "poles_ratio": ours.poles / peer.poles, "build_ratio": ours.build_s / peer.build_s})  # fmt: skip
    return {"axis": description, "kind": tube.axis.family, "length": tube.length, "radius": tube.radius,
            "axis_s": axis_s, "exact_grid": {"F": grid.max_orthogonality_error, "M": grid.max_M_error,
                                             "nu": grid.nu, "ns": grid.ns},
            "spines": spine_info, "methods": [m.as_dict() for m in results],
            "failed": [m.method for m, ok in zip(peers, made) if not ok],
            "ratios": ratios(results[0], counted), "equal_accuracy": equal}  # fmt: skip


def run(quick: bool = False, samples: int = 60_000, repeats: int = 3, log=print) -> dict:
    out = {"peers": list(SWEEPS), "tubecad_tolerances": [DEFAULT_TOLERANCE, *TUBECAD_TOLERANCES],
           "samples_per_method": samples, "quick": quick, "cases": {}}  # fmt: skip
    start = time.perf_counter()
    for name, setup in CASES.items():
        log(f"  {name}:")
        out["cases"][name] = run_case(name, setup, quick, samples, repeats, log)
    out["seconds"] = time.perf_counter() - start
    return out


def table(result: dict) -> str:
    """tubecad's own numbers on each axis kind, where it stands against the 20 x targets,
    then the comparison per case (compare.py's table and ratio row)."""
    lines = ["**Any axis: tubecad** (default tolerance 1e-8; F, M: largest |F|/sqrt(EG) and conjugacy error on "
             "the exact grid; the rest measured on the B-rep as for the peers)", "",
             "| case | axis | L | rho | axis + tube ms | build ms | STEP ms | poles | max deviation | max \\|cos\\| "
             "| curvature-line angle (deg) | F (exact grid) | M (exact grid) | valid |", "|" + "---|" * 14]  # fmt: skip
    for name, case in result["cases"].items():
        m, g = case["methods"][0], case["exact_grid"]
        lines.append(f"| {name} | {case['kind']} | {case['length']:.0f} | {case['radius']:g} | {case['axis_s'] * 1e3:.0f} "
                     f"| {m['build_s'] * 1e3:.0f} | {m['export_s'] * 1e3:.0f} | {m['poles']:,} | {m['max_deviation']:.1e} "
                     f"| {m['max_orthogonality']:.1e} | {m['max_curvature_angle_deg']:.1e} | {g['F']:.1e} | {g['M']:.1e} "
                     f"| {'yes' if m['valid'] else 'NO'} |")  # fmt: skip
    lines += ["", "**Any axis: against the 20 x targets** (for each peer that made the tube, the tubecad row with the "
              "fewest poles at least as accurate; tubecad / peer, target 0.05 or less; the worst peer shown)", "",
              "| case | poles, worst | build time, worst | most accurate peer | its deviation | tubecad row "
              "| poles / its | build / its |", "|" + "---|" * 8]  # fmt: skip
    for name, case in result["cases"].items():
        equal = case["equal_accuracy"]
        poles, build = (max(equal, key=lambda e: e[key]) for key in ("poles_ratio", "build_ratio"))
        best = min(equal, key=lambda e: e["peer_deviation"])
        mark = "" if best["matched"] else " (less accurate)"
        lines.append(f"| {name} | {poles['poles_ratio']:.2g} ({poles['peer']}) | {build['build_ratio']:.2g} ({build['peer']}) "
                     f"| {best['peer']} | {best['peer_deviation']:.1e} | {best['tubecad']}{mark} "
                     f"| {best['poles_ratio']:.2g} | {best['build_ratio']:.2g} |")  # fmt: skip
    for name, case in result["cases"].items():
        spines = "; ".join(f"[{label}] {s['description']}, {s['deviation']:.1e} from the axis, made in {s['seconds']:.2g} s"
                           for label, s in case["spines"].items())  # fmt: skip
        failed = f"; not counted (not the tube): {', '.join(case['failed'])}" if case["failed"] else ""
        lines += ["", f"**{name}** ({case['axis']}; L = {case['length']:.6g}, rho = {case['radius']:g}; "
                      f"spines: {spines}{failed})", ""]  # fmt: skip
        lines += method_table(case["methods"], [("tubecad / best peer", case["ratios"])])
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a shorter trefoil, fewer samples, one build each")
    parser.add_argument("--json", type=str, default=None, help="also write the numbers to this file")
    args = parser.parse_args(argv)
    log = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    result = run(args.quick, samples=12_000 if args.quick else 60_000, repeats=1 if args.quick else 3, log=log)
    if args.json:
        with open(args.json, "w") as handle:
            json.dump(result, handle, indent=2)
    print(table(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
