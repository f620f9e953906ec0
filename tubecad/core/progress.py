"""Progress of a long ``tubecad build`` on stderr (never stdout).

The library reports through a plain callback, ``progress(item, done, total)``: ``item``
(e.g. ``ring_02``) is finished, ``done`` of the stage's ``total`` are. It never prints;
:class:`Progress` is what the command line passes in (its :meth:`Progress.update`), and it
also takes the stages of the command itself (:meth:`Progress.step`, :meth:`Progress.advance`).

What is shown, and when:

- Nothing until ``after`` seconds (default 2, or ``TUBECAD_PROGRESS_AFTER``) have passed since
  the reporter was made, i.e. since the build started: a build that ends sooner prints
  nothing. From then on every update is shown, starting with the state at that moment.
  (Updates come between steps: a single step longer than that shows at its end.)
- stderr a terminal: one line, redrawn with a carriage return: click's progress bar with the
  stage, the count and the last item; cleared when the build ends.
- otherwise plain lines, ``tubecad: building stiffeners 3/9 (ring_03)``: one per update, or
  about every 5 % of a stage with more than 20 items.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, TextIO

if TYPE_CHECKING:
    from click._termui_impl import ProgressBar  # what click.progressbar returns (click's own termui imports it so)

#: what the library's long functions take: progress(item, done, total)
ProgressCallback = Callable[[str, int, int], None]

#: seconds before anything is shown
DEFAULT_AFTER = 2.0
#: the environment variable that overrides DEFAULT_AFTER (seconds, >= 0)
AFTER_VARIABLE = "TUBECAD_PROGRESS_AFTER"
#: a stage with more items than this prints a plain line about every 1 / PLAIN_LINES of it
PLAIN_LINES = 20
PREFIX = "tubecad: "


def show_after() -> float:
    """DEFAULT_AFTER, or the seconds in TUBECAD_PROGRESS_AFTER when that is a number >= 0."""
    try:
        value = float(os.environ.get(AFTER_VARIABLE, ""))
    except ValueError:
        return DEFAULT_AFTER
    return value if value >= 0 else DEFAULT_AFTER


class Progress:
    """Stages with counted items, shown on ``stream`` (default stderr) once ``after``
    seconds have passed (default :func:`show_after`); ``enabled=False`` shows nothing."""

    def __init__(
        self,
        stream: TextIO | None = None,
        after: float | None = None,
        enabled: bool = True,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.after = show_after() if after is None else after
        self.enabled = enabled
        self.clock = clock
        self.start = clock()
        self.label, self.done, self.item = "", 0, ""
        self.total: int | None = None
        self.shown = False  # the threshold has passed and something was shown
        self._tty = enabled and _isatty(self.stream)
        self._bar: ProgressBar[str | None] | None = None
        self._last_bucket = -1

    # --- what the build reports ---------------------------------------------------------------
    def step(self, label: str, total: int | None = None) -> None:
        """Start a stage: ``label`` ('building stiffeners'), with ``total`` items or uncounted."""
        self.label, self.total, self.done, self.item = label, total, 0, ""
        self._last_bucket = -1
        if self._bar is not None:
            self._clear()
        self._show(new_stage=True)

    def advance(self, n: int = 1, item: str = "") -> None:
        """``n`` more items of the stage are done, the last of them ``item``."""
        self.done += n
        self.item = item
        self._show()

    def update(self, item: str, done: int, total: int) -> None:
        """The library's callback (:data:`ProgressCallback`): ``done`` of ``total`` are done."""
        self.total, self.done, self.item = total, done, item
        self._show()

    def close(self) -> None:
        """End: clear the bar (a terminal) so that what follows starts on a clean line."""
        if self._bar is not None:
            self._clear()
            self.stream.write("\x1b[?25h")  # click hides the cursor while a bar is drawn
            self.stream.flush()

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- showing ------------------------------------------------------------------------------
    def _show(self, new_stage: bool = False) -> None:
        if not self.enabled or not self.label:
            return
        if not self.shown:
            if self.clock() - self.start < self.after:
                return
            self.shown = True
            new_stage = True
        if self._tty:
            self._draw(new_stage)
        elif self._plain_due(new_stage):
            self.stream.write(self.line() + "\n")
            self.stream.flush()

    def line(self) -> str:
        """The plain line for the current state: 'tubecad: building stiffeners 3/9 (ring_03)'."""
        count = f" {self.done}/{self.total}" if self.total else ""
        return f"{PREFIX}{self.label}{count}" + (f" ({self.item})" if self.item else "")

    def _plain_due(self, new_stage: bool) -> bool:
        """A line at the stage's start, its end, and per item (every ~5 % of a long stage)."""
        if not self.total:
            return new_stage
        bucket = self.done * PLAIN_LINES // self.total if self.total > PLAIN_LINES else self.done
        due = new_stage or self.done >= self.total or bucket != self._last_bucket
        self._last_bucket = bucket
        return due

    def _draw(self, new_stage: bool) -> None:
        import click

        if self._bar is None or new_stage:
            if self._bar is not None:
                self._clear()
            bar = self._bar = click.progressbar(
                length=self.total or 1,
                label=PREFIX + self.label,
                file=self.stream,
                show_pos=bool(self.total),
                show_percent=False,
                show_eta=False,
                item_show_func=lambda item: item or None,
                width=24,
                fill_char="#",
                empty_char="-",
            )
            bar.__enter__()  # draws it (the bar is closed by _clear, never by click's newline)
        else:
            bar = self._bar
        bar.pos, bar.current_item = min(self.done, self.total or 1), self.item
        bar.render_progress()

    def _clear(self) -> None:
        self.stream.write("\r\x1b[K")
        self.stream.flush()
        self._bar = None


def _isatty(stream: TextIO) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False
