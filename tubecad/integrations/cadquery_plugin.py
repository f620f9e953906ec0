"""CadQuery Workplane plugin: curvature-line tubes and walls on the Workplane stack.

    import cadquery as cq
    import tubecad.integrations.cadquery_plugin  # registers the methods
    wall = cq.Workplane().curvatureLineWall(tube, thickness=2.0, rings=11, stringers=8)

The solids are in the tube's own (global) coordinates, as built; they are cq.Solid objects
whose faces are bounded by the chosen ring frames and stringers.
"""

from __future__ import annotations

try:
    import cadquery as cq
except ImportError as exc:  # CadQuery is an extra: it pins OCP 7.9, build123d 0.13 needs OCP 8
    raise ImportError(
        "tubecad's CadQuery plugin needs CadQuery: pip install 'tubecad[cadquery]' "
        "(CadQuery 2.8 runs on OCP 7.9, so it brings build123d 0.12)"
    ) from exc

from tubecad.brep import NetLayout, build_tube_solid, build_wall_solid
from tubecad.brep.layout import DEFAULT_RINGS, DEFAULT_STRINGERS
from tubecad.core.tolerance import DEFAULT_TOLERANCE
from tubecad.surface import CurvatureLineTube


def curvature_line_tube(
    self: cq.Workplane,
    tube: CurvatureLineTube,
    rings: int = DEFAULT_RINGS,
    stringers: int = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
) -> cq.Workplane:
    """Push the capped tube solid of ``tube`` onto the stack."""
    build = build_tube_solid(tube, NetLayout.equal(tube, rings, stringers), tolerance)
    return self.newObject([cq.Solid(build.shape.wrapped)])


def curvature_line_wall(
    self: cq.Workplane,
    tube: CurvatureLineTube,
    thickness: float,
    side: str = "centered",
    rings: int = DEFAULT_RINGS,
    stringers: int = DEFAULT_STRINGERS,
    tolerance: float = DEFAULT_TOLERANCE,
) -> cq.Workplane:
    """Push the wall solid (inner and outer curvature-line tubes, annular caps) onto the stack."""
    build = build_wall_solid(tube, thickness, side, NetLayout.equal(tube, rings, stringers), tolerance)
    return self.newObject([cq.Solid(build.shape.wrapped)])


# the plugin's methods, patched onto Workplane (CadQuery's plugin convention; its class does not declare them)
cq.Workplane.curvatureLineTube = curvature_line_tube  # type: ignore[attr-defined,unused-ignore]
cq.Workplane.curvatureLineWall = curvature_line_wall  # type: ignore[attr-defined,unused-ignore]
