"""A face the user already has, with its curvature-line net (issue 44): the design of
``[host]`` specs and of the :class:`~tubecad.parts.CurvatureNet` part.

:class:`NetDesign` holds the face, the lines per family (a count, or a spacing measured along
the other family's line through the seed), the seed, an optional wall (the split face
thickened: OCCT's ``BRepOffset_MakeOffset``, by join, as build123d's ``Solid.thicken``) and
flat-bar, T or L stiffeners on chosen lines (:mod:`tubecad.stiffeners.net_webs`). It builds through the
same :class:`~tubecad.design.model.Design` protocol as tubes and junctions: ``build`` (the
named assembly: ``net`` or ``wall``, ``stiffener_k1_03``..., the lines as edges ``k1_03``...,
the umbilics as vertices ``umbilic_0``...), ``shell_model`` (gmsh's shells on the patches,
webs as beams: :mod:`tubecad.fem.net_shell`) and ``shop`` (the webs developed and nested:
:mod:`tubecad.shop.net_shop`).

Errors speak Python terms (``k1_lines``, ``seed``, ``face``, ``thickness``) and carry the
stage (``host``, ``wall``, ``stiffeners``, ``mesh``, ``fabrication``) the spec turns into its
sections.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.design.model import WallChoice
from tubecad.design.stages import stage

if TYPE_CHECKING:
    from tubecad.core.progress import Progress
    from tubecad.design.result import BuildResult
    from tubecad.design.shell import ShellModel
    from tubecad.design.shop import ShopPackage
    from tubecad.export.registry import Exportable, OutputFormat
    from tubecad.fem.settings import MeshSettings
    from tubecad.nets import CurvatureNet
    from tubecad.nets.patch_shell import PatchShell
    from tubecad.shop.fabrication import Fabrication
    from tubecad.stiffeners.net_webs import NetWeb
    from tubecad.stiffeners.profiles import Profile, StiffenerSide

#: a choice of one family's lines: "all", or their indices
LineSelection = Literal["all"] | tuple[int, ...]
#: the surfaces of the net's cells: the host's own (the face split by the lines, exact), or
#: each four-sided cell refitted in curvature-line coordinates (:mod:`tubecad.nets.patch_shell`)
PatchSurfaces = Literal["host", "curvature"]
PATCH_SURFACES: tuple[PatchSurfaces, ...] = ("host", "curvature")
#: lines per family by default
DEFAULT_LINES = 8
#: a seed this share of the face's size from it is taken as its nearest point of the face
#: (a point typed to the millimetre); farther, it is refused
SEED_REACH = 1e-3


@dataclass(frozen=True)
class NetStiffenerChoice:
    """Stiffeners (flat bar, T or L) of ``profile`` on the net's lines ``k1`` and ``k2`` (indices, or
    ``"all"``), standing ``side`` of the face (or of the wall)."""

    profile: Profile
    k1: LineSelection = ()
    k2: LineSelection = ()
    side: StiffenerSide = "outside"
    density: float | None = None

    def names(self, counts: tuple[int, int]) -> list[str]:
        """The chosen lines' names (``k1_03``...), ``counts`` the lines per family; a
        ParameterError naming ``k1`` or ``k2`` for an index outside them."""
        out = []
        for family, chosen, count in (("k1", self.k1, counts[0]), ("k2", self.k2, counts[1])):
            picked = list(range(count)) if chosen == "all" else list(chosen)
            bad = [i for i in picked if not 0 <= i < count]
            if bad:
                raise ParameterError(f"{family} must be indices in [0, {count - 1}], got {bad}", key=family)
            out += [f"{family}_{i:02d}" for i in picked]
        return out


@dataclass(frozen=True)
class NetDesign:
    """A face and its curvature-line net (module docstring).

    Args:
        face: a build123d ``Face`` or an OCCT ``TopoDS_Face``.
        k1_lines: lines of family 1 (None with ``k1_spacing``).
        k2_lines: lines of family 2.
        k1_spacing: instead of a count, the distance between neighbouring k1 lines along the
            k2 line through the seed.
        k2_spacing: the same for the k2 lines.
        seed: a point (x, y, z) of the face: each family's lines are spread along the other
            family's line through it (None: the centre of its parameter box).
        wall: the face thickened into a wall (None: the split face itself).
        webs: stiffeners on chosen lines.
        length_unit: the unit of the face's coordinates.
        patches: the cells' surfaces: ``host`` (the face split by the lines) or
            ``curvature`` (each four-sided cell on its curvature-line patch,
            :func:`tubecad.nets.patch_shell.patch_shell`; the others stay on the host).
    """

    face: Any
    k1_lines: int | None = DEFAULT_LINES
    k2_lines: int | None = DEFAULT_LINES
    k1_spacing: float | None = None
    k2_spacing: float | None = None
    seed: tuple[float, float, float] | None = None
    wall: WallChoice | None = None
    webs: NetStiffenerChoice | None = None
    length_unit: str = DEFAULT_LENGTH_UNIT
    patches: PatchSurfaces = "host"

    WRITTEN_AS: ClassVar[frozenset[str]] = frozenset({"cad", "mesh", "png"})
    WHAT: ClassVar[str] = "a face's curvature-line net"
    #: a net's shop package is its webs': it needs them
    SHOP_NEEDS_PARTS: ClassVar[bool] = True

    @property
    def stiffeners(self) -> None:
        """A net's webs stand on its lines (``webs``), not on a tube's rings and stringers."""
        return None

    @cached_property
    def net(self) -> CurvatureNet:
        """The face's curvature-line net (:func:`tubecad.nets.curvature_net`), made once."""
        from tubecad.nets import curvature_net

        with stage("host"):
            uv = self._seed_parameters()
            counts = self._counts(uv)
            return curvature_net(self.face, counts[0], counts[1], seed=uv)

    @cached_property
    def refit(self) -> PatchShell | None:
        """With ``patches = "curvature"``, the net's cells on their curvature-line patches
        (:func:`tubecad.nets.patch_shell.patch_shell`), made once; else None."""
        if self.patches != "curvature":
            return None
        from tubecad.nets.patch_shell import patch_shell

        with stage("host"):
            return patch_shell(self.net)

    def build(self, progress: Progress | None = None) -> BuildResult:  # noqa: ARG002 - the protocol's signature
        """The net, the wall, the webs, named and measured (:func:`build_net`)."""
        return build_net(self)

    def build_net(self) -> NetResult:
        """:meth:`build`, typed as what it makes (the parts read its webs and lines)."""
        return build_net(self)

    def shell_model(self, settings: MeshSettings) -> ShellModel:
        """The face's shell model (:func:`tubecad.fem.net_shell.net_shell_mesh`)."""
        from tubecad.design.shell import NetShellModel
        from tubecad.fem.net_shell import net_shell_mesh

        webs = self.web_lines()
        with stage("mesh"):
            mesh = net_shell_mesh(
                self.net,
                settings,
                None if self.wall is None else self.wall.thickness,
                webs,
                None if self.webs is None else self.webs.profile,
                "outside" if self.webs is None else self.webs.side,
                self.length_unit,
                "centered" if self.wall is None else self.wall.side,
            )
        return NetShellModel(mesh)

    def shop(self, fab: Fabrication, progress: Callable[[str], None] | None = None) -> ShopPackage:
        """The webs developed flat and nested on plates, the net's marking lines, a pin jig per
        panel and, with ``patches = "curvature"``, each refitted panel's development
        (:func:`tubecad.shop.net_shop.net_shop`)."""
        from tubecad.shop.net_shop import net_shop

        if progress is not None:
            progress("tracing the net and its webs")
        webs = self.built_webs()
        refit = self.refit
        levels = (0.0, 0.0) if self.wall is None else self.wall.offsets()
        if refit is not None and progress is not None:
            progress("developing the refitted panels")
        with stage("fabrication"):
            return net_shop(self.net, webs, fab, levels, refit)

    @classmethod
    def analysis_ends(cls, given: str | None, default: str) -> str:  # noqa: ARG003 - the protocol's signature
        """A face's edges are held (``fixed``); ``given`` must be that or None."""
        if given not in (None, "fixed"):
            raise ParameterError(
                f"ends must be fixed for a face's net (its boundary is held), got {given!r:.40}", key="ends"
            )
        return "fixed"

    def web_lines(self) -> list[str]:
        """The names of the lines that carry webs."""
        if self.webs is None:
            return []
        counts = self.counts
        with stage("stiffeners"):
            return self.webs.names(counts)

    @property
    def counts(self) -> tuple[int, int]:
        """The net's lines per family (as built)."""
        lines = self.net.lines
        return (sum(n.startswith("k1_") for n in lines), sum(n.startswith("k2_") for n in lines))

    def built_webs(self) -> list[NetWeb]:
        """The webs on the chosen lines (:func:`tubecad.stiffeners.net_webs.net_web`)."""
        from tubecad.stiffeners.net_webs import net_web

        if self.webs is None:
            return []
        names = self.web_lines()
        net, chosen = self.net, self.webs
        base = 0.0
        if self.wall is not None:
            d_in, d_out = self.wall.offsets()
            base = d_out if chosen.side == "outside" else d_in
        with stage("stiffeners"):
            return [
                net_web(net.host, name, net.lines[name], net.edges[name], chosen.profile, chosen.side, base)
                for name in names
            ]

    def _seed_parameters(self) -> tuple[float, float] | None:
        """The seed point's parameters on the face (None without a seed); a ParameterError
        naming ``seed`` if it is off the face."""
        if self.seed is None:
            return None
        from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
        from OCP.gp import gp_Pnt

        from tubecad.nets import HostSurface

        host = HostSurface.of_face(self.face)
        u0, u1, v0, v1 = host.bounds
        projection = GeomAPI_ProjectPointOnSurf(gp_Pnt(*(float(c) for c in self.seed)), host.surface, u0, u1, v0, v1)
        size = float(np.ptp(host.jet(*np.meshgrid(np.linspace(u0, u1, 9), np.linspace(v0, v1, 9))).X, axis=0).max())
        if projection.NbPoints() == 0 or projection.LowerDistance() > SEED_REACH * size:
            far = "" if projection.NbPoints() == 0 else f" (it lies {projection.LowerDistance():.4g} from it)"
            raise ParameterError(f"seed must be a point on the face{far}, got {list(self.seed)}", key="seed")
        u, v = projection.LowerDistanceParameters()
        if not host.inside(np.array([u]), np.array([v]))[0]:
            raise ParameterError(
                f"seed must be a point on the face (it is outside its boundary), got {list(self.seed)}", key="seed"
            )
        return float(u), float(v)

    def _counts(self, uv: tuple[float, float] | None) -> tuple[int, int]:
        """The lines per family: given, or the guide line's length over the spacing."""
        from tubecad.nets import HostSurface, trace_line
        from tubecad.nets.net import MOST_LINES

        counts = []
        for family, count, spacing in ((1, self.k1_lines, self.k1_spacing), (2, self.k2_lines, self.k2_spacing)):
            if spacing is None:
                counts.append(DEFAULT_LINES if count is None else count)
                continue
            if not (spacing > 0 and np.isfinite(spacing)):
                raise ParameterError(
                    f"k{family}_spacing must be a finite length > 0, got {spacing}", key=f"k{family}_spacing"
                )
            host = HostSurface.of_face(self.face)
            u0, u1, v0, v1 = host.bounds
            start = uv if uv is not None else (0.5 * (u0 + u1), 0.5 * (v0 + v1))
            guide = trace_line(host, start, 2 if family == 1 else 1)
            length = float(guide.sigma[-1] - guide.sigma[0])
            n = max(1, round(length / spacing))
            if n > MOST_LINES:
                raise ParameterError(
                    f"k{family}_spacing must be >= {length / MOST_LINES:.6g} (at most {MOST_LINES} lines on a guide line "
                    f"{length:.6g} long), got {spacing:g}",
                    key=f"k{family}_spacing",
                )
            counts.append(n)
        return counts[0], counts[1]


@dataclass
class NetResult:
    """A net built (:class:`~tubecad.design.result.BuildResult`): its ``design``, the
    ``shell`` (the split face) or ``wall`` solid, the ``webs``, the ``shape`` its files are
    written from (the named assembly) and the ``report``."""

    design: NetDesign
    body: Any  # the split face (a TopoDS shell or compound) or the wall solid
    webs: list[NetWeb] = field(default_factory=list)
    shape: Any = None
    report: dict[str, Any] = field(default_factory=dict)

    @property
    def kind(self) -> str:
        """``net_wall`` with a wall, else ``net_shell``."""
        return "net_wall" if self.design.wall is not None else "net_shell"

    @property
    def length_unit(self) -> str:
        return self.design.length_unit

    @property
    def surfaces(self) -> list:
        """The host surface the net lies on."""
        return [self.design.net.host]

    @property
    def solids(self) -> list[tuple[str, Any]]:
        """(name, OCCT solid): the wall first (if any), then each web."""
        out = [("wall", self.body)] if self.design.wall is not None else []
        return out + [(web.name, web.solid) for web in self.webs]

    @property
    def named_edges(self) -> dict[str, list[Any]]:
        """The net's lines as edges on the face, by name (``k1_03``...)."""
        return {name: [edge.edge] for name, edge in self.design.net.edges.items()}

    @property
    def mesh_radius(self) -> float:
        """The smallest radius of curvature on the face (mesh tolerances are checked against it)."""
        return self.report["host"]["smallest_radius"]

    def lines(self) -> list:
        """A net's lines are its named edges (no polylines are written of them)."""
        return []

    def exportable(self, step_schema: str, deflection: float, angular: float) -> Exportable:
        """What every output of this net is written from: the named assembly."""
        from tubecad.export.registry import Exportable

        marks = tuple(
            ((float(p.point[0]), float(p.point[1]), float(p.point[2])), f"umbilic_{i}: {p.type}")
            for i, p in enumerate(self.design.net.umbilics.points)
        )
        return Exportable(
            self.shape,
            None,
            step_schema,
            mesh_deflection=deflection,
            mesh_angular=angular,
            length_unit=self.length_unit,
            marks=marks,
        )

    def written_reference(self) -> Any:
        """The assembly written, its area and volume integrated once for all the files."""
        from tubecad.export.readback import WrittenShape

        return WrittenShape(self.shape)

    def check_file(
        self, tmp: Path, fmt: OutputFormat, target: Path, reference: Any, deflection: float, angular: float
    ) -> dict[str, Any]:
        """Read a just-written file back: a CAD file's solids (the wall, the webs) and faces,
        valid, its area and volume those written, a STEP file's line and umbilic names all
        there; a mesh's triangles; a picture's pixels. Raises if not (never moved into place)."""
        from tubecad.export.cad import step_names
        from tubecad.export.readback import FileAccuracyError, mesh_report, picture_pixels, readback_report

        if fmt.kind == "picture":
            return picture_pixels(tmp, fmt.name)
        if fmt.kind == "mesh":
            return mesh_report(tmp, fmt.name, None, deflection, target, None, self.length_unit, angular)
        info = readback_report(tmp, reference, None, target, None, self.length_unit)
        if info["solids"] != len(self.solids):
            raise FileAccuracyError(f"{target.name}: reads back as {info['solids']} solids, not {len(self.solids)}")
        if info["area_relative_error"] > 1e-6:
            raise FileAccuracyError(
                f"{target.name}: its area reads back {info['area_relative_error']:.2g} off the net's", key="length_unit"
            )
        if fmt.name == "step":
            names = {name for _, name in step_names(tmp)}
            wanted = set(self.design.net.edges) | set(self.design.net.vertices) | {web.name for web in self.webs}
            missing = sorted(wanted - names)
            if missing:
                raise FileAccuracyError(f"{target.name}: the names {', '.join(missing[:4])} did not read back")
            info["names"] = len(wanted)
        return info


def build_net(design: NetDesign) -> NetResult:
    """The design built: the net (its patches one valid shell), the wall thickened from it,
    the webs on the chosen lines, the named assembly, and the report (:func:`net_report`)."""
    from tubecad.brep.segments import segmented

    net = design.net
    refit = design.refit  # before the edges' curves are cut: the cells find their lines by them
    body = net.patches if refit is None else refit.shell
    segmented(body)  # each piece of a split line on its own part of the curve: files 6x smaller
    if design.wall is not None:
        with stage("wall"):
            body = thickened(body, design.wall)
    webs = design.built_webs()
    result = NetResult(design, body, webs)
    result.shape = net_assembly(result)
    result.report = net_report(result)
    if refit is not None:
        result.report["patches"] = refit.report()
    return result


def thickened(patches: Any, wall: WallChoice) -> Any:
    """The split face as a wall of ``wall.thickness`` on its side of the face: offset by the
    wall's inner offset (centered: half the thickness against the normal), then thickened
    (``BRepOffset_MakeOffset`` by join, build123d's ``Solid.thicken``), its offset edges'
    curves made again to 1e-9 (:func:`~tubecad.brep.offset_edges.tighten_offset_edges`: OCCT's
    1e-5 reads back from STEP failing the pre-boolean check); a ParameterError
    naming ``thickness`` if OCCT cannot make it valid (a wall thicker than a radius of
    curvature folds)."""
    import build123d as bd
    from OCP.BRep import BRep_Tool
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepOffsetAPI import BRepOffsetAPI_MakeOffsetShape

    from tubecad.brep.offset_edges import tighten_offset_edges

    d_in, d_out = wall.offsets()
    shell = bd.Shell(bd.Shape.cast(patches).faces())
    if BRep_Tool.IsClosed_s(
        shell.wrapped
    ):  # every edge twice but the degenerate ones  # a closed face (an ellipsoid): the hollow between two offsets
        return hollow(shell.wrapped, d_in, d_out, wall.thickness)
    if d_in != 0.0:
        offset = BRepOffsetAPI_MakeOffsetShape()
        offset.PerformByJoin(shell.wrapped, d_in, 1e-7)
        if not offset.IsDone():
            raise ParameterError(
                f"thickness {wall.thickness:g}: OCCT could not offset the face by {d_in:g}", key="thickness"
            )
        shell = bd.Shell(bd.Shape.cast(offset.Shape()).faces())
    try:
        solid = bd.Solid.thicken(shell, d_out - d_in)
    except Exception as exc:
        raise ParameterError(
            f"thickness {wall.thickness:g}: OCCT could not thicken the face ({exc})", key="thickness"
        ) from None
    tighten_offset_edges(solid.wrapped)  # its edges exact enough to survive a STEP file
    if not BRepCheck_Analyzer(solid.wrapped).IsValid():
        raise ParameterError(
            f"thickness {wall.thickness:g}: the wall fails OCCT's validity check (thicker than a radius of curvature?)",
            key="thickness",
        )
    return solid.wrapped


def hollow(shell: Any, d_in: float, d_out: float, thickness: float) -> Any:
    """The solid between a closed shell's offsets by ``d_in`` and ``d_out`` (OCCT's simple
    offset, ``BRepOffsetAPI_MakeOffsetShape::PerformBySimple``: face by face, no joins to make
    on a closed shell), the inner one its hole; checked valid.

    The offset faces' surfaces are made B-splines (``ShapeCustom::ConvertToBSpline``, within
    1e-7 of the offset, then ``ShapeFix_Shape``): a ``Geom_OffsetSurface`` of a C0 basis (a
    sphere or an ellipsoid converted to NURBS: degree 2, double knots) is written to STEP but OCCT's reader refuses
    it ("Offset with no C1 Surface") and drops the face, and OCCT integrates its volume
    0.3 % off near the poles. The conversion approximates the whole offset for each face;
    each is cut to its face (:func:`tubecad.brep.trimmed_surfaces.segment_to_faces`: 7.2 MB
    of STEP for a 3 x 3 net's wall, 18 MB before)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepOffsetAPI import BRepOffsetAPI_MakeOffsetShape
    from OCP.ShapeCustom import ShapeCustom
    from OCP.ShapeFix import ShapeFix_Shape

    from tubecad.brep.trimmed_surfaces import segment_to_faces
    from tubecad.occ_compat import as_shell

    def offset(distance: float) -> Any:
        if distance == 0.0:
            return shell
        maker = BRepOffsetAPI_MakeOffsetShape()
        maker.PerformBySimple(shell, distance)
        if not maker.IsDone():
            raise ParameterError(
                f"thickness {thickness:g}: OCCT could not offset the face by {distance:g}", key="thickness"
            )
        fix = ShapeFix_Shape(ShapeCustom.ConvertToBSpline_s(maker.Shape(), False, False, True, False))
        fix.SetPrecision(1e-7)
        fix.SetMaxTolerance(1e-5)
        fix.Perform()  # a converted face by a pole can come out invalid: its edges retoleranced
        sewing = BRepBuilderAPI_Sewing(1e-7)
        sewing.Add(fix.Shape())
        sewing.Perform()
        sewn = as_shell(sewing.SewedShape())
        segment_to_faces(sewn)  # each face's B-spline of the whole offset cut to the face
        return sewn

    maker = BRepBuilderAPI_MakeSolid(offset(d_out))
    maker.Add(as_shell(offset(d_in).Reversed()))
    solid = maker.Solid()
    if not BRepCheck_Analyzer(solid).IsValid():
        raise ParameterError(f"thickness {thickness:g}: the hollow wall fails OCCT's validity check", key="thickness")
    return solid


def net_assembly(result: NetResult) -> Any:
    """``net`` (the split face) or ``wall``, each web (``stiffener_k1_03``...), the lines
    (``k1_03``... as edges) and the umbilics (``umbilic_0``... as vertices)."""
    import build123d as bd
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Compound

    from tubecad.occ_compat import as_solid

    builder = BRep_Builder()
    net = result.design.net
    body = (
        bd.Solid(as_solid(result.body))
        if result.design.wall is not None
        else bd.Shell(bd.Shape.cast(result.body).faces())
    )
    body.label = "wall" if result.design.wall is not None else "net"
    children: list[Any] = [body]
    for web in result.webs:
        solid = bd.Solid(web.solid)
        solid.label = web.name
        children.append(solid)
    edges = []
    for name, line in net.edges.items():
        edge = bd.Edge(line.edge)
        edge.label = name
        edges.append(edge)
    lines = bd.Compound(children=edges)
    lines.label = "lines"
    children.append(lines)
    vertices = []
    for name, vertex in net.vertices.items():  # each in a compound of its own: STEP names a compound, not a vertex
        holder = TopoDS_Compound()
        builder.MakeCompound(holder)
        builder.Add(holder, vertex)
        point = bd.Compound(holder)
        point.label = name
        vertices.append(point)
    if vertices:
        umbilics = bd.Compound(children=vertices)
        umbilics.label = "umbilics"
        children.append(umbilics)
    assembly = bd.Compound(children=children)
    assembly.label = "curvature_net"
    return assembly


def net_report(result: NetResult) -> dict[str, Any]:
    """The report: ``host`` (the face's area, its smallest radius of curvature, its umbilics
    ``[{"name", "point", "type", "index", "separatrices"}]``, an umbilic region), ``net``
    (lines per family, each line's length, how it stopped, its edge's angle to the principal
    direction and gap; the largest angle), ``brep`` (kind, patches, validity, area, volume),
    ``stiffeners`` (each web's length, developed area, volume)."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    from tubecad.brep import properties as props

    design, net = result.design, result.design.net
    lines = net.report()
    counts = design.counts
    report: dict[str, Any] = {
        "kind": result.kind,
        "units": {"length": design.length_unit},
        "host": {
            "area": props.area(net.patches),
            "smallest_radius": smallest_radius(net.host),
            "umbilics": lines["umbilics"],
            "umbilic_region": lines["umbilic_region"],
            "umbilic_parts": lines["umbilic_parts"],
        },
        "net": {
            "k1_lines": counts[0],
            "k2_lines": counts[1],
            "angle": lines["angle"],
            "gap": max((e.gap for e in net.edges.values()), default=0.0),
            "lines": lines["lines"],
        },
        "brep": {
            "kind": result.kind,
            "patches": props.count(net.patches, "face"),
            "valid": bool(BRepCheck_Analyzer(result.body).IsValid()),
        },
    }
    if design.wall is not None:
        report["brep"]["volume"] = props.volume(result.body)
        report["brep"]["thickness"] = design.wall.thickness
    if result.webs:
        report["stiffeners"] = {
            web.name: {
                "line": web.line,
                "length": web.pattern.base_length,
                "developed_area": web.pattern.area,
                "volume": props.volume(web.solid),
            }
            for web in result.webs
        }
    return report


def smallest_radius(face: Any) -> float:
    """The face's smallest radius of curvature: 1 / the largest |k1|, |k2| on a 41 x 41 grid
    of its parameter box (``face``: a face or a HostSurface); what mesh tolerances are
    checked against."""
    from tubecad.nets import HostSurface, principal_field

    host = face if isinstance(face, HostSurface) else HostSurface.of_face(face)
    u0, u1, v0, v1 = host.bounds
    u, v = np.meshgrid(np.linspace(u0, u1, 41), np.linspace(v0, v1, 41))
    field = principal_field(host, u.ravel(), v.ravel())
    largest = float(np.nanmax(np.maximum(np.abs(field.k1), np.abs(field.k2))))
    return 1.0 / largest if largest > 0 else float("inf")
