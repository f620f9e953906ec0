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
left out, and so are the parameterisation's poles, for both. Each way is timed, best of 3.

Then whole nets on the samples' faces (``nets``): lines traced, made edges and the face split,
timed per face (best of 3; the issue's target: 2 s for 10 x 10 on a bicubic face) and as a
multiple of libigl's time above, each edge measured against OCCT's own principal directions
(``GeomLProp_SLProps``), the ellipsoid's umbilics against their closed form.
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
    out["nets"] = {name: _net(name, *counts, t_peer) for name, counts in NETS.items()}
    out["patches"] = {name: _patch(name, *cell) for name, cell in PATCHES.items()}
    out["patch_shells"] = {name: _patch_shell(name, *counts) for name, counts in SHELLS.items()}
    return out


#: the nets timed per face: the samples' faces and the lines per family
NETS = {"hull_panel": (10, 10), "dome": (10, 10), "ellipsoid": (6, 4)}


def _net(name: str, k1: int, k2: int, t_peer: float) -> dict:
    """A whole net on a sample's face (traced, made edges, the face split), best of 3, its time
    also as a multiple of libigl's directions on the ellipsoid's mesh above (same run); each
    edge's angle to the principal directions of OCCT's own ``GeomLProp_SLProps`` (not
    tubecad's field) at 60 points an edge, outside the umbilics' 2 % discs; on the ellipsoid
    the umbilics against their closed form (scaled to its 300 x 200 x 100)."""
    from OCP.BRep import BRep_Tool
    from OCP.GeomLProp import GeomLProp_SLProps
    from OCP.gp import gp_Dir

    from tubecad.export.cad import read_faces
    from tubecad.nets import curvature_net
    from tubecad.occ_compat import as_face

    face = as_face(read_faces(ROOT / "samples" / f"{name}.step")[0][1])
    net, seconds = timed(lambda: curvature_net(face, k1, k2))
    surface = BRep_Tool.Surface_s(face)
    size = float(
        np.ptp(np.array([e.curve.Value(e.curve.FirstParameter()).Coord() for e in net.edges.values()]), axis=0).max()
    )
    stops = np.array([p.point for p in net.umbilics.points]).reshape(-1, 3)
    worst = 0.0
    for line_name, edge in net.edges.items():
        for t in np.linspace(edge.curve.FirstParameter(), edge.curve.LastParameter(), 62)[1:-1]:
            point = edge.curve.Value(float(t))
            if len(stops) and np.linalg.norm(stops - np.array(point.Coord()), axis=1).min() < 0.02 * size:
                continue
            uv = edge.pcurve.Value(float(t))
            props = GeomLProp_SLProps(surface, uv.X(), uv.Y(), 2, 1e-9)
            if not props.IsCurvatureDefined() or props.IsUmbilic():
                continue
            d1, d2 = gp_Dir(), gp_Dir()
            props.CurvatureDirections(d1, d2)
            k1_is_max = props.MaxCurvature() >= props.MinCurvature()
            direction = np.array((d1 if (line_name.startswith("k1_") == k1_is_max) else d2).Coord())
            tangent = np.array(edge.curve.DN(float(t), 1).Coord())
            cross = np.linalg.norm(np.cross(tangent, direction))
            worst = max(worst, float(np.arctan2(cross, abs(tangent @ direction))))
    out = {
        "lines": [k1, k2],
        "seconds": seconds,
        "x_libigl_directions": seconds / t_peer,
        "patches": _faces(net.patches),
        "edge_angle_rad_vs_occt": worst,
    }
    if name == "ellipsoid":
        exact = umbilics(300.0, 200.0, 100.0)
        found = np.array([p.point for p in net.umbilics.points])
        error = max(float(np.linalg.norm(exact - f, axis=1).min()) for f in found) / 300.0
        out["umbilics"] = {"count": len(found), "relative_position_error": error}
    return out


#: one interior cell of each sample's net refitted in curvature-line coordinates: the net's
#: lines per family and the cell's two lines of each family
PATCHES = {
    "dome": ((4, 6), ("k1_01", "k1_02"), ("k2_01", "k2_02")),
    "hull_panel": ((6, 5), ("k1_02", "k1_03"), ("k2_01", "k2_02")),
}


def _patch(name: str, counts: tuple[int, int], k1: tuple[str, str], k2: tuple[str, str]) -> dict:
    """The cell refitted (:func:`tubecad.nets.patches.curvature_patch`, the grid chosen by its
    default target, degree 5), its figures measured on a grid four times finer than the fit's:
    the distance from the host (OCCT's projection), the isolines' angle to the principal
    directions, the poles, the time (once: the grids are traced anew each call)."""
    from tubecad.export.cad import read_faces
    from tubecad.nets import curvature_net
    from tubecad.nets.patches import curvature_patch
    from tubecad.occ_compat import as_face

    face = as_face(read_faces(ROOT / "samples" / f"{name}.step")[0][1])
    net = curvature_net(face, *counts)
    report = curvature_patch(net, k1, k2, degree=5).report()
    return {"net": list(counts), "cell": [*k1, *k2], **report}


#: the samples' nets made one shell of curvature-line patches (the nets of samples/*.toml)
SHELLS = {"dome": (6, 8), "hull_panel": (6, 5)}


def _patch_shell(name: str, k1: int, k2: int) -> dict:
    """The net's four-sided cells refitted and put in one shell
    (:func:`tubecad.nets.patch_shell.patch_shell`, its default target: 1e-8 of the face's size
    and 1e-6 rad): the time (once), how many cells were refitted and why the others were kept,
    the worst figures over the refitted ones, the poles."""
    from tubecad.export.cad import read_faces
    from tubecad.nets import curvature_net
    from tubecad.nets.patch_shell import patch_shell
    from tubecad.occ_compat import as_face

    face = as_face(read_faces(ROOT / "samples" / f"{name}.step")[0][1])
    net = curvature_net(face, k1, k2)
    shell, seconds = timed(lambda: patch_shell(net), repeats=1)
    report = shell.report()
    kept: dict[str, int] = {}
    for reason in report["kept"].values():
        kept[reason.split(":")[0]] = kept.get(reason.split(":")[0], 0) + 1
    return {
        "net": [k1, k2],
        "seconds": seconds,
        "refitted": len(report["refitted"]),
        "kept": kept,
        "worst": {key: report[key] for key in ("distance", "angle", "F", "M", "edge_tolerance")},
        "poles": sorted({tuple(f["poles"]) for f in report["refitted"].values()}),
    }


def _faces(shape) -> int:
    from tubecad.brep.properties import count

    return count(shape, "face")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, help="write the results here too")
    args = parser.parse_args()
    result = main()
    text = json.dumps(result, indent=2)
    print(text)
    if args.json:
        args.json.write_text(text + "\n")
