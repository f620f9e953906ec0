"""A junction as a shell model (issue 25): the main tube's and the branches' mid-surfaces
joined on their saddles, meshed by gmsh, with the named sets a pressure analysis needs.

The model's surface is the boundary of the union of the mid-surface tubes, less their end
discs: each tube's faces (bounded by its rings and stringers, :func:`build_tube_solid`)
outside the others, joined along the mid-surfaces' saddle by OCCT's fuse. gmsh meshes it
(read from STEP): a face bounded by four curvature lines is meshed transfinite (its
element edges on the rings and stringers: curvature-line quads), a face cut by the saddle
is meshed unstructured and recombined into quads (Blossom; the few triangles left, S3/S6,
go in blocks of their own), and the faces share their edges' nodes, so the mesh is
conforming across the saddle. Second order: gmsh's 8-node serendipity quads.

Every node is placed on its tube by :func:`~tubecad.junctions.coordinates.surface_coordinates`
(its ring s and stringer u), which gives the exact normal (outward) and principal
directions; an element takes the normals of its own tube at its nodes (``element_normals``:
a saddle node carries the main's normal in the main's elements and the branch's in the
branch's; CalculiX joins the two by a knot, as at any shell intersection).

A branch with a crotch blend (:mod:`tubecad.junctions.blend`) is joined through the rolling
ball on the mid-surfaces (:class:`JunctionBlend`): of radius rb + (t + t_b) / 4, so that with
equal walls its outer face, half a thickness in, is the solid's blend of radius rb exactly; its
shells the walls' mean thickness, their normals away from the ball's centre curve's side (the
pressure pushes outward); the solid's extra material in the bore's sharp corner is no shell's.
Its faces join the main's and the branch's along the ball's contact curves, not by OCCT's fuse
(:meth:`~tubecad.junctions.blend.RollingBall.join`, the wall's own).

Sets: ``saddle`` (the nodes both tubes share; a blended branch's: those on the blend's contact
lines, also ``blend_main`` and ``blend_branch``, ``blend_main_1``... per branch with several), ``crotch`` (an equal tee's: the two saddle nodes
where the mid-surfaces touch), ``pad`` (the nodes of the pad's elements;
``pad_0``, ``pad_1``... with several branches, one per pad),
``main_start``, ``main_end``, ``branch_end`` (``branch_1_end``...), element blocks ``main``,
``branch`` (``branch_1``...), ``blend`` (``blend_1``...), ``pad`` (a pad's elements: the main's and the pad's
thickness, offset outward). A pad is bounded by two rings and two stringers of the main,
which are added to the main's faces so that its boundary is a line of elements.
"""

from __future__ import annotations

import math
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import cached_property, partial
from pathlib import Path

import numpy as np
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape

from tubecad.brep.layout import NetLayout
from tubecad.brep.wall import wall_offsets
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.fem.model import ElementBlock, FEMesh, ShellSection
from tubecad.fem.settings import DEFAULT_SIZE_PER_RADIUS, MeshSettings
from tubecad.junctions.blend import RollingBall
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.junctions.solid import BranchWall
from tubecad.surface.protocol import CurvatureLineSurface

#: a saddle node is an equal tee's crotch node within this of its radius from the crotch point
#: (the mesh's node at the joined mid-surfaces' vertex there: measured 1e-15 of it)
CROTCH_NODE = 1e-4
#: gmsh's element types used here -> (corner count, CalculiX element for order 1 / 2)
GMSH_ELEMENTS = {3: (4, 1), 16: (4, 2), 2: (3, 1), 9: (3, 2)}
#: a quad side is on a ring or stringer when s or u agree at its ends to this (relative; radians)
NET_TOLERANCE = 1e-7
#: the rings a blend's faces are bounded by in the shell model (its closing ring and the one
#: half way round): few vertices on the toes, none a short edge away from a wall's net line
MESH_BLEND_RINGS = 3
#: a face is taken as a tube's when its nodes are within this many fit tolerances of it
ON_TUBE = 100.0


@dataclass(frozen=True)
class JunctionTube:
    """One tube of the shell model: its ``name`` (``main``, ``branch``, ``branch_1``), its
    reference ``surface`` (the wall's mid-surface), its wall ``thickness``, the rings
    and stringers its faces are bounded by (``layout``), and those that carry stiffeners
    (``stiffened``: ring s values, stringer angles in degrees), which stay lines of the mesh
    wherever they lie (their beams stand on them, :mod:`tubecad.fem.junction_beams`)."""

    name: str
    surface: CurvatureLineSurface
    thickness: float
    layout: NetLayout
    stiffened: tuple[tuple[float, ...], tuple[float, ...]] = ((), ())
    #: a branch's crotch blend: the ball's radius on the mid-surfaces (None: none)
    blend: float | None = None

    @property
    def radius(self) -> float:
        """The smallest radius of the reference surface."""
        return float(self.surface.radius_law.min_radius)


@dataclass(frozen=True)
class JunctionBlend:
    """A branch's crotch blend in the shell model (module docstring): its block's ``name``
    (``blend``, ``blend_1``...), the ``branch`` it joins (its index among the tubes), the
    rolling ``ball`` on the mid-surfaces and the shells' ``thickness``."""

    name: str
    branch: int
    ball: RollingBall
    thickness: float

    @property
    def surface(self) -> CurvatureLineSurface:
        """The blend's canal surface (the tube about the ball's centre curve)."""
        return self.ball.surface


@dataclass(frozen=True)
class PadRegion:
    """A reinforcement pad on the main tube: bounded by the rings ``s_range`` and the
    stringers ``angles_deg`` (u_a < u_b, degrees), ``thickness`` on the main's outside."""

    name: str
    s_range: tuple[float, float]
    angles_deg: tuple[float, float]
    thickness: float

    def holds(self, u: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Whether the points (u radians, s) lie inside the pad's bounds."""
        u_a, u_b = self.angles_deg
        around = np.mod(np.degrees(u) - u_a, 360.0)
        return (self.s_range[0] < s) & (s < self.s_range[1]) & (around < u_b - u_a)


def mid_surface_tubes(
    main: CurvatureLineSurface,
    thickness: float,
    layout: NetLayout,
    branches: Sequence[BranchWall],
    *,
    side: str = "centered",
) -> list[JunctionTube]:
    """The shell model's tubes of a junction wall (:func:`tubecad.junctions.build_branched_wall`'s
    arguments): the main (``main`` with its wall ``thickness`` placed ``side``, its ``layout``)
    and each branch wall, each at its wall's mid-surface, named ``main``, ``branch`` (or
    ``branch_0``, ``branch_1``... with several); a branch wall's crotch blend of radius rb
    as the ball of radius rb + (t + t_b) / 4 on the mid-surfaces."""
    d_in, d_out = wall_offsets(thickness, side)
    tubes = [JunctionTube("main", _offset(main, 0.5 * (d_in + d_out)), thickness, layout)]
    for k, wall in enumerate(branches):
        b_in, b_out = wall.offsets()
        name = "branch" if len(branches) == 1 else f"branch_{k}"
        b_layout = wall.layout or NetLayout.equal(wall.surface)
        # a crotch blend's ball on the mid-surfaces: each half a wall farther (module docstring)
        blend = None if wall.blend is None else wall.blend + 0.25 * (thickness + wall.thickness)
        mid = _offset(wall.surface, 0.5 * (b_in + b_out))
        tubes.append(JunctionTube(name, mid, wall.thickness, b_layout, blend=blend))
    return tubes


def _offset(surface: CurvatureLineSurface, distance: float) -> CurvatureLineSurface:
    return surface.offset(distance) if distance else surface


def junction_shell_mesh(
    main: JunctionTube,
    branches: Sequence[JunctionTube],
    *,
    pads: Sequence[PadRegion] = (),
    settings: MeshSettings | None = None,
    tolerance: float = 1e-7,
    length_unit: str = "mm",
) -> FEMesh:
    """The junction's shell model (module docstring). ``settings``: the element (S4, S4R,
    S8, S8R) and size (default DEFAULT_SIZE_PER_RADIUS times the smallest radius; gmsh takes
    one size, the smaller of ``size_along`` and ``size_around``); ``tolerance``: the faces'
    fit tolerance. A ParameterError names ``size`` where the mesh would exceed
    ``max_elements``, ``surface`` for a surface other than ``mid`` (its key)."""
    settings = settings or MeshSettings()
    if settings.surface != "mid":
        raise ParameterError(
            f"surface must be 'mid' for a junction (its tubes' mid-surfaces joined on their saddle), "
            f"got {settings.surface!r}",
            key="surface",
        )
    size = junction_mesh_size(settings, [main, *branches])
    blends = _blends(main, branches, tolerance)
    tubes = _clear_of_saddles(main, branches, blends, size)
    tubes[0] = _with_pads(tubes[0], pads, size)
    faces = _joined_faces(tubes, blends, tolerance)
    estimate = _area(faces) / size**2
    if estimate > settings.max_elements:
        raise ParameterError(
            f"size {size:g} would give about {estimate:.3g} elements, more than max_elements = "
            f"{settings.max_elements}; choose a larger size",
            key="size",
        )
    surfaces = [t.surface for t in tubes] + [b.surface for b in blends]
    nodes, patches = _gmsh_mesh(faces, size, settings.order, partial(_nearest_surface, surfaces))
    return _model(tubes, blends, pads, nodes, patches, settings, tolerance, size, length_unit)


def junction_mesh_size(settings: MeshSettings, tubes: Sequence[JunctionTube]) -> float:
    """gmsh's one element size: the smaller of ``size_along`` and ``size_around``, default
    DEFAULT_SIZE_PER_RADIUS times the smallest radius."""
    sizes = [v for v in (settings.size_along, settings.size_around) if v is not None]
    return min(sizes) if sizes else DEFAULT_SIZE_PER_RADIUS * min(t.radius for t in tubes)


def _nearest_surface(surfaces: list[CurvatureLineSurface], points: np.ndarray) -> np.ndarray:
    """The index of the surface (a tube's or a blend's) each point lies nearest to (by its gap)."""
    return np.argmin(np.abs(np.stack([surface_coordinates(surface, points).gap for surface in surfaces])), axis=0)


def _blends(main: JunctionTube, branches: Sequence[JunctionTube], tolerance: float) -> list[JunctionBlend]:
    """The crotch blends of the ``branches`` that have one: the rolling ball of their
    ``blend`` radius on the mid-surfaces (:func:`~tubecad.junctions.blend.rolling_ball`),
    the walls' mean thickness."""
    from tubecad.junctions.blend import rolling_ball

    out = []
    for k, branch in enumerate(branches, start=1):
        if branch.blend is not None:
            ball = rolling_ball(main.surface, branch.surface, branch.blend, tolerance)
            name = "blend" + branch.name.removeprefix("branch")
            out.append(JunctionBlend(name, k, ball, 0.5 * (main.thickness + branch.thickness)))
    return out


def _clear_of_saddles(
    main: JunctionTube, branches: Sequence[JunctionTube], blends: Sequence[JunctionBlend], clearance: float
) -> list[JunctionTube]:
    """The tubes with the rings and stringers that come within ``clearance`` of a saddle (a
    blend's contact curves, where the branch has one) left out of their faces (the main's
    round the opening, the branch's rings near its foot): a net line that meets the saddle a
    fraction of an element from another line's meeting point would leave an edge far shorter
    than the elements, and a sliver element on it."""
    from tubecad.junctions.saddle import saddle_curve

    main_rings, main_angles = list(main.layout.s_rings), list(main.layout.stringers_deg)
    spines = {b.branch: b.ball.spine for b in blends}  # its parameters: the contact curves'
    out = []
    for k, branch in enumerate(branches, start=1):
        saddle = spines[k] if k in spines else saddle_curve(main.surface, branch.surface)
        (s_lo, s_hi), (u_lo, u_hi) = saddle.extent(saddle.main_s), saddle.extent(saddle.main_u)
        lo, hi = s_lo - clearance, s_hi + clearance
        main_rings = [x for x in main_rings if not lo < x < hi or x in main.stiffened[0]]
        widen = math.degrees(clearance / main.radius)
        centre = math.degrees(0.5 * (u_lo + u_hi))
        half = 0.5 * math.degrees(u_hi - u_lo) + widen
        away = [a for a in main_angles if abs((a - centre + 180.0) % 360.0 - 180.0) > half or a in main.stiffened[1]]
        main_angles = away or [(centre + 180.0) % 360.0]
        b_lo, b_hi = saddle.branch_s.min() - clearance, saddle.branch_s.max() + clearance
        b_rings = [x for x in branch.layout.s_rings if not b_lo < x < b_hi or x in branch.stiffened[0]]
        layout = NetLayout.explicit(branch.surface, b_rings, list(branch.layout.stringers_deg))
        out.append(replace(branch, layout=layout))
    layout = NetLayout.explicit(main.surface, main_rings, main_angles)
    return [replace(main, layout=layout), *out]


def _with_pads(main: JunctionTube, pads: Sequence[PadRegion], clearance: float) -> JunctionTube:
    """The main tube with the pads' bounding rings and stringers added to its layout, and its
    own lines within ``clearance`` of them left out (no strip of faces narrower than an element)."""
    if not pads:
        return main
    pad_rings = [s for pad in pads for s in pad.s_range]
    pad_angles = [a % 360.0 for pad in pads for a in pad.angles_deg]
    turn = math.degrees(clearance / main.radius)
    rings = [
        s for s in main.layout.s_rings if min(abs(s - p) for p in pad_rings) >= clearance or s in main.stiffened[0]
    ]
    angles = [
        a
        for a in main.layout.stringers_deg
        if min(abs((a - p + 180.0) % 360.0 - 180.0) for p in pad_angles) >= turn or a in main.stiffened[1]
    ]
    rings = sorted({*rings, *pad_rings})
    layout = NetLayout.explicit(main.surface, rings, sorted({round(a, 9) for a in angles + pad_angles}))
    return replace(main, layout=layout)


def _joined_faces(tubes: list[JunctionTube], blends: Sequence[JunctionBlend], tolerance: float) -> list[TopoDS_Face]:
    """The faces of the union of the tubes' capped solids (and the blends' fillets), less the
    end discs (planes): OCCT's fuse for the branches without a blend, then each blend's join
    (:meth:`~tubecad.junctions.blend.RollingBall.join`)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import sub_shapes
    from tubecad.brep.solids import build_tube_solid
    from tubecad.junctions.blend import BLEND_STRINGERS
    from tubecad.occ_compat import as_face

    solids = [
        build_tube_solid(
            t.surface, NetLayout.explicit(t.surface, list(t.layout.s_rings), list(t.layout.stringers_deg)), tolerance
        ).shape.wrapped
        for t in tubes
    ]
    blended = {b.branch for b in blends}
    shape = _fused(solids[0], [solid for k, solid in enumerate(solids) if k and k not in blended])
    for blend in blends:
        ball = build_tube_solid(
            blend.surface, NetLayout.equal(blend.surface, MESH_BLEND_RINGS, BLEND_STRINGERS), tolerance
        )
        shape, _ = blend.ball.join(shape, tubes[0].surface, solids[blend.branch], ball.shape.wrapped, "blend")
    faces = [as_face(face) for face in sub_shapes(shape, TopAbs_FACE)]
    return [face for face in faces if BRepAdaptor_Surface(face).GetType() != GeomAbs_Plane]


def _fused(base: TopoDS_Shape, tools: list[TopoDS_Shape]) -> TopoDS_Shape:
    """``base`` fused with ``tools`` (OCCT's fuse, in parallel; ``base`` itself without tools)."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse

    from tubecad.brep.operations import built

    if not tools:
        return base
    fuse = built(BRepAlgoAPI_Fuse(), [base], tools, parallel=True)
    if not fuse.IsDone():
        raise TubecadError("OCCT could not join the tubes' mid-surfaces (the fuse failed)", key="branches")
    return fuse.Shape()


def _area(faces: list[TopoDS_Face]) -> float:
    from tubecad.brep.properties import faces_area

    return faces_area(faces)


def _gmsh_mesh(
    faces: list[TopoDS_Face], size: float, order: int, tube_of: Callable[[np.ndarray], np.ndarray]
) -> tuple[np.ndarray, list[tuple[int, np.ndarray]]]:
    """gmsh's mesh of the faces (module docstring): nodes (n, 3) and per face and element
    type (gmsh's type number, connectivity (m, k) 0-based in gmsh's node order);
    ``tube_of``: the tube each of some points (n, 3) lies on."""
    import build123d as bd

    from tubecad.fem.gmsh_model import gmsh_model, quad_options

    with tempfile.TemporaryDirectory(prefix="tubecad-gmsh-") as tmp:
        step = Path(tmp) / "junction.step"
        bd.export_step(bd.Shell([bd.Face(f) for f in faces]), step)
        with gmsh_model(step, "tubecad-junction", "a junction") as gmsh:
            quad_options(gmsh, size)
            gmsh.model.mesh.setTransfiniteAutomatic(_away_from_saddle(gmsh, tube_of), recombine=True)
            gmsh.model.mesh.generate(2)
            if order == 2:
                gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
                gmsh.model.mesh.setOrder(2)
            tags, coords, _ = gmsh.model.mesh.getNodes()
            index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
            index[tags.astype(np.int64)] = np.arange(len(tags))
            patches = []
            for _, surface in gmsh.model.getEntities(2):
                types, _, conns = gmsh.model.mesh.getElements(2, surface)
                for kind, conn in zip(types, conns):
                    if int(kind) not in GMSH_ELEMENTS:
                        raise TubecadError(f"gmsh made elements of type {int(kind)} on a junction face")
                    per = gmsh.model.mesh.getElementProperties(int(kind))[3]
                    patches.append((int(kind), index[np.asarray(conn, dtype=np.int64)].reshape(-1, per)))
    return np.asarray(coords, dtype=float).reshape(-1, 3), patches


def _away_from_saddle(gmsh, tube_of: Callable[[np.ndarray], np.ndarray]) -> list[tuple[int, int]]:
    """gmsh's surfaces that touch no saddle curve (a curve between faces of two tubes): the
    ones meshed transfinite where they have four corners. A face along the saddle is
    meshed unstructured: its corners there may be acute, which a transfinite mesh skews."""
    surfaces = [tag for _, tag in gmsh.model.getEntities(2)]
    centres = []
    for tag in surfaces:
        low, high = gmsh.model.getParametrizationBounds(2, tag)
        centres.append(gmsh.model.getValue(2, tag, list(0.5 * (np.asarray(low) + np.asarray(high)))))
    tube = dict(zip(surfaces, tube_of(np.asarray(centres, dtype=float).reshape(-1, 3)).tolist()))
    touching = set()
    for _, curve in gmsh.model.getEntities(1):
        upward = [int(t) for t in gmsh.model.getAdjacencies(1, curve)[0]]
        if len({tube[t] for t in upward}) > 1:
            touching.update(upward)
    return [(2, tag) for tag in surfaces if tag not in touching]


def _model(
    tubes: list[JunctionTube],
    blends: Sequence[JunctionBlend],
    pads: Sequence[PadRegion],
    nodes: np.ndarray,
    patches: list[tuple[int, np.ndarray]],
    settings: MeshSettings,
    tolerance: float,
    size: float,
    length_unit: str,
) -> FEMesh:
    """The FEMesh of gmsh's patches: each patch given to the tube (or blend) it lies on,
    oriented, with its normals, sets and sections (module docstring)."""
    owners = _Owners(tubes, blends)
    coordinates = [surface_coordinates(surface, nodes) for surface in owners.surfaces]
    gaps = np.abs(np.stack([c.gap for c in coordinates]))  # (tubes and blends, nodes)
    scale = max(float(np.abs(nodes).max()), max(t.radius for t in tubes))
    near = ON_TUBE * max(tolerance, 1e-12 * scale)
    owner = np.full(len(nodes), -1, dtype=np.int64)  # the first tube (or blend) holding each used node
    grouped: dict[tuple[str, str], list[np.ndarray]] = {}
    normals_of: dict[tuple[str, str], list[np.ndarray]] = {}
    for kind, conn in patches:
        k = int(np.argmin(np.median(gaps[:, np.unique(conn)], axis=1)))
        if np.median(gaps[k, np.unique(conn)]) > near:
            raise TubecadError(
                f"a face of the joined mid-surfaces lies on none of the tubes (nearest {gaps[k, conn].max():.3g} away)"
            )
        c = coordinates[k]
        corners, order = GMSH_ELEMENTS[kind]
        normal = owners.sign[k] * owners.surfaces[k].normal(c.u[conn], c.s[conn])  # (m, per, 3)
        conn, normal = _oriented(conn, normal, nodes, corners)
        used = np.unique(conn)
        owner[used[owner[used] < 0]] = k
        name = owners.names[k]
        if k == 0 and pads:
            left = np.ones(len(conn), dtype=bool)  # the main's elements in no pad
            centre_u, centre_s = _centres(c, conn[:, :corners])
            parts = []
            for pad in pads:
                inside = left & pad.holds(centre_u, centre_s)
                parts.append((pad.name, inside))
                left &= ~inside
            for part, rows in [(name, left), *parts]:
                if rows.any():
                    _add(grouped, normals_of, part, corners, conn[rows], normal[rows])
            continue
        _add(grouped, normals_of, name, corners, conn, normal)
    return _assemble(owners, pads, nodes, coordinates, owner, grouped, normals_of, settings, size, length_unit)


@dataclass(frozen=True)
class _Owners:
    """The surfaces a junction's elements lie on: the tubes', then the blends', with their
    blocks' names and the sign that turns each surface's normal outward (a blend's away from
    its ball's centre curve: the tube about it faces the other way)."""

    tubes: list[JunctionTube]
    blends: Sequence[JunctionBlend]

    @cached_property
    def surfaces(self) -> list[CurvatureLineSurface]:
        return [t.surface for t in self.tubes] + [b.surface for b in self.blends]

    @cached_property
    def names(self) -> list[str]:
        return [t.name for t in self.tubes] + [b.name for b in self.blends]

    @cached_property
    def sign(self) -> list[float]:
        return [1.0] * len(self.tubes) + [-1.0] * len(self.blends)

    @cached_property
    def thickness(self) -> dict[str, float]:
        return {t.name: t.thickness for t in self.tubes} | {b.name: b.thickness for b in self.blends}


def _centres(c, corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """An element's (u, s) centre from its corners' (u unwrapped about the first corner)."""
    u = c.u[corners]
    u = u[:, :1] + np.angle(np.exp(1j * (u - u[:, :1])))
    return u.mean(axis=1), c.s[corners].mean(axis=1)


def _add(grouped, normals_of, name: str, corners: int, conn: np.ndarray, normal: np.ndarray) -> None:
    key = (name, "quad" if corners == 4 else "tri")
    grouped.setdefault(key, []).append(conn)
    normals_of.setdefault(key, []).append(normal)


def _oriented(conn: np.ndarray, normal: np.ndarray, nodes: np.ndarray, corners: int) -> tuple[np.ndarray, np.ndarray]:
    """Each element's nodes ordered counter-clockwise about its tube's outward normal
    (CalculiX's pressure pushes along it): reversed where the corners turn the other way."""
    p = nodes[conn[:, :corners]]
    turn = np.cross(p[:, 1] - p[:, 0], p[:, -1] - p[:, 0])
    flip = np.einsum("mk,mk->m", turn, normal[:, 0]) < 0
    per = conn.shape[1]
    if corners == 4:
        order = [0, 3, 2, 1] if per == 4 else [0, 3, 2, 1, 7, 6, 5, 4]
    else:
        order = [0, 2, 1] if per == 3 else [0, 2, 1, 5, 4, 3]
    conn, normal = conn.copy(), normal.copy()
    conn[flip], normal[flip] = conn[flip][:, order], normal[flip][:, order]
    return conn, normal


def _assemble(
    owners: _Owners, pads, nodes, coordinates, owner, grouped, normals_of, settings, size, length_unit
) -> FEMesh:
    """The blocks (one per tube or pad and element shape), sections, sets and per-node data."""
    tubes = owners.tubes
    main = tubes[0]
    tri = "S6" if settings.order == 2 else "S3"
    blocks, sections, element_normals = [], [], {}
    first = 0
    thickness = {name: (t, 0.0) for name, t in owners.thickness.items()}
    for pad in pads:
        total = main.thickness + pad.thickness  # the section's middle pad.thickness / 2 outside the nodes
        thickness[pad.name] = (total, -0.5 * pad.thickness / total)
    for (name, shape), parts in sorted(grouped.items(), key=lambda item: _block_order(item[0], owners.names)):
        block_name = name if shape == "quad" else f"{name}_tri"
        conn = np.concatenate(parts)
        blocks.append(ElementBlock(block_name, settings.element if shape == "quad" else tri, conn, first))
        element_normals[block_name] = np.concatenate(normals_of[(name, shape)])
        t, offset = thickness[name]
        sections.append(ShellSection(block_name, t, offset))
        first += len(conn)
    used = np.unique(np.concatenate([b.connectivity.ravel() for b in blocks]))
    if len(used) != len(nodes):  # gmsh's nodes of the end discs' edges are all used; anything else is dropped
        keep = np.zeros(len(nodes), dtype=bool)
        keep[used] = True
        new = np.cumsum(keep) - 1
        blocks = [ElementBlock(b.name, b.element, new[b.connectivity], b.first) for b in blocks]
        nodes, owner = nodes[keep], owner[keep]
        coordinates = [type(c)(c.u[keep], c.s[keep], c.gap[keep]) for c in coordinates]
    u = np.choose(owner, [c.u for c in coordinates])
    s = np.choose(owner, [c.s for c in coordinates])
    per_node = [np.zeros((len(nodes), 3)) for _ in range(3)]
    for k, (surface, sign) in enumerate(zip(owners.surfaces, owners.sign)):
        rows = owner == k
        d = surface.derivatives(u[rows], s[rows])
        per_node[0][rows] = sign * d.normal
        per_node[1][rows] = d.S_u / np.linalg.norm(d.S_u, axis=-1, keepdims=True)
        per_node[2][rows] = d.S_s / np.linalg.norm(d.S_s, axis=-1, keepdims=True)
    mesh = FEMesh(
        nodes,
        per_node[0],
        per_node[1],
        per_node[2],
        np.column_stack([u, s]),
        blocks,
        sections,
        [],
        length_unit=length_unit,
        info={
            "kind": "junction",
            "element": settings.element,
            "size": size,
            "thickness": main.thickness,
            "tubes": [t.name for t in tubes],
            "blends": {b.name: {"radius": b.ball.radius, "thickness": b.thickness} for b in owners.blends},
        },
        element_normals=element_normals,
    )
    mesh.node_sets.update(_node_sets(mesh, tubes, owners.blends, pads))
    mesh.info["quality"] = _quality(mesh, coordinates, owners.names)
    return mesh


def _quality(mesh: FEMesh, coordinates, names: list[str]) -> dict[str, float | int]:
    """The quads' aspect ratio and skew, and how many are curvature-line quads: each side
    on a ring (s the same at both ends) or a stringer (u the same), to NET_TOLERANCE (a pad's
    quads on the main's coordinates, :func:`tube_index`; ``names``: the tubes' and the
    blends', as ``coordinates``)."""
    from tubecad.fem.quality import corner_measures

    quads = [b for b in mesh.shell_blocks if b.corners == 4]
    corners = np.concatenate([b.connectivity[:, :4] for b in quads])
    aspect, skew = corner_measures(mesh.nodes, corners)
    on_net = 0
    for block in quads:
        c = coordinates[tube_index(block.name, names) or 0]
        ends = block.connectivity[:, :4]
        a, b = ends, np.roll(ends, -1, axis=1)
        same_s = np.abs(c.s[a] - c.s[b]) <= NET_TOLERANCE * (1.0 + np.abs(c.s[a]))
        same_u = np.abs(np.angle(np.exp(1j * (c.u[a] - c.u[b])))) <= NET_TOLERANCE
        on_net += int(np.count_nonzero((same_s | same_u).all(axis=1)))
    triangles = sum(len(b.connectivity) for b in mesh.shell_blocks if b.corners == 3)
    return {
        "aspect_ratio_max": float(aspect.max()),
        "skew_deg_max": float(skew.max()),
        "quads": int(len(corners)),
        "quads_on_curvature_lines": on_net,
        "triangles": int(triangles),
    }


def _block_order(key: tuple[str, str], names: list[str]) -> tuple[float, bool, str]:
    """Blocks in the order of ``names`` (the tubes', then the blends'), a pad's after the
    main's, triangles after quads."""
    name, shape = key
    return (names.index(name) if name in names else 0.5, shape == "tri", name)


def _node_sets(
    mesh: FEMesh, tubes: list[JunctionTube], blends: Sequence[JunctionBlend], pads: Sequence[PadRegion]
) -> dict[str, np.ndarray]:
    """saddle, blend_main, blend_branch, crotch, pad, main_start, main_end, <branch>_end: see
    the module."""
    names = [t.name for t in tubes] + [b.name for b in blends]
    users: list[set[int]] = [set() for _ in names]
    for block in mesh.shell_blocks:
        users[tube_index(block.name, names) or 0].update(np.unique(block.connectivity).tolist())
    sets: dict[str, np.ndarray] = {}
    main_nodes = users[0]
    shared = set().union(*(main_nodes & other for other in users[1 : len(tubes)]))
    for j, blend in enumerate(blends):  # a blended branch's saddle: the blend's contact lines
        tag = blend.name.removeprefix("blend")
        on_main, on_branch = users[len(tubes) + j] & main_nodes, users[len(tubes) + j] & users[blend.branch]
        sets[f"blend_main{tag}"] = np.array(sorted(on_main), dtype=np.int64)
        sets[f"blend_branch{tag}"] = np.array(sorted(on_branch), dtype=np.int64)
        shared |= on_main | on_branch
    sets["saddle"] = np.array(sorted(shared), dtype=np.int64)
    sets.update(_crotch_nodes(mesh, tubes, sets["saddle"]))
    for pad in pads:  # pad (one branch), pad_0, pad_1 ... (several): each pad's elements' nodes
        blocks = [b.connectivity.ravel() for b in mesh.shell_blocks if b.name.removesuffix("_tri") == pad.name]
        if blocks:
            sets[pad.name] = np.unique(np.concatenate(blocks))
    for k, tube in enumerate(tubes):
        own = np.array(sorted(users[k]), dtype=np.int64)
        s0, s1 = tube.surface.span
        ends = _end_nodes(mesh.nodes[own], tube.surface, (s0, s1))
        if k == 0:
            sets["main_start"], sets["main_end"] = own[ends[0]], own[ends[1]]
        else:
            sets[f"{tube.name}_end"] = own[ends[1]]
    return sets


def _crotch_nodes(mesh: FEMesh, tubes: list[JunctionTube], saddle: np.ndarray) -> dict[str, np.ndarray]:
    """``crotch`` (``crotch_1``... per branch with several): the saddle nodes at an equal tee's
    two crotch points (:func:`~tubecad.junctions.crotch.crotch`, where the mid-surfaces touch),
    each the saddle node nearest to the point, within CROTCH_NODE of the branch's radius."""
    from tubecad.junctions.crotch import crotch

    sets: dict[str, np.ndarray] = {}
    if not saddle.size:
        return sets
    points = mesh.nodes[saddle]
    scale = float(np.abs(mesh.nodes).max())
    for k, tube in enumerate(tubes[1:], start=1):
        touch = crotch(tubes[0].surface, tube.surface, scale)
        if touch is None:
            continue
        distance = np.linalg.norm(points[None, :, :] - touch.points[:, None, :], axis=-1)
        nearest = np.argmin(distance, axis=1)
        if (distance[[0, 1], nearest] <= CROTCH_NODE * tube.radius).all():
            sets["crotch" if len(tubes) == 2 else f"crotch_{k - 1}"] = np.unique(saddle[nearest])
    return sets


def _end_nodes(points: np.ndarray, surface: CurvatureLineSurface, span: tuple[float, float]) -> tuple[np.ndarray, ...]:
    """Per end of ``span``: which points lie on that end's ring (in its plane, on its circle)."""
    out = []
    for s in span:
        centre, radius, normal = (v[0] for v in surface.circle(np.array([s])))
        d = points - centre
        off_plane = np.abs(d @ normal)
        off_circle = np.abs(np.linalg.norm(d - np.outer(d @ normal, normal), axis=1) - radius)
        out.append((off_plane < 1e-6 * radius) & (off_circle < 1e-3 * radius))
    return tuple(out)


def ring_in_order(mesh: FEMesh, ring: np.ndarray) -> np.ndarray:
    """The nodes of an end ring in order round it (by their stringer angle), starting at a
    corner node (the consistent forces of :func:`tubecad.fem.loads.ring_forces` need it)."""
    ordered = ring[np.argsort(mesh.parameters[ring, 0])]
    corners = np.unique(np.concatenate([b.connectivity[:, : b.corners].ravel() for b in mesh.shell_blocks]))
    start = int(np.flatnonzero(np.isin(ordered, corners))[0])
    return np.roll(ordered, -start)


def tube_index(block: str, tubes: Sequence[str]) -> int | None:
    """The index among the tubes' names ``tubes`` of the tube a shell block lies on: its own
    (``branch``, ``branch_tri``), the main's (0) for a pad's block, None for a blend's."""
    base = block.removesuffix("_tri")
    if base in tubes:
        return tubes.index(base)
    return None if is_blend_block(block) else 0


def is_blend_block(block: str) -> bool:
    """Whether a shell block is a crotch blend's (``blend``, ``blend_1_tri``...)."""
    return block.removesuffix("_tri").split("_")[0] == "blend"


def radius_at(surface: CurvatureLineSurface, s: float) -> float:
    """The ring's radius at ``s``."""
    return float(surface.circle(np.array([s]))[1][0])


def smallest_distance(points: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Each point's distance to the nearest of ``targets``."""
    from scipy.spatial import cKDTree

    return cKDTree(targets).query(points)[0]
