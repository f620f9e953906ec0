"""Exceptions raised by tubecad.

Every error a user can provoke with bad input is a :class:`TubecadError`; its message
names the offending parameter (or spec key) and the allowed range.
"""


class TubecadError(Exception):
    """Base class of all tubecad errors."""


class ParameterError(TubecadError, ValueError):
    """A parameter is missing, of the wrong type, or out of its allowed range."""


class ExpressionError(ParameterError):
    """A curvature expression k(s) is not a safe arithmetic expression in s."""


class RegularityError(TubecadError, ValueError):
    """The tube is not a regular surface over the requested span (docs/MATH.md section 5)."""


class SpecError(TubecadError, ValueError):
    """A spec file (TOML) is malformed or has a bad key or value."""
