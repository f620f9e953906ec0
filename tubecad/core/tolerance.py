"""The fit-tolerance policy, in one place: how close the fitted B-rep must stay to the exact
tube, how orthogonal its isolines, and the smallest sizes a B-rep can hold.

Light on purpose (no OCCT): the spec checker uses it before anything is built."""

from __future__ import annotations

import math

from tubecad.core.errors import ParameterError

#: the default largest distance, model units, of the fitted surfaces from the exact tube
#: (the spec's [fit] tolerance and every fit's and builder's ``tolerance`` default)
DEFAULT_FIT_TOLERANCE = 1e-8

#: the default largest |cos| of the angle between the fitted isolines: the fits'
#: ``orthogonality`` default, ``orthogonality_for(DEFAULT_FIT_TOLERANCE)``
DEFAULT_ORTHOGONALITY = 1e-9

#: the old name of DEFAULT_FIT_TOLERANCE, kept importable
DEFAULT_TOLERANCE = DEFAULT_FIT_TOLERANCE

#: the tolerance of the B-rep's edges and vertices: OCCT's Precision::Confusion
EDGE_TOLERANCE = 1e-7

#: the smallest radius and wall thickness a B-rep is built with: 100 x the edge tolerance;
#: below it edges and faces collapse within tolerance
MIN_SIZE = 100 * EDGE_TOLERANCE

#: significant digits tubecad's STEP and IGES writers give a real (tubecad.export.cad.FILE_REAL: a double to the bit)
WRITTEN_DIGITS = 17


def written_resolution(size: float, digits: int = WRITTEN_DIGITS) -> float:
    """How finely a file holds coordinates up to ``size``: half a unit in the last of
    ``digits`` significant digits, size * 0.5 * 10^(1 - digits)."""
    return abs(size) * 0.5 * 10.0 ** (1 - digits)


def file_uncertainty(size: float) -> float | None:
    """The uncertainty a STEP or IGES file of coordinates up to ``size`` declares, which its
    reader heals the B-rep to: 10 x :func:`written_resolution` where that exceeds the edge
    tolerance (from coordinates of about 2e4), so the vertices and edges read back cover
    the rounding of their coordinates; None below (the writer's own default)."""
    value = 10.0 * written_resolution(size)
    return value if value > EDGE_TOLERANCE else None


def check_tolerance(name: str, value: object) -> float:
    """A fit tolerance in (0, 1) model units, or a ParameterError naming ``name``."""
    import numpy as np  # numpy scalars are accepted; imported here so the module stays light

    if (
        isinstance(value, (bool, np.bool_))
        or not isinstance(value, (int, float, np.integer, np.floating))
        or not (math.isfinite(value) and 0 < value < 1)
    ):
        raise ParameterError(f"fit {name} must be in (0, 1) model units, got {value!r:.80}", key=name)
    return float(value)


def orthogonality_for(tolerance: float) -> float:
    """The |cos| the isolines are fitted to: tolerance / 10, and never worse than 1e-6
    (1e-9 at the default tolerance 1e-8)."""
    return min(1e-6, tolerance / 10) if isinstance(tolerance, (int, float)) and tolerance > 0 else tolerance


#: double precision's unit round-off (numpy.finfo(float).eps), without importing numpy
EPSILON = 2.0**-52

#: a fit's position error cannot be promised below POSITION_FLOOR_ULPS * eps * L for
#: coordinates up to L (the fit must meet half its tolerance; OCCT and numpy round every
#: pole and sample to eps * L / 2). Measured: the frame fit stalls at 6-48 eps L.
POSITION_FLOOR_ULPS = 8

#: nor its isolines' |cos| below ORTHOGONALITY_FLOOR_ULPS * eps: measured, the fit stalls
#: at |cos| 675-2900 eps; its target is half of ``orthogonality_for(tolerance)``
ORTHOGONALITY_FLOOR_ULPS = 64


def smallest_tolerance(size: float) -> float:
    """The smallest fit tolerance double precision can reach for coordinates up to ``size``.

    A fit meets half its tolerance in position and half its orthogonality
    (:func:`orthogonality_for`, tolerance / 10) in |cos|; neither can beat round-off. So the
    tolerance must be at least max(8 eps L, 10 * 64 eps) (about 4e-13 at L = 223, the
    paper's tube). This is a bound a spec can be refused by before fitting, not a promise:
    between it and what a fit measures (6-48 eps L, |cos| 675-2900 eps) the fit itself
    says it stalled.

    Args:
        size: the largest coordinate magnitude of the surfaces fitted (model units).

    Returns:
        The smallest tolerance worth fitting to.
    """
    return max(POSITION_FLOOR_ULPS * EPSILON * abs(size), 10.0 * ORTHOGONALITY_FLOOR_ULPS * EPSILON)


def check_reachable(name: str, tolerance: float, size: float) -> float:
    """``tolerance`` if double precision can reach it for coordinates up to ``size``.

    Args:
        name: the parameter's name, for the message.
        tolerance: the fit tolerance (already in (0, 1), see :func:`check_tolerance`).
        size: the largest coordinate magnitude of the surfaces fitted.

    Returns:
        ``tolerance``.

    Raises:
        ParameterError: below :func:`smallest_tolerance`, naming it.
    """
    floor = smallest_tolerance(size)
    if tolerance < floor:
        raise ParameterError(
            f"fit {name} {tolerance:g} is below what double precision can reach for coordinates up to "
            f"{size:.6g}: use at least {floor:.2g} (8 eps x size, and |cos| 64 eps at tolerance / 10)",
            key=name,
        )
    return tolerance
