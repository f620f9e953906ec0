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

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.curves.natural import NaturalAxis
from tubecad.surface.canal import tube_or_canal
from tubecad.surface.protocol import CurvatureLineSurface


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
