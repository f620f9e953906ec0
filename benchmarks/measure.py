"""The same measurements for every method: what a shape is, measured against the exact tube.

Nothing here trusts how a shape was made. Each non-planar face's own OCCT surface is
sampled on a dense grid inside its UV bounds (off any knot lattice) and, at every sample X:

- deviation: | |X - c(s*)| - rho |, c(s*) the closest point of the exact axis (Newton,
  tubecad.surface.checks.distance_to_axis): the distance from X to the exact tube;
- orthogonality: |cos| of the angle between the isoparametric directions S_u and S_v;
- curvature-direction angle: the principal directions of a tube at X are the circle
  direction t x e and the axis direction t (e = (X - c(s*)) / |X - c(s*)|, t = c'(s*));
  each isoline direction, projected into the tangent plane, is compared with the nearer
  of the two. The max over both isoline families, in degrees: 0 means the isolines are
  lines of curvature.

Plus, per shape: B-spline poles (summed over faces; other surface kinds are converted by
GeomConvert first), the area of the tube faces against 2 pi rho L and the solid's volume
against pi rho^2 L (adaptive integration), validity, and STEP export time and size.
"""

from __future__ import annotations

import math
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepTools import BRepTools
from OCP.GeomAbs import GeomAbs_Plane
from OCP.GeomAdaptor import GeomAdaptor_Surface
from OCP.GeomConvert import GeomConvert
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from tubecad.brep import properties
from tubecad.export.cad import export_shape
from tubecad.surface import CurvatureLineTube
from tubecad.surface.checks import distance_to_axis


@dataclass
class Measured:
    """One method on one tube (see the module docstring for the definitions)."""

    method: str
    build_s: float
    export_s: float
    step_bytes: int
    faces: int
    poles: int
    max_deviation: float
    max_orthogonality: float
    max_curvature_angle_deg: float
    area_rel_error: float
    volume_rel_error: float | None
    valid: bool
    samples: int

    def as_dict(self) -> dict:
        return asdict(self)


def tube_faces(shape):
    """The non-planar faces of ``shape`` (the tube; end caps are planar)."""
    explorer = TopExp_Explorer(properties.topods(shape), TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face_s(explorer.Current())
        if GeomAdaptor_Surface(BRep_Tool.Surface_s(face)).GetType() != GeomAbs_Plane:
            yield face
        explorer.Next()


def poles(face) -> int:
    """Number of B-spline poles of the face's surface (converted if it is not a B-spline)."""
    surface = BRep_Tool.Surface_s(face)
    bspline = GeomConvert.SurfaceToBSplineSurface_s(surface)
    return bspline.NbUPoles() * bspline.NbVPoles()


def sample_face(face, nu: int, nv: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points, d/du and d/dv of the face's surface on an nu x nv grid inside its UV bounds."""
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    us = u0 + (np.arange(nu) + 0.37) * (u1 - u0) / nu
    vs = v0 + (np.arange(nv) + 0.29) * (v1 - v0) / nv
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


def net_against_tube(tube: CurvatureLineTube, points: np.ndarray, d1: np.ndarray, d2: np.ndarray) -> tuple[float, float, float]:
    """(max deviation, max |cos| between d1 and d2, max angle in degrees from the curvature directions)."""
    dist, s_star = distance_to_axis(tube.axis, points)
    axis = tube.axis.evaluate(s_star)
    radial = points - axis.position
    e = radial / np.linalg.norm(radial, axis=1)[:, None]
    circle_dir = np.cross(axis.t, e)

    def angle_from_principal(w: np.ndarray) -> np.ndarray:
        w = w - np.einsum("ij,ij->i", w, e)[:, None] * e
        w = w / np.linalg.norm(w, axis=1)[:, None]
        # atan2(|w x d|, |w . d|): arccos of a cosine near 1 would floor at ~1e-6 deg
        angles = [np.arctan2(np.linalg.norm(np.cross(w, d), axis=1), np.abs(np.einsum("ij,ij->i", w, d)))
                  for d in (axis.t, circle_dir)]  # fmt: skip
        return np.degrees(np.minimum(*angles))

    cos = np.abs(np.einsum("ij,ij->i", d1, d2)) / (np.linalg.norm(d1, axis=1) * np.linalg.norm(d2, axis=1))
    angle = np.maximum(angle_from_principal(d1), angle_from_principal(d2))
    return float(np.abs(dist - tube.radius).max()), float(cos.max()), float(angle.max())


def measure(method: str, shape, tube: CurvatureLineTube, build_s: float, samples: int = 60_000,
            workdir: Path | None = None, solid: bool = True) -> Measured:  # fmt: skip
    """All the measurements of ``shape`` (a solid, or a face/shell if ``solid`` is False)."""
    faces = list(tube_faces(shape))
    per_face = max(samples // len(faces), 64)
    nu = max(int(math.sqrt(per_face / 20)), 4)  # around the tube x along it, about 1 : 20
    nv = max(per_face // nu, 16)
    deviation = orthogonality = angle = 0.0
    for face in faces:
        pts, du, dv = sample_face(face, nu, nv)
        d, o, a = net_against_tube(tube, pts, du, dv)
        deviation, orthogonality, angle = max(deviation, d), max(orthogonality, o), max(angle, a)
    area = properties.faces_area(faces)
    volume_error = abs(properties.volume(shape) / tube.volume_exact - 1.0) if solid else None
    with tempfile.TemporaryDirectory(dir=workdir) as folder:
        target = Path(folder) / f"{method}.step"
        start = time.perf_counter()
        export_shape(shape, target)
        export_s = time.perf_counter() - start
        size = target.stat().st_size
    return Measured(
        method=method, build_s=build_s, export_s=export_s, step_bytes=size, faces=len(faces),
        poles=sum(poles(f) for f in faces), max_deviation=deviation, max_orthogonality=orthogonality,
        max_curvature_angle_deg=angle, area_rel_error=abs(area / tube.area_exact - 1.0),
        volume_rel_error=volume_error, valid=properties.is_valid(shape), samples=len(faces) * nu * nv,
    )  # fmt: skip
