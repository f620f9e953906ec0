"""Running a batch of jobs (:mod:`.jobs`) on an executor (:mod:`.executors`): a line per
finished job with the rate and the time left, retries of lost runs, no temporary file left
behind, and the record that ``batch.json`` (:mod:`.manifest`) holds."""

from __future__ import annotations

import glob
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from tubecad.batch.executors import InlineExecutor, ProcessExecutor, run_jobs
from tubecad.batch.jobs import Job, JobResult, run_job
from tubecad.batch.manifest import file_hash


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
        return head + "FAILED" + tries + ": " + (error if len(error) <= 300 else error[:297] + "...") + pace
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
