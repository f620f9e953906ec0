"""The ``tubecad`` console script: Ctrl-C and SIGTERM answered cleanly from the start.

Importing the command line (OCCT, build123d, CadQuery) takes seconds, and an interrupt
during an import surfaces as a traceback (or an ImportError from a half-initialised
extension). Until that import is done nothing has been written, so an interrupt there
just ends the process: one line "interrupted", exit code 130. From then on
:func:`tubecad.interfaces.cli.main` turns both signals into KeyboardInterrupt, so atomic
writes in progress remove their temporary files before the same exit.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from typing import Iterator

INTERRUPTED_EXIT_CODE = 130  # 128 + SIGINT, as shells report Ctrl-C


def _exit_now(signum, frame) -> None:  # pragma: no cover - runs in a subprocess
    try:
        sys.stderr.write("\ninterrupted\n")
        sys.stderr.flush()
    finally:
        os._exit(INTERRUPTED_EXIT_CODE)


@contextlib.contextmanager
def interrupts_end_at_once() -> Iterator[None]:
    """Around imports that load extension modules, before anything is written: Ctrl-C or
    SIGTERM end the process at once (one line, exit 130), never a half-initialised import's
    traceback. Outside the main thread (embedded use) it changes nothing."""
    try:
        previous = signal.signal(signal.SIGINT, _exit_now), signal.signal(signal.SIGTERM, _exit_now)
    except ValueError:  # pragma: no cover - not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous[0])
        signal.signal(signal.SIGTERM, previous[1])


def main() -> None:
    """Entry point of the ``tubecad`` console script."""
    signal.signal(signal.SIGINT, _exit_now)
    signal.signal(signal.SIGTERM, _exit_now)
    from .cli import main as run  # the heavy imports

    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    run()


if __name__ == "__main__":  # pragma: no cover
    main()
