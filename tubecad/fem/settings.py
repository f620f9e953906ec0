"""The mesh's settings (the spec's ``[mesh]`` section, or keyword arguments of
:func:`tubecad.fem.shell_mesh`): element types, element sizes, which surface, the cap.

Light on purpose (no numpy, no OCCT): the spec checker uses it before anything is built.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tubecad.core.errors import ParameterError
from tubecad.core.validation import MAX_LENGTH, flag

#: shell elements (CalculiX/Abaqus names): 4-node linear, 8-node quadratic (serendipity); R: reduced integration
SHELL_TYPES = ("S4", "S4R", "S8", "S8R")
#: beam elements along the stiffeners: 2-node linear, 3-node quadratic
BEAM_TYPES = ("B31", "B31R", "B32", "B32R")
#: which surface carries the shell elements: the wall's mid-surface (with its thickness), its
#: inner or outer surface (the section offset into the wall), or both tube surfaces
SURFACES = ("mid", "inner", "outer", "both")
#: elements per mesh by default, and the most a [mesh] max_elements may allow
DEFAULT_MAX_ELEMENTS = 1_000_000
MAX_ELEMENTS_LIMIT = 20_000_000
#: the default element size: this fraction of the smallest tube radius (32 elements round a tube)
DEFAULT_SIZE_PER_RADIUS = 2 * math.pi / 32


@dataclass(frozen=True)
class MeshSettings:
    """Checked mesh settings; sizes in model units (None: the default, chosen on the tube).

    ``size_along``: the longest element edge along the stringers (s); ``size_around``: along
    the rings; ``beams``: stiffeners as beam elements (when the spec has [stiffeners])."""

    element: str = "S8R"
    beam: str | None = None
    size_along: float | None = None
    size_around: float | None = None
    surface: str = "mid"
    max_elements: int = DEFAULT_MAX_ELEMENTS
    beams: bool = True

    @property
    def order(self) -> int:
        """1 for S4 and S4R, 2 for S8 and S8R."""
        return 2 if self.element.startswith("S8") else 1

    @property
    def beam_type(self) -> str:
        """The beam element: as given, else B31 with linear shells and B32 with quadratic ones."""
        return self.beam or ("B32" if self.order == 2 else "B31")


def _size(key: str, value: object) -> float | None:
    if value is None:
        return None
    if (
        isinstance(value, bool)
        or not isinstance(value, (int, float))
        or not math.isfinite(value)
        or not 0 < value <= MAX_LENGTH
    ):
        raise ParameterError(
            f"{key} must be a finite length in (0, {MAX_LENGTH:g}] (model units), got {value!r:.40}", key=key
        )
    return float(value)


def mesh_settings(section: dict | None = None, **overrides: object) -> MeshSettings:
    """The checked ``[mesh]`` section (keys as in :class:`MeshSettings`, plus ``size`` for
    both sizes at once); ``overrides`` win over the section. A ParameterError names the key
    and its allowed values."""
    values = {**(section or {}), **{k: v for k, v in overrides.items() if v is not None}}
    known = {"element", "beam", "size", "size_along", "size_around", "surface", "max_elements", "beams"}
    unknown = sorted(set(values) - known)
    if unknown:
        raise ParameterError(
            f"unknown mesh setting {unknown[0]!r}; allowed: {', '.join(sorted(known))}", key=str(unknown[0])
        )
    element = values.get("element", "S8R")
    if element not in SHELL_TYPES:
        raise ParameterError(f"element must be one of {', '.join(SHELL_TYPES)}, got {element!r:.40}", key="element")
    beam = values.get("beam")
    if beam is not None and beam not in BEAM_TYPES:
        raise ParameterError(f"beam must be one of {', '.join(BEAM_TYPES)}, got {beam!r:.40}", key="beam")
    order = 2 if element.startswith("S8") else 1
    if beam is not None and (2 if beam.startswith("B32") else 1) != order:
        wanted = "B32 or B32R" if order == 2 else "B31 or B31R"
        raise ParameterError(
            f"beam must be {wanted} with {element} shells (the beams share the shells' "
            f"nodes, mid-side nodes included), got {beam!r}",
            key="beam",
        )
    size = _size("size", values.get("size"))
    along = _size("size_along", values.get("size_along", size))
    around = _size("size_around", values.get("size_around", size))
    surface = values.get("surface", "mid")
    if surface not in SURFACES:
        raise ParameterError(f"surface must be one of {', '.join(SURFACES)}, got {surface!r:.40}", key="surface")
    cap = values.get("max_elements", DEFAULT_MAX_ELEMENTS)
    if isinstance(cap, bool) or not isinstance(cap, int) or not 1 <= cap <= MAX_ELEMENTS_LIMIT:
        raise ParameterError(
            f"max_elements must be a whole number in [1, {MAX_ELEMENTS_LIMIT}], got {cap!r:.40}", key="max_elements"
        )
    beams = flag("beams", values.get("beams", True))
    return MeshSettings(element, beam, along, around, surface, cap, beams)


#: the wall's support in the pressure analysis (tubecad.fem.loads)
ENDS = ("fixed", "capped", "free")
#: steel's Young's modulus, 210 GPa, in N per square [units] length (mm: MPa)
STEEL_YOUNGS_MODULUS_PA = 210e9


@dataclass(frozen=True)
class AnalysisSettings:
    """The spec's ``[analysis]``: internal ``pressure`` and the material, in N and the
    model's length unit (mm: N/mm^2 = MPa); ``ends`` fixed, capped or free (a closed tube)."""

    pressure: float = 0.0
    ends: str = "fixed"
    youngs_modulus: float = 210000.0
    poisson_ratio: float = 0.3


def analysis_settings(section: dict | None, length_unit: str = "mm", closed: bool = False) -> AnalysisSettings:
    """The checked ``[analysis]`` section; a ParameterError names the key and its range."""
    from tubecad.core.units import length_unit as unit_of

    values = dict(section or {})
    # allowable_stress is the junctions' (tubecad.spec.junction), not the solver's
    known = {"pressure", "ends", "youngs_modulus", "poisson_ratio", "allowable_stress"}
    unknown = sorted(set(values) - known)
    if unknown:
        raise ParameterError(
            f"unknown analysis setting {unknown[0]!r}; allowed: {', '.join(sorted(known))}", key=str(unknown[0])
        )

    def real(key: str, default: float, low: float, high: float, low_open: bool = True) -> float:
        value = values.get(key, default)
        ok = (
            not isinstance(value, bool)
            and isinstance(value, (int, float))
            and math.isfinite(value)
            and (value > low if low_open else value >= low)
            and value < high
        )
        if not ok:
            bracket = "(" if low_open else "["
            raise ParameterError(
                f"{key} must be a finite number in {bracket}{low:g}, {high:g}), got {value!r:.40}", key=key
            )
        return float(value)

    steel = float(f"{STEEL_YOUNGS_MODULUS_PA * unit_of(length_unit).metres ** 2:.12g}")
    pressure = real("pressure", 0.0, -1e15, 1e15)
    if "allowable_stress" in values:
        real("allowable_stress", 1.0, 0.0, 1e15)
    modulus = real("youngs_modulus", steel, 0.0, 1e20)
    nu = real("poisson_ratio", 0.3, -1.0, 0.5)
    ends = values.get("ends", "free" if closed else "fixed")
    if ends not in ENDS:
        raise ParameterError(f"ends must be one of {', '.join(ENDS)}, got {ends!r:.40}", key="ends")
    if closed and ends != "free":
        raise ParameterError(f"ends = {ends!r} needs end rings; a closed tube has none: use ends = 'free'", key="ends")
    return AnalysisSettings(pressure, ends, modulus, nu)
