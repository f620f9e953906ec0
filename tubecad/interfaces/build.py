"""From a checked spec to B-rep: layout, wall and fit sections (README, "Spec files")."""

from __future__ import annotations

from typing import Any

from ..brep import NetLayout, TubeBuild, build_tube_solid, build_wall_solid
from ..brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS
from ..brep.solids import DEFAULT_TOLERANCE
from ..errors import ParameterError, RegularityError, SpecError
from ..fitting import FitError
from ..surface import CurvatureLineTube
from .spec import TubeSpec


def layout_from_section(tube: CurvatureLineTube, section: dict[str, Any]) -> NetLayout:
    """[layout]: rings / stringers counts, or s_rings / u_stringers_deg lists."""
    import numpy as np

    if "s_rings" in section:
        s_rings = section["s_rings"]
    else:
        rings = section.get("rings", DEFAULT_RINGS)
        NetLayout.equal(tube, rings, 1)  # checks the count
        s_rings = np.linspace(*tube.span, rings)
    if "u_stringers_deg" in section:
        angles = section["u_stringers_deg"]
    else:
        stringers = section.get("stringers", DEFAULT_STRINGERS)
        NetLayout.equal(tube, 2, stringers)
        angles = 360.0 * np.arange(stringers) / stringers
    return NetLayout.explicit(tube, s_rings, angles)


def build_from_spec(spec: TubeSpec) -> TubeBuild:
    """The wall solid if the spec has [wall], else the capped tube solid."""
    tube = spec.tube
    try:
        layout = layout_from_section(tube, spec.sections.get("layout", {}))
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [layout] {exc}") from None
    tolerance = spec.sections.get("fit", {}).get("tolerance", DEFAULT_TOLERANCE)
    wall = spec.sections.get("wall")
    try:
        if wall is None:
            return build_tube_solid(tube, layout, tolerance)
        return build_wall_solid(tube, wall["thickness"], wall.get("side", "centered"), layout, tolerance)
    except FitError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}") from None
    except RegularityError as exc:
        raise SpecError(f"{spec.source}: [wall] the wall's outer surface is not regular: {exc}") from None
    except ParameterError as exc:
        section = "[fit]" if "tolerance" in str(exc) else "[wall]"
        raise SpecError(f"{spec.source}: {section} {exc}") from None
