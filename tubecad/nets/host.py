"""The surface of a host face: any OCCT surface (B-spline, NURBS, analytic) evaluated with its
first and second derivatives, vectorised over points (issue 44).

A user's face (a build123d ``Face``, a face of a STEP file, a ``Geom_Surface``) is read as its
underlying surface and its parameter bounds: for a trimmed face the bounds of its parameter box
(``BRepTools::UVBounds``). OCCT evaluates the surface exactly (``Geom_Surface::D2``: the
position X and X_u, X_v, X_uu, X_uv, X_vv; about 1 us a point), so every quantity downstream is
the surface's own, not a mesh's. A periodic direction (a surface of revolution's u, a NURBS
sphere's) is reported with its period: the umbilic search and the tracer wrap round it, so
nothing stops at the seam.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_Surface
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape

from tubecad.core.errors import ParameterError
from tubecad.occ_compat import as_face

FloatArray = np.ndarray


@dataclass(frozen=True)
class SurfaceJet:
    """Per point: the position ``X`` and the derivatives ``Xu``, ``Xv``, ``Xuu``, ``Xuv``,
    ``Xvv``, each (n, 3)."""

    X: FloatArray
    Xu: FloatArray
    Xv: FloatArray
    Xuu: FloatArray
    Xuv: FloatArray
    Xvv: FloatArray


@dataclass(frozen=True)
class HostSurface:
    """An OCCT ``surface`` over the parameter box ``bounds`` = (u0, u1, v0, v1), with the
    periods of its periodic directions (``periods``: (u period or None, v period or None))."""

    surface: Geom_Surface
    bounds: tuple[float, float, float, float]
    periods: tuple[float | None, float | None]
    #: the interior parameters (u's, v's) where the surface is less than C3 (a B-spline's
    #: knots of high multiplicity): its second derivatives, and the principal field's
    #: parameter directions, may jump there, so a line is traced in pieces between them
    breaks: tuple[FloatArray, FloatArray] = (np.zeros(0), np.zeros(0))
    #: the trimmed face the surface came from (its own boundary bounds the lines), or None
    face: TopoDS_Face | None = None

    @classmethod
    def of_face(cls, face: object) -> HostSurface:
        """The host surface of a face: a build123d ``Face`` (or anything with ``.wrapped``)
        or an OCCT ``TopoDS_Face``, over its parameter box.

        Args:
            face: the face.

        Returns:
            Its surface and bounds.

        Raises:
            ParameterError: (``face``) not a face.
        """
        shape = getattr(face, "wrapped", face)
        if isinstance(shape, TopoDS_Shape) and not shape.IsNull() and shape.ShapeType() == TopAbs_FACE:
            shape = as_face(shape)  # a face found by an explorer, a file's face
        if not isinstance(shape, TopoDS_Face):
            raise ParameterError(
                f"face must be a build123d Face or a TopoDS_Face, got {type(face).__name__}", key="face"
            )
        surface = BRep_Tool.Surface_s(shape)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(shape)
        from dataclasses import replace

        return replace(cls.of_surface(surface, (u0, u1, v0, v1)), face=shape)

    @classmethod
    def of_surface(cls, surface: Geom_Surface, bounds: tuple[float, float, float, float] | None = None) -> HostSurface:
        """A ``Geom_Surface`` over ``bounds`` (default: its own, which must be finite).

        Args:
            surface: the surface.
            bounds: (u0, u1, v0, v1), or None.

        Returns:
            The host surface.

        Raises:
            ParameterError: (``bounds``) bounds not finite with u0 < u1 and v0 < v1.
        """
        box = tuple(float(b) for b in (bounds if bounds is not None else surface.Bounds()))
        u0, u1, v0, v1 = box
        if not (all(math.isfinite(b) for b in box) and u0 < u1 and v0 < v1):
            raise ParameterError(f"bounds must be finite with u0 < u1 and v0 < v1, got {box}", key="bounds")
        periods = (
            surface.UPeriod() if surface.IsUPeriodic() else None,
            surface.VPeriod() if surface.IsVPeriodic() else None,
        )
        return cls(surface, (u0, u1, v0, v1), periods, _breaks(surface))

    @property
    def closed(self) -> tuple[bool, bool]:
        """Whether the box spans a whole period in u and in v (the seam is then inside the face)."""
        u0, u1, v0, v1 = self.bounds
        pu, pv = self.periods
        return (pu is not None and u1 - u0 >= pu * (1 - 1e-12), pv is not None and v1 - v0 >= pv * (1 - 1e-12))

    def wrapped(self, u: FloatArray, v: FloatArray) -> tuple[FloatArray, FloatArray]:
        """(u, v) brought into the box along a closed direction (a whole period), unchanged otherwise."""
        u0, _, v0, _ = self.bounds
        (cu, cv), (pu, pv) = self.closed, self.periods
        u = np.asarray(u, dtype=float)
        v = np.asarray(v, dtype=float)
        if cu and pu is not None:
            u = u0 + np.mod(u - u0, pu)
        if cv and pv is not None:
            v = v0 + np.mod(v - v0, pv)
        return u, v

    def wrapped_point(self, u: float, v: float) -> tuple[float, float]:
        """:meth:`wrapped` for one point in Python floats (the tracer's inner loop)."""
        (cu, cv), (pu, pv) = self._closed_periods
        if cu:
            u = self.bounds[0] + (u - self.bounds[0]) % pu
        if cv:
            v = self.bounds[2] + (v - self.bounds[2]) % pv
        return u, v

    @cached_property
    def _closed_periods(self) -> tuple[tuple[bool, bool], tuple[float, float]]:
        """(whether closed, the period or 1.0) in u and in v, computed once."""
        (cu, cv), (pu, pv) = self.closed, self.periods
        return (cu and pu is not None, cv and pv is not None), (pu or 1.0, pv or 1.0)

    def inside(self, u: FloatArray, v: FloatArray) -> FloatArray:
        """Whether the points lie on the face: in its trimmed domain where it came from a face
        (OCCT's ``IntTools_FClass2d``: in, or on its boundary), else in the box (a
        closed direction always is)."""
        u0, u1, v0, v1 = self.bounds
        cu, cv = self.closed
        u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
        boxed = (cu | ((u >= u0) & (u <= u1))) & (cv | ((v >= v0) & (v <= v1)))
        if self.face is None or self._whole_box:
            return boxed
        wu, wv = self.wrapped(u, v)
        return boxed & self._classifier(wu, wv).reshape(np.shape(wu))

    @cached_property
    def size(self) -> float:
        """The face's size: the largest extent of the points of a 9 x 9 grid over its
        parameter box (what the nets' relative tolerances are shares of)."""
        u0, u1, v0, v1 = self.bounds
        uu, vv = np.meshgrid(np.linspace(u0, u1, 9), np.linspace(v0, v1, 9), indexing="ij")
        return float(np.ptp(self.points(uu, vv), axis=0).max())

    @cached_property
    def _whole_box(self) -> bool:
        """Whether the face is its surface's whole parameter box (a B-spline patch as a STEP
        file gives it): its area the box's to 1e-12 (the same integration: 0 on the samples),
        so the box alone classifies its points."""
        from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace

        from tubecad.brep.properties import area

        u0, u1, v0, v1 = self.bounds
        box = BRepBuilderAPI_MakeFace(self.surface, u0, u1, v0, v1, 1e-7).Face()
        whole = area(box)
        return whole > 0.0 and abs(area(self.face) - whole) <= 1e-12 * whole

    @cached_property
    def _classifier(self) -> Callable[[FloatArray, FloatArray], FloatArray]:
        """The face's 2-D classifier, made once (:func:`face_classifier`)."""
        assert self.face is not None  # inside() asks only where the host came from a face
        return face_classifier(self.face)

    def points(self, u: FloatArray, v: FloatArray) -> FloatArray:
        """The positions at the points (u, v) (broadcast; (n, 3)), by OCCT's ``Value``: the
        jet's ``X`` without its derivatives.

        Args:
            u: the first parameters.
            v: the second parameters.

        Returns:
            The points, (n, 3).
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        value = self.surface.Value
        return np.array(
            [value(a, b).Coord() for a, b in zip(u.ravel().tolist(), v.ravel().tolist())], dtype=float
        ).reshape(-1, 3)

    def jet(self, u: FloatArray, v: FloatArray) -> SurfaceJet:
        """The position and first and second derivatives at the points (u, v) (any shape,
        broadcast; the results flattened to (n, 3)), by OCCT's ``D2``.

        Args:
            u: the first parameters.
            v: the second parameters.

        Returns:
            The jet at each point.
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        out = np.empty((6, u.size, 3))
        p, du, dv, duu, dvv, duv = gp_Pnt(), gp_Vec(), gp_Vec(), gp_Vec(), gp_Vec(), gp_Vec()
        d2 = self.surface.D2
        for i, (a, b) in enumerate(zip(u.ravel().tolist(), v.ravel().tolist())):
            d2(a, b, p, du, dv, duu, dvv, duv)
            out[0, i] = p.X(), p.Y(), p.Z()
            out[1, i] = du.X(), du.Y(), du.Z()
            out[2, i] = dv.X(), dv.Y(), dv.Z()
            out[3, i] = duu.X(), duu.Y(), duu.Z()
            out[4, i] = duv.X(), duv.Y(), duv.Z()
            out[5, i] = dvv.X(), dvv.Y(), dvv.Z()
        return SurfaceJet(*out)


def face_classifier(face: TopoDS_Face) -> Callable[[FloatArray, FloatArray], FloatArray]:
    """(u, v) arrays -> whether each point lies on ``face`` in its surface's parameters, in or
    on its boundary (OCCT's ``IntTools_FClass2d``, made once, its edges' pcurves to 1e-9).

    Args:
        face: the face.

    Returns:
        The classifier: (u, v) of any shape -> a flat bool array.
    """
    from OCP.gp import gp_Pnt2d
    from OCP.IntTools import IntTools_FClass2d
    from OCP.TopAbs import TopAbs_IN, TopAbs_ON

    classifier = IntTools_FClass2d(face, 1e-9)

    def inside(u: FloatArray, v: FloatArray) -> FloatArray:
        states = [
            classifier.Perform(gp_Pnt2d(a, b)) in (TopAbs_IN, TopAbs_ON)
            for a, b in zip(np.ravel(u).tolist(), np.ravel(v).tolist())
        ]
        return np.array(states, dtype=bool)

    return inside


def _breaks(surface: Geom_Surface) -> tuple[FloatArray, FloatArray]:
    """The surface's parameters inside its own bounds where it is less than C3, in u and in v
    (OCCT's continuity intervals, ``GeomAdaptor_Surface::UIntervals``)."""
    from OCP.GeomAbs import GeomAbs_C3
    from OCP.GeomAdaptor import GeomAdaptor_Surface

    from tubecad.occ_compat import Array1OfReal

    adaptor = GeomAdaptor_Surface(surface)
    out = []
    for count, fill in (
        (adaptor.NbUIntervals(GeomAbs_C3), adaptor.UIntervals),
        (adaptor.NbVIntervals(GeomAbs_C3), adaptor.VIntervals),
    ):
        if count <= 1:
            out.append(np.zeros(0))
            continue
        values = Array1OfReal(1, count + 1)
        fill(values, GeomAbs_C3)
        out.append(np.array([values.Value(i) for i in range(2, count + 1)]))
    return out[0], out[1]


def crossed_breaks(host: HostSurface, a: FloatArray, b: FloatArray) -> list[tuple[int, float]]:
    """The break lines (coordinate 0 for u, 1 for v; the value, unwrapped as ``a`` is) strictly
    between the parameter points ``a`` and ``b``, nearest ``a`` first."""
    out = []
    for k in (0, 1):
        values = host.breaks[k]
        period = host.periods[k] if host.closed[k] else None
        if period is not None:  # the periodic seam too: a B-spline's knot, smooth or not
            values = np.append(values, host.bounds[2 * k])
        if not values.size or a[k] == b[k]:
            continue
        low, high = min(a[k], b[k]), max(a[k], b[k])
        if period is not None:
            turns = np.arange(math.floor((low - values.max()) / period), math.ceil((high - values.min()) / period) + 1)
            values = (values[None, :] + period * turns[:, None]).ravel()
        inside = values[(values > low) & (values < high)]
        out += [(k, float(v)) for v in inside]
    return sorted(out, key=lambda item: abs(item[1] - a[item[0]]) / max(abs(b[item[0]] - a[item[0]]), 1e-300))
