"""The generic path, for comparison: the exact grid fitted by OCCT's
GeomAPI_PointsToBSplineSurface (polynomial, not periodic, its own parameterisation).

It does not know the surface is a tube: circles are only approximated, and its isolines
need not be lines of curvature. Measured here by true distance (projection of exact
points onto it), since its parameters do not match (u, s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.Geom import Geom_BSplineSurface
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_PointsToBSplineSurface, GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt, gp_Vec

from tubecad.core.errors import TubecadError
from tubecad.fitting.occ_arrays import points_2d
from tubecad.surface import CurvatureLineTube


@dataclass(frozen=True)
class GridFit:
    surface: Geom_BSplineSurface
    nu: int
    ns: int
    tolerance: float

    @property
    def pole_count(self) -> tuple[int, int]:
        return self.surface.NbUPoles(), self.surface.NbVPoles()


def grid_surface(tube: CurvatureLineTube, nu: int = 33, ns: int = 201, tolerance: float = 1e-6) -> GridFit:
    """Approximate S on an nu x ns grid (u closed: the first and last rows coincide)."""
    u = np.linspace(0.0, 2.0 * math.pi, nu)
    s = np.linspace(*tube.span, ns)
    fitter = GeomAPI_PointsToBSplineSurface(points_2d(tube.grid(u, s)), 3, 8, GeomAbs_C2, tolerance)
    if not fitter.IsDone():
        raise TubecadError("GeomAPI_PointsToBSplineSurface failed on the exact grid")
    return GridFit(fitter.Surface(), nu, ns, tolerance)


def measure_by_projection(surface, tube: CurvatureLineTube, nu: int = 24, ns: int = 400) -> tuple[float, float]:
    """(max distance of exact tube points to ``surface``, max |cos| between its isoline
    directions at the projected parameters), on an nu x ns grid off the fit grid."""
    u = (np.arange(nu) + 0.41) * 2.0 * math.pi / nu
    s = np.linspace(*tube.span, ns)
    s[1:-1] += 0.37 * (s[1] - s[0])
    exact = tube.grid(u, s).reshape(-1, 3)
    projector = GeomAPI_ProjectPointOnSurf()
    p, du, ds = gp_Pnt(), gp_Vec(), gp_Vec()
    dist = cos = 0.0
    for x in exact:
        projector.Init(gp_Pnt(*map(float, x)), surface)
        if projector.NbPoints() == 0:
            raise TubecadError("a point of the exact tube could not be projected onto the surface")
        dist = max(dist, projector.LowerDistance())
        a, b = projector.LowerDistanceParameters()
        surface.D1(a, b, p, du, ds)
        cos = max(cos, abs(du.Dot(ds)) / (du.Magnitude() * ds.Magnitude()))
    return dist, cos
