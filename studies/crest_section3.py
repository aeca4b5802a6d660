"""The crest-resolved reading of the law on the paper §3 surface, against the full FEM.

Experimental. ``studies/scale_separation.py`` shows, with a linear law, that the hybrid's
remaining error at small wavelength ratios is how its low-slope solve shares the load among
the discrete high-slope crests, and that a small half-space solve with one cell per crest
(:func:`scale_separation.crest_resolved_loads`) predicts that sharing. Here the same
reading is applied with the FEM law of the section 3 validation and compared with the full
FEM, next to the windowed hybrid and the VHS:

    μ = μ_ls (the hybrid's low-slope solve) + <Δτ_hs(P_k)>/σ0,   A = <α_hs(P_k)>.

Needs the section 3 validation results (``docs/validation/section3/results.nc``) and its
cache (the law is rebuilt from the cached FEM solves exactly as the pipeline does). Run::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies crest_section3 \
        --report docs/validation/crest_section3.md
"""

from __future__ import annotations

import argparse
import subprocess
import warnings
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import xarray as xr

from rubbercontact.hybrid.metrics import mean_relative_error
from rubbercontact.hybrid.windowing import law_in_pressure
from rubbercontact.inputs import build_material, build_surface
from rubbercontact.pipeline import make_runner
from rubbercontact.pipeline.lawstage import build_law
from rubbercontact.pipeline.setup import translated_to_zero_phase

from . import _compare as compare
from . import validate
from ._rows import publish
from .scale_separation import crest_resolved_loads

DESCRIPTION = "The crest-resolved reading of the law on the paper §3 surface, against the full FEM."

ROOT = Path(__file__).resolve().parents[1]

def law_tables(cfg) -> dict:
    """Per velocity, the law table the pipeline's hybrid reads (from the cached FEM)."""
    base = build_surface(cfg.surface).series
    hs0 = translated_to_zero_phase(base.realizations(1, seed=cfg.seed)[0]
                                    .partition(cfg.surface.m2_threshold)[0])
    pressures = np.asarray(cfg.loads.pressures, float)
    return build_law(cfg, hs0, build_material(cfg.material), pressures,
                     make_runner(cfg, False, False)).tables


def material_model_part(cache: Path) -> list[str]:
    """The same reading with each material model's law, against that model's full FEM.

    One realization, 0.15 and 0.35 MPa, law 30 x 23, full FEM 64 x 48
    (``studies/material_model.py``, whose cache this reuses); the RG full FEM is taken at
    its first-order dt limit 2 μ(512) − μ(256) steps per period.
    """
    import material_model as mm

    import rubbercontact as rc

    out = ["## With each material model's law (one realization, 64 x 48 full FEM)", "",
           "From the cache of `studies/material_model.py`; the Reese-Govindjee (RG) FEM at "
           "its dt limit.", "",
           "| model | v [mm/s] | σ0 [MPa] | FEM | VHS | windowed | crest-resolved |",
           "|---|---|---|---|---|---|---|"]
    pressures = mm.S3_PRESSURES[:2]
    for model in mm.MODELS:
        cfg = mm._section3_config(model, cache, Path("/tmp/crest_section3_mm"), 1)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = rc.pipeline.run(cfg, progress=False)
            tables = law_tables(cfg)
            fine = (rc.pipeline.run(mm._section3_config(model, cache,
                                                      Path("/tmp/crest_section3_mm"), 1, 512,
                                                      pressures, ["fem"]), progress=False)
                    if model != "simo" else None)
        material = build_material(cfg.material)
        base = build_surface(cfg.surface).series
        hs, ls = base.realizations(1, seed=cfg.seed)[0].partition(cfg.surface.m2_threshold)
        for v in cfg.velocities:
            sig, _, tau = law_in_pressure(tables[float(v)])
            for p in pressures:
                s = ds.sel(velocity=v, pressure=p, realization=0)
                fem = float(s["friction"].sel(model="fem"))
                if fine is not None:
                    fem = mm.first_order_limit(fem, float(fine["friction"].sel(
                        model="fem", velocity=v, pressure=p, realization=0)))
                loads = crest_resolved_loads(ls, hs, base.period, tables[float(v)], material,
                                             float(v), float(p), n=cfg.halfspace.n)
                crest = (float(s["friction_ls"].sel(model="hybrid"))
                         + float(np.mean(np.interp(loads, sig, tau))) / p)
                out.append(f"| {model} | {v:g} | {p:g} | {fem:.3f} | "
                           f"{float(s['friction'].sel(model='vhs')):.3f} | "
                           f"{float(s['friction'].sel(model='hybrid-windowed')):.3f} | "
                           f"{crest:.3f} |")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--results", type=Path,
                    default=ROOT / "docs" / "validation" / "section3" / "results.nc")
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--report", type=Path)
    ap.add_argument("--skip-material-model", action="store_true",
                    help="skip the one-realization comparison with the Reese-Govindjee law")
    args = ap.parse_args(argv)
    ds = xr.load_dataset(args.results)
    n_real = ds.sizes["realization"]
    cfg = validate.case_config("section3", "quick", 1, args.cache, Path("/tmp/crest_section3"),
                           n_real)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tables = law_tables(cfg)
    material = build_material(cfg.material)
    base = build_surface(cfg.surface).series
    parts = [r.partition(cfg.surface.m2_threshold)
             for r in base.realizations(n_real, seed=cfg.seed)]
    if not np.allclose(ds["phase"].values,
                       [r.phases for r in base.realizations(n_real, seed=cfg.seed)]):
        raise SystemExit(f"{args.results}: its realizations are not those of the section 3 "
                         "quick config (seed or surface changed); rerun python -m studies validate")
    mu_c = np.full((ds.sizes["velocity"], n_real, ds.sizes["pressure"]), np.nan)
    area_c = np.full_like(mu_c, np.nan)
    for iv, v in enumerate(ds["velocity"].values):
        sig, alpha, tau = law_in_pressure(tables[float(v)])
        for ir, (hs, ls) in enumerate(parts):
            for ip, p in enumerate(ds["pressure"].values):
                loads = crest_resolved_loads(ls, hs, base.period, tables[float(v)], material,
                                             float(v), float(p), n=cfg.halfspace.n)
                mu_ls = float(ds["friction_ls"].sel(model="hybrid", velocity=v,
                                                    realization=ir, pressure=p))
                mu_c[iv, ir, ip] = mu_ls + float(np.mean(np.interp(loads, sig, tau))) / p
                area_c[iv, ir, ip] = float(np.mean(np.interp(loads, sig, alpha)))
    crest = ds.sel(model=["hybrid-windowed"]).assign_coords(model=["hybrid-crest"])
    crest["friction"] = (("model", "velocity", "realization", "pressure"), mu_c[None])
    crest["contact_fraction"] = (("model", "velocity", "realization", "pressure"),
                                 area_c[None])
    crest = compare.with_realization_means(crest)
    keep = ["friction", "contact_fraction", "friction_mean", "contact_fraction_mean"]
    both = xr.concat([ds[keep], crest[keep]], dim="model")
    models = ["vhs", "hybrid-windowed", "hybrid-crest"]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    lines = ["# Crest-resolved reading of the law on the section 3 surface (experimental)", "",
             f"Generated by `studies/crest_section3.py` "
             f"({datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}) from "
             f"`{args.results.relative_to(ROOT)}`: {n_real} "
             "realizations, the quick level's FEM law and full FEM (VALIDATION.md).", "",
             "Mean μ (A) over the realizations:", "",
             "| v [mm/s] | σ0 [MPa] | FEM | VHS | windowed | crest-resolved |",
             "|---|---|---|---|---|---|"]
    for v in both["velocity"].values:
        for p in both["pressure"].values:
            at = both.sel(velocity=v, pressure=p)
            cells = [f"{float(at['friction_mean'].sel(model=m)):.3f} "
                     f"({float(at['contact_fraction_mean'].sel(model=m)):.4f})"
                     for m in ["fem", *models]]
            lines.append(f"| {v:g} | {p:g} | " + " | ".join(cells) + " |")
    lines += ["", "Eq. 28 against the FEM:", "",
              "| v [mm/s] | compared | " + " | ".join(models) + " |", "|---|---|---|---|---|"]
    areas = compare.friction_at_common_areas(both)
    for v in both["velocity"].values:
        s = both.sel(velocity=v)
        fem = s["friction_mean"].sel(model="fem").values
        row = [f"{100 * mean_relative_error(fem, s['friction_mean'].sel(model=m).values):.1f} %"
               for m in models]
        lines.append(f"| {v:g} | equal σ0 | " + " | ".join(row) + " |")
        if float(v) in areas:
            a, mus = areas[float(v)]
            row = [f"{100 * mean_relative_error(mus['fem'], mus[m]):.1f} %" for m in models]
            lines.append(f"| {v:g} | equal A ({a.min():.3f}-{a.max():.3f}) | "
                         + " | ".join(row) + " |")
    if not args.skip_material_model:
        lines += ["", *material_model_part(args.cache)]
    text = "\n".join(lines) + "\n"
    return publish(text, args.report)


if __name__ == "__main__":
    raise SystemExit(main())
