"""Stiffener sets on a wall and the named STEP assembly handed downstream (issue 4).

The assembly is a build123d Compound: ``wall`` (or its panels ``panel_r0_s1``, ...), one
solid per stiffener (``ring_03``, ``stringer_05``), and ``curvature_lines`` with one
labelled edge per line (``line_ring_03``, ``line_stringer_05``, ``..._inner``): every name
unique. Written with OCCT's XCAF STEP writer (tubecad.export.cad.write_step), so names and
colours show in a downstream CAD tree, under a top product named after the file.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import build123d as bd

from tubecad.brep import TubeBuild
from tubecad.core.errors import ParameterError
from tubecad.core.tolerance import DEFAULT_FIT_TOLERANCE
from tubecad.stiffeners.lines import CurvatureLine, lines_compound
from tubecad.stiffeners.profiles import Profile
from tubecad.stiffeners.solids import Stiffener, ring_stiffener, stringer_stiffener
from tubecad.surface import CurvatureLineSurface

WALL_COLOUR = bd.Color(0.62, 0.68, 0.78)
RING_COLOUR = bd.Color(0.85, 0.45, 0.20)
STRINGER_COLOUR = bd.Color(0.25, 0.55, 0.35)


def build_stiffeners(
    build: TubeBuild,
    rings: Sequence[int],
    stringers: Sequence[int],
    profile: Profile,
    side: str = "outside",
    tolerance: float = DEFAULT_FIT_TOLERANCE,
    progress: Callable[[str, int, int], None] | None = None,
) -> list[Stiffener]:
    """Stiffeners on the wall of ``build`` at the layout's ring indices ``rings`` and stringer
    indices ``stringers``, standing on its outer (``outside``) or inner (``inside``) surface.
    ``progress(name, done, total)`` is called after each one (e.g. ``('ring_02', 2, 9)``)."""
    layout = build.layout
    base = stiffener_base(build, side)
    for name, chosen, count in (
        ("rings", rings, len(layout.s_rings)),
        ("stringers", stringers, len(layout.stringers_deg)),
    ):
        bad = [i for i in chosen if not (isinstance(i, int) and 0 <= i < count)]
        if bad:
            raise ParameterError(f"stiffener {name} must be indices in [0, {count - 1}], got {bad}")
    rings = distinct_rings(build, rings)
    makers = [
        lambda i=i: ring_stiffener(base, layout.s_rings[i], profile, side, tolerance, f"ring_{i:02d}") for i in rings
    ]
    makers += [
        lambda j=j: stringer_stiffener(
            base, layout.stringers_deg[j], profile, side, tolerance=tolerance, name=f"stringer_{j:02d}"
        )
        for j in stringers
    ]
    out = []
    for make in makers:
        out.append(make())
        if progress is not None:
            progress(out[-1].name, len(out), len(makers))
    return out


def stiffener_base(build: TubeBuild, side: str) -> CurvatureLineSurface:
    """The wall surface stiffeners on ``side`` stand on: the outer (outside) or the inner
    (inside) one: the exact surface that face was fitted to (the tube of its radius, or a
    canal wall's exact offset canal surface)."""
    surface = build.surfaces[0] if side == "outside" else build.surfaces[-1]
    return surface.tube


def distinct_rings(build: TubeBuild, rings: Sequence[int]) -> list[int]:
    """The ring indices ``rings``, each ring once: on a closed tube the last ring of the
    layout is the first one (the closing ring), so its index becomes 0."""
    last = len(build.layout.s_rings) - 1
    closed = build.surfaces[0].tube.axis.closed
    return list(dict.fromkeys(0 if closed and i == last else i for i in rings))


def stiffener_solids(stiffeners: Sequence[Stiffener]) -> list[bd.Solid]:
    """Each stiffener as a new labelled, coloured solid (its own shape is not put under an assembly)."""
    out = []
    for st in stiffeners:
        solid = bd.Solid(st.solid.wrapped)
        solid.label, solid.color = st.name, RING_COLOUR if st.kind == "ring" else STRINGER_COLOUR
        out.append(solid)
    return out


def named_assembly(
    build: TubeBuild,
    stiffeners: Sequence[Stiffener],
    lines: Sequence[CurvatureLine] = (),
    fuse: bool = False,
    panels: Sequence = (),
) -> bd.Compound:
    """``wall`` and the stiffeners as labelled, coloured solids (or, with ``fuse``, one solid
    ``wall`` with the stiffeners merged in), plus the ``curvature_lines``. With ``panels``
    the wall is an assembly ``wall`` of the panels ``panel_r0_s0``, ... (not fused)."""
    wall = bd.Solid(build.shape.wrapped)  # a new node: the build's own shape is not put under the assembly
    children: list[bd.Shape] = []
    if panels:
        parts = []
        for p in panels:
            solid = bd.Solid(p.solid.wrapped)
            solid.label, solid.color = p.name, WALL_COLOUR
            parts.append(solid)
        wall = bd.Compound(children=parts)
        fuse = False
    if fuse and stiffeners:
        wall = wall.fuse(*[st.solid for st in stiffeners]).clean()
    else:
        children += stiffener_solids(stiffeners)
    wall.label, wall.color = "wall", WALL_COLOUR
    children.insert(0, wall)
    if lines:
        curves = lines_compound(list(lines))
        curves.label = "curvature_lines"
        children.append(curves)
    return bd.Compound(label="tubecad", children=children)
