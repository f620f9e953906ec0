"""Measure a B-rep shape, as it is (built, or read back from a file), against the exact tube.

Nothing here trusts how the shape was made. Each non-planar face's own OCCT surface is
sampled on a grid inside its UV bounds (off any knot lattice) and, at every sample X:

- deviation: | |X - c(s*)| - rho |, c(s*) the closest point of the exact axis (Newton,
  tubecad.surface.checks.distance_to_axis): the distance from X to the exact tube;
- orthogonality: |cos| of the angle between the isoparametric directions S_u and S_v;
- curvature-direction angle: the principal directions of a tube at X are the circle
  direction t x e and the axis direction t (e = (X - c(s*)) / |X - c(s*)|, t = c'(s*));
  each isoline direction, projected into the tangent plane, is compared with the nearer
  of the two: 0 means the isolines are lines of curvature.

Used by the read-back check of every CAD file tubecad writes (tubecad.export.readback)
and by the benchmarks (benchmarks/measure.py).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_BSplineSurface
from OCP.GeomAbs import GeomAbs_Cone, GeomAbs_Plane
from OCP.GeomAdaptor import GeomAdaptor_Surface
from OCP.GeomLib import GeomLib_IsPlanarSurface
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS_Face

from tubecad.brep.properties import topods
from tubecad.curves.axis import Axis
from tubecad.fitting.nurbs import SurfaceArrays
from tubecad.occ_compat import as_face
from tubecad.surface import CurvatureLineTube
from tubecad.surface.checks import distance_to_axis


def tube_faces(shape: object) -> Iterator[TopoDS_Face]:
    """The faces of ``shape`` on its tubes: not its end caps, which are planar (a file may
    hold a plane as a B-spline, which is recognised as planar too), or conical between the
    end circles of a canal surface's wall."""
    explorer = TopExp_Explorer(topods(shape), TopAbs_FACE)
    while explorer.More():
        face = as_face(explorer.Current())
        surface = BRep_Tool.Surface_s(face)
        kind = GeomAdaptor_Surface(surface).GetType()
        if kind not in (GeomAbs_Plane, GeomAbs_Cone) and not GeomLib_IsPlanarSurface(surface, 1e-7).IsPlanar():
            yield face
        explorer.Next()


def sample_face(face: TopoDS_Face, nu: int, nv: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points, d/du and d/dv of the face's own surface on an nu x nv grid inside its UV bounds
    (offsets 0.37 and 0.29 of a cell, so no sample sits on a knot or an edge)."""
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    us = u0 + (np.arange(nu) + 0.37) * (u1 - u0) / nu
    vs = v0 + (np.arange(nv) + 0.29) * (v1 - v0) / nv
    if isinstance(surface, Geom_BSplineSurface):  # what tubecad writes and reads back: on the grid at once
        return tuple(a.reshape(-1, 3) for a in SurfaceArrays.from_occ(surface).grid_d1(us, vs))  # type: ignore[return-value]
    out = np.empty((3, nu * nv, 3))
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    k = 0
    for u in us:
        for v in vs:
            surface.D1(u, v, p, du, dv)
            out[0, k] = p.X(), p.Y(), p.Z()
            out[1, k] = du.X(), du.Y(), du.Z()
            out[2, k] = dv.X(), dv.Y(), dv.Z()
            k += 1
    return out[0], out[1], out[2]


def face_orthogonality(face: TopoDS_Face, per_span: int = 4) -> float:
    """The largest |cos| between the face's isoparametric directions d/du and d/dv, sampled
    on every knot span of its B-spline surface inside its UV bounds, the bounds (its edges)
    and corners included (:func:`~tubecad.fitting.nurbs.span_grid`): where a file's rounded
    poles and a fit's error peak. Another kind of surface: :func:`sample_face`'s grid.

    Args:
        face: a face of a read-back or built shape.
        per_span: samples per knot span, both ways.

    Returns:
        max |cos| over the samples.
    """
    from tubecad.fitting.nurbs import span_grid

    face = as_face(face)
    surface = BRep_Tool.Surface_s(face)
    if not isinstance(surface, Geom_BSplineSurface):
        _, du, dv = sample_face(face, 8, 8)
        return float(orthogonality(du, dv).max())
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    arrays = SurfaceArrays.from_occ(surface)
    _, du, dv = arrays.grid_d1(span_grid(arrays.u_knots, u0, u1, per_span), span_grid(arrays.v_knots, v0, v1, per_span))
    return float(orthogonality(du.reshape(-1, 3), dv.reshape(-1, 3)).max())


def orthogonality(d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
    """|cos| of the angle between each pair of rows of ``d1`` and ``d2``."""
    return np.abs(np.einsum("ij,ij->i", d1, d2)) / (np.linalg.norm(d1, axis=1) * np.linalg.norm(d2, axis=1))


def net_against_tube(
    tube: CurvatureLineTube, points: np.ndarray, d1: np.ndarray, d2: np.ndarray
) -> tuple[float, float, float]:
    """(max deviation, max |cos| between d1 and d2, max angle in degrees from the curvature
    directions) of the samples against ``tube`` (a CurvatureLineTube)."""
    dist, s_star = distance_to_axis(tube.axis, points)
    axis = tube.axis.at(s_star)
    radial = points - axis.position
    e = radial / np.linalg.norm(radial, axis=1)[:, None]
    circle_dir = np.cross(axis.t, e)

    def angle_from_principal(w: np.ndarray) -> np.ndarray:
        w = w - np.einsum("ij,ij->i", w, e)[:, None] * e
        w = w / np.linalg.norm(w, axis=1)[:, None]
        # atan2(|w x d|, |w . d|): arccos of a cosine near 1 would floor at ~1e-6 deg
        angles = [
            np.arctan2(np.linalg.norm(np.cross(w, d), axis=1), np.abs(np.einsum("ij,ij->i", w, d)))
            for d in (axis.t, circle_dir)
        ]
        return np.degrees(np.minimum(*angles))

    angle = np.maximum(angle_from_principal(d1), angle_from_principal(d2))
    return float(np.abs(dist - tube.radius).max()), float(orthogonality(d1, d2).max()), float(angle.max())


@dataclass(frozen=True)
class TubeFacesMeasure:
    """The tube faces of a shape against the exact tubes of the radii they lie on."""

    max_deviation: float  # from the exact tube of the face's radius
    max_orthogonality: float  # |cos| between the face's isoparametric directions
    faces: int  # tube faces measured
    samples: int
    skipped: int  # non-planar faces on none of the radii (not measured)
    per_radius: dict[float, tuple[int, float, float]]  # radius -> (faces, max deviation, max |cos|)


def surface_levels(build) -> tuple[Callable, list[float]]:
    """How a build's faces are measured: (level(points, s_guess=None, iters=12) -> (values,
    s*), the level of each of its surfaces). For tubes the level is the distance from the
    axis and the surfaces' levels their radii; for a canal surface's build it is the
    distance outside the first surface's sphere envelope (:func:`envelope_distance`) and the
    levels are each surface's offset from it (0 and -thickness for a wall)."""
    from tubecad.surface.checks import envelope_distance

    first = build.surfaces[0].tube
    if first.constant_radius:
        return (lambda p, g=None, iters=12: distance_to_axis(first.axis, p, g, iters)), list(build.radii)
    base = first.radius_law.offset
    levels = [ts.tube.radius_law.offset - base for ts in build.surfaces]
    return (lambda p, g=None, iters=12: envelope_distance(first, p, g, iters)), levels


def measure_tube_faces(
    shape: object,
    axis: Axis,
    radii: Sequence[float],
    samples: int = 3000,
    every_face: bool = True,
    level: Callable | None = None,
    size: float | None = None,
) -> TubeFacesMeasure:
    """Sample every tube face of ``shape`` (about ``samples`` points in all, at least one per
    face) and measure it against the exact tube of the radius in ``radii`` it lies on
    (``level``: measured otherwise, e.g. a canal surface's, with ``radii`` its levels: see
    :func:`surface_levels`).

    With ``every_face`` (a wall or tube solid) each non-planar face is measured against the
    nearest radius. Otherwise (an assembly) a face is measured only if its median distance
    from ``axis`` is within 1e-3 r of a radius r (1e-3 ``size`` for levels that are offsets,
    a canal surface's), and within a quarter of the gap to the next one; other faces (a
    stiffener's web or flange) are counted as ``skipped``.
    """
    radii = sorted(float(r) for r in radii)
    gaps = [b - a for a, b in zip(radii[:-1], radii[1:])]
    faces = list(tube_faces(shape))
    if not faces:
        return TubeFacesMeasure(0.0, 0.0, 0, 0, 0, {})
    per_face = samples // len(faces)
    if per_face >= 4:
        nu = max(int(math.sqrt(per_face / 4)), 2)  # around the tube x along it, about 1 : 4
        nv = max(per_face // nu, 2)
    else:  # many faces: still every face, with one or two samples each
        nu, nv = 1, max(per_face, 1)
    grids = [sample_face(face, nu, nv) for face in faces]
    points = np.concatenate([g[0] for g in grids])
    dist, _ = distance_to_axis(axis, points) if level is None else level(points)
    dist = dist.reshape(len(faces), nu * nv)
    cos = [face_orthogonality(face) for face in faces]  # edges, corners and every knot span
    per_radius: dict[float, list] = {}
    measured = 0
    for i in range(len(faces)):
        median = float(np.median(dist[i]))
        k = int(np.argmin([abs(median - r) for r in radii]))
        r = radii[k]
        near = [g for g in (gaps[k - 1] if k > 0 else None, gaps[k] if k < len(gaps) else None) if g is not None]
        if not every_face and abs(median - r) > min([1e-3 * (r if size is None else size)] + [0.25 * g for g in near]):
            continue
        measured += 1
        entry = per_radius.setdefault(r, [0, 0.0, 0.0])
        entry[0] += 1
        entry[1] = max(entry[1], float(np.abs(dist[i] - r).max()))
        entry[2] = max(entry[2], cos[i])
    return TubeFacesMeasure(
        max_deviation=max((e[1] for e in per_radius.values()), default=0.0),
        max_orthogonality=max((e[2] for e in per_radius.values()), default=0.0),
        faces=measured,
        samples=measured * nu * nv,
        skipped=len(faces) - measured,
        per_radius={r: tuple(e) for r, e in per_radius.items()},
    )
