"""Benchmark: the half-space part of a 15-speed friction curve, this code against a baseline.

Issue 27's second performance case: the VHS and hybrid solves of μ(v) on the Table 2 asphalt
(15 speeds 1e-3 … 1e4 mm/s × 5 loads × 8 realizations, n = 8192: 600 solves per model) with
the hybrid's law given, so that no FEM runs. The law comes from a results file written by
``bench_speed_sweep.py --save``. The same model stage runs from an empty cache under this
tree and under a baseline commit (checked out in a temporary ``git worktree``, run in a
subprocess with its ``src`` first on ``PYTHONPATH``), one after the other in one run; the
answers are compared point by point::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_speed_sweep.py --save /tmp/sweep15.nc
    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_halfspace_sweep.py \\
        --law /tmp/sweep15.nc --baseline 037705f --output benchmarks/halfspace_sweep.md
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_speed_sweep import CONFIG  # noqa: E402


def measure(law_path: Path, workers: int) -> dict:
    """Run the model stage of the 15-speed curve with the given law into an empty cache."""
    import xarray as xr

    import rubbercontact as rc

    law = xr.load_dataset(law_path)
    with tempfile.TemporaryDirectory() as tmp:
        cfg = {**CONFIG, "execution": {"workers": workers, "cache": str(Path(tmp) / "c")},
               "output": {"directory": str(Path(tmp) / "out")}}
        cpu0, t0 = time.process_time(), time.perf_counter()
        ds = rc.pipeline.run(cfg, law=law, progress=False)
        wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
    timings = json.loads(ds.attrs["timings_s"])
    model_cpu = json.loads(ds.attrs["model_cpu_time_s"])
    return {"wall_s": wall, "process_cpu_s": cpu, "models_wall_s": timings["models"],
            "task_time_s": {m: model_cpu[m] for m in ("vhs", "hybrid")},
            "friction": ds["friction"].sel(model=["vhs", "hybrid"]).values.tolist(),
            "contact_fraction": ds["contact_fraction"].sel(model=["vhs", "hybrid"])
            .values.tolist()}


def run_baseline(commit: str, law_path: Path, workers: int) -> dict:
    """:func:`measure` under ``commit``, in a temporary worktree and a subprocess."""
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree),
                        commit], check=True, capture_output=True)
        try:
            out = Path(tmp) / "res.json"
            env = {**os.environ, "PYTHONPATH": str(tree / "src")}
            subprocess.run([sys.executable, __file__, "--law", str(law_path), "--workers",
                            str(workers), "--measure-only", str(out)], check=True, env=env)
            return json.loads(out.read_text())
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                            str(tree)], check=False, capture_output=True)


def markdown(new: dict, old: dict | None, head: str, baseline: str | None) -> str:
    rows = [("this tree", new)] + ([(f"baseline {baseline}", old)] if old else [])
    lines = ["# Half-space part of a 15-speed friction curve "
             "(`benchmarks/bench_halfspace_sweep.py`)", "", head, "",
             "Table 2 asphalt, 15 speeds 1e-3 … 1e4 mm/s × 5 loads 0.05 … 0.4 MPa × "
             "8 realizations, n = 8192 (the hybrid's low-slope solve on its own grid where "
             "the code has one: 4096 by rubbercontact.hybrid.grid): 600 VHS and 600 hybrid "
             "solves, the hybrid's law read "
             "from a results file (no FEM), empty cache. Task time: the solves' own wall "
             "time summed over tasks (one thread each); process CPU: the whole run's CPU "
             "time (with one worker the tasks run in this process). The two codes run one "
             "after the other: compare them at similar load.", "",
             "| code | VHS tasks | hybrid tasks | half-space part (sum) | model stage wall | "
             "process CPU |", "|---|---:|---:|---:|---:|---:|"]
    for name, r in rows:
        t = r["task_time_s"]
        lines.append(f"| {name} | {t['vhs']:.1f} s | {t['hybrid']:.1f} s | "
                     f"{t['vhs'] + t['hybrid']:.1f} s | {r['models_wall_s']:.1f} s | "
                     f"{r['process_cpu_s']:.1f} s |")
    if old:
        mu_n, mu_o = np.asarray(new["friction"]), np.asarray(old["friction"])
        a_n, a_o = np.asarray(new["contact_fraction"]), np.asarray(old["contact_fraction"])
        ok = np.isfinite(mu_n) & np.isfinite(mu_o)
        tn = sum(new["task_time_s"].values())
        to = sum(old["task_time_s"].values())
        lines += ["", f"Speed-up of the half-space part: {to / tn:.1f}× in task time, "
                  f"{old['models_wall_s'] / new['models_wall_s']:.1f}× in model-stage wall "
                  f"(with the result cache's writes), "
                  f"{old['process_cpu_s'] / new['process_cpu_s']:.1f}× in process CPU (the "
                  f"least sensitive to the machine's load). Largest difference "
                  f"between the two codes over the {int(ok.sum())} points: μ "
                  f"{np.max(np.abs(mu_n[ok] - mu_o[ok]) / np.abs(mu_o[ok])):.1e} (relative), "
                  f"contact fraction {np.max(np.abs(a_n[ok] - a_o[ok])):.1e} (absolute)."]
        lines += ["", "Per model (model axis: vhs, hybrid), over the points both codes solved: "
                  "largest and median relative difference of μ and of the contact "
                  "fraction A, and the largest absolute difference of μ:", "",
                  "| model | max \\|Δμ\\|/μ | median \\|Δμ\\|/μ | max \\|Δμ\\| | "
                  "max \\|ΔA\\|/A | median \\|ΔA\\|/A |", "|---|---:|---:|---:|---:|---:|"]
        for i, name in enumerate(("vhs", "hybrid")):
            mn, mo, an, ao = mu_n[i], mu_o[i], a_n[i], a_o[i]
            k = np.isfinite(mn) & np.isfinite(mo)
            dmu = np.abs(mn[k] - mo[k])
            rmu, ra = dmu / np.abs(mo[k]), np.abs(an[k] - ao[k]) / np.abs(ao[k])
            lines.append(f"| {name} | {rmu.max():.1e} | {np.median(rmu):.1e} | "
                         f"{dmu.max():.1e} | {ra.max():.1e} | {np.median(ra):.1e} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--law", type=Path, required=True,
                    help="results file with the law (bench_speed_sweep.py --save)")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--baseline", help="commit to measure side by side")
    ap.add_argument("--output", type=Path)
    ap.add_argument("--save-json", type=Path, help="write both runs' figures and answers")
    ap.add_argument("--measure-only", type=Path, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.measure_only:
        args.measure_only.write_text(json.dumps(measure(args.law, args.workers)))
        return
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True, check=False).stdout.strip() or "?"
    load0 = os.getloadavg()[0]
    new = measure(args.law, args.workers)
    old = run_baseline(args.baseline, args.law, args.workers) if args.baseline else None
    head = (f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, commit {commit}, "
            f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
            f"{args.workers} worker(s), one thread each; load average {load0:.1f} at the "
            f"start, {os.getloadavg()[0]:.1f} at the end.")
    if args.save_json:
        args.save_json.write_text(json.dumps({"new": new, "old": old, "head": head}))
    text = markdown(new, old, head, args.baseline)
    print(text)
    if args.output:
        args.output.write_text(text)


if __name__ == "__main__":
    main()
