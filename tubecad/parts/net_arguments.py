"""The keyword arguments of :class:`~tubecad.parts.net.CurvatureNet` (and of the CadQuery
plugin's ``curvatureNet``) made into the :class:`~tubecad.design.net.NetDesign` a ``[host]``
spec makes, checked once here for both: a ParameterError names the argument at fault."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from tubecad.brep.wall import WallSide
from tubecad.core.errors import ParameterError
from tubecad.design.model import WallChoice
from tubecad.design.net import PATCH_SURFACES, LineSelection, NetDesign, NetStiffenerChoice, PatchSurfaces
from tubecad.stiffeners.profiles import Profile, StiffenerSide

#: the families ``stiffened`` may name
FAMILIES = ("k1", "k2")


def net_part_design(
    face: Any,
    k1_lines: int | None,
    k2_lines: int | None,
    thickness: float,
    side: WallSide = "centered",
    k1_spacing: float | None = None,
    k2_spacing: float | None = None,
    seed: Sequence[float] | None = None,
    stiffened: Mapping[str, LineSelection | Sequence[int]] | None = None,
    profile: Profile | None = None,
    stiffener_side: StiffenerSide = "outside",
    patches: PatchSurfaces = "host",
) -> NetDesign:
    """The design of a net part's arguments (:class:`~tubecad.parts.net.CurvatureNet`'s).

    Args:
        face: the face.
        k1_lines: lines of family 1 (ignored with ``k1_spacing``).
        k2_lines: lines of family 2 (ignored with ``k2_spacing``).
        thickness: the wall's thickness.
        side: ``centered``, ``inside`` or ``outside`` of the face.
        k1_spacing: the k1 lines' spacing instead of their count.
        k2_spacing: the k2 lines' spacing.
        seed: a point (x, y, z) of the face the guide lines pass through.
        stiffened: ``{"k1": [indices] or "all", "k2": ...}``: the lines that carry webs.
        profile: the stiffeners' profile (flat bar, T or L).
        stiffener_side: ``outside`` or ``inside``.
        patches: the cells' surfaces, ``host`` or ``curvature``.

    Returns:
        The design, not built.

    Raises:
        ParameterError: naming the argument (``thickness``, ``side``, ``stiffened``,
            ``profile``, ``seed``, ``patches``).
    """
    if patches not in PATCH_SURFACES:
        raise ParameterError(f"patches must be one of {', '.join(PATCH_SURFACES)}, got {patches!r:.40}", key="patches")
    wall = WallChoice(thickness, side)
    try:
        wall.offsets()
    except ParameterError as exc:
        raise ParameterError(
            str(exc), key=exc.key or ("side" if str(exc).startswith("side") else "thickness")
        ) from None
    webs = None
    if stiffened is not None:
        unknown = [key for key in stiffened if key not in FAMILIES]
        if unknown:
            raise ParameterError(f"stiffened takes the families k1 and k2, got {unknown[0]!r:.40}", key="stiffened")
        k1, k2 = _picked(stiffened, "k1"), _picked(stiffened, "k2")
        if profile is None:
            raise ParameterError("profile: stiffened lines need the webs' profile", key="profile")
        webs = NetStiffenerChoice(profile, k1, k2, stiffener_side)
    if seed is not None and len(seed) != 3:
        raise ParameterError(f"seed must be a point (x, y, z), got {seed!r:.60}", key="seed")
    point = None if seed is None else (float(seed[0]), float(seed[1]), float(seed[2]))
    return NetDesign(
        face,
        None if k1_spacing is not None else k1_lines,
        None if k2_spacing is not None else k2_lines,
        k1_spacing,
        k2_spacing,
        point,
        wall,
        webs,
        patches=patches,
    )


def _picked(stiffened: Mapping[str, LineSelection | Sequence[int]], family: str) -> LineSelection:
    """``stiffened[family]`` as a selection: "all" or whole-number indices."""
    chosen = stiffened.get(family, ())
    if chosen == "all":
        return "all"
    if isinstance(chosen, str) or not all(isinstance(i, int) and not isinstance(i, bool) for i in chosen):
        raise ParameterError(
            f'stiffened["{family}"] must be "all" or line indices, got {chosen!r:.60}', key="stiffened"
        )
    return tuple(int(i) for i in chosen)
