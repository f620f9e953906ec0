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
from tubecad.surface import CurvatureLineSurface, CurvatureLineTube


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
        False on a tube's, whose rings the frame's circle spline gives with u = theta."""
        return False


def exact_section_surface(
    tube: CurvatureLineTube, frame: FrameSpline, origin_deg: float = 0.0, stringers_deg: Sequence[float] | None = None
) -> TubeSurface:
    """Build the periodic-in-u rational surface of ``tube`` on the fitted ``frame``.

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
    rho = tube.radius
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
