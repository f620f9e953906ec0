"""The grid on which the net is measured (``--nu``/``--ns``): points around the circle and
along the axis. Its own module so that the command line's options load no numpy."""

DEFAULT_NU = 256
DEFAULT_NS = 2001
