"""Running a batch of jobs (:mod:`.jobs`) on an executor (:mod:`.executors`): a line per
finished job with the rate and the time left, retries of lost runs, no temporary file left
behind, and the record that ``batch.json`` (:mod:`.manifest`) holds.

:func:`build_batch` is a whole batch as ``tubecad build`` runs it (plan, resume from the
manifest, run, record), library code a script calls with :class:`BatchOptions`::

    from tubecad.batch.runner import BatchOptions, build_batch

    outcome = build_batch(["a.toml"], "out", BatchOptions(sweeps=("tube.radius=10,12",), formats=("step",)))
    assert outcome.failed == 0
"""

from __future__ import annotations

import glob
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tubecad.batch.executors import InlineExecutor, ProcessExecutor, run_jobs
from tubecad.batch.jobs import Job, JobResult, run_job
from tubecad.batch.manifest import file_hash
from tubecad.core.errors import ParameterError


def progress_line(result: JobResult, done: int, total: int, rate: float | None = None) -> str:
    """``[3/12] name: what was built, 2 files, 1.2 s``, then the rate and the time left."""
    head = f"[{done}/{total}] {result.name}: "
    pace = ""
    if rate:
        left = (total - done) / rate
        pace = f"; {rate:.3g} jobs/s, ~{_duration(left)} left" if done < total else f"; {rate:.3g} jobs/s"
    tries = f" (attempt {result.attempts})" if result.attempts > 1 else ""
    if result.status != "ok":
        error = result.error or result.status
        # whole: the end of a message often holds the fix ("... or set allow_irregular = true");
        # messages are one line and bounded where they are made (tubecad.batch.jobs.one_line)
        return head + "FAILED" + tries + ": " + error + pace
    built = result.built or f"{result.kind} {result.faces} faces {'valid' if result.valid else 'NOT VALID'}"
    files = len(result.outputs)
    return head + f"{built}, {files} file{'s' * (files != 1)}, {result.seconds:.1f} s{tries}{pace}"


def _duration(seconds: float) -> str:
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def run_batch(
    jobs: list[Job],
    workers: int,
    echo: Callable[[str], None],
    *,
    executor=None,
    retries: int = 0,
    timeout: float | None = None,
    on_result: Callable[[int, JobResult], None] | None = None,
) -> tuple[list[JobResult | None], bool]:
    """Run the jobs on ``executor`` (default: ``workers`` processes, or here if 1), echoing a
    line per finished job; ``on_result(index, result)`` after each (the manifest is written
    there). A lost run (its worker died, or it ran past ``timeout`` s) is retried up to
    ``retries`` times. Returns the results in job order (None: cancelled) and whether Ctrl-C
    interrupted it."""
    results: dict[int, JobResult] = {}
    attempts: dict[int, int] = {}
    start = time.perf_counter()
    own = executor is None
    if own:
        executor = InlineExecutor(run_job) if workers <= 1 and timeout is None else ProcessExecutor(max(1, workers))

    def finished(i: int, result: JobResult) -> None:
        result.attempts = attempts.get(i, 0) + 1
        if result.status == "ok":
            folder = Path(jobs[i].report).parent
            result.hashes = {
                name: file_hash(folder / name)
                for name in [*result.outputs, Path(jobs[i].report).name]
                if (folder / name).exists()
            }
        results[i] = result
        if on_result is not None:  # recorded (the manifest) before its line says it is done
            on_result(i, result)
        rate = len(results) / max(time.perf_counter() - start, 1e-9)
        echo(progress_line(result, len(results), len(jobs), rate))

    def retrying(i: int, message: str, attempt: int) -> None:
        attempts[i] = attempt - 1
        echo(f"[{len(results)}/{len(jobs)}] {jobs[i].name}: {message}; retrying (attempt {attempt})")

    def lost(i: int, message: str) -> JobResult:
        return JobResult(jobs[i].name, "failed", message)

    try:
        interrupted = run_jobs(jobs, executor, finished, retries, timeout, lost, retrying)
    finally:
        if own:
            executor.close()
    if interrupted or any(r.status != "ok" for r in results.values()):
        remove_temporaries(jobs)
    return [results.get(i) for i in range(len(jobs))], interrupted


def remove_temporaries(jobs: list[Job]) -> None:
    """Remove temporary files of the jobs' targets that a killed worker could leave behind."""
    for job in jobs:
        for target in map(Path, (*job.outputs, job.report)):
            for tmp in target.parent.glob(f".{glob.escape(target.name)}.*.part{glob.escape(target.suffix)}"):
                tmp.unlink(missing_ok=True)


def batch_record(
    jobs: list[Job],
    results: list[JobResult | None],
    interrupted: bool,
    seconds: float,
    workers: int,
    sweeps: list[str],
    formats,
) -> dict[str, Any]:
    """What batch.json holds: the run and every job (name, source, status, error, seconds, outputs)."""
    entries = []
    for job, result in zip(jobs, results):
        result = result or JobResult(job.name, "cancelled", "interrupted (Ctrl-C) before it finished")
        entries.append(
            {
                "name": job.name,
                "source": job.source,
                "sweep": {f"{s}.{k}": v for s, k, v in job.overrides},
                "status": result.status,
                "error": result.error,
                "seconds": None if result.seconds is None else round(result.seconds, 3),
                "outputs": result.outputs,
                "attempts": result.attempts,
                "skipped": result.skipped,
                "spec_hash": result.spec_hash,
                "hashes": result.hashes,
            }
        )
    counts = {status: sum(e["status"] == status for e in entries) for status in ("ok", "failed", "cancelled")}
    return {
        "jobs_total": len(jobs),
        **counts,
        "skipped": sum(e["skipped"] for e in entries),
        "interrupted": interrupted,
        "seconds": round(seconds, 3),
        "workers": workers,
        "formats": list(formats),
        "sweeps": list(sweeps),
        "jobs": entries,
    }


# ---------------------------------------------------------------- a whole batch: plan, resume, run, record

#: the manifest is rewritten as jobs finish, at most this often (seconds); the run's end
#: (or Ctrl-C) writes it once more, so only a killed submitter can lose that much of it
#: (those jobs are built again by the rerun)
MANIFEST_INTERVAL = 0.5


@dataclass(frozen=True)
class BatchOptions:
    """How :func:`build_batch` runs (``tubecad build``'s batch options, docs/command-line.md).

    ``formats``: the outputs per job, by extension without the dot (default step);
    ``sweeps``: ``SECTION.KEY=VALUES`` texts (:func:`~tubecad.batch.jobs.parse_sweep`);
    ``jobs``: how many run at once (default: every core); ``scheduler``: a Dask cluster
    ``tcp://HOST:PORT`` (default: the first spec's ``[batch] scheduler``; ``"local"``: this
    machine's processes), ``remote_dir``: the batch folder as its workers see it; ``resume``:
    skip the jobs the folder's batch.json shows built and unchanged; ``retries``: how often a
    lost job (its worker died, or it ran past ``job_timeout`` seconds) runs again;
    ``quiet``: no line per job (the closing summary is still told)."""

    formats: tuple[str, ...] = ()
    sweeps: tuple[str, ...] = ()
    step_schema: str = "AP214"
    jobs: int | None = None
    mesh_tolerance: float | None = None
    mesh_angle: float | None = None
    scheduler: str | None = None
    remote_dir: str | None = None
    resume: bool = True
    retries: int = 1
    job_timeout: float | None = None
    quiet: bool = False


@dataclass
class BatchOutcome:
    """What became of a batch: every planned job and its result (None: cancelled), whether
    Ctrl-C ended it, the manifest written, and the exit code ``tubecad build`` gives it."""

    jobs: list[Job]
    results: list[JobResult | None]
    interrupted: bool
    manifest: Path
    seconds: float
    where: str

    def count(self, status: str) -> int:
        return sum(r is not None and r.status == status for r in self.results)

    @property
    def ok(self) -> int:
        return self.count("ok")

    @property
    def failed(self) -> int:
        return self.count("failed")

    @property
    def cancelled(self) -> int:
        return sum(r is None for r in self.results)

    @property
    def skipped(self) -> int:
        return sum(r is not None and r.skipped for r in self.results)

    @property
    def exit_code(self) -> int:
        """130 if interrupted (as shells report Ctrl-C), 2 if any job failed, else 0."""
        return 130 if self.interrupted else 2 if self.failed else 0

    def summary(self) -> str:
        """The closing line: counts, time and the manifest."""
        if self.interrupted:
            return (
                f"interrupted: {self.cancelled} of {len(self.jobs)} jobs cancelled, {self.ok} done, "
                f"no partial files; {self.manifest}"
            )
        # each job counted once: a skipped job (built before, unchanged) is not also "ok"
        skipped = f", {self.skipped} skipped (unchanged)" if self.skipped else ""
        built = self.ok - self.skipped
        return (
            f"{len(self.jobs)} jobs: {built} ok{skipped}, {self.failed} failed, {self.seconds:.1f} s; {self.manifest}"
        )


def batch_scheduler(spec: str | Path) -> str | None:
    """``[batch] scheduler`` of ``spec``, if it has one (None if it cannot be read: its job says why)."""
    from tubecad.core.errors import TubecadError
    from tubecad.spec.parse import read_spec_data

    try:
        section = read_spec_data(spec).get("batch", {})
    except TubecadError:
        return None
    value = section.get("scheduler") if isinstance(section, dict) else None
    if value is not None and not isinstance(value, str):
        raise ParameterError(
            f'{spec}: [batch] scheduler must be a string such as "tcp://10.0.0.5:8786", got {value!r:.60}',
            key="batch.scheduler",
        )
    return value


def build_batch(
    specs: list[str | Path] | tuple[str | Path, ...],
    out_dir: str | Path,
    options: BatchOptions | None = None,
    echo: Callable[[str], None] | None = None,
) -> BatchOutcome:
    """Build every spec (and every combination of the swept values) into ``out_dir``:
    NAME.EXT per format, NAME.report.json per job, and the manifest batch.json, rewritten as
    jobs finish (at most every :data:`MANIFEST_INTERVAL` s) and at the end. A rerun resumes:
    a job the manifest shows built from the same spec, its files unchanged, is skipped.
    ``echo`` hears a line per finished job and the closing summary (default: nothing).

    Bad input (a sweep, a format, the scheduler, the folder) raises a TubecadError before
    anything is written; ``key="remote_dir"`` for a ``remote_dir`` without a cluster. A
    failed job does not stop the others: see the outcome's ``failed`` and ``exit_code``."""
    import os

    from tubecad.batch.jobs import parse_sweep, plan_jobs
    from tubecad.batch.manifest import read_manifest, spec_hash, up_to_date
    from tubecad.core.atomic import write_text
    from tubecad.spec.report import to_json

    options = options or BatchOptions()
    say = echo or (lambda _line: None)
    out_dir = Path(out_dir)
    planned = plan_jobs(
        specs,
        [parse_sweep(s) for s in options.sweeps],
        out_dir,
        options.formats,
        options.step_schema,
        options.mesh_tolerance,
        options.mesh_angle,
    )
    scheduler = options.scheduler or batch_scheduler(specs[0])
    scheduler = None if scheduler == "local" else scheduler
    if options.remote_dir is not None and scheduler is None:
        raise ParameterError("--remote-dir is for a batch on a Dask cluster (--scheduler)", key="remote_dir")
    executor = None
    if scheduler is not None:  # reached before anything is written
        from tubecad.batch.dask_executor import DaskExecutor

        executor = DaskExecutor(scheduler, remote_dir=options.remote_dir, out_dir=out_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        if executor is not None:
            executor.close()
        raise ParameterError(f"cannot create output folder {str(out_dir)!r}: {exc.strerror}", key="out_dir") from None
    manifest = read_manifest(out_dir) if options.resume else {}
    digests = [_digest(spec_hash, job) for job in planned]
    done = {i for i, job in enumerate(planned) if up_to_date(manifest.get(job.name), job, digests[i])}
    todo = [i for i in range(len(planned)) if i not in done]
    results: list[JobResult | None] = [None] * len(planned)
    for i in done:
        entry = manifest[planned[i].name]
        results[i] = JobResult(
            planned[i].name,
            "ok",
            None,
            entry.get("seconds"),
            list(entry.get("outputs", [])),
            attempts=entry.get("attempts", 1),
            hashes=dict(entry.get("hashes", {})),
            spec_hash=digests[i],
            skipped=True,
        )
    workers = min(options.jobs or os.cpu_count() or 1, max(len(todo), 1))
    start = time.perf_counter()
    where = executor.description if executor is not None else f"{workers} process{'es' * (workers > 1)}"
    formats = options.formats or ("step",)

    def record(interrupted: bool = False) -> Path:
        seconds = time.perf_counter() - start
        data = batch_record(planned, results, interrupted, seconds, workers, list(options.sweeps), formats)
        return write_text(out_dir / "batch.json", to_json(data))

    last = [0.0]

    def on_result(k: int, result: JobResult) -> None:
        result.spec_hash = digests[todo[k]]
        results[todo[k]] = result
        if time.perf_counter() - last[0] >= MANIFEST_INTERVAL:  # the manifest, atomically, as jobs finish
            record()
            last[0] = time.perf_counter()

    if not options.quiet:
        resumed = f" ({len(done)} of {len(planned)} already built and unchanged: skipped)" if done else ""
        say(f"building {len(todo)} job{'s' * (len(todo) != 1)} with {where} into {out_dir}{resumed}")
    interrupted = False
    try:
        if todo:
            _, interrupted = run_batch(
                [planned[i] for i in todo],
                workers,
                (lambda _line: None) if options.quiet else say,
                executor=executor,
                retries=options.retries,
                timeout=options.job_timeout,
                on_result=on_result,
            )
    finally:
        if executor is not None:
            executor.close()
    summary = record(interrupted)
    outcome = BatchOutcome(planned, results, interrupted, summary, time.perf_counter() - start, where)
    say(outcome.summary())
    return outcome


def _digest(spec_hash: Callable[[Job], str], job: Job) -> str | None:
    """The job's spec hash, or None when its spec cannot be read (the job then fails, saying why)."""
    try:
        return spec_hash(job)
    except Exception:  # a bad spec fails its own job with the checker's message
        return None
