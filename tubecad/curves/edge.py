"""Axes from CAD edges: a build123d Edge or Wire, a CadQuery Edge or Wire, a TopoDS edge or
wire, or an OCCT Geom curve (docs/MATH.md section 7).

The curve is read through OCCT's adaptor (BRepAdaptor_Curve, or BRepAdaptor_CompCurve for
a wire) and becomes a :class:`~.parametric.ParametricAxis` whose panels start where the
curve is less than C3 (a B-spline's knots, a wire's joints), so every panel is smooth and
the Chebyshev series reproduce the curve to round-off; the tube then follows that curve.
Where the curve is C2 its frame is C1, where it is only C1 (or G1 at a wire's joint) the
frame is C0: these are the axis' joints, where the fit allows the same. A kink (the
tangent turning at a point) is refused: no tube follows it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.curves.parametric import ParametricAxis


def _adaptor(curve: Any):
    """The OCCT adaptor of ``curve`` and a short description of what it was."""
    from OCP.BRepAdaptor import BRepAdaptor_CompCurve, BRepAdaptor_Curve
    from OCP.Geom import Geom_Curve
    from OCP.GeomAdaptor import GeomAdaptor_Curve
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_WIRE
    from OCP.TopoDS import TopoDS_Shape

    from tubecad.occ_compat import as_edge, as_wire

    shape = getattr(curve, "wrapped", curve)  # build123d and CadQuery objects hold the OCCT shape
    if isinstance(shape, TopoDS_Shape) and not shape.IsNull():
        if shape.ShapeType() == TopAbs_EDGE:
            return BRepAdaptor_Curve(as_edge(shape)), "edge"
        if shape.ShapeType() == TopAbs_WIRE:
            return BRepAdaptor_CompCurve(as_wire(shape), False), "wire"
    if isinstance(shape, Geom_Curve):
        return GeomAdaptor_Curve(shape), type(shape).__name__
    raise ParameterError(
        f"edge must be a build123d/CadQuery Edge or Wire, a TopoDS edge or wire, or a Geom curve, "
        f"got {type(curve).__name__}"
    )


def edge_axis(
    curve: Any, *, normal: Sequence[float] | None = None, source: str | None = None, closed: bool | None = None
) -> ParametricAxis:
    """The axis along ``curve`` (see the module docstring), from its first parameter to its
    last. ``closed``: a closed loop (None: detected, e.g. a periodic B-spline or a closed
    wire meeting itself tangentially; True: demanded; False: kept open).

    Args:
        curve: a build123d or CadQuery Edge or Wire, a TopoDS edge or wire, or an OCCT
            ``Geom_Curve``; bounded and tangent-continuous (no kink), in model units.
        normal: the initial r1 at the curve's start, made orthogonal to the tangent; None
            (default): the principal normal (see :class:`~.parametric.ParametricAxis`).
        source: what the curve was, for :meth:`describe` (default the curve's type name).
        closed: None (default) to detect a closed loop, True to demand one, False to keep
            the axis open.

    Returns:
        The :class:`~.parametric.ParametricAxis` along the curve, in arc length from 0 at
        its first parameter.

    Raises:
        ParameterError: an object that is not a curve, an unbounded curve, a kink (the
            tangent turning at a point: use :class:`~.route.RouteAxis` for straight legs and
            bends), or ``closed=True`` on a curve whose ends do not meet tangentially.
    """
    from OCP.GeomAbs import GeomAbs_C1, GeomAbs_C2, GeomAbs_C3
    from OCP.gp import gp_Pnt

    from tubecad.occ_compat import Array1OfReal

    adaptor, kind = _adaptor(curve)
    t0, t1 = adaptor.FirstParameter(), adaptor.LastParameter()
    if not (np.isfinite(t0) and np.isfinite(t1) and t1 > t0):
        raise ParameterError(f"edge: the {kind} must be bounded, got parameters [{t0:g}, {t1:g}]")

    def intervals(order) -> np.ndarray:
        n = adaptor.NbIntervals(order)
        values = Array1OfReal(1, n + 1)
        adaptor.Intervals(values, order)
        return np.array([values.Value(i) for i in range(1, n + 2)])

    breaks = intervals(GeomAbs_C3)
    below_c2, below_c1 = set(intervals(GeomAbs_C2)[1:-1]), set(intervals(GeomAbs_C1)[1:-1])
    for t in below_c1:  # C0 in its parameter: still a tube if the tangent does not turn (G1)
        before, after = _tangent(adaptor, t - 1e-9 * (t1 - t0)), _tangent(adaptor, t + 1e-9 * (t1 - t0))
        if np.linalg.norm(before - after) > 1e-6:
            p = gp_Pnt()
            adaptor.D0(float(t), p)
            angle = np.degrees(np.arccos(np.clip(before @ after, -1.0, 1.0)))
            raise ParameterError(
                f"edge: the {kind} has a kink at ({p.X():.6g}, {p.Y():.6g}, {p.Z():.6g}), its tangent "
                f"turns {angle:.3g} deg there; a tube needs a tangent-continuous axis: for a pipe of "
                f'straight legs and bends give its corner points to RouteAxis (curve = "route" in a '
                f"spec) with a bend_radius"
            )
    joints = [(float(t), 0 if (t in below_c2 or t in below_c1) else 1) for t in breaks[1:-1]]
    point = gp_Pnt()

    def x(t: np.ndarray) -> np.ndarray:
        out = np.empty(t.shape + (3,))
        flat = out.reshape(-1, 3)
        for i, value in enumerate(t.ravel()):
            adaptor.D0(float(value), point)
            flat[i] = point.X(), point.Y(), point.Z()
        return out

    description = {"curve": "edge", "kind": kind, "source": source or type(curve).__name__, "t": [t0, t1]}
    return ParametricAxis(
        x,
        (t0, t1),
        breaks=breaks,
        joints=joints,
        normal=normal,
        description=description,
        name=f"the {kind}",
        closed=closed,
    )


def _tangent(adaptor, t: float) -> np.ndarray:
    from OCP.gp import gp_Pnt, gp_Vec

    p, d = gp_Pnt(), gp_Vec()
    adaptor.D1(float(t), p, d)
    v = np.array([d.X(), d.Y(), d.Z()])
    return v / np.linalg.norm(v)
