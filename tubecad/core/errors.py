"""Exceptions raised by tubecad.

Every error a user can provoke with bad input is a :class:`TubecadError`; its message
names the offending parameter (or spec key) and the allowed range, and its ``key``, where
the raiser knows it, names that parameter for code: ``"tolerance"``, ``"wall.thickness"``
(a spec's ``section.key``), ``"stiffeners"`` (a whole section). Code classifies an error
by its ``key``, never by its message.
"""


class TubecadError(Exception):
    """Base class of all tubecad errors.

    ``key``: the parameter or spec key at fault (``"section.key"``, or ``"section"`` for a
    whole section), or None where the raiser does not know it. Optional, keyword only:
    ``TubecadError(message)`` works as before."""

    key: str | None = None
    #: the part of a design's build that failed (``"wall"``, ``"stiffeners"``...; tubecad.design.stages)
    stage: str | None = None
    #: with a branch's part of a junction's build, the branch's index
    branch: int | None = None

    def __init__(self, *args: object, key: str | None = None) -> None:
        super().__init__(*args)
        if key is not None:
            self.key = key


class ParameterError(TubecadError, ValueError):
    """A parameter is missing, of the wrong type, or out of its allowed range."""


class ExpressionError(ParameterError):
    """A curvature expression k(s) is not a safe arithmetic expression in s."""


class RegularityError(TubecadError, ValueError):
    """The tube is not a regular surface over the requested span (docs/MATH.md section 5)."""


class SpecError(TubecadError, ValueError):
    """A spec file (TOML) is malformed or has a bad key or value."""
