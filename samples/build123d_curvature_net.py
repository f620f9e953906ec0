"""build123d sample: the paper's curvature-line net as real build123d edges.

Ring frames (s = const) are exact circles in the axis' normal planes; stringers
(u = const) are splines through the exact points, with the exact tangents at both ends.
The script checks that every stringer crosses every ring at a right angle (the net is a
net of lines of curvature) and writes the net to STEP.

    python samples/build123d_curvature_net.py [OUT.step] [--rings 11] [--stringers 8]
"""

from __future__ import annotations

import argparse
import math

import numpy as np
from build123d import Compound, Edge, Plane, Vector, export_step

from tubecad import paper_tube


def ring_edge(tube, s: float) -> Edge:
    """The exact circle s = const: centre c(s), in the normal plane, through u = 0 at r1."""
    c = tube.axis.position(s)
    t, r1, _ = tube.axis.rotation_minimising_frame(s)
    plane = Plane(origin=Vector(*c), x_dir=Vector(*r1), z_dir=Vector(*t))
    return Edge.make_circle(tube.radius, plane)


def stringer_edge(tube, u: float, samples: int = 201) -> Edge:
    """The orthogonal trajectory u = const through exact points of S(u, s)."""
    s = np.linspace(*tube.span, samples)
    pts = tube.points(u, s)
    d = tube.derivatives(u, np.array(tube.span))
    tangents = [Vector(*(v / np.linalg.norm(v))) for v in d.S_s]
    return Edge.make_spline([Vector(*p) for p in pts], tangents=tangents)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="paper_net.step")
    parser.add_argument("--rings", type=int, default=11)
    parser.add_argument("--stringers", type=int, default=8)
    args = parser.parse_args()

    tube = paper_tube()
    s_rings = np.linspace(*tube.span, args.rings)
    u_stringers = 2 * math.pi * np.arange(args.stringers) / args.stringers
    rings = [ring_edge(tube, s) for s in s_rings]
    stringers = [stringer_edge(tube, u) for u in u_stringers]

    worst = 0.0
    for ring, s in zip(rings, s_rings):
        for stringer, u in zip(stringers, u_stringers):
            p = Vector(*tube.points(u, s))
            a = ring.tangent_at(ring.param_at_point(p))
            b = stringer.tangent_at(stringer.param_at_point(p))
            worst = max(worst, abs(a.dot(b)))
    net = Compound(children=rings + stringers)
    export_step(net, args.output)
    print(f"{len(rings)} rings x {len(stringers)} stringers -> {args.output}")
    print(f"max |cos| between ring and stringer tangents at the {len(rings) * len(stringers)} crossings: {worst:.2e}")


if __name__ == "__main__":
    main()
