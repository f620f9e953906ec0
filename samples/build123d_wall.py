"""build123d sample: the paper's wall solid, its curvature-line edges, a cut, and STEP.

    python samples/build123d_wall.py [OUT.step]

The wall (radii 14 and 16 around the paper's axis) has 11 ring frames and 8 stringers
as B-rep edges. It is an ordinary build123d Solid: here a hand hole is cut through it
with a build123d boolean, and the result is written to STEP.
"""

from __future__ import annotations

import sys

import numpy as np
from build123d import Cylinder, Location, Plane, Vector, export_step

from tubecad.brep import NetLayout, wall_solid
from tubecad.spec.paper import paper_tube


def main() -> None:
    output = sys.argv[1] if len(sys.argv) > 1 else "paper_wall.step"
    tube = paper_tube()
    wall = wall_solid(tube, thickness=2.0, side="centered", layout=NetLayout.equal(tube, rings=11, stringers=8))
    print(
        f"wall: valid={wall.is_valid}, {len(wall.faces())} faces, {len(wall.edges())} edges, volume {wall.volume:.6f}"
    )
    print(f"exact volume pi (16^2 - 14^2) L = {np.pi * (16**2 - 14**2) * tube.length:.6f}")

    # A hand hole of diameter 8 through the wall at s = 650, between two ring frames, on the
    # outward normal of the surface at u = 0.3 rad.
    s, u = 650.0, 0.3
    centre = tube.points(u, s)
    normal = tube.normal(u, s)
    hole = Plane(origin=Vector(*centre), z_dir=Vector(*normal)) * Location((0, 0, 0)) * Cylinder(4.0, 8.0)
    cut = wall - hole
    print(f"with hand hole: valid={cut.is_valid}, volume removed {wall.volume - cut.volume:.4f}")
    export_step(cut, output)
    print(f"written {output}")


if __name__ == "__main__":
    main()
