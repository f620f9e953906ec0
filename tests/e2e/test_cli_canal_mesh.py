"""Canal walls (a radius law r(s)) meshed on their curvature-line grid (tubecad.export.tessellate
.canal_grid): nodes on the characteristic circles and the stringers chi0 = const, the spacing
measured against the exact surface; the caps (normal cones, planar where r' = 0) between the
same end-circle nodes. Written by `tubecad build` and read back."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import sample_wall_spec

from tubecad.cli.app import cli

#: the walls of samples/nozzle.toml (r' = 0 at both ends: plane caps) and samples/tapered_helix.toml
#: (r' = -0.01: conical caps, stringers turned by the Moebius map), without their stiffeners
NOZZLE, HELIX = sample_wall_spec("nozzle"), sample_wall_spec("tapered_helix")
SPECS = {"nozzle": NOZZLE, "helix": HELIX}
#: a coarse tolerance keeps the tests fast (the default, 1e-3 of the smallest radius, gives
#: 35k and 426k triangles; the same checks hold there)
TOLERANCE = 0.05
#: |mesh volume - B-rep volume| <= VOLUME_SHARE x tolerance x the wall's area (measured: 0.016
#: for the nozzle and 0.019 for the helix; BRepMesh's meshes 0.012 and 0.018)
VOLUME_SHARE = 0.04


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.fixture(scope="module", params=sorted(SPECS))
def meshed(request, tmp_path_factory):
    """(name, spec path, STL path, report) of a canal wall built to STL at TOLERANCE."""
    folder = tmp_path_factory.mktemp(request.param)
    spec = folder / "spec.toml"
    spec.write_text(SPECS[request.param])
    out, report = folder / "wall.stl", folder / "r.json"
    result = run("build", spec, "-o", out, "--report", report, "--mesh-tolerance", TOLERANCE, "-q")
    assert result.exit_code == 0, result.output
    return request.param, spec, out, json.loads(report.read_text())


def closed_mesh(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The STL as meshio reads it (its STL reader merges the repeated vertices)."""
    import meshio

    mesh = meshio.read(path)
    return np.asarray(mesh.points, dtype=float), np.asarray(mesh.cells_dict["triangle"])


def signed_volume(vertices: np.ndarray, triangles: np.ndarray) -> float:
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


@pytest.mark.slow
def test_a_canal_wall_mesh_is_closed_outward_and_holds_the_volume(meshed):
    """Every edge is shared by exactly two triangles; the signed volume (outward triangles)
    is the B-rep's within VOLUME_SHARE x tolerance x area."""
    _, _, out, report = meshed
    vertices, triangles = closed_mesh(out)
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses.tolist()) == {2}
    assert len(vertices) - len(uses) + len(triangles) == 0  # the wall's boundary is one torus: V - E + F = 0
    brep = report["brep"]
    area = sum(surface["area"] for surface in brep["surfaces"])
    volume = signed_volume(vertices, triangles)
    assert volume > 0.0
    assert abs(volume - brep["volume"]) <= VOLUME_SHARE * TOLERANCE * area


@pytest.mark.slow
def test_every_canal_mesh_vertex_lies_on_the_exact_surface(meshed):
    """Every vertex (caps included: their nodes are the end circles') within the tolerance of
    the exact canal surface r + d it belongs to, by the sphere-envelope distance; the read-back
    check of the triangles' edge midpoints passed with its numbers in the report."""
    from tubecad.spec.build import build_from_spec
    from tubecad.spec.parse import load_spec
    from tubecad.surface.checks import envelope_distance

    _, spec, out, report = meshed
    info = report["exports"][str(out)]
    assert info["deflection"] == TOLERANCE
    assert info["max_vertex_deviation"] < 1e-4  # 32-bit floats
    assert 0.5 * TOLERANCE < info["max_triangle_deviation"] <= TOLERANCE + info["max_vertex_deviation"]
    build = build_from_spec(load_spec(spec), lambda *a: None)
    outer = build.surfaces[0].tube
    levels = np.array(
        [
            surface.tube.radius_law.r(np.array([0.0]))[0] - outer.radius_law.r(np.array([0.0]))[0]
            for surface in build.surfaces
        ]
    )
    vertices, _ = closed_mesh(out)
    distance, _ = envelope_distance(outer, vertices)
    assert np.abs(distance[:, None] - levels[None, :]).min(axis=1).max() < 1e-4


@pytest.mark.slow
def test_a_canal_wall_mesh_has_fewer_triangles_than_brepmesh(meshed):
    """BRepMesh at the same tolerances (absolute, as tubecad.export.meshing asks it for
    everything off the grid) makes more triangles of the same wall."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.IMeshTools import IMeshTools_Parameters
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location

    from tubecad.export.meshing import ANGULAR_DEFLECTION
    from tubecad.occ_compat import as_face
    from tubecad.spec.build import build_from_spec
    from tubecad.spec.parse import load_spec

    _, spec, out, report = meshed
    build = build_from_spec(load_spec(spec), lambda *a: None)
    params = IMeshTools_Parameters()
    params.Deflection, params.Angle, params.Relative, params.InParallel = TOLERANCE, ANGULAR_DEFLECTION, False, True
    BRepMesh_IncrementalMesh(build.shape.wrapped, params)
    brepmesh = 0
    explorer = TopExp_Explorer(build.shape.wrapped, TopAbs_FACE)
    while explorer.More():
        brepmesh += BRep_Tool.Triangulation_s(as_face(explorer.Current()), TopLoc_Location()).NbTriangles()
        explorer.Next()
    assert report["exports"][str(out)]["triangles"] < 0.6 * brepmesh  # measured 0.25 (nozzle), 0.50 (helix)


@pytest.mark.slow
def test_a_canal_tube_solid_meshes_closed_with_its_end_discs(tmp_path):
    """Without [wall], the capped tube: plane discs at the end circles (centred at c - r r' t,
    off the axis where r' != 0), triangulated on the circles' nodes alone."""
    spec = tmp_path / "tube.toml"
    spec.write_text(HELIX.split("[wall]")[0])
    out, report = tmp_path / "tube.stl", tmp_path / "r.json"
    result = run("build", spec, "-o", out, "--report", report, "--mesh-tolerance", TOLERANCE, "-q")
    assert result.exit_code == 0, result.output
    vertices, triangles = closed_mesh(out)
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses.tolist()) == {2}
    assert len(vertices) - len(uses) + len(triangles) == 2  # one sphere
    brep = json.loads(report.read_text())["brep"]
    area = brep["surfaces"][0]["area"] + 2.0 * math.pi * 12.0**2  # the surface and (at most) its discs
    # no inner surface to cancel the outer's chords: measured 0.17 x tolerance x area (BRepMesh 0.23)
    volume = signed_volume(vertices, triangles)
    assert 0.0 < brep["volume"] - volume <= 0.25 * TOLERANCE * area
