"""A batch on a Dask distributed cluster (``tubecad build ... --scheduler tcp://HOST:PORT``;
the extra ``tubecad[dask]``), behind the executor interface of :mod:`.executors`.

Each job goes to the cluster as plain data: its resolved spec (JSON) and the bytes of the
files the spec refers to, so the workers need tubecad installed but not the submitter's
files. A worker builds the job into a temporary folder of its own and sends back the
result and the files' bytes; the submitting machine writes them into the batch folder
atomically (each file complete or not at all). With ``--remote-dir DIR`` the workers share a
file system and write into DIR themselves (through the same atomic writes).

Faults: Dask reschedules the tasks of a worker that dies on the others; a task that keeps
killing workers ends as ``KilledWorker``, reported as a lost run (retried by
:func:`.executors.run_jobs`). A job past ``--job-timeout`` is cancelled and the worker running
it restarted by its nanny, so a hung job holds no worker.
"""

from __future__ import annotations

import dataclasses
import json
import tempfile
import uuid
from pathlib import Path
from typing import Any

from tubecad.batch.executors import Lost
from tubecad.core.errors import TubecadError


def remote_job(job, return_files: bool = True) -> tuple[Any, dict[str, bytes]]:
    """On a worker: build ``job`` (tubecad.batch.jobs.run_job); with ``return_files``,
    in a temporary folder, returning the result and {file name: bytes}."""
    from tubecad.batch.jobs import run_job

    with tempfile.TemporaryDirectory(prefix="tubecad-job-") as tmp:
        folder = Path(tmp)
        for name, data in job.attachments:
            target = folder / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        spec_path = str(folder / "spec.toml") if job.spec_data is not None else job.spec
        if not return_files:
            return run_job(dataclasses.replace(job, spec=spec_path)), {}
        local = dataclasses.replace(
            job,
            spec=spec_path,
            outputs=tuple(str(folder / Path(p).name) for p in job.outputs),
            report=str(folder / Path(job.report).name),
        )
        result = run_job(local)
        files = {}
        if result.status == "ok":
            files = {Path(p).name: Path(p).read_bytes() for p in (*local.outputs, local.report) if Path(p).exists()}
        return result, files


def shipped(job, remote_dir: str | None = None):
    """``job`` as it travels: its resolved spec as JSON and the files its [axis] refers to;
    with ``remote_dir``, its outputs under that folder (the batch folder as workers see it)."""
    from tubecad.batch.jobs import referred_files, resolved_data

    data = resolved_data(job)
    attachments = tuple((name, path.read_bytes()) for name, path in referred_files(job, data) if path.is_file())
    changes: dict[str, Any] = {"spec_data": json.dumps(data), "attachments": attachments}
    if remote_dir is not None:
        changes["outputs"] = tuple(str(Path(remote_dir) / Path(p).name) for p in job.outputs)
        changes["report"] = str(Path(remote_dir) / Path(job.report).name)
    return dataclasses.replace(job, **changes)


class DaskExecutor:
    """Jobs on the Dask cluster at ``address`` (module docstring); results written into
    ``out_dir`` here unless ``remote_dir`` (the workers write there)."""

    def __init__(
        self, address: str, remote_dir: str | None = None, out_dir: str | Path | None = None, timeout: str = "5s"
    ) -> None:
        try:
            from distributed import Client
        except ImportError:
            raise TubecadError("--scheduler needs Dask: pip install 'tubecad[dask]'") from None
        try:
            self.client = Client(address, timeout=timeout)
        except (OSError, TimeoutError) as exc:
            raise TubecadError(f"--scheduler {address}: cannot reach the Dask scheduler ({exc})") from None
        except ValueError as exc:
            raise TubecadError(
                f"--scheduler {address!r}: not a scheduler address such as tcp://HOST:PORT ({exc})"
            ) from None
        info = self.client.scheduler_info()
        workers = info.get("workers", {})
        threads = sum(w.get("nthreads", 1) for w in workers.values()) or 1
        self.capacity = threads  # one job per thread: a job's --job-timeout runs from when it starts, not queues
        self.remote_dir = remote_dir
        self.out_dir = Path(out_dir) if out_dir is not None else None
        self.description = (
            f"Dask at {address} ({len(workers)} worker{'s' * (len(workers) != 1)}, {threads} "
            f"thread{'s' * (threads != 1)}; dashboard {self.client.dashboard_link})"
        )
        self._futures: dict[Any, int] = {}
        self._jobs: dict[int, Any] = {}

    def submit(self, index: int, job) -> None:
        task = shipped(job, self.remote_dir)
        key = f"tubecad-{job.name}-{uuid.uuid4().hex[:8]}"
        future = self.client.submit(remote_job, task, self.remote_dir is None, key=key, pure=False)
        self._futures[future] = index
        self._jobs[index] = job

    def poll(self, timeout: float) -> list[tuple[int, Any]]:
        from distributed import wait

        if not self._futures:
            return []
        try:
            done, _ = wait(list(self._futures), timeout=timeout, return_when="FIRST_COMPLETED")
        except TimeoutError:
            return []
        out = []
        for future in done:
            index = self._futures.pop(future)
            job = self._jobs.pop(index)
            out.append((index, self._outcome(future, job)))
        return out

    def _outcome(self, future, job):
        from distributed import KilledWorker

        from tubecad.batch.jobs import JobResult, one_line

        if future.status == "finished":
            result, files = future.result()
            if files:
                self._deliver(job, files)
            return result
        exc = future.exception()
        if isinstance(exc, KilledWorker):
            return Lost(f"its Dask worker died running it ({one_line(exc)})")
        return JobResult(job.name, "failed", one_line(exc))

    def _deliver(self, job, files: dict[str, bytes]) -> None:
        """Write the files a worker sent back into the batch folder, each atomically."""
        from tubecad.core.atomic import atomic_path

        folder = Path(job.report).parent
        for name, data in files.items():
            with atomic_path(folder / name) as tmp:
                tmp.write_bytes(data)

    def cancel(self, index: int) -> None:
        for future, i in list(self._futures.items()):
            if i == index:
                running = [w for w, keys in self.client.processing().items() if future.key in keys]
                self.client.cancel(future)
                if running:
                    try:
                        self.client.restart_workers(running)
                    except Exception:  # a worker without a nanny cannot be restarted
                        pass
                del self._futures[future]
                self._jobs.pop(index, None)

    def stop(self) -> list[tuple[int, Any]]:
        self.client.cancel(list(self._futures))
        self._futures.clear()
        return []

    def close(self) -> None:
        self.client.close()
