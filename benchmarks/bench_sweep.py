"""Benchmark of the sweep executor: speed-up 1 vs 2 workers, per-task overhead, memory.

Usage::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_sweep.py            # toy kernel
    .venv/bin/python benchmarks/bench_sweep.py --task rubbercontact.hybrid.tasks:fem_task \\
        --kwargs '{"surface": {...}, "material": {...}, "velocity": 10, "mean_pressure": 0.5}'

Prints a Markdown report (machine, date, commit, figures) on stdout; the figures
quoted in ``benchmarks/sweep.md`` and ``docs/scaling.md`` come from it.

What is measured
----------------
* **startup**: wall time of ``run_sweep`` with one trivial task (starting and
  stopping the managed ``LocalCluster``), 1 and 2 workers.
* **speed-up**: ``n`` CPU-bound tasks of ≈1 s (toy kernel with deterministic FFT
  work, or ``--task``) on a running local cluster (reached by its address) with
  1 and with 2 worker processes; speed-up = wall(1) / wall(2), also with the
  startup of a managed cluster added.
* **overhead per task**: ``m`` trivial tasks (no work) per executor mode, with
  and without the cache, on an already running cluster: wall / m − mean task time.
  "cores used" = Σ task CPU time / wall and "tasks in flight" = Σ task wall
  time / wall tell apart what the executor does (keep every worker busy) from
  what a shared machine gives (CPU contention).
* **memory per task**: peak of Python/numpy allocations inside one task
  (tracemalloc), result size in memory and on disk (cache entry), and the RSS of
  an idle worker process.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import tracemalloc

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, run_sweep  # noqa: E402
from rubbercontact.sweep.tasks import resolve_function  # noqa: E402

TOY = "rubbercontact.sweep.examples:toy_kernel"


def timed_toy(**kwargs):
    """The toy kernel, with the CPU time of the task process in ``attrs["cpu_s"]``.

    On a shared machine the wall time of a task grows with other people's load; its
    CPU time does not, so sum(cpu) / wall tells how many cores the sweep really had.
    """
    from rubbercontact.sweep.examples import toy_kernel

    t0 = time.process_time()
    ds = toy_kernel(**kwargs)
    ds.attrs["cpu_s"] = time.process_time() - t0
    return ds


def _machine() -> dict:
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            cpu = next(line.split(":", 1)[1].strip() for line in fh
                       if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    import dask
    import distributed

    return {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),  # noqa: UP017
            "cpu": cpu, "cores": os.cpu_count(), "load_avg": os.getloadavg(),
            "python": platform.python_version(), "dask": dask.__version__,
            "distributed": distributed.__version__, "commit": commit}


def _timed(tasks, **kw) -> tuple[float, object]:
    t0 = time.perf_counter()
    res = run_sweep(tasks, progress=False, **kw)
    return time.perf_counter() - t0, res


def _calibrate(target: float) -> int:
    """Iterations of toy-kernel work that take ≈ target CPU seconds."""
    from rubbercontact.sweep.examples import toy_kernel

    toy_kernel(1.0, 1.0, work=50)  # warm-up: imports, FFT plans
    # CPU time, not wall time: on a shared machine the wall time depends on other users.
    t0 = time.process_time()
    toy_kernel(1.0, 1.0, work=500)
    per_iter = (time.process_time() - t0) / 500
    return max(1, int(round(target / per_iter)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default=TOY, help="task function 'module:function'")
    parser.add_argument("--kwargs", default=None, help="JSON kwargs of --task (one task; "
                        "each copy gets a distinct 'velocity' offset when it has one)")
    parser.add_argument("--seconds", type=float, default=1.0, help="toy task duration [s]")
    parser.add_argument("-n", type=int, default=8, help="tasks in the speed-up sweep")
    parser.add_argument("-m", type=int, default=200, help="trivial tasks for the overhead")
    parser.add_argument("--repeat", type=int, default=2, help="speed-up repetitions")
    args = parser.parse_args()

    info = _machine()
    out: dict = {"machine": info}
    load_before = os.getloadavg()[0]

    # -- tasks ------------------------------------------------------------------------
    if args.task == TOY and args.kwargs is None:
        work = _calibrate(args.seconds)
        # Imported by the workers as module "bench_sweep" (spawned workers inherit sys.path).
        heavy = [Task("bench_sweep:timed_toy",
                      {"velocity": 10.0 + i, "pressure": 0.5, "work": work},
                      label=f"toy {i}") for i in range(args.n)]
        out["task"] = f"toy_kernel, work={work} FFT iterations (~{args.seconds} s)"
    else:
        base = json.loads(args.kwargs or "{}")
        heavy = []
        for i in range(args.n):
            kw = dict(base)
            if "velocity" in kw:
                kw["velocity"] = float(kw["velocity"]) * (1 + 1e-9 * i)  # distinct keys
            heavy.append(Task(args.task, kw, label=f"task {i}"))
        out["task"] = args.task
    resolve_function(args.task)
    trivial = [Task(TOY, {"velocity": 1.0 + i, "pressure": 0.5}) for i in range(args.m)]
    one = [Task(TOY, {"velocity": 0.5, "pressure": 0.5})]

    # -- startup of a managed local cluster (start + one trivial task + shutdown) -------
    startup = {"sync": min(_timed(one, executor=ExecutorConfig(workers=1))[0]
                           for _ in range(2))}
    for k in (1, 2):
        startup[f"local-{k}"] = min(
            _timed(one, executor=ExecutorConfig(workers=k, synchronous=False))[0]
            for _ in range(2))
    out["startup_s"] = startup

    # The rest runs on clusters started once and reached by address, so that the figures
    # exclude startup (as for a long sweep) instead of subtracting a noisy estimate.
    import dask
    from distributed import LocalCluster

    from rubbercontact.sweep.executor import THREAD_ENV

    with dask.config.set({"distributed.nanny.pre-spawn-environ": THREAD_ENV}):
        clusters = {k: LocalCluster(n_workers=k, threads_per_worker=1, dashboard_address=None,
                                    silence_logs=40) for k in (1, 2)}
    configs = {"sync": ExecutorConfig(workers=1),
               "local-1": ExecutorConfig(scheduler=clusters[1].scheduler_address),
               "local-2": ExecutorConfig(scheduler=clusters[2].scheduler_address)}

    # -- speed-up ---------------------------------------------------------------------
    speed: dict = {}
    for _ in range(args.repeat):  # alternate, keep the best: other users' load varies
        for name in ("local-1", "local-2"):
            wall, res = _timed(heavy, executor=configs[name])
            assert res.ok, res.summary()
            cpu = sum(float(ds.attrs.get("cpu_s", np.nan)) for ds in res.results)
            if name not in speed or wall < speed[name]["wall_s"]:
                speed[name] = {"wall_s": wall, "with_startup_s": wall + startup[name],
                               "mean_task_s": sum(res.task_times) / len(res.task_times),
                               "cpu_s": cpu, "cores_used": cpu / wall,
                               # average number of tasks running at once: shows that the
                               # executor keeps every worker busy, whatever the load
                               "in_flight": sum(res.task_times) / wall}
    speed["speedup"] = speed["local-1"]["wall_s"] / speed["local-2"]["wall_s"]
    speed["speedup_with_startup"] = (speed["local-1"]["with_startup_s"]
                                     / speed["local-2"]["with_startup_s"])
    out["speedup"] = speed

    # -- overhead per task ------------------------------------------------------------
    overhead = {}
    for name, cfg in configs.items():
        for cached in (False, True):
            with tempfile.TemporaryDirectory() as d:
                cache = ResultCache(d) if cached else None
                wall, res = _timed(trivial, executor=cfg, cache=cache)
                kernel = sum(res.task_times) / len(res.task_times)
                per = wall / len(trivial) - kernel
                overhead[f"{name}{' +cache' if cached else ''}"] = {
                    "per_task_ms": 1e3 * per, "kernel_ms": 1e3 * kernel}
                if cached and name == "sync":
                    wall2, res2 = _timed(trivial, executor=cfg, cache=cache)
                    assert res2.n_cached == len(trivial)
                    overhead["cache hit (read+verify)"] = {
                        "per_task_ms": 1e3 * wall2 / len(trivial), "kernel_ms": 0.0}
    out["overhead"] = overhead
    for c in clusters.values():
        c.close()

    # -- memory -----------------------------------------------------------------------
    func = resolve_function(heavy[0].function)
    tracemalloc.start()
    ds = func(**heavy[0].kwargs)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    with tempfile.TemporaryDirectory() as d:
        cache = ResultCache(d)
        path = cache.store(heavy[0].key(), heavy[0], ds, 0.0)
        entry_bytes = path.stat().st_size
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None,
                      silence_logs=40) as cluster, Client(cluster) as client:
        rss = list(client.run(lambda: __import__("psutil").Process().memory_info().rss)
                   .values())[0]
    out["memory"] = {"task_peak_alloc_MB": peak / 1e6, "result_nbytes": int(ds.nbytes),
                     "cache_entry_bytes": entry_bytes, "idle_worker_rss_MB": rss / 1e6}

    info["load_avg_1min_before_after"] = (round(load_before, 2), round(os.getloadavg()[0], 2))
    # -- report -----------------------------------------------------------------------
    print(f"# bench_sweep: {out['task']}\n")
    print("| machine | |\n|---|---|")
    for k, v in info.items():
        print(f"| {k} | {v} |")
    print("\n| startup (1 trivial task) | s |\n|---|---|")
    for k, v in startup.items():
        print(f"| {k} | {v:.2f} |")
    print(f"\n| speed-up, {args.n} tasks (best of {args.repeat}) | wall s (cluster up) | "
          f"+ startup s | mean task wall s | task CPU s (sum) | cores used | tasks in flight |")
    print("|---|---|---|---|---|---|---|")
    for k in ("local-1", "local-2"):
        s = speed[k]
        print(f"| {k} | {s['wall_s']:.2f} | {s['with_startup_s']:.2f} | "
              f"{s['mean_task_s']:.3f} | {s['cpu_s']:.2f} | {s['cores_used']:.2f} | "
              f"{s['in_flight']:.2f} |")
    print(f"\nspeed-up 2 vs 1 workers: {speed['speedup']:.2f}× (cluster up), "
          f"{speed['speedup_with_startup']:.2f}× (including startup)\n")
    print(f"| overhead, {args.m} trivial tasks | per task ms | kernel ms |\n|---|---|---|")
    for k, v in overhead.items():
        print(f"| {k} | {v['per_task_ms']:.2f} | {v['kernel_ms']:.2f} |")
    print("\n| memory | |\n|---|---|")
    for k, v in out["memory"].items():
        print(f"| {k} | {v:.1f} |" if isinstance(v, float) else f"| {k} | {v} |")
    print("\n```json\n" + json.dumps(out, indent=1, default=str) + "\n```")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
