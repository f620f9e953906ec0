"""Small checks shared by every constructor: finite numbers in a named allowed range."""

from __future__ import annotations

import math
from collections.abc import Sequence

from tubecad.core.errors import ParameterError

#: the largest length accepted (radius, arc length, a length parameter, a coordinate), model
#: units: beyond it double precision cannot place the geometry to the fit tolerances, and
#: the squares of lengths that the checks compute would overflow
MAX_LENGTH = 1e9

#: the shortest span relative to its arc lengths' magnitude: below it double precision
#: cannot tell the span's points apart well enough to integrate or fit the axis
MIN_SPAN_RESOLUTION = 1e-9


def finite_number(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise naming ``name`` if it is not a finite real."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        try:
            import numpy as np

            if isinstance(value, np.generic) and np.isreal(value):
                value = float(value)
            else:
                raise TypeError
        except TypeError:
            raise ParameterError(f"{name} must be a real number, got {value!r}") from None
    value = float(value)
    if not math.isfinite(value):
        raise ParameterError(f"{name} must be finite, got {value}")
    return value


def number_in_range(
    name: str,
    value: object,
    low: float = -math.inf,
    high: float = math.inf,
    *,
    low_open: bool = True,
    high_open: bool = True,
) -> float:
    """Return ``value`` as a float checked against the interval (low, high)."""
    x = finite_number(name, value)
    below = x <= low if low_open else x < low
    above = x >= high if high_open else x > high
    if below or above:
        raise ParameterError(f"{name} must be in {_interval(low, high, low_open, high_open)}, got {x:g}")
    return x


def flag(name: str, value: object) -> bool:
    """Return ``value`` if it is a bool (numpy's too), else raise naming ``name``: a string
    like "no" must not silently count as true."""
    import numpy as np

    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ParameterError(f"{name} must be True or False, got {value!r:.80}", key=name)


def bounded_length(name: str, value: object, low: float = -math.inf, *, low_open: bool = True) -> float:
    """Return ``value`` as a float in the allowed range with |value| <= MAX_LENGTH."""
    x = number_in_range(name, value, low, low_open=low_open)
    if abs(x) > MAX_LENGTH:
        raise ParameterError(f"{name} must be at most {MAX_LENGTH:g} model units in magnitude, got {x:g}")
    return x


def span_pair(name: str, value: Sequence[object], low: float = -math.inf) -> tuple[float, float]:
    """Return an increasing pair (s0, s1) with both ends finite and s0 > ``low``."""
    try:
        s0, s1 = value
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a pair [start, end], got {value!r:.80}") from None
    s0 = bounded_length(f"{name} start", s0)
    s1 = bounded_length(f"{name} end", s1)
    if not s1 > s0:
        raise ParameterError(f"{name} must be increasing (start < end), got [{s0:g}, {s1:g}]")
    if s1 - s0 < MIN_SPAN_RESOLUTION * max(abs(s0), abs(s1)):
        raise ParameterError(
            f"{name} [{s0:.17g}, {s1:.17g}] is too short for its distance from s = 0: the length "
            f"end - start must be at least {MIN_SPAN_RESOLUTION:g} x max(|start|, |end|)"
        )
    if not s0 > low:
        raise ParameterError(f"{name} must lie in s > {low:g} for this curve, got start {s0:g}")
    return s0, s1


def _interval(low: float, high: float, low_open: bool, high_open: bool) -> str:
    left = "(" if low_open else "["
    right = ")" if high_open else "]"
    lo = "-inf" if low == -math.inf else f"{low:g}"
    hi = "inf" if high == math.inf else f"{high:g}"
    return f"{left}{lo}, {hi}{right}"


def coordinates(name: str, value: object) -> tuple[float, float, float]:
    """Three finite coordinates [x, y, z] within +-MAX_LENGTH, or a ParameterError naming
    ``name`` (and the coordinate ``name[i]`` that is out of range)."""
    try:
        items = list(value)  # type: ignore[call-overload]
    except TypeError:
        items = []
    if len(items) != 3 or isinstance(value, (str, bytes)):
        raise ParameterError(f"{name} must be three coordinates [x, y, z], got {value!r:.80}")
    return tuple(bounded_length(f"{name}[{i}]", v) for i, v in enumerate(items))  # type: ignore[return-value]
