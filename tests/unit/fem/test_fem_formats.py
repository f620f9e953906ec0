"""The FE mesh written as gmsh .msh, VTU and CalculiX .inp, read back by other programs:
gmsh's own reader (its Python API), meshio's VTU, gmsh and Abaqus readers.

Three small meshes: a torus (closed, S8R shells, B32 T stiffeners), a helix tube (open, S4
on both wall surfaces, B31) and a straight tube (open, S8, B32R). On the torus and the
straight tube every ring and stringer is a circle or a line, so a mid-side node lies exactly
halfway (in distance) between its element side's ends: that catches a wrong node order.
"""

import math

import numpy as np
import pytest
from conftest import requires

meshio = pytest.importorskip("meshio")

from tubecad.brep.layout import NetLayout
from tubecad.core.errors import ParameterError
from tubecad.curves import Helix
from tubecad.curves.natural import NaturalAxis
from tubecad.fem import MeshSettings, StiffenerPlan, shell_mesh
from tubecad.fem.inp import write_inp
from tubecad.fem.meshio_formats import msh_text, panel_names, to_meshio, write_msh, write_vtu
from tubecad.stiffeners.profiles import Profile
from tubecad.surface import CurvatureLineTube

#: written here, not taken from the module: meshio's cell type and gmsh's element type number
#: (3 4-node quadrangle, 16 8-node quadrangle, 1 2-node line, 8 3-node line) per element
MESHIO_TYPE = {
    "S4": "quad",
    "S4R": "quad",
    "S8": "quad8",
    "S8R": "quad8",
    "B31": "line",
    "B31R": "line",
    "B32": "line3",
    "B32R": "line3",
}
GMSH_TYPE = {"S4": 3, "S4R": 3, "S8": 16, "S8R": 16, "B31": 1, "B31R": 1, "B32": 8, "B32R": 8}
#: gmsh and meshio put a 3-node line's middle node last; ours (Abaqus) is end, middle, end
MIDDLE_LAST = [0, 2, 1]
#: mid-side node k of an 8-node quadrangle (index 4 + k) lies between corners k and k + 1
QUAD8_SIDES = [(4, 0, 1), (5, 1, 2), (6, 2, 3), (7, 3, 0)]
#: |d(mid, end 1) - d(mid, end 2)| / chord: measured 4.0e-14 at most on these meshes (round-off
#: in coordinates ~1e3 over chords ~1e2); a node order mixed up gives 0.5 or more
MIDDLE_RTOL = 1e-9
#: the .inp's numbers (inp.number, at most 20 characters) read back, relative to the largest
#: coordinate: measured 2.2e-30 (only coordinates ~1e-13, round-off about 0, are not exact)
INP_RTOL = 1e-14
#: relative rounding of one .inp number: 14 significant digits are left in the worst case
#: ("-1.2345678901235e-13" is 20 characters), half a unit of the 14th digit; measured 2.7e-14
INP_NUMBER_RTOL = 5e-14
#: the .inp types meshio 5.3.5's Abaqus reader knows (it has no S8, B31R, B32R)
MESHIO_ABAQUS = {"S4", "S4R", "S8R", "B31", "B32"}


def _torus():
    R, r = 1000.0, 200.0
    tube = CurvatureLineTube(NaturalAxis("0.001", "0", (0.0, 2 * math.pi * R)), r)
    layout = NetLayout.equal(tube, 9, 8)
    mesh = shell_mesh(
        tube,
        layout,
        thickness=4.0,
        settings=MeshSettings(element="S8R", size_along=100, size_around=80),
        stiffeners=StiffenerPlan([1, 3], [0, 2], Profile("T", 40, 4, 30, 4), "outside"),
    )
    return mesh, layout


def _helix():
    tube = CurvatureLineTube(Helix(0.002, 10.0, (0.0, 2000.0)), 100.0)
    layout = NetLayout.equal(tube, 5, 4)
    settings = MeshSettings(element="S4", surface="both", size_along=40, size_around=40)
    mesh = shell_mesh(
        tube,
        layout,
        thickness=4.0,
        settings=settings,
        stiffeners=StiffenerPlan([1, 2], [0], Profile("L", 20, 2, 15, 2), "inside"),
    )
    return mesh, layout


def _straight():
    tube = CurvatureLineTube(NaturalAxis("0", "0", (0.0, 1000.0)), 100.0)
    layout = NetLayout.equal(tube, 4, 6)
    mesh = shell_mesh(
        tube,
        layout,
        thickness=3.0,
        settings=MeshSettings(element="S8", beam="B32R", size_along=50),
        stiffeners=StiffenerPlan([1], [0, 3], Profile("flat", 20, 3), "outside"),
    )
    return mesh, layout


MESHES = {"torus_S8R_B32": _torus, "helix_S4_B31_both": _helix, "straight_S8_B32R": _straight}
QUADRATIC = ["torus_S8R_B32", "straight_S8_B32R"]


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """name -> (mesh, layout, {"msh", "vtu", "inp"} -> path)."""
    out = {}
    for name, make in MESHES.items():
        mesh, layout = make()
        folder = tmp_path_factory.mktemp(name)
        paths = {
            "msh": write_msh(mesh, folder / "m.msh"),
            "vtu": write_vtu(mesh, folder / "m.vtu"),
            "inp": write_inp(mesh, folder / "m.inp"),
        }
        out[name] = (mesh, layout, paths)
    return out


def test_meshes_are_what_the_tests_assume(written):
    counts = {name: mesh.element_count for name, (mesh, _, _) in written.items()}
    assert all(200 <= c <= 5000 for c in counts.values()), counts
    kinds = {name: sorted({b.element for b in mesh.blocks}) for name, (mesh, _, _) in written.items()}
    assert kinds == {
        "torus_S8R_B32": ["B32", "S8R"],
        "helix_S4_B31_both": ["B31", "S4"],
        "straight_S8_B32R": ["B32R", "S8"],
    }
    helix = written["helix_S4_B31_both"][0]
    assert [b.name for b in helix.shell_blocks] == ["wall_inner", "wall_outer"]


def _expected_cells(block) -> np.ndarray:
    conn = block.connectivity
    return conn[:, MIDDLE_LAST] if block.element.startswith("B32") else conn


def _gmsh_read(path):
    """(node tags, coordinates (n, 3), {(dim, tag): name}, {(dim, tag): entities},
    {entity (dim, tag): [(type, element tags, node tags (m, k))]}) from a fresh gmsh session."""
    from conftest import gmsh_initialized

    with gmsh_initialized() as gmsh:
        gmsh.open(str(path))
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        groups = gmsh.model.getPhysicalGroups()
        names = {g: gmsh.model.getPhysicalName(*g) for g in groups}
        members = {g: list(gmsh.model.getEntitiesForPhysicalGroup(*g)) for g in groups}
        elements = {}
        for dim, tag in gmsh.model.getEntities():
            types, etags, ntags = gmsh.model.mesh.getElements(dim, tag)
            elements[(dim, tag)] = [
                (int(t), np.asarray(e), np.asarray(n).reshape(len(e), -1)) for t, e, n in zip(types, etags, ntags)
            ]
        return np.asarray(tags), np.asarray(xyz).reshape(-1, 3), names, members, elements


@pytest.mark.parametrize("name", MESHES)
def test_msh_read_by_gmsh(written, name):
    requires("gmsh")
    mesh, _, paths = written[name]
    tags, xyz, names, members, elements = _gmsh_read(paths["msh"])
    # nodes: tags 1..n, coordinates exactly (the file has Python's shortest round-trip decimals)
    assert sorted(tags.tolist()) == list(range(1, len(mesh.nodes) + 1))
    xyz = xyz[np.argsort(tags)]
    assert np.array_equal(xyz, mesh.nodes)
    # one physical group per block, named after it, on one entity of its own
    assert sorted(names.values()) == sorted(b.name for b in mesh.blocks)
    assert len(names) == len(mesh.blocks)
    for (dim, tag), group in names.items():
        block = mesh.block(group)
        assert dim == (2 if block.shell else 1)
        (entity,) = members[(dim, tag)]
        ((etype, etags, enodes),) = elements[(dim, entity)]
        assert etype == GMSH_TYPE[block.element]
        assert np.array_equal(etags, block.ids + 1)  # the .inp's element numbers
        assert np.array_equal(enodes, _expected_cells(block) + 1)
    # nothing else: the counts per gmsh type add up
    total = {}
    for blocks in elements.values():
        for etype, etags, _ in blocks:
            total[etype] = total.get(etype, 0) + len(etags)
    wanted = {}
    for b in mesh.blocks:
        wanted[GMSH_TYPE[b.element]] = wanted.get(GMSH_TYPE[b.element], 0) + len(b.connectivity)
    assert total == wanted


@pytest.mark.parametrize("name", MESHES)
def test_msh_read_by_meshio(written, name):
    mesh, _, paths = written[name]
    m = meshio.read(paths["msh"], file_format="gmsh")
    assert np.array_equal(m.points, mesh.nodes)
    assert len(m.cells) == len(mesh.blocks)
    for k, (cells, block) in enumerate(zip(m.cells, mesh.blocks)):
        assert cells.type == MESHIO_TYPE[block.element]
        assert np.array_equal(cells.data, _expected_cells(block))
        assert np.all(m.cell_data["gmsh:physical"][k] == k + 1)
    assert {n: v.tolist() for n, v in m.field_data.items()} == {
        b.name: [k + 1, 2 if b.shell else 1] for k, b in enumerate(mesh.blocks)
    }


def _on_rings(mesh, layout) -> np.ndarray:
    """Per node: the layout ring whose s it has (to 1e-9 of the span), -1 if none; a closed
    axis' last ring is its first."""
    s = mesh.parameters[:, 1]
    rings = layout.s_rings[:-1] if mesh.closed else layout.s_rings
    span = layout.s_rings[-1] - layout.s_rings[0]
    out = np.full(len(s), -1)
    for i, si in enumerate(rings):
        out[np.abs(s - si) <= 1e-9 * span] = i
    return out


@pytest.mark.parametrize("name", MESHES)
def test_vtu_round_trip(written, name):
    mesh, layout, paths = written[name]
    v = meshio.read(paths["vtu"], file_format="vtu")
    assert np.array_equal(v.points, mesh.nodes)
    for key, values in (
        ("normal", mesh.normals),
        ("ring_tangent", mesh.ring_tangents),
        ("stringer_tangent", mesh.stringer_tangents),
    ):
        assert np.array_equal(v.point_data[key], values), key
    ring = v.point_data["ring"]
    assert np.array_equal(ring, _on_rings(mesh, layout))
    assert (ring == -1).any() and (ring >= 0).any()
    # meshio reads one cell block per run of one type: compare in the global element order
    read_types = np.concatenate([[c.type] * len(c.data) for c in v.cells])
    assert len(read_types) == mesh.element_count
    wanted = {}
    for c, data in zip(v.cells, v.cell_data["block"]):
        for k in np.unique(data):
            wanted.setdefault(int(k), []).append(c.data[data == k])
    assert sorted(wanted) == list(range(len(mesh.blocks)))
    for k, block in enumerate(mesh.blocks):
        assert np.array_equal(np.concatenate(wanted[k]), _expected_cells(block)), block.name
    assert read_types.tolist() == [MESHIO_TYPE[b.element] for b in mesh.blocks for _ in b.connectivity]
    # panel: each shell's panel_rI_sJ, in the order of (I, J); -1 on the beams
    panel = np.concatenate(v.cell_data["panel"])
    names = panel_names(mesh)
    assert names[:2] == ["panel_r0_s0", "panel_r0_s1"] and len(names) == len(set(names))
    for k, set_name in enumerate(names):
        assert np.array_equal(np.flatnonzero(panel == k), np.sort(mesh.element_sets[set_name])), set_name
    beams = np.concatenate([b.ids for b in mesh.beam_blocks])
    assert np.all(panel[beams] == -1) and np.all(panel[np.concatenate([b.ids for b in mesh.shell_blocks])] >= 0)


def _middle_offsets(points: np.ndarray, triples: np.ndarray) -> float:
    """max over (middle, end, end) index triples of |d(m, a) - d(m, b)| / |a - b|."""
    m, a, b = (points[triples[:, k]] for k in range(3))
    da, db = np.linalg.norm(m - a, axis=1), np.linalg.norm(m - b, axis=1)
    return float((np.abs(da - db) / np.linalg.norm(a - b, axis=1)).max())


def _triples(cell_type: str, conn: np.ndarray) -> np.ndarray:
    """(middle, end, end) in meshio's and gmsh's order: line3 end, end, middle; quad8 sides."""
    if cell_type == "line3":
        return conn[:, [2, 0, 1]]
    return np.concatenate([conn[:, list(side)] for side in QUAD8_SIDES])


@pytest.mark.parametrize("name", QUADRATIC)
def test_middle_nodes_between_their_ends(written, name):
    """Read back from .msh (gmsh) and .vtu (meshio): every 3-node beam's middle node and every
    8-node shell's mid-side node is as far from both ends of its side (to 1e-9 of the side's
    chord; measured 4.0e-14). A middle node read as an end would be 0 from one of them."""
    requires("gmsh")
    mesh, _, paths = written[name]
    tags, xyz, _, _, elements = _gmsh_read(paths["msh"])
    points = np.empty_like(xyz)
    points[tags - 1] = xyz
    offsets = {}
    for blocks in elements.values():
        for etype, _, enodes in blocks:
            kind = {8: "line3", 16: "quad8"}[etype]
            offsets.setdefault(f"msh {kind}", []).append(_middle_offsets(points, _triples(kind, enodes - 1)))
    v = meshio.read(paths["vtu"])
    for c in v.cells:
        offsets.setdefault(f"vtu {c.type}", []).append(_middle_offsets(v.points, _triples(c.type, c.data)))
    assert sorted(offsets) == ["msh line3", "msh quad8", "vtu line3", "vtu quad8"]
    worst = {k: max(v) for k, v in offsets.items()}
    assert max(worst.values()) <= MIDDLE_RTOL, worst
    # and the check bites: the Abaqus order (end, middle, end) read as gmsh's is caught
    beam = mesh.beam_blocks[0]
    assert _middle_offsets(mesh.nodes, _triples("line3", beam.connectivity)) > 0.5


@pytest.mark.parametrize("name", [n for n in MESHES if n != "straight_S8_B32R"])
def test_inp_read_by_meshio(written, name):
    """The mesh-only .inp (with *NORMAL, which meshio skips) through meshio's Abaqus reader."""
    mesh, _, paths = written[name]
    assert {b.element for b in mesh.blocks} <= MESHIO_ABAQUS
    m = meshio.read(paths["inp"], file_format="abaqus")
    scale = np.abs(mesh.nodes).max()
    assert np.abs(m.points - mesh.nodes).max() <= INP_RTOL * scale
    assert len(m.cells) == len(mesh.blocks)
    for cells, block in zip(m.cells, mesh.blocks):
        assert cells.type == MESHIO_TYPE[block.element]
        # meshio's Abaqus reader keeps the file's node order: a B32's middle node stays second
        assert np.array_equal(cells.data, block.connectivity), block.name
    assert set(mesh.node_sets) <= set(m.point_sets)
    for set_name, ids in mesh.node_sets.items():
        assert np.array_equal(np.sort(m.point_sets[set_name]), np.sort(ids)), set_name
    firsts = [b.first for b in mesh.blocks]
    for set_name, ids in mesh.element_sets.items():
        got = np.concatenate([f + np.asarray(part, dtype=int) for f, part in zip(firsts, m.cell_sets[set_name])])
        assert np.array_equal(np.sort(got), np.sort(ids)), set_name
    # to_meshio's sets are meshio's own reading of the .inp's
    ours = to_meshio(mesh)
    for set_name in mesh.element_sets:
        for a, b in zip(ours.cell_sets[set_name], m.cell_sets[set_name]):
            assert np.array_equal(np.sort(a), np.sort(b)), set_name
    for set_name in mesh.node_sets:
        assert np.array_equal(np.sort(ours.point_sets[set_name]), np.sort(m.point_sets[set_name]))
    assert {"ring_00", "panel_r0_s0", "wall" if mesh.closed else "wall_outer"} <= set(m.point_sets) | set(m.cell_sets)


def test_inp_number_rounding(written):
    """Coordinates of 1e-4 or more are exact in the .inp (the shortest round-trip text fits in
    20 characters); the smaller ones, round-off about 0 here, keep 14 digits at least."""
    for name in ("torus_S8R_B32", "helix_S4_B31_both"):
        mesh, _, paths = written[name]
        m = meshio.read(paths["inp"], file_format="abaqus")
        big = np.abs(mesh.nodes) >= 1e-4
        assert np.array_equal(m.points[big], mesh.nodes[big])
        small = ~big & (mesh.nodes != 0)
        assert small.any()  # the case is there
        rel = np.abs(m.points[small] - mesh.nodes[small]) / np.abs(mesh.nodes[small])
        assert rel.max() <= INP_NUMBER_RTOL, (name, rel.max())


def test_to_meshio_tags_and_data(written):
    mesh, layout, _ = written["helix_S4_B31_both"]
    m = to_meshio(mesh)
    assert [c.type for c in m.cells] == [MESHIO_TYPE[b.element] for b in mesh.blocks]
    assert [int(np.unique(t)[0]) for t in m.cell_data["gmsh:physical"]] == list(range(1, len(mesh.blocks) + 1))
    assert [np.unique(t).tolist() for t in m.cell_data["block"]] == [[k] for k in range(len(mesh.blocks))]
    assert m.field_data["wall_outer"].tolist() == [2, 2] and m.field_data[mesh.beam_blocks[0].name][1] == 1
    assert np.array_equal(m.point_data["ring"], _on_rings(mesh, layout))
    # start_ring and end_ring are the first and last ring; ring 0 on both wall surfaces
    assert np.all(m.point_data["ring"][mesh.node_sets["end_ring"]] == len(layout.s_rings) - 1)
    assert len(m.point_sets["ring_00"]) == 2 * len(np.unique(mesh.parameters[mesh.node_sets["ring_00"], 0]))


def test_msh_text_sections(written):
    """The file's own structure: 4.1 ASCII, one entity per block with its physical tag."""
    mesh, _, _ = written["torus_S8R_B32"]
    text = msh_text(mesh)
    assert text.startswith("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n")
    entities = text.split("$Entities\n")[1].split("$EndEntities")[0].splitlines()
    assert entities[0] == f"0 {len(mesh.beam_blocks)} {len(mesh.shell_blocks)} 0"
    for line in entities[1:]:
        fields = line.split()
        assert fields[-3:] == ["1", fields[0], "0"]  # one physical tag, the entity's own; no boundary
        low, high = np.array(fields[1:4], float), np.array(fields[4:7], float)
        block = mesh.blocks[int(fields[0]) - 1]
        used = mesh.nodes[np.unique(block.connectivity)]
        assert np.array_equal(low, used.min(axis=0)) and np.array_equal(high, used.max(axis=0))


@pytest.mark.parametrize("writer", [write_msh, write_vtu])
def test_writes_are_atomic(tmp_path, written, monkeypatch, writer):
    """A missing folder is refused before anything is written; a write failing half-way
    leaves the old file as it was and no temporary beside it."""
    from pathlib import Path

    mesh, _, _ = written["straight_S8_B32R"]
    with pytest.raises(ParameterError, match="does not exist"):
        writer(mesh, tmp_path / "missing" / "m.out")
    target = tmp_path / "m.out"
    target.write_text("old")

    def half_written(path):
        with open(path, "w") as f:
            f.write("$MeshFormat\n")
        raise OSError("disk full")

    if writer is write_msh:
        monkeypatch.setattr(Path, "write_text", lambda self, *args, **kwargs: half_written(self))
    else:
        monkeypatch.setattr(meshio, "write", lambda path, *args, **kwargs: half_written(path))
    with pytest.raises(OSError, match="disk full"):
        writer(mesh, target)
    monkeypatch.undo()
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["m.out"]
