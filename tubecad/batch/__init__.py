"""Batches of spec builds: sweeps and jobs, the executors (this process, worker processes, a
Dask cluster), the manifest that makes reruns resume, and the runner: a whole batch as
``tubecad build`` runs it, for a script too::

    from tubecad.batch import BatchOptions, build_batch

    outcome = build_batch(["a.toml", "b.toml"], "out", BatchOptions(formats=("step", "iges"), jobs=2))

Names are imported on first use."""

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "BatchOptions": "tubecad.batch.runner",
    "BatchOutcome": "tubecad.batch.runner",
    "build_batch": "tubecad.batch.runner",
    "run_batch": "tubecad.batch.runner",
    "Job": "tubecad.batch.jobs",
    "JobResult": "tubecad.batch.jobs",
    "parse_sweep": "tubecad.batch.jobs",
    "plan_jobs": "tubecad.batch.jobs",
    "run_job": "tubecad.batch.jobs",
    "read_manifest": "tubecad.batch.manifest",
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
