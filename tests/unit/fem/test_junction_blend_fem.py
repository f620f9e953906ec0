"""A crotch-blended tee's shell model (issue 43), checked against closed forms: the tee's
mid-surfaces are the cylinders y^2 + z^2 = R^2 (the main) and (x - AT)^2 + y^2 = r^2 (the
branch, along z), and the blend is the ball of radius rho = rb + (T + t) / 4 rolled between
them, so its centre lies on both cylinders offset by rho:

    C(phi) = (AT + (r + rho) cos phi, (r + rho) sin phi, sqrt((R + rho)^2 - (r + rho)^2 sin^2 phi)),

its surface at distance rho from that curve, its contact with the main at C - rho (0, y, z) /
(R + rho) and with the branch at C - rho (cos phi, sin phi, 0): all without tubecad."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from shared.junction_fem import AT, TEE, R, T, branch_gap, main_gap, r, t

pytestmark = [pytest.mark.requires("gmsh")]

RB = 6.0
RHO = RB + (T + t) / 4


def centre(phi: np.ndarray) -> np.ndarray:
    a = r + RHO
    return np.stack([AT + a * np.cos(phi), a * np.sin(phi), np.sqrt((R + RHO) ** 2 - (a * np.sin(phi)) ** 2)], axis=-1)


def nearest_centre(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each point's distance to the centre curve and the nearest centre (dense table, then
    a bounded 1-D minimisation)."""
    table = np.linspace(-np.pi, np.pi, 4097)
    c = centre(table)
    distances, centres = [], []
    for p in points:
        k = int(np.argmin(np.linalg.norm(c - p, axis=1)))
        lo, hi = table[max(k - 1, 0)], table[min(k + 1, len(table) - 1)]
        found = minimize_scalar(
            lambda x: float(np.linalg.norm(centre(np.array(x)) - p)),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-12},
        )
        distances.append(found.fun)
        centres.append(centre(np.array(found.x)))
    return np.array(distances), np.array(centres)


@pytest.fixture(scope="module")
def blended(tmp_path_factory):
    from tubecad.spec.mesh import mesh_from_spec
    from tubecad.spec.parse import load_spec

    spec = tmp_path_factory.mktemp("blend") / "tee.toml"
    spec.write_text(TEE.replace("layout = { rings = 4", f"blend = {{ radius = {RB} }}\nlayout = {{ rings = 4"))
    return mesh_from_spec(load_spec(spec))


def _nodes(mesh, prefix: str) -> np.ndarray:
    return np.unique(np.concatenate([b.connectivity.ravel() for b in mesh.shell_blocks if b.name.startswith(prefix)]))


def test_the_blend_nodes_lie_on_the_rolling_ball_and_its_toes_on_the_cylinders(blended):
    mesh = blended
    names = {b.name for b in mesh.shell_blocks}
    assert {"main", "branch", "blend"} <= names
    blend = _nodes(mesh, "blend")
    distance, c = nearest_centre(mesh.nodes[blend])
    assert np.abs(distance - RHO).max() < 1e-9 * R  # measured 3.0e-11 R
    # on each ring's short arc: outside both cylinders (between the ball's two contacts)
    assert main_gap(mesh.nodes[blend]).min() > -1e-6 * R
    assert branch_gap(mesh.nodes[blend]).min() > -1e-6 * R
    on_main, on_branch = mesh.node_sets["blend_main"], mesh.node_sets["blend_branch"]
    assert len(on_main) >= 32 and len(on_branch) >= 32
    assert np.abs(main_gap(mesh.nodes[on_main])).max() < 1e-9 * R  # measured 3.0e-11 R
    assert np.abs(branch_gap(mesh.nodes[on_branch])).max() < 1e-9 * R  # measured 5.8e-13 R
    # the saddle set of a blended branch is its blend's two toes
    assert set(mesh.node_sets["saddle"].tolist()) == set(on_main.tolist()) | set(on_branch.tolist())
    # no main node inside the blend's band: on the main's top, none nearer the branch's axis
    # than the toe comes, (r + rho) R / (R + rho) (at phi = +-90 deg), and the branch's nodes
    # all above its toe's lowest point, sqrt((R + rho)^2 - (r + rho)^2)
    top = _nodes(mesh, "main")
    top = top[mesh.nodes[top, 2] > 0]
    reach = (r + RHO) * R / (R + RHO)
    assert np.hypot(mesh.nodes[top, 0] - AT, mesh.nodes[top, 1]).min() > reach - 1e-6 * R
    lowest = np.sqrt((R + RHO) ** 2 - (r + RHO) ** 2)
    assert mesh.nodes[_nodes(mesh, "branch"), 2].min() > lowest - 1e-6 * R


def test_the_blend_faces_the_ball_and_is_tangent_to_both_walls(blended):
    """A blend element's corners turn about the direction to the ball's centre (outward: the
    pressure pushes the blend away from the pipes' inside); at the toes the main's and the
    branch's element normals equal the blend's (tangent)."""
    mesh = blended
    for block in (b for b in mesh.shell_blocks if b.name.startswith("blend")):
        corners = 4 if block.element[1] in "48" else 3
        p = mesh.nodes[block.connectivity[:, :corners]]
        _, c = nearest_centre(p.mean(axis=1))
        turn = np.cross(p[:, 1] - p[:, 0], p[:, -1] - p[:, 0])
        assert (np.einsum("mk,mk->m", turn, c - p.mean(axis=1)) > 0).all()
        normals = mesh.element_normals[block.name]
        exact = c[:, None, :] - p  # towards the centre at each corner (nearest centre of the element)
        _, each = nearest_centre(mesh.nodes[block.connectivity].reshape(-1, 3))
        exact = each.reshape(normals.shape) - mesh.nodes[block.connectivity]
        exact /= np.linalg.norm(exact, axis=-1, keepdims=True)
        assert np.abs(normals - exact).max() < 2e-6  # measured 2.9e-7: the centre curve's tangent, fitted
    for toe, wall in (("blend_main", "main"), ("blend_branch", "branch")):
        at = set(mesh.node_sets[toe].tolist())
        seen: dict[str, dict[int, np.ndarray]] = {"blend": {}, wall: {}}
        for block in mesh.shell_blocks:
            base = block.name.removesuffix("_tri")
            if base in seen:
                for row, conn in enumerate(block.connectivity):
                    for j, node in enumerate(conn.tolist()):
                        if node in at:
                            seen[base][node] = mesh.element_normals[block.name][row, j]
        assert set(seen["blend"]) == set(seen[wall]) == at
        gap = max(np.linalg.norm(seen["blend"][n] - seen[wall][n]) for n in at)
        assert gap < 1e-8  # measured 2.1e-10 (main), 8.7e-10 (branch)


def test_the_mesh_is_conforming_along_the_toes(blended):
    """Every element side on a toe is a side of a blend element and of a wall element."""
    mesh = blended

    def sides(prefix: str, on: set[int]) -> set[frozenset[int]]:
        out = set()
        for block in mesh.shell_blocks:
            if block.name.startswith(prefix):
                corners = 4 if block.element[1] in "48" else 3
                c = block.connectivity[:, :corners]
                for a, b in zip(c.T, np.roll(c, -1, axis=1).T):
                    out |= {frozenset(e) for e in zip(a.tolist(), b.tolist()) if e[0] in on and e[1] in on}
        return out

    for toe, wall in (("blend_main", "main"), ("blend_branch", "branch")):
        on = set(mesh.node_sets[toe].tolist())
        assert sides("blend", on) == sides(wall, on) and len(sides(wall, on)) == len(on) // 2
