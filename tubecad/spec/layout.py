"""The [layout] section of a spec: which curvature lines become B-rep edges.

Light on purpose (no OCCT): the spec checker uses it before anything is built."""

from __future__ import annotations

from typing import Any

import numpy as np

from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS, NetLayout
from tubecad.surface import CurvatureLineTube


def layout_from_section(tube: CurvatureLineTube, section: dict[str, Any]) -> NetLayout:
    """[layout]: rings / stringers counts, or s_rings / u_stringers_deg lists."""
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
