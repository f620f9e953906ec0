"""The shop's settings (the spec's ``[fabrication]`` section): plate size, kerf, joint gap,
strain limit, pin spacing and chosen butt joints, in the model's length unit.

One place for the defaults: they are stated in millimetres and converted to the spec's
[units] length, so that a spec in metres gets the same plates as one in millimetres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT, length_unit

#: defaults in millimetres (converted to the model's unit by :func:`fabrication_settings`)
DEFAULT_PLATE_MM = (3000.0, 1500.0)  # a common steel plate, length x width
DEFAULT_KERF_MM = 2.0  # plasma or laser
DEFAULT_JOINT_GAP_MM = 0.0  # butt joints closed (a root gap opens them)
DEFAULT_MAX_STRAIN = 0.01  # panels whose development strains more are flagged
#: a bent profile's table must bend back onto the exact line within this (issue 13)
BEND_BACK_MM = 0.1


@dataclass(frozen=True)
class Fabrication:
    """Checked shop settings, lengths in the model's unit.

    ``plate_size``: (length, width) of the stock plates webs are nested on; ``kerf``: the
    cut's width (parts lie 2 kerf apart and a kerf from the plate's edge, so each cut path,
    kerf / 2 outside its part, clears its neighbours); ``joint_gap``: a butt joint's root
    gap, measured along the web's base line; ``max_strain``: panels whose development
    strains more are flagged; ``pin_spacing``: the pin-jig grid (None: chosen per panel);
    ``pin_clearance``: the panel's lowest point above the jig plane; ``joints``: chosen
    butt joints per stiffener (s along a stringer, degrees round a ring)."""

    plate_size: tuple[float, float]
    kerf: float
    joint_gap: float
    max_strain: float = DEFAULT_MAX_STRAIN
    pin_spacing: float | None = None
    pin_clearance: float = 0.0
    joints: dict[str, tuple[float, ...]] = field(default_factory=dict)
    length_unit: str = DEFAULT_LENGTH_UNIT

    @property
    def bend_back_tolerance(self) -> float:
        """0.1 mm in the model's unit."""
        return BEND_BACK_MM / length_unit(self.length_unit).mm

    @property
    def usable(self) -> tuple[float, float]:
        """The plate less a kerf at every edge: the largest part that fits, (long, short)."""
        a, b = sorted(self.plate_size, reverse=True)
        return a - 2 * self.kerf, b - 2 * self.kerf


def _finite(key: str, value: object, low: float, low_open: bool, what: str) -> float:
    if (
        isinstance(value, bool)
        or not isinstance(value, (int, float))
        or not math.isfinite(value)
        or (value <= low if low_open else value < low)
    ):
        bound = f"> {low:g}" if low_open else f">= {low:g}"
        raise ParameterError(f"{key} must be a finite number {bound} ({what}), got {value!r:.40}", key=key)
    return float(value)


def fabrication_settings(section: dict | None = None, unit: str = DEFAULT_LENGTH_UNIT) -> Fabrication:
    """The ``[fabrication]`` section checked, with the defaults for absent keys; a
    ParameterError names the key and its allowed range."""
    section = dict(section or {})
    mm = length_unit(unit).mm
    plate = section.get("plate_size", [v / mm for v in DEFAULT_PLATE_MM])
    if not (isinstance(plate, (list, tuple)) and len(plate) == 2):
        raise ParameterError(
            f"plate_size must be [length, width], two numbers > 0, got {plate!r:.60}", key="plate_size"
        )
    plate = tuple(_finite("plate_size", v, 0.0, True, "[length, width] of the stock plate") for v in plate)
    kerf = _finite("kerf", section.get("kerf", DEFAULT_KERF_MM / mm), 0.0, False, "the cut's width")
    gap = _finite(
        "joint_gap", section.get("joint_gap", DEFAULT_JOINT_GAP_MM / mm), 0.0, False, "a butt joint's root gap"
    )
    strain = _finite(
        "max_strain",
        section.get("max_strain", DEFAULT_MAX_STRAIN),
        0.0,
        True,
        "the panel development's largest strain allowed, e.g. 0.01 for 1 %",
    )
    pins = section.get("pin_spacing")
    if pins is not None:
        pins = _finite("pin_spacing", pins, 0.0, True, "the pin-jig grid's spacing")
    clearance = _finite(
        "pin_clearance", section.get("pin_clearance", 0.0), 0.0, False, "the panel's lowest point above the jig plane"
    )
    if min(plate) <= 2 * kerf:
        raise ParameterError(
            f"plate_size {list(plate)} leaves no room inside a kerf of {kerf:g} "
            f"at its edges: its sides must exceed 2 kerf = {2 * kerf:g}",
            key="plate_size",
        )
    joints = section.get("joints", {})
    if not isinstance(joints, dict):
        raise ParameterError(
            f"joints must be a table of stiffener name = [positions], got {joints!r:.60}", key="joints"
        )
    checked = {}
    for name, values in joints.items():
        if not (isinstance(values, list) and values):
            raise ParameterError(
                f"joints.{name} must be a non-empty list of positions, got {values!r:.60}", key=f"joints.{name}"
            )
        checked[name] = tuple(
            _finite(f"joints.{name}", v, -math.inf, True, "s along a stringer, degrees round a ring") for v in values
        )
    return Fabrication(plate, kerf, gap, strain, pins, clearance, checked, unit)
