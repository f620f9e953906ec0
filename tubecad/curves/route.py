"""A route: a polyline of points with circular bends at its inner vertices (docs/MATH.md
section 7), the way pipes and ducts are specified (IFC IfcSweptDiskSolidPolygonal).

Vertex i (0 < i < n) turns the route by theta_i = angle(d_in, d_out), d the unit leg
directions. Its bend of radius R_i is the arc tangent to both legs: it starts and ends at
the tangent length T_i = R_i tan(theta_i / 2) from the vertex, and each leg must hold the
tangent lengths of the bends at both its ends. The axis is then lines and arcs, tangent
continuous, in arc length s from 0:

    line:  c = A + (s - s_a) d,                              t = d,   r1, r2 constant
    bend:  c = O + R (cos phi e1 + sin phi e2),  phi = (s - s_a) / R,  e1 = (A - O) / R, e2 = d_in

On a bend the rotation-minimising frame turns with the tangent about the bend's binormal
b = e1 x e2 (torsion 0): every vector v of the frame becomes
v(phi) = (v.b) b + (v.e1)(cos phi e1 + sin phi e2) + (v.e2)(-sin phi e1 + cos phi e2),
so r1' = -k1 t with k1 = -(r1 . e1(phi)) / R constant on the bend (likewise k2) and 0 on a
line. Each piece of the tube is an exact cylinder or torus piece; the frame (c, r1, r2) is
only C0 at a line-bend joint (k jumps), which :attr:`joints` reports.

A closed route (the last point repeats the first, or ``closed=True``) has its legs and
bends all round, vertex 0 included (indices mod n). Its axis starts at the end of the
bend at points[0], on the leg points[0]-points[1], and ends there after that bend: the
closing is a joint like the others, and the frame comes back turned by the holonomy.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError
from tubecad.core.validation import MAX_LENGTH
from tubecad.curves.axis import Axis, FloatArray, closing
from tubecad.curves.natural import unit_vector
from tubecad.curves.points import checked_points, closed_loop, same_point, shown

#: turning angles below this (radians) make no bend: the vertex is refused as collinear
MIN_TURN = 1e-9
#: turning angles within this of pi (a leg folding back on the previous one) are refused
MAX_TURN = math.pi - 1e-6


@dataclass(frozen=True)
class Piece:
    """One line or bend of the route over s in [s0, s1]; on a bend ``centre``, ``radius``
    and the in-plane unit vectors e1 (from the centre to the start), e2 (the start tangent)."""

    kind: str  # "line" | "bend"
    s0: float
    s1: float
    start: np.ndarray
    direction: np.ndarray  # the line's direction; a bend's start tangent e2
    r1: np.ndarray  # the RMF at s0
    r2: np.ndarray
    vertex: int = -1  # a bend's vertex index
    centre: np.ndarray | None = None
    radius: float = math.inf
    e1: np.ndarray | None = None

    @property
    def angle(self) -> float:
        """A bend's turning angle (s1 - s0) / R."""
        return (self.s1 - self.s0) / self.radius if self.kind == "bend" else 0.0

    def rotate(self, v: np.ndarray, phi: np.ndarray) -> np.ndarray:
        """v (3,) turned by phi (...,) about the bend's binormal (v unchanged on a line)."""
        if self.kind == "line":
            return np.broadcast_to(v, phi.shape + (3,)).copy()
        e1, e2 = self.e1, self.direction
        assert e1 is not None  # a bend has its e1
        a, b = float(v @ e1), float(v @ e2)
        c, s = np.cos(phi)[..., None], np.sin(phi)[..., None]
        return (v - a * e1 - b * e2) + a * (c * e1 + s * e2) + b * (-s * e1 + c * e2)


class RouteAxis(Axis):
    """Lines and circular bends through ``points`` (n x 3, n >= 2) with ``bend_radius`` (one
    value, or one per inner vertex); ``normal``: r1 at the start (made normal to the first
    leg; default the first bend's inward normal, or the coordinate axis least along the
    leg for a straight route).

    ``closed``: a closed loop (None: when the last point repeats the first; True: the first
    point is appended if the last differs; False: an open route even so). Every vertex of a
    loop has a bend, points[0] too (``bend_radius``: one value or one per distinct vertex,
    points[0]..points[n-1]); the axis starts and ends at the end of the bend at points[0],
    on the leg points[0]-points[1], so the closing is a joint like the others.

    Args:
        points: the route's vertices [[x, y, z], ...], model units: at least 2, each
            differing from the next; no inner vertex collinear with its neighbours or turning
            the route back on itself.
        bend_radius: the bends' radius R_i, model units, > 0: one value for every bend, or
            one per inner vertex (per distinct vertex on a closed route); each leg must be
            long enough for the tangent lengths R_i tan(theta_i / 2) of the bends at its ends.
        normal: r1 at the start, made normal to the first leg; None (default): the first
            bend's inward normal, or the coordinate axis least along the leg.
        closed: None (default): a closed loop when the last point repeats the first; True:
            always a loop; False: an open route.

    Raises:
        ParameterError: bad points or radii, a collinear or folding vertex, or a leg too
            short for its bends, naming the point.
    """

    family = "route"
    rings_at_joints = True
    pieces: list[Piece]

    def __init__(
        self,
        points: Sequence[Sequence[float]] | np.ndarray,
        bend_radius: float | Sequence[float],
        *,
        normal: Sequence[float] | None = None,
        closed: bool | None = None,
    ) -> None:
        p = checked_points(points, 2)
        loop = closed_loop(p, closed)
        v = p[:-1] if loop and same_point(p[0], p[-1], p) else p  # the distinct vertices
        n = len(v)
        if loop and n < 3:
            raise ParameterError(f"a closed route needs 3 or more distinct points, got {n}")
        bent = np.ones(n, dtype=bool)  # the vertices with a bend: all but an open route's ends
        if not loop:
            bent[[0, -1]] = False
        radii = _checked_radii(bend_radius, int(bent.sum()), first=0 if loop else 1)
        radius = np.zeros(n)
        radius[bent] = radii
        # leg j runs from vertex j to vertex j + 1 (mod n on a loop)
        legs = (np.roll(v, -1, axis=0) - v) if loop else np.diff(v, axis=0)
        lengths = np.linalg.norm(legs, axis=1)
        d = legs / lengths[:, None]
        turn = np.zeros(n)  # per vertex: the angle between its legs in and out
        for i in np.flatnonzero(bent):
            turn[i] = math.acos(min(max(float(d[i - 1] @ d[i]), -1.0), 1.0))  # d[-1]: a loop's last leg
            before, after = (i - 1) % n, (i + 1) % n
            if turn[i] < MIN_TURN:
                raise ParameterError(
                    f"points[{i}] {shown(v[i])} makes no bend: points[{before}], points[{i}] and "
                    f"points[{after}] are collinear; remove it"
                )
            if turn[i] > MAX_TURN:
                raise ParameterError(
                    f"points[{i}] {shown(v[i])} turns the route back on itself (by "
                    f"{math.degrees(turn[i]):.6g} deg); a bend must turn by less than 180 deg"
                )
        tangent = radius * np.tan(turn / 2)  # per vertex; 0 at an open route's ends
        for j, length in enumerate(lengths):
            k = (j + 1) % n
            need = tangent[j] + tangent[k]
            if need > length * (1 + 1e-12):
                at = k if tangent[k] >= tangent[j] else j
                detail = " + ".join(f"{tangent[i]:.6g} (the bend at points[{i}])" for i in (j, k) if tangent[i] > 0)
                raise ParameterError(
                    f"bend_radius {radius[at]:g} at points[{at}] {shown(v[at])} does not fit: "
                    f"the leg points[{j}]-points[{k}] is {length:.6g} long but its bends need "
                    f"{detail}"
                )
        self.points, self.bend_radii = p, radii
        self.pieces = self._build(v, d, lengths, turn, tangent, radius, normal)
        self.span = (0.0, self.pieces[-1].s1)
        self._starts = np.array([piece.s0 for piece in self.pieces])
        self._closed = closing(self, True) if loop else False  # the loop's ends agree to round-off

    # --- construction -------------------------------------------------------------------
    def _build(
        self,
        v: np.ndarray,
        d: np.ndarray,
        lengths: np.ndarray,
        turn: np.ndarray,
        tangent: np.ndarray,
        radius: np.ndarray,
        normal: Sequence[float] | None,
    ) -> list[Piece]:
        """The pieces leg by leg: leg j's line, then the bend at its end vertex (if it has
        one). A loop (n legs, its vertex 0 bent) starts after the bend at vertex 0 and ends
        with it; an open route (n - 1 legs, its ends not bent) from end to end."""
        n = len(v)
        r1 = _start_normal(d, normal)
        r2 = np.cross(d[0], r1)
        pieces: list[Piece] = []
        s = 0.0
        for j in range(len(d)):
            k = (j + 1) % n  # the leg's end vertex
            a = v[j] + tangent[j] * d[j]
            line = lengths[j] - tangent[j] - tangent[k]
            if line > 1e-12 * max(lengths[j], 1.0):
                pieces.append(Piece("line", s, s + line, a, d[j], r1, r2))
                s += line
            if radius[k] > 0:  # the bend at vertex k
                d_out = d[k]
                R, angle = float(radius[k]), float(turn[k])
                start = v[k] - tangent[k] * d[j]
                inward = d_out - float(d_out @ d[j]) * d[j]
                inward /= np.linalg.norm(inward)
                bend = Piece("bend", s, s + R * angle, start, d[j], r1, r2, k, start + R * inward, R, -inward)
                pieces.append(bend)
                s += R * angle
                r1, r2 = (bend.rotate(x, np.array(angle)) for x in (r1, r2))
                r1 = r1 - float(r1 @ d_out) * d_out  # round-off only
                r1 /= np.linalg.norm(r1)
                r2 = np.cross(d_out, r1)
        return pieces

    # --- evaluation ---------------------------------------------------------------------
    def _each(self, s: ArrayLike) -> Iterator[tuple[Piece, np.ndarray, np.ndarray]]:
        """(piece, mask, local s - s0) for every piece the array ``s`` touches."""
        s = self._inside(s)
        idx = np.clip(np.searchsorted(self._starts, s, side="right") - 1, 0, len(self.pieces) - 1)
        for k in np.unique(idx):
            mask = idx == k
            piece = self.pieces[k]
            yield piece, mask, s[mask] - piece.s0

    def position(self, s: ArrayLike) -> FloatArray:
        """c(s): A + (s - s_a) d on a line, O + R (cos phi e1 + sin phi e2) on a bend."""
        s_arr = np.asarray(s, dtype=float)
        out = np.empty(s_arr.shape + (3,))
        for piece, mask, x in self._each(s_arr):
            if piece.kind == "line":
                out[mask] = piece.start + x[:, None] * piece.direction
            else:
                phi = (x / piece.radius)[:, None]
                out[mask] = piece.centre + piece.radius * (np.cos(phi) * piece.e1 + np.sin(phi) * piece.direction)
        return out

    def rotation_minimising_frame(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(t, r1, r2): constant on a line, turned by phi about the binormal on a bend."""
        s_arr = np.asarray(s, dtype=float)
        t, r1, r2 = (np.empty(s_arr.shape + (3,)) for _ in range(3))
        for piece, mask, x in self._each(s_arr):
            phi = x / piece.radius if piece.kind == "bend" else np.zeros_like(x)
            t[mask], r1[mask], r2[mask] = (piece.rotate(v, phi) for v in (piece.direction, piece.r1, piece.r2))
        return t, r1, r2

    def normal_development(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(k1, k2) = (t' . r1, t' . r2): 0 on a line, -(e1 . r1_a, e1 . r2_a) / R on a bend
        (t' = -e1(phi) / R and r1, e1(phi) turn together, so the products are constant)."""
        s_arr = np.asarray(s, dtype=float)
        k1, k2 = np.zeros(s_arr.shape), np.zeros(s_arr.shape)
        for piece, mask, _ in self._each(s_arr):
            if piece.kind == "bend":
                k1[mask] = -float(piece.e1 @ piece.r1) / piece.radius
                k2[mask] = -float(piece.e1 @ piece.r2) / piece.radius
        return k1, k2

    def normal_development_derivative(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(0, 0): the normal development is constant on every piece."""
        s_arr = self._inside(s)
        return np.zeros(s_arr.shape), np.zeros(s_arr.shape)

    def torsion(self, s: ArrayLike) -> FloatArray:
        return np.zeros(self._inside(s).shape)

    @property
    def joints(self) -> tuple[tuple[float, int], ...]:
        """Every line-bend (and bend-bend) joint inside the span, continuity 0."""
        s0, s1 = self.span
        slack = 1e-12 * max(self.pieces[-1].s1, 1.0)
        return tuple((piece.s0, 0) for piece in self.pieces[1:] if s0 + slack < piece.s0 < s1 - slack)

    def piece_at(self, s: float) -> Piece:
        """The piece holding arc length ``s`` (the later one at a joint)."""
        k = int(np.clip(np.searchsorted(self._starts, s, side="right") - 1, 0, len(self.pieces) - 1))
        return self.pieces[k]

    def tube_radius_problem(self, radius: float) -> str | None:
        """The first bend whose radius is not above the tube's: there rho k >= 1 (the tube folds)."""
        for piece in self.pieces:
            if piece.kind == "bend" and piece.radius <= radius:
                v = piece.vertex
                return (
                    f"tube is not regular: the bend at points[{v}] {shown(self.points[v])} has bend_radius "
                    f"{piece.radius:g}, not above the tube radius {radius:g}"
                )
        return None

    def describe(self) -> dict[str, Any]:
        return {
            "curve": self.family,
            "points": self.points.tolist(),
            "bend_radius": self.bend_radii.tolist(),
            "bends": sum(p.kind == "bend" for p in self.pieces),
            "lines": sum(p.kind == "line" for p in self.pieces),
            "s": list(self.span),
            **({"closed": True} if self.closed else {}),
        }

    def __repr__(self) -> str:
        return f"RouteAxis({len(self.points)} points, length={self.length:.6g})"


def _checked_radii(bend_radius: object, inner: int, first: int = 1) -> np.ndarray:
    """One radius per bent vertex points[first]..points[first + inner - 1] (first 1: an open
    route's inner vertices; 0: every vertex of a loop)."""
    values = [bend_radius] if isinstance(bend_radius, (int, float, np.number)) else bend_radius
    try:
        radii = np.asarray(values, dtype=float).ravel()
    except (TypeError, ValueError):
        radii = np.zeros(0)
    if isinstance(bend_radius, (bool, str, bytes)) or radii.size == 0:
        raise ParameterError(
            f"bend_radius must be a number or a list of one number per inner vertex, got {bend_radius!r:.80}"
        )
    if radii.size == 1:
        radii = np.full(inner, radii[0])
    elif radii.size != inner:
        which = "inner vertex" if first else "vertex of the loop"
        raise ParameterError(
            f"bend_radius must be one number or {inner} (one per {which} points[{first}].."
            f"points[{first + inner - 1}]), got {radii.size}"
        )
    for i, r in enumerate(radii, first):
        if not (math.isfinite(r) and 0 < r <= MAX_LENGTH):
            raise ParameterError(f"bend_radius at points[{i}] must be a finite number > 0, got {r:g}")
    return radii


def _start_normal(d: np.ndarray, normal: Sequence[float] | None) -> np.ndarray:
    """r1 at the start: ``normal``, else the first bend's inward normal, else the coordinate
    axis least along the first leg; made normal to the first leg."""
    t = d[0]
    if normal is not None:
        n = unit_vector("normal", normal)
    else:
        bent = [k for k in range(1, len(d)) if np.linalg.norm(np.cross(d[0], d[k])) > 1e-9]
        n = d[bent[0]] if bent else np.eye(3)[int(np.argmin(np.abs(t)))]
    n = n - float(n @ t) * t
    if np.linalg.norm(n) < 1e-6:
        raise ParameterError("normal must not be parallel to the route's first leg")
    return n / np.linalg.norm(n)
