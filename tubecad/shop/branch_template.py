"""Cutting templates: the saddle unrolled onto the branch pipe's development, and the
opening on the main tube's.

On the branch tube X_B(u, s) = c(s) + rho e(u, s) the rings and stringers are the curvature
lines, with E = rho^2, F = 0, G = (1 - rho k cos(u - theta))^2 (docs/MATH.md section 2). The
map (u, s) -> (x, y) = (rho u, s - s_0) is the development of the pipe when its axis is
straight (k = 0: G = 1, an isometry) and the template is then exact: wrapped round the pipe
with its bottom edge on the ring s_0 and x = 0 on the stringer u = 0, its saddle line is the
cut. Where the axis is curved the map stretches the stringers by sqrt(G) - 1; the template
reports that largest strain along the saddle (0 on a straight branch), and a branch whose
radius varies (a cone) is refused: its development is a sector, not this strip.

The main tube's opening is the bore's saddle on the main surface, (R u_A, s_A - s_0): a
closed line on the main tube's strip, exact where the main axis is straight. A main tube whose
radius varies (a nozzle on a conical head) has no strip: its opening is developed on the panel
of the main's surface round it instead, :func:`tubecad.shop.hole_development.hole_development`
(exact on a cone), and :func:`hole_template` refuses it naming that function.

The drawing (1:1, the model's unit, :class:`tubecad.core.dxf.Drawing`): the saddle line on
layer ``saddle`` (one polyline: across the girth 0 .. 2 pi rho, or closed round a hole), the strip's outline on
``outline``, and a girth mark with its stringer's name at every stringer on ``girth_marks``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from tubecad.core.atomic import write_text
from tubecad.core.dxf import Drawing
from tubecad.core.errors import ParameterError
from tubecad.junctions.saddle import SaddleCurve
from tubecad.surface.protocol import CurvatureLineSurface

#: the girth marks' length, as a share of the strip's height
MARK_SHARE = 0.05


@dataclass(frozen=True)
class BranchTemplate:
    """The developed saddle: ``points`` (n, 2) = (rho u_B, s_B - s_0) over one girth, the
    strip's ``girth`` 2 pi rho and ``height``, the stringers' marks ``marks`` {name: x} and
    the largest stretch ``strain`` of the development along the saddle (0: exact)."""

    points: np.ndarray
    girth: float
    height: float
    marks: dict[str, float]
    strain: float
    #: more lines on the strip, by layer: a crotch blend's toe (``blend_toe``), (n, 2) each
    lines: dict[str, np.ndarray] = field(default_factory=dict)

    def save_dxf(self, path: str | Path, unit: str = "mm") -> Path:
        """The template at 1:1 as a DXF drawing (layers saddle, outline, girth_marks, and
        one per entry of ``lines``)."""
        drawing = Drawing(unit, {"saddle": 1, "outline": 7, "girth_marks": 3} | dict.fromkeys(self.lines, 6))
        for layer, points in [("saddle", self.points), *self.lines.items()]:
            closed = bool(np.allclose(points[0], points[-1], rtol=0, atol=1e-9 * self.girth))
            drawing.polyline(points[:-1] if closed else points, layer, closed=closed)
        corners = [(0.0, 0.0), (self.girth, 0.0), (self.girth, self.height), (0.0, self.height)]
        drawing.polyline(corners, "outline", closed=True)
        mark = MARK_SHARE * self.height
        for name, x in self.marks.items():
            drawing.line((x, 0.0), (x, mark), "girth_marks")
            drawing.text(name, (x, mark), mark / 2, "girth_marks")
        return drawing.save(path)

    def info(self) -> dict[str, Any]:
        """The index's entry: ``developed`` "strip", its ``girth``, ``height`` and ``strain``."""
        return {"developed": "strip", "girth": self.girth, "height": self.height, "strain": self.strain}


def branch_template(
    branch: CurvatureLineSurface, saddle: SaddleCurve, stringers: int = 8, *, key: str = "branch"
) -> BranchTemplate:
    """The saddle ``saddle`` (on ``branch``) unrolled onto the branch's development, with
    ``stringers`` girth marks (stringer_00 at u = 0, evenly round); the strip runs from the
    branch's first ring to its last. The saddle's u_B runs 0 .. 2 pi: one open line across.
    A branch whose radius varies is refused naming ``{key}.radius`` (``key``: the branch's
    name for the caller, ``branch`` by default)."""
    return _developed(branch, saddle.branch_u, saddle.branch_s, stringers, f"{key}.radius", "a branch")


def hole_template(
    main: CurvatureLineSurface, saddle: SaddleCurve, stringers: int = 8, *, key: str = "main"
) -> BranchTemplate:
    """The opening the branch's bore cuts in the main tube (``saddle`` the bore's saddle on
    ``main``, e.g. ``saddle_inner``), unrolled onto the main tube's development as one closed
    line (R u_A, s_A - s_0), placed on the strip's girth 0 .. 2 pi R; girth marks at the
    main tube's ``stringers``. A main tube whose radius varies is refused naming
    ``{key}.radius`` (``key``: the main tube's name for the caller, ``main`` by default): its
    opening is :func:`tubecad.shop.hole_development.hole_development`'s, on a panel."""
    u = saddle.main_u - 2 * math.pi * np.floor(np.mean(saddle.main_u) / (2 * math.pi))
    return _developed(main, u, saddle.main_s, stringers, f"{key}.radius", "a main tube")


def _developed(
    surface: CurvatureLineSurface, u: np.ndarray, s: np.ndarray, stringers: int, key: str, what: str
) -> BranchTemplate:
    """(rho u, s - s_0) on ``surface``'s strip, with the largest |sqrt(G) - 1| along it."""
    if not surface.constant_radius:
        made = (
            "its opening is developed on a panel by tubecad.shop.hole_development.hole_development"
            if what == "a main tube"
            else "its template is not made yet"
        )
        raise ParameterError(f"{key}: {what} whose radius varies develops to a sector, not a strip; {made}", key=key)
    if not isinstance(stringers, int) or not 1 <= stringers <= 360:
        raise ParameterError(f"stringers must be an integer in 1..360, got {stringers!r:.40}", key="stringers")
    rho = float(surface.radius_law.r(np.array([surface.span[0]]))[0])
    s0, s1 = surface.span
    k1, k2 = surface.axis.normal_development(s)
    strain = float(np.abs(rho * (k1 * np.cos(u) + k2 * np.sin(u))).max())  # |sqrt(G) - 1| = rho k |cos(u - theta)|
    girth = 2 * math.pi * rho
    marks = {f"stringer_{j:02d}": girth * j / stringers for j in range(stringers)}
    return BranchTemplate(np.column_stack([rho * u, s - s0]), girth, s1 - s0, marks, strain)


#: the bevel file's columns: the branch's u in degrees, the template's girth position and
#: height, the dihedral angle between the outer surfaces
BEVEL_COLUMNS = ("u_deg", "girth_position", "height", "dihedral_deg")


def write_bevel_csv(path: str | Path, branch_u: np.ndarray, template: BranchTemplate, dihedral: np.ndarray) -> Path:
    """The bevel's basis round the saddle as CSV, written atomically: a row per saddle point,
    its branch angle ``branch_u`` (radians, written in degrees), its position on the cutting
    ``template`` (girth position, height) and the ``dihedral`` angle (degrees) between the
    outer surfaces there; floats to 15 significant digits."""
    rows = [",".join(BEVEL_COLUMNS)] + [
        f"{math.degrees(u):.15g},{x:.15g},{y:.15g},{a:.15g}"
        for u, (x, y), a in zip(branch_u, template.points, dihedral)
    ]
    return write_text(path, "\n".join(rows) + "\n")
