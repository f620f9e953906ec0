"""The grid the net is measured on, as the command line's ``--nu``/``--ns`` defaults: the
policy itself lives in :mod:`tubecad.core.grid` (no numpy, so the options load fast)."""

from tubecad.core.grid import DEFAULT_NS, DEFAULT_NU

__all__ = ["DEFAULT_NS", "DEFAULT_NU"]
