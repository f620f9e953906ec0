"""The junction's shell model and its pressure analysis (issue 25), checked from outside:
the tee's mid-surfaces are the cylinders y^2 + z^2 = R^2 along x (the main) and
(x - 300)^2 + y^2 = r^2 along z (the branch), so where the nodes lie, which way the elements
face, which quads follow the curvature lines (rings x = const and z = const, stringers at a
constant angle) and the hoop directions are all known without tubecad. The commands (tubecad
mesh, and tubecad analyse against membrane theory's hoop stress) are run in
tests/e2e/test_cli_junction_fem.py."""

from __future__ import annotations

import numpy as np
import pytest
from shared.junction_fem import AT, PAD, TEE, R, T, branch_gap, main_gap, r, t
from shared.junction_fem import tee_fixture as tee_fixture  # the fixture tee; `as`: imported for pytest

pytestmark = [pytest.mark.requires("gmsh")]


def test_every_node_lies_on_its_cylinder_and_the_saddle_nodes_on_both(tee):
    _, mesh = tee
    on_main = np.abs(main_gap(mesh.nodes)) < 1e-6 * R
    on_branch = np.abs(branch_gap(mesh.nodes)) < 1e-6 * R
    assert np.all(on_main | on_branch)
    saddle = mesh.node_sets["saddle"]
    assert len(saddle) >= 32 and np.all(on_main[saddle] & on_branch[saddle])  # measured 3e-8 R
    assert np.count_nonzero(on_main & on_branch) == len(saddle)  # no other node is on both


def test_the_mesh_is_conforming_across_the_saddle(tee):
    """Every element side on the saddle is a side of a main element and of a branch element."""
    _, mesh = tee
    saddle = set(mesh.node_sets["saddle"].tolist())

    def saddle_sides(names: tuple[str, ...]) -> set[frozenset[int]]:
        out = set()
        for block in mesh.shell_blocks:
            if block.name.removesuffix("_tri") in names:
                corners = 4 if block.element[1] in "48" else 3
                c = block.connectivity[:, :corners]
                for a, b in zip(c.T, np.roll(c, -1, axis=1).T):
                    out |= {frozenset(e) for e in zip(a.tolist(), b.tolist()) if e[0] in saddle and e[1] in saddle}
        return out

    main, branch = saddle_sides(("main", "pad")), saddle_sides(("branch",))
    assert main == branch and len(main) == len(saddle) // 2  # a closed loop of quadratic sides: 2 nodes each


def test_elements_face_outwards_with_their_own_cylinders_normals(tee):
    """Each element's corners turn counter-clockwise about the outward normal of its own
    cylinder, and the deck's normals (per element node) are those normals, on the saddle too."""
    _, mesh = tee
    for block in mesh.shell_blocks:
        corners = 4 if block.element[1] in "48" else 3
        p = mesh.nodes[block.connectivity[:, :corners]]
        centre = p.mean(axis=1)
        if block.name.startswith("branch"):
            outward = np.column_stack([centre[:, 0] - AT, centre[:, 1], np.zeros(len(p))])
        else:
            outward = np.column_stack([np.zeros(len(p)), centre[:, 1], centre[:, 2]])
        turn = np.cross(p[:, 1] - p[:, 0], p[:, -1] - p[:, 0])
        assert np.all(np.einsum("mk,mk->m", turn, outward) > 0), block.name
        given = mesh.element_normals[block.name]
        nodes = mesh.nodes[block.connectivity]
        if block.name.startswith("branch"):
            exact = np.stack([nodes[..., 0] - AT, nodes[..., 1], np.zeros(nodes.shape[:2])], axis=-1) / r
        else:
            exact = np.stack([np.zeros(nodes.shape[:2]), nodes[..., 1], nodes[..., 2]], axis=-1) / R
        assert np.abs(given - exact).max() < 1e-6, block.name


def test_quads_away_from_the_saddle_follow_the_curvature_lines(tee):
    """A quad whose corners are all farther than 2 r from the branch's axis has every side on
    a ring (x the same at both ends on the main, z on the branch) or on a stringer (the angle
    round the axis the same): the cylinders' lines of curvature."""
    _, mesh = tee
    checked = 0
    for block in mesh.shell_blocks:
        if block.element[1] not in "48":
            continue
        c = block.connectivity[:, :4]
        p = mesh.nodes[c]
        if block.name.startswith("branch"):
            far = np.all(p[..., 2] > R + 2 * r, axis=1)
            along, angle = p[..., 2], np.arctan2(p[..., 1], p[..., 0] - AT)
        else:
            far = np.all(np.abs(p[..., 0] - AT) > 2 * r, axis=1)
            along, angle = p[..., 0], np.arctan2(p[..., 2], p[..., 1])
        ring = np.abs(along - np.roll(along, -1, axis=1)) < 1e-6 * R
        stringer = np.abs(np.angle(np.exp(1j * (angle - np.roll(angle, -1, axis=1))))) < 1e-8
        assert np.all((ring | stringer)[far]), block.name
        checked += int(far.sum())
    assert checked > 0.6 * sum(len(b.connectivity) for b in mesh.shell_blocks)
    q = mesh.info["quality"]
    assert q["quads_on_curvature_lines"] >= checked and q["aspect_ratio_max"] < 3.0  # measured 2.3


def test_the_sets_hold_the_ends_and_the_pad(tee):
    _, mesh = tee
    x, z = mesh.nodes[:, 0], mesh.nodes[:, 2]
    assert np.array_equal(np.sort(mesh.node_sets["main_start"]), np.flatnonzero(np.abs(x) < 1e-9))
    assert np.array_equal(np.sort(mesh.node_sets["main_end"]), np.flatnonzero(np.abs(x - 600.0) < 1e-9))
    assert np.array_equal(np.sort(mesh.node_sets["branch_end"]), np.flatnonzero(np.abs(z - 250.0) < 1e-9))
    pad = mesh.block("pad")
    assert {s.block: (s.thickness, s.offset) for s in mesh.shell_sections}["pad"] == (T + 3.0, -0.5 * 3.0 / (T + 3.0))
    # the pad: main elements round the opening, from 20 before to 20 beyond the outer saddle
    # (where the branch's outer cylinder, radius r + t / 2, leaves the main's) along the axis
    px = mesh.nodes[pad.connectivity][..., 0]
    assert px.min() == pytest.approx(AT - (r + t / 2) - 20.0, abs=1e-6)
    assert px.max() == pytest.approx(AT + (r + t / 2) + 20.0, abs=1e-6)
    assert np.array_equal(np.sort(mesh.node_sets["pad"]), np.unique(pad.connectivity))


STIFFENED = """
[stiffeners]
rings = [1, 2]
stringers = "all"
profile = "flat"
height = 10.0
thickness = 3.0
"""


@pytest.fixture(scope="module")
def stiffened(tmp_path_factory):
    """The tee without a pad, its main's rings at s = 150 (clear of the opening) and 300 (across
    its middle) and all its stringers stiffened, and the branch's ring 2 and stringers 0, 2, as
    beams on the shell model."""
    from tubecad.spec.mesh import mesh_from_spec
    from tubecad.spec.parse import load_spec

    folder = tmp_path_factory.mktemp("stiffened")
    spec = folder / "tee.toml"
    text = TEE.replace("layout = { rings = 4", "stiffeners = { rings = [2], stringers = [0, 2] }\nlayout = { rings = 4")
    spec.write_text(text + STIFFENED)
    return mesh_from_spec(load_spec(spec))


def _beam_nodes(mesh, name: str) -> np.ndarray:
    """(elements, nodes per beam, 3) of the stiffener ``name``'s beams (its web block)."""
    return mesh.nodes[mesh.block(f"{name}_web").connectivity]


def test_the_stiffeners_are_beams_on_their_lines_of_the_shells(stiffened):
    mesh = stiffened
    webs = [b for b in mesh.blocks if not b.shell]
    assert {b.name for b in webs} == {
        *(f"ring_0{i}_web" for i in (1, 2)),
        *(f"stringer_0{j}_web" for j in range(8)),
        "branch_ring_02_web",
        "branch_stringer_00_web",
        "branch_stringer_02_web",
    }
    assert all(b.element == "B32" for b in webs)  # with S8R shells
    shell_nodes = np.unique(np.concatenate([b.connectivity.ravel() for b in mesh.shell_blocks]))
    for block in webs:
        assert np.isin(block.connectivity, shell_nodes).all()  # on the shells' own nodes
        p = mesh.nodes[block.connectivity]
        if block.name.startswith("branch_"):
            assert np.abs(branch_gap(p)).max() < 1e-6 * r
        else:
            assert np.abs(main_gap(p)).max() < 1e-6 * R
        if block.name.startswith("ring_0"):  # x = 150 or 300 (the main's axis runs along x)
            assert np.ptp(p[..., 0]) < 1e-6 * R
        if block.name == "branch_ring_02_web":
            assert np.ptp(p[..., 2]) < 1e-6 * R


def test_the_main_ring_across_the_opening_stops_on_the_saddle(stiffened):
    """Angles covered round the main axis: the whole turn at x = 150; at x = 300 the turn less
    the opening, 2 asin(r / R) (the branch cylinder's width there is 2 r)."""
    for name, expected in (("ring_01", 2 * np.pi), ("ring_02", 2 * np.pi - 2 * np.arcsin(r / R))):
        p = _beam_nodes(stiffened, name)
        angle = np.arctan2(p[..., 2], p[..., 1])
        turned = np.abs(np.angle(np.exp(1j * (angle[:, -1] - angle[:, 0])))).sum()
        assert turned == pytest.approx(expected, abs=1e-7), name  # measured ~1e-9


def test_the_stringers_stop_on_the_saddle(stiffened):
    """The main's stringers: 600 long, less 2 r for the one the opening cuts (straight lines:
    their beams' lengths exactly); the branch's run from its end (z = 250) down to the main
    cylinder, where their last node lies on it."""
    lengths = {}
    for j in range(8):
        p = _beam_nodes(stiffened, f"stringer_0{j}")
        lengths[j] = float(np.linalg.norm(p[:, -1] - p[:, 0], axis=1).sum())
    cut = [j for j, length in lengths.items() if length < 599.0]
    assert len(cut) == 1 and lengths[cut[0]] == pytest.approx(600.0 - 2 * r, abs=1e-6)
    assert all(lengths[j] == pytest.approx(600.0, abs=1e-9) for j in lengths if j not in cut)
    for j in (0, 2):
        p = _beam_nodes(stiffened, f"branch_stringer_0{j}").reshape(-1, 3)
        low = p[np.argmin(p[:, 2])]
        assert abs(main_gap(low)) < 1e-6 * R  # the beam reaches the saddle
        assert np.ptp(p[:, 0]) < 1e-6 * r and np.ptp(p[:, 1]) < 1e-6 * r  # along z
        assert p[:, 2].max() == pytest.approx(250.0, abs=1e-9)


def test_two_branches_with_their_pads_make_one_model_with_a_set_and_a_section_each(tmp_path):
    """Two branches on the tee's main (at s = 150 and 450, each with a pad): the model holds both
    pads, each an element block with the main's and its own pad's thickness and a node set of
    its own (pad_0, pad_1), every pad element within its pad's bounds on the main cylinder."""
    from tubecad.spec.mesh import mesh_from_spec
    from tubecad.spec.parse import load_spec

    text = TEE.replace("layout = { rings = 4", PAD + "layout = { rings = 4").replace(f"at = {AT}", "at = 150.0")
    second = text[text.index("[[branches]]") : text.index("[mesh]")].replace("at = 150.0", "at = 450.0")
    second = second.replace("thickness = 3.0, width = 20.0", "thickness = 5.0, width = 15.0")
    spec = tmp_path / "two.toml"
    spec.write_text(text.replace("[mesh]", second + "[mesh]"))
    mesh = mesh_from_spec(load_spec(spec))
    assert {"pad_0", "pad_1", "branch_0_end", "branch_1_end"} <= set(mesh.node_sets)
    sections = {sec.block: sec for sec in mesh.shell_sections}
    for name, pad_t, width, centre in (("pad_0", 3.0, 20.0, 150.0), ("pad_1", 5.0, 15.0, 450.0)):
        assert sections[name].thickness == pytest.approx(T + pad_t, rel=1e-12)
        p = mesh.nodes[mesh.node_sets[name]]
        assert np.abs(main_gap(p)).max() < 1e-6 * R  # on the main cylinder
        # round its own branch: the outer saddle spans x = at +- (r + t / 2), the pad reaches
        # ``width`` beyond it along the main axis
        assert np.abs(p[:, 0] - centre).max() == pytest.approx(r + t / 2 + width, abs=1e-6)
    assert not set(mesh.node_sets["pad_0"]) & set(mesh.node_sets["pad_1"])
