"""tubecad's canal surfaces against the sweeps with a radius law (issue 12), by the measure of
compare.py and axes.py (each tube face's own OCCT surface sampled densely; poles; build and
STEP time; validity), taken against the true envelope of the spheres of radius r(s) about
the axis. Ratios are tubecad / best peer: below 1 tubecad is better.

``python benchmarks/canal.py [--quick]`` (also ``benchmarks/run.py --only canal``). The
cases are the repository's samples, loaded with load_spec (``.tube``: a CanalSurface):

- nozzle (samples/nozzle.toml): a straight axis, r a smooth step from 40 down to 15;
- tapered helix (samples/tapered_helix.toml): a helix, r = 12 - 0.01 s;
- tapered bend (samples/tapered_bend.toml): a route (a line, a 90 degree bend, a line), r a
  table (a C2 cubic spline through the rows).

The peers sweep an OCCT curve of the same centreline (its distance from the exact axis
reported): the nozzle's straight line as a line edge; the helix as a degree-8 B-spline on
uniform knots, fitted by least squares at arc-length parameters to within 1e-11 of 2000
exact points (the fewest spans that reach it); the route's lines and arcs as a wire
(axes.route_wire, the same curve exactly). The peers (PEERS), each closed into a solid by
planar caps:

- OCCT BRepOffsetAPI_MakePipeShell with a radius law: the circle of radius r(s0) in the
  normal plane at the start and SetLaw with a Law_Interpol through LAW_SAMPLES points
  (parameter, r(s) / r(s0)), s evenly spaced and mapped linearly onto the spine's parameter
  range (OCCT evaluates the law by the spine's relative arc length: the "from the r(s) pipe"
  column shows it lands on r(s)); CorrectedFrenet and DiscreteTrihedron, tolerance 1e-9,
  max degree 11, up to 1000 segments (peers.occt_pipe_shell's settings);
- build123d ``sweep(sections, path, multisection=True)`` of SECTIONS circles of radius
  r(s_i) in the normal planes at s_i evenly spaced (build123d's settings: CorrectedFrenet,
  OCCT's default tolerances);
- build123d ``loft`` (BRepOffsetAPI_ThruSections) through the same circles (no spine).

These peers model the canal surface as circles of radius r(s) centred on the axis in its
normal planes. That is not the envelope: its characteristic circles have radius r q
(q = sqrt(1 - r'^2)), centre c - r r' t, and are the lines of curvature with the stringers
(docs/MATH.md section 8). On a straight axis a point of the normal circle lies about
r r'^2 / 2 inside the envelope; each case's header gives that estimate (largest over s). So
each sweep is measured twice: against the envelope (the result) and against the pipe it was
asked for, | |X - c(s')| - r(s') | with c(s') the closest axis point (how well it built its
model; a peer further than FAILED r_min from that pipe, or invalid by BRepCheck, is not
counted: it did not make the shape it was asked for; one that raises is reported as failed).

At every sample X of a face: e, s* = envelope_distance (the distance outside the envelope,
min over s of |X - c(s)| - r(s), and where it is); the closest point of the envelope is
c(s*) + r(s*) n, n = (X - c(s*)) / |X - c(s*)|, the surface normal there. Its principal
directions are the characteristic circle's, ebar = t x n / |t x n| (t = c'(s*)), and the
stringer's, m = n x ebar (= q t + r' e). The curvature-line angle is that of each isoline
direction of the face, projected into the tangent plane, from the nearer of the two (0: the
isolines are lines of curvature); |cos| is between the face's isoline directions. (The
characteristic circles lie in normal planes too, shifted by -r r' along t: on a straight
axis a normal-circle sweep's isolines are parallel to the envelope's lines of curvature,
while it lies up to r r'^2 / 2 inside; on a curved axis its stringers keep the sweep's frame,
and the envelope's turn from the rotation-minimising one by d chi / ds = (r' / q) kbar.)
Area error: the tube faces' area against the envelope's (CanalSurface.area, a quadrature).

tubecad: build_tube_solid(surface, NetLayout.equal(surface, 2, 1), tolerance) (one face
between the end rings, the route's joints added as rings: one face per piece; planar discs
of the end characteristic circles as caps) at its default tolerance 1e-8 and at 1e-5 and
1e-9; against each counted peer, the tubecad row with the fewest poles that is at least as
accurate (axes.at_equal_accuracy). Where no peer comes within 1e-6 of the envelope the
comparison is one of accuracy first, then poles and time at equal or better accuracy.
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import build123d as bd
import numpy as np
from axes import at_equal_accuracy, route_wire
from compare import case_main, ratios, timed_build
from measure import Measured, poles
from OCP.BRepAdaptor import BRepAdaptor_CompCurve
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell
from OCP.gp import gp_Pnt2d
from OCP.Law import Law_Interpol
from peers import DEFAULT_TOLERANCE, PIPE_MODES, spine_deviation

from tubecad.brep import NetLayout, build_tube_solid, properties
from tubecad.brep.measure import orthogonality, sample_face, tube_faces
from tubecad.export.registry import export_shape
from tubecad.occ_compat import Array1OfPnt2d  # OCP 7.9 and 8 name it differently
from tubecad.spec.parse import load_spec
from tubecad.surface import CanalSurface
from tubecad.surface.checks import distance_to_axis, envelope_distance

ROOT = Path(__file__).resolve().parent.parent
#: tubecad is also fitted to these tolerances (besides its default 1e-8), to compare at equal accuracy
TUBECAD_TOLERANCES = (1e-5, 1e-9)
#: points of the radius law given to MakePipeShell (Law_Interpol through them)
LAW_SAMPLES = 101
#: circles of the multi-section sweep and the loft (evenly spaced in s, both ends included)
SECTIONS = 17
#: a peer further than this (relative to the smallest radius) from the pipe it was asked for is not counted
FAILED = 1e-3
#: a spine further than this from the exact axis is refused
SPINE_LIMIT = 1e-9
#: the helix's spine: degree, exact points, tolerance
FIT_DEGREE, FIT_POINTS, FIT_TOLERANCE = 8, 2000, 1e-11
#: lower is better for each; the ratio columns of the table
RATIO_METRICS = (
    "build_s",
    "export_s",
    "poles",
    "max_deviation",
    "max_orthogonality",
    "max_curvature_angle_deg",
    "area_rel_error",
)


# --- the spines ---------------------------------------------------------------------------------
def line_spine(surface: CanalSurface) -> tuple[bd.Edge, str]:
    """A straight axis as a line edge between its ends."""
    a, b = surface.axis.position(np.array(surface.span))
    return bd.Edge.make_line(bd.Vector(*a), bd.Vector(*b)), "a line edge between the axis' ends"


def fitted_spine(
    surface: CanalSurface, degree: int = FIT_DEGREE, points: int = FIT_POINTS, tolerance: float = FIT_TOLERANCE
) -> tuple[bd.Edge, str]:
    """The axis as a clamped B-spline of ``degree`` on uniform knots in arc length, fitted by
    least squares to ``points`` exact points: the fewest spans within ``tolerance`` of them."""
    from scipy.interpolate import make_lsq_spline

    s0, s1 = surface.span
    s = np.linspace(s0, s1, points)
    xyz = surface.axis.position(s)
    for spans in range(2, 501):
        knots = np.concatenate([[s0] * degree, np.linspace(s0, s1, spans + 1), [s1] * degree])
        fit = make_lsq_spline(s, xyz, knots, degree)
        if np.linalg.norm(fit(s) - xyz, axis=1).max() <= tolerance:
            break
    else:
        raise RuntimeError(f"no degree-{degree} fit within {tolerance:g} with up to {spans} spans")
    return (
        bd.Edge.make_bspline([tuple(p) for p in fit.c], list(knots), degree),
        f"degree {degree} on {spans} uniform spans in arc length, least squares within {tolerance:g} of {points} "
        "exact points",
    )


def wire_spine(surface: CanalSurface) -> tuple[bd.Wire, str]:
    """A route's lines and arcs as a wire (the same curve exactly)."""
    return route_wire(surface.axis), "the route's lines and arcs as a wire"


#: case name -> (sample spec, spine maker)
CASES: dict[str, tuple[Path, Callable]] = {
    "nozzle": (ROOT / "samples" / "nozzle.toml", line_spine),
    "tapered helix": (ROOT / "samples" / "tapered_helix.toml", fitted_spine),
    "tapered bend": (ROOT / "samples" / "tapered_bend.toml", wire_spine),
}


# --- the peers ----------------------------------------------------------------------------------
def normal_circle(surface: CanalSurface, s: float) -> bd.Wire:
    """The circle of radius r(s) centred on the axis in its normal plane at ``s`` (starting along r1)."""
    a = surface.axis.at(np.array([s]))
    r = float(surface.radius_law.r(np.array([s]))[0])
    plane = bd.Plane(origin=tuple(a.position[0]), x_dir=tuple(a.r1[0]), z_dir=tuple(a.t[0]))
    return bd.Wire([bd.Edge.make_circle(r, plane)])


def as_wire(path: bd.Edge | bd.Wire) -> bd.Wire:
    return path if isinstance(path, bd.Wire) else bd.Wire([path])


def radius_law(surface: CanalSurface, path: bd.Edge | bd.Wire, samples: int = LAW_SAMPLES) -> Law_Interpol:
    """Law_Interpol through (parameter, r(s) / r(s0)) at ``samples`` s evenly spaced, s mapped
    linearly onto the spine's parameter range."""
    curve = BRepAdaptor_CompCurve(as_wire(path).wrapped)
    u0, u1 = curve.FirstParameter(), curve.LastParameter()
    s0, s1 = surface.span
    s = np.linspace(s0, s1, samples)
    values = surface.radius_law.r(s) / float(surface.radius_law.r(np.array([s0]))[0])
    table = Array1OfPnt2d(1, samples)
    for i, (x, y) in enumerate(zip(u0 + (s - s0) * (u1 - u0) / (s1 - s0), values), start=1):
        table.SetValue(i, gp_Pnt2d(float(x), float(y)))
    law = Law_Interpol()
    law.Set(table, False)
    return law


def pipe_with_law(mode: str) -> Callable:
    def make(surface: CanalSurface, path: bd.Edge | bd.Wire):
        builder = BRepOffsetAPI_MakePipeShell(as_wire(path).wrapped)
        PIPE_MODES[mode](builder)
        builder.SetTolerance(1e-9, 1e-9, 1e-9)
        builder.SetMaxDegree(11)
        builder.SetMaxSegments(1000)
        builder.SetLaw(normal_circle(surface, surface.span[0]).wrapped, radius_law(surface, path), False, False)
        builder.Build()
        if not builder.IsDone():
            raise RuntimeError("MakePipeShell did not build")
        builder.MakeSolid()
        return bd.Solid(builder.Shape()), True

    return make


def sections(surface: CanalSurface, count: int = SECTIONS) -> list[bd.Face]:
    return [bd.Face(normal_circle(surface, float(s))) for s in np.linspace(*surface.span, count)]


def multisection_sweep(surface: CanalSurface, path: bd.Edge | bd.Wire):
    return bd.sweep(sections(surface), as_wire(path), multisection=True).solids()[0], True


def loft(surface: CanalSurface, _path):
    return bd.loft(sections(surface)).solids()[0], True


#: name -> builder(surface, spine) -> (shape, is_solid)
PEERS: dict[str, Callable] = {
    f"OCCT MakePipeShell + radius law ({LAW_SAMPLES} points), CorrectedFrenet, tol 1e-9": pipe_with_law(
        "CorrectedFrenet"
    ),
    f"OCCT MakePipeShell + radius law ({LAW_SAMPLES} points), DiscreteTrihedron, tol 1e-9": pipe_with_law(
        "DiscreteTrihedron"
    ),
    f"build123d sweep, multisection=True, {SECTIONS} circles": multisection_sweep,
    f"build123d loft, {SECTIONS} circles (no spine)": loft,
}


def tubecad_at(tolerance: float) -> Callable:
    """tubecad's capped canal solid fitted to ``tolerance`` (the spine is not used)."""

    def make(surface: CanalSurface, _path):
        return build_tube_solid(surface, NetLayout.equal(surface, 2, 1), tolerance).shape, True

    return make


# --- the measure --------------------------------------------------------------------------------
@dataclass
class CanalMeasured(Measured):
    """measure.Measured against the envelope (max_deviation, the curvature-line angle, area
    and volume errors), plus the distance from the pipe of the normal circles r(s)."""

    max_pipe_deviation: float


def against_envelope(
    surface: CanalSurface, points: np.ndarray, d1: np.ndarray, d2: np.ndarray
) -> tuple[float, float, float, float]:
    """(max |distance from the envelope|, max distance from the normal-circle pipe of r(s),
    max |cos| between d1 and d2, max angle in degrees of d1 and d2 from the principal
    directions of the envelope at the closest point) of the samples."""
    e, s_star = envelope_distance(surface, points)
    a = surface.axis.at(s_star)
    n = points - a.position
    n /= np.linalg.norm(n, axis=1)[:, None]
    ebar = np.cross(a.t, n)
    ebar /= np.linalg.norm(ebar, axis=1)[:, None]
    m = np.cross(n, ebar)

    def angle(w: np.ndarray) -> np.ndarray:
        w = w - np.einsum("ij,ij->i", w, n)[:, None] * n
        w = w / np.linalg.norm(w, axis=1)[:, None]
        # atan2(|w x d|, |w . d|): arccos of a cosine near 1 would floor at ~1e-6 deg
        angles = [
            np.arctan2(np.linalg.norm(np.cross(w, d), axis=1), np.abs(np.einsum("ij,ij->i", w, d))) for d in (ebar, m)
        ]
        return np.degrees(np.minimum(*angles))

    d, s_axis = distance_to_axis(surface.axis, points)
    pipe = np.abs(d - surface.radius_law.r(s_axis))
    return (
        float(np.abs(e).max()),
        float(pipe.max()),
        float(orthogonality(d1, d2).max()),
        float(np.maximum(angle(d1), angle(d2)).max()),
    )


def measure_canal(
    method: str,
    shape,
    surface: CanalSurface,
    exact: tuple[float, float],
    build_s: float,
    samples: int = 60_000,
    solid: bool = True,
) -> CanalMeasured:
    """All the measurements of ``shape`` against ``surface``; ``exact``: its (area, volume)."""
    faces = list(tube_faces(shape))
    per_face = max(samples // len(faces), 64)
    nu = max(int(math.sqrt(per_face / 20)), 4)  # around x along, about 1 : 20 (measure.py's)
    nv = max(per_face // nu, 16)
    deviation = pipe = cos = angle = 0.0
    for face in faces:
        found = against_envelope(surface, *sample_face(face, nu, nv))
        deviation, pipe, cos, angle = (max(x, y) for x, y in zip((deviation, pipe, cos, angle), found))
    area = properties.faces_area(faces)
    volume_error = abs(properties.volume(shape) / exact[1] - 1.0) if solid else None
    with tempfile.TemporaryDirectory() as folder:
        target = Path(folder) / "shape.step"
        start = time.perf_counter()
        export_shape(shape, target)
        export_s = time.perf_counter() - start
        size = target.stat().st_size
    return CanalMeasured(
        method=method,
        build_s=build_s,
        export_s=export_s,
        step_bytes=size,
        faces=len(faces),
        poles=sum(poles(f) for f in faces),
        max_deviation=deviation,
        max_orthogonality=cos,
        max_curvature_angle_deg=angle,
        area_rel_error=abs(area / exact[0] - 1.0),
        volume_rel_error=volume_error,
        valid=properties.is_valid(shape),
        samples=len(faces) * nu * nv,
        max_pipe_deviation=pipe,
    )


# --- the run ------------------------------------------------------------------------------------
def model_error(surface: CanalSurface, samples: int = 4001) -> dict:
    """The largest |r'| and r r'^2 / 2 (about how far inside the envelope a normal circle of
    radius r lies, on a straight axis), largest over s."""
    s = np.linspace(*surface.span, samples)
    r, dr = surface.radius_law.r(s), surface.radius_law.dr(s)
    return {"max_abs_slope": float(np.abs(dr).max()), "normal_circle_estimate": float((0.5 * r * dr * dr).max())}


def run_case(name: str, spec: Path, make_spine: Callable, samples: int, repeats: int, log=print) -> dict:
    start = time.perf_counter()
    surface = load_spec(spec).tube
    load_s = time.perf_counter() - start
    if not isinstance(surface, CanalSurface):
        raise RuntimeError(f"{name}: {spec.name} is not a canal surface")
    start = time.perf_counter()
    path, spine_text = make_spine(surface)
    spine_s = time.perf_counter() - start
    spine_dev = spine_deviation(surface, path, 20_000)
    if not spine_dev < SPINE_LIMIT:
        raise RuntimeError(f"{name}: the spine is {spine_dev:.2g} from the axis (limit {SPINE_LIMIT:g})")
    exact = surface.measures()
    runs = [("tubecad", tubecad_at(DEFAULT_TOLERANCE))]
    runs += [(f"tubecad, tol {t:.0e}".replace("e-0", "e-"), tubecad_at(t)) for t in TUBECAD_TOLERANCES]
    own = [method for method, _ in runs]
    runs += list(PEERS.items())
    results: list[CanalMeasured] = []
    errors: dict[str, str] = {}
    for method, make in runs:
        try:
            shape, solid, build_s = timed_build(make, surface, path, repeats)
            results.append(measure_canal(method, shape, surface, exact, build_s, samples, solid))
        except Exception as exc:  # a peer failing here is a result
            if method in own:
                raise
            errors[method] = f"{type(exc).__name__}: {str(exc).strip() or 'no message'}"[:200]
            log(f"  {name}: {method}: FAILED ({errors[method]})")
            continue
        m = results[-1]
        log(
            f"  {name}: {method}: {m.max_deviation:.2e} from the envelope, {m.max_pipe_deviation:.2e} from the r(s) "
            f"pipe, {build_s * 1e3:.0f} ms{'' if m.valid else ', INVALID'}"
        )
    variants = [m for m in results if m.method in own]
    peers = [m for m in results if m.method not in own]
    limit = FAILED * surface.radius_law.min_radius
    not_counted = {
        m.method: ", ".join(
            ([] if m.valid else ["invalid"])
            + ([] if m.max_pipe_deviation < limit else [f"{m.max_pipe_deviation:.1e} off the r(s) pipe"])
        )
        for m in peers
    }
    not_counted = {**{k: v for k, v in not_counted.items() if v}, **{k: "failed" for k in errors}}
    counted = [m for m in peers if m.method not in not_counted]
    equal = []
    for peer in counted:
        ours, matched = at_equal_accuracy(variants, peer)
        equal.append(
            {
                "peer": peer.method,
                "peer_deviation": peer.max_deviation,
                "peer_poles": peer.poles,
                "tubecad": ours.method,
                "tubecad_deviation": ours.max_deviation,
                "matched": matched,
                "poles_ratio": ours.poles / peer.poles,
                "build_ratio": ours.build_s / peer.build_s,
            }
        )
    summary = None
    if counted:  # the tubecad row at least as accurate as the most accurate peer (so as every peer)
        best = min(counted, key=lambda m: m.max_deviation)
        ours, matched = at_equal_accuracy(variants, best)
        fewest, fastest = min(counted, key=lambda m: m.poles), min(counted, key=lambda m: m.build_s)
        summary = {
            "best_peer": best.method,
            "best_peer_deviation": best.max_deviation,
            "tubecad": ours.method,
            "tubecad_deviation": ours.max_deviation,
            "tubecad_poles": ours.poles,
            "tubecad_build_s": ours.build_s,
            "matched": matched,
            "fewest_poles_peer": fewest.method,
            "fewest_poles": fewest.poles,
            "poles_ratio": ours.poles / fewest.poles,
            "fastest_peer": fastest.method,
            "fastest_build_s": fastest.build_s,
            "build_ratio": ours.build_s / fastest.build_s,
        }
    law = surface.radius_law
    return {
        "spec": str(spec.relative_to(ROOT)),
        "axis": type(surface.axis).__name__,
        "length": surface.length,
        "radius": {"min": law.min_radius, "max": law.max_radius},
        "model": model_error(surface),
        "exact": {"area": exact[0], "volume": exact[1]},
        "load_s": load_s,
        "spine": {"description": spine_text, "deviation": spine_dev, "seconds": spine_s},
        "methods": [m.as_dict() for m in results],
        "errors": errors,
        "not_counted": not_counted,
        "peers_within_1e-6": [m.method for m in counted if m.max_deviation <= 1e-6],
        "ratios": ratios(results[0], counted, RATIO_METRICS) if counted else None,
        "equal_accuracy": equal,
        "summary": summary,
    }


def run(quick: bool = False, samples: int = 60_000, repeats: int = 3, log=print) -> dict:
    out = {
        "peers": list(PEERS),
        "tubecad_tolerances": [DEFAULT_TOLERANCE, *TUBECAD_TOLERANCES],
        "law_samples": LAW_SAMPLES,
        "sections": SECTIONS,
        "samples_per_method": samples,
        "quick": quick,
        "cases": {},
    }
    start = time.perf_counter()
    for name, (spec, make_spine) in CASES.items():
        log(f"  {name}:")
        out["cases"][name] = run_case(name, spec, make_spine, samples, repeats, log)
    out["seconds"] = time.perf_counter() - start
    return out


# --- the tables ---------------------------------------------------------------------------------
def method_table(case: dict) -> list[str]:
    lines = [
        "| method | build ms | STEP ms | poles | max deviation from the envelope | from the r(s) pipe "
        "| max \\|cos\\| | curvature-line angle (deg) | area error | valid |",
        "|" + "---|" * 10,
    ]
    for m in case["methods"]:
        lines.append(
            f"| {m['method']} | {m['build_s'] * 1e3:.0f} | {m['export_s'] * 1e3:.0f} | {m['poles']:,} "
            f"| {m['max_deviation']:.1e} | {m['max_pipe_deviation']:.1e} | {m['max_orthogonality']:.1e} "
            f"| {m['max_curvature_angle_deg']:.1e} | {m['area_rel_error']:.1e} | {'yes' if m['valid'] else 'NO'} |"
        )
    lines += [
        f"| {method} | failed: {error.replace('|', '/')} |" + " |" * 7 + " NO |"
        for method, error in case["errors"].items()
    ]
    if case["ratios"]:
        r = case["ratios"]
        cells = ["-" if r[k]["ratio"] is None else f"{r[k]['ratio']:.2g}" for k in RATIO_METRICS]
        lines.append("| *tubecad / best peer* | " + " | ".join(cells[:4]) + " | - | " + " | ".join(cells[4:]) + " | |")
    return lines


def table(result: dict) -> str:
    """The summary (per case: the most accurate peer, and tubecad at least as accurate), then
    per case the methods with the ratio row."""
    lines = [
        "**Canal surfaces: against the sweeps with a radius law** (deviation from the true envelope of the "
        "spheres; the tubecad row with the fewest poles at least as accurate as every counted peer, against the "
        "peer with the fewest poles and the fastest one)",
        "",
        "| case | axis | L | r | max \\|r'\\| | r r'^2/2 | peers within 1e-6 | most accurate peer's deviation "
        "| tubecad row | its deviation | poles / fewest-poles peer | build / fastest peer | tubecad (1e-8) deviation |",
        "|" + "---|" * 13,
    ]
    for name, case in result["cases"].items():
        m, rad, e = case["model"], case["radius"], case["summary"]
        head = (
            f"| {name} | {case['axis']} | {case['length']:.0f} | {rad['max']:g} to {rad['min']:g} "
            f"| {m['max_abs_slope']:.3g} | {m['normal_circle_estimate']:.1e} | {len(case['peers_within_1e-6'])} "
        )
        own = case["methods"][0]["max_deviation"]
        if e is None:
            lines.append(head + f"| no peer counted | | | | | {own:.1e} |")
            continue
        mark = "" if e["matched"] else " (less accurate)"
        lines.append(
            head + f"| {e['best_peer_deviation']:.1e} | {e['tubecad']}{mark} | {e['tubecad_deviation']:.1e} "
            f"| {e['poles_ratio']:.2g} ({e['fewest_poles_peer']}) | {e['build_ratio']:.2g} ({e['fastest_peer']}) "
            f"| {own:.1e} |"
        )
    for name, case in result["cases"].items():
        m, spine = case["model"], case["spine"]
        grouped: dict[str, list[str]] = {}
        for method, why in case["not_counted"].items():
            grouped.setdefault(why, []).append(method)
        groups = "; ".join(f"{why}: {', '.join(methods)}" for why, methods in grouped.items())
        lines += [
            "",
            f"**{name}** (`{case['spec']}`, {case['axis']}, L = {case['length']:.6g}, r from "
            f"{case['radius']['max']:g} to {case['radius']['min']:g}, max |r'| = {m['max_abs_slope']:.3g} "
            f"(a normal circle of radius r lies up to about r r'^2/2 = {m['normal_circle_estimate']:.1e} "
            f"inside the envelope); spine: {spine['description']}, {spine['deviation']:.1e} from the axis"
            f"{f'; not counted: {groups}' if groups else ''})",
            "",
        ]
        lines += method_table(case)
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    return case_main(argv, __doc__, run, table, "fewer samples, one build each")


if __name__ == "__main__":
    sys.exit(main())
