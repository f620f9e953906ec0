"""A checked spec as a design value (:mod:`tubecad.design`), and the design's build errors
in the spec's vocabulary.

:func:`design_of` is the one place that reads the spec's sections into what is built: a
:class:`~tubecad.design.wall.WallDesign` from [tube], [layout], [fit], [wall],
[stiffeners] and [panels], a :class:`~tubecad.design.junction.JunctionDesign` when the spec
has [[branches]]. Every command then builds the design the same way, whatever it is.
:func:`spec_errors` turns an error of the build (Python terms, tagged with the design
field that failed: :func:`tubecad.design.stages.stage`) into a SpecError naming the
section and the key.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from tubecad.core.errors import ParameterError, SpecError, TubecadError
from tubecad.spec.parse import AnySpec, TubeSpec
from tubecad.spec.sections import spec_error

if TYPE_CHECKING:
    from tubecad.design.junction import JunctionDesign
    from tubecad.design.model import BranchDesign
    from tubecad.design.net import NetDesign
    from tubecad.design.wall import WallDesign
    from tubecad.spec.host import HostSpec

#: the mesh's parameters named otherwise than the spec's keys (:func:`tubecad.fem.shell_mesh`'s)
SHELL_MESH_KEYS = {"thickness": "wall.thickness", "wall_side": "wall.side", "panel_rings": "panels.rings"}
#: the written files' refusals (tubecad.export.readback) under the spec's section and key
EXPORT_KEYS = {"tolerance": ("fit", "fit.tolerance"), "length_unit": ("units", "units.length")}
#: the shop templates' parameters (tubecad.shop.branch_template) under the spec's keys
TEMPLATE_KEYS = {"branch.radius": "branches.radius", "main.radius": "tube.radius"}
#: the keys of a ParameterError about the fit's tolerances (a [fit] error, not [wall]'s)
FIT_KEYS = ("tolerance", "orthogonality", "fit.tolerance")


def design_of(spec: AnySpec, grid: tuple[int, int] = (64, 501)) -> WallDesign | JunctionDesign | NetDesign:
    """What ``spec`` builds: its wall (or tube), with [[branches]] its junction, or with
    [host] the face's net; ``grid`` = (nu, ns), where a tube's exact surface is measured. A
    SpecError names the section and the key of what cannot be made."""
    return spec.dispatch(lambda tube: tube_design(tube, grid), net_design)


def tube_design(spec: TubeSpec, grid: tuple[int, int] = (64, 501)) -> WallDesign | JunctionDesign:
    """A tube spec's wall (or tube), or with [[branches]] its junction."""
    main = wall_design(spec, grid)
    if not spec.branches:
        return main
    return junction_design(spec, main)


def design_class(spec: AnySpec) -> type[WallDesign] | type[JunctionDesign] | type[NetDesign]:
    """The kind of design ``spec`` builds, known without building anything (what its
    outputs are checked against before the kernel loads)."""
    from tubecad.design.junction import JunctionDesign
    from tubecad.design.net import NetDesign
    from tubecad.design.wall import WallDesign

    def of_tube(tube: TubeSpec) -> type[WallDesign] | type[JunctionDesign]:
        return JunctionDesign if tube.branches else WallDesign

    return spec.dispatch(of_tube, lambda _host: NetDesign)


def net_design(spec: HostSpec) -> NetDesign:
    """A [host] spec's face, its lines, its [wall] and its [stiffeners] webs, as a design."""
    from tubecad.brep.wall import as_wall_side
    from tubecad.design.model import WallChoice
    from tubecad.design.net import NetDesign, NetStiffenerChoice
    from tubecad.stiffeners.profiles import as_stiffener_side

    host = spec.host
    wall = None if spec.wall is None else WallChoice(spec.wall.thickness, as_wall_side(spec.wall.side))
    webs = None
    chosen = spec.stiffeners
    if chosen is not None:
        try:
            profile = chosen.make_profile()
        except ParameterError as exc:
            raise SpecError(f"{spec.source}: [stiffeners] {exc}", key=within("stiffeners", exc)) from None
        webs = NetStiffenerChoice(profile, chosen.k1, chosen.k2, as_stiffener_side(chosen.side), chosen.density)
    seed = None if host.seed is None else (float(host.seed[0]), float(host.seed[1]), float(host.seed[2]))
    return NetDesign(
        spec.face,
        host.lines("k1"),
        host.lines("k2"),
        host.k1_spacing,
        host.k2_spacing,
        seed,
        wall,
        webs,
        spec.length_unit,
        "curvature" if host.patches == "curvature" else "host",
    )


def wall_design(spec: TubeSpec, grid: tuple[int, int] = (64, 501)) -> WallDesign:
    """The spec's main tube or wall, its stiffeners and panels, as a design."""
    from tubecad.brep.wall import as_wall_side
    from tubecad.core.tolerance import check_tolerance
    from tubecad.design.model import PanelChoice, StiffenerChoice, WallChoice
    from tubecad.design.wall import WallDesign
    from tubecad.stiffeners.profiles import as_stiffener_side

    tube = spec.tube
    try:
        layout = spec.layout.net(tube)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [layout] {exc}", key=within("layout", exc)) from None
    try:  # parse_spec checked it; a model made by a script is checked here
        tolerance = check_tolerance("tolerance", spec.fit.tolerance)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}", key="fit.tolerance") from None
    wall = None if spec.wall is None else WallChoice(spec.wall.thickness, as_wall_side(spec.wall.side))
    stiffeners = None
    if spec.stiffeners is not None:  # the section's one check (the mesh makes it too)
        chosen = spec.stiffeners.select(layout, spec.source, spec.length_unit)
        stiffeners = StiffenerChoice(
            tuple(chosen.rings),
            tuple(chosen.stringers),
            chosen.profile,
            as_stiffener_side(chosen.side),
            chosen.fuse,
            chosen.density,
        )
    panels = None
    if spec.panels is not None:
        rings = spec.panels.ring_indices()
        panels = PanelChoice(
            tuple(spec.panels.seam_indices(len(layout.stringers_deg))), None if rings is None else tuple(rings)
        )
    return WallDesign(tube, layout, tolerance, wall, stiffeners, panels, spec.length_unit, grid)


def junction_design(spec: TubeSpec, main: WallDesign) -> JunctionDesign:
    """The spec's junction: ``main`` (its wall design) with every [[branches]] table."""
    from tubecad.design.junction import JunctionDesign

    assert spec.wall is not None  # parse_spec refuses [[branches]] without [wall]
    branches = tuple(branch_design(spec, k, len(main.layout.stringers_deg)) for k in range(len(spec.branches)))
    analysis = spec.analysis
    load = None
    if analysis is not None and analysis.pressure and analysis.allowable_stress:
        load = (analysis.pressure, analysis.allowable_stress)
    return JunctionDesign(main, branches, load)


def branch_design(spec: TubeSpec, k: int, main_stringers: int) -> BranchDesign:
    """The [[branches]] table ``k`` as a design (its wall the main's where it has none)."""
    from tubecad.brep.wall import as_wall_side
    from tubecad.design.model import BranchDesign, PadChoice, WallChoice

    branch = spec.branches[k]
    surface = branch.surface(spec.tube)
    section = branch.wall or spec.wall
    assert section is not None
    layout = branch.net(surface, main_stringers)
    pad = None if branch.pad is None else PadChoice(branch.pad.thickness, branch.pad.width)
    blend = None if branch.blend is None else branch.blend.radius
    chosen = branch.stiffeners
    if chosen is None:
        return BranchDesign(
            surface, WallChoice(section.thickness, as_wall_side(section.side)), layout, pad, blend=blend
        )
    try:
        rings = tuple(chosen.indices("rings", len(layout.s_rings)))
        stringers = tuple(chosen.indices("stringers", len(layout.stringers_deg)))
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: [stiffeners] {exc}", key=exc.key or "stiffeners") from None
    return BranchDesign(
        surface,
        WallChoice(section.thickness, as_wall_side(section.side)),
        layout,
        pad,
        True,
        rings,
        stringers,
        chosen.start,
        blend,
    )


def within(section: str, exc: TubecadError) -> str:
    """The spec key of an error about ``section``: ``section.key``, or the section."""
    key = exc.key
    if key is None:
        return section
    return key if key == section or key.startswith(f"{section}.") else f"{section}.{key}"


@contextmanager
def spec_errors(spec: AnySpec) -> Iterator[None]:
    """Errors of a design's build as SpecErrors naming ``spec``'s section and key: the
    stage the error was tagged with (:func:`tubecad.design.stages.stage`) is the section."""
    from tubecad.fitting import FitError

    try:
        yield
    except SpecError:
        raise
    except FitError as exc:
        raise SpecError(f"{spec.source}: [fit] {exc}", key="fit.tolerance") from None
    except TubecadError as exc:
        raise as_spec_error(spec, exc) from None


def as_spec_error(spec: AnySpec, exc: TubecadError) -> SpecError:
    """``exc`` (raised while ``spec``'s design was built) with the spec's section and key."""
    source, stage = spec.source, exc.stage
    if stage in ("fit", "wall"):
        section = "fit" if exc.key in FIT_KEYS else "wall"
        return SpecError(f"{source}: [{section}] {exc}", key=within(section, exc))
    if stage in ("stiffeners", "panels", "layout", "host"):
        return SpecError(f"{source}: [{stage}] {exc}", key=within(stage, exc))
    if stage == "pads":
        number = "" if exc.branch is None else f" #{exc.branch + 1}"
        key = f"branches.{exc.key}" if exc.key and exc.key.startswith("pad") else exc.key or "branches.pad"
        return SpecError(f"{source}: [[branches]]{number} {exc}", key=key)
    if stage == "mesh":  # the mesh's own keys ([mesh] size, surface), else the section of the key
        return spec_error(source, exc, ("mesh", "stiffeners", "panels"), "mesh", SHELL_MESH_KEYS)
    if stage == "analysis":
        return spec_error(source, exc, ("analysis",), "analysis")
    if stage == "export" and exc.key in EXPORT_KEYS:  # a file that does not hold the build
        section, key = EXPORT_KEYS[exc.key]
        return SpecError(f"{source}: [{section}] {exc}", key=key)
    if stage == "fabrication":  # a value the pieces cannot have (a plate too small, a joint)
        return spec_error(source, exc, ("fabrication",), "fabrication")
    if stage == "templates":  # a branch's or the main tube's radius, under their spec keys
        number = "" if exc.branch is None else f" #{exc.branch + 1}"
        key = TEMPLATE_KEYS.get(exc.key or "", exc.key or "branches")
        return SpecError(f"{source}: [[branches]]{number} {exc}", key=key)
    if stage == "branches":
        number = "" if exc.branch is None else f" #{exc.branch + 1}"
        if exc.key and exc.key.startswith("blend"):  # a branch's own blend table
            return SpecError(f"{source}: [[branches]]{number} {exc}", key=f"branches.{exc.key}")
        key = exc.key if exc.key and exc.key.startswith(("branches", "fit")) else "branches"
        return SpecError(f"{source}: [[branches]]{number} {exc}", key=key)
    return SpecError(f"{source}: {exc}", key=exc.key)
