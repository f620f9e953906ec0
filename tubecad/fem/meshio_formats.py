"""The model as a gmsh mesh (``.msh`` 4.1 ASCII) and as VTU (VTK's XML unstructured grid), and
as a :class:`meshio.Mesh` for any other format meshio writes.

What each holds (node and element numbers are the ``.inp``'s: 0-based ids plus one):

- ``.msh``: the nodes (shortest round-trip decimals, exact), one physical group per element
  block named after it (dimension 2 for shells, 1 for beams; tag = block index + 1), each
  on its own entity of the same tag, elements with the ``.inp``'s numbers. No sections, no
  normals or tangents, no node sets and no other element sets (panels, stiffeners): gmsh
  groups whole entities, and those sets are in the ``.inp`` (whose element numbers these
  are).
- ``.vtu``: the nodes (float64, exact), one cell block per element block, point data
  ``normal``, ``ring_tangent``, ``stringer_tangent`` (unit vectors, exact) and ``ring`` (the
  layout ring index of a node on a layout ring, from the node sets ``ring_NN``; a closed
  tube's last ring is ring 0; -1 elsewhere), cell data ``block`` (the index of the element's
  block in ``FEMesh.blocks``) and ``panel`` (the index of a shell's ``panel_rI_sJ`` in the
  order of (I, J), :func:`panel_names`; -1 for beams). VTU holds no names: the indices are
  those orders. No sections, no node or element sets as such.
- :func:`to_meshio`: all of the above plus meshio's ``point_sets`` (the node sets),
  ``cell_sets`` (every element set, as per-block row indices), the gmsh tags
  (``gmsh:physical``, ``gmsh:geometrical``) and ``field_data`` (block name -> [tag, dim]).

Why our own ``.msh`` writer: meshio 5.3's gmsh 4.1 writer puts every node in one entity of
``point_data["gmsh:dim_tags"]`` and writes $Entities only for entities that own nodes. The
beams share the shells' nodes (a ring's web and flange share all of theirs), so their
entities are never written and gmsh stops at "Unknown entity 2 of dimension 1"; without
dim tags it refuses several blocks. Here every block has its entity, with its bounding box;
a node belongs to the entity of the first block using it (gmsh's nodes may be classified on
an entity other than their elements').

Node order: the blocks' (Abaqus) order is meshio's and gmsh's for quad, quad8 (corners,
then the mid-sides of 1-2, 2-3, 3-4, 4-1) and line; a 3-node beam is end, middle, end in
Abaqus and end, end, middle in meshio and gmsh (:data:`LINE3_ORDER`).

meshio is needed for VTU and :func:`to_meshio` only (imported when they run); the ``.msh``
writer is plain text.
"""

from __future__ import annotations

import io
import re
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from tubecad.core.errors import TubecadError
from tubecad.fem.model import ElementBlock, FEMesh

if TYPE_CHECKING:
    import meshio

#: element -> (meshio cell type, gmsh element type number)
CELL_TYPES = {
    "S4": ("quad", 3),
    "S4R": ("quad", 3),
    "S8": ("quad8", 16),
    "S8R": ("quad8", 16),
    "S3": ("triangle", 2),
    "S6": ("triangle6", 9),
    "B31": ("line", 1),
    "B31R": ("line", 1),
    "B32": ("line3", 8),
    "B32R": ("line3", 8),
}
#: a 3-node beam's nodes (end, middle, end) in meshio's and gmsh's order (end, end, middle);
#: the permutation is its own inverse
LINE3_ORDER = [0, 2, 1]

_PANEL = re.compile(r"panel_r(\d+)_s(\d+)")
_RING = re.compile(r"ring_(\d+)")


def cells(block: ElementBlock) -> np.ndarray:
    """The block's connectivity (0-based) in meshio's and gmsh's node order."""
    conn = np.asarray(block.connectivity, dtype=np.int64)
    return conn[:, LINE3_ORDER] if CELL_TYPES[block.element][0] == "line3" else conn


def physical_groups(mesh: FEMesh) -> dict[str, tuple[int, int]]:
    """Block name -> (tag, dimension): tag = block index + 1, dimension 2 (shells) or 1 (beams)."""
    return {b.name: (k + 1, 2 if b.shell else 1) for k, b in enumerate(mesh.blocks)}


def panel_names(mesh: FEMesh) -> list[str]:
    """The element sets ``panel_rI_sJ`` in the order of (I, J): the values of cell data ``panel``."""
    found = [(tuple(map(int, m.groups())), name) for name in mesh.element_sets if (m := _PANEL.fullmatch(name))]
    return [name for _, name in sorted(found)]


def panel_index(mesh: FEMesh) -> np.ndarray:
    """Per element (global order): the index of its panel in :func:`panel_names`, -1 if none."""
    out = np.full(mesh.element_count, -1, dtype=np.int64)
    for k, name in enumerate(panel_names(mesh)):
        out[mesh.element_sets[name]] = k
    return out


def ring_index(mesh: FEMesh) -> np.ndarray:
    """Per node: NN of the node set ``ring_NN`` holding it, -1 if none (``start_ring`` and
    ``end_ring`` are ring 0 and the last ring under other names)."""
    out = np.full(len(mesh.nodes), -1, dtype=np.int64)
    for name, ids in mesh.node_sets.items():
        if m := _RING.fullmatch(name):
            out[ids] = int(m.group(1))
    return out


def _per_block(mesh: FEMesh, values: np.ndarray) -> list[np.ndarray]:
    """A per-element array (global order) split into the blocks' parts."""
    return [values[b.first : b.first + len(b.connectivity)] for b in mesh.blocks]


def _meshio():
    try:
        import meshio
    except ImportError:
        raise TubecadError("writing VTU or a meshio.Mesh needs meshio: pip install meshio") from None
    return meshio


def to_meshio(mesh: FEMesh) -> meshio.Mesh:
    """The model as a meshio.Mesh (module docstring). Write a ``.msh`` with :func:`write_msh`:
    meshio's own gmsh writer cannot write it (shared nodes)."""
    meshio = _meshio()
    groups = physical_groups(mesh)
    tags = [np.full(len(b.connectivity), groups[b.name][0], dtype=np.int64) for b in mesh.blocks]
    cell_sets = {}
    for name, ids in mesh.element_sets.items():
        ids = np.sort(np.asarray(ids, dtype=np.int64))
        cell_sets[name] = [ids[(ids >= b.first) & (ids < b.first + len(b.connectivity))] - b.first for b in mesh.blocks]
    return meshio.Mesh(
        np.asarray(mesh.nodes, dtype=np.float64),
        [meshio.CellBlock(CELL_TYPES[b.element][0], cells(b)) for b in mesh.blocks],
        point_data=_point_data(mesh),
        cell_data={
            "block": [np.full(len(b.connectivity), k, dtype=np.int64) for k, b in enumerate(mesh.blocks)],
            "panel": _per_block(mesh, panel_index(mesh)),
            "gmsh:physical": tags,
            "gmsh:geometrical": [t.copy() for t in tags],
        },
        field_data={name: np.array(tag_dim) for name, tag_dim in groups.items()},
        point_sets={name: np.asarray(ids, dtype=np.int64) for name, ids in mesh.node_sets.items()},
        cell_sets=cell_sets,
    )


def _point_data(mesh: FEMesh) -> dict[str, np.ndarray]:
    return {
        "normal": np.asarray(mesh.normals, dtype=np.float64),
        "ring_tangent": np.asarray(mesh.ring_tangents, dtype=np.float64),
        "stringer_tangent": np.asarray(mesh.stringer_tangents, dtype=np.float64),
        "ring": ring_index(mesh),
    }


def write_vtu(mesh: FEMesh, path: str | Path) -> Path:
    """Write the VTU (module docstring; binary, zlib-compressed) to ``path`` atomically.
    meshio's VTU writer has no sets (it would fold them into one cell array, overlapping
    sets lost) and drops field data, so only the arrays listed are written."""
    from tubecad.core.atomic import atomic_path

    meshio = _meshio()
    grid = meshio.Mesh(
        np.asarray(mesh.nodes, dtype=np.float64),
        [meshio.CellBlock(CELL_TYPES[b.element][0], cells(b)) for b in mesh.blocks],
        point_data=_point_data(mesh),
        cell_data={
            "block": [np.full(len(b.connectivity), k, dtype=np.int64) for k, b in enumerate(mesh.blocks)],
            "panel": _per_block(mesh, panel_index(mesh)),
        },
    )
    with atomic_path(path) as tmp:
        meshio.write(tmp, grid, file_format="vtu", binary=True, compression="zlib")
    return Path(path)


def msh_text(mesh: FEMesh) -> str:
    """The gmsh 4.1 ASCII file (module docstring): $MeshFormat, $PhysicalNames, $Entities
    (one per block), $Nodes (grouped by the entity owning them), $Elements (one entity block
    per element block)."""
    if not mesh.blocks:
        raise TubecadError("a mesh without elements has no gmsh entities to write")
    groups = physical_groups(mesh)
    nodes = np.asarray(mesh.nodes, dtype=np.float64)
    owner = np.full(len(nodes), -1, dtype=np.int64)
    for k, b in enumerate(mesh.blocks):
        used = np.unique(b.connectivity)
        owner[used[owner[used] < 0]] = k
    owner[owner < 0] = 0  # unused nodes (none in a shell_mesh) go with the first block
    out = io.StringIO()
    w = out.write
    w("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
    w(f"$PhysicalNames\n{len(groups)}\n")
    w("".join(f'{dim} {tag} "{name}"\n' for name, (tag, dim) in groups.items()))
    w("$EndPhysicalNames\n$Entities\n")
    curves = [(k, b) for k, b in enumerate(mesh.blocks) if not b.shell]
    surfaces = [(k, b) for k, b in enumerate(mesh.blocks) if b.shell]
    w(f"0 {len(curves)} {len(surfaces)} 0\n")
    for k, b in curves + surfaces:  # tag, bounding box, 1 physical tag, 0 bounding entities
        box = nodes[np.unique(b.connectivity)]
        w(f"{k + 1} " + " ".join(map(repr, box.min(axis=0).tolist() + box.max(axis=0).tolist())) + f" 1 {k + 1} 0\n")
    w("$EndEntities\n")
    owning = [k for k in range(len(mesh.blocks)) if np.any(owner == k)]
    w(f"$Nodes\n{len(owning)} {len(nodes)} 1 {len(nodes)}\n")
    for k in owning:
        ids = np.flatnonzero(owner == k)
        w(f"{2 if mesh.blocks[k].shell else 1} {k + 1} 0 {len(ids)}\n")
        w("".join(f"{i}\n" for i in (ids + 1).tolist()))
        w("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in nodes[ids].tolist()))
    w(f"$EndNodes\n$Elements\n{len(mesh.blocks)} {mesh.element_count} 1 {mesh.element_count}\n")
    for k, b in enumerate(mesh.blocks):
        w(f"{2 if b.shell else 1} {k + 1} {CELL_TYPES[b.element][1]} {len(b.connectivity)}\n")
        rows = np.column_stack([b.ids + 1, cells(b) + 1])
        w("".join(" ".join(map(str, row)) + "\n" for row in rows.tolist()))
    w("$EndElements\n")
    return out.getvalue()


def write_msh(mesh: FEMesh, path: str | Path) -> Path:
    """Write :func:`msh_text` to ``path`` atomically."""
    from tubecad.core.atomic import write_text

    return write_text(path, msh_text(mesh))
