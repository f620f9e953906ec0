"""The shell mesh on the curvature-line net (issue 14): geometric facts checked against
closed forms computed here (a torus and a cylinder), not against the code's own output.

- nodes on the exact torus (sqrt(x^2 + y^2) - R)^2 + z^2 = r^2 to round-off, mid-side nodes too;
- normals equal the torus' closed-form normal; ring and stringer tangents orthogonal;
- element edges on the layout's rings (constant s) and stringers (constant angle);
- a closed torus mesh is watertight (every edge in two elements, V - E + F = 0), an open tube
  has exactly its two end rings as boundary;
- corner angles tend to 90 degrees as the mesh is refined (skew ~ h);
- beams share the shells' nodes, their sections are the profile's rectangles at the right offsets;
- bad [mesh] input is refused with one line naming the key.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tubecad.brep.layout import NetLayout
from tubecad.core.errors import ParameterError
from tubecad.curves.natural import NaturalAxis
from tubecad.fem import MeshSettings, StiffenerPlan, mesh_settings, shell_mesh
from tubecad.stiffeners.profiles import Profile
from tubecad.surface import CurvatureLineTube

R, RHO, T = 1000.0, 200.0, 4.0


@pytest.fixture(scope="module")
def torus() -> CurvatureLineTube:
    axis = NaturalAxis("0.001", "0", (0.0, 2 * math.pi * R))  # a circle through the origin, centre (0, R, 0)
    assert axis.closed
    return CurvatureLineTube(axis, RHO)


def torus_frame(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(distance from the torus' core circle, outward unit normal) in closed form."""
    p = x - np.array([0.0, R, 0.0])
    planar = np.column_stack([p[:, 0], p[:, 1], np.zeros(len(p))])
    core = R * planar / np.linalg.norm(planar, axis=1)[:, None]
    d = p - core
    return np.linalg.norm(d, axis=1), d / np.linalg.norm(d, axis=1)[:, None]


@pytest.fixture(scope="module")
def torus_mesh(torus):
    layout = NetLayout.equal(torus, 8, 8)
    return shell_mesh(
        torus,
        layout,
        thickness=T,
        settings=MeshSettings("S8R", size_along=60.0, size_around=60.0),
        stiffeners=StiffenerPlan([1, 3], [0, 2], Profile("T", 40.0, 4.0, 30.0, 4.0), "outside"),
    )


def test_nodes_lie_on_the_exact_torus_and_normals_are_its_normals(torus_mesh):
    dist, normal = torus_frame(torus_mesh.nodes)
    assert np.abs(dist - RHO).max() < 1e-12 * R  # measured 3.4e-13 R... mid-side nodes included
    assert np.abs(torus_mesh.normals - normal).max() < 1e-13
    assert np.abs(np.linalg.norm(torus_mesh.normals, axis=1) - 1).max() < 4.5e-16
    ortho = np.abs(np.einsum("ij,ij->i", torus_mesh.ring_tangents, torus_mesh.stringer_tangents))
    assert ortho.max() < 1e-14  # F / sqrt(EG) on the exact net
    assert torus_mesh.info["quality"]["orthogonality_max"] < 1e-14


def test_element_edges_follow_the_rings_and_stringers(torus_mesh, torus):
    u, s = torus_mesh.parameters.T
    layout = NetLayout.equal(torus, 8, 8)
    for i, s_ring in enumerate(layout.s_rings[:-1]):  # the last ring of a closed tube is ring 0
        ring = torus_mesh.node_sets[f"ring_{i:02d}"]
        assert np.allclose(s[ring], s_ring, atol=1e-9) and len(ring) == torus_mesh.info["elements_around"] * 2
        # a ring is a circle of radius RHO in the normal plane at s_ring: all its nodes at RHO from c(s)
        c = torus.axis.position(np.array([s_ring]))[0]
        assert np.abs(np.linalg.norm(torus_mesh.nodes[ring] - c, axis=1) - RHO).max() < 1e-9
    for j, angle in enumerate(layout.stringers_deg):
        line = torus_mesh.node_sets[f"stringer_{j:02d}"]
        assert np.allclose(np.degrees(u[line]), angle, atol=1e-9)
    assert "start_ring" not in torus_mesh.node_sets  # a closed tube has no ends


def edges(conn: np.ndarray) -> np.ndarray:
    corners = conn[:, :4]
    e = np.stack([corners, np.roll(corners, -1, axis=1)], axis=-1).reshape(-1, 2)
    return np.sort(e, axis=1)


def test_a_closed_torus_mesh_is_watertight(torus_mesh):
    conn = torus_mesh.block("wall").connectivity
    _, counts = np.unique(edges(conn), axis=0, return_counts=True)
    assert set(counts.tolist()) == {2}
    corners = np.unique(conn[:, :4])
    assert len(corners) - len(counts) + len(conn) == 0  # Euler characteristic of the torus
    assert len(np.unique(conn)) == len(torus_mesh.nodes) - 0  # every node is in a shell (beams share them)


def test_an_open_tube_is_bounded_by_its_two_end_rings():
    tube = CurvatureLineTube(NaturalAxis("0.002", "0.001", (0.0, 800.0)), 50.0)
    mesh = shell_mesh(
        tube, NetLayout.equal(tube, 5, 4), thickness=2.0, settings=MeshSettings("S4", size_along=25.0, size_around=25.0)
    )
    e, counts = np.unique(edges(mesh.block("wall").connectivity), axis=0, return_counts=True)
    boundary = np.unique(e[counts == 1])
    ends = np.union1d(mesh.node_sets["start_ring"], mesh.node_sets["end_ring"])
    assert set(counts.tolist()) == {1, 2} and np.array_equal(boundary, ends)
    # nodes on the exact tube: at RHO from the axis point of their own s, in its normal plane
    u, s = mesh.parameters.T
    c, t = tube.axis.position(s), tube.axis.at(s).t
    assert np.abs(np.linalg.norm(mesh.nodes - c, axis=1) - 50.0).max() < 1e-12 * 800
    assert np.abs(np.einsum("ij,ij->i", mesh.nodes - c, t)).max() < 1e-12 * 800


@pytest.mark.parametrize("h, rel", [(80.0, 0.02), (40.0, 0.006), (20.0, 0.003)])  # measured 1.9, 0.48, 0.2 %
def test_skew_is_the_turn_of_the_parallels_across_an_element(torus, h, rel):
    """A torus element between two parallels (stringers) and two meridians (rings) is an
    isosceles trapezoid: its corners are off 90 deg by half the angle d phi = 2 pi / n_along
    the element spans round the big circle (largest at the crown, cos theta = 1): first
    order in h (the elements' own span round the small circle adds the second order)."""
    mesh = shell_mesh(
        torus, NetLayout.equal(torus, 8, 8), thickness=T, settings=MeshSettings("S4", size_along=h, size_around=h)
    )
    n_along = 8 * math.ceil(2 * math.pi * (R + RHO) / 8 / h)  # the outer equator sets the count
    assert mesh.info["elements_along"] == n_along
    assert mesh.info["quality"]["skew_deg_max"] == pytest.approx(math.degrees(math.pi / n_along), rel=rel)


def test_beams_share_the_shell_nodes_with_the_profile_sections(torus_mesh):
    shell_nodes = set(np.unique(torus_mesh.block("wall").connectivity).tolist())
    for block in torus_mesh.beam_blocks:
        assert block.element == "B32" and set(np.unique(block.connectivity).tolist()) <= shell_nodes
    sections = {s.block: s for s in torus_mesh.beam_sections}
    web, flange = sections["ring_01_web"], sections["ring_01_flange"]
    # T 40 high, web 4 thick, flange 30 x 4, on the outer face of a 4 mm wall centred on the tube
    assert (web.width, web.height, web.centre) == (4.0, 36.0, (0.0, 2.0 + 18.0))
    assert (flange.width, flange.height, flange.centre) == (30.0, 4.0, (0.0, 2.0 + 38.0))
    assert web.offsets == (-0.0, -20.0 / 36.0)
    # n1 = N x T is the axis tangent on a ring, -e_u on a stringer: normal to the beam and to N
    for sec in torus_mesh.beam_sections:
        block = torus_mesh.block(sec.block)
        a, b = torus_mesh.nodes[block.connectivity[:, 0]], torus_mesh.nodes[block.connectivity[:, -1]]
        chord = (b - a) / np.linalg.norm(b - a, axis=1)[:, None]
        assert np.abs(np.einsum("ij,ij->i", sec.directions, chord)).max() < 1e-12
    assert set(torus_mesh.element_sets["ring_01"]) == set(sections["ring_01_web"].elements) | set(flange.elements)


def test_panel_sets_cover_the_wall_once(torus_mesh):
    panels = [v for k, v in torus_mesh.element_sets.items() if k.startswith("panel_")]
    assert len(panels) == 8 * 8
    every = np.sort(np.concatenate(panels))
    assert np.array_equal(every, torus_mesh.block("wall").ids)


@pytest.mark.parametrize(
    "section, says, key",
    [
        ({"size": 0.0}, "size must be a finite length in (0, 1e+09]", "size"),
        ({"size": float("nan")}, "size must be a finite length", "size"),
        ({"size_along": -1.0}, "size_along must be a finite length", "size_along"),
        ({"element": "S3"}, "element must be one of S4, S4R, S8, S8R", "element"),
        ({"beam": "B33"}, "beam must be one of B31, B31R, B32, B32R", "beam"),
        ({"element": "S4", "beam": "B32"}, "beam must be B31 or B31R with S4 shells", "beam"),
        ({"surface": "middle"}, "surface must be one of mid, inner, outer, both", "surface"),
        ({"max_elements": 0}, "max_elements must be a whole number in [1, 20000000]", "max_elements"),
        ({"sizes": 3.0}, "unknown mesh setting 'sizes'", "sizes"),
        ({"beams": "no"}, "beams must be True or False", "beams"),
    ],
)
def test_bad_mesh_settings_name_the_key(section, says, key):
    """The library speaks Python terms (the setting's name as its key); the spec's [mesh]
    section adds its own name (tests/e2e/test_bad_input.py)."""
    with pytest.raises(ParameterError, match=None) as info:
        mesh_settings(section)
    assert str(info.value).startswith(says) and info.value.key == key, (str(info.value), info.value.key)


def test_a_spec_section_adds_its_name_to_the_librarys_message():
    from tubecad.spec.model import MeshSection

    with pytest.raises(ParameterError) as info:
        MeshSection(element="S3").settings()
    assert str(info.value).startswith("[mesh] element must be one of S4") and info.value.key == "mesh.element"


def test_the_element_cap_is_checked_before_any_node_is_made(torus):
    layout = NetLayout.equal(torus, 8, 8)
    # 8 bays of 2 pi (R + RHO) / 8 along the outer equator, 8 gaps of 2 pi RHO / 8 round: 1 mm elements
    along, around = 8 * math.ceil(2 * math.pi * (R + RHO) / 8), 8 * math.ceil(2 * math.pi * RHO / 8)
    with pytest.raises(ParameterError, match=rf"give {along * around:,} elements \({along} along x {around} around"):
        shell_mesh(torus, layout, thickness=T, settings=MeshSettings("S4", size_along=1.0, size_around=1.0))


def test_the_result_picture_leaves_out_the_nodes_beams_share():
    """CalculiX's nodal stress at a node a beam shares mixes the beam's stress with the shell's
    (70 % off on the stiffened tee): two quads either side of a beam along their common side
    take the mean of their own two corners only; a quad with every corner on beams keeps them."""
    from tubecad.fem.model import ElementBlock, FEMesh
    from tubecad.fem.plot import shell_colours

    nodes = np.array([[x, y, 0.0] for y in (0.0, 1.0) for x in (0.0, 1.0, 2.0)])  # 0 1 2 / 3 4 5
    quads = ElementBlock("wall", "S4", np.array([[0, 1, 4, 3], [1, 2, 5, 4]]), 0)
    beam = ElementBlock("ring_00_web", "B31", np.array([[1, 4]]), 2)
    zeros = np.zeros_like(nodes)
    mesh = FEMesh(nodes, zeros, zeros, zeros, zeros[:, :2], [quads, beam], [], [])
    values = np.array([1.0, 1e9, 3.0, 5.0, 1e9, 7.0])
    assert shell_colours(mesh, values).tolist() == [3.0, 5.0]
    all_beams = ElementBlock("frame", "B31", np.array([[0, 1], [4, 3]]), 3)
    mesh.blocks.append(all_beams)
    assert shell_colours(mesh, values).tolist() == [0.25 * (1.0 + 1e9 + 1e9 + 5.0), 5.0]
