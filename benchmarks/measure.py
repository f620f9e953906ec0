"""The same measurements for every method: what a shape is, measured against the exact tube.

The sampling and the measures (deviation from the exact tube, |cos| between the isolines,
angle from the curvature directions) are the library's, defined in tubecad.brep.measure,
which also checks every CAD file tubecad writes as read back; nothing here trusts how a
shape was made.

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

from OCP.BRep import BRep_Tool
from OCP.GeomConvert import GeomConvert

from tubecad.brep import properties
from tubecad.brep.measure import net_against_tube, sample_face, tube_faces  # also checks every file tubecad writes
from tubecad.export.registry import export_shape
from tubecad.surface import CurvatureLineTube


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


def poles(face) -> int:
    """Number of B-spline poles of the face's surface (converted if it is not a B-spline)."""
    surface = BRep_Tool.Surface_s(face)
    bspline = GeomConvert.SurfaceToBSplineSurface_s(surface)
    return bspline.NbUPoles() * bspline.NbVPoles()


def measure(
    method: str,
    shape,
    tube: CurvatureLineTube,
    build_s: float,
    samples: int = 60_000,
    workdir: Path | None = None,
    solid: bool = True,
) -> Measured:
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
        method=method,
        build_s=build_s,
        export_s=export_s,
        step_bytes=size,
        faces=len(faces),
        poles=sum(poles(f) for f in faces),
        max_deviation=deviation,
        max_orthogonality=orthogonality,
        max_curvature_angle_deg=angle,
        area_rel_error=abs(area / tube.area_exact - 1.0),
        volume_rel_error=volume_error,
        valid=properties.is_valid(shape),
        samples=len(faces) * nu * nv,
    )
