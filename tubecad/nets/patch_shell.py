"""A net's cells as one shell of curvature-line patches (issue 44, item 3; docs/MATH.md
section 15).

The net's split face (:attr:`~tubecad.nets.net.CurvatureNet.patches`) has a face per cell.
Each cell bounded by exactly two lines of each family (four edges, none on the face's own
boundary) is refitted in curvature-line coordinates (:func:`~tubecad.nets.patches.curvature_patch`:
a grid of traced lines, degree ``degree`` both ways), and its face is put on that surface with
the **same edges** (the net's lines, shared with the neighbouring cells): each edge is given a
pcurve on the new surface (its 3-D curve's points at CHECKS_PER_EDGE parameters projected on the
surface, OCCT's ``GeomAPI_ProjectPointOnSurf``, interpolated in the edge's parameter by a cubic
spline) and a tolerance of twice its largest distance from the surface along that pcurve (at
least OCCT's 1e-7). So the shell stays one shell: no sewing, no new edge.

A cell is kept on the host's own surface (exact, trimmed) where it is not four-sided (the
face's boundary cuts it, an umbilic or an umbilic part lies in it, three lines meet), where the
refit fails, or where it misses ``target`` (distance from the host as a share of the face's
size, angle of the isolines to the principal directions): the report says which and why, so
nothing is silently worse than the host.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepTools import BRepTools_ReShape
from OCP.Geom import Geom_BSplineSurface
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve, GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_REVERSED, TopAbs_VERTEX, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape
from scipy.interpolate import make_interp_spline

from tubecad.brep.properties import area as _area
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.core.tolerance import EDGE_TOLERANCE
from tubecad.fitting.nurbs import occ_curve_2d
from tubecad.nets.net import CurvatureNet
from tubecad.nets.patches import CurvaturePatch, curvature_patch
from tubecad.occ_compat import as_edge, as_face, as_vertex, as_wire

#: the default target: distance from the host (share of the face's size) and angle (radians)
TARGET = (1e-8, 1e-6)
#: points of each edge projected onto the patch for its pcurve
CHECKS_PER_EDGE = 41
#: a patch's face must have its cell's area (on the host) to this share: it covers that cell
AREA_SHARE = 1e-6


@dataclass(frozen=True)
class PatchShell:
    """The net's split face with its four-sided cells on curvature-line patches (module
    docstring): ``shell`` (the same topology as the net's), ``patches`` (cell name ->
    :class:`~tubecad.nets.patches.CurvaturePatch`) and ``kept`` (cell name -> why its face
    stays on the host). A four-sided cell is named by its lines (``k1_02:k1_03/k2_01:k2_02``), any
    other by its place among the split face's faces (``panel_07``, the shop's name)."""

    shell: TopoDS_Shape
    patches: dict[str, CurvaturePatch] = field(default_factory=dict)
    kept: dict[str, str] = field(default_factory=dict)
    #: the largest tolerance given to an edge on a patch (twice its gap, at least 1e-7)
    edge_tolerance: float = 0.0
    #: each refitted cell's place among the split face's faces (1-based, in OCCT's order: the
    #: shop's ``panel_NN``)
    panels: dict[str, int] = field(default_factory=dict)

    def report(self) -> dict[str, Any]:
        """``refitted`` (per cell its patch's figures), ``kept`` (per cell the reason), the
        worst ``distance``, ``angle``, ``F`` and ``M`` over the refitted cells and the edges'
        largest tolerance."""
        figures = {name: patch.report() for name, patch in self.patches.items()}
        worst = {key: max((f[key] for f in figures.values()), default=0.0) for key in ("distance", "angle", "F", "M")}
        return {"refitted": figures, "kept": dict(self.kept), **worst, "edge_tolerance": self.edge_tolerance}


def patch_shell(
    net: CurvatureNet,
    *,
    samples: int | None = None,
    degree: int = 5,
    target: tuple[float, float] = TARGET,
) -> PatchShell:
    """The net's shell with each four-sided cell on its curvature-line patch (module docstring).

    Args:
        net: the net.
        samples: lines a family in each cell's grid (its own two included), degree + 1 .. 200;
            None: the first of 9, 17 and 33 whose patch meets ``target``
            (:data:`~tubecad.nets.patches.GRIDS`).
        degree: the patches' degree both ways (3, 5 or 7).
        target: (distance as a share of the face's size, angle in radians) a patch must meet
            to replace the host's face.

    Returns:
        The shell, its patches and the cells kept on the host.

    Raises:
        ParameterError: (``samples``, ``degree``, ``target``) out of range.
        TubecadError: the shell is not valid after the faces are replaced.
    """
    if degree not in (3, 5, 7):
        raise ParameterError(f"degree must be 3, 5 or 7, got {degree!r:.20}", key="degree")
    if samples is not None and (
        isinstance(samples, bool) or not isinstance(samples, int) or not degree + 1 <= samples <= 200
    ):
        raise ParameterError(f"samples must be an integer in {degree + 1}..200, got {samples!r:.20}", key="samples")
    if not all(isinstance(t, float | int) and t > 0 for t in target) or len(target) != 2:
        raise ParameterError(f"target must be two positive numbers, got {target!r:.60}", key="target")
    names = _LineNames(net)
    size = net.host.size
    patches: dict[str, CurvaturePatch] = {}
    kept: dict[str, str] = {}
    panels: dict[str, int] = {}
    reshape = BRepTools_ReShape()
    worst_tolerance = 0.0
    faces = TopExp_Explorer(net.patches, TopAbs_FACE)
    index = 0
    while faces.More():
        face = as_face(faces.Current())
        faces.Next()
        index += 1
        lines = _lines_round(face, names)
        if lines is None:
            kept[f"panel_{index:02d}"] = "not four-sided: the face's boundary, an umbilic or three lines bound it"
            continue
        k1, k2 = lines
        name = f"{k1[0]}:{k1[1]}/{k2[0]}:{k2[1]}"
        try:
            patch = curvature_patch(
                net,
                k1,
                k2,
                None if samples is None else (samples, samples),
                target=target,
                degree=degree,
                near=_corner(face, net, k1, k2),
                bounded=False,
            )
        except TubecadError as exc:
            kept[name] = f"not refitted: {exc}"
            continue
        if patch.distance > target[0] * size or patch.angle > target[1]:
            kept[name] = (
                f"misses the target: distance {patch.distance:.2g} ({patch.distance / size:.2g} of the face), "
                f"angle {patch.angle:.2g} rad"
            )
            continue
        replaced = _on_patch(face, patch)
        if replaced is None:
            kept[name] = "its edges could not be put on the patch as a valid face"
            continue
        new_face, tolerance = replaced
        area, host_area = _area(new_face), _area(face)
        if not abs(area - host_area) <= AREA_SHARE * host_area:
            kept[name] = f"the patch does not cover the cell (area {area:.6g}, the host's {host_area:.6g})"
            continue
        worst_tolerance = max(worst_tolerance, tolerance)
        reshape.Replace(face, new_face)
        patches[name] = patch
        panels[name] = index
    shell = reshape.Apply(net.patches)
    if not BRepCheck_Analyzer(shell).IsValid():
        raise TubecadError("the net's shell is not valid with its cells on their curvature-line patches")
    return PatchShell(shell, patches, kept, worst_tolerance, panels)


class _LineNames:
    """The net's line an edge of the split face lies on: by its 3-D curve (the splitter keeps
    each piece on its line's curve), or for the lines along the face's own edges (its seam,
    on_face_edges) by the edge's middle point lying on the line (to 10 x EDGE_TOLERANCE)."""

    def __init__(self, net: CurvatureNet) -> None:
        self.by_curve = {id(edge.curve): name for name, edge in net.edges.items()}
        self.along = {name: net.edges[name].curve for name in net.on_face_edges}

    def get(self, edge: Any) -> str | None:
        curve = BRep_Tool.Curve_s(edge, TopLoc_Location(), 0.0, 0.0)
        if curve is None:
            return None
        name = self.by_curve.get(id(curve))
        if name is not None or not self.along:
            return name
        first, last = BRep_Tool.Range_s(edge)
        middle = curve.Value(0.5 * (first + last))
        for name, line in self.along.items():
            projector = GeomAPI_ProjectPointOnCurve(middle, line)
            if projector.NbPoints() and projector.LowerDistance() < 10 * EDGE_TOLERANCE:
                return name
        return None


def _lines_round(face: TopoDS_Face, names: _LineNames) -> tuple[tuple[str, str], tuple[str, str]] | None:
    """The two lines of each family bounding ``face`` (sorted by name), or None: an edge not on
    a line (the face's boundary), a line bounding it twice, or other than two a family."""
    wires = TopExp_Explorer(face, TopAbs_WIRE)
    count = 0
    found: list[str] = []
    while wires.More():
        count += 1
        edges = TopExp_Explorer(as_wire(wires.Current()), TopAbs_EDGE)
        while edges.More():
            name = names.get(as_edge(edges.Current()))
            edges.Next()
            if name is None:
                return None
            found.append(name)
        wires.Next()
    if count != 1 or len(found) != 4 or len(set(found)) != 4:
        return None
    k1 = sorted(n for n in found if n.startswith("k1_"))
    k2 = sorted(n for n in found if n.startswith("k2_"))
    if len(k1) != 2 or len(k2) != 2:
        return None
    return (k1[0], k1[1]), (k2[0], k2[1])


def _corner(face: TopoDS_Face, net: CurvatureNet, k1: tuple[str, str], k2: tuple[str, str]) -> tuple[float, float]:
    """The host parameters of the face's corner on the lines k1[0] and k2[0] (the patch's
    C00 where those lines cross more than once): the face's vertex nearest both."""
    a, b = net.lines[k1[0]].points, net.lines[k2[0]].points
    best, at = np.inf, np.zeros(3)
    vertices = TopExp_Explorer(face, TopAbs_VERTEX)
    while vertices.More():
        point = np.array(BRep_Tool.Pnt_s(as_vertex(vertices.Current())).Coord())
        vertices.Next()
        score = np.linalg.norm(a - point, axis=1).min() + np.linalg.norm(b - point, axis=1).min()
        if score < best:
            best, at = score, point
    projector = GeomAPI_ProjectPointOnSurf(gp_Pnt(*(float(c) for c in at)), net.host.surface)
    u, v = projector.LowerDistanceParameters()
    return float(u), float(v)


def _on_patch(face: TopoDS_Face, patch: CurvaturePatch) -> tuple[TopoDS_Face, float] | None:
    """``face``'s wire on the patch's surface (each edge given a pcurve on it), the face
    oriented so its normal is the host face's (the patch's normal may be the host's opposite)
    and its wire run round it either way (the one OCCT's check takes: the patch's parameters
    may run the other way round the cell); with the largest tolerance given to an edge. None
    where neither way gives a valid face."""
    surface = patch.surface
    wire = as_wire(TopExp_Explorer(face, TopAbs_WIRE).Current())
    builder = BRep_Builder()
    worst = 0.0
    curves = []
    edges = TopExp_Explorer(wire, TopAbs_EDGE)
    while edges.More():
        edge = as_edge(edges.Current())
        edges.Next()
        pcurve, gap = _pcurve(edge, surface)
        curves.append((edge, occ_curve_2d(pcurve), max(EDGE_TOLERANCE, 2.0 * gap, BRep_Tool.Tolerance_s(edge))))
    reversed_on_host = face.Orientation() == TopAbs_REVERSED
    flip = reversed_on_host == patch.same_sense  # the face's sense on the patch
    for loop in (wire, as_wire(wire.Reversed())):
        new_face = TopoDS_Face()
        builder.MakeFace(new_face, surface, TopLoc_Location(), EDGE_TOLERANCE)
        builder.Add(new_face, loop)
        for edge, pcurve, tolerance in curves:
            builder.UpdateEdge(edge, pcurve, new_face, tolerance)
            worst = max(worst, tolerance)
        candidate = as_face(new_face.Reversed()) if flip else new_face
        if BRepCheck_Analyzer(candidate).IsValid():
            return candidate, worst
    return None


def _pcurve(edge: Any, surface: Geom_BSplineSurface) -> tuple[Any, float]:
    """The edge's pcurve on ``surface`` (scipy's cubic interpolant of its points' projections
    against the edge's parameter) and the largest distance between the edge's curve and the
    surface along it (measured at the points and half-way between)."""
    curve = BRep_Tool.Curve_s(edge, TopLoc_Location(), 0.0, 0.0)
    first, last = BRep_Tool.Range_s(edge)
    t = np.linspace(first, last, CHECKS_PER_EDGE)
    uv = np.empty((len(t), 2))
    projector = GeomAPI_ProjectPointOnSurf()
    u0, u1, v0, v1 = surface.Bounds()
    for i, x in enumerate(t.tolist()):
        projector.Init(curve.Value(x), surface)
        if not projector.NbPoints():
            raise TubecadError("an edge of a cell could not be projected onto its curvature-line patch")
        uv[i] = projector.LowerDistanceParameters()
    uv[:, 0], uv[:, 1] = np.clip(uv[:, 0], u0, u1), np.clip(uv[:, 1], v0, v1)
    spline = make_interp_spline(t, uv, k=3)
    at = np.linspace(first, last, 2 * CHECKS_PER_EDGE - 1)
    on = spline(at)
    gap = max(curve.Value(float(x)).Distance(surface.Value(float(p), float(q))) for x, (p, q) in zip(at, on.tolist()))
    return spline, gap
