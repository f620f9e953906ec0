"""Where a batch's jobs run: one interface, three executors (issue 15).

- :class:`InlineExecutor`: here, one job at a time (``-j 1``);
- :class:`ProcessExecutor`: worker processes on this machine (the default: one per core),
  started with "spawn" (OCCT and fork do not mix), each running one job at a time, so that a
  job that hangs past ``--job-timeout`` or whose worker dies costs only that job: its worker
  is stopped (SIGTERM: the job's atomic writes remove their temporary files, then SIGKILL)
  and replaced, and the job is retried (``--retries``);
- :class:`tubecad.batch.dask_executor.DaskExecutor`: a Dask distributed cluster
  (``--scheduler tcp://HOST:PORT``; the extra ``tubecad[dask]``).

Jobs are specs and results are plain data: no OCCT object crosses a process boundary (OCCT
shapes do not pickle). :func:`run_jobs` drives any executor: it keeps it busy, times jobs
out, retries the ones whose worker was lost and hands each final result over once.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import signal
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from multiprocessing.connection import wait
from typing import Any, Protocol


@dataclass(frozen=True)
class Lost:
    """A job whose run was lost, not failed: its worker died or it ran past the timeout.
    Worth a retry (a failed job is not: the same spec fails the same way)."""

    message: str


class Executor(Protocol):
    """Runs jobs somewhere. ``capacity``: how many may run at once; ``description``: for
    the batch's first line; ``returns_files``: whether results carry the files' bytes."""

    capacity: int
    description: str

    def submit(self, index: int, job: Any) -> None:
        """Start ``job`` (known by ``index``) without waiting for it."""

    def poll(self, timeout: float) -> list[tuple[int, Any]]:
        """The (index, result or :class:`Lost`) of runs that ended, waiting up to ``timeout`` s."""

    def cancel(self, index: int) -> None:
        """Stop the run of ``index`` (it timed out); its worker is replaced."""

    def stop(self) -> list[tuple[int, Any]]:
        """Ctrl-C: stop every run without partial files; returns the (index, result) of runs
        that had ended as the stop came (their files are whole and kept)."""

    def close(self) -> None:
        """Release the workers."""


class InlineExecutor:
    """One job at a time in this process (no timeout: nothing here can stop it)."""

    capacity = 1
    description = "this process"

    def __init__(self, run: Callable[[Any], Any]) -> None:
        self._run = run
        self._done: list[tuple[int, Any]] = []

    def submit(self, index: int, job: Any) -> None:
        self._done.append((index, self._run(job)))

    def poll(self, timeout: float) -> list[tuple[int, Any]]:  # noqa: ARG002 - the Executor protocol's; nothing to wait for
        done, self._done = self._done, []
        return done

    def cancel(self, index: int) -> None:  # pragma: no cover - a run here has ended before it could time out
        pass

    def stop(self) -> list[tuple[int, Any]]:
        return []

    def close(self) -> None:
        pass


def _worker_main(conn, run_name: str) -> None:
    """A worker process: run the jobs it is sent, one at a time, until told to stop."""
    from importlib import import_module

    from tubecad.batch import jobs

    jobs.init_worker()
    idle = [False]

    def on_sigterm(signum, frame) -> None:
        if idle[0]:  # between jobs: nothing to clean up
            raise SystemExit(0)
        jobs.on_sigterm(signum, frame)  # in a job: its files removed; sending a result: after it

    signal.signal(signal.SIGTERM, on_sigterm)
    module, _, name = run_name.rpartition(".")
    run = getattr(import_module(module), name)
    while True:
        try:
            idle[0] = True
            message = conn.recv()
            idle[0] = False
        except (EOFError, OSError):
            return
        if message is None:
            return
        index, job = message
        result = run(job)  # SIGTERM in a job: KeyboardInterrupt, its files removed, the process ends
        conn.send((index, result))
        if jobs._stopping:  # SIGTERM after the job had ended: its result is sent, nothing more to do
            return


@dataclass
class _Worker:
    process: Any
    conn: Any
    index: int | None = None


class ProcessExecutor:
    """``workers`` processes on this machine, one job each at a time (module docstring).
    ``run``: the dotted name of the function a worker runs per job."""

    def __init__(self, workers: int, run: str = "tubecad.batch.jobs.run_job") -> None:
        self.capacity = workers
        self.description = f"{workers} process{'es' * (workers > 1)}"
        self._run = run
        self._context = multiprocessing.get_context("spawn")
        self._workers = [self._start() for _ in range(workers)]

    def _start(self) -> _Worker:
        parent, child = self._context.Pipe()
        process = self._context.Process(target=_worker_main, args=(child, self._run), daemon=True)
        process.start()
        child.close()
        return _Worker(process, parent)

    def submit(self, index: int, job: Any) -> None:
        worker = next(w for w in self._workers if w.index is None)
        worker.index = index
        worker.conn.send((index, job))

    def poll(self, timeout: float) -> list[tuple[int, Any]]:
        busy = [(w, i) for w in self._workers if (i := w.index) is not None]  # the workers holding a job
        if not busy:
            return []
        ready = set(wait([w.conn for w, _ in busy] + [w.process.sentinel for w, _ in busy], timeout))
        out: list[tuple[int, Any]] = []
        for worker, held in busy:
            if worker.conn in ready:
                try:
                    index, result = worker.conn.recv()
                except (EOFError, OSError):
                    out.append((held, self._lost(worker)))
                    continue
                worker.index = None
                out.append((index, result))
            elif worker.process.sentinel in ready:
                out.append((held, self._lost(worker)))
        return out

    def _lost(self, worker: _Worker) -> Lost:
        worker.process.join(1.0)
        code = worker.process.exitcode
        self._replace(worker)
        return Lost(f"its worker process died (exit code {code}: killed, or out of memory?) before it finished")

    def _replace(self, worker: _Worker, grace: float = 5.0) -> None:
        """Stop ``worker`` (SIGTERM, then SIGKILL after ``grace`` s) and start another in its place."""
        with contextlib.suppress(Exception):
            if worker.process.is_alive():
                worker.process.terminate()
                worker.process.join(grace)
            if worker.process.is_alive():
                worker.process.kill()
                worker.process.join(grace)
        with contextlib.suppress(Exception):
            worker.conn.close()
        self._workers[self._workers.index(worker)] = self._start()

    def cancel(self, index: int) -> None:
        for worker in self._workers:
            if worker.index == index:
                self._replace(worker)

    def stop(self) -> list[tuple[int, Any]]:
        busy = [w for w in self._workers if w.index is not None]
        for worker in busy:
            with contextlib.suppress(Exception):
                worker.process.terminate()
        ended: list[tuple[int, Any]] = []
        for worker in busy:
            worker.process.join(10.0)
            if worker.process.is_alive():
                worker.process.kill()
            worker.index = None
            with contextlib.suppress(EOFError, OSError):
                if worker.conn.poll():  # the job had ended, its files written, as the stop came
                    ended.append(worker.conn.recv())
        return ended

    def close(self) -> None:
        for worker in self._workers:
            if not worker.process.is_alive():  # a stopped worker's pipe is closed: no write to it
                continue
            with contextlib.suppress(Exception):
                worker.conn.send(None)
        for worker in self._workers:
            worker.process.join(10.0)
            if worker.process.is_alive():
                worker.process.kill()


def run_jobs(
    jobs: list,
    executor: Executor,
    finished: Callable[[int, Any], None],
    retries: int = 0,
    timeout: float | None = None,
    lost: Callable[[int, str], Any] | None = None,
    retrying: Callable[[int, str, int], None] | None = None,
) -> bool:
    """Run ``jobs`` on ``executor``, calling ``finished(index, result)`` once per job. A run
    that is lost (its worker died) or times out is retried up to ``retries`` times, then
    ``lost(index, message)`` makes its failed result; ``retrying(index, message, attempt)``
    hears of each retry. Returns whether Ctrl-C interrupted it (the executor is stopped)."""
    pending = deque(range(len(jobs)))
    started: dict[int, float] = {}
    attempts: dict[int, int] = {}

    def ended(index: int, result: Any) -> None:
        started.pop(index, None)
        if isinstance(result, Lost):
            if attempts[index] <= retries:
                if retrying is not None:
                    retrying(index, result.message, attempts[index] + 1)
                pending.appendleft(index)
                return
            result = lost(index, result.message) if lost is not None else result
        finished(index, result)

    try:
        while pending or started:
            while pending and len(started) < executor.capacity:
                index = pending.popleft()
                attempts[index] = attempts.get(index, 0) + 1
                started[index] = time.monotonic()
                executor.submit(index, jobs[index])
            for index, result in executor.poll(0.2):
                ended(index, result)
            if timeout is not None:
                now = time.monotonic()
                for index, since in list(started.items()):
                    if now - since > timeout:
                        executor.cancel(index)
                        ended(index, Lost(f"timed out after {timeout:g} s (--job-timeout)"))
    except KeyboardInterrupt:
        while True:  # a second Ctrl-C only repeats the stop
            try:
                for index, result in executor.stop():
                    if not isinstance(result, Lost):
                        started.pop(index, None)
                        finished(index, result)
                break
            except KeyboardInterrupt:
                continue
        return True
    return False
