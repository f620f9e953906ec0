"""CadQuery sample: a helical duct wall (curvature-line edges) on the Workplane stack, to STEP.

python samples/cadquery_wall.py [OUT.step]
"""

from __future__ import annotations

import sys

import cadquery as cq

import tubecad.integrations.cadquery_plugin  # noqa: F401  (registers Workplane.curvatureWall)
from tubecad import Helix


def main() -> None:
    output = sys.argv[1] if len(sys.argv) > 1 else "helix_wall.step"
    # A helical duct: cylinder radius 100, pitch 65, tube radius 12, wall 1.5 outside.
    axis = Helix.from_radius_pitch(100.0, 65.0, (0.0, 1200.0))
    duct = cq.Workplane().curvatureWall(axis, radius=12.0, thickness=1.5, side="outside", rings=13, stringers=6)
    solid = duct.val()
    print(f"duct: valid={solid.isValid()}, {len(solid.Faces())} faces, volume {solid.Volume():.4f}")
    cq.exporters.export(duct, output)
    print(f"written {output}")


if __name__ == "__main__":
    main()
