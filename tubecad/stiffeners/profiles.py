"""Stiffener cross-sections: flat bar, T and L (issue 4).

A profile is drawn in the stiffener's own plane: w across the web (the wall's tangent
direction across the line), and h outward from the wall along the surface normal.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, TypeAlias, get_args

from tubecad.core.errors import ParameterError
from tubecad.core.validation import number_in_range

#: a stiffener's cross-section
ProfileKind: TypeAlias = Literal["flat", "T", "L"]
KINDS: tuple[str, ...] = get_args(ProfileKind)
#: which side of the wall a stiffener stands on
StiffenerSide: TypeAlias = Literal["outside", "inside"]
SIDES: tuple[str, ...] = get_args(StiffenerSide)


def as_stiffener_side(side: str) -> StiffenerSide:
    """``side`` as a :data:`StiffenerSide`; a ParameterError (key ``side``) naming the allowed ones."""
    for allowed in get_args(StiffenerSide):
        if side == allowed:
            return allowed
    raise ParameterError(f"side must be one of {', '.join(SIDES)}, got {side!r:.80}", key="side")


@dataclass(frozen=True)
class Profile:
    """``kind`` flat | T | L; web ``height`` (from the wall) and ``thickness``; for T and L
    a flange of ``flange_width`` (total, across) and ``flange_thickness`` at the top.

    Args:
        kind: ``flat``, ``T`` or ``L``.
        height: the web's height from the wall (model units, > 0).
        thickness: the web's thickness (> 0).
        flange_width: for T and L, the flange's total width across (> ``thickness``).
        flange_thickness: for T and L, the flange's thickness at the top (in (0, ``height``]).

    Raises:
        ParameterError: a kind or size out of range, naming it.
    """

    kind: str = "flat"
    height: float = 10.0
    thickness: float = 1.0
    flange_width: float = 0.0
    flange_thickness: float = 0.0

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ParameterError(f"profile must be one of {', '.join(KINDS)}, got {self.kind!r}")
        number_in_range("height", self.height, 0.0)
        number_in_range("thickness", self.thickness, 0.0)
        if self.kind != "flat":
            number_in_range("flange_thickness", self.flange_thickness, 0.0, self.height)
            if not self.flange_width > self.thickness:
                raise ParameterError(
                    f"flange_width must be > thickness ({self.thickness:g}) for a {self.kind} profile, "
                    f"got {self.flange_width:g}"
                )

    @property
    def web_height(self) -> float:
        """The web plate's height: a flat bar's whole height, a T's or L's up to its flange
        (the flange plate, ``flange_thickness``, sits on it)."""
        return self.height if self.kind == "flat" else self.height - self.flange_thickness

    def outline(self) -> list[tuple[float, float]]:
        """(w, h) corners from the base's +w corner round to its -w corner (the base itself,
        which follows the wall, closes the outline)."""
        tw, h = self.thickness / 2, self.height
        if self.kind == "flat":
            return [(tw, 0.0), (tw, h), (-tw, h), (-tw, 0.0)]
        hf, bf = h - self.flange_thickness, self.flange_width
        if self.kind == "T":
            return [(tw, 0.0), (tw, hf), (bf / 2, hf), (bf / 2, h), (-bf / 2, h), (-bf / 2, hf), (-tw, hf), (-tw, 0.0)]
        return [(tw, 0.0), (tw, hf), (-tw + bf, hf), (-tw + bf, h), (-tw, h), (-tw, 0.0)]  # L: flange to +w

    @property
    def area(self) -> float:
        """Cross-section area on a flat base."""
        web = self.thickness * self.height
        if self.kind == "flat":
            return web
        return web + (self.flange_width - self.thickness) * self.flange_thickness
