"""Length units: the one table of what a spec's ``[units] length`` may be and how each
file format writes it (docs/spec-files.md).

The model's coordinates are always in the spec's own unit (a tube of radius 15 in a spec
with ``length = "m"`` is 15 m): nothing is rescaled. Each writer states that unit in its
file, so a reader converts correctly (STEP's SI_UNIT or CONVERSION_BASED_UNIT, the IGES
global section's unit flag, DXF's $INSUNITS, 3MF's unit attribute), and glTF, whose unit
is fixed to metres, is scaled by :attr:`LengthUnit.metres`. STL and BREP hold no unit.

Only units that STEP, IGES, DXF and 3MF can all name are offered. Light on purpose (no
numpy, no OCCT): the spec checker and ``tubecad schema`` use it.
"""

from __future__ import annotations

from dataclasses import dataclass

from tubecad.core.errors import ParameterError


@dataclass(frozen=True)
class LengthUnit:
    """One length unit and its name in each format that records units."""

    name: str  # as the spec writes it
    mm: float  # millimetres per unit (exact decimal literals, so no conversion noise)
    metres: float  # metres per unit
    step: str  # OCCT's write.step.unit / xstep.cascade.unit value
    iges_flag: int  # IGES global section parameter 14 (OCCT writes the matching name, 15)
    dxf: int  # DXF $INSUNITS (ezdxf.units)
    build123d: str  # build123d.Unit member (glTF and 3MF writers, the XCAF document)


#: spec name -> unit; the order is the one messages and the JSON Schema list
LENGTH_UNITS: dict[str, LengthUnit] = {
    "mm": LengthUnit("mm", 1.0, 0.001, "MM", 2, 4, "MM"),
    "cm": LengthUnit("cm", 10.0, 0.01, "CM", 10, 5, "CM"),
    "m": LengthUnit("m", 1000.0, 1.0, "M", 6, 6, "M"),
    "in": LengthUnit("in", 25.4, 0.0254, "INCH", 1, 1, "IN"),
    "ft": LengthUnit("ft", 304.8, 0.3048, "FT", 4, 2, "FT"),
}

DEFAULT_LENGTH_UNIT = "mm"

#: steel, kg/m^3: the default density of the reported masses
STEEL_KG_PER_M3 = 7850.0


def length_unit(name: str) -> LengthUnit:
    """The unit called ``name``, or a ParameterError naming every allowed one."""
    unit = LENGTH_UNITS.get(name) if isinstance(name, str) else None
    if unit is None:
        raise ParameterError(f"length unit must be one of {', '.join(LENGTH_UNITS)}, got {name!r:.80}")
    return unit


def steel_density(name: str = DEFAULT_LENGTH_UNIT) -> float:
    """Steel's density in kg per cubic ``name`` (7.85e-6 for mm, 7850 for m), rounded to 12
    significant digits so that the metric units give their plain decimal values."""
    return float(f"{STEEL_KG_PER_M3 * length_unit(name).metres ** 3:.12g}")


def density_unit(name: str = DEFAULT_LENGTH_UNIT) -> str:
    """How the report names a density in ``name``'s cubic unit: 'kg/mm^3', 'kg/m^3', ..."""
    return f"kg/{length_unit(name).name}^3"
