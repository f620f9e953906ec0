"""Ctrl-C and SIGTERM before the heavy imports: the process ends at once with one line,
"interrupted", and exit code 130 (128 + SIGINT, as shells report Ctrl-C)."""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from collections.abc import Iterator

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
