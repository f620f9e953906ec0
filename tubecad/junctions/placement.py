"""Where a straight branch stands on a main tube: its axis from the main axis' point and frame.

A branch leaves the main axis c(s) at arc length ``at``, ``angle`` degrees from the tangent t
towards the side ``around`` degrees round the axis from its first stringer r1 (towards r2):

    d = cos(angle) t + sin(angle) (cos(around) r1 + sin(around) r2),

its axis leaving c(at) + offset n along d, with n = t x side / |t x side| the sideways
direction of a hillside nozzle: the line of ``length`` (the default), or the curve of natural
equations k(s), tau(s) (expressions in the branch's own arc length s, 0 <= s <= length) whose
principal normal at the start is t's part normal to d. Its first stringer points along that
normal (towards the main axis' forward end), so its stringer 0 starts in the plane of t and d.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.curves.natural import NaturalAxis
from tubecad.junctions.crotch import TOUCHING
from tubecad.surface.canal import tube_or_canal
from tubecad.surface.protocol import CurvatureLineSurface

if TYPE_CHECKING:
    from shapely.geometry import Polygon

    from tubecad.junctions.saddle import SaddleCurve


def branch_surface(
    main: CurvatureLineSurface,
    at: float,
    length: float,
    radius: object,
    *,
    angle: float = 90.0,
    around: float = 90.0,
    offset: float = 0.0,
    k: str = "0",
    tau: str = "0",
) -> CurvatureLineSurface:
    """The branch's tube (a radius law: its canal surface, r along the branch) placed on
    ``main`` (see the module). A ParameterError names ``at``, ``angle``, ``length`` or
    ``radius`` for a value out of range."""
    s0, s1 = main.span
    if not s0 < at < s1:
        raise ParameterError(f"at must be inside the main axis' span ({s0:g}, {s1:g}), got {at:g}", key="at")
    if not 0.0 < angle < 180.0:
        raise ParameterError(f"angle must be in (0, 180) degrees, got {angle:g}", key="angle")
    if not length > 0:
        raise ParameterError(f"length must be > 0, got {length:g}", key="length")
    s = np.array([float(at)])
    centre = main.axis.position(s)[0]
    t, r1, r2 = (v[0] for v in main.axis.rotation_minimising_frame(s))
    a, b = math.radians(angle), math.radians(around)
    side = math.cos(b) * r1 + math.sin(b) * r2
    direction = math.cos(a) * t + math.sin(a) * side
    along = t - (t @ direction) * direction
    try:
        axis = NaturalAxis(
            k,
            tau,
            (0.0, float(length)),
            origin=tuple(centre + offset * np.cross(t, side)),
            tangent=tuple(direction),
            normal=tuple(along / np.linalg.norm(along)),
        )
    except ParameterError as exc:  # a bad k(s) or tau(s): the branch's axis keys
        which = exc.key if exc.key in ("k", "tau") else ("tau" if str(exc).startswith("tau") else "k")
        exc.key = f"axis.{which}"
        raise
    try:
        return tube_or_canal(axis, radius)  # type: ignore[arg-type]
    except ParameterError as exc:
        if exc.key is None:
            exc.key = "radius"
        raise


def branch_start_problem(
    main: CurvatureLineSurface,
    main_offsets: tuple[float, float],
    branch: CurvatureLineSurface,
    branch_offsets: tuple[float, float],
    at: float,
) -> tuple[str, str] | None:
    """Why a branch wall cannot be joined to the main wall at arc length ``at``, or None: the
    one rule of the spec and the builder alike (issue 43).

    The junction W = (A_o u B_o) - (A_i u B_i) needs each branch surface to start inside its
    main surface and leave it through the wall: the branch's outer surface B_o (offset
    ``branch_offsets[1]``) inside the main's outer surface A_o (``main_offsets[1]``) at the
    branch's first ring, and its bore B_i (``branch_offsets[0]``) inside the main's bore A_i
    (``main_offsets[0]``). Then B_o's start lies in the main wall or its bore (fused away or
    bored out) and each saddle is one closed curve. (B_o may start inside the main wall itself:
    r + t_b/2 < R - t/2 is not needed; the equal tee, where the surfaces are tangent, is
    refused by the saddle's own tangency test.)

    Args:
        main: the main tube's exact surface.
        main_offsets: (d_in, d_out) of the main wall (tubecad.brep.wall.wall_offsets).
        branch: the branch tube's exact surface (placed: :func:`branch_surface`).
        branch_offsets: (d_in, d_out) of the branch's wall.
        at: the arc length on the main axis where the branch starts.

    Returns:
        None, or (what is wrong, the branch's parameter at fault: ``radius``) for the
        caller's message and key.
    """
    u = np.linspace(0.0, 2.0 * np.pi, 73)
    s_main = np.clip(np.array([at]), *main.span)
    centre = main.axis.position(s_main)[0]
    r_main = float(main.radius_law.r(s_main)[0])
    for which, k in (("outer surface", 1), ("bore", 0)):
        start = branch.offset(branch_offsets[k]).points(u, np.full_like(u, branch.span[0]))
        reach = float(np.linalg.norm(start - centre, axis=1).max())
        limit = r_main + main_offsets[k]
        if reach > limit * (1.0 + TOUCHING):  # touching (to TOUCHING) is an equal tee: built
            main_surface = "outer surface" if k else "bore"
            return (
                f"the branch's {which} must start inside the main tube's {main_surface}: it reaches {reach:.6g} "
                f"from the main axis there, the main's {main_surface} {limit:.6g} (a smaller radius or offset, "
                "or a thinner branch wall)",
                "radius",
            )
    return None


def opening_clearance(main: CurvatureLineSurface, first: SaddleCurve, second: SaddleCurve) -> float:
    """The clearance between two openings in the main tube: the shortest distance between the
    two saddles' regions unrolled onto the main's surface (girth r u_A by arc length s_A, u_A
    taken round either way), 0 where they touch or overlap, measured with shapely.

    Args:
        main: the main tube's surface the saddles lie on (its outer surface for the openings).
        first: one branch's saddle on it (:func:`tubecad.junctions.saddle.saddle_curve`).
        second: the other branch's.

    Returns:
        The clearance in model units (>= 0; 0: the openings meet).
    """
    return region_clearance(main, unrolled_opening(main, first), unrolled_opening(main, second))


def unrolled_opening(main: CurvatureLineSurface, saddle: SaddleCurve) -> Polygon:
    """The region a saddle bounds on ``main``, unrolled: (girth r u_A, arc length s_A)."""
    from shapely.geometry import Polygon

    s = saddle.main_s
    return Polygon(np.column_stack([main.radius_law.r(s) * saddle.main_u, s])).buffer(0)


def unrolled_patch(
    main: CurvatureLineSurface, s_range: tuple[float, float], angles_deg: tuple[float, float]
) -> Polygon:
    """The patch between the rings ``s_range`` and the stringer angles ``angles_deg`` of
    ``main`` (a pad's bounds), unrolled as :func:`unrolled_opening` unrolls a saddle (the
    girth at the patch's middle radius)."""
    from shapely.geometry import box

    r = float(main.radius_law.r(np.array([0.5 * (s_range[0] + s_range[1])]))[0])
    return box(r * math.radians(angles_deg[0]), s_range[0], r * math.radians(angles_deg[1]), s_range[1])


def region_clearance(main: CurvatureLineSurface, first: Polygon, second: Polygon) -> float:
    """The shortest distance between two unrolled regions of ``main``, the second taken round
    either way (its girth shifted by +-2 pi r); 0 where they meet."""
    from shapely.affinity import translate

    s0, s1 = first.bounds[1], first.bounds[3]
    turn = 2.0 * math.pi * float(main.radius_law.r(np.array([0.5 * (s0 + s1)]))[0])
    return float(min(first.distance(translate(second, xoff=k * turn)) for k in (-1, 0, 1)))


#: stringers of the offset branch whose crossings with the offset main the blend check finds
BLEND_CHECK_STRINGERS = 36
#: rings along the offset branch on which they are looked for
BLEND_CHECK_RINGS = 129


def blend_problem(main: CurvatureLineSurface, branch: CurvatureLineSurface, radius: float) -> str | None:
    """Why a ball of ``radius`` cannot roll round the saddle of the outer surfaces ``main``
    and ``branch``, or None: the one rule of the spec and the builder (issue 43).

    The ball's centre curve is the saddle of the surfaces offset by the radius
    (:mod:`~tubecad.junctions.blend`), so that saddle must exist: each stringer of the branch's
    offset must leave the main's offset before the branch ends, and cross it within the main's
    span (the toe on the main inside it); an equal tee's offsets touch (their saddle has
    corners), where the blend is not made yet. Checked on BLEND_CHECK_STRINGERS stringers at
    BLEND_CHECK_RINGS rings (the crossings to within a ring's spacing): a few hundredths of a
    second, before anything is built.

    Args:
        main: the main's outer surface.
        branch: the branch's outer surface (placed).
        radius: the ball's radius (> 0).

    Returns:
        None, or what is wrong (for the caller's message, key ``blend.radius``).
    """
    from tubecad.junctions.coordinates import surface_coordinates
    from tubecad.junctions.crotch import crotch

    main_off, branch_off = main.offset(radius), branch.offset(radius)
    scale = float(np.abs(main.axis.position(np.array(main.span))).max()) + float(
        main.radius_law.r(np.array(main.span)).max()
    )
    if crotch(main_off, branch_off, scale) is not None:
        return "a blend on an equal tee (the surfaces offset by the ball's radius touch) is not made yet"
    u = np.linspace(0.0, 2.0 * math.pi, BLEND_CHECK_STRINGERS + 1)[:-1]
    s = np.linspace(*branch_off.span, BLEND_CHECK_RINGS)
    end = surface_coordinates(main_off, branch_off.points(u, np.full_like(u, s[-1]))).gap
    if (end <= 0).any():  # the end ring first: a ball far too large is told at once
        inside = float(-end.min())
        return (
            f"a ball of radius {radius:g} does not roll round the saddle: its centre stays inside the main's outer "
            f"surface offset by it to the branch's end ({inside:.4g} inside there); a smaller radius or a longer branch"
        )
    points = branch_off.points(np.repeat(u, len(s)), np.tile(s, len(u)))
    gap = surface_coordinates(main_off, points).gap.reshape(len(u), len(s))
    last_inside = np.array([np.flatnonzero(row <= 0).max(initial=0) for row in gap])
    rows = np.arange(len(u))
    g0, g1 = gap[rows, last_inside], gap[rows, last_inside + 1]
    t = np.where(g1 != g0, -g0 / np.where(g1 != g0, g1 - g0, 1.0), 0.0)
    s_cross = s[last_inside] + np.clip(t, 0.0, 1.0) * (s[1] - s[0])
    cross = branch_off.points(u, s_cross)
    on_main = surface_coordinates(main_off, cross).s
    s0, s1 = main.span
    margin = 1e-9 * (s1 - s0)
    if on_main.min() <= s0 + margin or on_main.max() >= s1 - margin:
        return (
            f"a ball of radius {radius:g} does not roll round the saddle: its toe on the main reaches its end "
            f"(the main's span [{s0:g}, {s1:g}]); a smaller radius or a longer main"
        )
    return None
