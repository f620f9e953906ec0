"""Any face's curvature-line net as a shell model (issue 44): gmsh's quads on the net's patches,
every node on the exact host surface, stiffened lines as beams, and the pressure step.

The net's patches (:func:`~tubecad.nets.curvature_net`: the face split by its lines of
curvature, one shell) are written as an OCCT BREP and read by gmsh as they are, each patch a
surface of gmsh's OCC kernel on the host's own ``Geom_Surface``: its nodes lie on the exact
surface (gmsh evaluates the surface at the nodes' parameters; a node on a line lies on the
line's edge, whose 3-D curve is within its ``gap`` of the surface). A patch with four corners
(two lines of each family, or the face's boundary) is meshed transfinite and recombined: its
elements' sides run along the lines; any other (a patch at the face's corner, one a line does
not cross whole) is meshed unstructured and recombined (Blossom), the triangles left going in
a block of their own (S3/S6). Second order: gmsh's 8-node serendipity quads.

Each node's parameters (u, v) are its projection on the host (OCCT's
``ShapeAnalysis_Surface::ValueOfUV``); there the host gives the exact unit normal
N = s (X_u x X_v) / |X_u x X_v| (s = -1 where the face is reversed: N is the face's own
outward side) and the unit principal directions d1, d2 (:mod:`~tubecad.nets.principal`). Each
element's nodes turn counter-clockwise about N (CalculiX's pressure pushes along it).

The mesh's lines are recognised by where gmsh's curves lie: a curve whose points lie on a
line's edge (to ON_EDGE of the face's size) is that line's, one on a boundary edge of the face
(an edge used once: not a periodic face's seam) is the boundary's.

Sets: node sets ``boundary`` (the nodes on the face's boundary edges), ``boundary_0``,
``boundary_1``... (per boundary edge, in the face's edge order) and one per line by its name
(``k1_03``: the nodes on its edge, where the mesh has it); element set ``net`` (every shell),
blocks ``net`` (the quads) and ``net_tri`` (triangles, if any); a stiffened line's beams in
blocks ``<line>_web`` (and ``<line>_flange`` for a T or L) and its element set ``<line>``.
In a CalculiX deck the block ``net`` is the element set ``net``: with triangles present
(``net_tri``) it holds the quads only.
"""

from __future__ import annotations

import math
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from OCP.TopoDS import TopoDS_Edge, TopoDS_Shape

from tubecad.brep.wall import wall_offsets
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.fem.beams import beam_directions, profile_rectangles, section_centre
from tubecad.fem.inp import Step
from tubecad.fem.junction import GMSH_ELEMENTS, _oriented
from tubecad.fem.model import BeamSection, ElementBlock, FEMesh, ShellSection
from tubecad.fem.settings import DEFAULT_SIZE_PER_RADIUS, MeshSettings
from tubecad.nets.host import HostSurface
from tubecad.nets.net import CurvatureNet
from tubecad.stiffeners.profiles import Profile, as_stiffener_side

#: a gmsh curve lies on a line's (or the boundary's) edge when its points do, to this share of the face's size
ON_EDGE = 1e-7
#: a quad side runs along a curvature line when its chord is within this angle (degrees) of
#: the mean of the principal direction at its two ends (the chord of an arc is parallel to the
#: mean of its end tangents to second order: measured 0.056 deg on the dome's transfinite patches)
NET_ANGLE_DEG = 0.5
#: a patch is meshed transfinite where its four corners are right angles to this (degrees)
SQUARE_DEG = 30.0
#: ... and where each side is at least this share of the side opposite
OPPOSITE_SHARE = 0.25
#: the default size: the face's size over this, at the most (a face of little curvature)
SIZE_PER_FACE = 16
#: gmsh's line elements -> nodes in the CalculiX beam's order (B31: ends; B32: end, middle, end)
GMSH_LINES = {1: [0, 1], 8: [0, 2, 1]}
#: the points (shares of its parameter range) a gmsh curve is recognised by
CURVE_SAMPLES = (0.25, 0.5, 0.75)


@dataclass(frozen=True)
class _Curve:
    """A gmsh curve: its ``points`` at CURVE_SAMPLES, its mesh ``nodes`` (its ends included)
    and its element sides ``sides`` ((m, 2) or (m, 3): end, middle, end)."""

    points: np.ndarray
    nodes: np.ndarray
    sides: np.ndarray


@dataclass(frozen=True)
class _Meshed:
    """gmsh's mesh: ``nodes`` (n, 3), their parameters ``uv`` (n, 2) on the host where gmsh
    has them (a patch's own nodes: its surface is the host's; NaN on curves and corners),
    ``patches`` [(gmsh type, connectivity 0-based)] and its ``curves``."""

    nodes: np.ndarray
    uv: np.ndarray
    patches: list[tuple[int, np.ndarray]]
    curves: list[_Curve]


def net_shell_mesh(
    net: CurvatureNet,
    settings: MeshSettings,
    thickness: float | None,
    stiffened: Sequence[str] = (),
    profile: Profile | None = None,
    side: str = "outside",
    length_unit: str = "mm",
    wall_side: str = "centered",
) -> FEMesh:
    """The shell model of ``net``'s face (module docstring).

    Args:
        net: the face's curvature-line net.
        settings: the element (S4, S4R, S8, S8R), the beam element, the size (gmsh takes one:
            the smaller of ``size_along`` and ``size_around``; default :func:`net_mesh_size`)
            and ``max_elements``; ``surface`` must be ``mid`` (the face is the shells' middle).
        thickness: the shells' thickness (model units), or None: the face alone, no shell
            section (a surface mesh; a .inp is refused).
        stiffened: the lines (``k1_03``...) that carry stiffeners, made beams.
        profile: the stiffeners' profile (needed with ``stiffened``).
        side: ``outside`` (the stiffeners stand along +N) or ``inside``.
        length_unit: the model's length unit.
        wall_side: where the wall lies from the face (``centered``, ``inside``, ``outside``:
            :func:`tubecad.brep.wall.wall_offsets`): the shells' nodes stay on the face, their
            section offset to the wall's middle (CalculiX's SHELL SECTION OFFSET), and the
            stiffeners stand on the wall's face on their side.

    Returns:
        The mesh: shells ``net`` (``net_tri``), beams ``<line>_web`` (``_flange``), sets
        ``boundary``, ``boundary_<k>``, ``<line>``, ``net``; ``parameters`` the nodes' (u, v),
        ``ring_tangents`` d1 and ``stringer_tangents`` d2; ``info`` its kind, size and quality.

    Raises:
        ParameterError: ``size`` (the mesh would exceed ``max_elements``), ``thickness``,
            ``stiffened`` (a line the net has not), ``profile``, ``side``, ``surface``, ``beam``.
    """
    _check(net, settings, thickness, stiffened, profile, side)
    size = net_mesh_size(settings, net)
    estimate = _area(net.patches) / size**2
    if estimate > settings.max_elements:
        raise ParameterError(
            f"size {size:g} would give about {estimate:.3g} elements, more than max_elements = "
            f"{settings.max_elements}; choose a larger size",
            key="size",
        )
    meshed = _compact(_gmsh_mesh(net.patches, size, settings.order))
    offsets = (0.0, 0.0) if thickness is None else wall_offsets(thickness, wall_side)
    mesh = _shells(net.host, meshed, settings, thickness, offsets, length_unit)
    owners = _curve_owners(net, meshed.curves, _face_size(net.host))
    _line_sets(mesh, meshed.curves, owners)
    for name in stiffened:
        assert profile is not None  # _check: stiffened lines need a profile
        curves = [meshed.curves[i] for i in owners.get(name, [])]
        _add_beams(mesh, net, name, curves, profile, side, offsets, settings.beam_type)
    mesh.info |= {
        "kind": "net",
        "element": settings.element,
        "element_size": size,
        "thickness": thickness,
        "quality": _quality(mesh),
        "lines": _coverage(net, mesh.nodes, meshed.curves, owners),
    }
    return mesh


def net_mesh_size(settings: MeshSettings, net: CurvatureNet) -> float:
    """gmsh's one element size: the smaller of ``size_along`` and ``size_around``; by default
    DEFAULT_SIZE_PER_RADIUS over the face's largest principal curvature |k| (as a tube's
    32 elements round its radius; over a 17 x 17 grid of the face's box), at most the face's
    size over SIZE_PER_FACE (the grid's points where the parameterisation degenerates, a
    pole, left out).

    Args:
        settings: the mesh settings.
        net: the net meshed.

    Returns:
        The element size (model units).
    """
    sizes = [v for v in (settings.size_along, settings.size_around) if v is not None]
    if sizes:
        return min(sizes)
    from tubecad.nets.principal import principal_field

    host = net.host
    u0, u1, v0, v1 = host.bounds
    u, v = np.meshgrid(np.linspace(u0, u1, 17), np.linspace(v0, v1, 17))
    field = principal_field(host, u.ravel(), v.ravel())
    inside = host.inside(u.ravel(), v.ravel()) & (field.area > 1e-8 * field.area.max())  # not at a pole
    curvature = float(np.nanmax(np.maximum(np.abs(field.k1), np.abs(field.k2))[inside], initial=0.0))
    largest = _face_size(host) / SIZE_PER_FACE
    return min(DEFAULT_SIZE_PER_RADIUS / curvature, largest) if curvature > 0 else largest


def net_pressure_step(
    mesh: FEMesh,
    pressure: float,
    *,
    fixed: Sequence[str] = ("boundary",),
    held: Sequence[tuple[int, int]] = (),
    loads: Sequence[tuple[int, int, float]] = (),
) -> Step:
    """The pressure step of a net's shell model: ``pressure`` on every shell, pushing along the
    mesh's normals N for p > 0 (CalculiX's P on a shell face whose nodes turn counter-clockwise
    about N): the face's own outward side, so a vessel's face oriented outward (a dome's: N
    away from its axis) takes p > 0 as internal pressure; the nodes of the node sets ``fixed``
    held (dofs 1-3, as :func:`tubecad.fem.loads.pressure_step` holds a tube's fixed ends).

    Args:
        mesh: the net's mesh (:func:`net_shell_mesh`).
        pressure: the pressure (force / length^2), > 0 along N.
        fixed: node sets held (``boundary`` by default; ``()`` none).
        held: further (node, dof) held at 0 (0-based node, dof 1..3): a roller, a 3-2-1 support.
        loads: (node, dof, force) nodal forces (an edge's line load, as consistent nodal forces).

    Returns:
        The step.

    Raises:
        ParameterError: ``pressure`` not finite, ``fixed`` a set the mesh has not, ``held`` a
            node or dof out of range.
    """
    if isinstance(pressure, bool) or not isinstance(pressure, (int, float)) or not math.isfinite(pressure):
        raise ParameterError(f"pressure must be a finite number, got {pressure!r:.40}", key="pressure")
    unknown = [name for name in fixed if name not in mesh.node_sets]
    if unknown:
        raise ParameterError(f"fixed: the mesh has no node set {unknown[0]!r:.60}", key="fixed")
    given = [(int(n), int(d)) for n, d in held]
    if any(not (0 <= n < len(mesh.nodes) and 1 <= d <= 3) for n, d in given):
        raise ParameterError("held: each (node, dof) needs a node of the mesh and a dof in 1..3", key="held")
    clamped = sorted({int(n) for name in fixed for n in mesh.node_sets[name]})
    dofs = dict.fromkeys([(n, d) for n in clamped for d in (1, 2, 3)] + given)
    ends = "fixed" if clamped else "held"
    return Step(float(pressure), ends, tuple(dofs), tuple((int(n), int(d), float(f)) for n, d, f in loads))


def _check(
    net: CurvatureNet,
    settings: MeshSettings,
    thickness: float | None,
    stiffened: Sequence[str],
    profile: Profile | None,
    side: str,
) -> None:
    """A ParameterError naming the first argument out of range (:func:`net_shell_mesh`)."""
    if settings.surface != "mid":
        raise ParameterError(
            f"surface must be 'mid' for a net's shells (the face is their middle), got {settings.surface!r}",
            key="surface",
        )
    if (2 if settings.beam_type.startswith("B32") else 1) != settings.order:
        raise ParameterError(
            f"beam {settings.beam_type} does not match {settings.element} shells (B31 with S4, B32 with S8)",
            key="beam",
        )
    if thickness is not None and (
        isinstance(thickness, bool) or not isinstance(thickness, (int, float)) or not 0 < thickness < math.inf
    ):
        raise ParameterError(f"thickness must be a finite length > 0, got {thickness!r:.40}", key="thickness")
    missing = [name for name in stiffened if name not in net.lines]
    if missing:
        raise ParameterError(
            f"stiffened: the net has no line {missing[0]!r:.40} (its lines: {', '.join(net.lines)})", key="stiffened"
        )
    if stiffened and profile is None:
        raise ParameterError("stiffened lines need a profile", key="profile")
    as_stiffener_side(side)


def _face_size(host: HostSurface) -> float:
    """The face's size: the largest extent of its box's 9 x 9 points."""
    u0, u1, v0, v1 = host.bounds
    u, v = np.meshgrid(np.linspace(u0, u1, 9), np.linspace(v0, v1, 9))
    return float(np.ptp(host.jet(u, v).X, axis=0).max())


def _area(shape: TopoDS_Shape) -> float:
    from OCP.TopAbs import TopAbs_FACE

    from tubecad.brep.properties import faces_area, sub_shapes

    return faces_area(sub_shapes(shape, TopAbs_FACE))


def _gmsh_mesh(patches: TopoDS_Shape, size: float, order: int) -> _Meshed:
    """gmsh's mesh of the net's patches (module docstring), read from an OCCT BREP file."""
    from OCP.BRepTools import BRepTools

    from tubecad.fem.gmsh_model import gmsh_model

    with tempfile.TemporaryDirectory(prefix="tubecad-gmsh-") as tmp:
        path = Path(tmp) / "net.brep"
        BRepTools.Write_s(patches, str(path))
        with gmsh_model(path, "tubecad-net", "a net") as gmsh:
            return _generated(gmsh, size, order)


def _generated(gmsh: Any, size: float, order: int) -> _Meshed:
    """Mesh gmsh's current model (transfinite where four-sided, recombined) and read it."""
    from tubecad.fem.gmsh_model import quad_options

    quad_options(gmsh, size)
    gmsh.model.mesh.setTransfiniteAutomatic(_square_patches(gmsh), recombine=True)
    gmsh.model.mesh.generate(2)
    if order == 2:
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.setOrder(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    patches = []
    uv = np.full((len(tags), 2), np.nan)
    for _, surface in gmsh.model.getEntities(2):
        own, _, parameters = gmsh.model.mesh.getNodes(2, surface, returnParametricCoord=True)
        uv[index[np.asarray(own, dtype=np.int64)]] = np.reshape(parameters, (-1, 2))
        for kind, conn in zip(*gmsh.model.mesh.getElements(2, surface)[::2]):
            if int(kind) not in GMSH_ELEMENTS:
                raise TubecadError(f"gmsh made elements of type {int(kind)} on a net's patch")
            per = gmsh.model.mesh.getElementProperties(int(kind))[3]
            patches.append((int(kind), index[np.asarray(conn, dtype=np.int64)].reshape(-1, per)))
    curves = [_curve(gmsh, tag, index) for _, tag in gmsh.model.getEntities(1)]
    return _Meshed(np.asarray(coords, dtype=float).reshape(-1, 3), uv, patches, curves)


def _square_patches(gmsh: Any) -> list[tuple[int, int]]:
    """gmsh's surfaces bounded by four curves between four corners, each within SQUARE_DEG of
    a right angle, and each side at least OPPOSITE_SHARE of the length of the side opposite: a
    patch between two lines of each family (they cross at right angles), or one a boundary
    closes square; these are meshed transfinite. A patch cut off by a boundary the lines meet
    at a slant, or near a corner (a side far shorter than its opposite), is left to the
    unstructured mesher (a transfinite mesh skews it)."""
    out = []
    limit = math.sin(math.radians(SQUARE_DEG))
    for _, tag in gmsh.model.getEntities(2):
        curves = [abs(int(c)) for _, c in gmsh.model.getBoundary([(2, tag)], oriented=False)]
        leaving: dict[int, list[np.ndarray]] = {}
        ends: dict[int, set[int]] = {}
        for curve in curves:
            for point, direction in _curve_ends(gmsh, curve):
                leaving.setdefault(point, []).append(direction)
                ends.setdefault(curve, set()).add(point)
        if not (len(curves) == 4 and len(leaving) == 4 and all(len(d) == 2 for d in leaving.values())):
            continue
        length = {c: gmsh.model.occ.getMass(1, c) for c in curves}
        opposite = [(a, b) for a in curves for b in curves if a < b and not ends.get(a, set()) & ends.get(b, set())]
        even = all(min(length[a], length[b]) >= OPPOSITE_SHARE * max(length[a], length[b]) for a, b in opposite)
        if even and all(abs(float(a @ b)) <= limit for a, b in leaving.values()):
            out.append((2, tag))
    return out


def _curve_ends(gmsh: Any, curve: int) -> list[tuple[int, np.ndarray]]:
    """The curve's two end points (gmsh's tags) and its unit tangent at each, leaving it (each
    point matched to the parameter end it lies at: an edge reversed in the shell lists its
    points the other way)."""
    points = [abs(int(p)) for _, p in gmsh.model.getBoundary([(1, curve)], oriented=False)]
    if len(points) != 2:
        return []  # a closed curve: no corner
    low, high = gmsh.model.getParametrizationBounds(1, curve)
    start = np.asarray(gmsh.model.getValue(1, curve, [low[0]]), dtype=float)
    first = np.asarray(gmsh.model.getValue(0, points[0], []), dtype=float)
    second = np.asarray(gmsh.model.getValue(0, points[1], []), dtype=float)
    if np.linalg.norm(second - start) < np.linalg.norm(first - start):
        points.reverse()
    out = []
    for point, at, sign in ((points[0], low[0], 1.0), (points[1], high[0], -1.0)):
        d = sign * np.asarray(gmsh.model.getDerivative(1, curve, [at]), dtype=float)
        out.append((point, d / max(float(np.linalg.norm(d)), 1e-300)))
    return out


def _curve(gmsh: Any, tag: int, index: np.ndarray) -> _Curve:
    """gmsh's curve ``tag``: its sample points, nodes and element sides (0-based nodes)."""
    low, high = gmsh.model.getParametrizationBounds(1, tag)
    at = [low[0] + share * (high[0] - low[0]) for share in CURVE_SAMPLES]
    points = np.asarray(gmsh.model.getValue(1, tag, at), dtype=float).reshape(-1, 3)
    nodes = index[np.asarray(gmsh.model.mesh.getNodes(1, tag, includeBoundary=True)[0], dtype=np.int64)]
    sides = []
    for kind, conn in zip(*gmsh.model.mesh.getElements(1, tag)[::2]):
        order = GMSH_LINES[int(kind)]
        sides.append(index[np.asarray(conn, dtype=np.int64)].reshape(-1, len(order))[:, order])
    return _Curve(points, np.unique(nodes), np.concatenate(sides) if sides else np.zeros((0, 2), dtype=np.int64))


def _node_frames(host: HostSurface, nodes: np.ndarray, known: np.ndarray) -> tuple[np.ndarray, ...]:
    """Per node: its (u, v) on ``host`` (``known``'s where not NaN, else projected), the unit
    normal N = s X_u x X_v / |.| (s = -1 on a reversed face), the principal directions d1, d2
    and its distance to the host."""
    from OCP.gp import gp_Pnt
    from OCP.ShapeAnalysis import ShapeAnalysis_Surface
    from OCP.TopAbs import TopAbs_REVERSED

    from tubecad.nets.principal import principal_field

    analysis = ShapeAnalysis_Surface(host.surface)
    precision = 1e-12 * _face_size(host)
    uv = known.copy()
    missing = np.flatnonzero(np.isnan(uv).any(axis=1))
    for k in missing.tolist():
        uv[k] = _uv(analysis.ValueOfUV(gp_Pnt(*nodes[k].tolist()), precision))
    u, v = host.wrapped(uv[:, 0], uv[:, 1])
    field = principal_field(host, u, v)
    if not np.all(field.area > 0):
        raise TubecadError("a node of the net's mesh lies where the face's parameterisation degenerates (a pole)")
    sign = -1.0 if host.face is not None and host.face.Orientation() == TopAbs_REVERSED else 1.0
    gap = np.linalg.norm(host.jet(u, v).X - nodes, axis=1)
    return np.column_stack([u, v]), sign * field.n, field.d1, field.d2, gap


def _uv(point: Any) -> tuple[float, float]:
    return point.X(), point.Y()


def _compact(meshed: _Meshed) -> _Meshed:
    """``meshed`` without the nodes no element uses (gmsh's points of nothing), renumbered."""
    used = np.unique(np.concatenate([conn.ravel() for _, conn in meshed.patches]))
    new = np.full(len(meshed.nodes), -1, dtype=np.int64)
    new[used] = np.arange(len(used))
    curves = [_Curve(c.points, new[c.nodes], new[c.sides]) for c in meshed.curves]
    patches = [(kind, new[conn]) for kind, conn in meshed.patches]
    return _Meshed(meshed.nodes[used], meshed.uv[used], patches, curves)


def _shells(
    host: HostSurface,
    meshed: _Meshed,
    settings: MeshSettings,
    thickness: float | None,
    offsets: tuple[float, float],
    unit: str,
) -> FEMesh:
    """The shell blocks ``net`` (quads) and ``net_tri`` (triangles) oriented counter-clockwise
    about the host's normal, with the nodes' frames (module docstring); their sections
    ``thickness`` thick, offset from the nodes (on the face) to the middle of the wall's
    ``offsets`` (d_in, d_out) along the normal; none without a thickness."""
    nodes = meshed.nodes
    uv, normals, d1, d2, gap = _node_frames(host, nodes, meshed.uv)
    grouped: dict[int, list[np.ndarray]] = {}
    for kind, conn in meshed.patches:
        corners = GMSH_ELEMENTS[kind][0]
        grouped.setdefault(corners, []).append(_oriented(conn, normals[conn], nodes, corners)[0])
    blocks, sections, first = [], [], 0
    triangle = "S6" if settings.order == 2 else "S3"
    for corners, name, element in ((4, "net", settings.element), (3, "net_tri", triangle)):
        if corners in grouped:
            block = ElementBlock(name, element, np.concatenate(grouped[corners]), first)
            blocks.append(block)
            if thickness is not None:  # the nodes at w = 0, the section's middle at (d_in + d_out) / 2
                sections.append(ShellSection(name, float(thickness), -0.5 * (offsets[0] + offsets[1]) / thickness))
            first += len(block.connectivity)
    mesh = FEMesh(nodes, normals, d1, d2, uv, blocks, sections, [], length_unit=unit)
    mesh.element_sets["net"] = np.concatenate([b.ids for b in blocks])
    mesh.info["surface_distance"] = float(gap.max())
    return mesh


def _boundary_edges(host: HostSurface) -> list[TopoDS_Edge]:
    """The face's boundary edges: each but its seams (used twice) and degenerate edges."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_EDGE

    from tubecad.brep.properties import sub_shapes
    from tubecad.occ_compat import as_edge

    if host.face is None:
        return []
    edges = [as_edge(e) for e in sub_shapes(host.face, TopAbs_EDGE)]
    return [e for e in edges if not BRep_Tool.IsClosed_s(e, host.face) and not BRep_Tool.Degenerated_s(e)]


def _curve_owners(net: CurvatureNet, curves: list[_Curve], scale: float) -> dict[str, list[int]]:
    """The indices of the gmsh curves on each line's edge (by name) and on each boundary edge
    (``boundary_<k>``; ``boundary``: all of them), each curve's points within ON_EDGE of it."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt

    tolerance = ON_EDGE * scale
    targets = {name: edge.edge for name, edge in net.edges.items()}
    targets |= {f"boundary_{k}": edge for k, edge in enumerate(_boundary_edges(net.host))}
    boxes = {}
    for name, edge in targets.items():
        box = Bnd_Box()
        BRepBndLib.Add_s(edge, box)
        box.Enlarge(tolerance)
        boxes[name] = box
    owners: dict[str, list[int]] = {}
    for i, curve in enumerate(curves):
        points = [gp_Pnt(*p) for p in curve.points.tolist()]
        for name, edge in targets.items():
            if any(boxes[name].IsOut(p) for p in points):
                continue
            vertices = [BRepBuilderAPI_MakeVertex(p).Vertex() for p in points]
            if max(BRepExtrema_DistShapeShape(vx, edge).Value() for vx in vertices) <= tolerance:
                owners.setdefault(name, []).append(i)
                if name.startswith("boundary_"):
                    owners.setdefault("boundary", []).append(i)
    return owners


def _line_sets(mesh: FEMesh, curves: list[_Curve], owners: dict[str, list[int]]) -> None:
    """The node sets of the lines and boundary edges (:func:`_curve_owners`); ``boundary``
    always (empty on a closed face, which is then ``closed``)."""
    for name, members in owners.items():
        mesh.node_sets[name] = np.unique(np.concatenate([curves[i].nodes for i in members]))
    mesh.node_sets.setdefault("boundary", np.zeros(0, dtype=np.int64))
    mesh.closed = not len(mesh.node_sets["boundary"])


def _add_beams(
    mesh: FEMesh,
    net: CurvatureNet,
    name: str,
    curves: list[_Curve],
    profile: Profile,
    side: str,
    offsets: tuple[float, float],
    beam_type: str,
) -> None:
    """The line ``name``'s element sides as beams (:mod:`tubecad.fem.beams`), in order along its
    edge and each along it: a block per profile rectangle (``<name>_web``, ``<name>_flange``),
    its section's centre off the nodes to the wall's face on its side (``offsets`` = (d_in, d_out)) and the rectangle's
    middle along +-N (``side``), its 1-direction n1 = N x T (N: the mean of the side's end
    normals, T its chord), the profile's w along n1; element set ``name``."""
    if not curves:
        raise TubecadError(
            f"stiffened line {name}: the mesh has no element sides on it (the net did not split the face there)"
        )
    sides = np.concatenate([c.sides for c in curves])
    along, tangent = _along(net.edges[name].curve, mesh.nodes[sides].mean(axis=1))
    ends = mesh.nodes[sides[:, -1]] - mesh.nodes[sides[:, 0]]
    backwards = np.einsum("ij,ij->i", ends, tangent) < 0
    sides[backwards] = sides[backwards][:, ::-1]
    sides = sides[np.argsort(along)]
    chord = mesh.nodes[sides[:, -1]] - mesh.nodes[sides[:, 0]]
    normal = mesh.normals[sides[:, 0]] + mesh.normals[sides[:, -1]]
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    n1 = beam_directions(normal, chord / np.linalg.norm(chord, axis=1, keepdims=True))
    base = offsets[1] if side == "outside" else offsets[0]  # the wall's face the stiffener stands on
    members = []
    for rect in profile_rectangles(profile):
        block = ElementBlock(f"{name}_{rect.name}", beam_type, sides, mesh.element_count)
        mesh.blocks.append(block)
        centre = section_centre(rect, base, side, 1.0)
        mesh.beam_sections.append(
            BeamSection(block.name, name, rect.w1 - rect.w0, rect.h1 - rect.h0, centre, block.ids, n1)
        )
        members.append(block.ids)
    mesh.element_sets[name] = np.concatenate(members)


def _along(curve: Any, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each point's parameter on ``curve`` (its projection, OCCT's ``GeomAPI_ProjectPointOnCurve``)
    and the curve's unit tangent there."""
    from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
    from OCP.gp import gp_Pnt, gp_Vec

    params, tangents = [], []
    p, d = gp_Pnt(), gp_Vec()
    for point in points.tolist():
        t = GeomAPI_ProjectPointOnCurve(gp_Pnt(*point), curve).LowerDistanceParameter()
        curve.D1(t, p, d)
        params.append(t)
        tangents.append((d.X(), d.Y(), d.Z()))
    tangent = np.array(tangents)
    return np.array(params), tangent / np.linalg.norm(tangent, axis=1, keepdims=True)


def _quality(mesh: FEMesh) -> dict[str, float | int]:
    """The quads' aspect ratio and skew (:func:`~tubecad.fem.quality.corner_measures`) and how
    many are curvature-line quads: each side within NET_ANGLE_DEG of a principal direction
    (the mean of d1, or of d2, at its two ends)."""
    from tubecad.fem.quality import corner_measures

    quads = [b.connectivity[:, :4] for b in mesh.shell_blocks if b.corners == 4]
    triangles = sum(len(b.connectivity) for b in mesh.shell_blocks if b.corners == 3)
    out: dict[str, float | int] = {"quads": 0, "triangles": int(triangles), "quads_on_curvature_lines": 0}
    if not quads:
        return out
    corners = np.concatenate(quads)
    aspect, skew = corner_measures(mesh.nodes, corners)
    a, b = corners.ravel(), np.roll(corners, -1, axis=1).ravel()
    chord = mesh.nodes[b] - mesh.nodes[a]
    chord /= np.linalg.norm(chord, axis=1, keepdims=True)
    angle = np.minimum(_off(chord, mesh.ring_tangents, a, b), _off(chord, mesh.stringer_tangents, a, b))
    on_lines = (angle <= math.radians(NET_ANGLE_DEG)).reshape(-1, 4).all(axis=1)
    out |= {
        "quads": int(len(corners)),
        "quads_on_curvature_lines": int(on_lines.sum()),
        "aspect_ratio_max": float(aspect.max()),
        "skew_deg_max": float(skew.max()),
        "side_angle_deg_max": float(np.degrees(angle.max())),
    }
    return out


def _off(chord: np.ndarray, direction: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The angle (radians) between each unit ``chord`` a -> b and the line of the mean of
    ``direction`` at a and b (the one at b turned the way of the one at a)."""
    da, db = direction[a], direction[b]
    mean = da + db * np.sign(np.einsum("ij,ij->i", da, db))[:, None]
    mean /= np.linalg.norm(mean, axis=1, keepdims=True)
    return np.arccos(np.clip(np.abs(np.einsum("ij,ij->i", mean, chord)), 0.0, 1.0))


def _coverage(
    net: CurvatureNet, nodes: np.ndarray, curves: list[_Curve], owners: dict[str, list[int]]
) -> dict[str, dict[str, float]]:
    """Per line: its ``length`` and ``meshed``, the sum of the chords of the mesh's element
    sides on it over that length (1 less the chords' sag; less where the net did not split the
    face along all of the line)."""
    out = {}
    for name, line in net.lines.items():
        length = float(line.sigma[-1] - line.sigma[0])
        chords = 0.0
        for i in owners.get(name, []):
            sides = curves[i].sides
            chords += float(np.linalg.norm(nodes[sides[:, -1]] - nodes[sides[:, 0]], axis=1).sum())
        out[name] = {"length": length, "meshed": chords / length}
    return out
