"""Spec files: a tube described in TOML (see docs/spec-files.md).

    [axis]
    curve = "log_spiral"      # log_spiral | helix | clothoid | involute | custom
    a = 10.0                  # the family's parameters (custom: k = "<expression in s>")
    beta_deg = 10.0
    s = [200.0, 1200.0]

    [tube]
    radius = 15.0

    [units]                   # optional
    length = "mm"             # mm | cm | m | in | ft: every length above, and in the files

Every key is checked: unknown or missing keys, wrong types and out-of-range values raise
:class:`SpecError` naming the section, the key and what is allowed.

The keys themselves are tables in :mod:`tubecad.spec.keys` (light, no numpy),
from which ``tubecad schema`` also makes the JSON Schema (:mod:`tubecad.spec.schema`)
that editors use. The schema checks types, ranges, choices and unknown keys; this checker
checks those with one-line messages and, beyond them, what depends on the geometry.
[units] length is the model's unit: nothing is rescaled, the writers state it in the files
(:mod:`tubecad.core.units`), and [stiffeners] density is per cubic unit of it.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, TypeAlias, TypeVar

from tubecad.core.errors import ParameterError, RegularityError, SpecError, TubecadError

# the key tables live in a light module (no numpy, no OCCT) that ``tubecad schema`` reads too
from tubecad.spec.checks import check_keys as _check_keys
from tubecad.spec.checks import short as _short
from tubecad.spec.checks import toml_type as _toml_type
from tubecad.spec.keys import (  # noqa: F401
    ARRAY_SECTIONS,
    AXIS_COMMON,
    EXTRA_SECTIONS,
    FAMILY_KEYS,
    TUBE_KEYS,
    UNITS_KEYS,
    Key,
)
from tubecad.spec.model import (
    BatchSection,
    BranchSection,
    FitSection,
    LayoutSection,
    PanelsSection,
    SpecModel,
    SpecSections,
)

if TYPE_CHECKING:  # the axis and the surface load numpy and scipy: imported once the keys are checked
    from tubecad.curves import Axis
    from tubecad.spec.host import HostSpec
    from tubecad.surface import CanalSurface, CurvatureLineTube
    from tubecad.surface.protocol import CurvatureLineSurface

MAX_SPEC_BYTES = 1_000_000
T = TypeVar("T")


@dataclass(frozen=True)
class TubeSpec(SpecSections):
    """A checked spec: the tube it describes, its sections typed (``model``, a
    :class:`~tubecad.spec.model.SpecModel`, also reached as ``spec.wall``, ``spec.stiffeners``,
    ...) and the checked tables as the file gives them (``sections``, for a script that reads
    a key by name); the later stages read the typed model only."""

    tube: CurvatureLineTube | CanalSurface  # a constant radius, or a radius law
    sections: dict[str, dict[str, Any]]
    source: str
    model: SpecModel = None  # type: ignore[assignment]  # made from ``sections`` when not given

    def __post_init__(self) -> None:
        if self.model is None:
            object.__setattr__(self, "model", SpecModel.from_sections(self.sections))

    #: a tube spec has no [host] (tubecad.spec.host.HostSpec has)
    host: ClassVar[None] = None

    def dispatch(self, on_tube: Callable[[TubeSpec], T], on_host: Callable[[Any], T]) -> T:  # noqa: ARG002 - the specs' signature
        """``on_tube(self)``: what a command does with a spec, chosen by its kind (a [host]
        spec calls ``on_host``)."""
        return on_tube(self)

    @property
    def axis(self) -> Axis:
        return self.tube.axis

    @property
    def layout(self) -> LayoutSection:
        return self.model.layout

    @property
    def fit(self) -> FitSection:
        return self.model.fit

    @property
    def panels(self) -> PanelsSection | None:
        return self.model.panels

    @property
    def batch(self) -> BatchSection | None:
        return self.model.batch

    @property
    def branches(self) -> tuple[BranchSection, ...]:
        return self.model.branches

    @property
    def canal(self) -> bool:
        """Whether the tube is a canal surface (a radius law), not a constant radius."""
        return not self.tube.constant_radius

    @property
    def min_radius(self) -> float:
        """The tube's radius, or the smallest radius of its law."""
        return self.tube.radius_law.min_radius  # a tube's law is its constant radius


#: a checked spec: a tube's ([axis] and [tube]) or a face's ([host])
AnySpec: TypeAlias = "TubeSpec | HostSpec"


def load_spec(path: str | Path) -> AnySpec:
    """Read and check a TOML spec file.

    Nothing is built in OCCT: the spec's sections are checked and its exact surface made
    (:func:`parse_spec`); :func:`~tubecad.spec.build.build_spec` builds it.

    Args:
        path: the spec file (TOML, UTF-8); relative paths inside it (a points file, ...)
            are read from its folder.

    Returns:
        The checked :class:`TubeSpec`: its tube (or canal surface) and typed sections.

    Raises:
        SpecError: the file cannot be read, is not TOML, or has a bad section, key or value;
            its message and its ``key`` (``"wall.thickness"``) name what is wrong.
    """
    return parse_spec(read_spec_data(path), str(path), Path(path).parent)


def tube_spec(spec: AnySpec, command: str) -> TubeSpec:
    """``spec`` if it is a tube's; a [host] spec is refused in one line naming ``host``: the
    ``command`` (``tubecad paper``...) makes tubes only (build, report, flat, view, shop, mesh and analyse
    take both)."""

    def refuse(host: Any) -> TubeSpec:
        raise SpecError(
            f"{host.source}: [host]: {command} makes tubes ([axis] and [tube]); a face's net is built by tubecad "
            "build, report, flat, view, shop, mesh and analyse",
            key="host",
        )

    return spec.dispatch(lambda tube: tube, refuse)


def read_spec_data(path: str | Path) -> dict[str, Any]:
    """Read a TOML spec file into a dict, unchecked (:func:`parse_spec` checks it)."""
    path = Path(path)
    try:
        with open(path, "rb") as file:
            raw = file.read(MAX_SPEC_BYTES + 1)  # bounded: /dev/zero or a huge file is refused, not read
    except OSError as exc:
        raise SpecError(f"cannot read spec file {str(path)!r}: {exc.strerror}") from None
    if len(raw) > MAX_SPEC_BYTES:
        raise SpecError(
            f"{path}: spec file is larger than {MAX_SPEC_BYTES} bytes; at most {MAX_SPEC_BYTES} are allowed"
        )
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise SpecError(f"{path}: spec file is not UTF-8 text") from None
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:
        raise SpecError(f"{path}: not valid TOML: nested too deeply") from None
    return data


def parse_spec(data: dict[str, Any], source: str = "<spec>", base: Path | None = None) -> AnySpec:
    """Check a parsed spec (a dict as tomllib gives), build its tube and type its sections
    (:class:`~tubecad.spec.model.SpecModel`). A :class:`SpecError` names the section and the
    key in its message and, for code, in its ``key`` (``"wall.thickness"``, ``"layout"``)."""

    def fail(msg: str, key: str | None = None) -> SpecError:
        return SpecError(f"{source}: {msg}", key=key)

    if "host" in data:  # a face the user has, not a tube: its own sections (tubecad.spec.host)
        from tubecad.spec.host import parse_host_spec

        if not isinstance(data["host"], dict):
            raise fail(f"[host] must be a table (a [host] section), got {_toml_type(data['host'])}", "host")
        return parse_host_spec(data, source, base)
    allowed_sections = {"axis": None, "tube": TUBE_KEYS, **EXTRA_SECTIONS}
    for name, value in data.items():
        if name in ARRAY_SECTIONS:
            if not (isinstance(value, list) and value and all(isinstance(v, dict) for v in value)):
                raise fail(f"[[{name}]] must be tables (one [[{name}]] section each), got {_toml_type(value)}", name)
            continue
        if name not in allowed_sections:
            known = [f"[{s}]" for s in allowed_sections] + [f"[[{s}]]" for s in ARRAY_SECTIONS]
            raise fail(f"unknown section [{_short(name)}]; allowed sections are {', '.join(known)}", _short(name))
        if not isinstance(value, dict):
            raise fail(f"[{name}] must be a table (a [{name}] section), got {_toml_type(value)}", name)
    for name in ("axis", "tube"):
        if name not in data:
            raise fail(f"missing section [{name}]", name)

    axis_data = data["axis"]
    curve = axis_data.get("curve")
    if not isinstance(curve, str) or curve not in FAMILY_KEYS:
        if "curve" not in axis_data:
            raise fail(f"[axis] curve is missing; allowed: {AXIS_COMMON['curve'].help}", "axis.curve")
        raise fail(f"[axis] curve must be one of {AXIS_COMMON['curve'].help}, got {_short(repr(curve))}", "axis.curve")
    axis_keys = {**AXIS_COMMON, **FAMILY_KEYS[curve]}
    sections = {"axis": _check_keys("axis", axis_data, axis_keys, fail)}
    for name, keys in allowed_sections.items():
        if name != "axis" and name in data:
            sections[name] = _check_keys(name, data[name], keys, fail)  # type: ignore[arg-type]
    checked: dict[str, Any] = dict(sections)
    for name, keys in ARRAY_SECTIONS.items():
        if name in data:
            checked[name] = [
                _check_keys(name, table, keys, _numbered(fail, name, i)) for i, table in enumerate(data[name])
            ]
    model = SpecModel.from_sections(checked)

    # the keys and their values are checked: now the maths (numpy, scipy), never before, so a
    # mistake in the file is refused in a fraction of a second
    from tubecad.spec.axis import build_axis
    from tubecad.surface import tube_or_canal

    length_unit = model.units.length
    axis = _with_section("axis", fail, lambda: build_axis(curve, model.axis.values, base, length_unit))
    radius = model.tube.radius
    try:  # a number: the tube; an expression or a table: the canal surface of that radius law
        tube = tube_or_canal(axis, radius, allow_irregular=model.tube.allow_irregular)
    except ParameterError as exc:
        raise fail(f"[tube] {exc}", _key("tube", exc, "radius")) from None
    except RegularityError as exc:
        shown = f"{radius:g}" if isinstance(radius, (int, float)) else _short(repr(radius), 40)
        raise fail(f"[tube] radius {shown}: {_irregular(exc)}", "tube.radius") from None
    layout = model.layout
    for count, listed in (("rings", "s_rings"), ("stringers", "u_stringers_deg")):
        if getattr(layout, count) is not None and getattr(layout, listed) is not None:
            raise fail(f"[layout] give either {count} or {listed}, not both", f"layout.{count}")
    if model.stiffeners is not None:
        for key in ("k1", "k2"):  # a [host] net's lines, not a tube's
            if getattr(model.stiffeners, key) != ():
                raise fail(
                    f"[stiffeners] {key} chooses a [host] net's lines; a tube's are its rings and stringers",
                    f"stiffeners.{key}",
                )
    _check_build_sections(tube, model, fail, source)
    if model.branches:
        _check_branches(tube, model, fail)
    return TubeSpec(tube, checked, source, model)


def _numbered(fail: Callable[..., SpecError], name: str, index: int) -> Callable[..., SpecError]:
    """``fail`` for the table ``index`` of [[name]]: its messages say which one (from 1)."""

    def numbered(msg: str, key: str | None = None) -> SpecError:
        number = f"[[{name}]] #{index + 1}"
        if f"[{name}." in msg:  # a key of an inline table: [branches.wall] side -> [[branches]] #1 [wall] side
            return fail(msg.replace(f"[{name}.", f"{number} [", 1), key)
        return fail(msg.replace(f"[{name}]", number, 1), key)

    return numbered


def _check_branches(tube: CurvatureLineSurface, model: SpecModel, fail: Callable[..., SpecError]) -> None:
    """[[branches]]: a main [wall] to join (and no [panels]: not built on a junction yet);
    branch stiffeners with the main [stiffeners] and indices in the branch's layout; each branch placed inside the main axis' span, its tube regular, its
    surfaces starting inside the main's (:func:`tubecad.junctions.placement.branch_start_problem`,
    the builder's rule too), a blend's ball rolling round its saddle
    (:func:`tubecad.junctions.placement.blend_problem`, the same)."""
    from tubecad.core.tolerance import MIN_SIZE
    from tubecad.junctions.placement import blend_problem, branch_start_problem

    if model.wall is None:
        raise fail("[[branches]] join the branch's wall to the main tube's: the spec needs a [wall] section", "wall")
    if model.panels is not None:
        raise fail("[panels] on a wall with [[branches]] is not built yet: remove one of them", "panels")
    main_offsets = model.wall.offsets()
    for i, branch in enumerate(model.branches):
        where = f"[[branches]] #{i + 1}"
        try:
            surface = branch.surface(tube)
        except ParameterError as exc:
            raise fail(f"{where} {exc}", f"branches.{exc.key or 'radius'}") from None
        except RegularityError as exc:
            raise fail(f"{where} radius: {_irregular(exc)}", "branches.radius") from None
        if branch.layout is not None:
            try:
                branch.layout.net(surface)
            except ParameterError as exc:
                raise fail(f"{where} layout {exc}", f"branches.{_key('layout', exc)}") from None
        if branch.stiffeners is not None:
            if model.stiffeners is None:
                raise fail(
                    f"{where} stiffeners take the main [stiffeners] profile and side: the spec needs a [stiffeners] "
                    "section",
                    "stiffeners",
                )
            gap = branch.stiffeners.start
            if gap is not None and not (gap >= 0 and math.isfinite(gap)):
                raise fail(f"{where} stiffeners start must be >= 0, got {gap:g}", "branches.stiffeners.start")
            net = branch.net(surface, len(model.layout.net(tube).stringers_deg))
            for key, count in (("rings", len(net.s_rings)), ("stringers", len(net.stringers_deg))):
                try:
                    branch.stiffeners.indices(key, count)
                except ParameterError as exc:
                    raise fail(f"{where} {exc}", exc.key or "branches.stiffeners") from None
        if branch.pad is not None:
            for name in ("thickness", "width"):
                value = getattr(branch.pad, name)
                if not (value > 0 and math.isfinite(value)):
                    raise fail(f"{where} pad {name} must be > 0, got {value:g}", f"branches.pad.{name}")
        if branch.blend is not None:
            if not (branch.blend.radius > 0 and math.isfinite(branch.blend.radius)):
                raise fail(f"{where} blend radius must be > 0, got {branch.blend.radius:g}", "branches.blend.radius")
            if branch.pad is not None:
                raise fail(f"{where} blend: a blend with a pad round the branch is not made yet", "branches.blend")
        wall = branch.wall or model.wall
        try:
            b_in, b_out = wall.offsets()
        except ParameterError as exc:
            raise fail(f"{where} wall {exc}", "branches.wall.thickness") from None
        if surface.radius_law.min_radius + b_in < MIN_SIZE:
            raise fail(
                f"{where} wall: thickness {wall.thickness:g} leaves no bore in the branch", "branches.wall.thickness"
            )
        # each branch surface starts inside its main surface: the builder's own rule
        problem = branch_start_problem(tube, main_offsets, surface, (b_in, b_out), branch.at)
        if problem is not None:
            raise fail(f"{where} {problem[0]}", "branches.radius" if abs(branch.offset) == 0 else "branches.offset")
        if branch.blend is not None:  # the ball rolls round the outer saddle: the builder's rule too
            outer = tube.offset(main_offsets[1]), surface.offset(b_out)
            rolls = blend_problem(*outer, branch.blend.radius)
            if rolls is not None:
                raise fail(f"{where} blend radius: {rolls}", "branches.blend.radius")


def _check_build_sections(
    tube: CurvatureLineSurface, model: SpecModel, fail: Callable[..., SpecError], source: str
) -> None:
    """Check what the B-rep needs ([tube] sizes, [layout], [wall], [fit]) against the tube now,
    so that a bad value is refused before anything is built, by ``report`` as by ``build``.
    The rules themselves live with the B-rep code."""
    from tubecad.core.tolerance import MIN_SIZE, check_reachable, check_tolerance

    canal = not tube.constant_radius
    smallest = tube.radius_law.min_radius  # a tube's law is its constant radius
    if smallest < MIN_SIZE:
        where = (
            f"; r reaches {smallest:g} at s = {tube.radius_law.s_at_min_radius:.6g}" if canal else f", got {smallest:g}"
        )
        raise fail(f"[tube] radius must be >= {MIN_SIZE:g} model units for a B-rep{where}", "tube.radius")
    if tube.length < MIN_SIZE:
        raise fail(f"[axis] s must span at least {MIN_SIZE:g} model units for a B-rep, got {tube.length:g}", "axis.s")
    tolerance = _with_section("fit", fail, lambda: check_tolerance("tolerance", model.fit.tolerance), "tolerance")
    _with_section("fit", fail, lambda: check_reachable("tolerance", tolerance, _size(tube, model)), "tolerance")
    layout = _with_section("layout", fail, lambda: model.layout.net(tube))
    unit = model.units.length
    if model.stiffeners is not None:  # the indices against the layout, before anything is built
        model.stiffeners.select(layout, source, unit)
    if model.panels is not None:
        panels = model.panels
        _with_section(
            "panels",
            fail,
            lambda: layout.panel_bounds(panels.seam_indices(len(layout.stringers_deg)), panels.ring_indices()),
        )
    if model.fabrication is not None:  # the shop's settings, in the spec's length unit
        try:
            model.fabrication.settings(unit)
        except ParameterError as exc:
            raise fail(str(exc), _key("fabrication", exc)) from None
    if model.mesh is not None or model.analysis is not None:  # the mesh's and the analysis' settings
        from tubecad.spec.model import AnalysisSection, MeshSection

        try:
            (model.mesh or MeshSection()).settings()
        except ParameterError as exc:
            raise fail(str(exc), _key("mesh", exc)) from None
        try:
            (model.analysis or AnalysisSection()).settings(unit, bool(tube.axis.closed))
        except ParameterError as exc:
            raise fail(str(exc), _key("analysis", exc)) from None
    if canal:  # a varying radius law: its offsets are canal surfaces
        return _check_canal_sections(tube, model, fail)
    wall = model.wall
    if wall is not None:
        radius = tube.radius_law.constant_value  # a constant radius: the tube's rho
        r_in, r_out = _with_section("wall", fail, lambda: wall.radii(radius), "thickness")
        from tubecad.surface import CurvatureLineTube

        try:
            CurvatureLineTube(tube.axis, r_out)
        except ParameterError as exc:
            raise fail(
                f"[wall] thickness {wall.thickness:g} puts the wall's outer surface at radius {r_out:g}: {exc}",
                "wall.thickness",
            ) from None
        except RegularityError as exc:
            raise fail(
                f"[wall] the wall's outer surface is not regular: thickness {wall.thickness:g} "
                f"(side = {wall.side!r}) puts it at radius {r_out:g}: {_irregular(exc)}",
                "wall.thickness",
            ) from None
        if model.stiffeners is not None:  # a stiffener too high for the wall's curvature
            from tubecad.stiffeners.limits import check_spec_heights

            stiffeners, layout = model.stiffeners, model.layout.net(tube)
            _with_section(
                "stiffeners",
                fail,
                lambda: check_spec_heights(tube.axis, layout, (r_in, r_out), stiffeners.table()),
                "height",
            )


def _size(tube: CurvatureLineSurface, model: SpecModel) -> float:
    """The largest coordinate magnitude of the surfaces a spec fits: the axis's largest |c|
    (2001 samples) plus the largest radius and the wall's thickness."""
    import numpy as np

    s = np.linspace(*tube.span, 2001)
    wall = model.wall.thickness if model.wall is not None else 0.0
    return float(np.abs(tube.axis.position(s)).max()) + tube.radius_law.max_radius + wall


def _check_canal_sections(surface: CurvatureLineSurface, model: SpecModel, fail: Callable[..., SpecError]) -> None:
    """A radius law's [wall]: the offsets of the law, the inner one above MIN_SIZE, the outer
    one regular, and a [stiffeners] section's surfaces regular too."""
    from tubecad.core.tolerance import MIN_SIZE

    law, wall = surface.radius_law, model.wall
    if wall is not None:
        side = wall.side
        d_in, d_out = _with_section("wall", fail, wall.offsets, "thickness")
        if law.min_radius + d_in < MIN_SIZE:
            raise fail(
                f"[wall] thickness {wall.thickness:g} (side = {side!r}) is too thick for the smallest radius "
                f"{law.min_radius:g} at s = {law.s_at_min_radius:.6g}: the inner surface must stay at radius "
                f">= {MIN_SIZE:g}",
                "wall.thickness",
            )
        try:
            surface.offset(d_out)
        except (ParameterError, RegularityError) as exc:
            raise fail(
                f"[wall] the wall's outer surface (the radius law + {d_out:g}) is not regular: {_irregular(exc)}",
                "wall.thickness",
            ) from None
        if model.stiffeners is not None:  # a stiffener whose own surfaces would fold, or reach past the axis
            from tubecad.stiffeners.canal import check_spec_heights

            stiffeners, layout = model.stiffeners, model.layout.net(surface)
            _with_section(
                "stiffeners",
                fail,
                lambda: check_spec_heights(surface, layout, (d_in, d_out), stiffeners.table()),
                "height",
            )


def _key(section: str, exc: TubecadError, default: str | None = None) -> str:
    """``section.key`` for an error a rule raised about ``section``: its own key (made
    ``section.key`` if it names a key alone), else ``default``, else the section."""
    key = exc.key or default
    if key is None:
        return section
    return key if key == section or key.startswith(f"{section}.") else f"{section}.{key}"


def _irregular(exc: TubecadError) -> str:
    return str(exc).replace(
        "(pass allow_irregular=True to build it anyway)", "(set [tube] allow_irregular = true to build it anyway)"
    )


def _with_section(
    name: str, fail: Callable[..., SpecError], build: Callable[[], Any], default_key: str | None = None
) -> Any:
    """``build()``, a ParameterError from it raised as a SpecError on section ``name``
    (its key: the error's own, else ``default_key``, within the section)."""
    try:
        return build()
    except ParameterError as exc:
        raise fail(f"[{name}] {exc}", _key(name, exc, default_key)) from None
