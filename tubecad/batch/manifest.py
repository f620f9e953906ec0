"""The batch's manifest (``DIR/batch.json``): what each job was built from and what it wrote,
by content hash, so that a rerun builds only what is missing or changed.

- A job's **spec hash** is SHA-256 of its resolved spec (the file's tables with the swept
  values put in, as canonical JSON), the bytes of every file the spec refers to (``[axis]
  file``), what the job asks for (formats, STEP schema, mesh tolerances) and tubecad's version.
- An output's **hash** is SHA-256 of its bytes, a STEP file's with the header's time stamp
  (the second field of FILE_NAME) left out: the one part of a STEP file that differs
  between two builds of one spec (tubecad sets it from SOURCE_DATE_EPOCH when that is set).
- A rerun **skips** a job whose entry says ok, whose spec hash is unchanged and whose every
  output is present with its recorded hash; anything else is built again.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path
from typing import Any

from tubecad.export.formats import FORMATS

#: FILE_NAME('name','2026-12-02T02:11:22',... : the time stamp is left out of a STEP file's hash
_STEP_STAMP = re.compile(rb"(FILE_NAME\s*\(\s*'(?:[^']|'')*'\s*,\s*)'[^']*'")
STEP_SUFFIXES = next(f.extensions for f in FORMATS if f.name == "step")


def content_hash(data: bytes, name: str = "") -> str:
    """SHA-256 (hex) of ``data``; for a STEP file (by ``name``'s suffix) without its time stamp."""
    if name.lower().endswith(STEP_SUFFIXES):
        data = _STEP_STAMP.sub(rb"\1''", data, count=1)
    return hashlib.sha256(data).hexdigest()


def file_hash(path: str | Path) -> str | None:
    """:func:`content_hash` of the file at ``path``, or None if it cannot be read."""
    try:
        return content_hash(Path(path).read_bytes(), str(path))
    except OSError:
        return None


def spec_hash(job) -> str:
    """The job's spec hash (module docstring)."""
    from importlib.metadata import PackageNotFoundError, version

    from tubecad.batch.jobs import referred_files, resolved_data

    data = resolved_data(job)
    digest = hashlib.sha256()
    digest.update(json.dumps(data, sort_keys=True, default=str).encode())
    for _, path in referred_files(job, data):
        digest.update(path.read_bytes() if path.is_file() else b"missing")
    try:
        tubecad_version = version("tubecad")
    except PackageNotFoundError:  # pragma: no cover - a source tree not installed
        tubecad_version = "unknown"
    asked = [
        [Path(p).suffix for p in job.outputs],
        job.step_schema,
        job.mesh_tolerance,
        job.mesh_angle,
        tubecad_version,
    ]
    digest.update(json.dumps(asked).encode())
    return digest.hexdigest()


def read_manifest(folder: Path) -> dict[str, dict[str, Any]]:
    """Job name -> its entry in ``folder``/batch.json ({} if there is none or it is unreadable)."""
    try:
        record = json.loads((Path(folder) / "batch.json").read_text(encoding="utf-8"))
        return {entry["name"]: entry for entry in record.get("jobs", []) if isinstance(entry, dict) and "name" in entry}
    except (OSError, ValueError, TypeError, KeyError):
        return {}


def up_to_date(entry: dict[str, Any] | None, job, digest: str | None) -> bool:
    """Whether ``entry`` (from the manifest) shows ``job`` built from the spec hashing to
    ``digest``, with every output present and unchanged."""
    if not entry or entry.get("status") != "ok" or entry.get("spec_hash") != digest:
        return False
    hashes = entry.get("hashes") or {}
    folder = Path(job.report).parent
    names = [Path(p).name for p in (*job.outputs, job.report)]
    return all(name in hashes and file_hash(folder / name) == hashes[name] for name in names)
