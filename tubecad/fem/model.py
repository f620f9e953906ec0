"""The finite-element model of a wall: nodes on the exact surface, shell and beam element
blocks, their sections and the named node and element sets. Plain numpy containers, written
by :mod:`.inp` (CalculiX/Abaqus) and :mod:`.meshio_formats` (gmsh .msh, VTU).

Numbering: nodes and elements are 0-based here; a file's ids are these plus one. The
elements of all blocks are numbered in block order (``ElementBlock.first``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np


@dataclass(frozen=True)
class ElementBlock:
    """Elements of one type: ``connectivity`` (m, nodes per element), 0-based node indices
    in CalculiX/Abaqus order (S4: corners counter-clockwise about the outward normal; S8:
    corners, then the mid-side nodes of sides 1-2, 2-3, 3-4, 4-1; B31: ends; B32: end, middle,
    end). Its elements are numbered ``first`` .. ``first + m - 1``."""

    name: str  # wall, wall_inner, ring_03_web, stringer_05_flange
    element: str  # S4, S4R, S8, S8R, B31, B31R, B32, B32R
    connectivity: np.ndarray
    first: int

    @property
    def ids(self) -> np.ndarray:
        """The block's 0-based element numbers."""
        return self.first + np.arange(len(self.connectivity))

    @property
    def shell(self) -> bool:
        return self.element.startswith("S")

    @property
    def corners(self) -> int:
        """An element's corner nodes (its first ones): 4 for a quad (S4, S8), 3 for a triangle
        (S3, S6), 2 for a beam."""
        return 2 if not self.shell else 4 if self.element[1] in "48" else 3


@dataclass(frozen=True)
class ShellSection:
    """A shell block's section: ``thickness`` and where its reference surface (the nodes)
    lies in it, ``offset`` in thicknesses along the normal from the section's middle to the
    nodes (CalculiX's *SHELL SECTION OFFSET: 0 mid-surface, 0.5 the nodes on the outer face,
    -0.5 on the inner face)."""

    block: str
    thickness: float
    offset: float = 0.0


@dataclass(frozen=True)
class BeamSection:
    """A rectangle of a stiffener's profile (the web, or a T or L flange) as the section of
    beam elements ``elements`` (0-based ids) of block ``block``: ``width`` across (local
    1-direction n1 = N x T), ``height`` along the surface normal N (local 2-direction), its
    centre ``centre`` = (along n1, along N) from the beam's nodes, and per element the
    direction n1 at its middle (``directions``, (m, 3))."""

    block: str
    part: str  # ring_03, stringer_05
    width: float
    height: float
    centre: tuple[float, float]
    elements: np.ndarray
    directions: np.ndarray

    @property
    def offsets(self) -> tuple[float, float]:
        """CalculiX's OFFSET1, OFFSET2: where the nodes lie from the rectangle's centre, in
        its width and height (nodes on its +n1 side at OFFSET1 = 0.5): -centre / size."""
        return -self.centre[0] / self.width, -self.centre[1] / self.height


@dataclass
class FEMesh:
    """A wall as shell elements on its curvature-line net, with stiffeners as beams.

    ``nodes`` (n, 3) lie on the exact surface; ``normals`` (n, 3) are its exact outward
    unit normals there; ``ring_tangents`` / ``stringer_tangents`` (n, 3) the unit tangents of
    the ring and the stringer through each node (principal directions); ``parameters`` (n, 2)
    the node's (angle in radians, s). Sets map names to 0-based node or element numbers."""

    nodes: np.ndarray
    normals: np.ndarray
    ring_tangents: np.ndarray
    stringer_tangents: np.ndarray
    parameters: np.ndarray
    blocks: list[ElementBlock]
    shell_sections: list[ShellSection]
    beam_sections: list[BeamSection]
    node_sets: dict[str, np.ndarray] = field(default_factory=dict)
    element_sets: dict[str, np.ndarray] = field(default_factory=dict)
    length_unit: str = "mm"
    closed: bool = False
    info: dict[str, Any] = field(default_factory=dict)
    #: per shell block (by name), the normal at each of its elements' nodes (m, nodes per
    #: element, 3), where one node carries different normals in different elements (a
    #: junction's saddle); blocks not named here take ``normals``
    element_normals: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def element_count(self) -> int:
        return sum(len(b.connectivity) for b in self.blocks)

    def block(self, name: str) -> ElementBlock:
        for b in self.blocks:
            if b.name == name:
                return b
        raise KeyError(name)

    @property
    def shell_blocks(self) -> list[ElementBlock]:
        return [b for b in self.blocks if b.shell]

    @property
    def beam_blocks(self) -> list[ElementBlock]:
        return [b for b in self.blocks if not b.shell]
