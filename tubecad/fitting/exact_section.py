"""Exact-section NURBS of the tube (docs/MATH.md section 6): exact rational circles in u,
a B-spline of the axis and its rotation-minimising frame in s.

Poles P_ij = C_j + rho (X_i R1_j + Y_i R2_j), weights w_i (1 in s; w_i v_j on a route's
exact rational frame, :mod:`.route_frame`, which is the same identity in homogeneous form), where (X_i, Y_i, w_i)
is the unit circle of :mod:`.circle` and (C_j, R1_j, R2_j) the poles of the frame spline.
Because the weights are a product with all s-weights 1, every s-isoline is exactly the
circle C(s) + rho (x(u) R1(s) + y(u) R2(s)); only the s direction is approximated.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from OCP.Geom import Geom_BSplineSurface

from tubecad.fitting.circle import CircleSpline
from tubecad.fitting.frame_spline import FrameSpline
from tubecad.fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals, reals_2d
from tubecad.surface import CurvatureLineSurface


@dataclass(frozen=True)
class TubeSurface:
    """An OCCT surface of a curvature-line tube; u = 0 is the angle ``origin_deg`` from r1.

    Convert angles around the tube (from the RMF normal r1, as in S(u, s)) to the
    surface's u with :meth:`u_at`; at the circle's breaks (the stringers) u is the angle
    from the origin exactly.
    """

    surface: Geom_BSplineSurface
    #: the exact surface it approximates (a CanalSurface for a CanalSectionSurface)
    tube: CurvatureLineSurface
    origin_deg: float
    circle: CircleSpline
    #: v -> s where the surface's parameter v is not the arc length (a route's rational frame)
    arc_length: Callable[[np.ndarray], np.ndarray] | None = None

    def s_at(self, v: np.ndarray | float) -> np.ndarray:
        """Arc length s of the ring at the OCCT parameter v (v itself unless the frame is
        rational; equal at every ring in any case)."""
        v = np.asarray(v, dtype=float)
        return v if self.arc_length is None else self.arc_length(v)

    def u_at(self, theta_deg: np.ndarray | float) -> np.ndarray:
        """OCCT u parameter of the stringer at angle ``theta_deg`` (degrees), in [0, 2 pi)."""
        rel = np.mod(np.radians(np.asarray(theta_deg, dtype=float) - self.origin_deg), 2 * math.pi)
        return self.circle.u_of_theta(rel)

    def theta_at(self, u: np.ndarray | float) -> np.ndarray:
        """Angle around the tube (radians, from r1) at the OCCT parameter u."""
        return self.circle.theta_of_u(u) + math.radians(self.origin_deg)

    @property
    def pole_count(self) -> tuple[int, int]:
        return self.surface.NbUPoles(), self.surface.NbVPoles()

    @property
    def canal(self) -> bool:
        """Whether this is a canal surface's section (rings the exact characteristic circles, the
        stringers crossing them at angles the Moebius map moves: :meth:`ring`, :meth:`ring_angles`);
        False on a tube's, whose rings the frame's circle spline gives with u = theta (the
        fast path: one pcurve per stringer interval for every ring)."""
        return False

    @property
    def level(self) -> float:
        """Where the surface lies in the family of surfaces one fit serves, as a distance
        along the normal: a tube's radius rho; a canal section's offset d (the canal surface
        of r + d). Two surfaces of one wall are ``outer.level - inner.level`` apart."""
        return self.tube.radius_law.constant_value

    # --- the rings, for every kind (a tube: chi = u, Mb = I, so theta = u - origin) ----------
    def ring(self, s: float) -> tuple[np.ndarray, float, np.ndarray, np.ndarray, float]:
        """The ring at ``s`` as an exact circle: (centre c - r r' t, radius r q, normal t, the
        direction e of the origin stringer, chi of the origin stringer); on a tube (c, rho,
        t, cos o r1 + sin o r2, o) with o the origin's angle."""
        exact = self.tube
        centre, radius, t = exact.circle(np.array([s]))
        chi_o = float(exact.stringer_angle(math.radians(self.origin_deg), np.array([s]))[0])
        _, r1, r2 = exact.axis.rotation_minimising_frame(np.array([s]))
        x_dir = math.cos(chi_o) * r1[0] + math.sin(chi_o) * r2[0]
        return centre[0], float(radius[0]), t[0], x_dir, chi_o

    def ring_angles(self, s: float, angles: Sequence[float]) -> np.ndarray:
        """Where the stringers at ``angles`` (chi0 - origin, radians, increasing from 0, the
        last 2 pi) cross the circle at ``s``: the angles theta from the origin stringer there
        (increasing: the Moebius map keeps the order; the last 2 pi; a tube's: ``angles``)."""
        o = math.radians(self.origin_deg)
        chi = self.tube.stringer_angle(o + np.asarray(angles[:-1], dtype=float), np.full(len(angles) - 1, s))
        theta = np.mod(chi - chi[0], 2.0 * math.pi)
        theta[0] = 0.0
        return np.append(theta, 2.0 * math.pi)

    def ring_chi0(
        self,
        s: float,
        chi_o: float,
        chi0_a: float,
        theta: np.ndarray,
        theta_mid: float,
        moebius: np.ndarray | None = None,
    ) -> np.ndarray:
        """chi0 (radians, absolute) of the points at angles ``theta`` from the origin stringer
        on the circle at ``s``, on the arc that starts on the stringer chi0_a: the
        exact inverse Moebius map, continued from the arc's start through its middle (each
        step turns the half-angle vector by less than pi). ``moebius``: Mb(s), if already known."""
        m = self.tube.moebius_matrix(np.array([s]))[0] if moebius is None else moebius
        inverse = np.array([[m[1, 1], -m[0, 1]], [-m[1, 0], m[0, 0]]])

        def half(angle: np.ndarray) -> np.ndarray:
            h = 0.5 * (chi_o + np.asarray(angle, dtype=float))
            return np.stack([np.sin(h), np.cos(h)], axis=-1) @ inverse.T

        def turn(v0: np.ndarray, v1: np.ndarray) -> np.ndarray:
            return np.arctan2(v0[..., 1] * v1[..., 0] - v0[..., 0] * v1[..., 1], np.einsum("...i,...i", v0, v1))

        v_a = np.array([math.sin(0.5 * chi0_a), math.cos(0.5 * chi0_a)])
        v_mid = half(np.array(theta_mid))
        # the start's half-angle vector is +- v_a (chi_o plus the arc's start angle is chi_a only
        # mod 2 pi, so that angle is not used): the turn to the middle is in (0, pi), so taken mod pi
        return chi0_a + 2.0 * (np.mod(turn(v_a, v_mid), math.pi) + turn(v_mid, half(theta)))


def exact_section_surface(
    tube: CurvatureLineSurface,
    frame: FrameSpline,
    origin_deg: float = 0.0,
    stringers_deg: Sequence[float] | None = None,
) -> TubeSurface:
    """Build the periodic-in-u rational surface of ``tube`` (a surface of constant radius:
    a tube, or the tube's fast path of a constant law) on the fitted ``frame``.

    With ``stringers_deg`` (angles from r1, the face boundaries) the circle's C0 knots are
    chosen among them (:meth:`CircleSpline.for_stringers`) and the first is the origin
    u = 0; without, the circle has four quarter arcs from ``origin_deg``.
    """
    if stringers_deg is None:
        circle = CircleSpline.quarters()
    else:
        origin_deg = float(stringers_deg[0])
        circle = CircleSpline.for_stringers(np.radians(np.asarray(stringers_deg, dtype=float) - origin_deg))
    F = frame.spline.c
    C, R1, R2 = F[:, :3], F[:, 3:6], F[:, 6:]
    a = math.radians(origin_deg)
    R1, R2 = math.cos(a) * R1 + math.sin(a) * R2, -math.sin(a) * R1 + math.cos(a) * R2
    rho = tube.radius_law.constant_value  # a ValueError on a varying law (that is canal_section_surface's)
    poles = C[None] + rho * (circle.x[:, None, None] * R1[None] + circle.y[:, None, None] * R2[None])
    s_weights = np.ones(len(C)) if frame.weights is None else frame.weights
    weights = circle.weights[:, None] * s_weights[None, :]  # a product: rational circles in u and (routes) in s
    s_knots, s_mults = knots_and_multiplicities(frame.spline.t)
    surface = Geom_BSplineSurface(
        points_2d(poles),
        reals_2d(weights),
        reals(circle.knots),
        reals(s_knots),
        integers(circle.multiplicities),
        integers(s_mults),
        2,
        frame.degree,
        True,
        False,
    )
    return TubeSurface(surface, tube, origin_deg, circle, frame.arc_length)
