"""Section 3 at 50 mm/s: the full FEM's load sweep once creep has settled, on 5 realizations.

The validation's full FEM slides 3 periods of the 0.25 mm cell (15 ms at 50 mm/s, under
one of the SBR's longest retardation times, 16.3 ms). ``studies/cell_creep.py`` showed
on realization 0 that at 2 MPa the settled friction and contact area lie *below* their
0.8 MPa values: the friction stress exceeds E∞/3, the cell creeps into a bulk shear above 1,
and the 3-period result is a transient. If that holds on other realizations, the FEM cell
has no settled answer above some contact area at 50 mm/s, and eq. 28 cannot compare over
the paper's range 0.01-0.1 there.

This study slides the same coarse cell (``cell_creep.run_case``: 96 columns, 16 rows
graded x8, H/L0 = 0.75, 96 steps per period) 17 periods (85 ms, 5.2 retardation times) at
loads 0.1-3 MPa on realizations 0-4 of seed 2021, and reports per realization the settled
μ(p̄) and A(p̄), where A(p̄) stops growing, the bulk shear, and the change from period 3. The
VHS (converged half-space, steady sliding, the same realization and load) is given beside
it: a linear model's area only grows with load.

The coarse mesh follows the validation's (240 × 45 graded ×8) in trend: from 3 to 6
periods at 2 MPa μ −8.9 % against −8.4 %, tall/paper cell after 3 periods +5 % / +22 %
against +5.7 % / +19 % (``docs/validation/cell_height.md``). Its values are lower (μ 7 %,
A 12 % at 2 MPa, period 3, realization 0), so the report compares each test with itself
(settled against period 3) and areas across loads, not with the validation's numbers.

With ``--eq28`` the report adds eq. 28 at 50 mm/s against a creep-settled estimate of the
validation's full FEM: each of its tests (240 × 45 graded ×8, 3 periods, realizations 0-4
at 0.1 / 0.15 / 0.35 / 0.8 / 2 MPa, from the validation cache) times this study's settling
factor for the same realization and load (coarse settled / coarse period 3, for μ and A
separately). The phase average is taken as in VALIDATION.md (cheap models on N = 1000
realizations, the FEM by control variate). The hybrids read either the validation's law or,
with ``--law``, another one, and with ``--law-min-creep-times 5`` a creep-settled law (built
through the cache by ``sampling_study.creep_settled_law``; its FEM points are in the
reference cache).

Resumable: one JSON line per finished test in the ``.jsonl`` beside the report (the
realization-0 tests of ``docs/validation/cell_creep.jsonl`` are reused). Two processes::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies settled_loads --workers 2 \\
        --eq28 --law-min-creep-times 5 --report docs/validation/settled_loads.md
"""

from __future__ import annotations

import argparse
import functools
import json
import sys
import traceback
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import rubbercontact as rc
from rubbercontact.pipeline import make_runner

from . import _compare as compare
from . import _validation_report as vreport
from . import validate
from ._rows import append_row, publish, read_rows
from .cell_creep import SEED, VELOCITY, run_case
from .fem_reference_mesh import _mesh
from .sampling_study import creep_settled_law

DESCRIPTION = ("Section 3 at 50 mm/s: the full FEM's load "
               "sweep once creep has settled, on 5 realizations.")

ROOT = Path(__file__).resolve().parents[1]
LOADS = (0.1, 0.15, 0.35, 0.8, 1.2, 2.0, 3.0)
REALIZATIONS = (0, 1, 2, 3, 4)
RATIO = 0.75
PERIODS = 17
#: settled = the last period; "still moving" is reported when μ or A changed by more than
#: this over the last 2 periods (relative)
DRIFT = 0.01


def _case(p: float, r: int) -> dict:
    """One test, or the failure's last line (a non-converged step is a result here too)."""
    try:
        return run_case(p, RATIO, PERIODS, r)
    except Exception as exc:  # noqa: BLE001 - reported in the table, the sweep goes on
        return {"p": p, "ratio": RATIO, "periods": PERIODS, "realization": r,
                "error": f"{type(exc).__name__}: {exc}".splitlines()[0],
                "traceback": traceback.format_exc()}


@functools.cache
def vhs(p: float, r: int) -> tuple[float, float]:
    """The VHS's μ and A on realization ``r`` at ``p`` [MPa] (4096 points, LJ wall)."""
    from rubbercontact.hybrid.tasks import halfspace_law

    surf = rc.roughness.section3().realizations(r + 1, seed=SEED)[r]
    res = rc.halfspace.solve_sliding(surf, surf.period, rc.materials.sbr(), VELOCITY, p,
                                     law=halfspace_law("lennard-jones"), n=4096)
    return res.friction, res.contact_fraction


def _fmt(x: float, digits: int) -> str:
    return "-" if not np.isfinite(x) else f"{x:.{digits}f}"


def report(rows: list[dict]) -> str:
    by = {(r["realization"], r["p"]): r for r in rows}
    reals = sorted({r for r, _ in by})
    loads = sorted({p for _, p in by})
    g_inf = rc.materials.sbr().equilibrium_modulus / 3
    out = ["# Section 3, 50 mm/s: the full FEM's load sweep once creep has settled",
           "",
           "Generated by `studies/settled_loads.py` (see its docstring): the coarse full "
           f"cell (96 columns, 16 rows graded x8, H/L0 = {RATIO}), {PERIODS} periods of the "
           "0.25 mm cell (85 ms, 5.2 of the SBR's longest retardation times), realizations "
           f"of seed {SEED}. Settled = the last period's mean; 'period 3' = the third "
           "period's mean, where the validation's full FEM stops. VHS: steady-sliding "
           "half-space on the same realization and load. γ = the bulk shear (face lag / H) "
           f"at the end; G∞ = E∞/3 = {g_inf:.2f} MPa.", ""]
    summary = ["| r | settled A grows with p̄ up to | largest settled A | settled μ there | "
               "VHS A at that load | loads where the settled A falls |",
               "|---|---|---|---|---|---|"]
    tables = []
    for r in reals:
        tab = [f"## Realization {r}", "",
               "| p̄ [MPa] | μ settled | μ period 3 | μ VHS | A settled | A period 3 | "
               "A VHS | γ | μp̄/G∞ | still moving | min |",
               "|---|---|---|---|---|---|---|---|---|---|---|"]
        a_set, mu_set, ps = [], [], []
        for p in loads:
            row = by.get((r, p))
            if row is None:
                continue
            mu_v, a_v = vhs(p, r)
            if "error" in row:
                tab.append(f"| {p:g} | failed: {row['error']} | | {mu_v:.3f} | | | "
                           f"{a_v:.4f} | | | | |")
                continue
            mu, a, g = (np.asarray(row[k]) for k in ("friction", "contact_fraction",
                                                     "bulk_shear"))
            moving = max(abs(mu[-1] / mu[-3] - 1), abs(a[-1] / a[-3] - 1)) > DRIFT
            tab.append(f"| {p:g} | {mu[-1]:.3f} | {mu[2]:.3f} | {mu_v:.3f} | {a[-1]:.4f} | "
                       f"{a[2]:.4f} | {a_v:.4f} | {g[-1]:.2f} | "
                       f"{mu[-1] * p / g_inf:.2f} | {'yes' if moving else 'no'} | "
                       f"{row['wall_time'] / 60:.1f} |")
            ps.append(p)
            a_set.append(a[-1])
            mu_set.append(mu[-1])
        tables += tab + [""]
        if not ps:
            continue
        a_set = np.asarray(a_set)
        k = int(np.argmax(a_set))
        falls = [f"{ps[i]:g}" for i in range(1, len(ps)) if a_set[i] < a_set[i - 1]]
        mu_v, a_v = vhs(ps[k], r)
        summary.append(f"| {r} | {ps[k]:g} MPa | {a_set[k]:.4f} | {mu_set[k]:.3f} | "
                       f"{a_v:.4f} | {', '.join(falls) or 'none'} |")
    return "\n".join(out + summary + [""] + tables)


#: the validation's full-FEM loads at 50 mm/s (core and extended) and the realizations all
#: of them ran on
EQ28_LOADS = (0.1, 0.15, 0.35, 0.8, 2.0)
EQ28_REALIZATIONS = 5
EQ28_MODELS = ("hybrid-windowed", "vhs", "hybrid")


def settling_factors(rows: list[dict]) -> dict:
    """``{(r, p): (μ_settled/μ_3, A_settled/A_3)}`` of every finished coarse test."""
    return {(r["realization"], r["p"]): (r["friction"][-1] / r["friction"][2],
                                         r["contact_fraction"][-1] / r["contact_fraction"][2])
            for r in rows if "error" not in r}


#: The settling factors are also applied from this load [MPa] up only: at 0.1-0.15 MPa the
#: coarse cell's contact is 1-2 columns wide and two of its ten tests there switch crests
#: mid-run (realization 3 at 0.1 MPa, 4 at 0.15 MPa, period 8), where the bulk shear that
#: this study is about is below 0.03.
SETTLED_FROM = 0.35
FEM_VARIANTS = ("3 periods", "settled", f"settled from {SETTLED_FROM:g} MPa")


def eq28_data(law: Path | None, workers: int, cache: Path, n: int, factors: dict,
              label: str | None = None) -> dict:
    """The validation's section 3 run at 50 mm/s on :data:`EQ28_LOADS` (5 realizations; the
    FEM from the cache), its hybrids reading ``law`` (default: the validation's), and its
    phase data per :data:`FEM_VARIANTS`: the FEM as run (3 periods), times the settling
    factors at every load, and times them from :data:`SETTLED_FROM` up."""
    cfg = validate.case_config("section3", "quick", workers, cache, ROOT / "results",
                           EQ28_REALIZATIONS)
    data = cfg.model_dump(mode="json", exclude_none=True)
    data.update(velocities=[VELOCITY], loads={"pressures": list(EQ28_LOADS)})
    data["output"]["directory"] = str(ROOT / "results" / "settled_loads")
    if law is not None:
        data["law"] = {"file": str(law)}
    cfg = rc.config.parse_config(data, source="section3 at 50 mm/s, loads 0.1-2 MPa")
    ds = rc.pipeline.run(cfg, runner=make_runner(cfg, progress="log"))
    missing = [(r, p) for r in range(EQ28_REALIZATIONS) for p in EQ28_LOADS
               if (r, p) not in factors]
    if missing:
        raise RuntimeError(f"settling factors missing for (realization, load): {missing}")
    out = {"law": label or (str(law) if law is not None else "the validation's"),
           "law_points": _law_summary(ds)}
    for variant, p_min in zip(FEM_VARIANTS, (np.inf, 0.0, SETTLED_FROM), strict=True):
        settled = ds.copy(deep=True)
        for (r, p), (f_mu, f_a) in factors.items():
            if r < EQ28_REALIZATIONS and p in EQ28_LOADS and p >= p_min:
                at = {"model": "fem", "velocity": VELOCITY, "realization": r, "pressure": p}
                settled["friction"].loc[at] = float(ds["friction"].sel(at)) * f_mu
                settled["contact_fraction"].loc[at] = (float(ds["contact_fraction"].sel(at))
                                                       * f_a)
        out[variant] = compare.phase_average_data(settled, cfg, n)[VELOCITY]
    return out


def _law_summary(ds) -> str:
    """The law's pressures and which were screened out, from a results set."""
    p = ds["law_pressure"].values
    st = ds["law_status"].sel(velocity=VELOCITY).values if "law_status" in ds else None
    if st is None:
        return ", ".join(f"{x:g}" for x in p) + " MPa"
    return ", ".join(f"{x:g}" + ("" if str(s) == "ok" else " (excluded)")
                     for x, s in zip(p, st, strict=True)) + " MPa"


def eq28_section(runs: list[dict], resamples: int) -> tuple[list[str], list[dict]]:
    """Eq. 28 at equal area against the FEM as run and creep-settled, per law: the
    report's lines and one record per row (``studies/validate.py`` reads them)."""
    out = ["## Eq. 28 at 50 mm/s against a creep-settled full FEM", "",
           "The validation's full FEM (240 × 45 graded ×8, 3 periods; realizations 0-"
           f"{EQ28_REALIZATIONS - 1} at " + " / ".join(f"{p:g}" for p in EQ28_LOADS)
           + " MPa) *as run*, and *settled*: each test times the settling factor of the coarse "
           "test above for the same realization and load (μ and A separately), at every load or "
           f"from {SETTLED_FROM:g} MPa up (see SETTLED_FROM in the script). Phase average "
           "as in VALIDATION.md: the cheap models on N realizations, the FEM as mean_N(VHS) + "
           "mean_R(FEM − VHS); eq. 28 at 4 areas log-spaced over the range every model "
           "covers, on each sweep's rising branch (a load whose area does not exceed a lower "
           "load's is left out); 90 % interval from "
           f"{resamples} two-sample bootstrap resamples. 'Below 2 MPa': loads 0.1-0.8 MPa.",
           "",
           "| hybrids' law | FEM | loads | areas | windowed hybrid | VHS | pointwise hybrid |",
           "|---|---|---|---|---|---|---|"]
    curves_lines, records = [], []
    for run in runs:
        for kind in FEM_VARIANTS:
            for label, data in (("all", run[kind]), ("below 2 MPa",
                                                     compare.below_load(run[kind], 2.0))):
                e, ci = compare.eq28_phase_averaged({VELOCITY: data}, resamples)[VELOCITY]
                lo, hi = compare.phase_area_range(data)
                cells = [f"{100 * e[m]:.1f} % ({vreport.interval_text(*ci[m], resamples)})"
                         if m in ci else "-" for m in EQ28_MODELS]
                out.append(f"| {run['law']} | {kind} | {label} | {lo:.3f}-{hi:.3f} | "
                           + " | ".join(cells) + " |")
                records.append({"velocity": VELOCITY, "law": run["law"], "fem": kind,
                                "loads": label, "areas": [float(lo), float(hi)],
                                "error": {m: float(e[m]) for m in EQ28_MODELS},
                                "interval": {m: list(ci[m]) for m in EQ28_MODELS if m in ci},
                                "resamples": resamples})
            curves = compare.phase_mean_curves(run[kind])["phase"]
            curves_lines.append(
                f"| {run['law']} | {kind} | " + " | ".join(
                    f"{curves['fem'][1][k]:.3f} ({curves['fem'][0][k]:.4f}) / "
                    f"{curves['hybrid-windowed'][1][k]:.3f} "
                    f"({curves['hybrid-windowed'][0][k]:.4f})"
                    for k in range(len(run[kind]["pressures"]))) + " |")
    p = runs[0]["settled"]["pressures"]
    out += ["", "Phase-averaged μ (A), FEM / windowed hybrid, per load:", "",
            "| hybrids' law | FEM | " + " | ".join(f"{x:g} MPa" for x in p) + " |",
            "|---|---|" + "---|" * len(p), *curves_lines, "",
            "Law points: " + "; ".join(f"{r['law']}: {r['law_points']}" for r in runs) + ".",
            ""]
    return out, records


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--report", type=Path, required=True,
                    help="Markdown report; finished tests go to the .jsonl beside it")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--realizations", type=int, nargs="+", default=list(REALIZATIONS))
    ap.add_argument("--loads", type=float, nargs="+", default=list(LOADS))
    ap.add_argument("--eq28", action="store_true",
                    help="add eq. 28 against the creep-settled estimate of the validation's "
                         "full FEM (needs realizations 0-4 at 0.1-2 MPa)")
    ap.add_argument("--law", type=Path, action="append", default=None,
                    help="with --eq28: a law file for the hybrids besides the validation's "
                         "(repeatable)")
    ap.add_argument("--law-min-creep-times", type=float, default=None,
                    help="with --eq28: also a law whose FEM points slide this many longest "
                         "retardation times (built through the cache, as "
                         "sampling_study.py --law-min-creep-times does)")
    ap.add_argument("--phase-realizations", type=int, default=compare.PHASE_REALIZATIONS)
    ap.add_argument("--resamples", type=int, default=2000)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    args = ap.parse_args(argv)
    store = args.report.with_suffix(".jsonl")
    # realization 0's long paper-cell tests of the creep study are the same computation
    seed = [r for r in read_rows(ROOT / "docs" / "validation" / "cell_creep.jsonl")
            if r["ratio"] == RATIO and r["periods"] == PERIODS]
    done = {(r["realization"], r["p"]) for r in read_rows(store)}
    for r in seed:
        if (r["realization"], r["p"]) not in done:
            append_row(store, r)
            done.add((r["realization"], r["p"]))
    todo = [(p, r) for p in sorted(args.loads, reverse=True)   # dearest first
            for r in args.realizations if (r, p) not in done]
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        futures = [pool.submit(_case, p, r) for p, r in todo]
        for fut in as_completed(futures):
            append_row(store, fut.result())
    rows = read_rows(store)
    text = report(rows)
    if args.eq28:
        validate.seed_cache(validate.REFERENCE_CACHE, args.cache)
        factors = settling_factors(rows)
        laws = [(None, None), *((law, None) for law in args.law or [])]
        if args.law_min_creep_times is not None:
            laws.append((creep_settled_law(SimpleNamespace(
                velocities=[VELOCITY], workers=args.workers, cache=args.cache,
                outdir=ROOT / "results" / "settled_loads" / "law",
                law_min_creep_times=args.law_min_creep_times), *_mesh("240x45:g8", 4.0)),
                f"creep-settled ({args.law_min_creep_times:g} retardation times)"))
        runs = [eq28_data(law, args.workers, args.cache, args.phase_realizations, factors,
                          label) for law, label in laws]
        lines, records = eq28_section(runs, args.resamples)
        text += "\n" + "\n".join(lines)
        # the rows VALIDATION.md shows (s3report.SETTLED_EQ28), written whole or not at all
        publish(json.dumps(records, indent=1), args.report.with_suffix(".json"), echo=False)
    return publish(text, args.report)


if __name__ == "__main__":
    sys.exit(main())
