"""The ``tubecad`` console script: Ctrl-C and SIGTERM answered cleanly from the start.

Importing the command line (OCCT, build123d, CadQuery) takes seconds, and an interrupt
during an import surfaces as a traceback (or an ImportError from a half-initialised
extension). Until that import is done nothing has been written, so an interrupt there
just ends the process: one line "interrupted", exit code 130. From then on
:func:`tubecad.cli.app.main` turns both signals into KeyboardInterrupt, so atomic
writes in progress remove their temporary files before the same exit.
"""

from __future__ import annotations

import signal

from tubecad.cli import signals
from tubecad.cli.signals import _exit_now


def main() -> None:
    """Entry point of the ``tubecad`` console script."""
    signals._console_process = True
    signal.signal(signal.SIGINT, _exit_now)
    signal.signal(signal.SIGTERM, _exit_now)
    from tubecad.cli.app import main as run  # the heavy imports

    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    run()


if __name__ == "__main__":  # pragma: no cover
    main()
