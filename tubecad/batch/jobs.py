"""``tubecad build`` over many specs or a parameter sweep, on all cores (docs/command-line.md).

    tubecad build a.toml b.toml -d OUT [-f step -f iges] [-j N]
    tubecad build paper.toml --sweep tube.radius=10,12,15 --sweep axis.beta_deg=0:30:4 -d OUT

Every job is one spec: a file, or a file with swept values put in (``paper.toml[tube.radius=12]``,
checked exactly like a file). It runs :func:`~tubecad.spec.build.build_and_export`, the
code path of a single ``tubecad build``, and writes OUT/NAME.EXT for each format and
OUT/NAME.report.json. Jobs run on an executor (:mod:`.executors`): worker processes started
with "spawn" (OCCT and fork do not mix well), this process with one job at a time, or a Dask
cluster (:mod:`.dask_executor`). A failed job does not stop the others and leaves none of its
files; a job whose worker dies or that hangs past ``--job-timeout`` is retried
(``--retries``). OUT/batch.json, the manifest (:mod:`.manifest`), is rewritten as each job
finishes with the hashes of its spec and files, so that a rerun builds only what is missing
or changed. On Ctrl-C the pending jobs are cancelled and the running ones stopped without
partial files; a rerun resumes.
"""

from __future__ import annotations

import contextlib
import itertools
import json
import math
import re
import signal
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tubecad.core.errors import ParameterError, TubecadError
from tubecad.export.registry import FORMAT_NAMES

#: what -f/--format accepts: every extension of tubecad.export.registry, without the dot
FORMATS = FORMAT_NAMES
MAX_JOBS = 10_000
MAX_NAME = 120


@dataclass(frozen=True)
class Sweep:
    """One --sweep: the spec key ``section.key`` and the values it takes."""

    section: str
    key: str
    values: tuple[Any, ...]

    @property
    def label(self) -> str:
        return f"{self.section}.{self.key}"


@dataclass(frozen=True)
class Job:
    """One spec to build (picklable: it travels to a worker process)."""

    name: str
    spec: str  # the spec file
    source: str  # how messages name it: the file, or file[section.key=value, ...]
    overrides: tuple[tuple[str, str, Any], ...]  # (section, key, value) put into the file's spec
    outputs: tuple[str, ...]
    report: str
    step_schema: str = "AP214"
    mesh_tolerance: float | None = None  # --mesh-tolerance (model units), for mesh formats
    mesh_angle: float | None = None  # --mesh-angle (degrees)
    #: a job sent to another machine: its resolved spec as JSON (then ``spec`` only names the
    #: folder its relative files are in) and those files' bytes (name, data)
    spec_data: str | None = None
    attachments: tuple[tuple[str, bytes], ...] = ()


@dataclass
class JobResult:
    """What became of a job; ``outputs`` are the file names written into the batch folder."""

    name: str
    status: str  # ok | failed | cancelled
    error: str | None = None
    seconds: float | None = None
    outputs: list[str] = field(default_factory=list)
    kind: str = ""
    faces: int = 0
    valid: bool = False
    built: str = ""  # what was built, for the job's line: "wall 50 faces valid + 5 ring + 4 stringer stiffeners (T)"
    attempts: int = 1
    # file name -> content hash (tubecad.batch.manifest; None: the file could not be read)
    hashes: dict[str, str | None] = field(default_factory=dict)
    spec_hash: str | None = None
    skipped: bool = False  # built by an earlier run, unchanged (resumed)


# ---------------------------------------------------------------- sweeps and job names


def schema_sections() -> dict[str, dict]:
    """section -> its allowed keys, as the spec files have them (every family's [axis] keys)."""
    from tubecad.spec.keys import AXIS_COMMON, EXTRA_SECTIONS, FAMILY_KEYS, TUBE_KEYS

    axis = dict(AXIS_COMMON)
    for keys in FAMILY_KEYS.values():
        axis.update(keys)
    return {"axis": axis, "tube": TUBE_KEYS, **EXTRA_SECTIONS}


def parse_sweep(text: str) -> Sweep:
    """``section.key=v1,v2,...`` (TOML values) or ``section.key=start:stop:count`` (inclusive)."""
    where = f"--sweep {text!r}"
    name, sep, values = text.partition("=")
    name, values = name.strip(), values.strip()
    if not sep or not name or not values:
        raise ParameterError(f"{where}: expected SECTION.KEY=VALUES, e.g. tube.radius=10,12,15 or axis.beta_deg=0:30:4")
    section, dot, key = name.partition(".")
    sections = schema_sections()
    if not dot or not key:
        raise ParameterError(f"{where}: the key must be SECTION.KEY as in the spec file, e.g. tube.radius")
    if section not in sections:
        raise ParameterError(
            f"{where}: unknown section [{section}]; allowed sections are {', '.join(f'[{s}]' for s in sections)}"
        )
    if key not in sections[section]:
        raise ParameterError(f"{where}: unknown key [{section}] {key}; allowed keys are {', '.join(sections[section])}")
    if "\n" in values or "\r" in values:
        raise ParameterError(f"{where}: the values must be on one line")
    span = re.fullmatch(r"([^:,\[\]\"']+):([^:,\[\]\"']+):([^:,\[\]\"']+)", values)
    parsed = _range(where, *span.groups()) if span else _toml_list(where, values)
    if len(parsed) > MAX_JOBS:
        raise ParameterError(f"{where}: {len(parsed)} values; at most {MAX_JOBS} are allowed")
    return Sweep(section, key, tuple(parsed))


def _toml(text: str) -> dict[str, Any]:
    """Parse one generated TOML line ``v = ...`` (tomllib only: nothing is evaluated)."""
    doc = tomllib.loads(f"v = {text}")
    if set(doc) != {"v"}:
        raise tomllib.TOMLDecodeError("expected a single value")
    return doc


def _toml_list(where: str, values: str) -> list[Any]:
    try:
        parsed = _toml(f"[{values}]")["v"]
    except (tomllib.TOMLDecodeError, RecursionError):
        raise ParameterError(
            f"{where}: the values must be TOML values separated by commas, e.g. 10,12,15 or "
            f'\'"helix","clothoid"\' (strings in quotes), or START:STOP:COUNT'
        ) from None
    if not parsed:
        raise ParameterError(f"{where}: no values")
    return parsed


def _range(where: str, *parts: str) -> list[Any]:
    def number(v: Any) -> bool:
        return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)

    try:
        start, stop, count = (_toml(p.strip())["v"] for p in parts)
        ok = number(start) and number(stop) and type(count) is int and 2 <= count <= MAX_JOBS
    except tomllib.TOMLDecodeError:
        ok = False
    if not ok:
        raise ParameterError(
            f"{where}: a range is START:STOP:COUNT with numbers START and STOP and a whole "
            f"COUNT in [2, {MAX_JOBS}], e.g. 0:30:4 for 0, 10, 20, 30"
        )
    import numpy as np

    values = np.linspace(start, stop, count).tolist()
    if isinstance(start, int) and isinstance(stop, int) and all(float(v).is_integer() for v in values):
        values = [int(v) for v in values]  # 3:9:4 gives the whole numbers 3, 5, 7, 9
    return values


def toml_text(value: Any) -> str:
    """A value as TOML writes it (for job sources such as ``paper.toml[tube.radius=12.0]``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {toml_text(v)}" for k, v in value.items()) + "}"
    return str(value)


def _name_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list):
        return "-".join(_name_value(v) for v in value)
    return str(value)


def safe_name(text: str) -> str:
    """Letters, digits and ``. _ + -`` only, at most MAX_NAME characters."""
    return re.sub(r"[^A-Za-z0-9._+-]+", "_", text).strip("._")[:MAX_NAME] or "spec"


def plan_jobs(
    specs,
    sweeps: list[Sweep],
    out_dir: Path,
    formats,
    step_schema: str = "AP214",
    mesh_tolerance: float | None = None,
    mesh_angle: float | None = None,
) -> list[Job]:
    """One job per spec file and per combination of the swept values, with unique names;
    mesh formats are meshed to ``mesh_tolerance`` and ``mesh_angle`` (checked per job)."""
    formats = list(dict.fromkeys(f.lower() for f in formats)) or ["step"]
    bad = [f for f in formats if f not in FORMATS]
    if bad:
        raise ParameterError(f"-f/--format {bad[0]!r}: use one of {', '.join(FORMATS)}")
    labels = [s.label for s in sweeps]
    repeated = sorted({x for x in labels if labels.count(x) > 1})
    if repeated:
        raise ParameterError(f"--sweep {repeated[0]} is given more than once; give all its values in one --sweep")
    keys = [s.key for s in sweeps]
    tags = [s.key if keys.count(s.key) == 1 else f"{s.section}-{s.key}" for s in sweeps]
    combos = list(itertools.product(*(s.values for s in sweeps)))
    if len(specs) * len(combos) > MAX_JOBS:
        raise ParameterError(
            f"{len(specs)} specs x {len(combos)} swept combinations = {len(specs) * len(combos)} jobs; "
            f"at most {MAX_JOBS} are allowed"
        )
    taken = {"batch.json"}
    jobs = []
    for spec in specs:
        spec = Path(spec)
        for combo in combos:
            base = safe_name(spec.stem + "".join(f"_{tag}-{_name_value(v)}" for tag, v in zip(tags, combo)))
            name, n = base, 2
            while any(f.lower() in taken for f in _file_names(name, formats)):
                name, n = f"{base}_{n}", n + 1  # same stem twice, or names equal once made safe
            taken.update(f.lower() for f in _file_names(name, formats))
            source = str(spec) + (
                f"[{', '.join(f'{s.label}={toml_text(v)}' for s, v in zip(sweeps, combo))}]" if sweeps else ""
            )
            overrides = tuple((s.section, s.key, v) for s, v in zip(sweeps, combo))
            jobs.append(
                Job(
                    name,
                    str(spec),
                    source,
                    overrides,
                    tuple(str(out_dir / f"{name}.{f}") for f in formats),
                    str(out_dir / f"{name}.report.json"),
                    step_schema,
                    mesh_tolerance,
                    mesh_angle,
                )
            )
    return jobs


def _file_names(name: str, formats) -> list[str]:
    return [f"{name}.{f}" for f in formats] + [f"{name}.report.json"]


# ---------------------------------------------------------------- one job (in a worker or here)

_stopping = False  # a worker was told to stop (the batch was interrupted)
_busy = False  # a worker is running a job


def resolved_data(job: Job) -> dict[str, Any]:
    """The job's spec tables: the file's (or those it travelled with) with the swept values put in."""
    from tubecad.spec.parse import read_spec_data

    data = json.loads(job.spec_data) if job.spec_data is not None else read_spec_data(job.spec)
    if job.spec_data is None:
        for section, key, value in job.overrides:
            table = data.setdefault(section, {})
            if isinstance(table, dict):  # else parse_spec says the section is not a table
                table[key] = value
    return data


def referred_files(job: Job, data: dict[str, Any]) -> list[tuple[str, Path]]:
    """The files the spec refers to ([axis] file: points, a route, a STEP edge), as (the name
    the spec gives, its path beside the spec)."""
    axis = data.get("axis", {})
    name = axis.get("file") if isinstance(axis, dict) else None
    return [(name, Path(job.spec).parent / name)] if isinstance(name, str) else []


def job_spec(job: Job):
    """The job's checked spec: the file, with the swept values put in, checked as a file is."""
    from tubecad.spec.parse import parse_spec

    return parse_spec(resolved_data(job), job.source, Path(job.spec).parent)


def run_job(job: Job) -> JobResult:
    """Build one job with the single-spec code path; on failure remove what it wrote."""
    from tubecad.spec.build import build_and_export

    global _busy
    start = time.perf_counter()
    written: list[Path] = []
    _busy = True
    try:
        if _stopping:
            raise KeyboardInterrupt
        # only the tolerances given, by keyword (build_and_export's defaults otherwise)
        mesh: dict[str, Any] = {
            k: v for k, v in (("mesh_tolerance", job.mesh_tolerance), ("mesh_angle", job.mesh_angle)) if v is not None
        }
        report = build_and_export(job_spec(job), job.outputs, job.step_schema, Path(job.report), written, **mesh)
    except BaseException as exc:
        _busy = False
        for path in written:
            with contextlib.suppress(OSError):
                path.unlink()
        if not isinstance(exc, Exception):
            raise  # KeyboardInterrupt, SystemExit
        return JobResult(job.name, "failed", one_line(exc), time.perf_counter() - start)
    _busy = False
    brep = report["brep"]
    valid = bool(brep["valid"]) and all(e.get("valid", True) for e in report["exports"].values())
    return JobResult(
        job.name,
        "ok",
        None,
        time.perf_counter() - start,
        [p.name for p in written],
        brep["kind"],
        brep["faces"],
        valid,
        what_was_built(report, valid),
    )


def what_was_built(report: dict[str, Any], valid: bool = True) -> str:
    """From a job's report: 'wall 50 faces valid + 5 ring + 4 stringer stiffeners (T)', with
    '+ 6 panels' for [panels]; 'tube_solid 6 faces valid' for a plain tube."""
    brep = report["brep"]
    text = f"{brep['kind']} {brep['faces']} faces {'valid' if valid else 'NOT VALID'}"
    stiffeners = (report.get("stiffeners") or {}).get("stiffeners", [])
    if stiffeners:
        kinds = [k for k in ("ring", "stringer") if any(s["kind"] == k for s in stiffeners)]
        counts = " + ".join(f"{sum(s['kind'] == k for s in stiffeners)} {k}" for k in kinds)
        profiles = ", ".join(dict.fromkeys(s["profile"] for s in stiffeners))
        text += f" + {counts} stiffener{'s' * (len(stiffeners) > 1)} ({profiles})"
    if report.get("panels"):
        text += f" + {len(report['panels'])} panels"
    return text


#: a runaway message (an unexpected exception's repr of a huge value) is cut here; tubecad's own are far shorter
MAX_ERROR = 2000


def one_line(exc: BaseException) -> str:
    """The error of a failed job on one line, whole up to :data:`MAX_ERROR` characters."""
    text = str(exc) if isinstance(exc, TubecadError) else f"{type(exc).__name__}: {exc}"
    line = " ".join(text.split()) or type(exc).__name__
    return line if len(line) <= MAX_ERROR else line[: MAX_ERROR - 3] + "..."


def init_worker() -> None:
    """Workers leave Ctrl-C to the main process, which stops them with SIGTERM."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, on_sigterm)


def on_sigterm(_signum, _frame) -> None:
    global _stopping
    _stopping = True
    if _busy:
        raise KeyboardInterrupt  # the job's atomic writes remove their temporary files
