"""The crotch of an equal tee: the two points where a branch surface touches the main
surface at the branch's start (issue 43, docs/MATH.md section 13).

A canal surface (a tube, where the radius is constant) envelops the spheres of radius r(s)
about its axis c(s) and touches each along its characteristic circle, its ring at s
(Monge). Where the branch's first sphere, about its axis' start c_B with its first radius
r_B, is a sphere of the main surface (c_B is the main axis' point c_A(s*) nearest to it and
r_B = R(s*)), both surfaces touch that sphere, and so each other, where their two rings on
it meet: the crotch points. With the rings' planes (x - a) . n_A = 0 and (x - b) . n_B = 0,
their line x = p + t d, d = n_A x n_B, meets the sphere |x - c_B| = r_B at

    t = +-sqrt(r_B^2 - |p - c_B|^2),      p: both planes' point with (p - c_B) . d = 0.

There the surfaces are tangent: the saddle is not one smooth closed curve round the branch
but two curves from crotch point to crotch point (the half-ellipses of two equal straight
tubes, in the planes bisecting their axes), which cross there at an angle.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from tubecad.junctions.coordinates import surface_coordinates
from tubecad.surface.protocol import CurvatureLineSurface

FloatArray = np.ndarray

#: the branch's first sphere is the main's where their centres and radii agree to this times
#: the model's size (round-off of placing the branch: ~1e-15; a near-equal tee r/R = 0.999 is
#: 5e-4 off)
TOUCHING = 1e-9
#: main axis stations searched for the point nearest the branch's start
STATIONS = 513


@dataclass(frozen=True)
class Crotch:
    """The two crotch points of an equal tee: ``points`` (2, 3), the branch's stringer angles
    ``branch_u`` (increasing, in [0, 2 pi)) and ring ``branch_s`` (its first) there, and the
    main surface's ``main_u`` (in (-pi, pi]) and ``main_s`` of the same points."""

    points: FloatArray
    branch_u: FloatArray
    branch_s: float
    main_u: FloatArray
    main_s: FloatArray


def crotch(main: CurvatureLineSurface, branch: CurvatureLineSurface, scale: float) -> Crotch | None:
    """The crotch where ``branch`` touches ``main`` at its start, or None where the branch's
    first sphere is not one of the main's (every tee but the equal one: the surfaces then
    cross, or the branch starts outside, which the callers refuse).

    Args:
        main: the main surface.
        branch: the branch surface, starting at its span's first end.
        scale: the model's size (TOUCHING is relative to it).

    Returns:
        The crotch points and their parameters on both surfaces, or None.
    """
    s_b = float(branch.span[0])
    start = np.array([s_b])
    centre = branch.axis.position(start)[0]
    radius = float(branch.radius_law.r(start)[0])
    s_star = _nearest_station(main, centre)
    if s_star is None:
        return None
    at = np.array([s_star])
    if (
        np.linalg.norm(main.axis.position(at)[0] - centre) > TOUCHING * scale
        or abs(float(main.radius_law.r(at)[0]) - radius) > TOUCHING * scale
    ):
        return None
    (a,), _, (n_a,) = main.circle(at)
    (b,), _, (n_b,) = branch.circle(start)
    d = np.cross(n_a, n_b)
    if np.linalg.norm(d) < TOUCHING:  # one ring plane: the branch runs along the main axis
        return None
    d /= np.linalg.norm(d)
    p = np.linalg.solve(np.array([n_a, n_b, d]), np.array([n_a @ a, n_b @ b, d @ centre]))
    left = radius**2 - float((p - centre) @ (p - centre))
    if left < 0.0:
        return None
    points = p + np.outer([-1.0, 1.0], np.sqrt(left) * d)
    on_branch = surface_coordinates(branch, points)
    order = np.argsort(np.mod(on_branch.u, 2.0 * np.pi))
    on_main = surface_coordinates(main, points[order])
    return Crotch(points[order], np.mod(on_branch.u, 2.0 * np.pi)[order], s_b, on_main.u, on_main.s)


def _nearest_station(main: CurvatureLineSurface, point: FloatArray) -> float | None:
    """The main axis' arc length s* nearest to ``point`` ((point - c(s)) . t(s) = 0, the
    root nearest to it, by Brent's method), or None where no axis normal plane holds it."""
    s = np.linspace(*main.span, STATIONS)

    def along(x: float | FloatArray) -> FloatArray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        tangent = main.axis.rotation_minimising_frame(x)[0]
        return np.einsum("pk,pk->p", point - main.axis.position(x), tangent)

    f = along(s)
    change = np.flatnonzero(np.signbit(f[:-1]) != np.signbit(f[1:]))
    exact = np.flatnonzero(f == 0.0)
    roots = [float(s[i]) for i in exact] + [
        float(brentq(lambda x: float(along(x)[0]), s[i], s[i + 1], xtol=1e-15 * (1.0 + abs(s[i])), rtol=1e-15))
        for i in change
    ]
    if not roots:
        return None
    distance = np.linalg.norm(main.axis.position(np.array(roots)) - point, axis=1)
    return roots[int(np.argmin(distance))]
