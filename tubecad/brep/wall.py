"""Where a wall of given thickness lies around the tube: its inner and outer radii.

Light on purpose (no OCCT): the spec checker uses it before anything is built."""

from __future__ import annotations

from typing import Literal, TypeAlias, get_args

from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import MIN_SIZE
from tubecad.core.validation import bounded_length

#: where a wall lies on its surface: astride it, inside it (towards the axis) or outside it
WallSide: TypeAlias = Literal["centered", "inside", "outside"]
WALL_SIDES: tuple[str, ...] = get_args(WallSide)


def as_wall_side(side: str) -> WallSide:
    """``side`` as a :data:`WallSide`; a ParameterError (key ``side``) naming the allowed ones."""
    for allowed in get_args(WallSide):
        if side == allowed:
            return allowed
    raise ParameterError(f"side must be one of {', '.join(WALL_SIDES)}, got {side!r:.80}", key="side")


def wall_offsets(thickness: float, side: str) -> tuple[float, float]:
    """(d_in, d_out): where the wall's inner and outer surfaces lie from the surface, along
    its normal: centered (-t/2, t/2), inside (-t, 0) or outside (0, t). A canal surface's
    wall is bounded by the canal surfaces of r + d_in and r + d_out."""
    thickness = bounded_length("thickness", thickness, 0.0)
    if not isinstance(side, str) or side not in WALL_SIDES:
        raise ParameterError(f"side must be one of {', '.join(WALL_SIDES)}, got {side!r:.80}")
    if thickness < MIN_SIZE:
        raise ParameterError(
            f"thickness must be >= {MIN_SIZE:g} model units (100 x OCCT's edge precision 1e-7), got {thickness:g}"
        )
    return {"centered": (-thickness / 2, thickness / 2), "inside": (-thickness, 0.0), "outside": (0.0, thickness)}[side]


def wall_radii(radius: float, thickness: float, side: str) -> tuple[float, float]:
    """(r_in, r_out) of a wall of ``thickness`` placed ``side`` of the tube of ``radius``:
    centered (rho -+ t/2), inside (rho - t, rho) or outside (rho, rho + t)."""
    d_in, d_out = wall_offsets(thickness, side)
    thickness = d_out - d_in
    r_in, r_out = radius + d_in, radius + d_out
    if r_in < MIN_SIZE:
        if side == "outside":
            raise ParameterError(f"radius must be >= {MIN_SIZE:g} model units for a B-rep, got {radius:g}")
        limit = {"centered": 2 * radius, "inside": radius}[side]
        raise ParameterError(
            f"thickness must be < {limit:g} for side = {side!r} (radius {radius:g}; the inner "
            f"radius must stay >= {MIN_SIZE:g}), got {thickness:g}"
        )
    return r_in, r_out
