"""tubecad against the sweeps on axes that are not slope curves (issue 11), by the same
measure as compare.py (measure.py): each face's own OCCT surface sampled densely against
the exact tube; twist = the angle of the isolines from the curvature directions; poles,
build and STEP time, validity. Ratios are tubecad / best peer: below 1 tubecad is better.

``python benchmarks/axes.py [--quick]`` (also ``benchmarks/run.py --only axes``). Cases:

- trefoil: ParametricAxis of expression_curve("40*(sin(t)+2*sin(2*t))",
  "40*(cos(t)-2*cos(2*t))", "-40*sin(3*t)") for t in [0, 2 pi], rho 8
  (samples/trefoil_closed.toml): the whole knot, a closed loop (detected: axis.closed), so
  the tube is closed, without caps (tubecad: two faces, the fewest a closed tube takes);
  its rotation-minimising frame comes back turned by the holonomy (axis.holonomy, in the
  case's notes), which tubecad's stringers take up at the closing ring;
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
- trefoil: closed periodic curves (the sweeps along a closed spine): a periodic cubic
  through 2000 points with exact tangents at arc-length parameters (compare.py's recipe,
  GeomAPI_Interpolate with PeriodicFlag; --quick 1000), a periodic degree-8 B-spline on
  uniform knots fitted by least squares to within 1e-11 of 1000 exact points (the fewest
  spans, in steps of 50, that reach it; GeomAPI_PointsToBSpline, the open cases' recipe,
  makes no periodic curve), and that B-spline with 9 knots inserted in every span.

The Frenet frame is the curve's own, so it closes round the loop; a sweep whose frame does
not (CorrectedFrenet, which build123d's is_frenet=False uses too, and DiscreteTrihedron:
they turn by the holonomy, as a rotation-minimising frame does) cannot close its surface on
itself: its solid is invalid by BRepCheck and not counted. A method that raises is
reported as failed (its error in the table and the JSON), not a crash. On the closed axis
the closest-point search runs across the closing (tubecad.surface.checks.distance_to_axis).

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

import math
import sys
import time
from collections.abc import Callable

import build123d as bd
import numpy as np
from compare import case_main, method_table, ratios, timed_build
from measure import Measured, measure
from peers import DEFAULT_TOLERANCE, SWEEPS, spine_deviation
from peers import tubecad_at as open_tubecad_at

from tubecad import CurvatureLineTube, ParametricAxis, edge_axis, expression_curve
from tubecad.brep import NetLayout, build_tube_solid
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
#: the closed trefoil's degree-8 periodic spine: degree, exact points, tolerance, spans tried
PERIODIC_DEGREE, PERIODIC_POINTS, PERIODIC_TOLERANCE, PERIODIC_SPANS = 8, 1000, 1e-11, range(100, 1001, 50)


def timed(make: Callable, *args):
    """make(*args) and the seconds it took."""
    start = time.perf_counter()
    value = make(*args)
    return value, time.perf_counter() - start


def tubecad_at(tolerance: float) -> Callable:
    """peers.tubecad_at (one face), but round a closed axis the closed tube, which takes a
    ring besides the closing one: two faces (3 rings, 1 stringer), no caps."""
    open_tube = open_tubecad_at(tolerance)

    def make(tube: CurvatureLineTube, path):
        if not tube.axis.closed:
            return open_tube(tube, path)
        return build_tube_solid(tube, NetLayout.equal(tube, 3, 1), tolerance).shape, True

    return make


tubecad_solid = tubecad_at(DEFAULT_TOLERANCE)


def edge_of(curve) -> bd.Edge:
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge

    return bd.Edge(BRepBuilderAPI_MakeEdge(curve).Edge())


def periodic_cubic(tube: CurvatureLineTube, points: int) -> bd.Edge:
    """The closed axis as a periodic cubic (GeomAPI_Interpolate, PeriodicFlag) through
    ``points`` exact points (the closing one not repeated) with their exact unit tangents,
    parameterised by arc length: peers.spine's recipe, closed."""
    s = np.linspace(*tube.span, points + 1)
    a = tube.axis.at(s[:-1])
    return bd.Edge.make_spline(
        [bd.Vector(*p) for p in a.position],
        tangents=[bd.Vector(*t) for t in a.t],
        periodic=True,
        parameters=list(s),
        scale=False,
    )


def periodic_fit(
    tube: CurvatureLineTube,
    points: int = PERIODIC_POINTS,
    degree: int = PERIODIC_DEGREE,
    tolerance: float = PERIODIC_TOLERANCE,
) -> tuple[bd.Edge, int]:
    """The closed axis as a periodic B-spline of ``degree`` on uniform knots (C^(degree-1)
    everywhere, the closing point too), fitted by least squares to ``points`` exact points at
    their arc lengths: the fewest spans of PERIODIC_SPANS within ``tolerance`` of them."""
    from scipy.interpolate import BSpline
    from scipy.sparse import csr_matrix
    from scipy.sparse.linalg import splu

    s0, s1 = tube.span
    s = np.linspace(s0, s1, points + 1)[:-1]
    xyz = tube.axis.position(s)
    for spans in PERIODIC_SPANS:
        h = (s1 - s0) / spans
        basis = BSpline.design_matrix(s, s0 + h * np.arange(-degree, spans + degree + 1), degree).tocoo()
        # the basis functions that wrap round the loop are one (duplicates are summed)
        periodic = csr_matrix((basis.data, (basis.row, basis.col % spans)), shape=(points, spans))
        gram = splu((periodic.T @ periodic).tocsc())  # sparse normal equations (B is well conditioned)
        poles = gram.solve(periodic.T @ xyz)
        poles += gram.solve(periodic.T @ (xyz - periodic @ poles))  # one step of refinement
        if np.linalg.norm(periodic @ poles - xyz, axis=1).max() <= tolerance:
            break
    else:
        raise RuntimeError(f"no periodic degree-{degree} fit within {tolerance:g} with up to {spans} spans")
    knots = list(s0 + h * np.arange(spans + 1))
    knots[-1] = s1
    return bd.Edge.make_bspline([tuple(p) for p in poles], knots, degree, periodic=True), spans


def refined(edge: bd.Edge, per_span: int = REFINE) -> bd.Edge:
    """The same B-spline curve (a copy; periodic if it is) with ``per_span - 1`` knots
    inserted in every span."""
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
        edges.append(
            bd.Edge.make_line(*ends)
            if piece.kind == "line"
            else bd.Edge.make_three_point_arc(ends[0], bd.Vector(*m), ends[1])
        )
    return bd.Wire(edges)


def trefoil(quick: bool):
    """The whole trefoil knot (t in [0, 2 pi], closed) and its three closed spines."""
    axis = ParametricAxis(expression_curve(*TREFOIL), (0.0, 2.0 * math.pi))
    if not axis.closed:
        raise RuntimeError("the trefoil knot over t in [0, 2 pi] is not detected closed")
    tube = CurvatureLineTube(axis, 8.0)
    cubic = 1000 if quick else 2000
    fits: dict = {}

    def degree_8(_built):
        edge, fits["spans"] = periodic_fit(tube)
        return edge

    spines = {
        f"periodic cubic {cubic}": (
            lambda _built: periodic_cubic(tube, cubic),
            f"periodic cubic through {cubic} points with exact tangents at arc-length parameters",
        ),
        "periodic degree 8": (
            degree_8,
            lambda: (
                f"periodic degree 8 on {fits['spans']} uniform spans (C7), least squares "
                f"within {PERIODIC_TOLERANCE:g} of {PERIODIC_POINTS} points"
            ),
        ),
        "periodic degree 8 refined": (
            lambda built: refined(built["periodic degree 8"]),
            f"the periodic degree-8 spine with {REFINE - 1} knots inserted per span",
        ),
    }
    turn = axis.holonomy
    return (
        tube,
        spines,
        (
            f"ParametricAxis x(t) = {TREFOIL[0]}, y(t) = {TREFOIL[1]}, z(t) = {TREFOIL[2]}, t in [0, 2 pi]: "
            f"the whole knot, closed (holonomy {turn:.4f} rad = {math.degrees(turn):.2f} deg: the "
            "rotation-minimising frame comes back turned by it; no caps)"
        ),
    )


def spline_edge(_quick: bool):
    """The axis along a build123d Spline edge; the spines: that edge, and it refined."""
    edge = bd.Spline(*SPLINE_POINTS)
    tube = CurvatureLineTube(edge_axis(edge), 6.0)
    spines = {
        "the edge": (lambda _built: edge, "the build123d Spline edge itself"),
        "the edge refined": (lambda _built: refined(edge), f"the same edge with {REFINE - 1} knots inserted per span"),
    }
    return tube, spines, f"edge_axis of the build123d Spline through {', '.join(map(str, SPLINE_POINTS))}"


def route(_quick: bool):
    """The pipe route of samples/route.toml; the spine: its lines and arcs."""
    axis = RouteAxis(ROUTE_POINTS, ROUTE_BENDS)
    tube = CurvatureLineTube(axis, 20.0)
    return (
        tube,
        {"lines and arcs": (lambda _built: route_wire(axis), "the route's lines and arcs as a wire")},
        (
            f"RouteAxis through {len(ROUTE_POINTS)} points, bend radii {', '.join(f'{r:g}' for r in ROUTE_BENDS)}: "
            f"{sum(p.kind == 'line' for p in axis.pieces)} legs, {sum(p.kind == 'bend' for p in axis.pieces)} bends in three planes"
        ),
    )


#: case name -> (quick) -> (tube, {spine label: (make(spines built so far), description)}, description)
CASES: dict[str, Callable] = {"trefoil (parametric)": trefoil, "spline edge": spline_edge, "route": route}


def at_equal_accuracy(variants: list[Measured], peer: Measured) -> tuple[Measured, bool]:
    """The tubecad variant with the fewest poles that is at least as accurate as ``peer``
    (and True), or the most accurate variant if none is (and False)."""
    good = [m for m in variants if m.max_deviation <= peer.max_deviation]
    if good:
        return min(good, key=lambda m: (m.poles, m.build_s)), True
    return min(variants, key=lambda m: m.max_deviation), False


def run_methods(
    name: str, tube: CurvatureLineTube, runs, samples: int, repeats: int, log=print
) -> tuple[list[Measured], dict[str, str]]:
    """compare.run_methods, where a method that raises (building or measuring) is reported,
    not fatal: the measured methods, and {method: error} of the others."""
    results: list[Measured] = []
    errors: dict[str, str] = {}
    for method, make, path in runs:
        try:
            shape, solid, build_s = timed_build(make, tube, path, repeats)
            results.append(measure(method, shape, tube, build_s, samples, solid=solid))
        except Exception as exc:  # a peer failing on this axis is a result
            errors[method] = f"{type(exc).__name__}: {str(exc).strip() or 'no message'}"[:200]
            log(f"  {name}: {method}: FAILED ({errors[method]})")
            continue
        log(
            f"  {name}: {method}: {results[-1].max_deviation:.2e} deviation, {build_s * 1e3:.0f} ms"
            f"{'' if results[-1].valid else ', INVALID'}"
        )
    return results, errors


def not_counted(m: Measured, radius: float) -> str | None:
    """Why a peer's shape is not the tube (None if it is): invalid (BRepCheck), or off it."""
    why = ([] if m.valid else ["invalid"]) + (
        [] if m.max_deviation < FAILED * radius else [f"{m.max_deviation:.1e} off"]
    )
    return ", ".join(why) or None


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
        spine_info[label] = {
            "description": text() if callable(text) else text,
            "deviation": deviation,
            "seconds": seconds,
            "closed": bool(paths[label].is_closed),
        }
    named = (lambda sweep, label: f"{sweep} [{label}]") if len(paths) > 1 else (lambda sweep, _label: sweep)
    runs = [("tubecad", tubecad_solid, None)] + [
        (f"tubecad, tol {t:.0e}".replace("e-0", "e-"), tubecad_at(t), None) for t in TUBECAD_TOLERANCES
    ]
    runs += [(named(sweep, label), make, path) for label, path in paths.items() for sweep, make in SWEEPS.items()]
    results, errors = run_methods(name, tube, runs, samples, repeats, log)
    own = [run[0] for run in runs[: 1 + len(TUBECAD_TOLERANCES)]]
    if own[0] in errors:
        raise RuntimeError(f"{name}: tubecad failed: {errors[own[0]]}")
    variants = [m for m in results if m.method in own]
    peers = [m for m in results if m.method not in own]
    why = {m.method: not_counted(m, tube.radius) for m in peers}
    counted = [m for m in peers if why[m.method] is None]
    equal = []
    for peer in counted:
        ours, matched = at_equal_accuracy(variants, peer)
        equal.append(
            {
                "peer": peer.method,
                "peer_deviation": peer.max_deviation,
                "tubecad": ours.method,
                "tubecad_deviation": ours.max_deviation,
                "matched": matched,
                "poles_ratio": ours.poles / peer.poles,
                "build_ratio": ours.build_s / peer.build_s,
            }
        )
    return {
        "axis": description,
        "kind": tube.axis.family,
        "length": tube.length,
        "radius": tube.radius,
        "closed": tube.axis.closed,
        "holonomy": tube.axis.holonomy,
        "axis_s": axis_s,
        "exact_grid": {"F": grid.max_orthogonality_error, "M": grid.max_M_error, "nu": grid.nu, "ns": grid.ns},
        "spines": spine_info,
        "methods": [m.as_dict() for m in results],
        "errors": errors,
        "failed": [m for m, reason in why.items() if reason is not None] + list(errors),
        "not_counted": {
            **{m: reason for m, reason in why.items() if reason is not None},
            **{m: "failed" for m in errors},
        },
        "ratios": ratios(results[0], counted) if counted else None,
        "equal_accuracy": equal,
    }


def run(quick: bool = False, samples: int = 60_000, repeats: int = 3, log=print) -> dict:
    out = {
        "peers": list(SWEEPS),
        "tubecad_tolerances": [DEFAULT_TOLERANCE, *TUBECAD_TOLERANCES],
        "samples_per_method": samples,
        "quick": quick,
        "cases": {},
    }
    start = time.perf_counter()
    for name, setup in CASES.items():
        log(f"  {name}:")
        out["cases"][name] = run_case(name, setup, quick, samples, repeats, log)
    out["seconds"] = time.perf_counter() - start
    return out


def table(result: dict) -> str:
    """tubecad's own numbers on each axis kind, where it stands against the 20 x targets,
    then the comparison per case (compare.py's table and ratio row)."""
    lines = [
        "**Any axis: tubecad** (default tolerance 1e-8; F, M: largest |F|/sqrt(EG) and conjugacy error on "
        "the exact grid; the rest measured on the B-rep as for the peers)",
        "",
        "| case | axis | L | rho | axis + tube ms | build ms | STEP ms | poles | max deviation | max \\|cos\\| "
        "| curvature-line angle (deg) | F (exact grid) | M (exact grid) | valid |",
        "|" + "---|" * 14,
    ]
    for name, case in result["cases"].items():
        m, g = case["methods"][0], case["exact_grid"]
        lines.append(
            f"| {name} | {case['kind']} | {case['length']:.0f} | {case['radius']:g} | {case['axis_s'] * 1e3:.0f} "
            f"| {m['build_s'] * 1e3:.0f} | {m['export_s'] * 1e3:.0f} | {m['poles']:,} | {m['max_deviation']:.1e} "
            f"| {m['max_orthogonality']:.1e} | {m['max_curvature_angle_deg']:.1e} | {g['F']:.1e} | {g['M']:.1e} "
            f"| {'yes' if m['valid'] else 'NO'} |"
        )
    lines += [
        "",
        "**Any axis: against the 20 x targets** (for each peer that made the tube, the tubecad row with the "
        "fewest poles at least as accurate; tubecad / peer, target 0.05 or less; the worst peer shown)",
        "",
        "| case | poles, worst | build time, worst | most accurate peer | its deviation | tubecad row "
        "| poles / its | build / its |",
        "|" + "---|" * 8,
    ]
    for name, case in result["cases"].items():
        equal = case["equal_accuracy"]
        if not equal:
            lines.append(f"| {name} | no peer made the tube | | | | | | |")
            continue
        poles, build = (max(equal, key=lambda e: e[key]) for key in ("poles_ratio", "build_ratio"))
        best = min(equal, key=lambda e: e["peer_deviation"])
        mark = "" if best["matched"] else " (less accurate)"
        lines.append(
            f"| {name} | {poles['poles_ratio']:.2g} ({poles['peer']}) | {build['build_ratio']:.2g} ({build['peer']}) "
            f"| {best['peer']} | {best['peer_deviation']:.1e} | {best['tubecad']}{mark} "
            f"| {best['poles_ratio']:.2g} | {best['build_ratio']:.2g} |"
        )
    for name, case in result["cases"].items():
        spines = "; ".join(
            f"[{label}] {s['description']}, {s['deviation']:.1e} from the axis, made in {s['seconds']:.2g} s"
            for label, s in case["spines"].items()
        )
        grouped: dict[str, list[str]] = {}
        for method, why in case["not_counted"].items():
            grouped.setdefault(why, []).append(method)
        groups = "; ".join(f"{why}: {', '.join(methods)}" for why, methods in grouped.items())
        failed = f"; not counted (not the tube): {groups}" if groups else ""
        lines += [
            "",
            f"**{name}** ({case['axis']}; L = {case['length']:.6g}, rho = {case['radius']:g}; "
            f"spines: {spines}{failed})",
            "",
        ]
        rows = method_table(case["methods"], [("tubecad / best peer", case["ratios"])] if case["ratios"] else [])
        errors = case.get("errors", {})
        at = 2 + len(case["methods"])  # after the header and the measured methods, before the ratio row
        rows[at:at] = [
            f"| {method} | failed: {error.replace('|', '/')} |" + " |" * 7 + " NO |" for method, error in errors.items()
        ]
        lines += rows
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    return case_main(argv, __doc__, run, table, "a coarser trefoil spine, fewer samples, one build each")


if __name__ == "__main__":
    sys.exit(main())
