"""Batch throughput of ``tubecad build --sweep`` on the local pool and on a Dask cluster (issue 15).

``python benchmarks/batch_scaling.py [--quick] [--rounds N] [--output FILE]``

Every batch is what a user runs: the command line in a subprocess
(``python -m tubecad.cli.console build SPEC --sweep tube.radius=4:6:N -d DIR --force``),
its per-job lines on stderr time-stamped here as they arrive (the jobs' finish times), its
DIR/batch.json read afterwards (each job's own build seconds, the batch's wall time).

1. **Scaling**: 24 jobs of a small helix tube (about 0.3-1 s each) on the local pool with
   ``-j 1`` (the jobs run in the command's own process: tubecad's InlineExecutor), ``-j 1
   --job-timeout 1e6`` (one spawned worker process: the pool of one), ``-j 2``, and on
   ``distributed.LocalCluster``\\ s of 1 and 2 worker processes (1 thread each) started here
   and passed with ``--scheduler``. Scaling efficiency = jobs/s at 2 / (2 x jobs/s at 1).
2. **Overhead per job**: the same executors on 40 jobs of the smallest tube tubecad builds
   (20 mm of helix, 2 rings, 1 stringer, ``-f brep``).
3. **1,000 jobs** of the small tube on the local pool with ``-j 2``: wall time, jobs/s,
   peak memory (process tree polled every 0.5 s), the manifest checked, and a rerun into
   the same folder (all 1000 skipped: the resume check's cost). Stopped (Ctrl-C, so the
   manifest stays consistent) if it runs past ``--max-minutes``.

Side by side: the machine is shared (other processes, e.g. a CI run, may use the CPU), so
the executors are measured in rounds, each round running every configuration once, one
after the other (the order reversed every other round), and the numbers compared are
medians over the rounds; scaling efficiencies are paired within a round. Every run records
the CPU the rest of the machine used meanwhile (``other_cores``: busy CPU seconds of the
whole machine minus those of this benchmark's processes, per second of wall time) and the
load average. The Dask workers persist between batches: before the rounds, one batch of the
small tube runs on each fresh cluster (``cold``: its workers import OCCT in their first
jobs), reported apart; in the rounds the Dask workers are warm, while the local pool starts
(spawns) its workers in every batch, as a user's every ``tubecad build`` does.

Throughput is given two ways:

- ``jobs_per_s``: jobs / the command's wall time, launch to exit (what a user waits for:
  Python and tubecad imports, planning, worker start-up, every job, the manifest);
- ``steady_jobs_per_s``: (N - W) / (finish time of the last job - finish time of the W-th),
  W the number of workers: the rate once every worker has finished its first job, so
  without the start-up and the first job's warm-up.

Overhead per job (what a job costs beyond its own build, as seen by a worker slot):

- ``overhead_steady_s`` = W / steady_jobs_per_s - the mean own seconds of the jobs that
  finished in that window (the cleanest: no start-up, no tail where a worker idles);
- ``overhead_batch_s`` = (batch.json seconds x W - sum of the jobs' own seconds) / N, the
  issue's definition on the batch's own clock (from the executor's start to the end);
- ``overhead_total_s``: the same with the command's wall time (start-up included).

``startup_s``: launch to the moment the first job's build began (its finish time minus its
own seconds): imports, planning, the manifest check, worker start-up. A spawned worker's
first job imports the build modules (OCCT, build123d) inside its own timed seconds
(tubecad imports them lazily in run_job), so the overheads from own seconds count that
import as build time; the steady numbers leave each worker's first job out.
"""

from __future__ import annotations

import argparse
import contextlib
import hashlib
import json
import os
import platform
import re
import resource
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import psutil

ROOT = Path(__file__).resolve().parent.parent
RESULT = ROOT / "benchmarks" / "results" / "batch_scaling.json"
CLI = [sys.executable, "-m", "tubecad.cli.console", "build"]
#: the code measured: hashed before and after, since the tree may be edited meanwhile
WATCHED = [
    "tubecad/batch/jobs.py",
    "tubecad/batch/executors.py",
    "tubecad/batch/dask_executor.py",
    "tubecad/cli/app.py",
    "tubecad/batch/manifest.py",
    "tubecad/spec/build.py",
    "tubecad/design/report.py",
]

SMALL = """[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 300.0]

[tube]
radius = 5.0

[layout]
rings = 3
stringers = 2
"""
TRIVIAL = (
    SMALL.replace("s = [0.0, 300.0]", "s = [0.0, 20.0]")
    .replace("rings = 3", "rings = 2")
    .replace("stringers = 2", "stringers = 1")
)

RUNNING: list[subprocess.Popen] = []  # the command running now (stopped with the benchmark)
JOB_LINE = re.compile(r"\[(\d+)/(\d+)\] ([A-Za-z0-9._+-]+): (.*)")
MB = 1024.0 * 1024.0


# ---------------------------------------------------------------- one command, watched


class Monitor(threading.Thread):
    """Polls the memory of the command's process tree (and of ``extra`` processes: Dask
    workers and nannies) every ``interval`` s; keeps peaks and a sparse time series."""

    def __init__(self, pid: int, extra: list[int] = (), interval: float = 0.5, every: float = 10.0) -> None:
        super().__init__(daemon=True)
        self.root = psutil.Process(pid)
        self.extra = [psutil.Process(p) for p in extra if psutil.pid_exists(p)]
        self.interval, self.every = interval, every
        self.done = threading.Event()
        self.t0 = time.perf_counter()
        self.peak = {
            "submitter_mb": 0.0,
            "children_sum_mb": 0.0,
            "largest_child_mb": 0.0,
            "tree_mb": 0.0,
            "cluster_sum_mb": 0.0,
            "largest_cluster_process_mb": 0.0,
            "total_mb": 0.0,
        }
        self.series: list[dict] = []
        self._last = -1e9
        self.samples = 0
        self._cpu: dict[int, float] = {}  # pid -> its CPU seconds when last seen
        self._ours = 0.0  # CPU seconds of the watched processes (increments, so exited ones stay counted)
        self._mark = (time.perf_counter(), _machine_busy(psutil.cpu_times()), 0.0)

    @staticmethod
    def _rss(process: psutil.Process) -> float:
        try:
            return process.memory_info().rss / MB
        except (psutil.NoSuchProcess, psutil.AccessDenied, psutil.ZombieProcess):
            return 0.0

    def sample(self) -> None:
        own = self._rss(self.root)
        try:
            children = self.root.children(recursive=True)
        except (psutil.NoSuchProcess, psutil.ZombieProcess):
            children = []
        kids = {c.pid: self._rss(c) for c in children}
        cluster = [self._rss(p) for p in self.extra]
        now = {
            "submitter_mb": own,
            "children_sum_mb": sum(kids.values()),
            "largest_child_mb": max(kids.values(), default=0.0),
            "tree_mb": own + sum(kids.values()),
            "cluster_sum_mb": sum(cluster),
            "largest_cluster_process_mb": max(cluster, default=0.0),
        }
        now["total_mb"] = now["tree_mb"] + now["cluster_sum_mb"]
        for key, value in now.items():
            self.peak[key] = max(self.peak[key], value)
        for process in [self.root, *children, *self.extra]:
            cpu = _cpu_seconds([process])
            if cpu:
                self._ours += max(cpu - self._cpu.get(process.pid, 0.0), 0.0)
                self._cpu[process.pid] = cpu
        self.samples += 1
        t = time.perf_counter() - self.t0
        if t - self._last >= self.every:
            self._last = t
            wall, busy = time.perf_counter(), _machine_busy(psutil.cpu_times())
            span = max(wall - self._mark[0], 1e-9)
            others = max(busy - self._mark[1] - (self._ours - self._mark[2]), 0.0) / span
            self._mark = (wall, busy, self._ours)
            self.series.append(
                {
                    "t": round(t, 1),
                    "submitter_mb": round(own, 1),
                    "children_mb": [round(kids[p], 1) for p in sorted(kids)],
                    "cluster_mb": [round(c, 1) for c in cluster],
                    "other_cores_since_last": round(others, 2),
                }
            )

    def run(self) -> None:
        while not self.done.is_set():
            self.sample()
            self.done.wait(self.interval)

    def stop(self) -> None:
        self.done.set()
        self.join()


def _cpu_seconds(processes: list[psutil.Process]) -> float:
    total = 0.0
    for p in processes:
        try:
            t = p.cpu_times()
            total += t.user + t.system
        except (psutil.NoSuchProcess, psutil.AccessDenied, psutil.ZombieProcess):
            pass
    return total


def _machine_busy(times) -> float:
    idle = times.idle + getattr(times, "iowait", 0.0)
    return sum(times) - idle - getattr(times, "guest", 0.0) - getattr(times, "guest_nice", 0.0)


def run_command(
    args: list[str],
    out_dir: Path,
    *,
    extra_pids: list[int] = (),
    limit_s: float | None = None,
    interrupt_when_planned: bool = False,
    series_every: float = 10.0,
) -> dict:
    """Run ``tubecad build ARGS`` in a subprocess; time-stamp its job lines; watch memory and CPU."""
    extra = [psutil.Process(p) for p in extra_pids if psutil.pid_exists(p)]
    load0 = os.getloadavg()
    machine0 = psutil.cpu_times()
    children0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    self0 = resource.getrusage(resource.RUSAGE_SELF)
    extra0 = _cpu_seconds(extra)
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        CLI + args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, cwd=ROOT
    )
    RUNNING[:] = [proc]
    monitor = Monitor(proc.pid, extra_pids, every=series_every)
    monitor.start()
    stopped = []

    def interrupt(reason: str) -> None:
        if proc.poll() is None and not stopped:
            stopped.append(reason)
            proc.send_signal(signal.SIGINT)

    timer = threading.Timer(limit_s, interrupt, ("time limit",)) if limit_s else None
    if timer:
        timer.start()
    planned_s, finishes, retries, other = None, [], 0, []
    for line in proc.stderr:
        t = time.perf_counter() - t0
        line = line.rstrip("\n")
        m = JOB_LINE.match(line)
        if line.startswith("building ") and planned_s is None:
            planned_s = t
            other.append(line)
            if interrupt_when_planned:
                interrupt("asked to stop once planned")
        elif m and "; retrying (attempt" in m.group(4):
            retries += 1
            other.append(line)
        elif m:
            finishes.append((t, m.group(3), m.group(4).startswith("FAILED")))
        else:
            other.append(line)
    rc = proc.wait()
    wall = time.perf_counter() - t0
    RUNNING.clear()
    if timer:
        timer.cancel()
    monitor.stop()
    children1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    self1 = resource.getrusage(resource.RUSAGE_SELF)
    machine1 = psutil.cpu_times()
    ours = (
        children1.ru_utime
        + children1.ru_stime
        - children0.ru_utime
        - children0.ru_stime
        + self1.ru_utime
        + self1.ru_stime
        - self0.ru_utime
        - self0.ru_stime
        + _cpu_seconds(extra)
        - extra0
    )
    busy = _machine_busy(machine1) - _machine_busy(machine0)
    try:
        manifest = json.loads((out_dir / "batch.json").read_text())
    except (OSError, ValueError):
        manifest = None
    return {
        "args": args,
        "returncode": rc,
        "wall_s": wall,
        "planned_s": planned_s,
        "finishes": finishes,
        "retry_lines": retries,
        "other_lines": other[-6:],
        "stopped": stopped[0] if stopped else None,
        "manifest": manifest,
        "memory": {k: round(v, 1) for k, v in monitor.peak.items()},
        "memory_samples": monitor.samples,
        "memory_series": monitor.series,
        "conditions": {
            "loadavg_1min_start": round(load0[0], 2),
            "loadavg_1min_end": round(os.getloadavg()[0], 2),
            "machine_busy_cores": round(busy / wall, 2),
            "benchmark_cores": round(ours / wall, 2),
            "other_cores": round(max(busy - ours, 0.0) / wall, 2),
        },
    }


def metrics(raw: dict, workers: int) -> dict:
    """The numbers of one batch (module docstring) from its watched run."""
    manifest = raw["manifest"] or {}
    entries = {e["name"]: e for e in manifest.get("jobs", [])}
    finishes = raw["finishes"]
    n = len(finishes)
    own = [entries.get(name, {}).get("seconds") or 0.0 for _, name, _ in finishes]
    out = {
        "jobs": n,
        "workers": workers,
        "returncode": raw["returncode"],
        "ok": manifest.get("ok"),
        "failed": manifest.get("failed"),
        "skipped": manifest.get("skipped"),
        "wall_s": round(raw["wall_s"], 3),
        "planned_s": None if raw["planned_s"] is None else round(raw["planned_s"], 3),
        "batch_s": manifest.get("seconds"),
        "sum_job_s": round(sum(own), 3),
        "mean_job_s": round(sum(own) / n, 4) if n else None,
    }
    if n:
        first_t, first_name, _ = finishes[0]
        out["first_finish_s"] = round(first_t, 3)
        out["last_finish_s"] = round(finishes[-1][0], 3)
        out["startup_s"] = round(first_t - own[0], 3)
        out["jobs_per_s"] = round(n / raw["wall_s"], 4)
        if manifest.get("seconds"):
            out["batch_jobs_per_s"] = round(n / manifest["seconds"], 4)
            out["overhead_batch_s"] = round((manifest["seconds"] * workers - sum(own)) / n, 4)
        out["overhead_total_s"] = round((raw["wall_s"] * workers - sum(own)) / n, 4)
    if n > workers + 1:
        window = finishes[-1][0] - finishes[workers - 1][0]
        steady = (n - workers) / window
        mean_steady = statistics.fmean(own[workers:])
        out["steady_jobs_per_s"] = round(steady, 4)
        out["steady_mean_job_s"] = round(mean_steady, 4)
        out["overhead_steady_s"] = round(workers / steady - mean_steady, 4)
    out["memory"] = raw["memory"]
    out["conditions"] = raw["conditions"]
    if raw["stopped"]:
        out["stopped"] = raw["stopped"]
    if raw["retry_lines"]:
        out["retry_lines"] = raw["retry_lines"]
    bad = [line for line in raw["other_lines"] if not line.startswith(("building ", f"{n} jobs:", "interrupted"))]
    if raw["returncode"] != 0 or bad:
        out["stderr_tail"] = raw["other_lines"]
    return out


# ---------------------------------------------------------------- executors and rounds


class Clusters:
    """The Dask LocalClusters (1 and 2 workers, 1 thread each, processes) for the whole run."""

    def __init__(self, sizes=(1, 2), log=print) -> None:
        from distributed import Client, LocalCluster

        self.clusters, self.clients, self.start_s = {}, {}, {}
        for n in sizes:
            start = time.perf_counter()
            cluster = LocalCluster(
                n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address="127.0.0.1:0"
            )
            self.start_s[n] = round(time.perf_counter() - start, 3)
            self.clusters[n] = cluster
            self.clients[n] = Client(cluster)
            log(
                f"  LocalCluster({n} worker{'s' * (n > 1)}) at {cluster.scheduler_address}: started in {self.start_s[n]:.1f} s"
            )

    def pids(self, n: int) -> list[int]:
        """The cluster's worker processes and their nannies (asked again each run: a nanny may restart its worker)."""
        workers = list(self.clients[n].run(os.getpid).values())
        nannies = []
        for pid in workers:
            try:
                parent = psutil.Process(pid).parent()
                if parent is not None and parent.pid != os.getpid():
                    nannies.append(parent.pid)
            except psutil.NoSuchProcess:
                pass
        return workers + nannies

    def address(self, n: int) -> str:
        return self.clusters[n].scheduler_address

    def close(self) -> None:
        import logging

        logging.getLogger("distributed").setLevel(logging.ERROR)  # no INFO lines of the shutdown
        for n in list(self.clusters):
            self.clients[n].close()
            self.clusters[n].close()


#: name -> (workers, extra CLI arguments or a Dask cluster size)
CONFIGS = {
    "local -j 1 (inline)": (1, ["-j", "1"], None),
    "local -j 1 (1 process)": (1, ["-j", "1", "--job-timeout", "1000000"], None),
    "local -j 2": (2, ["-j", "2"], None),
    "dask 1 worker": (1, [], 1),
    "dask 2 workers": (2, [], 2),
}


def run_batch(config: str, spec: Path, jobs: int, formats: list[str], clusters: Clusters | None, work: Path) -> dict:
    workers, extra, cluster = CONFIGS[config]
    out = Path(tempfile.mkdtemp(prefix="batch-", dir=work))
    args = [str(spec), "--sweep", f"tube.radius=4:6:{jobs}", "-d", str(out), "--force", *extra]
    for f in formats:
        args += ["-f", f]
    pids = []
    if cluster is not None:
        args += ["--scheduler", clusters.address(cluster)]
        pids = clusters.pids(cluster)
    try:
        return metrics(run_command(args, out, extra_pids=pids), workers)
    finally:
        shutil.rmtree(out, ignore_errors=True)


def _median(runs: list[dict], key: str):
    values = [r[key] for r in runs if r.get(key) is not None]
    return round(statistics.median(values), 4) if values else None


def summarise(runs: list[dict]) -> dict:
    if not runs:
        return {"runs": 0}
    keys = [
        "jobs_per_s",
        "steady_jobs_per_s",
        "batch_jobs_per_s",
        "wall_s",
        "planned_s",
        "batch_s",
        "startup_s",
        "mean_job_s",
        "overhead_steady_s",
        "overhead_batch_s",
        "overhead_total_s",
    ]
    out = {"runs": len(runs), **{k: _median(runs, k) for k in keys}}
    rates = [r["jobs_per_s"] for r in runs if r.get("jobs_per_s") is not None]
    out["jobs_per_s_range"] = [min(rates), max(rates)] if rates else None
    out["peak_total_mb"] = max((r["memory"]["total_mb"] for r in runs), default=None)
    out["other_cores"] = _median([r["conditions"] for r in runs], "other_cores")
    out["all_ok"] = all(r["returncode"] == 0 and r["ok"] == r["jobs"] for r in runs)
    return out


def efficiency(one: list[dict], two: list[dict], key: str, keep=lambda _run: True) -> dict:
    """jobs/s at 2 / (2 x jobs/s at 1): paired round by round (the median of those), and of the
    medians; only the rounds where both runs pass ``keep``."""
    both = [(a, b) for a, b in zip(one, two) if keep(a) and keep(b)]
    pairs = [b[key] / (2 * a[key]) for a, b in both if a.get(key) and b.get(key)]
    m1, m2 = _median([a for a, _ in both], key), _median([b for _, b in both], key)
    return {
        "paired_median": round(statistics.median(pairs), 3) if pairs else None,
        "of_medians": round(m2 / (2 * m1), 3) if m1 and m2 else None,
        "pairs": [round(p, 3) for p in pairs],
    }


def _log_run(log, label: str, config: str, result: dict) -> None:
    nan = float("nan")
    status = "" if result["returncode"] == 0 else f"  EXIT {result['returncode']}"
    log(
        f"  {label:17} {config:24} {result['jobs']:4} jobs {result['wall_s']:6.1f} s  "
        f"{result.get('jobs_per_s', nan):.3g} jobs/s end-to-end, {result.get('steady_jobs_per_s', nan):.3g} steady; "
        f"overhead/job {result.get('overhead_steady_s', nan):.3f} s steady, {result.get('overhead_batch_s', nan):.3f} s "
        f"batch; others used {result['conditions']['other_cores']:.2f} cores{status}"
    )


def _warm(_=None) -> bool:
    """On a Dask worker: import what a job imports (pickled by value from this script)."""
    import tubecad.batch.dask_executor
    import tubecad.batch.jobs
    import tubecad.spec.build  # noqa: F401

    return True


def rounds(suites: dict, n_rounds: int, state: State, work: Path, log) -> None:
    """First a batch of the first suite on each fresh Dask cluster (cold: its workers import
    OCCT in their first jobs); then every suite's every configuration once per round, one
    after the other (side by side), the order reversed every other round. Each batch's
    numbers go into ``state`` as it ends; batches already there (an earlier, interrupted
    session) are not run again."""
    first = next(iter(suites))
    plan = [("cold", first, c) for c, (_, _, cluster) in CONFIGS.items() if cluster is not None]
    order = [(suite, config) for suite in suites for config in CONFIGS]
    for r in range(n_rounds):
        plan += [(r, suite, config) for suite, config in (order if r % 2 == 0 else order[::-1])]
    todo = [step for step in plan if state.key(*step) not in state.data["runs"]]
    if not todo:
        return
    clusters = None
    if any(CONFIGS[c][2] is not None for _, _, c in todo):
        clusters = Clusters(log=log)
        state.data.setdefault("dask_cluster_start_s", {str(n): t for n, t in clusters.start_s.items()})
        if all(step[0] != "cold" for step in todo):  # resumed after the cold batches: warm the new workers first
            for n in clusters.clients:
                clusters.clients[n].run(_warm)
            for config, (_, _, cluster) in CONFIGS.items():
                if cluster is not None:
                    run_batch(config, suites[first][0], 4, suites[first][2], clusters, work)
            log("  new Dask workers warmed up (a 4-job batch each, not recorded)")
    try:
        for phase, suite, config in todo:
            result = run_batch(config, *suites[suite], clusters, work)
            result["session"] = len(state.data["sessions"])
            state.data["runs"][state.key(phase, suite, config)] = result
            state.save()
            _log_run(log, f"cold {suite}" if phase == "cold" else f"round {phase + 1} {suite}", config, result)
    finally:
        if clusters is not None:
            clusters.close()


class State:
    """What the run has measured so far, in a file outside the project, so that a session
    stopped from outside (this shared machine has seen SIGTERM and SIGKILL to the benchmark's
    whole process tree) resumes with ``--resume`` instead of starting over."""

    def __init__(self, path: Path, params: dict, resume: bool) -> None:
        self.path = path
        if resume and path.is_file():
            self.data = json.loads(path.read_text())
            if self.data["params"] != params:
                raise SystemExit(f"{path} holds a run with other parameters {self.data['params']}; drop --resume")
        else:
            self.data = {"params": params, "runs": {}, "long": None, "sessions": []}
        self.data["sessions"].append(
            {
                "started": time.strftime("%Y-%m-%dT%H:%M:%S"),
                "ended": None,
                "ended_by": "still running or killed (SIGKILL)",
                "seconds": 0.0,
            }
        )
        self._t0 = time.perf_counter()
        self.save()

    @staticmethod
    def key(phase, suite: str, config: str) -> str:
        return f"{phase}|{suite}|{config}"

    def save(self, ended_by: str | None = None) -> None:
        session = self.data["sessions"][-1]
        session["seconds"] = round(time.perf_counter() - self._t0, 1)
        session["ended"] = time.strftime("%Y-%m-%dT%H:%M:%S")
        if ended_by:
            session["ended_by"] = ended_by
        tmp = self.path.with_name(self.path.name + ".tmp")
        tmp.write_text(json.dumps(self.data))
        os.replace(tmp, self.path)


# ---------------------------------------------------------------- the long sweep


def long_sweep(spec: Path, jobs: int, work: Path, limit_s: float, log) -> dict:
    """``jobs`` small tubes with -j 2 to completion (or the time limit), then a rerun (resume)."""
    out = work / f"sweep-{jobs}"
    shutil.rmtree(out, ignore_errors=True)
    args = [str(spec), "--sweep", f"tube.radius=4:6:{jobs}", "-d", str(out), "-j", "2"]
    log(f"  {jobs} jobs, -j 2, into {out} (stopped after {limit_s / 60:.0f} min)")
    raw = run_command(args, out, limit_s=limit_s)
    first = metrics(raw, 2)
    first["memory_series"] = raw["memory_series"]
    finishes = raw["finishes"]
    manifest = raw["manifest"] or {}
    entries = manifest.get("jobs", [])
    from tubecad.batch.manifest import file_hash  # light: hashlib and json

    mismatched = [
        e["name"]
        for e in entries
        if e["status"] == "ok" and any(file_hash(out / name) != h for name, h in e["hashes"].items())
    ]
    missing = [e["name"] for e in entries if e["status"] == "ok" and not all((out / f).is_file() for f in e["outputs"])]
    check = {
        "jobs_total": manifest.get("jobs_total"),
        "ok": manifest.get("ok"),
        "failed": manifest.get("failed"),
        "cancelled": manifest.get("cancelled"),
        "skipped": manifest.get("skipped"),
        "interrupted": manifest.get("interrupted"),
        "workers": manifest.get("workers"),
        "entries": len(entries),
        "unique_names": len({e["name"] for e in entries}),
        "attempts_over_1": sum(e.get("attempts", 1) > 1 for e in entries),
        "job_lines": len(finishes),
        "unique_job_lines": len({name for _, name, _ in finishes}),
        "files_missing": len(missing),
        "hash_mismatches": len(mismatched),
        "all_ok": manifest.get("ok") == jobs and manifest.get("jobs_total") == jobs and not missing and not mismatched,
    }
    # drift over the run: the own seconds and the finish rate, first tenth against last tenth
    by_name = {e["name"]: e.get("seconds") or 0.0 for e in entries}
    tenth = max(len(finishes) // 10, 2)
    drift = {}
    if len(finishes) >= 4 * tenth:
        head, tail = finishes[2 : 2 + tenth], finishes[-tenth:]
        drift = {
            "mean_job_s_first_tenth": round(statistics.fmean(by_name.get(n, 0.0) for _, n, _ in head), 4),
            "mean_job_s_last_tenth": round(statistics.fmean(by_name.get(n, 0.0) for _, n, _ in tail), 4),
            "jobs_per_s_first_tenth": round((len(head) - 1) / (head[-1][0] - head[0][0]), 4),
            "jobs_per_s_last_tenth": round((len(tail) - 1) / (tail[-1][0] - tail[0][0]), 4),
        }
    series = raw["memory_series"]
    if len(series) >= 3:
        running = [
            s for s in series if (first.get("first_finish_s") or 0) <= s["t"] <= (first.get("last_finish_s") or 0)
        ]
        running = running or series
        early, last = running[0], running[-1]  # while the workers run: after the first job, before the last
        drift["worker_rss_mb_early"] = early["children_mb"]
        drift["worker_rss_mb_end"] = last["children_mb"]
        drift["submitter_rss_mb_early"], drift["submitter_rss_mb_end"] = early["submitter_mb"], last["submitter_mb"]
        drift["series_t_early_end"] = [early["t"], last["t"]]
    log(
        f"  {first['jobs']} jobs in {first['wall_s']:.0f} s ({first['jobs_per_s']:.3g} jobs/s; steady "
        f"{first.get('steady_jobs_per_s', float('nan')):.3g}); peak RSS: tree {first['memory']['tree_mb']:.0f} MB, "
        f"submitter {first['memory']['submitter_mb']:.0f} MB, largest worker {first['memory']['largest_child_mb']:.0f} MB; "
        f"manifest ok {check['ok']}/{check['jobs_total']}{' STOPPED: ' + first['stopped'] if first.get('stopped') else ''}"
    )
    # the rerun: every job already built (if the first run finished), so only the resume check
    mtimes = {p.name: p.stat().st_mtime_ns for p in out.iterdir()}
    rerun_raw = run_command(args, out, interrupt_when_planned=not check["all_ok"])
    rerun = metrics(rerun_raw, 2)
    rewritten = sum(1 for p in out.iterdir() if p.name != "batch.json" and mtimes.get(p.name) != p.stat().st_mtime_ns)
    rm = rerun_raw["manifest"] or {}
    rerun_check = {
        "skipped": rm.get("skipped"),
        "ok": rm.get("ok"),
        "batch_s": rm.get("seconds"),
        "files_rewritten": rewritten,
        "first_line": next((line for line in rerun_raw["other_lines"] if line.startswith("building ")), None),
        "last_line": rerun_raw["other_lines"][-1] if rerun_raw["other_lines"] else None,
    }
    log(
        f"  rerun (resume): {rerun['wall_s']:.1f} s wall, {rerun['planned_s'] or float('nan'):.1f} s to its first line; "
        f"skipped {rerun_check['skipped']}, files rewritten {rewritten}"
    )
    rerun_check["in_process"] = resume_check_in_process(spec, jobs, out)
    log(f"  resume check in this process: {rerun_check['in_process']}")
    disk = sum(p.stat().st_size for p in out.iterdir())
    shutil.rmtree(out, ignore_errors=True)
    blocks = []  # per 50 jobs, in finish order: rate, own seconds, the rest of the machine's CPU meanwhile
    size = 50 if len(finishes) >= 200 else max(len(finishes) // 4, 2)
    for b in range(0, len(finishes) - size + 1, size):
        chunk = finishes[b : b + size]
        t_start = finishes[b - 1][0] if b else (first.get("startup_s") or 0.0)
        near = [p["other_cores_since_last"] for p in series if t_start <= p["t"] <= chunk[-1][0] + 10.0]
        blocks.append(
            {
                "jobs": [b + 1, b + len(chunk)],
                "t_end": round(chunk[-1][0], 1),
                "jobs_per_s": round(len(chunk) / max(chunk[-1][0] - t_start, 1e-9), 3),
                "mean_job_s": round(statistics.fmean(by_name.get(n, 0.0) for _, n, _ in chunk), 3),
                "other_cores": round(statistics.fmean(near), 2) if near else None,
            }
        )
    control = radius_control(spec, work)
    log(f"  radius control (-j 1, radii 4 and 6 alternating): mean job s {control['mean_job_s']}")
    return {
        "jobs": jobs,
        "run": first,
        "manifest_check": check,
        "drift": drift,
        "blocks": blocks,
        "radius_control": control,
        "disk_mb": round(disk / MB, 1),
        "rerun": {
            **{k: rerun[k] for k in ("wall_s", "planned_s", "returncode", "memory", "conditions")},
            **rerun_check,
        },
    }


def resume_check_in_process(spec: Path, jobs: int, out: Path) -> dict:
    """The rerun's resume check alone, timed in this process: plan the jobs, hash their specs,
    read the manifest and verify every recorded output's hash (what the command does before
    its first line)."""
    try:
        from tubecad.batch.jobs import parse_sweep, plan_jobs
        from tubecad.batch.manifest import read_manifest, spec_hash, up_to_date

        t0 = time.perf_counter()
        planned = plan_jobs([spec], [parse_sweep(f"tube.radius=4:6:{jobs}")], out, [])
        t1 = time.perf_counter()
        digests = [spec_hash(job) for job in planned]
        t2 = time.perf_counter()
        manifest = read_manifest(out)
        t3 = time.perf_counter()
        fresh = sum(up_to_date(manifest.get(job.name), job, d) for job, d in zip(planned, digests))
        t4 = time.perf_counter()
    except Exception as exc:  # the tree is being edited; record, do not fail the run
        return {"error": f"{type(exc).__name__}: {exc}"}
    return {
        "plan_s": round(t1 - t0, 3),
        "spec_hashes_s": round(t2 - t1, 3),
        "read_manifest_s": round(t3 - t2, 3),
        "verify_outputs_s": round(t4 - t3, 3),
        "total_s": round(t4 - t0, 3),
        "up_to_date": fresh,
    }


def radius_control(spec: Path, work: Path, pairs: int = 6) -> dict:
    """Does a job's own time depend on the radius the long sweep walks from 4 to 6? A -j 1
    batch with radii near 4 and near 6 alternating (so both see the same load)."""
    values = ",".join(f"{4.0 + 1e-3 * i},{6.0 - 1e-3 * i}" for i in range(pairs))
    out = Path(tempfile.mkdtemp(prefix="radius-", dir=work))
    try:
        raw = run_command([str(spec), "--sweep", f"tube.radius={values}", "-d", str(out), "--force", "-j", "1"], out)
    finally:
        shutil.rmtree(out, ignore_errors=True)
    entries = (raw["manifest"] or {}).get("jobs", [])
    by_radius = {"4": [], "6": []}
    for e in entries:
        r = e.get("sweep", {}).get("tube.radius")
        if r is not None and e.get("seconds") is not None:
            by_radius["4" if r < 5 else "6"].append(e["seconds"])
    return {
        "values": values,
        "seconds": by_radius,
        "returncode": raw["returncode"],
        "mean_job_s": {k: round(statistics.fmean(v), 3) if v else None for k, v in by_radius.items()},
        "conditions": raw["conditions"],
    }


# ---------------------------------------------------------------- machine, table, main


def _version(name: str) -> str | None:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(name)
    except PackageNotFoundError:
        return None


def watched_hashes() -> dict[str, str]:
    return {p: hashlib.sha256((ROOT / p).read_bytes()).hexdigest()[:16] for p in WATCHED if (ROOT / p).is_file()}


def machine() -> dict:
    model = None
    try:
        model = next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    except OSError:
        head = None
    return {
        "cpus": os.cpu_count(),
        "physical_cpus": psutil.cpu_count(logical=False),
        "cpu_model": model,
        "memory_gb": round(psutil.virtual_memory().total / 1024**3, 1),
        "platform": platform.platform(),
        "python": platform.python_version(),
        "tubecad": _version("tubecad"),
        "dask": _version("dask"),
        "distributed": _version("distributed"),
        "cadquery-ocp": _version("cadquery-ocp"),
        "psutil": _version("psutil"),
        "git_head": head,
        "note": "HEAD plus uncommitted edits in the working tree (being edited meanwhile); the measured "
        "files' hashes are in code_hashes",
    }


def _f(value, fmt: str) -> str:
    return "-" if value is None else format(value, fmt)


def table(result: dict) -> str:
    lines = []
    for suite, title in (("scaling", "small helix tube"), ("trivial", "trivial tube, -f brep")):
        s = result["suites"][suite]
        lines += [
            f"{suite}: {s['jobs']} jobs of the {title}; medians of {result['rounds']} rounds "
            f"(Dask cold = the first batch on fresh workers, 1 run)",
            "",
            "| executor | jobs/s end-to-end | jobs/s steady | wall s | start-up s | mean job s | overhead/job steady s | "
            "overhead/job batch s | overhead/job total s | peak MB | others' cores |",
            "|---|---|---|---|---|---|---|---|---|---|---|",
        ]
        rows = [(c, m) for c, m in s["summary"].items()] + [(f"{c} (cold)", m) for c, m in s["cold"].items()]
        for config, m in rows:
            lines.append(
                f"| {config} | {_f(m['jobs_per_s'], '.3g')} | {_f(m['steady_jobs_per_s'], '.3g')} | "
                f"{_f(m['wall_s'], '.1f')} | {_f(m['startup_s'], '.2f')} | {_f(m['mean_job_s'], '.3f')} | "
                f"{_f(m['overhead_steady_s'], '.3f')} | {_f(m['overhead_batch_s'], '.3f')} | "
                f"{_f(m['overhead_total_s'], '.3f')} | {_f(m['peak_total_mb'], '.0f')} | {_f(m['other_cores'], '.2f')} |"
            )
        lines += ["", "scaling efficiency (jobs/s at 2 / (2 x jobs/s at 1); paired by round, median):", ""]
        for name, e in s["efficiency"].items():
            if not e:
                continue
            lines.append(
                f"- {name}: end-to-end {_f(e['jobs_per_s']['paired_median'], '.2f')}, "
                f"steady {_f(e['steady_jobs_per_s']['paired_median'], '.2f')}"
            )
        for label, part in s.get("by_condition", {}).items():
            lines += ["", f"{label}: jobs/s end-to-end / steady (runs)", ""]
            lines += [
                f"- {c}: {_f(m.get('jobs_per_s'), '.3g')} / {_f(m.get('steady_jobs_per_s'), '.3g')} ({m['runs']})"
                for c, m in part["summary"].items()
            ]
            lines += [
                f"- efficiency {name}: {_f(e['jobs_per_s']['paired_median'], '.2f')} / "
                f"{_f(e['steady_jobs_per_s']['paired_median'], '.2f')} ({len(e['steady_jobs_per_s']['pairs'])} rounds)"
                for name, e in part["efficiency"].items()
            ]
        lines.append("")
    if "long" in result:
        g = result["long"]
        r, c, d = g["run"], g["manifest_check"], g["drift"]
        lines += [
            f"long sweep: {g['jobs']} small tubes, local -j 2"
            + (f" (STOPPED: {r['stopped']})" if r.get("stopped") else ""),
            "",
            f"- wall {r['wall_s']:.0f} s ({r['wall_s'] / 60:.1f} min), {r['jobs']} jobs, {r['jobs_per_s']:.3g} jobs/s "
            f"end-to-end, {_f(r.get('steady_jobs_per_s'), '.3g')} steady; mean job {r['mean_job_s']:.3f} s; "
            f"overhead/job steady {_f(r.get('overhead_steady_s'), '.3f')} s, batch {_f(r.get('overhead_batch_s'), '.3f')} s",
            f"- peak RSS: process tree {r['memory']['tree_mb']:.0f} MB (submitter {r['memory']['submitter_mb']:.0f} MB, "
            f"largest worker {r['memory']['largest_child_mb']:.0f} MB, children {r['memory']['children_sum_mb']:.0f} MB)",
            f"- memory early -> end: workers {d.get('worker_rss_mb_early')} -> {d.get('worker_rss_mb_end')} MB, "
            f"submitter {d.get('submitter_rss_mb_early')} -> {d.get('submitter_rss_mb_end')} MB",
            f"- first -> last tenth: job s {d.get('mean_job_s_first_tenth')} -> {d.get('mean_job_s_last_tenth')}, "
            f"jobs/s {d.get('jobs_per_s_first_tenth')} -> {d.get('jobs_per_s_last_tenth')}",
            f"- manifest: ok {c['ok']}/{c['jobs_total']}, failed {c['failed']}, retried {c['attempts_over_1']}, "
            f"files missing {c['files_missing']}, hash mismatches {c['hash_mismatches']}: {'OK' if c['all_ok'] else 'NOT OK'}",
            f"- rerun (resume): {g['rerun']['wall_s']:.1f} s wall ({_f(g['rerun']['planned_s'], '.1f')} s to its first "
            f"line), skipped {g['rerun']['skipped']}, files rewritten {g['rerun']['files_rewritten']}; the check alone "
            f"(in process): {g['rerun']['in_process']}",
            f"- radius control (-j 1, alternating): mean job s {g['radius_control']['mean_job_s']}",
            "- per 50 jobs (jobs/s, mean job s, others' cores): "
            + "; ".join(
                f"{b['jobs_per_s']:.2f} {b['mean_job_s']:.2f} {_f(b['other_cores'], '.2f')}" for b in g["blocks"]
            ),
            "",
        ]
    sessions = result.get("sessions") or [None]
    lines.append(
        f"Dask LocalCluster start-up: {result['dask_cluster_start_s']} s; run time {result['total_minutes']:.1f} min "
        f"in {len(sessions)} session{'s' * (len(sessions) > 1)}"
    )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick", action="store_true", help="a smoke run: 4 jobs per batch, 1 round, a 10-job long sweep"
    )
    parser.add_argument("--rounds", type=int, default=None, help="rounds of every configuration (default 3; quick 1)")
    parser.add_argument("--long-jobs", type=int, default=None, help="jobs of the long sweep (default 1000; quick 10)")
    parser.add_argument("--max-minutes", type=float, default=15.0, help="stop the long sweep after this long")
    parser.add_argument("--skip-long", action="store_true", help="no long sweep")
    parser.add_argument(
        "--resume",
        action="store_true",
        help="continue a run that was stopped (its state file), skipping the batches it measured",
    )
    parser.add_argument(
        "--state",
        type=Path,
        default=None,
        help="the state file (default: in the temporary folder, one for full runs, one for quick ones)",
    )
    parser.add_argument(
        "--output",
        type=Path,
        default=None,
        help=f"the JSON (default {RESULT.relative_to(ROOT)}; with --quick a file in the temporary folder)",
    )
    parser.add_argument(
        "--retable",
        type=Path,
        default=None,
        metavar="RESULT.json",
        help="measure nothing: recompute the summaries of RESULT.json from its raw runs, print the table",
    )
    args = parser.parse_args(argv)
    if args.retable:
        return retable(args.retable, args.output)
    quick = args.quick
    n_rounds = args.rounds or (1 if quick else 3)
    scaling_jobs, trivial_jobs = (4, 4) if quick else (24, 40)
    long_jobs = 0 if args.skip_long else args.long_jobs or (10 if quick else 1000)
    log = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    tmp_root = Path(tempfile.gettempdir())
    output = args.output or (tmp_root / "tubecad-batch-scaling.quick.json" if quick else RESULT)
    params = {
        "quick": quick,
        "rounds": n_rounds,
        "scaling_jobs": scaling_jobs,
        "trivial_jobs": trivial_jobs,
        "long_jobs": long_jobs,
        "max_minutes": args.max_minutes,
    }
    state = State(
        args.state or tmp_root / f"tubecad-batch-scaling-state{'.quick' if quick else ''}.json", params, args.resume
    )

    def on_signal(signum, _frame) -> None:  # recorded, the command stopped cleanly, then this process ends as asked
        state.save(ended_by=f"signal {signum} (from outside the benchmark)")
        for proc in RUNNING:
            with contextlib.suppress(OSError, subprocess.TimeoutExpired):
                proc.send_signal(signal.SIGINT)
                proc.wait(15)
        signal.signal(signum, signal.SIG_DFL)
        os.kill(os.getpid(), signum)

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGHUP, on_signal)
    state.data.setdefault("machine", machine())
    state.data.setdefault("code_before", watched_hashes())
    work = Path(tempfile.mkdtemp(prefix="tubecad-batch-bench-"))
    (work / "small.toml").write_text(SMALL)
    (work / "trivial.toml").write_text(TRIVIAL)
    suites = {
        "scaling": (work / "small.toml", scaling_jobs, []),
        "trivial": (work / "trivial.toml", trivial_jobs, ["brep"]),
    }
    done = len(state.data["runs"])
    log(
        f"tubecad batch scaling ({'quick' if quick else 'full'}): {n_rounds} rounds, work folder {work}, state "
        f"{state.path}" + (f" (resumed: {done} batches measured before)" if args.resume else "")
    )
    try:
        rounds(suites, n_rounds, state, work, log)
        if long_jobs and state.data["long"] is None:
            log(f"long sweep ({long_jobs} jobs)")
            state.data["long"] = long_sweep(work / "small.toml", long_jobs, work, args.max_minutes * 60.0, log)
            state.data["long"]["session"] = len(state.data["sessions"])
            state.save()
    except KeyboardInterrupt:
        state.save(ended_by="Ctrl-C")
        log(f"interrupted; continue with --resume ({state.path})")
        return 130
    finally:
        shutil.rmtree(work, ignore_errors=True)
    state.save(ended_by="finished")
    result = assemble(state.data, suites)
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(json.dumps(result, indent=1) + "\n")
    print(table(result))
    print(f"\nwritten {output}")
    state.path.unlink(missing_ok=True)
    return 0


#: the rounds split by what the rest of the machine used meanwhile (other_cores of the run)
CONDITIONS = {
    "quiet (others < 0.3 cores)": lambda run: run["conditions"]["other_cores"] < 0.3,
    "loaded (others >= 0.5 cores)": lambda run: run["conditions"]["other_cores"] >= 0.5,
}


def summaries(runs: dict[str, list[dict]], cold: dict[str, dict]) -> dict:
    """Medians per configuration, the scaling efficiencies, and both again per condition."""
    pairs = {
        "local (inline -j 1 vs -j 2)": (runs["local -j 1 (inline)"], runs["local -j 2"]),
        "local (1 process vs -j 2)": (runs["local -j 1 (1 process)"], runs["local -j 2"]),
        "dask warm (1 vs 2 workers)": (runs["dask 1 worker"], runs["dask 2 workers"]),
    }
    cold_pairs = dict(pairs)
    if "dask 1 worker" in cold and "dask 2 workers" in cold:
        cold_pairs["dask cold (1 vs 2 workers)"] = ([cold["dask 1 worker"]], [cold["dask 2 workers"]])
    keys = ("jobs_per_s", "steady_jobs_per_s")
    return {
        "summary": {c: summarise(r) for c, r in runs.items()},
        "cold": {c: {**summarise([r]), "runs": 1} for c, r in cold.items()},
        "efficiency": {name: {k: efficiency(a, b, k) for k in keys} for name, (a, b) in cold_pairs.items()},
        "by_condition": {
            label: {
                "summary": {c: summarise([r for r in rs if keep(r)]) for c, rs in runs.items()},
                "efficiency": {name: {k: efficiency(a, b, k, keep) for k in keys} for name, (a, b) in pairs.items()},
            }
            for label, keep in CONDITIONS.items()
        },
        "raw": runs,
        "raw_cold": cold,
    }


def retable(path: Path, output: Path | None) -> int:
    """Recompute the summaries of a written result from its raw runs; print the table."""
    result = json.loads(path.read_text())
    for suite in result["suites"].values():
        suite.update(summaries(suite["raw"], suite["raw_cold"]))
    result["summaries_recomputed"] = (
        f"{time.strftime('%Y-%m-%dT%H:%M:%S')}: summaries, efficiencies and by_condition "
        f"recomputed from the raw runs (--retable); the measurements are unchanged"
    )
    (output or path).write_text(json.dumps(result, indent=1) + "\n")
    print(table(result))
    print(f"\nwritten {output or path}")
    return 0


def assemble(data: dict, suites: dict) -> dict:
    """The published JSON from the state: per suite and configuration the runs, their medians and the efficiencies."""
    params = data["params"]
    result = {
        "benchmark": "batch_scaling",
        "quick": params["quick"],
        "machine": data["machine"],
        "rounds": params["rounds"],
        "method": {
            "side_by_side": "the machine is shared (a CI run and another engineer's tests used the CPU "
            "meanwhile): every configuration runs once per round, one after the other, order "
            "reversed every other round; medians over rounds, efficiencies paired within a "
            "round; conditions per run (other_cores = CPU the rest of the machine used "
            "meanwhile); by_condition splits the rounds into quiet and loaded ones",
            "command": "python -m tubecad.cli.console build SPEC --sweep tube.radius=4:6:N -d DIR --force",
            "local -j 1": "tubecad runs -j 1 jobs in the command's own process (InlineExecutor); "
            "'-j 1 --job-timeout 1e6' forces the pool of one spawned worker",
            "dask": "distributed.LocalCluster(n_workers=1|2, threads_per_worker=1, processes=True, "
            "host='127.0.0.1') started in the benchmark process (its scheduler runs there), "
            "passed with --scheduler; workers persist across batches; 'cold' = the first batch "
            "on fresh workers",
            "definitions": __doc__.split("Throughput is given two ways:", 1)[1].strip(),
            "memory": "RSS of the command's process tree (submitter + its workers) and, for Dask, of the "
            "worker processes and nannies, polled every 0.5 s; peaks",
            "sessions": "the run may span several sessions (--resume) when something outside stopped it; "
            "each batch records its session; see 'sessions'",
        },
        "specs": {"small": SMALL, "trivial": TRIVIAL, "trivial_formats": ["brep"]},
        "dask_cluster_start_s": data.get("dask_cluster_start_s"),
        "suites": {},
    }
    runs_by = {}
    for key, value in data["runs"].items():
        phase, suite, config = key.split("|")
        runs_by.setdefault((suite, "cold" if phase == "cold" else "warm", config), []).append((phase, value))
    for suite, (_, jobs, formats) in suites.items():
        runs = {
            c: [v for _, v in sorted(runs_by.get((suite, "warm", c), []), key=lambda pv: int(pv[0]))] for c in CONFIGS
        }
        cold = {c: runs_by[(suite, "cold", c)][0][1] for c in CONFIGS if (suite, "cold", c) in runs_by}
        result["suites"][suite] = {"jobs": jobs, "formats": formats or ["step"], **summaries(runs, cold)}
    if data.get("long"):
        result["long"] = data["long"]
    before, after = data["code_before"], watched_hashes()
    result["code_hashes"] = {
        "before": before,
        "after": after,
        "changed_during_run": before != after,
        "changed": [f for f in before if before[f] != after.get(f)],
        "git_head_end": machine()["git_head"],
    }
    result["sessions"] = data["sessions"]
    result["total_minutes"] = round(sum(x["seconds"] for x in data["sessions"]) / 60.0, 2)
    return result


if __name__ == "__main__":
    sys.exit(main())
