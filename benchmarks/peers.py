"""The ways to make the tube that are compared, each returning (shape, is_solid).

- tubecad: the capped tube solid, one face around the tube (exact-section NURBS, default
  tolerance 1e-8);
- build123d ``sweep`` of the circle along the axis interpolated as a spline, with
  ``is_frenet`` on (Frenet trihedron) and off (OCCT's CorrectedFrenet, build123d's default);
- OCCT ``BRepOffsetAPI_MakePipeShell`` with CorrectedFrenet, tightened as far as its API
  allows (approximation tolerance 1e-9, max degree 11, up to 1000 segments);
- OCCT ``GeomAPI_PointsToBSplineSurface`` on the exact grid (a face: the fit is not closed
  in u, so it makes no solid without sewing and caps).

The sweeps' spine is what an engineer would make from the exact axis: a B-spline through
``SPINE_POINTS`` points of it, parameterised by arc length, with their exact unit tangents
(the best-practice input: chord-length parameters are ~10x worse). Its own distance from
the exact axis is measured and reported, so the share of the error from the spine shows.
"""

from __future__ import annotations


from typing import Callable

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell

from tubecad.brep import NetLayout, build_tube_solid
from tubecad.fitting.generic import grid_surface
from tubecad.surface import CurvatureLineTube
from tubecad.surface.checks import distance_to_axis

SPINE_POINTS = 1001


def spine(tube: CurvatureLineTube, points: int = SPINE_POINTS) -> bd.Edge:
    """The axis as a build123d spline through ``points`` exact points with exact tangents,
    parameterised by arc length."""
    s = np.linspace(*tube.span, points)
    a = tube.axis.evaluate(s)
    return bd.Edge.make_spline([bd.Vector(*p) for p in a.position], tangents=[bd.Vector(*t) for t in a.t],
                               parameters=list(s), scale=False)  # fmt: skip


def spine_deviation(tube: CurvatureLineTube, edge: bd.Edge, samples: int = 4000) -> float:
    """Max distance of the spine from the exact axis."""
    pts = np.array([tuple(edge.position_at(x)) for x in np.linspace(0.0, 1.0, samples)])
    return float(distance_to_axis(tube.axis, pts)[0].max())


def profile(tube: CurvatureLineTube) -> bd.Wire:
    """The circle of radius rho in the normal plane at the start of the axis."""
    a = tube.axis.evaluate(np.array([tube.span[0]]))
    plane = bd.Plane(origin=tuple(a.position[0]), x_dir=tuple(a.n[0]), z_dir=tuple(a.t[0]))
    return bd.Wire([bd.Edge.make_circle(tube.radius, plane)])


def tubecad_solid(tube: CurvatureLineTube, path: bd.Edge):
    return build_tube_solid(tube, NetLayout.equal(tube, 2, 1)).shape, True


def build123d_sweep(is_frenet: bool) -> Callable:
    def make(tube: CurvatureLineTube, path: bd.Edge):
        return bd.sweep(bd.Face(profile(tube)), path, is_frenet=is_frenet).solids()[0], True

    return make


def occt_pipe_shell(tube: CurvatureLineTube, path: bd.Edge):
    builder = BRepOffsetAPI_MakePipeShell(bd.Wire([path]).wrapped)
    builder.SetMode(False)  # IsFrenet = False: GeomFill_IsCorrectedFrenet
    builder.SetTolerance(1e-9, 1e-9, 1e-9)
    builder.SetMaxDegree(11)
    builder.SetMaxSegments(1000)
    builder.Add(profile(tube).wrapped, False, False)
    builder.Build()
    builder.MakeSolid()
    return bd.Solid(builder.Shape()), True


def grid_fit(nu: int, ns: int, tolerance: float) -> Callable:
    def make(tube: CurvatureLineTube, path: bd.Edge):
        fit = grid_surface(tube, nu, ns, tolerance)
        return bd.Face(BRepBuilderAPI_MakeFace(fit.surface, 1e-6).Face()), False

    return make


#: name -> builder(tube, spine) -> (shape, is_solid); tubecad first
METHODS: dict[str, Callable] = {
    "tubecad": tubecad_solid,
    "build123d sweep, is_frenet=True": build123d_sweep(True),
    "build123d sweep, is_frenet=False": build123d_sweep(False),
    "OCCT MakePipeShell CorrectedFrenet, tol 1e-9": occt_pipe_shell,
    "OCCT PointsToBSplineSurface 33x201, tol 1e-6": grid_fit(33, 201, 1e-6),
    "OCCT PointsToBSplineSurface 65x801, tol 1e-8": grid_fit(65, 801, 1e-8),
}

#: the methods an engineer could use instead of tubecad
PEERS = [name for name in METHODS if name != "tubecad"]

