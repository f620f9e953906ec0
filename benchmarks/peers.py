"""The ways to make the tube that are compared, each returning (shape, is_solid).

- tubecad: the capped tube solid, one face around the tube (exact-section NURBS, default
  tolerance 1e-8; benchmarks/axes.py also fits it to other tolerances);
- build123d ``sweep`` of the circle along the axis interpolated as a spline, with
  ``is_frenet`` on (Frenet trihedron) and off (OCCT's CorrectedFrenet, build123d's default);
- OCCT ``BRepOffsetAPI_MakePipeShell`` with CorrectedFrenet (or DiscreteTrihedron, used by
  benchmarks/axes.py), tightened as far as its API allows (approximation tolerance 1e-9,
  max degree 11, up to 1000 segments);
- OCCT ``GeomAPI_PointsToBSplineSurface`` on the exact grid (a face: the fit is not closed
  in u, so it makes no solid without sewing and caps).

The sweeps' spine is what an engineer would make from the exact axis: a B-spline through
``SPINE_POINTS`` points of it, parameterised by arc length, with their exact unit tangents
(the best-practice input: chord-length parameters are ~10x worse); an axis read from a CAD
edge is swept along that edge itself (benchmarks/axes.py). Its own distance from the exact
axis is measured and reported, so the share of the error from the spine shows. Every
builder takes any :class:`~tubecad.curves.Axis` (the circle starts along r1 at s0).
"""

from __future__ import annotations

from collections.abc import Callable

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell

from tubecad.brep import NetLayout, build_tube_solid
from tubecad.brep.solids import DEFAULT_TOLERANCE
from tubecad.fitting.generic import grid_surface
from tubecad.surface import CurvatureLineTube
from tubecad.surface.checks import distance_to_axis

SPINE_POINTS = 1001


def spine(tube: CurvatureLineTube, points: int = SPINE_POINTS) -> bd.Edge:
    """The axis as a build123d spline through ``points`` exact points with exact tangents,
    parameterised by arc length."""
    s = np.linspace(*tube.span, points)
    a = tube.axis.at(s)
    return bd.Edge.make_spline(
        [bd.Vector(*p) for p in a.position], tangents=[bd.Vector(*t) for t in a.t], parameters=list(s), scale=False
    )


def spine_deviation(tube: CurvatureLineTube, path: bd.Edge | bd.Wire, samples: int = 4000) -> float:
    """Max distance of the spine (an edge or a wire) from the exact axis, at ``samples``
    points evenly spaced in its parameter."""
    from OCP.BRepAdaptor import BRepAdaptor_CompCurve, BRepAdaptor_Curve

    curve = BRepAdaptor_CompCurve(path.wrapped) if isinstance(path, bd.Wire) else BRepAdaptor_Curve(path.wrapped)
    points = [curve.Value(x) for x in np.linspace(curve.FirstParameter(), curve.LastParameter(), samples)]
    return float(distance_to_axis(tube.axis, np.array([(p.X(), p.Y(), p.Z()) for p in points]))[0].max())


def profile(tube: CurvatureLineTube) -> bd.Wire:
    """The circle of radius rho in the normal plane at the start of the axis."""
    a = tube.axis.at(np.array([tube.span[0]]))
    plane = bd.Plane(origin=tuple(a.position[0]), x_dir=tuple(a.r1[0]), z_dir=tuple(a.t[0]))
    return bd.Wire([bd.Edge.make_circle(tube.radius, plane)])


def tubecad_at(tolerance: float) -> Callable:
    """tubecad's capped tube solid fitted to ``tolerance`` (the spine is not used)."""

    def make(tube: CurvatureLineTube, _path: bd.Edge | None):
        return build_tube_solid(tube, NetLayout.equal(tube, 2, 1), tolerance).shape, True

    return make


tubecad_solid = tubecad_at(DEFAULT_TOLERANCE)


def build123d_sweep(is_frenet: bool) -> Callable:
    def make(tube: CurvatureLineTube, path: bd.Edge):
        return bd.sweep(bd.Face(profile(tube)), path, is_frenet=is_frenet).solids()[0], True

    return make


#: MakePipeShell's trihedron modes: how each is set on the builder
PIPE_MODES: dict[str, Callable] = {
    "CorrectedFrenet": lambda builder: builder.SetMode(False),  # IsFrenet = False: GeomFill_IsCorrectedFrenet
    "DiscreteTrihedron": lambda builder: builder.SetDiscreteMode(),  # GeomFill_IsDiscreteTrihedron
}


def occt_pipe_shell(mode: str = "CorrectedFrenet") -> Callable:
    def make(tube: CurvatureLineTube, path: bd.Edge | bd.Wire):
        builder = BRepOffsetAPI_MakePipeShell((path if isinstance(path, bd.Wire) else bd.Wire([path])).wrapped)
        PIPE_MODES[mode](builder)
        builder.SetTolerance(1e-9, 1e-9, 1e-9)
        builder.SetMaxDegree(11)
        builder.SetMaxSegments(1000)
        builder.Add(profile(tube).wrapped, False, False)
        builder.Build()
        builder.MakeSolid()
        return bd.Solid(builder.Shape()), True

    return make


def grid_fit(nu: int, ns: int, tolerance: float) -> Callable:
    def make(tube: CurvatureLineTube, _path: bd.Edge):
        fit = grid_surface(tube, nu, ns, tolerance)
        return bd.Face(BRepBuilderAPI_MakeFace(fit.surface, 1e-6).Face()), False

    return make


#: the sweeps of the circle along a spine (edge or wire): name -> builder(tube, spine)
SWEEPS: dict[str, Callable] = {
    "build123d sweep, is_frenet=True": build123d_sweep(True),
    "build123d sweep, is_frenet=False": build123d_sweep(False),
    "OCCT MakePipeShell CorrectedFrenet, tol 1e-9": occt_pipe_shell("CorrectedFrenet"),
    "OCCT MakePipeShell DiscreteTrihedron, tol 1e-9": occt_pipe_shell("DiscreteTrihedron"),
}

#: name -> builder(tube, spine) -> (shape, is_solid); tubecad first (compare.py: the sweeps
#: but DiscreteTrihedron, which benchmarks/axes.py adds, and the grid fits)
METHODS: dict[str, Callable] = {
    "tubecad": tubecad_solid,
    **{name: make for name, make in SWEEPS.items() if "DiscreteTrihedron" not in name},
    "OCCT PointsToBSplineSurface 33x201, tol 1e-6": grid_fit(33, 201, 1e-6),
    "OCCT PointsToBSplineSurface 65x801, tol 1e-8": grid_fit(65, 801, 1e-8),
}

#: the methods an engineer could use instead of tubecad
PEERS = [name for name in METHODS if name != "tubecad"]
