"""build123d sample: a curvature-line wall with stiffeners around a spline Edge of a model.

    python samples/build123d_spline_wall.py [OUT.step]

The centreline is an ordinary build123d Spline (any Edge or Wire of a model works, or an
edge read from another CAD system's STEP file). tubecad follows it with its
rotation-minimising frame: the ring frames are circles and the stringers the curves of
constant angle against that frame, so all the wall's edges are lines of curvature. Four
T ring frames stand on the outside; the named assembly (wall, ring_XX, curvature_lines)
is written to STEP.
"""

from __future__ import annotations

import sys

import build123d as bd

from tubecad import CurvatureLineTube, edge_axis
from tubecad.brep import NetLayout, build_wall_solid
from tubecad.export.cad import export_named_step
from tubecad.stiffeners import net_lines
from tubecad.stiffeners.assembly import build_stiffeners, named_assembly
from tubecad.stiffeners.profiles import Profile


def main() -> None:
    output = sys.argv[1] if len(sys.argv) > 1 else "spline_wall.step"
    with bd.BuildLine() as model:  # the centreline, as it would come from a model
        bd.Spline((0, 0, 0), (60, 25, 10), (120, 10, 45), (180, -30, 40), (230, -20, 0))
    centreline = model.edges()[0]

    axis = edge_axis(centreline)
    print(
        f"axis: {axis.length:.6f} long (the edge: {centreline.length:.6f}), joints at the spline's knots: "
        f"{len(axis.joints)}"
    )
    tube = CurvatureLineTube(axis, 6.0)
    build = build_wall_solid(tube, 0.8, "outside", NetLayout.equal(tube, rings=9, stringers=8))
    print(
        f"wall: valid={build.shape.is_valid}, {len(build.shape.faces())} faces, "
        f"fit deviation {build.frame.position_bound:.1e}, poles along the axis {build.frame.poles}"
    )
    stiffeners = build_stiffeners(
        build,
        [1, 3, 5, 7],
        [],
        Profile("T", height=4.0, thickness=0.8, flange_width=3.0, flange_thickness=0.8),
        "outside",
    )
    lines = net_lines(build.surfaces[0], build.layout)
    assembly = named_assembly(build, stiffeners, lines)
    print(
        f"stiffeners: {', '.join(st.name for st in stiffeners)}; all valid: "
        f"{all(st.solid.is_valid for st in stiffeners)}"
    )
    print(f"written {export_named_step(assembly, output)}")


if __name__ == "__main__":
    main()
