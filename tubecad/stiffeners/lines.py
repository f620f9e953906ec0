"""Curvature lines as CAD edges and as polylines for CNC, FEA and robots (issue 4).

A ring frame (s = const) is the exact circle (Geom_Circle: centre c(s), normal t(s)), as
the wall's ring edges are, within the fit tolerance of the fitted surface's isoline; a
stringer (angle theta = const) is the fitted surface's isoline UIso(u(theta)), an
orthogonal trajectory of the circles, within the fit tolerance of the exact tube. Polylines carry exact values from the tube's own formulas: position
S(theta, s), unit tangent (-sin th r1 + cos th r2 along a ring, t along a stringer,
docs/MATH.md section 3) and the outward unit surface normal.
"""

from __future__ import annotations

import csv
import io
import json
import math
from dataclasses import dataclass
from pathlib import Path

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.Geom import Geom_Circle
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

from tubecad.brep.faces import seam_angles
from tubecad.brep.layout import NetLayout
from tubecad.core.atomic import write_text
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.fitting import TubeSurface


@dataclass(frozen=True)
class CurvatureLine:
    """One ring frame or stringer (or seam) on one tube surface."""

    #: line_ring_03, line_stringer_05, line_seam_00 (inner surface: ..._inner): unlike the stiffeners ring_03, ...
    name: str
    #: "ring" | "stringer" | "seam" (a face edge u = const that is no stringer: :func:`net_lines`)
    kind: str
    index: int
    value: float  # s of a ring, angle in degrees of a stringer or a seam
    surface: TubeSurface

    @property
    def canal(self) -> bool:
        """Whether the line lies on a canal surface (a radius law) rather than a tube."""
        return self.surface.canal

    @property
    def radius(self) -> float:
        """The tube's radius; on a canal surface r(s) + d, at a ring's s or averaged along a stringer."""
        law = self.surface.tube.radius_law
        if not self.canal:
            return law.constant_value  # the tube's radius
        s0, s1 = law.span
        return float(law.r(self.value) if self.kind == "ring" else np.mean(law.r(np.linspace(s0, s1, 257))))

    def edge(self) -> bd.Edge:
        """The line as a build123d Edge: a ring is the exact circle (Geom_Circle, as the
        wall's ring edges), a stringer the fitted surface's isoline."""
        surf = self.surface.surface
        if self.kind == "ring":  # the exact circle (a canal surface's characteristic circle)
            centre, radius, t, x_dir, _ = self.surface.ring(self.value)
            circle = Geom_Circle(
                gp_Ax2(gp_Pnt(*map(float, centre)), gp_Dir(*map(float, t)), gp_Dir(*map(float, x_dir))), radius
            )
            maker = BRepBuilderAPI_MakeEdge(circle)
        else:
            s0, s1 = self.surface.tube.span
            maker = BRepBuilderAPI_MakeEdge(surf.UIso(float(self.surface.u_at(self.value))), s0, s1)
        return bd.Edge(maker.Edge())

    def polyline(self, points: int = 200) -> dict[str, np.ndarray]:
        """Exact positions, unit tangents and unit outward normals at ``points`` samples
        (a ring is sampled over [0, 360) deg from the stringer origin, closing implied)."""
        tube = self.surface.tube
        if self.canal:
            return self._canal_polyline(points)
        if self.kind == "ring":
            theta = math.radians(self.surface.origin_deg) + np.linspace(0.0, 2 * math.pi, points, endpoint=False)
            s = np.full_like(theta, self.value)
            _, r1, r2 = tube.axis.rotation_minimising_frame(s)
            tangent = -np.sin(theta)[:, None] * r1 + np.cos(theta)[:, None] * r2
        else:
            s = np.linspace(tube.span[0], tube.span[1], points)
            theta = np.full_like(s, math.radians(self.value))
            tangent = tube.axis.rotation_minimising_frame(s)[0]  # S_s = (1 - rho kappa_u) t, 1 - rho kappa_u > 0
        return {
            "s": s,
            "theta_deg": np.degrees(theta),
            "position": tube.points(theta, s),
            "tangent": tangent,
            "normal": tube.normal(theta, s),
        }

    def _canal_polyline(self, points: int) -> dict[str, np.ndarray]:
        """:meth:`polyline` on a canal surface: samples uniform in chi0 round a ring (the
        stringers' angle at the span's start; ``theta_deg`` holds it) or in s along a
        stringer, unit tangents X_u or X_s of the exact surface."""
        canal = self.surface.tube
        if self.kind == "ring":
            chi0 = math.radians(self.surface.origin_deg) + np.linspace(0.0, 2 * math.pi, points, endpoint=False)
            s = np.full_like(chi0, self.value)
        else:
            s = np.linspace(canal.span[0], canal.span[1], points)
            chi0 = np.full_like(s, math.radians(self.value))
        d = canal.derivatives(chi0, s)
        tangent = d.S_u if self.kind == "ring" else d.S_s
        return {
            "s": s,
            "theta_deg": np.degrees(chi0),
            "position": d.S,
            "tangent": tangent / np.linalg.norm(tangent, axis=-1, keepdims=True),
            "normal": canal.normal(chi0, s),
        }


def net_lines(surface: TubeSurface, layout: NetLayout, suffix: str = "") -> list[CurvatureLine]:
    """The layout's rings and stringers on ``surface``, named line_ring_00.., line_stringer_00..
    (plus ``suffix``, e.g. ``_inner``), so that no line shares a name with a stiffener; then
    the seams, line_seam_00..: the face edges u = const that are no stringer, where the faces
    are split at the circle's C0 knots (one stringer, or stringers leaving an arc over 330 deg:
    :func:`~tubecad.brep.faces.face_columns`), lines of curvature but not stringers."""
    rings = [CurvatureLine(f"line_ring_{i:02d}{suffix}", "ring", i, s, surface) for i, s in enumerate(layout.s_rings)]
    stringers = [
        CurvatureLine(f"line_stringer_{j:02d}{suffix}", "stringer", j, a, surface)
        for j, a in enumerate(layout.stringers_deg)
    ]
    seams = [
        CurvatureLine(f"line_seam_{k:02d}{suffix}", "seam", k, a, surface)
        for k, a in enumerate(seam_angles(surface, layout.stringers_deg))
    ]
    return rings + stringers + seams


def lines_compound(lines: list[CurvatureLine]) -> bd.Compound:
    """All lines as one build123d Compound of labelled edges (for STEP/IGES curves)."""
    edges = []
    for line in lines:
        edge = line.edge()
        edge.label = line.name
        edges.append(edge)
    return bd.Compound(children=edges)


COLUMNS = [
    "line",
    "kind",
    "index",
    "surface_radius",
    "s",
    "theta_deg",
    "x",
    "y",
    "z",
    "tx",
    "ty",
    "tz",
    "nx",
    "ny",
    "nz",
]


def polylines_csv(lines: list[CurvatureLine], path: str | Path, points: int = 200) -> Path:
    """One row per point: line, kind, index, surface radius, s, theta, position, tangent, normal."""
    return write_text(path, polylines_csv_text(lines, points))


def polylines_csv_text(lines: list[CurvatureLine], points: int = 200) -> str:
    """The text of :func:`polylines_csv`."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(COLUMNS)
    for line in lines:
        p = line.polyline(points)
        for i in range(points):
            writer.writerow(
                [
                    line.name,
                    line.kind,
                    line.index,
                    repr(line.radius),
                    repr(float(p["s"][i])),
                    repr(float(p["theta_deg"][i])),
                    *map(repr, map(float, p["position"][i])),
                    *map(repr, map(float, p["tangent"][i])),
                    *map(repr, map(float, p["normal"][i])),
                ]
            )
    return out.getvalue()


def polylines_json(
    lines: list[CurvatureLine], path: str | Path, points: int = 200, length_unit: str = DEFAULT_LENGTH_UNIT
) -> Path:
    """{"units": length_unit, "lines": [{name, kind, index, surface_radius, closed, s, theta_deg, position,
    tangent, normal}]}; ``length_unit``: the model's unit (tubecad.core.units)."""
    return write_text(path, polylines_json_text(lines, points, length_unit))


def polylines_json_text(lines: list[CurvatureLine], points: int = 200, length_unit: str = DEFAULT_LENGTH_UNIT) -> str:
    """The text of :func:`polylines_json`."""
    data = []
    for line in lines:
        p = line.polyline(points)
        data.append(
            {
                "name": line.name,
                "kind": line.kind,
                "index": line.index,
                "surface_radius": line.radius,
                "closed": line.kind == "ring",
                **{k: v.tolist() for k, v in p.items()},
            }
        )
    return json.dumps({"units": length_unit, "lines": data}) + "\n"
