"""The axis: the one protocol every stage takes (surface, fitting, B-rep, stiffeners, report).

docs/MATH.md section 7. An axis is a C2 curve c(s) in arc length s over ``span``, with its
rotation-minimising (Bishop) frame (t, r1, r2):

    c' = t,   t' = k1 r1 + k2 r2,   r1' = -k1 t,   r2' = -k2 t,   k1^2 + k2^2 = k^2

(k1, k2): the normal development of the curve. The frame exists through inflections
(k = 0) and along straight runs, where the Frenet frame does not. The tube
S(u, s) = c + rho (cos u r1 + sin u r2) has its rings and stringers on its lines of
curvature for every axis, so the surface, its forms, the fit and the B-rep need nothing
else. A concrete kind supplies ``position``, ``rotation_minimising_frame``,
``normal_development`` and its derivative; the rest is derived here.
"""

from __future__ import annotations

import copy
import math
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from tubecad.core.errors import ParameterError
from tubecad.core.validation import span_pair

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class AxisFrame:
    """The axis and its rotation-minimising frame at an array of arc lengths (vectors (..., 3))."""

    s: FloatArray
    position: FloatArray
    t: FloatArray
    r1: FloatArray
    r2: FloatArray
    k1: FloatArray
    k2: FloatArray

    @property
    def curvature_vector(self) -> FloatArray:
        """t' = c'' = k1 r1 + k2 r2 (= k n where the Frenet frame exists)."""
        return self.k1[..., None] * self.r1 + self.k2[..., None] * self.r2


class Axis(ABC):
    """A spatial axis over the arc-length ``span``; all evaluation methods take arrays of s
    (any shape) and are vectorised."""

    #: the spec's name of this kind of axis (``[axis] curve = ...``); a class attribute, which
    #: a parametric axis sets per instance (points and edge axes are parametric curves too)
    family: str
    #: the open lower bound of arc lengths where the axis is defined
    s_lower_bound: ClassVar[float] = -math.inf
    #: whether the axis' joints are always ring frames of a layout (a route's line-bend joints)
    rings_at_joints: ClassVar[bool] = False

    span: tuple[float, float]
    #: the axis as exact straight lines and circular arcs (a route's ``Piece`` list), or None
    #: for a smooth curve: the fit then takes the exact rational frame instead of fitting one
    pieces: Sequence[Any] | None = None
    #: whether the axis is a closed loop (kinds set it with :func:`closing`)
    _closed: bool = False

    # --- what a kind provides ----------------------------------------------------------
    @abstractmethod
    def position(self, s: ArrayLike) -> FloatArray:
        """c(s), shape (..., 3)."""

    @abstractmethod
    def rotation_minimising_frame(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(t, r1, r2), each (..., 3): r1' = -k1 t, r2' = -k2 t (no spin about t)."""

    @abstractmethod
    def normal_development(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(k1, k2): the components of t' = k1 r1 + k2 r2."""

    @abstractmethod
    def normal_development_derivative(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(k1', k2'), d/ds of the normal development."""

    @abstractmethod
    def describe(self) -> dict[str, Any]:
        """Spec-style description: ``curve``, the kind's parameters, ``s``."""

    # --- derived ----------------------------------------------------------------------
    @property
    def length(self) -> float:
        """Arc length of the axis over its span, s1 - s0."""
        return self.span[1] - self.span[0]

    @property
    def joints(self) -> tuple[tuple[float, int], ...]:
        """(s, continuity) where the frame (c, r1, r2) is only C^continuity: a spline axis'
        knots (C1: r1' = -k1 t with k only continuous), a route's line-bend joints (C0).
        Empty for an axis smooth throughout; the fit puts knots of reduced continuity there."""
        return ()

    @property
    def closed(self) -> bool:
        """Whether the axis is a closed loop: c and t at the span's end equal those at its
        start (its tube then has no caps). Kinds set ``_closed`` with :func:`closing`."""
        return getattr(self, "_closed", False)

    @property
    def holonomy(self) -> float:
        """On a closed axis, the angle (radians, in (-pi, pi]) by which the rotation-minimising
        frame comes back turned about t: r1(L) = cos a r1(0) + sin a r2(0). Its stringers
        (u = const) meet the closing ring shifted by it. 0 on an open axis."""
        if not self.closed:
            return 0.0
        _, r1, r2 = self.rotation_minimising_frame(np.array(self.span))
        return float(math.atan2(r1[1] @ r2[0], r1[1] @ r1[0]))

    def piece_at(self, s: float) -> Any:
        """The piece of :attr:`pieces` (an exact line or circular arc) holding arc length
        ``s``, the later one at a joint: what the exact rational frame is made of. A kind with
        pieces (RouteAxis) gives it; a smooth axis has none (a ParameterError here)."""
        raise ParameterError(f"piece_at: the axis is a smooth curve, not made of lines and arcs (s = {s:g})")

    def tube_radius_problem(self, radius: float) -> str | None:  # noqa: ARG002 - the hook's signature
        """Why a tube of ``radius`` cannot be regular, said in the axis' own terms (a route
        names the bend), or None; the general check (rho k < 1, no self-approach) follows.
        None here: a kind that knows its limits (RouteAxis) overrides it."""
        return None

    def curvature(self, s: ArrayLike) -> FloatArray:
        """k(s) = sqrt(k1^2 + k2^2) >= 0 (a slope curve gives its signed k instead)."""
        return np.hypot(*self.normal_development(s))

    def frame_rate(self, s: ArrayLike) -> FloatArray:
        """How fast the frame (c, r1, r2) turns per unit s: the density by which the fit
        places its first knots. |k| here; sqrt(k^2 + tau^2) where the kind knows tau."""
        return np.abs(self.curvature(s))

    def at(self, s: ArrayLike) -> AxisFrame:
        """Position, rotation-minimising frame and normal development at arc lengths ``s``."""
        s = np.asarray(s, dtype=float)
        t, r1, r2 = self.rotation_minimising_frame(s)
        k1, k2 = self.normal_development(s)
        return AxisFrame(s, self.position(s), t, r1, r2, k1, k2)

    def _inside(self, s: ArrayLike) -> FloatArray:
        """:meth:`inside` (the former private name, which the kinds call on themselves)."""
        return self.inside(s)

    def inside(self, s: ArrayLike) -> FloatArray:
        """``s`` as a float array, checked to lie in the span within 1e-9 of it (for kinds
        known only there); a ParameterError otherwise."""
        s = np.asarray(s, dtype=float)
        s0, s1 = self.span
        slack = 1e-9 * (s1 - s0)
        if s.size and (s.min() < s0 - slack or s.max() > s1 + slack):
            raise ParameterError(f"s must lie in the span [{s0:g}, {s1:g}] of the axis, got [{s.min():g}, {s.max():g}]")
        return s

    def restricted(self, span: tuple[float, float]) -> Axis:
        """The same axis over a sub-span of its span (e.g. one ring frame's width), with the
        same frame (r1, r2 are not re-started)."""
        s0, s1 = span_pair("span", span, self.s_lower_bound)
        lo, hi = self.span
        slack = 1e-9 * (hi - lo)
        if s0 < lo - slack or s1 > hi + slack:
            raise ParameterError(f"span must lie within [{lo:g}, {hi:g}], got [{s0:g}, {s1:g}]")
        curve = copy.copy(self)
        curve.span = (max(s0, lo), min(s1, hi))
        if curve.span != self.span:
            curve._closed = False  # a piece of a loop is open
        return curve


#: the ends of a closed axis agree to this, relative to its length or its coordinates (c), and in radians (t)
CLOSING_GAP = 1e-10
CLOSING_ANGLE = 1e-8


def closing(axis: Axis, closed: bool | None, key: str = "closed") -> bool:
    """Whether ``axis`` is a closed loop: ``closed`` None detects it (the ends and their
    tangents agree to CLOSING_GAP x max(length, |c|) and CLOSING_ANGLE), True demands it (a
    ParameterError naming ``key`` says how far the ends are apart, or by how much the
    tangents differ: the closing rings would not lie in one plane), False keeps it open."""
    if closed is not None and not isinstance(closed, (bool, np.bool_)):
        raise ParameterError(f"{key} must be true or false, got {closed!r:.80}")
    if closed is False:
        return False
    ends = axis.position(np.array(axis.span))
    t = axis.rotation_minimising_frame(np.array(axis.span))[0]
    gap = float(np.linalg.norm(ends[1] - ends[0]))
    allowed = CLOSING_GAP * max(axis.length, float(np.abs(ends).max()))  # round-off grows with the coordinates
    angle = float(math.atan2(np.linalg.norm(np.cross(t[0], t[1])), float(t[0] @ t[1])))
    if gap <= allowed and angle <= CLOSING_ANGLE:
        return True
    if closed:
        if gap > allowed:
            raise ParameterError(
                f"{key} = true, but the axis' ends are {gap:.6g} apart (at most {allowed:.3g} for a closed loop)"
            )
        raise ParameterError(
            f"{key} = true, but the tangents at the axis' ends differ by {math.degrees(angle):.6g} deg: "
            "the closing rings would not lie in one plane (a kink); the ends must meet tangentially"
        )
    return False
