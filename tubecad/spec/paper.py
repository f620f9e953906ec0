"""The paper's example tube (Nesvidomin et al. 2026, section 5.2, Fig. 2).

k = 10 / s (a logarithmic spiral in plan), beta = 10 deg, rho = 15. The paper gives no
span; tubecad uses s in [200, 1200], where the tube is regular (rho k <= 0.75 < 1 and the
axis never comes back within 2 rho = 30 of itself: its closest return is about 32.8).

``tubecad paper`` is a sample spec built like any other: :data:`PAPER_SPEC` (the wall, 2
thick, on 11 rings and 8 stringers; samples/paper_log_spiral.toml says the same) goes
through :func:`~tubecad.spec.build.build_spec` and :func:`~tubecad.spec.build.export_build`
as ``tubecad build`` takes it; :func:`write_paper` adds the pictures, the stiffened
assembly (its two profiles, 3 high on the rings and 2 on the stringers, are more than one
[stiffeners] section says: :func:`paper_stiffeners`), the polylines and the flat patterns.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from tubecad.curves import LogSpiral
from tubecad.surface import CurvatureLineTube

if TYPE_CHECKING:
    from tubecad.brep import NetLayout, TubeBuild
    from tubecad.spec.parse import TubeSpec
    from tubecad.stiffeners.solids import Stiffener

PAPER_A = 10.0
PAPER_BETA_DEG = 10.0
PAPER_RADIUS = 15.0
PAPER_SPAN = (200.0, 1200.0)
#: the wall `tubecad paper` writes: 2 thick, centred (radii 14 and 16). The axis comes back
#: within 32.8 of itself near s = 200, so an outer radius above about 16.4 self-intersects.
PAPER_WALL_THICKNESS = 2.0
PAPER_RINGS = 11
PAPER_STRINGERS = 8


def PAPER_LAYOUT(tube: CurvatureLineTube) -> NetLayout:  # reads as a constant
    """11 ring frames every 100 along the axis (ends included) and 8 stringers 45 deg apart."""
    from tubecad.brep import NetLayout  # OCCT is loaded only when B-rep is asked for

    return NetLayout.equal(tube, PAPER_RINGS, PAPER_STRINGERS)


def paper_tube(span: tuple[float, float] = PAPER_SPAN) -> CurvatureLineTube:
    """The paper's tube over ``span`` (default s in [200, 1200])."""
    return CurvatureLineTube(LogSpiral(PAPER_A, PAPER_BETA_DEG, span), PAPER_RADIUS)


#: the stiffeners `tubecad paper` adds, inside the wall (outside, the next coil is only
#: 32.8 - 32 = 0.8 away near s = 200): flat-bar ring frames 3 high, 1 thick at the 9
#: interior rings, and flat-bar stringers 2 high, 1 thick at 0 and 180 deg. They are
#: separate solids that overlap where stringers cross rings (fuse merges them).
#: Only those two of the 8 stringers (issue 41): a web along a line of curvature develops
#: flat without strain, its base edge the plane curve of curvature kappa_n (stiffeners/flat.py;
#: an unrolling of the 3-D web triangle by triangle gives the same outline to 6e-6). On the
#: webs at 90 and 270 deg (stringer_02, _06) that curve turns by 648 deg, its curvature
#: growing up to s = 381 and falling after, so its later turns cross its earlier ones (on
#: stringer_02 the part at s = 544 crosses the part at s = 253; 13.3 and 8.9 mm^2 of the two
#: outlines covered twice): a fact of those webs, not of their drawing, which no one plate
#: gives (`tubecad shop` cuts them in pieces); _03 and _07 cross themselves too. The webs at 0 and 180 deg turn by 352 deg, their curvature largest at
#: s = 200, and stay 45.5 and 21.6 clear of themselves: each is cut whole, and the command
#: warns of nothing.
PAPER_STIFFENER_RINGS = list(range(1, PAPER_RINGS - 1))
PAPER_STIFFENER_STRINGERS = [0, 4]
PAPER_RING_PROFILE = ("flat", 3.0, 1.0)
PAPER_STRINGER_PROFILE = ("flat", 2.0, 1.0)
STEEL_DENSITY = 7.85e-6  # kg / mm^3


#: the spec `tubecad paper` builds: the paper's tube, its wall PAPER_WALL_THICKNESS thick,
#: centred, on PAPER_RINGS ring frames and PAPER_STRINGERS stringers
PAPER_SPEC = f"""# The paper's example (Nesvidomin et al. 2026, Fig. 2): tubecad paper
[axis]
curve = "log_spiral"
a = {PAPER_A!r}
beta_deg = {PAPER_BETA_DEG!r}
s = [{PAPER_SPAN[0]!r}, {PAPER_SPAN[1]!r}]

[tube]
radius = {PAPER_RADIUS!r}

[layout]
rings = {PAPER_RINGS}
stringers = {PAPER_STRINGERS}

[wall]
thickness = {PAPER_WALL_THICKNESS!r}
side = "centered"
"""


def paper_spec() -> TubeSpec:
    """:data:`PAPER_SPEC`, checked like a spec file (named ``paper`` in messages)."""
    import tomllib

    from tubecad.spec.parse import parse_spec, tube_spec

    return tube_spec(parse_spec(tomllib.loads(PAPER_SPEC), "paper"), "tubecad paper")


def paper_wall() -> TubeBuild:
    """The wall `tubecad paper` writes: :data:`PAPER_SPEC` built (the paper's tube,
    PAPER_WALL_THICKNESS thick, centred, on PAPER_LAYOUT)."""
    from tubecad.spec.build import build_from_spec

    return build_from_spec(paper_spec())


def paper_stiffeners(build: TubeBuild) -> list[Stiffener]:
    """The stiffeners `tubecad paper` adds to ``build`` (the paper wall): flat-bar ring frames
    at PAPER_STIFFENER_RINGS and stringers at PAPER_STIFFENER_STRINGERS, inside the wall."""
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.profiles import Profile

    rings = build_stiffeners(build, PAPER_STIFFENER_RINGS, [], Profile(*PAPER_RING_PROFILE), "inside")
    return rings + build_stiffeners(build, [], PAPER_STIFFENER_STRINGERS, Profile(*PAPER_STRINGER_PROFILE), "inside")


def write_paper(output: str | Path, nu: int | None = None, ns: int | None = None) -> list[Path]:
    """``tubecad paper``: into ``output`` (created), the projections (projections.png/.svg),
    the wall of :data:`PAPER_SPEC` as paper.step and paper.iges (each read back and measured),
    paper_step.png, the stiffened assembly paper_stiffened.step with its picture, the
    curvature lines as paper_lines.csv/.json, the webs' flat patterns (flat/) and
    report.json, written last; the tube's checks on an ``nu`` x ``ns`` grid. Returns the
    files written, in that order."""
    from tubecad.core.atomic import save_figure, write_text
    from tubecad.export.plots import projection_figure_of_build
    from tubecad.spec.build import build_wall_spec, export_build
    from tubecad.spec.grid import DEFAULT_NS, DEFAULT_NU
    from tubecad.spec.outputs import output_folder, render_step_picture
    from tubecad.spec.report import to_json

    output = output_folder(output)
    built = build_wall_spec(paper_spec(), grid=(DEFAULT_NU if nu is None else nu, DEFAULT_NS if ns is None else ns))
    deviation = built.report["brep"]["fit"]["max_deviation"]  # the projections: the wall's net as built
    written = save_figure(projection_figure_of_build(built.build, deviation), output, "projections")
    names = ("paper.step", "paper.iges")  # each file measured as read back before it is moved into place
    exports = export_build(built, [output / name for name in names], written=written)
    built.report["exports"] = dict(zip(names, exports.values()))
    written.append(render_step_picture(output / "paper.step", output / "paper_step.png"))
    written += write_paper_stiffeners(built.build, output, built.report)
    written.append(write_text(output / "report.json", to_json(built.report)))
    return written


def write_paper_stiffeners(build: TubeBuild, output: Path, report: dict) -> list[Path]:
    """The paper's default stiffeners on ``build`` (the paper wall): the named assembly
    paper_stiffened.step, the polylines, its picture and the webs' flat patterns into
    ``output``; their measures into ``report["stiffeners"]`` (issue 4)."""
    import build123d as bd

    from tubecad.export.cad import export_named_step
    from tubecad.export.render import render_shape_png
    from tubecad.spec.build import wall_lines
    from tubecad.spec.outputs import write_flat_patterns
    from tubecad.spec.report import stiffener_report
    from tubecad.stiffeners import polylines_csv, polylines_json
    from tubecad.stiffeners.assembly import named_assembly

    stiffeners = paper_stiffeners(build)  # shared with `tubecad view paper`
    lines = wall_lines(build)  # on the outer surface, then the inner one (``_inner``)
    step = export_named_step(named_assembly(build, stiffeners, lines), output / "paper_stiffened.step")
    report["stiffeners"] = stiffener_report(stiffeners, lines, STEEL_DENSITY)
    written = write_flat_patterns(stiffeners, output / "flat")
    frame = [c for c in bd.import_step(step).children if c.label.startswith(("ring_", "stringer_"))]
    picture = render_shape_png(
        bd.Compound(children=frame),
        output / "paper_stiffened.png",
        title="paper_stiffened.step as read back: the stiffeners inside the wall (wall hidden)",
    )
    return [
        step,
        polylines_csv(lines, output / "paper_lines.csv"),
        polylines_json(lines, output / "paper_lines.json"),
        picture,
        *written,
    ]
