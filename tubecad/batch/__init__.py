"""Batches of spec builds: sweeps and jobs, the executors (this process, worker processes, a
Dask cluster), the manifest that makes reruns resume."""
