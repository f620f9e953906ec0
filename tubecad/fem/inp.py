"""The model as a CalculiX input deck (``.inp``, the Abaqus keyword format in CalculiX's
dialect), written as text: meshio's Abaqus writer has no *NORMAL, sections or materials.

Model data: *NODE; *ELEMENT per block; *NSET and *ELSET per named set; *NORMAL, the exact
unit normal at every node of every shell (global node numbers); *MATERIAL; *SHELL SECTION
(thickness, OFFSET: where the nodes lie in it); *BEAM SECTION, SECTION=RECT per stiffener
rectangle, with OFFSET1/OFFSET2 from the nodes to its centre and the 1-direction n1 = N x T
(given per group of elements sharing one n1 to 1e-9, each group its own element set
``<block>_NNNN``: CalculiX takes a beam's n1 from its section, not from *NORMAL).

An optional step (:class:`Step`) adds the boundary conditions and loads: internal pressure
on the shells, the ends fixed or capped (the cap's resultant p A as nodal forces on the end
ring), or free with the six rigid-body motions held at three points.

CalculiX only: OFFSET1/OFFSET2 on *BEAM SECTION and the per-element sections are its
dialect; Abaqus reads the mesh, sets, normals and shell sections.
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.fem.model import FEMesh


@dataclass(frozen=True)
class Material:
    """Linear elastic isotropic: ``youngs_modulus`` and ``density`` in the model's units
    (force / length^2, mass / length^3), ``poisson_ratio`` in (-1, 0.5)."""

    youngs_modulus: float
    poisson_ratio: float = 0.3
    density: float | None = None
    name: str = "steel"


@dataclass(frozen=True)
class Step:
    """A linear static step: internal ``pressure`` (force / length^2) on the shells, the ends
    ``fixed`` (all displacements 0), ``capped`` (one end held axially, the other loaded by
    the cap's resultant) or ``free`` (closed tubes; rigid-body motions held at 3 points);
    ``outputs``: what the .frd file gets."""

    pressure: float = 0.0
    ends: str = "fixed"
    held: tuple[tuple[int, int], ...] = field(default_factory=tuple)  # (node, dof) held at 0
    loads: tuple[tuple[int, int, float], ...] = field(default_factory=tuple)  # (node, dof, force)


#: CalculiX reads a number from at most 20 characters
FIELD = 20


def number(x: float) -> str:
    """``x`` in at most FIELD characters: Python's shortest round-trip form (17 significant
    digits at most) when it fits, else fewer digits (14 at the least: a relative rounding of 5e-14 or better)."""
    text = repr(float(x))
    digits = 16
    while len(text) > FIELD:
        text = f"{float(x):.{digits}g}"
        digits -= 1
    return text


def _ids(values: np.ndarray, per_line: int = 16) -> str:
    """1-based ids, ``per_line`` to a line."""
    v = np.asarray(values, dtype=np.int64) + 1
    lines = [", ".join(map(str, v[i : i + per_line])) for i in range(0, len(v), per_line)]
    return "\n".join(lines) + "\n"


def _rows(ids: np.ndarray, values: np.ndarray) -> str:
    """``id, v1, v2, ...`` lines (ids 1-based), each number by :func:`number`."""
    text = [repr(v) for v in values.ravel().tolist()]
    text = [s if len(s) <= FIELD else number(float(s)) for s in text]
    width = values.shape[1]
    ids = (np.asarray(ids) + 1).tolist()
    return "".join(f"{i}, " + ", ".join(text[k * width : (k + 1) * width]) + "\n" for k, i in enumerate(ids))


def _direction_groups(directions: np.ndarray, tol: float = 1e-9) -> list[np.ndarray]:
    """Runs of consecutive elements whose n1 agree with the run's first to ``tol``."""
    groups, start = [], 0
    for k in range(1, len(directions) + 1):
        if k == len(directions) or np.abs(directions[k] - directions[start]).max() > tol:
            groups.append(np.arange(start, k))
            start = k
    return groups


def inp_text(
    mesh: FEMesh, material: Material | None = None, step: Step | None = None, title: str = "tubecad mesh"
) -> str:
    """The deck (module docstring). Without ``material`` the model data has nodes, elements,
    sets and normals only (no sections); a step needs a material."""
    if material is None and step is not None:
        raise ParameterError("a CalculiX step needs a material")
    if material is not None and not mesh.shell_sections:
        raise ParameterError(
            "surface = 'both' gives two unconnected surface meshes with no shell section; "
            "a CalculiX model needs one reference surface: 'mid', 'inner' or 'outer'",
            key="surface",
        )
    out = io.StringIO()
    w = out.write
    w(f"** {title}\n** written by tubecad: nodes on the exact surface, element edges on its lines of curvature\n")
    w(f"** length unit {mesh.length_unit}; {len(mesh.nodes)} nodes, {mesh.element_count} elements\n*HEADING\n{title}\n")
    w("*NODE, NSET=NALL\n")
    w(_rows(np.arange(len(mesh.nodes)), mesh.nodes))
    for block in mesh.blocks:
        w(f"*ELEMENT, TYPE={block.element}, ELSET={block.name}\n")
        conn = np.column_stack([block.ids + 1, block.connectivity + 1])
        w("\n".join(", ".join(map(str, row)) for row in conn) + "\n")
    for name, ids in mesh.node_sets.items():
        w(f"*NSET, NSET={name}\n" + _ids(ids))
    for name, ids in mesh.element_sets.items():
        if name not in {b.name for b in mesh.blocks}:
            w(f"*ELSET, ELSET={name}\n" + _ids(ids))
    groups = {}
    for sec in mesh.beam_sections:
        groups[sec.block] = _direction_groups(sec.directions)
        if len(groups[sec.block]) > 1:
            for g, members in enumerate(groups[sec.block]):
                w(f"*ELSET, ELSET={sec.block}_{g:04d}\n" + _ids(sec.elements[members]))
    w("*NORMAL\n")
    for block in mesh.shell_blocks:
        elem = np.repeat(block.ids + 1, block.connectivity.shape[1])
        node = block.connectivity.ravel()
        # unit vectors in fixed point: 17 decimals fit 20 characters ("-0.12345678901234567")
        # and round each component by 5e-18 at most
        given = mesh.element_normals.get(block.name)
        normals = mesh.normals[node] if given is None else given.reshape(-1, 3)
        rows = zip(elem.tolist(), (node + 1).tolist(), *normals.T.tolist())
        w("".join(map("%d, %d, %.17f, %.17f, %.17f\n".__mod__, rows)))
    if material is None:
        return out.getvalue()
    w(
        f"*MATERIAL, NAME={material.name}\n*ELASTIC\n{number(material.youngs_modulus)}, {number(material.poisson_ratio)}\n"
    )
    if material.density is not None:
        w(f"*DENSITY\n{number(material.density)}\n")
    for shell in mesh.shell_sections:
        w(
            f"*SHELL SECTION, ELSET={shell.block}, MATERIAL={material.name}, OFFSET={shell.offset:g}\n{number(shell.thickness)}\n"
        )
    for sec in mesh.beam_sections:
        o1, o2 = sec.offsets
        parts = groups[sec.block]
        for g, members in enumerate(parts):
            elset = sec.block if len(parts) == 1 else f"{sec.block}_{g:04d}"
            n1 = sec.directions[members[0]]
            w(
                f"*BEAM SECTION, ELSET={elset}, MATERIAL={material.name}, SECTION=RECT, "
                f"OFFSET1={number(o1)}, OFFSET2={number(o2)}\n{number(sec.width)}, {number(sec.height)}\n"
                f"{number(n1[0])}, {number(n1[1])}, {number(n1[2])}\n"
            )
    if step is not None:
        w(_step_text(mesh, step))
    return out.getvalue()


def _step_text(mesh: FEMesh, step: Step) -> str:
    out = io.StringIO()
    w = out.write
    if step.held:
        w("*BOUNDARY\n" + "".join(f"{n + 1}, {d}, {d}, 0\n" for n, d in step.held))
    w("*STEP\n*STATIC\n")
    if step.pressure:
        # CalculiX pushes a shell face along its normal for P > 0 (measured: the tube expands)
        w("*DLOAD\n" + "".join(f"{b.name}, P, {number(step.pressure)}\n" for b in mesh.shell_blocks))
    if step.loads:
        w("*CLOAD\n" + "".join(f"{n + 1}, {d}, {number(f)}\n" for n, d, f in step.loads))
    w("*NODE FILE, OUTPUT=2D\nU\n*EL FILE, OUTPUT=2D\nS\n*END STEP\n")
    return out.getvalue()


def write_inp(
    mesh: FEMesh,
    path: str | Path,
    material: Material | None = None,
    step: Step | None = None,
    title: str = "tubecad mesh",
) -> Path:
    """Write :func:`inp_text` to ``path`` atomically."""
    from tubecad.core.atomic import write_text

    return write_text(path, inp_text(mesh, material, step, title))
