"""The crotch blend: a ball of radius rb rolled along a junction's outer saddle (issue 43).

A ball touching both outer surfaces A (the main's) and B (the branch's) from outside has its
centre at distance rb from both, on the saddle of the offset surfaces A + rb and B + rb: the
ball's centre curve (the *spine*) is that saddle (:func:`~tubecad.junctions.saddle.saddle_curve`,
to round-off), and since an offset surface keeps its parameters and normals, the spine's
(u_A, s_A) and (u_B, s_B) are the contact points' on A and B, X_A(u_A, s_A) = C - rb n_A and
X_B(u_B, s_B) = C - rb n_B. The blend is the envelope of the balls, a canal surface of constant
radius: the tube of radius rb about the spine (tubecad's own, the spine a parametric axis whose
points are Newton's), whose rings are the balls' characteristic circles, lines of curvature of
the blend; both contact directions are normal to the spine (the centre moves on both offset
surfaces), so the contacts lie on the ring of their spine point, and the blend is each ring's
short arc between them (the one facing the corner it fills). The blend is tangent to A along
the contact curve on A and to B along the one on B: they are its edges, periodic B-splines in
the spine's u_B fitted as the saddle is (:func:`~tubecad.junctions.edges.periodic_bspline`,
their nodes doubled until the midpoints lie within the fit tolerance of the exact contacts).

The union of the main, the branch and the blend is made without intersecting the tangent faces
(:func:`~tubecad.junctions.touching.split_and_sewn`): the main's faces split by the contact curve
on A (its pieces inside it, in the (u_A, s_A) plane, dropped: the opening and the band the blend
covers), the branch's by the one on B (its pieces below it dropped), the blend tube's by both
(the pieces in each ring's short arc kept), sewn; the contact edges are then made again on their
exact curves (:func:`~tubecad.junctions.touching.exact_saddle_edges`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.Geom import Geom_BSplineCurve
from OCP.TopoDS import TopoDS_Edge, TopoDS_Shape

from tubecad.core.errors import ParameterError
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.junctions.edges import FIRST_INTERVALS, MOST_INTERVALS, fit_periodic
from tubecad.junctions.placement import blend_problem
from tubecad.junctions.saddle import SaddleCurve, saddle_curve, saddle_parameters
from tubecad.junctions.touching import Pieces, split_and_sewn
from tubecad.surface.protocol import CurvatureLineSurface

#: rings of the blend's tube (its faces' rows; the rings in the blend are named edges)
BLEND_RINGS = 17
#: stringers of the blend's tube
BLEND_STRINGERS = 4
#: the ball's centres at which a point of its tube is placed on a ring (the blend's pieces sorted)
BLEND_SAMPLES = 2049


@dataclass(frozen=True)
class RollingBall:
    """The rolling-ball blend of ``radius`` between the outer surfaces ``main`` and ``branch``:
    the ball's centre curve ``spine`` (the saddle of the surfaces offset by the radius, its
    parameters the contact points'), the blend's canal ``surface`` (the tube about it), the
    contact curves ``contacts`` (on the main, on the branch: periodic B-splines in u_B) and
    their ``edges``, and ``deviation``, their largest distance from the exact contacts at the
    midpoints between their nodes."""

    radius: float
    main: CurvatureLineSurface
    branch: CurvatureLineSurface
    spine: SaddleCurve
    surface: CurvatureLineSurface
    contacts: tuple[Geom_BSplineCurve, Geom_BSplineCurve]
    edges: tuple[TopoDS_Edge, TopoDS_Edge]
    deviation: float

    def contact_points(self, u_b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The ball's centre and its two contact points at the spine's parameters ``u_b``
        (exact: Newton on the offset surfaces from the spine's samples).

        Args:
            u_b: the spine's parameters (the branch's stringer angles).

        Returns:
            (centres, contacts on the main, contacts on the branch), each (n, 3).
        """
        main_off = self.main.offset(self.radius)
        x = _spine_parameters(main_off, self.branch.offset(self.radius), self.spine, u_b)
        u = np.mod(np.asarray(u_b, dtype=float), 2.0 * math.pi)
        centre = main_off.points(x[:, 0], x[:, 1])
        return centre, self.main.points(x[:, 0], x[:, 1]), self.branch.points(u, x[:, 2])

    def contact_parameters(self, u_b: np.ndarray) -> np.ndarray:
        """The contact points' parameters at the spine's parameters ``u_b``: (u_A, s_A) of the
        contact on the main, s_B of the one on the branch (at the branch's stringer u_b); the
        offset surfaces keep their parameters, so the spine's are theirs (exact: Newton).

        Args:
            u_b: the spine's parameters (the branch's stringer angles).

        Returns:
            (n, 3) rows (u_A, s_A, s_B).
        """
        return _spine_parameters(self.main.offset(self.radius), self.branch.offset(self.radius), self.spine, u_b)

    def join(
        self, base: TopoDS_Shape, base_surface: CurvatureLineSurface, branch: TopoDS_Shape, ball: TopoDS_Shape, key: str
    ) -> tuple[TopoDS_Shape, Pieces]:
        """``base`` (the main's outer solid, or its union with other branches), the capped
        ``branch`` and the blend tube's solid ``ball`` as one solid (module docstring).

        Args:
            base: the main's solid.
            base_surface: its exact surface (``main``).
            branch: the branch's capped solid.
            ball: the capped tube about the spine (:attr:`surface`'s solid).
            key: the key a failure names.

        Returns:
            (the union, the history: input edges -> their pieces).
        """
        # the contact curve on the main in its (u_A, s_A): the spine's own main parameters
        opening = _periodic_polygon(self.spine.main_u, self.spine.main_s)
        floor_u, floor_s = self.spine.branch_u, self.spine.branch_s
        in_blend = self._in_blend()

        def outside_opening(p: np.ndarray) -> bool:
            at = surface_coordinates(base_surface, p[None, :])
            return not any(opening.contains(_point(at.u[0] + k * 2.0 * math.pi, at.s[0])) for k in (-1, 0, 1))

        def above_contact(p: np.ndarray) -> bool:
            at = surface_coordinates(self.branch, p[None, :])
            u = floor_u[0] + np.mod(at.u[0] - floor_u[0], 2.0 * math.pi)
            return bool(at.s[0] > np.interp(u, floor_u, floor_s))

        main_edge, branch_edge = self.edges
        return split_and_sewn(
            [
                (base, [main_edge], outside_opening),
                (branch, [branch_edge], above_contact),
                (ball, [main_edge, branch_edge], in_blend),
            ],
            key,
        )

    def _in_blend(self):
        """A test of a point on the blend's tube: whether it lies on its ring's short arc
        between the two contacts, i.e. its direction d from the ring's centre C is
        alpha a + beta b with alpha, beta >= 0 (a, b the contacts' directions from C, all three
        in the ring's plane; C the nearest of BLEND_SAMPLES exact centres)."""
        from scipy.spatial import cKDTree

        centre, on_main, on_branch = self.contact_points(np.linspace(0.0, 2.0 * math.pi, BLEND_SAMPLES))
        tree = cKDTree(centre)
        a, b = on_main - centre, on_branch - centre

        def test(p: np.ndarray) -> bool:
            _, i = tree.query(p)
            basis = np.column_stack([a[i], b[i]])
            (alpha, beta), *_ = np.linalg.lstsq(basis, p - centre[i], rcond=None)
            return bool(alpha >= 0.0 and beta >= 0.0)

        return test


def rolling_ball(
    main: CurvatureLineSurface, branch: CurvatureLineSurface, radius: float, tolerance: float, *, key: str = "blend"
) -> RollingBall:
    """The rolling-ball blend of ``radius`` between the outer surfaces ``main`` and ``branch``
    (module docstring), its contact curves within ``tolerance`` of the exact ones.

    Args:
        main: the main's outer surface.
        branch: the branch's outer surface.
        radius: the ball's radius rb (> 0).
        tolerance: the contact curves' fit tolerance.
        key: the key a refusal names (``blend``; the radius's ``blend.radius``).

    Returns:
        The blend.

    Raises:
        ParameterError: (``blend.radius``) a radius that is not > 0, or one the surfaces'
            offsets do not meet in one closed saddle with inside both spans (too large a
            ball; :func:`~tubecad.junctions.placement.blend_problem`), or an equal tee's.
    """
    from tubecad.curves.parametric import ParametricAxis
    from tubecad.surface.canal import tube_or_canal

    if not (radius > 0 and math.isfinite(radius)):
        raise ParameterError(f"{key}.radius must be > 0, got {radius!r:.40}", key=f"{key}.radius")
    problem = blend_problem(main, branch, radius)
    if problem is not None:
        raise ParameterError(f"{key}.radius: {problem}", key=f"{key}.radius")
    main_off, branch_off = main.offset(radius), branch.offset(radius)
    try:
        spine = saddle_curve(main_off, branch_off, 2 * FIRST_INTERVALS + 1, key=f"{key}.radius")
    except ParameterError as exc:
        raise ParameterError(
            f"{key}.radius: a ball of radius {radius:g} does not roll round the saddle ({exc})", key=f"{key}.radius"
        ) from None
    if spine.corners:  # touching offsets: blend_problem's test, to its tolerance
        raise ParameterError(
            f"{key}.radius: a blend on an equal tee (the surfaces touch) is not made yet", key=f"{key}.radius"
        )

    def centre(t: np.ndarray) -> np.ndarray:
        shape = np.shape(t)
        x = _spine_parameters(main_off, branch_off, spine, np.ravel(t))
        return main_off.points(x[:, 0], x[:, 1]).reshape(*shape, 3)

    axis = ParametricAxis(centre, (0.0, 2.0 * math.pi), closed=True, name="the ball's centre")
    surface = tube_or_canal(axis, radius)
    intervals = FIRST_INTERVALS
    while True:
        u = np.linspace(0.0, 2.0 * math.pi, 2 * intervals + 1)
        x = _spine_parameters(main_off, branch_off, spine, u)
        exact = (main.points(x[:, 0], x[:, 1]), branch.points(u, x[:, 2]))
        fits = [fit_periodic(u, points) for points in exact]
        curves, deviation = [c for c, _ in fits], max(d for _, d in fits)
        if deviation <= tolerance or intervals >= MOST_INTERVALS:
            break
        intervals *= 2
    edges = tuple(BRepBuilderAPI_MakeEdge(c).Edge() for c in curves)
    return RollingBall(radius, main, branch, spine, surface, (curves[0], curves[1]), (edges[0], edges[1]), deviation)


def _spine_parameters(
    main_off: CurvatureLineSurface, branch_off: CurvatureLineSurface, spine: SaddleCurve, u_b: np.ndarray
) -> np.ndarray:
    """(u_A, s_A, s_B) of the spine at ``u_b``: Newton from the spine's samples' interpolation."""
    solved = saddle_parameters(main_off, branch_off, u_b, spine)
    if solved is None:
        raise ParameterError("blend.radius: the ball's centre curve did not converge", key="blend.radius")
    return solved


def _periodic_polygon(u: np.ndarray, s: np.ndarray):
    from shapely.geometry import Polygon

    return Polygon(np.column_stack([u, s])).buffer(0)


def _point(u: float, s: float):
    from shapely.geometry import Point

    return Point(u, s)
