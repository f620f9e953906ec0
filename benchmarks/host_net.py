"""Principal directions on a user's surface: tubecad's exact field beside a mesh tool's (issue 44).

``python benchmarks/host_net.py [--json FILE]`` (the peer: ``pip install libigl``). The surface:
the triaxial ellipsoid (30, 20, 10) as an exact NURBS (OCCT's sphere, its poles scaled:
tests/shared/ellipsoid.py), meshed by OCCT (``BRepMesh_IncrementalMesh``) to about 40,000
nodes. At every node both ways give the k1 direction:

- **libigl**: ``igl.principal_curvature`` on the triangle mesh (quadric fitting on the
  vertices' two-ring neighbourhoods), what mesh-based layout tools start from;
- **tubecad**: :func:`tubecad.nets.principal_field` on the exact surface at the node's (u, v).

Both are measured against the closed form, the tangent of the confocal quadric through the
node (Dupin), as the angle to the nearer of its two line directions; nodes within 2 % of the
size of an umbilic (where the directions turn fastest, and a mesh method is least defined) and
on the symmetry planes (where the closed form's formula is 0 / 0: it cannot judge them) are
left out, and so are the parameterisation's poles, for both. Each way is timed, best of 3. Lines of curvature traced and made edges are
measured by tests/unit/nets (1e-9 rad, 9.5e-9 next to an umbilic).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from shared.ellipsoid import curvature_directions, nurbs_ellipsoid, umbilics  # noqa: E402
from tee import timed  # noqa: E402

from tubecad.nets import HostSurface, principal_field  # noqa: E402

A, B, C = 30.0, 20.0, 10.0
#: the mesh's linear deflection, chosen for about 40,000 nodes
DEFLECTION = 0.004


def _mesh() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(nodes (n, 3), triangles (m, 3), the nodes' (u, v)) of OCCT's mesh of the ellipsoid,
    its seam's and poles' duplicate nodes merged (a closed mesh for the peer)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.TopLoc import TopLoc_Location
    from scipy.spatial import cKDTree

    face = BRepBuilderAPI_MakeFace(nurbs_ellipsoid(A, B, C), 1e-7).Face()
    BRepMesh_IncrementalMesh(face, DEFLECTION, False, 0.1, True)
    mesh = BRep_Tool.Triangulation_s(face, TopLoc_Location())
    n = mesh.NbNodes()
    nodes = np.array([[mesh.Node(i).X(), mesh.Node(i).Y(), mesh.Node(i).Z()] for i in range(1, n + 1)])
    uv = np.array([[mesh.UVNode(i).X(), mesh.UVNode(i).Y()] for i in range(1, n + 1)])
    triangles = np.array([mesh.Triangle(i).Get() for i in range(1, mesh.NbTriangles() + 1)]) - 1
    # merge the nodes the seam and the poles repeat
    tree = cKDTree(nodes)
    first = np.arange(n)
    for i, j in sorted(tree.query_pairs(1e-9 * A)):
        first[j] = min(first[j], first[i])
    keep, index = np.unique(first, return_inverse=True)
    triangles = index[triangles]
    triangles = triangles[
        (triangles[:, 0] != triangles[:, 1])
        & (triangles[:, 1] != triangles[:, 2])
        & (triangles[:, 0] != triangles[:, 2])
    ]
    return nodes[keep], triangles, uv[keep]


def _angle(d: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The angle to the nearer closed-form line direction (NaN on the symmetry planes, where
    a confocal parameter meets a^2, b^2 or c^2 and the closed form divides by zero)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = curvature_directions(points, A, B, C)

    def between(p: np.ndarray, q: np.ndarray) -> np.ndarray:
        return np.arctan2(np.linalg.norm(np.cross(p, q), axis=1), np.abs(np.einsum("nk,nk->n", p, q)))

    with np.errstate(invalid="ignore"):
        return np.minimum(between(d, t1), between(d, t2))


def _version(package: str) -> str:
    from importlib.metadata import version

    return version(package)


def _stats(angle: np.ndarray) -> dict[str, float]:
    angle = angle[np.isfinite(angle)]
    return {
        "nodes": int(angle.size),
        "p50": float(np.median(angle)),
        "p95": float(np.percentile(angle, 95)),
        "max": float(angle.max()),
    }


def main() -> dict:
    nodes, triangles, uv = _mesh()
    near = np.min(np.linalg.norm(nodes[:, None, :] - umbilics(A, B, C)[None], axis=-1), axis=1) < 0.02 * 2 * A
    # on a symmetry plane a confocal parameter is a^2, b^2 or c^2: the closed form's limit is
    # the plane itself, which its formula does not reach (0 / 0); counted apart
    near |= (np.abs(nodes) < 1e-6 * A).any(axis=1)
    poles = np.abs(np.abs(uv[:, 1]) - np.pi / 2) < 1e-9  # the parameterisation's poles: no (u, v) direction
    host = HostSurface.of_surface(nurbs_ellipsoid(A, B, C))
    field, t_ours = timed(lambda: principal_field(host, uv[:, 0], uv[:, 1]))
    ours = _angle(field.d1, host.jet(uv[:, 0], uv[:, 1]).X)
    out: dict = {
        "surface": "NURBS ellipsoid (30, 20, 10)",
        "nodes": int(len(nodes)),
        "triangles": int(len(triangles)),
        "left_out": {"near_umbilics_or_on_symmetry_planes": int(near.sum()), "at_the_poles": int(poles.sum())},
        "tubecad": {
            "seconds": t_ours,
            "angle_rad": _stats(ours[~near & ~poles]),
        },
    }
    try:
        import igl
    except ImportError:
        out["libigl"] = "not installed (pip install libigl)"
        return out
    result, t_peer = timed(lambda: igl.principal_curvature(nodes, triangles.astype(np.int64)))
    pd1 = result[0]
    peer = _angle(pd1 / np.linalg.norm(pd1, axis=1, keepdims=True), nodes)
    out["libigl"] = {
        "version": _version("libigl"),
        "seconds": t_peer,
        "angle_rad": _stats(peer[~near & ~poles]),
    }
    return out


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, help="write the results here too")
    args = parser.parse_args()
    result = main()
    text = json.dumps(result, indent=2)
    print(text)
    if args.json:
        args.json.write_text(text + "\n")
