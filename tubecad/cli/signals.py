"""Ctrl-C and SIGTERM before the heavy imports: the process ends at once with one line,
"interrupted", and exit code 130 (128 + SIGINT, as shells report Ctrl-C)."""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from collections.abc import Iterator

INTERRUPTED_EXIT_CODE = 130  # 128 + SIGINT, as shells report Ctrl-C

#: set by the console script (:mod:`tubecad.cli.console`) only: a script or a test that calls
#: the commands in its own process keeps its own Ctrl-C handling, never an ``os._exit``
_console_process = False


def _exit_now(_signum, _frame) -> None:  # pragma: no cover - runs in a subprocess
    try:
        sys.stderr.write("\ninterrupted\n")
        sys.stderr.flush()
    finally:
        os._exit(INTERRUPTED_EXIT_CODE)


@contextlib.contextmanager
def interrupts_end_at_once() -> Iterator[None]:
    """Around imports that load extension modules, before anything is written: Ctrl-C or
    SIGTERM end the process at once (one line, exit 130), never a half-initialised import's
    traceback. Only in the ``tubecad`` console script's process: called from a script or a
    test (``CliRunner``), or outside the main thread, it changes nothing."""
    if not _console_process:
        yield
        return
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
