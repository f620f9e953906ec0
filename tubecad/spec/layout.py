"""The [layout] section of a spec: which curvature lines become B-rep edges
(:class:`~tubecad.spec.model.LayoutSection`, its rule :meth:`~tubecad.spec.model.LayoutSection.net`).

Light on purpose (no OCCT): the spec checker uses it before anything is built."""

from __future__ import annotations

from typing import Any

from tubecad.brep.layout import NetLayout
from tubecad.spec.model import LayoutSection
from tubecad.surface import CurvatureLineTube


def layout_from_section(tube: CurvatureLineTube, section: LayoutSection | dict[str, Any]) -> NetLayout:
    """[layout]: rings / stringers counts, or s_rings / u_stringers_deg lists (a checked
    table, as a spec file gives it, or the typed section)."""
    if not isinstance(section, LayoutSection):
        section = LayoutSection(**section)
    return section.net(tube)
