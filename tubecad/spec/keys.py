"""The keys a spec file may hold, section by section: the one table that the spec checker
(:mod:`tubecad.spec.parse`), the JSON Schema (:mod:`tubecad.spec.schema`,
``tubecad schema``), ``--sweep`` and the README's checks are all made from.

Light on purpose (no numpy, no OCCT), so that ``tubecad schema`` starts at once: the
limits it names come from the light modules that enforce them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from tubecad.brep.wall import WALL_SIDES
from tubecad.core.tolerance import MIN_SIZE
from tubecad.core.units import DEFAULT_LENGTH_UNIT, LENGTH_UNITS
from tubecad.core.validation import MAX_LENGTH
from tubecad.fem.settings import BEAM_TYPES, DEFAULT_MAX_ELEMENTS, ENDS, MAX_ELEMENTS_LIMIT, SHELL_TYPES, SURFACES
from tubecad.stiffeners.profiles import KINDS, SIDES


@dataclass(frozen=True)
class Key:
    """One allowed key: its TOML type(s), whether it is required, and what it means.

    ``choices``: the values a string key may take (the checker refuses any other, naming
    them). ``low``/``high`` (open or closed ends): the key's numeric range as the schema
    gives it to editors; the checker enforces it with the rule's own message (the tests
    hold the two together). ``default``: what an absent key means, for the schema.
    """

    kind: str  # "number", "string", "bool", "pair", "triple", "numbers", "number_or_numbers", "integer", "selection",
    #            "points", "radius" (a number, an expression or a table of [s, r] rows), "joints" (a table of
    #            name = [numbers]), "table" (an inline table of the keys ``keys``)
    required: bool = True
    help: str = ""
    choices: tuple[str, ...] = ()
    low: float | None = None
    high: float | None = None
    low_open: bool = True
    high_open: bool = True
    default: Any = None
    keys: Any = None  # a "table" key's own keys (dict[str, Key])


#: the keys every slope-curve family shares
SLOPE_KEYS = {
    "beta_deg": Key("number", help="elevation angle, -90 < beta_deg < 90", low=-90.0, high=90.0),
    "s": Key("pair", help="arc-length span [start, end]"),
}
#: an axis' optional start normal r1 (the stringers' u = 0)
NORMAL_KEY = Key(
    "triple",
    required=False,
    help="the first stringer's direction r1 at the start, [x, y, z] "
    "(made normal to the tangent; default the principal normal)",
)
#: whether an axis is a closed loop (not a slope curve's: those never close)
CLOSED_KEY = Key(
    "bool",
    required=False,
    help="a closed loop (true: demand, false: keep open; default: detected when the ends and tangents agree)",
)

#: curve -> its [axis] keys (besides curve)
FAMILY_KEYS: dict[str, dict[str, Key]] = {
    "log_spiral": {"a": Key("number", help="k = a / s, a > 0", low=0.0), **SLOPE_KEYS},
    "helix": {"k": Key("number", help="constant curvature k (0 gives a straight axis)"), **SLOPE_KEYS},
    "clothoid": {"A": Key("number", help="k = s / A^2, A > 0", low=0.0), **SLOPE_KEYS},
    "involute": {
        "a": Key("number", help="k = 1 / sqrt(2 a s): involute of a circle of radius a > 0", low=0.0),
        **SLOPE_KEYS,
    },
    "custom": {
        "k": Key("string", help="curvature as an arithmetic expression in s"),
        **SLOPE_KEYS,
        "psi0_deg": Key("number", required=False, help="direction of the plan at s0, degrees"),
        "origin": Key("triple", required=False, help="axis point at s0, [x, y, z]"),
    },
    "natural": {
        "k": Key("string", help="curvature k(s) >= 0 as an expression in s"),
        "tau": Key("string", help="torsion tau(s) as an expression in s"),
        "s": Key("pair", help="arc-length span [start, end]"),
        "origin": Key("triple", required=False, help="axis point at the start, [x, y, z] (default [0, 0, 0])"),
        "tangent": Key("triple", required=False, help="unit tangent at the start (default [1, 0, 0])"),
        "normal": Key("triple", required=False, help="principal normal at the start (default [0, 1, 0])"),
        "closed": CLOSED_KEY,
    },
    "parametric": {
        "x": Key("string", help="x(t) as an expression in t"),
        "y": Key("string", help="y(t) as an expression in t"),
        "z": Key("string", help="z(t) as an expression in t"),
        "t": Key("pair", help="parameter span [start, end]"),
        "normal": NORMAL_KEY,
        "closed": CLOSED_KEY,
    },
    "points": {
        "points": Key("points", required=False, help="the points [[x, y, z], ...], 3 or more (or file)"),
        "file": Key("string", required=False, help="a CSV file of x, y, z rows, relative to the spec (or points)"),
        "parameterisation": Key(
            "string",
            required=False,
            help="centripetal | chord (default centripetal)",
            choices=("centripetal", "chord"),
            default="centripetal",
        ),
        "normal": NORMAL_KEY,
        "closed": CLOSED_KEY,
    },
    "route": {
        "points": Key("points", required=False, help="the route's vertices [[x, y, z], ...], 3 or more (or file)"),
        "file": Key("string", required=False, help="a CSV file of x, y, z rows, relative to the spec (or points)"),
        "bend_radius": Key(
            "number_or_numbers",
            help="the bends' radius (of the axis): one number, or one per inner "
            "vertex; each bend must fit its legs and exceed the tube radius",
        ),
        "normal": NORMAL_KEY,
        "closed": CLOSED_KEY,
    },
    "edge": {
        "file": Key("string", help="a STEP or BREP file holding the centreline, relative to the spec"),
        "name": Key("string", required=False, help="the edge or wire's name in the STEP file"),
        "index": Key(
            "integer",
            required=False,
            help="which edge or wire (0-based, wires first) if several",
            low=0,
            low_open=False,
        ),
        "normal": NORMAL_KEY,
        "closed": CLOSED_KEY,
    },
}
AXIS_COMMON = {
    "curve": Key("string", help=" | ".join(FAMILY_KEYS), choices=tuple(FAMILY_KEYS)),
}
TUBE_KEYS = {
    "radius": Key(
        "radius",
        help="radius rho > 0 of the generating circle; or a radius law r(s), a canal surface: an "
        "expression in s (and x, y, z, the axis point), or a table [[s, r], ...] (C2 cubic spline), with |r'| < 1",
        low=MIN_SIZE,
        high=MAX_LENGTH,
        low_open=False,
        high_open=False,
    ),
    "allow_irregular": Key("bool", required=False, help="build even if rho*k >= 1 or the axis comes back within 2 rho"),
}

LAYOUT_KEYS = {
    "rings": Key(
        "integer",
        required=False,
        help="ring frames equally spaced in s, ends included (a closed axis: that many distinct rings), 2 to 10000",
        low=2,
        high=10_000,
        low_open=False,
        high_open=False,
    ),
    "stringers": Key(
        "integer",
        required=False,
        help="stringers at u = 360 j / M degrees, 1 to 1000",
        low=1,
        high=1_000,
        low_open=False,
        high_open=False,
    ),
    "s_rings": Key("numbers", required=False, help="explicit ring arc lengths (span ends are added)"),
    "u_stringers_deg": Key("numbers", required=False, help="explicit stringer angles, degrees"),
}
WALL_KEYS = {
    "thickness": Key("number", help="wall thickness > 0", low=MIN_SIZE, low_open=False),
    "side": Key("string", required=False, help=f"{' | '.join(WALL_SIDES)} (default centered)", choices=WALL_SIDES),
}
FIT_KEYS = {
    "tolerance": Key(
        "number", required=False, help="max deviation from the exact tube, model units, in (0, 1)", low=0.0, high=1.0
    ),
}

STIFFENER_KEYS = {
    "rings": Key("selection", required=False, help='ring indices into the layout, or "all" (default none)'),
    "stringers": Key("selection", required=False, help='stringer indices into the layout, or "all" (default none)'),
    "profile": Key("string", required=False, help=f"{' | '.join(KINDS)} (default flat)", choices=KINDS),
    "height": Key("number", help="web height from the wall > 0", low=0.0),
    "thickness": Key("number", help="web thickness > 0", low=0.0),
    "flange_width": Key("number", required=False, help="T and L: total flange width > thickness", low=0.0),
    "flange_thickness": Key("number", required=False, help="T and L: flange thickness in (0, height)", low=0.0),
    "k1": Key("selection", required=False, help='a [host] net: its k1 lines\' indices, or "all" (default none)'),
    "k2": Key("selection", required=False, help='a [host] net: its k2 lines\' indices, or "all" (default none)'),
    "side": Key("string", required=False, help=f"{' | '.join(SIDES)} (default outside)", choices=SIDES),
    "fuse": Key("bool", required=False, help="merge the stiffeners into the wall (default false)"),
    "density": Key(
        "number",
        required=False,
        low=0.0,
        help="kg per cubic [units] length for the reported masses (default steel: 7.85e-6 kg/mm^3, 7850 kg/m^3)",
    ),
}

PANEL_KEYS = {
    "seams": Key("selection", help='seam stringers: indices into the layout\'s stringers, or "all"'),
    "rings": Key("selection", required=False, help='ring indices bounding the panels, or "all" (default all)'),
}

FABRICATION_KEYS = {
    "plate_size": Key(
        "pair",
        required=False,
        help="[length, width] of the stock plates webs and flanges are nested "
        "on, each > 2 kerf (default 3000 x 1500 mm)",
    ),
    "kerf": Key(
        "number",
        required=False,
        low=0.0,
        low_open=False,
        help="the cut's width >= 0: parts lie 2 kerf apart and a kerf from the plate's edge (default 2 mm)",
    ),
    "joint_gap": Key(
        "number",
        required=False,
        low=0.0,
        low_open=False,
        help="a butt joint's root gap >= 0, along the web's base line (default 0)",
    ),
    "max_strain": Key(
        "number", required=False, low=0.0, help="panels whose development strains more are flagged, > 0 (default 0.01)"
    ),
    "pin_spacing": Key(
        "number",
        required=False,
        low=0.0,
        help="the pin-jig grid's spacing > 0 (default: a round value giving ~6 pins across each panel)",
    ),
    "pin_clearance": Key(
        "number",
        required=False,
        low=0.0,
        low_open=False,
        help="the panel's lowest point above the jig plane >= 0 (default 0)",
    ),
    "joints": Key(
        "joints",
        required=False,
        help="chosen butt joints per stiffener: a table of name = [positions], s "
        "along a stringer, degrees in [0, 360) round a ring (e.g. stringer_02 = [450.0])",
    ),
}

MESH_KEYS = {
    "element": Key(
        "string",
        required=False,
        choices=SHELL_TYPES,
        default="S8R",
        help=f"the shell element: {' | '.join(SHELL_TYPES)} (linear or quadratic; R: reduced integration)",
    ),
    "beam": Key(
        "string",
        required=False,
        choices=BEAM_TYPES,
        help=f"the stiffeners' beam element: {' | '.join(BEAM_TYPES)} (default B31 with S4, B32 with S8)",
    ),
    "size": Key(
        "number",
        required=False,
        low=0.0,
        high=MAX_LENGTH,
        high_open=False,
        help="the longest element edge, both ways, > 0 (default 2 pi r / 32 of the smallest radius)",
    ),
    "size_along": Key(
        "number",
        required=False,
        low=0.0,
        high=MAX_LENGTH,
        high_open=False,
        help="the longest element edge along the stringers, > 0 (default size)",
    ),
    "size_around": Key(
        "number",
        required=False,
        low=0.0,
        high=MAX_LENGTH,
        high_open=False,
        help="the longest element edge round the rings, > 0 (default size)",
    ),
    "surface": Key(
        "string",
        required=False,
        choices=SURFACES,
        default="mid",
        help=f"{' | '.join(SURFACES)}: the wall's mid-surface with its thickness, its inner or outer face "
        "(the section offset into the wall), or both faces",
    ),
    "max_elements": Key(
        "integer",
        required=False,
        low=1,
        high=MAX_ELEMENTS_LIMIT,
        low_open=False,
        high_open=False,
        default=DEFAULT_MAX_ELEMENTS,
        help=f"refuse meshes with more elements, 1 to {MAX_ELEMENTS_LIMIT}",
    ),
    "beams": Key("bool", required=False, default=True, help="the [stiffeners] as beam elements (default true)"),
}

ANALYSIS_KEYS = {
    "pressure": Key(
        "number", required=False, default=0.0, help="internal pressure, N per square [units] length (mm: MPa)"
    ),
    "ends": Key(
        "string",
        required=False,
        choices=ENDS,
        help=f"{' | '.join(ENDS)}: end rings held, capped (the caps' resultant on the end rings), or free "
        "(a closed tube; default fixed, free when closed)",
    ),
    "youngs_modulus": Key(
        "number", required=False, low=0.0, help="N per square [units] length (default steel, 210 GPa: 210000 in mm)"
    ),
    "poisson_ratio": Key("number", required=False, low=-1.0, high=0.5, default=0.3, help="in (-1, 0.5)"),
    "allowable_stress": Key(
        "number",
        required=False,
        low=0.0,
        help="the allowable stress S of shell and branches, N per square [units] length, > 0: with pressure, "
        "the [[branches]]' area-replacement figures (UG-37 style, a geometric aid) in the report",
    ),
}

BATCH_KEYS = {
    "scheduler": Key(
        "string",
        required=False,
        help="a Dask distributed scheduler, tcp://HOST:PORT: tubecad build's batches of this spec (its "
        "first SPEC) run there (the extra tubecad[dask]; --scheduler wins)",
    ),
}

UNITS_KEYS = {
    "length": Key(
        "string",
        required=False,
        choices=tuple(LENGTH_UNITS),
        default=DEFAULT_LENGTH_UNIT,
        help=f"{' | '.join(LENGTH_UNITS)}: the unit of every length in the spec, written into STEP, "
        f"IGES, DXF, 3MF and glTF (default {DEFAULT_LENGTH_UNIT})",
    ),
}

#: a branch's reinforcement pad: a plate on the main wall bounded by two rings and two stringers
PAD_KEYS = {
    "thickness": Key("number", help="the pad's thickness > 0, on the main wall's outer surface", low=0.0),
    "width": Key("number", help="how far the pad reaches beyond the branch's outer saddle every way, > 0", low=0.0),
}

BLEND_KEYS = {
    "radius": Key(
        "number",
        help="the rolling ball's radius > 0: the blend along the branch's outer saddle (a forged tee's crotch "
        "radius, a weld fillet), a canal surface tangent to both walls",
        low=0.0,
    ),
}

#: a branch's own stiffeners: its rings and stringers with the main [stiffeners] profile and side
BRANCH_STIFFENER_KEYS = {
    "rings": Key("selection", required=False, help='ring indices into the branch\'s layout, or "all" (default none)'),
    "stringers": Key(
        "selection", required=False, help='stringer indices into the branch\'s layout, or "all" (default none)'
    ),
    "start": Key(
        "number",
        required=False,
        low=0.0,
        low_open=False,
        help="how far beyond the saddle's highest point the branch's ring frames must lie, >= 0 "
        "(default the profile's height)",
    ),
}

#: a branch's own axis by its natural equations (default: a straight line)
BRANCH_AXIS_KEYS = {
    "k": Key("string", required=False, default="0", help="curvature k(s) >= 0 along the branch, an expression in s"),
    "tau": Key("string", required=False, default="0", help="torsion tau(s) along the branch, an expression in s"),
}

#: one [[branches]] table: a branch tube whose wall joins the main tube's wall
BRANCH_KEYS = {
    "at": Key("number", help="arc length s on the main axis where the branch's axis leaves it, inside the span"),
    "length": Key(
        "number", help="the branch's length along its axis, from where it leaves the main axis, > 0", low=0.0
    ),
    "radius": Key(
        "radius",
        help="the branch's radius rho > 0, its outer surface starting inside the main's outer surface and its bore "
        "inside the main's bore; or a radius law r(s) along the branch",
    ),
    "angle": Key(
        "number",
        required=False,
        default=90.0,
        low=0.0,
        high=180.0,
        help="degrees from the main axis' tangent at `at` to the branch's axis, 0 < angle < 180 "
        "(default 90: a square tee; 45: a lateral)",
    ),
    "around": Key(
        "number",
        required=False,
        default=90.0,
        help="degrees round the main axis from its first stringer (u = 0) to the side the branch leaves on (default 90)",
    ),
    "offset": Key(
        "number",
        required=False,
        default=0.0,
        help="the branch axis' sideways offset from the main axis (a hillside nozzle); the branch's surfaces must "
        "start inside the main's (default 0)",
    ),
    "axis": Key(
        "table",
        required=False,
        keys=BRANCH_AXIS_KEYS,
        help='the branch\'s axis by its natural equations, { k = "...", tau = "..." } in its own arc '
        "length s from the main axis (default a straight line); it leaves along the angle and side given",
    ),
    "wall": Key(
        "table",
        required=False,
        keys=WALL_KEYS,
        help="the branch's wall, { thickness = ..., side = ... } (default the main [wall])",
    ),
    "layout": Key(
        "table",
        required=False,
        keys=LAYOUT_KEYS,
        help="the branch's rings and stringers, as [layout] (default 3 rings and the main tube's stringers)",
    ),
    "stiffeners": Key(
        "table",
        required=False,
        keys=BRANCH_STIFFENER_KEYS,
        help="the branch's ring frames and stringers, { rings = [...], stringers = [...], start = ... }, with the "
        "main [stiffeners] profile and side: its stringers start on the saddle, its rings beyond it (default none)",
    ),
    "pad": Key(
        "table",
        required=False,
        keys=PAD_KEYS,
        help="a reinforcement pad round the branch, { thickness = ..., width = ... }: its own solid `pad`, "
        "bounded by two rings and two stringers of the main wall (no pad by default)",
    ),
    "blend": Key(
        "table",
        required=False,
        keys=BLEND_KEYS,
        help="a crotch blend along the branch's outer saddle, { radius = ... }: the rolling ball's canal surface, "
        "tangent to both walls along its edges blend_main and blend_branch (no blend by default)",
    ),
}

#: the most lines of curvature per family on a [host] face (tubecad.nets.net.MOST_LINES)
MOST_HOST_LINES = 200


def _lines_key(family: str) -> Key:
    return Key(
        "integer",
        required=False,
        help=f"{family} lines: how many, 1 to {MOST_HOST_LINES} (or {family}_spacing; default 8)",
        low=1,
        high=MOST_HOST_LINES,
        low_open=False,
        high_open=False,
    )


def _spacing_key(family: str) -> Key:
    return Key(
        "number",
        required=False,
        help=f"the distance between neighbouring {family} lines > 0, along the other family's line through "
        f"the seed (instead of {family}_lines)",
        low=0.0,
    )


#: [host]: a face the user already has, its curvature-line net (instead of [axis] and [tube])
HOST_KEYS = {
    "step": Key("string", help="the STEP file holding the face, relative to the spec"),
    "face": Key(
        "index_or_name",
        required=False,
        help="which face: its 0-based index in the file's order, or its name (default 0)",
        low=0,
        low_open=False,
    ),
    "k1_lines": _lines_key("k1"),
    "k2_lines": _lines_key("k2"),
    "k1_spacing": _spacing_key("k1"),
    "k2_spacing": _spacing_key("k2"),
    "seed": Key(
        "triple",
        required=False,
        help="a point [x, y, z] of the face: each family's lines are spread along the other family's line through it "
        "(default the face's parameter centre)",
    ),
    "patches": Key(
        "string",
        required=False,
        help="host | curvature: the cells on the face's own surface (default), or each four-sided cell refitted "
        "as a B-spline patch whose isolines are its lines of curvature (those missing the fit's target stay on "
        "the face; the report's patches section says which)",
        choices=("host", "curvature"),
        default="host",
    ),
}
#: the sections a [host] spec may have besides [host]
HOST_SECTIONS = ("wall", "stiffeners", "units", "fabrication", "mesh", "analysis")

#: sections beyond [axis] and [tube]
EXTRA_SECTIONS: dict[str, dict[str, Key]] = {
    "layout": LAYOUT_KEYS,
    "wall": WALL_KEYS,
    "fit": FIT_KEYS,
    "stiffeners": STIFFENER_KEYS,
    "panels": PANEL_KEYS,
    "units": UNITS_KEYS,
    "fabrication": FABRICATION_KEYS,
    "mesh": MESH_KEYS,
    "analysis": ANALYSIS_KEYS,
    "batch": BATCH_KEYS,
}

#: what each section is for (the schema's descriptions)
SECTION_HELP = {
    "axis": "the axis: a slope curve (k(s) and an elevation angle), natural equations k(s), tau(s), a parametric "
    "curve, points, a route of lines and bends or a CAD edge",
    "tube": "the tube: the circle of radius rho moved along the axis",
    "host": "instead of [axis] and [tube]: a face the user already has (a STEP file's), its curvature-line net "
    "as edges, the face split into its patches; [stiffeners] k1 and k2 stand webs on its lines",
    "layout": "the B-rep's ring frames and stringers (default 11 rings, 8 stringers)",
    "wall": "a wall solid of this thickness instead of the capped tube",
    "fit": "the fit of the B-spline surfaces to the exact tube",
    "stiffeners": "stiffener solids (ring frames, stringers) on the layout's lines",
    "panels": "split the wall into panels along seam stringers",
    "units": "the unit of every length in the spec and in the files written",
    "fabrication": "shop-floor settings for tubecad shop: plates, kerf, butt joints, strain limit, pin jigs",
    "mesh": "the finite-element mesh of tubecad mesh: shell and beam elements, sizes, surface, element cap",
    "analysis": "the pressure analysis of tubecad analyse (CalculiX): pressure, ends, material",
    "batch": "where tubecad build runs a batch of this spec: a Dask cluster",
    "branches": "branch tubes on the main tube's wall ([[branches]], one table each; needs [wall]): tubecad build "
    "makes the junction one solid with the saddles as named edges",
}

#: sections that are arrays of tables ([[name]]), each table of these keys
ARRAY_SECTIONS: dict[str, dict[str, Key]] = {"branches": BRANCH_KEYS}
