"""Atomic file output: write to a temporary file beside the target, then rename; a folder
of outputs is filled in a staging folder beside it, then moved into place (:func:`staged_folder`).

A failed or interrupted write never leaves a partial or corrupt file at the target path.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from tubecad.core.errors import ParameterError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: temporaries of atomic writes in progress: an interrupt that lands between two steps of
#: the bookkeeping below still leaves none (see :func:`remove_temporaries`)
_LIVE: set[Path] = set()
#: staging folders being filled (:func:`staged_folder`), likewise
_LIVE_FOLDERS: set[Path] = set()


def remove_temporaries() -> None:
    """Remove the temporary file of every atomic write and the staging folder of every
    :func:`staged_folder` still in progress (called when an interrupt ends the command), so
    an interrupt can never leave a ``.part`` file or folder."""
    for path in list(_LIVE):
        path.unlink(missing_ok=True)
        _LIVE.discard(path)
    for folder in list(_LIVE_FOLDERS):
        shutil.rmtree(folder, ignore_errors=True)
        _LIVE_FOLDERS.discard(folder)


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


@contextlib.contextmanager
def staged_folder(target: str | Path) -> Iterator[Path]:
    """Yield an empty staging folder beside the folder ``target`` (``.NAME.XXXX.part``, made
    with ``target``'s missing parent folders) to write a set of outputs into. When the block
    ends without an error, every file left in it is moved into ``target`` (made if need be) at
    the same relative path, replacing a file of that name and keeping the folder's other files
    (``-o .`` never loses the user's files); empty folders are not moved. On an error or an
    interrupt nothing is moved: the staging folder is removed, so a failed run leaves no
    partial set of outputs, and ``target`` is made only once the outputs are complete.

    The one staging recipe of tubecad's folder outputs (``tubecad shop`` and ``analyse``)."""
    target = Path(target)
    folder = target.parent if str(target.parent) else Path(".")
    folder.mkdir(parents=True, exist_ok=True)
    staging = None
    try:
        staging = _temporary_folder(target, folder)
        yield staging
        target.mkdir(exist_ok=True)
        for path in sorted(p for p in staging.rglob("*") if p.is_file()):
            moved = target / path.relative_to(staging)
            moved.parent.mkdir(parents=True, exist_ok=True)
            os.replace(path, moved)
    finally:
        if staging is not None:
            shutil.rmtree(staging, ignore_errors=True)
            _LIVE_FOLDERS.discard(staging)


def _temporary_folder(target: Path, folder: Path) -> Path:
    """An empty folder beside ``target`` in ``folder``, recorded in ``_LIVE_FOLDERS`` before it
    is made (as :func:`_temporary` records a file), with the usual mode (umask's)."""
    for _ in range(100):
        candidate = folder / f".{target.name}.{secrets.token_hex(6)}.part"
        _LIVE_FOLDERS.add(candidate)
        try:
            os.mkdir(candidate)
            return candidate
        except FileExistsError:  # another run's staging folder of that name: draw again
            _LIVE_FOLDERS.discard(candidate)
        except OSError as exc:
            _LIVE_FOLDERS.discard(candidate)
            raise ParameterError(
                f"output folder {str(target)!r}: cannot write to {str(folder)!r}: {exc.strerror}", key="output"
            ) from None
        except BaseException:
            shutil.rmtree(candidate, ignore_errors=True)
            _LIVE_FOLDERS.discard(candidate)
            raise
    raise ParameterError(
        f"output folder {str(target)!r}: cannot make a staging folder in {str(folder)!r}", key="output"
    )


def write_text(target: str | Path, text: str) -> Path:
    """Write ``text`` to ``target`` atomically."""
    with atomic_path(target) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(target)


def save_figure(
    fig: Figure, folder: str | Path, stem: str, formats: tuple[str, ...] = ("png", "svg"), dpi: int = 150
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


def close_figure(fig: Figure) -> None:
    """Release ``fig``: pyplot forgets it if it manages it (imported only if already loaded:
    tubecad's own figures are not pyplot's and are simply dropped)."""
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None and getattr(fig.canvas, "manager", None) is not None:
        pyplot.close(fig)
