"""The grid on which the net is measured by default (``--nu``/``--ns``): points around the
circle and along the axis. No numpy here, so that the command line's options load fast."""

DEFAULT_NU = 256
DEFAULT_NS = 2001
