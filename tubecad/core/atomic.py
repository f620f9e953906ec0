"""Atomic file output: write to a temporary file beside the target, then rename.

A failed or interrupted write never leaves a partial or corrupt file at the target path.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import sys
from collections.abc import Iterator
from pathlib import Path

from tubecad.core.errors import ParameterError

#: temporaries of atomic writes in progress: an interrupt that lands between two steps of
#: the bookkeeping below still leaves none (see :func:`remove_temporaries`)
_LIVE: set[Path] = set()


def remove_temporaries() -> None:
    """Remove the temporary file of every atomic write still in progress (called when an
    interrupt ends the command), so an interrupt can never leave a ``.part`` file."""
    for path in list(_LIVE):
        path.unlink(missing_ok=True)
        _LIVE.discard(path)


@contextlib.contextmanager
def atomic_path(target: str | Path) -> Iterator[Path]:
    """Yield a temporary path in the target's folder; on success it replaces ``target``."""
    target = Path(target)
    tmp_path = None
    try:
        tmp_path = _temporary(target)
        yield tmp_path
        os.chmod(tmp_path, 0o666 & ~_umask())  # made 0600 (as mkstemp); outputs get the usual mode
        os.replace(tmp_path, target)
        _LIVE.discard(tmp_path)
    except BaseException:
        if tmp_path is not None:
            tmp_path.unlink(missing_ok=True)
            _LIVE.discard(tmp_path)
        raise


def check_writable(target: str | Path) -> Path:
    """Refuse an output before anything is built: its folder is missing or not a folder, it
    is a folder itself, or no file can be created beside it (read-only, /proc, full disk)."""
    target = Path(target)
    if target.is_dir():
        raise ParameterError(f"output {str(target)!r} is a folder; give a file name")
    probe = None
    try:
        probe = _temporary(target)
    finally:
        if probe is not None:
            probe.unlink(missing_ok=True)
            _LIVE.discard(probe)
    return target


def _temporary(target: Path) -> Path:
    """An empty temporary file beside ``target`` (a ParameterError naming the output if impossible).

    The name is recorded in ``_LIVE`` before the file is created (``O_CREAT | O_EXCL``, as
    ``mkstemp`` does): an interrupt can land between any two bytecodes, also after the file
    exists but before its name is returned, and must still find it.
    """
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        why = "is not a folder" if folder.exists() else "does not exist"
        raise ParameterError(f"output {str(target)!r}: output folder {str(folder)!r} {why}")
    for _ in range(100):
        candidate = folder / f".{target.name}.{secrets.token_hex(6)}.part{target.suffix}"
        _LIVE.add(candidate)
        try:
            os.close(os.open(candidate, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
            return candidate
        except FileExistsError:  # another process's temporary of that name: draw again
            _LIVE.discard(candidate)
        except OSError as exc:
            _LIVE.discard(candidate)
            raise ParameterError(f"output {str(target)!r}: cannot write to {str(folder)!r}: {exc.strerror}") from None
        except BaseException:
            candidate.unlink(missing_ok=True)
            _LIVE.discard(candidate)
            raise
    raise ParameterError(f"output {str(target)!r}: cannot make a temporary file in {str(folder)!r}")


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text(target: str | Path, text: str) -> Path:
    """Write ``text`` to ``target`` atomically."""
    with atomic_path(target) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(target)


def save_figure(
    fig, folder: str | Path, stem: str, formats: tuple[str, ...] = ("png", "svg"), dpi: int = 150
) -> list[Path]:
    """Save a matplotlib figure as ``stem``.<format> in ``folder`` for each format, atomically,
    then close it; return the paths.

    tubecad draws on ``matplotlib.figure.Figure`` objects, which need neither pyplot nor a
    backend switch (``savefig`` picks the canvas of each format), so the user's backend is
    never changed; a figure that pyplot manages (a caller's own) is closed through pyplot."""
    paths = []
    try:
        for ext in formats:
            target = Path(folder) / f"{stem}.{ext}"
            with atomic_path(target) as tmp:
                fig.savefig(tmp, format=ext, dpi=dpi)
            paths.append(target)
    finally:
        close_figure(fig)
    return paths


def close_figure(fig) -> None:
    """Release ``fig``: pyplot forgets it if it manages it (imported only if already loaded:
    tubecad's own figures are not pyplot's and are simply dropped)."""
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None and getattr(fig.canvas, "manager", None) is not None:
        pyplot.close(fig)
