"""Does the finite-strain viscoelastic model explain FEM < VHS? Simo against Reese–Govindjee.

Our FEM's default (Simo-type: stress-like internal variables driven by the equilibrium
stress) and the paper's model (Reese & Govindjee 1998: multiplicative split per branch)
agree at small strain and differ at large strain. Three parts:

1. the paper's high-slope wave alone (0.0625 mm, m2 = 1.33) at 0.5/1/2/4 MPa, 10 mm/s,
   30 x 23 elements (friction within 0.6 % of 120 x 90 with the Simo model): Simo at one
   element of travel per step (second order, converged), RG at 120 and 240 steps per
   period with the first-order Richardson limit 2 μ(240) − μ(120); VHS alongside;
2. the section 3 surface (one realization, seed 2021) at 0.15/0.35/0.8 MPa, 10 and
   50 mm/s: the full pipeline (VHS, hybrid, windowed hybrid, full FEM) once with each
   model; law at 30 x 23, full FEM at 64 x 48, 240 and 256 steps per period; the RG full
   FEM again at 512 steps per period (0.15 and 0.35 MPa) for its first-order dt limit;
3. the AC-8 asphalt (paper §4; 3 realizations, n = 8192) at 10 and 50 mm/s: hybrid and
   windowed hybrid with each model's law (30 x 23, 240 steps per period), VHS alongside.

Every solve is cached (``--cache``), so the script resumes after a kill. About 2.5 h on
two cores with an empty cache (the RG runs dominate: ~4x the cost per Newton iteration
of the Simo model and first order in dt)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies material_model \
        --report docs/validation/material_model.md
"""

from __future__ import annotations

import argparse
import json
import subprocess
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.config import load_config
from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, run_sweep

from ._rows import publish

DESCRIPTION = ("Does the finite-strain viscoelastic model "
               "explain FEM < VHS? Simo against Reese–Govindjee.")

ROOT = Path(__file__).resolve().parents[1]
MODELS = ("simo", "reese-govindjee")
HS_PRESSURES = (0.5, 1.0, 2.0, 4.0)
S3_PRESSURES = [0.15, 0.35, 0.8]
S3_VELOCITIES = (10.0, 50.0)
RG_STEPS = (120, 240)


def first_order_limit(coarse: float, fine: float) -> float:
    """Richardson limit of a first-order (in dt) result from dt and dt/2: 2 fine − coarse."""
    return 2 * fine - coarse


def _hs_tasks() -> list[Task]:
    hs = rc.roughness.high_slope_wave().as_dict()
    mat = rc.materials.sbr().as_dict()
    tasks = []
    for p in HS_PRESSURES:
        base = {"surface": hs, "material": mat, "velocity": 10.0, "mean_pressure": p,
                "mesh": [30, 23], "periods": 4}
        tasks.append(Task("rubbercontact.hybrid.tasks:fem_task", base,
                          label=f"simo p={p}"))
        for spp in RG_STEPS:
            tasks.append(Task("rubbercontact.hybrid.tasks:fem_task",
                              {**base, "steps_per_period": spp,
                               "viscous_model": "reese-govindjee"},
                              label=f"rg p={p} spp={spp}"))
    return tasks


def _section3_config(model: str, cache: Path, outdir: Path, workers: int,
                     full_steps: int = 256, pressures=None, models=None):
    cfg = load_config(ROOT / "examples" / "section3.toml")
    data = cfg.model_dump(mode="json", exclude_none=True)
    data.update(realizations=1, velocities=list(S3_VELOCITIES),
                models=models or ["vhs", "hybrid", "hybrid-windowed", "fem"])
    data["loads"] = {"pressures": pressures or S3_PRESSURES}
    data["fem"].update(mesh=[30, 23], steps_per_period=240, full_mesh=[64, 48],
                       full_grading=1.0, full_steps_per_period=full_steps, periods=3,
                       viscous_model=model)
    data["law"] = {"pressures": [0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 4.0, 6.0]}
    data["execution"] = {"workers": workers, "cache": str(cache)}
    data["output"] = {"directory": str(outdir / f"{model}-{full_steps}"), "overwrite": True}
    return rc.config.parse_config(data, source=f"material model study ({model})")


def _asphalt_config(model: str, cache: Path, workers: int):
    cfg = load_config(ROOT / "examples" / "asphalt.toml")
    data = cfg.model_dump(mode="json", exclude_none=True)
    data.update(realizations=3)
    data["halfspace"]["n"] = 8192
    data["fem"].update(mesh=[30, 23], steps_per_period=240, periods=3, viscous_model=model)
    data["law"] = {"pressures": [0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 4.0, 6.0]}
    data["execution"] = {"workers": workers, "cache": str(cache)}
    return rc.config.parse_config(data, source=f"material model study, asphalt ({model})")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--output", type=Path, default=ROOT / "docs" / "validation" /
                    "material_model")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--report", type=Path)
    ap.add_argument("--skip-section3", action="store_true")
    ap.add_argument("--skip-asphalt", action="store_true")
    args = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    lines = ["# Finite-strain model: Simo against Reese–Govindjee", "",
             "Generated by `studies/material_model.py` "
             f"({datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}). SBR (Table 1).", ""]

    # -- 1. high-slope wave alone ----------------------------------------------------
    hs_tasks = _hs_tasks()
    res = run_sweep(hs_tasks, cache=ResultCache(args.cache),
                    executor=ExecutorConfig(workers=args.workers), progress="log").results
    out = {t.label: r for t, r in zip(hs_tasks, res, strict=True)}
    hs = rc.roughness.high_slope_wave()
    lines += ["## High-slope wave alone (0.0625 mm, m2 = 1.33), 30 x 23", "",
              "RG is first order in dt: its limit is 2 μ(240) − μ(120) (same for A).", "",
              "| p̄ [MPa] | VHS μ | VHS A | Simo μ | Simo A | RG μ (120/240 → limit) "
              "| RG A (240) | RG wall [s] (240) |", "|---|---|---|---|---|---|---|---|"]
    for p in HS_PRESSURES:
        vhs = rc.halfspace.solve_sliding(hs, hs.period, rc.materials.sbr(), 10.0, p, n=4096)
        s = out[f"simo p={p}"]
        r1, r2 = out[f"rg p={p} spp=120"], out[f"rg p={p} spp=240"]
        cells = [f"{vhs.friction:.3f}", f"{vhs.contact_fraction:.3f}"]
        cells += ([f"{float(s['friction']):.3f}", f"{float(s['contact_fraction']):.3f}"]
                  if hasattr(s, "data_vars") else ["failed", ""])
        if hasattr(r1, "data_vars") and hasattr(r2, "data_vars"):
            m1, m2 = float(r1["friction"]), float(r2["friction"])
            cells += [f"{m1:.3f} / {m2:.3f} → {first_order_limit(m1, m2):.3f}",
                      f"{float(r2['contact_fraction']):.3f}", f"{float(r2['wall_time']):.0f}"]
        else:
            cells += ["failed", "", ""]
        lines.append(f"| {p:g} | " + " | ".join(cells) + " |")

    # -- 2. section 3, full pipeline with each model ---------------------------------
    if not args.skip_section3:
        from rubbercontact.hybrid.metrics import mean_relative_error

        runs = {}
        for model in MODELS:
            cfg = _section3_config(model, args.cache, args.output, args.workers)
            print(f"== section 3 with {model}", flush=True)
            runs[model] = rc.pipeline.run(cfg, progress="log")
        hyb = ("hybrid", "hybrid-windowed", "vhs")
        lines += ["", "## Section 3 surface, realization seed 2021, law 30 x 23 (240 steps "
                  "per period), full FEM 64 x 48 (256 steps per period)", "",
                  "| model | v [mm/s] | σ0 [MPa] | VHS μ (A) | hybrid μ (A) | windowed μ (A) "
                  "| FEM μ (A) |", "|---|---|---|---|---|---|---|"]
        for model, ds in runs.items():
            for v in S3_VELOCITIES:
                for p in S3_PRESSURES:
                    s = ds.sel(velocity=v, pressure=p)
                    lines.append(f"| {model} | {v:g} | {p:g} | " + " | ".join(
                        f"{float(s['friction_mean'].sel(model=m)):.3f} "
                        f"({float(s['contact_fraction_mean'].sel(model=m)):.4f})"
                        for m in ("vhs", "hybrid", "hybrid-windowed", "fem")) + " |")
        fine = rc.pipeline.run(_section3_config("reese-govindjee", args.cache, args.output,
                                              args.workers, 512, S3_PRESSURES[:2], ["fem"]),
                             progress="log")
        lines += ["", "RG full FEM in dt (first order): μ at 256 / 512 steps per period → "
                  "limit 2 μ(512) − μ(256):", ""]
        limit = {}
        for v in S3_VELOCITIES:
            for p in S3_PRESSURES[:2]:
                m1 = float(runs["reese-govindjee"]["friction_mean"].sel(
                    model="fem", velocity=v, pressure=p))
                m2 = float(fine["friction_mean"].sel(model="fem", velocity=v, pressure=p))
                limit[v, p] = first_order_limit(m1, m2)
                simo = float(runs["simo"]["friction_mean"].sel(model="fem", velocity=v,
                                                               pressure=p))
                lines.append(f"- {v:g} mm/s, σ0 = {p:g} MPa: {m1:.3f} / {m2:.3f} → "
                             f"{limit[v, p]:.3f} (Simo at 256 steps, second order: {simo:.3f})")
        lines += ["", "Eq. 28 at equal σ0 over 0.15 and 0.35 MPa against the RG full FEM's dt "
                  "limit (RG law) and against the Simo full FEM (Simo law):", "",
                  "| model | v [mm/s] | hybrid | windowed hybrid | VHS |", "|---|---|---|---|---|"]
        for model in MODELS:
            ds = runs[model]
            for v in S3_VELOCITIES:
                ref = (np.array([limit[v, p] for p in S3_PRESSURES[:2]]) if model != "simo"
                       else ds["friction_mean"].sel(model="fem", velocity=v).values[:2])
                errs = [mean_relative_error(ref, ds["friction_mean"].sel(
                    model=m, velocity=v).values[:2]) for m in hyb]
                lines.append(f"| {model} | {v:g} | "
                             + " | ".join(f"{100 * e:.1f} %" for e in errs) + " |")
        lines += ["", "Eq. 28 error against the full FEM of the same material model at 256 steps "
                  "per period, at equal σ0 (three loads; the RG FEM there is well below its dt "
                  "limit, see above, so its rows are not a fair test of the hybrids):", "",
                  "| model | v [mm/s] | hybrid | windowed hybrid | VHS |", "|---|---|---|---|---|"]
        for model, ds in runs.items():
            for v in S3_VELOCITIES:
                ref = ds["friction_mean"].sel(model="fem", velocity=v).values
                errs = [mean_relative_error(ref, ds["friction_mean"].sel(
                    model=m, velocity=v).values) for m in hyb]
                lines.append(f"| {model} | {v:g} | "
                             + " | ".join(f"{100 * e:.1f} %" for e in errs) + " |")
        lines += ["", "Law (high-slope wave, 30 x 23) per model: friction μ_hs and α_hs:", "",
                  "| v [mm/s] | p̄ [MPa] | " + " | ".join(f"{m} μ_hs | {m} α_hs"
                                                       for m in MODELS) + " |",
                  "|---|---|" + "---|---|" * len(MODELS)]
        lp = runs[MODELS[0]]["law_pressure"].values
        for v in S3_VELOCITIES:
            for k, p in enumerate(lp):
                cells = []
                for model in MODELS:
                    s = runs[model].sel(velocity=v).isel(law_pressure=k)
                    cells += [f"{float(s['law_friction']):.3f}",
                              f"{float(s['law_contact_fraction']):.3f}"]
                lines.append(f"| {v:g} | {p:g} | " + " | ".join(cells) + " |")
        cost = {m: json.loads(ds.attrs["model_cpu_time_s"]) for m, ds in runs.items()}
        lines += ["", "Compute time [s] (sum over solves): " + "; ".join(
            f"{m}: " + ", ".join(f"{k} {v:.0f}" for k, v in c.items()) for m, c in cost.items())]
    if not args.skip_asphalt:
        lines += ["", "## AC-8 asphalt (paper §4), 3 realizations, law 30 x 23 (240 steps per "
                  "period) with each model", "",
                  "| v [mm/s] | σ0 [MPa] | VHS μ | " + " | ".join(
                      f"{m} hybrid μ | {m} windowed μ" for m in MODELS) + " |",
                  "|---|---|---|" + "---|---|" * len(MODELS)]
        asph = {m: rc.pipeline.run(_asphalt_config(m, args.cache, args.workers), progress="log")
                for m in MODELS}
        ref = asph[MODELS[0]]
        for v in ref["velocity"].values:
            for p in ref["pressure"].values:
                vhs = ref["friction_mean"].sel(model="vhs", velocity=v, pressure=p)
                cells = [f"{float(vhs):.3f}"]
                for m in MODELS:
                    s_ = asph[m].sel(velocity=v, pressure=p)["friction_mean"]
                    cells += [f"{float(s_.sel(model='hybrid')):.3f}",
                              f"{float(s_.sel(model='hybrid-windowed')):.3f}"]
                lines.append(f"| {v:g} | {p:g} | " + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    return publish(text, args.report)


if __name__ == "__main__":
    raise SystemExit(main())
