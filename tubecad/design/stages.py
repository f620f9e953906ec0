"""Which part of a design's build an error came from.

The builders raise in Python terms (a :class:`~tubecad.core.errors.ParameterError` naming
the parameter); :func:`stage` tags each error with the design field whose part of the build
failed, so a caller that wrote that field in another vocabulary (a spec's ``[section]``)
can say where it is without parsing messages (:func:`tubecad.spec.design.spec_errors`).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from tubecad.core.errors import TubecadError

#: the stages of a build, as design fields
Stage = str


@contextmanager
def stage(name: Stage, branch: int | None = None) -> Iterator[None]:
    """Tag a :class:`TubecadError` raised inside with ``stage`` = ``name`` (the innermost
    stage wins) and, for a branch's part, ``branch`` = its index."""
    try:
        yield
    except TubecadError as exc:
        if exc.stage is None:
            exc.stage, exc.branch = name, branch
        raise
