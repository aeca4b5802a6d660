"""Why the windowed hybrid's headline eq. 28 moved from 6.6 % to 0.7 % at 50 mm/s.

Between the time-stepped validation (docs/validation/section3_transient.md) and the steady
one, three things changed at once: the full FEM (time-stepped → steady solver), its
realizations (R = 10 → 6) and the cheap models' (N = 1000 → 100) — and the law (also
steady now). This study changes them one at a time on the section 3 quick case, with the
steady law throughout, and gives each eq. 28 with the range of
:class:`rubbercontact.compare.Eq28` (which contains it):

1. time-stepped full FEM, R = 10, N = 1000 (the old sampling);
2. time-stepped full FEM, R = 6 (the first six), N = 1000;
3. time-stepped full FEM, R = 6, N = 100;
4. steady full FEM, R = 6, N = 100 (the current VALIDATION.md row).

The time-stepped tests are read from docs/validation/reference-cache (matched to the steady
tests' problems: surface, rubber, speed, load, cell); the steady ones and the cheap models
from the validation cache. The difference between row 1 and the old published 6.6 % is
then the law's change. Cost: the cheap models on 1000 realizations, about ten minutes on
two cores the first time; everything else is cached.

    python -m studies headline_shift [--workers 2]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import warnings
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.compare import CHEAP_MODELS, eq28_phase_bounds
from rubbercontact.pipeline import make_runner
from rubbercontact.pipeline.plan import full_fem_task
from rubbercontact.pipeline.setup import resolve, task_material
from rubbercontact.sweep.tasks import canonical

from . import validate
from ._templates import render
from ._validation_report import _fem_signature

DESCRIPTION = "Why the headline eq. 28 moved between the time-stepped and the steady validation."

ROOT = Path(__file__).resolve().parents[1]
#: The old and the current sampling.
OLD_R, NEW_R, OLD_N, NEW_N = 10, 6, 1000, 100


def _transient_values(reference: Path) -> dict:
    """``{problem signature: (A, μ)}`` of the time-stepped full-FEM tests of the reference."""
    import xarray as xr

    out = {}
    for path in sorted(reference.glob("sweep-v1/*/*.nc")):
        with xr.open_dataset(path) as ds:
            task = json.loads(ds.attrs["rc_cache_task"])
            if (not task["function"].endswith(":fem_task") or task["label"].startswith("law")
                    or str(ds.attrs.get("solver", "transient")) != "transient"):
                continue
            sig = _fem_signature(task)
            if sig is not None and sig not in out:
                out[sig] = (float(ds["contact_fraction"]), float(ds["friction"]))
    return out


def _fem_arrays(cfg, r: int, values: dict | None, steady) -> dict:
    """``{v: (A, μ)}`` arrays (realization, load) of the full FEM on the first ``r``
    realizations: time-stepped (from ``values``) or steady (from the run ``steady``)."""
    setup = resolve(cfg.model_copy(update={"realizations": r}))
    material = rc.materials.GeneralizedMaxwell(**task_material(setup.material))
    out = {}
    for v in cfg.velocities:
        a = np.full((r, len(cfg.loads.pressures)), np.nan)
        mu = np.full_like(a, np.nan)
        for ir, real in enumerate(setup.realizations):
            for ip, p in enumerate(cfg.loads.pressures):
                if values is None:
                    sel = dict(model="fem", velocity=v, realization=ir, pressure=p)
                    a[ir, ip] = float(steady["contact_fraction"].sel(sel))
                    mu[ir, ip] = float(steady["friction"].sel(sel))
                    continue
                task = full_fem_task(cfg, real, material, float(v), float(p))
                desc = {"function": task.function, "kwargs": canonical(task.kwargs)}
                a[ir, ip], mu[ir, ip] = values.get(_fem_signature(desc), (np.nan, np.nan))
        out[float(v)] = (a, mu)
    return out


def _cheap(cfg, n: int) -> dict:
    """``{v: {model: (A, μ)}}`` of the cheap models on ``n`` realizations (cached)."""
    data = cfg.model_dump(mode="json", exclude_none=True)
    data.update(models=list(CHEAP_MODELS), realizations=n)
    cheap_cfg = rc.config.parse_config(data, source=f"section3 ({n} realizations)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the validation run has warned about its law
        ds = rc.pipeline.run(cheap_cfg, runner=make_runner(cheap_cfg, progress="log"))
    return {float(v): {m: tuple(ds[k].sel(model=m, velocity=v)
                                .transpose("realization", "pressure").values
                                for k in ("contact_fraction", "friction"))
                       for m in CHEAP_MODELS} for v in ds["velocity"].values}


def _row(fem: tuple, cheap: dict, r: int, n: int) -> dict:
    data = {"fem": fem, "paired": {m: tuple(x[:r] for x in xs) for m, xs in cheap.items()},
            "all": {m: tuple(x[:n] for x in xs) for m, xs in cheap.items()}}
    return eq28_phase_bounds(data)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--report", type=Path,
                    default=ROOT / "docs" / "validation" / "headline_shift.md")
    args = ap.parse_args(argv)
    validate.seed_cache(validate.REFERENCE_CACHE, args.cache)
    cfg = validate.case_config("section3", "quick", args.workers, args.cache,
                               ROOT / "results" / "headline_shift")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        steady = rc.pipeline.run(cfg, runner=make_runner(cfg, progress="log"))
    old_cfg = cfg.model_copy(update={"realizations": OLD_R})
    transient = _transient_values(validate.REFERENCE_CACHE)
    fem = {"transient": _fem_arrays(old_cfg, OLD_R, transient, None),
           "steady": _fem_arrays(cfg, NEW_R, None, steady)}
    cheap = _cheap(cfg, OLD_N)
    steps = [("time-stepped", OLD_R, OLD_N), ("time-stepped", NEW_R, OLD_N),
             ("time-stepped", NEW_R, NEW_N), ("steady", NEW_R, NEW_N)]
    lines = ["| v [mm/s] | full FEM | R | N | " + " | ".join(CHEAP_MODELS) + " |",
             "|---|---|---|---|" + "---|" * len(CHEAP_MODELS)]
    moves = []
    for v in sorted(cheap):
        windowed = []
        for solver, r, n in steps:
            a, mu = fem["transient" if solver == "time-stepped" else "steady"][v]
            res = _row((a[:r], mu[:r]), cheap[v], r, n)
            windowed.append(res["hybrid-windowed"].error if "hybrid-windowed" in res
                            else np.nan)
            cells = [f"{100 * b.error:.1f} % ({100 * b.low:.1f}–{100 * b.high:.1f}; mean "
                     f"{100 * b.bias:+.1f} %)" if (b := res.get(m)) else "-"
                     for m in CHEAP_MODELS]
            lines.append(f"| {v:g} | {solver} | {r} | {n} | " + " | ".join(cells) + " |")
        steps_pc = " → ".join(f"{100 * e:.1f} %" for e in windowed)
        moves.append(f"At {v:g} mm/s the windowed hybrid goes {steps_pc} (R, N, solver).")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip() or "unknown"
    missing = int(sum(np.isnan(fem["transient"][v][1]).sum() for v in fem["transient"]))
    text = "\n".join([
        render("headline_shift", "title"), "",
        render("headline_shift", "intro", script="studies/headline_shift.py",
               when=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"), commit=commit,
               missing=missing), "", *lines, "",
        render("headline_shift", "reading", moves=" ".join(moves)), ""])
    args.report.write_text(text)
    print(f"wrote {args.report}")
    return 0
