"""How far a stiffener may stand from its wall: the radius its frame is fitted to, and the
limit on ``height`` it implies, checked before anything is fitted.

A point at distance d from the axis, swept along it, moves at the rate 1 - d k cos(phi)
(docs/MATH.md section 3: G = (1 - rho k cos phi)^2), so the stiffener's surfaces stay
regular, and its frame can be fitted, only while d max|k| < 1 over its span. The largest d:
- ring frame (the tube slices between r_min and r_max): R + height outside, R inside;
- stringer (its outline swept with the rotation-minimising frame): the outline corner
  farthest from the axis, sqrt(v^2 + w^2) for a corner w across and v along the normal:
  sqrt((R + height)^2 + w_max^2) outside (w_max: half the web thickness, half a T flange,
  or an L flange's reach), and max(R, sqrt((R - height)^2 + w_max^2)) inside.
Outside, d max|k| < 1 gives height < 1 / max|k| - R for a ring and
height < sqrt(1 / max|k|^2 - w_max^2) - R for a stringer. Inside, the stiffener reaches
in to R - height, which must stay >= MIN_SIZE.

On a canal surface (a radius law) a stiffener's surfaces are the offsets r + d of the wall:
each must be regular and stay off the axis (:func:`checked_levels`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from scipy.optimize import minimize_scalar

from tubecad.core.errors import ParameterError, RegularityError
from tubecad.core.tolerance import MIN_SIZE
from tubecad.curves.axis import Axis
from tubecad.fitting.frame_spline import FitError
from tubecad.stiffeners.profiles import Profile
from tubecad.surface.protocol import CurvatureLineSurface

SAMPLES = 2001


def max_curvature(axis: Axis) -> tuple[float, float]:
    """(max |k(s)|, s where it is reached) over the axis' span: the largest of SAMPLES
    equally spaced values, refined by bounded minimisation between its neighbours."""
    s = np.linspace(*axis.span, SAMPLES)
    k = np.abs(axis.curvature(s))
    i = int(np.argmax(k))
    best = (float(k[i]), float(s[i]))
    if 0 < i < SAMPLES - 1:
        res = minimize_scalar(lambda x: -abs(float(axis.curvature(x))), bounds=(s[i - 1], s[i + 1]), method="bounded")
        if -res.fun > best[0]:
            best = (float(-res.fun), float(res.x))
    return best


def reach(profile: Profile, radius: float, side: str, kind: str) -> float:
    """The largest distance from the axis of the stiffener's cross-section (module docstring)."""
    sign = 1.0 if side == "outside" else -1.0
    top = radius + sign * profile.height
    if kind == "ring":
        return max(radius, top)
    w_max = max(abs(w) for w, _ in profile.outline())
    return max(radius, math.hypot(top, w_max))


def checked_reach(axis: Axis, profile: Profile, radius: float, side: str, kind: str) -> float:
    """:func:`reach`, or a ParameterError naming ``height`` (or ``flange_width``) and its
    limit on this wall when the stiffener cannot be built: reach max|k| >= 1 over the
    axis' span, or an inside stiffener reaching in past the axis."""
    h = profile.height
    if side == "inside" and not radius - h >= MIN_SIZE:
        raise ParameterError(
            f"height must be < R = {radius:g} for side = 'inside' on this wall (its innermost radius "
            f"R - height must stay >= {MIN_SIZE:g}), got {h:.10g}"
        )
    d = reach(profile, radius, side, kind)
    k_max, s_at = max_curvature(axis)
    if d * k_max < 1.0:
        return d
    where = f"R = {radius:g}, max|k| = {k_max:.6g} at s = {s_at:.6g}"
    w_max = max(abs(w) for w, _ in profile.outline())
    if side == "outside":
        if kind == "ring":
            limit, rule = 1.0 / k_max - radius, "(R + height) max|k| must stay < 1"
        else:
            limit = math.sqrt(max(1.0 / k_max**2 - w_max**2, 0.0)) - radius
            rule = (
                f"the stringer's outer corners, sqrt((R + height)^2 + {w_max:g}^2) from the axis, times max|k| "
                f"must stay < 1"
            )
        raise ParameterError(
            f"height must be < {limit:.6g} for side = 'outside' on this wall: {rule} ({where}), got {h:.10g}"
        )
    raise ParameterError(
        f"flange_width is too wide for side = 'inside' on this wall: the flange corners reach "
        f"{d:.6g} from the axis, and that times max|k| must stay < 1 ({where}; the flange reaches "
        f"{w_max:g} across), got {profile.flange_width:.10g}"
    )


def fit_failure(exc: Exception, name: str, axis: Axis, reach: float) -> FitError:
    """A FitError of a stiffener's frame, saying how close to the limit it stands."""
    k_max, s_at = max_curvature(axis)
    return FitError(
        f"{name}: its frame, fitted to its farthest point {reach:.6g} from the axis (reach max|k| = "
        f"{reach * k_max:.4g} at s = {s_at:.6g}, which must stay < 1), did not reach the fit tolerance "
        f"(a lower height or a looser tolerance helps): {exc}"
    )


def spec_profile(section: dict) -> tuple[Profile, str] | None:
    """A [stiffeners] section's (profile, side), or None where they are faulty (those faults
    are left to the build, which names them)."""
    from tubecad.stiffeners.profiles import SIDES

    side = section.get("side", "outside")
    try:
        profile = Profile(
            section.get("profile", "flat"),
            section["height"],
            section["thickness"],
            section.get("flange_width", 0.0),
            section.get("flange_thickness", 0.0),
        )
    except (KeyError, TypeError, ParameterError):
        return None
    return (profile, side) if side in SIDES else None


def chosen_indices(section: dict, key: str, count: int) -> list[int]:
    """The valid indices a [stiffeners] key (``rings``, ``stringers``: a list or "all") picks."""
    value = section.get(key, [])
    indices = range(count) if value == "all" else value if isinstance(value, list) else []
    return [i for i in indices if isinstance(i, int) and 0 <= i < count]


def spec_stiffeners(
    section: dict, layout, span: tuple[float, float], profile: Profile
) -> tuple[list[tuple[float, float, float]], bool]:
    """What a [stiffeners] section stands on the wall: (s, lo, hi) for each ring it picks,
    [lo, hi] the ring's own width about s within ``span`` (where it sees the wall), and
    whether it picks any stringer."""
    s0, s1 = span
    w = [w for w, _ in profile.outline()]
    rings = []
    for i in chosen_indices(section, "rings", len(layout.s_rings)):
        s = float(layout.s_rings[i])
        lo, hi = max(s0, s + min(w)), min(s1, s + max(w))
        if hi > lo:
            rings.append((s, lo, hi))
    return rings, bool(chosen_indices(section, "stringers", len(layout.stringers_deg)))


def check_spec_heights(axis: Axis, layout, radii: tuple[float, float], section: dict) -> None:
    """A [stiffeners] section's height against the tube wall between ``radii`` = (r_in, r_out)
    on ``axis`` with ``layout`` (a NetLayout), before anything is built (ParameterError as
    :func:`checked_reach`). Other faults (keys, profile, indices) are left to the build."""
    picked = spec_profile(section)
    if picked is None:
        return
    profile, side = picked
    radius = radii[1] if side == "outside" else radii[0]
    rings, stringers = spec_stiffeners(section, layout, axis.span, profile)
    for _, lo, hi in rings:  # a ring sees the curvature over its own width
        checked_reach(axis.restricted((lo, hi)), profile, radius, side, "ring")
    if stringers:
        checked_reach(axis, profile, radius, side, "stringer")


def check_canal_spec_heights(
    surface: CurvatureLineSurface, layout, offsets: tuple[float, float], section: dict
) -> None:
    """A [stiffeners] section on the canal wall between the offsets (d_in, d_out) of
    ``surface``: each stiffener's own surfaces regular and off the axis
    (:func:`checked_levels`; a ring over its own width), before anything is built. Other
    faults are left to the build."""
    picked = spec_profile(section)
    if picked is None:
        return
    profile, side = picked
    sign, wall = (1.0, offsets[1]) if side == "outside" else (-1.0, offsets[0])
    levels = sorted({wall + sign * h for _, h in profile.outline()})
    rings, stringers = spec_stiffeners(section, layout, surface.span, profile)
    for s, lo, hi in rings:
        checked_levels(surface.restricted((lo, hi)), levels, f"the ring at s = {s:g}")
    if stringers:
        checked_levels(surface, levels, "a stringer")


def checked_levels(base: CurvatureLineSurface, levels: Sequence[float], name: str) -> dict[float, CurvatureLineSurface]:
    """The offsets r + d of ``base`` at ``levels``, each checked regular (a ParameterError
    naming ``height``: too high a stiffener folds its own surface, as on a tube
    (R + height) max|k| must stay < 1) and above MIN_SIZE."""
    out = {}
    for d in levels:
        if d == 0.0:
            out[d] = base
            continue
        law = base.radius_law
        if law.min_radius + d < MIN_SIZE:
            raise ParameterError(
                f"height: {name} reaches in to r {d:+g}, and the radius law's r is {law.min_radius:g} "
                f"at s = {law.s_at_min_radius:.6g}: r {d:+g} must stay >= {MIN_SIZE:g} (lower the "
                "stiffener)"
            )
        try:
            out[d] = base.offset(d)
        except RegularityError as exc:
            raise ParameterError(
                f"height: {name} reaches the canal surface of r {d:+g}, which is not regular "
                f"(lower the stiffener): {exc}"
            ) from None
    return out
