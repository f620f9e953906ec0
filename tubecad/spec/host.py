"""A spec of a face the user already has: ``[host]`` instead of ``[axis]`` and ``[tube]``
(issue 44; docs/spec-files.md)::

    [host]
    step = "hull_panel.step"   # relative to the spec
    face = 0                   # 0-based in the file's order, or the face's name
    k1_lines = 8               # or k1_spacing = 400.0
    k2_lines = 6               # or k2_spacing
    seed = [2000.0, 1400.0, 300.0]   # optional: a point the first lines pass through
    patches = "curvature"      # optional: the cells refitted in curvature-line coordinates

    [wall]                     # optional: the face thickened into a wall solid
    thickness = 12.0

    [stiffeners]               # optional: webs standing on the net's lines
    k1 = [1, 3, 5]
    height = 150.0
    thickness = 10.0

Its keys are checked like a tube spec's (:mod:`tubecad.spec.checks`, the tables of
:mod:`tubecad.spec.keys`), then the STEP file is read and the face chosen: a file that cannot
be read, a face index past the file's faces or a name it does not hold is refused naming
``host.step`` or ``host.face``. Light until then: OCCT is imported to read the file only.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from tubecad.core.errors import SpecError
from tubecad.export.formats import FORMATS
from tubecad.spec.checks import check_keys, short
from tubecad.spec.keys import EXTRA_SECTIONS, HOST_KEYS, HOST_SECTIONS
from tubecad.spec.model import (
    AnalysisSection,
    FabricationSection,
    MeshSection,
    SpecSections,
    StiffenersSection,
    UnitsSection,
    WallSection,
)

if TYPE_CHECKING:
    from OCP.TopoDS import TopoDS_Face

    from tubecad.spec.model import BranchSection

T = TypeVar("T")
#: lines per family when [host] gives neither a count nor a spacing
DEFAULT_LINES = 8
#: the STEP file's extensions [host] step takes (the format table's)
STEP_SUFFIXES = next(f.extensions for f in FORMATS if f.name == "step")


@dataclass(frozen=True)
class HostSection:
    """[host]: the STEP ``step`` (relative to the spec), which ``face`` of it, the lines per
    family (``k1_lines``, ``k2_lines``) or their spacing, a ``seed`` point, and the cells'
    surfaces (``patches``: ``host`` or ``curvature``)."""

    step: str
    face: int | str = 0
    k1_lines: int | None = None
    k2_lines: int | None = None
    k1_spacing: float | None = None
    k2_spacing: float | None = None
    seed: list[float] | None = None
    patches: str = "host"

    def lines(self, family: str) -> int | None:
        """The family's (``k1``, ``k2``) count: given, or DEFAULT_LINES without a spacing."""
        count, spacing = getattr(self, f"{family}_lines"), getattr(self, f"{family}_spacing")
        return count if count is not None else DEFAULT_LINES if spacing is None else None


@dataclass(frozen=True)
class HostModel:
    """Every section of a checked [host] spec, typed (None where absent)."""

    host: HostSection
    units: UnitsSection = field(default_factory=UnitsSection)
    wall: WallSection | None = None
    stiffeners: StiffenersSection | None = None
    fabrication: FabricationSection | None = None
    mesh: MeshSection | None = None
    analysis: AnalysisSection | None = None


@dataclass(frozen=True)
class HostSpec(SpecSections):
    """A checked [host] spec: the ``face`` read from its STEP file, its checked tables
    (``sections``), ``source`` and typed ``model``."""

    face: TopoDS_Face
    sections: dict[str, dict[str, Any]]
    source: str
    model: HostModel

    def dispatch(self, on_tube: Callable[[Any], T], on_host: Callable[[HostSpec], T]) -> T:  # noqa: ARG002 - the specs' signature
        """``on_host(self)``: what a command does with a spec, chosen by its kind (a tube
        spec calls ``on_tube``)."""
        return on_host(self)

    @property
    def host(self) -> HostSection:
        return self.model.host

    @property
    def min_radius(self) -> float:
        """The face's smallest radius of curvature (1 / the largest |k1|, |k2| on a 41 x 41
        grid of its parameter box): what mesh tolerances are checked against."""
        from tubecad.design.net import smallest_radius

        return smallest_radius(self.face)

    @property
    def panels(self) -> None:
        """A [host] spec has no [panels] (the net's patches are its faces)."""
        return None

    @property
    def branches(self) -> tuple[BranchSection, ...]:
        """A [host] spec has no [[branches]]."""
        return ()

    @property
    def batch(self) -> None:
        return None


def parse_host_spec(data: dict[str, Any], source: str, base: Path | None) -> HostSpec:
    """Check a spec with [host] (its sections' keys, then its file and face) into a HostSpec.

    Args:
        data: the spec as tomllib gives it.
        source: the spec's name in messages.
        base: the folder [host] step is relative to (None: the working folder).

    Returns:
        The checked spec.

    Raises:
        SpecError: naming the section and the key (``host.face``, ``stiffeners.rings``...).
    """

    def fail(msg: str, key: str | None = None) -> SpecError:
        return SpecError(f"{source}: {msg}", key=key)

    allowed = ("host", *HOST_SECTIONS)
    for name in data:
        if name not in allowed:
            raise fail(
                f"[{short(name)}] is not for a [host] spec (that is for a tube's [axis] and [tube]); a [host] spec takes "
                + ", ".join(f"[{s}]" for s in allowed),
                short(name),
            )
    keys = {"host": HOST_KEYS, **{name: EXTRA_SECTIONS[name] for name in HOST_SECTIONS}}
    sections = {name: check_keys(name, data[name], keys[name], fail) for name in allowed if name in data}
    host = HostSection(**sections["host"])
    _check_host(host, fail)
    typed: dict[str, Any] = {"wall": WallSection, "stiffeners": StiffenersSection, "units": UnitsSection}
    typed.update({"fabrication": FabricationSection, "mesh": MeshSection, "analysis": AnalysisSection})
    model = HostModel(host, **{name: typed[name](**sections[name]) for name in HOST_SECTIONS if name in sections})
    _check_stiffeners(model, fail)
    face = _read_face(host, base, model.units.length, fail)
    return HostSpec(face, sections, source, model)


def _check_host(host: HostSection, fail: Callable[..., SpecError]) -> None:
    """The [host] rules beyond the keys' types: one of lines or spacing per family, their
    ranges, a face index >= 0, a finite seed."""
    from tubecad.spec.keys import MOST_HOST_LINES

    for family in ("k1", "k2"):
        count, spacing = getattr(host, f"{family}_lines"), getattr(host, f"{family}_spacing")
        if count is not None and spacing is not None:
            raise fail(f"[host] give either {family}_lines or {family}_spacing, not both", f"host.{family}_lines")
        if count is not None and not 1 <= count <= MOST_HOST_LINES:
            raise fail(f"[host] {family}_lines must be in 1..{MOST_HOST_LINES}, got {count}", f"host.{family}_lines")
        if spacing is not None and not (spacing > 0 and math.isfinite(spacing)):
            raise fail(f"[host] {family}_spacing must be a finite length > 0, got {spacing}", f"host.{family}_spacing")
    if isinstance(host.face, int) and host.face < 0:
        raise fail(f"[host] face must be an index >= 0 or a face's name, got {host.face}", "host.face")
    if host.seed is not None and not all(math.isfinite(c) for c in host.seed):
        raise fail(f"[host] seed must be a finite point [x, y, z], got {host.seed}", "host.seed")


def _check_stiffeners(model: HostModel, fail: Callable[..., SpecError]) -> None:
    """[stiffeners] on a net: its lines by family (k1, k2), not a tube's rings and stringers;
    indices within the counts [host] gives."""
    chosen = model.stiffeners
    if chosen is None:
        return
    for key in ("rings", "stringers"):
        if getattr(chosen, key) != ():
            raise fail(
                f"[stiffeners] {key} are a tube's; on a [host] net choose its lines with k1 and k2", f"stiffeners.{key}"
            )
    if chosen.k1 == () and chosen.k2 == ():
        raise fail('[stiffeners] choose the net\'s lines with k1 and/or k2 (indices or "all")', "stiffeners.k1")
    for family in ("k1", "k2"):
        count, picked = model.host.lines(family), getattr(chosen, family)
        bad = [] if count is None or picked == "all" else [i for i in picked if not 0 <= i < count]
        if bad and count is not None:
            raise fail(
                f"[stiffeners] {family} must be indices in [0, {count - 1}] ([host] {family}_lines), got {bad}",
                f"stiffeners.{family}",
            )


def _read_face(host: HostSection, base: Path | None, length_unit: str, fail: Callable[..., SpecError]) -> TopoDS_Face:
    """[host] step's face ``face`` (an index or a name), read in ``length_unit``."""
    path = (base or Path(".")) / host.step
    if path.suffix.lower() not in STEP_SUFFIXES:
        raise fail(
            f"[host] step must be a STEP file ({', '.join(STEP_SUFFIXES)}), got {short(host.step)!r}", "host.step"
        )
    if not path.is_file():
        raise fail(f"[host] step: no file {str(path)!r}", "host.step")
    from tubecad.core.errors import TubecadError
    from tubecad.export.cad import read_faces
    from tubecad.occ_compat import as_face

    try:
        faces = read_faces(path, length_unit)
    except TubecadError as exc:
        raise fail(f"[host] step: {exc}", "host.step") from None
    if not faces:
        raise fail(f"[host] step: {path.name} holds no face", "host.step")
    if isinstance(host.face, str):  # a TOML string or integer, as checked
        named = [shape for name, shape in faces if name == host.face]
        if not named:
            names = sorted({name for name, _ in faces if name})
            shown = ", ".join(repr(n) for n in names[:8]) or "none"
            raise fail(
                f"[host] face: {path.name} has no face named {short(host.face)!r} (its names: {shown})", "host.face"
            )
        return as_face(named[0])
    if host.face >= len(faces):
        raise fail(
            f"[host] face must be in [0, {len(faces) - 1}] ({path.name} has {len(faces)} faces), got {host.face}",
            "host.face",
        )
    return as_face(faces[host.face][1])
