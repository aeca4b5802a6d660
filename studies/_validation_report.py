"""The words of VALIDATION.md shared by its cases, and the asphalt and CAPTIF reports:
tables from the results, prose from ``templates/validation*.md`` (section 3:
``_section3_report``).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from rubbercontact.pipeline.lawcheck import QS_LABEL

from ._compare import RESAMPLES, SHORT_WAVE_CUTOFF
from ._templates import render

ROOT = Path(__file__).resolve().parents[1]


MODELS = ("hybrid", "hybrid-windowed", "vhs")


def repo_path(p: Path) -> str:
    """``p`` relative to the repository (figure links)."""
    return str(p.relative_to(ROOT))


def joined(values, fmt: str, sep: str = " / ") -> str:
    return sep.join(format(x, fmt) for x in values)


def percent_off(ratio) -> str:
    """``"+18 / +20 / +22"``: ``ratio - 1`` in per cent, one value per load."""
    return " / ".join(f"{100 * (float(x) - 1):+.0f}" for x in np.ravel(ratio))


def interval_text(low: float, high: float, used: int, resamples: int = RESAMPLES) -> str:
    """``low-high`` in %, and how many resamples defined the error if not all did."""
    text = f"{100 * low:.1f}-{100 * high:.1f}"
    return text if used == resamples else f"{text}; {used} of {resamples} resamples"


def warning_lines(msgs) -> list[str]:
    return ["", render("validation", "warnings"), ""] + [f"- {m}" for m in msgs] if msgs else []


def cost_lines(ds) -> list[str]:
    """The compute-time table of a run, the FEM / hybrid cost ratio and the FEM's times."""
    cost = json.loads(ds.attrs["model_cpu_time_s"])
    lines = ["| model | compute time [s] (sum over solves, 1 core) |", "|---|---|"]
    lines += [f"| {k} | {v:.1f} |" for k, v in cost.items()]
    if "fem" in cost and "hybrid" in cost:
        law = cost.get("law (FEM, counted once)", 0.0)
        lines += ["", render("validation", "cost_ratio",
                             with_law=f"{cost['fem'] / (cost['hybrid'] + law):.1f}",
                             without_law=f"{cost['fem'] / max(cost['hybrid'], 1e-9):.0f}")]
    if "fem" in cost and "wall_time" in ds and "fem" in ds["model"].values:
        t = ds["wall_time"].sel(model="fem").values
        t = t[np.isfinite(t)]
        text = render("validation", "fem_times", n=t.size, median=f"{np.median(t):.0f}",
                      low=f"{t.min():.0f}", high=f"{t.max():.0f}")
        law = cost.get("law (FEM, counted once)")
        if law and "law_pressure" in ds.dims:
            n_law = ds.sizes["law_pressure"] * ds.sizes["velocity"]
            text += render("validation", "fem_times_law", n=n_law, mean=f"{law / n_law:.0f}")
        lines += ["", text + "."]
    return lines




def law_lines(ds) -> list[str]:
    """The run's own lines on its law cell (crests, quasi-static check, coverage), as
    Markdown list items."""
    law = [ds.attrs.get("law_cell_note"), ds.attrs.get("law_quasi_static") and
           f"law cell: {ds.attrs['law_quasi_static']}",
           ds.attrs.get("law_coverage") and f"law: {ds.attrs['law_coverage']}"]
    return [f"- {line}" for line in law if line]


def fem_solves(cache: Path, keys) -> list[dict]:
    """Every FEM solve among the task ``keys`` found in the result cache ``cache``.

    One dict per solve: ``label`` (the task's), ``kind`` ("law", "check": the law cell's
    quasi-static point, or "full"), ``solver``
    ("steady", "transient", "transient (fallback)", or "failed"), ``status``, ``wall_time``
    [s] and ``newton_iterations`` (a speed-path task gives one entry per speed).
    """
    import xarray as xr

    from rubbercontact.sweep import ResultCache

    store, out = ResultCache(cache), []
    for key in sorted(keys):
        entry = store.load(key)
        if entry is None:
            continue
        attrs = xr.open_dataset(entry.path).attrs
        if "fem_" not in str(attrs.get("rc_cache_task", "")):
            continue
        label = str(attrs.get("rc_cache_label", key[:12]))
        kind = ("check" if label.startswith(QS_LABEL) else
                "law" if label.startswith("law") else "full")
        if entry.status != "ok":
            out.append({"label": label, "kind": kind, "solver": "failed",
                        "status": entry.result.message, "wall_time": entry.wall_time,
                        "newton_iterations": np.nan})
            continue
        res = entry.result
        status = np.atleast_1d(res["status"].values if "status" in res
                               else [res.attrs.get("status", "ok")]).astype(str)
        for i, st in enumerate(status):
            one = res.isel(velocity=i) if "velocity" in res.dims else res
            out.append({"label": label if status.size == 1 else f"{label} #{i}", "kind": kind,
                        "solver": str(res.attrs.get("solver", "?")) if st == "ok" or
                        status.size == 1 else "failed", "status": str(
                            res.attrs.get("status", st)) if status.size == 1 else st,
                        "wall_time": float(one["wall_time"]) if "wall_time" in one
                        else entry.wall_time,
                        "newton_iterations": float(one["newton_iterations"])
                        if "newton_iterations" in one else np.nan})
    return out


def _fem_signature(task: dict) -> str | None:
    """What a full-FEM task solves (surface, rubber, speed, load, cell), without the solver
    and its controls: the same for a steady and a time-stepped test of one problem."""
    kw = task["kwargs"]
    opts = kw.get("options", kw)              # older tasks: the options as keyword arguments
    if "min_creep_times" in kw or "min_sliding_time" in str(kw.get("transient", "")):
        return None
    cell = {k: opts.get(k) for k in ("mesh", "grading", "height_ratio", "contact_points")}
    cell["viscous_model"] = opts.get("viscous_model", "simo")
    return json.dumps([kw["surface"], kw["material"], kw["velocity"], kw["mean_pressure"],
                       cell], sort_keys=True)


def steady_vs_transient(cache: Path, keys, reference: Path) -> list[dict]:
    """The steady full-FEM solves among ``keys`` in ``cache`` next to the time-stepped test
    of the same problem in ``reference`` (the tracked solves of the earlier validation; the
    shortest slide where there are several): ``{label, velocity, steady, transient}`` with
    ``(friction, contact fraction, wall time)`` each."""
    import xarray as xr

    def read(path):
        with xr.open_dataset(path) as ds:
            task = json.loads(ds.attrs["rc_cache_task"])
            if not task["function"].endswith(":fem_task") or "wall_time" not in ds:
                return None
            values = tuple(float(ds[k]) for k in ("friction", "contact_fraction", "wall_time"))
            return (task, str(ds.attrs.get("solver", "transient")), values,
                    int(task["kwargs"].get("periods", {}).get("i", 0)))

    old = {}
    for path in sorted(reference.glob("sweep-v1/*/*.nc")):
        rec = read(path)
        if rec is None or rec[1] != "transient" or rec[0]["label"].startswith("law"):
            continue
        sig = _fem_signature(rec[0])
        if sig is not None and (sig not in old or rec[3] < old[sig][3]):
            old[sig] = rec
    out = []
    for key in sorted(keys):
        path = cache / "sweep-v1" / key[:2] / f"{key}.nc"
        rec = read(path) if path.exists() else None
        if rec is None or rec[1] != "steady" or rec[0]["label"].startswith("law"):
            continue
        match = old.get(_fem_signature(rec[0]))
        if match is not None:
            out.append({"label": rec[0]["label"],
                        "velocity": float(rec[0]["kwargs"]["velocity"]["f"]),
                        "steady": rec[2], "transient": match[2]})
    return out


def not_steady(solves: list[dict]) -> list[dict]:
    """The solves of :func:`fem_solves` that are not steady solutions (fallback, failed)."""
    return [s for s in solves if s["solver"] != "steady"]


def fem_solves_line(solves: list[dict]) -> str:
    """One sentence: how many FEM solves of a case were steady, which fell back or failed."""
    if not solves:
        return ""
    bad = not_steady(solves)
    cases = "; ".join(f"{s['label']} ({s['solver']}: {s['status']})" for s in bad)
    return render("validation", "fem_solves", n=len(solves),
                  steady=len(solves) - len(bad),
                  others=render("validation", "fem_solves_others", count=len(bad),
                                cases=cases) if bad else
                  render("validation", "fem_solves_none"))


_FEM_TIMES = re.compile(r"The (\d+) full-FEM tests took (\d+) s each \(median; (\d+)-(\d+) s\), "
                        r"the (\d+) law points (\d+) s on average")


def eq28_rows(text: str) -> dict:
    """``{(velocity, row label): (hybrid, windowed, VHS)}`` in per cent, read from the
    eq. 28 table of a section 3 report (Markdown as this module writes it)."""
    out, inside = {}, False
    for line in text.splitlines():
        if line.startswith("| velocity [mm/s] | realizations |"):
            inside = True
            continue
        if inside and not line.startswith("|"):
            break
        cells = [c.strip().strip("*") for c in line.strip("|").split("|")]
        if not inside or cells[0].startswith("---") or len(cells) < 5:
            continue
        values = []
        for c in cells[2:5]:
            m = re.match(r"\**([\d.]+) %", c)
            values.append(float(m.group(1)) if m else float("nan"))
        out[(cells[0], cells[1])] = tuple(values)
    return out


def _area_range(label: str) -> str:
    m = re.search(r"A = ([\d.]+-[\d.]+)", label)
    return f"A = {m.group(1)}" if m else "?"


def fem_times(text: str) -> tuple[str, str] | None:
    """``("404 s (213-956 s)", "108 s")``: the full-FEM and law-point times of a section 3
    report, or None."""
    m = _FEM_TIMES.search(text)
    if m is None:
        return None
    return f"{m.group(2)} s ({m.group(3)}-{m.group(4)} s)", f"{m.group(6)} s"


def what_changed(old: str, new: str) -> list[str]:
    """The 'What changed' section of VALIDATION.md: section 3's eq. 28 and FEM cost, from
    the frozen time-stepped report ``old`` and this run's ``new`` (both Markdown)."""
    before, after = eq28_rows(old), eq28_rows(new)
    if not before or not after:
        return []

    def kind(text):      # a row by its kind, whatever its N, R or area range
        return "plain" if text.isdigit() else text.split(":")[0].split(" (N")[0]

    out = [render("validation", "what_changed"), "",
           "| v [mm/s] | eq. 28 row | hybrid | windowed hybrid | VHS |", "|---|---|---|---|---|"]
    for key in before:
        if kind(key[1]) not in ("plain", "first 5", "phase-averaged",
                                "extended loads, all models"):
            continue
        new_key = next((k for k in after if k[0] == key[0] and kind(k[1]) == kind(key[1])),
                       None)
        if new_key is None:
            continue
        row = {"plain": f"all realizations ({key[1]} → {new_key[1]})",
               "first 5": "first 5 realizations (the same surfaces)",
               "phase-averaged": f"{key[1]} → {new_key[1]}".replace(
                   " → phase-averaged", " →")}.get(kind(key[1]))
        if row is None:
            row = f"{kind(key[1])}: {_area_range(key[1])} → {_area_range(new_key[1])}"
        out.append(f"| {key[0]} | {row} | " + " | ".join(
            f"{a:.1f} % → **{b:.1f} %**" for a, b in zip(before[key], after[new_key],
                                                        strict=True)) + " |")
    versus = next((line for line in new.splitlines()
                   if line.startswith("**Steady against time-stepped")), None)
    if versus:
        out += ["", versus]
    t_old, t_new = fem_times(old), fem_times(new)
    if t_old and t_new:
        out += ["", render("validation", "what_changed_cost", old_fem=t_old[0],
                           new_fem=t_new[0], old_law=t_old[1], new_law=t_new[1])]
    return out + [""]


def _asphalt_row(s, windowed: bool) -> str:
    def mu(m):
        return (f"{float(s['friction_mean'].sel(model=m)):.3f} "
                f"({float(s['friction_ls'].sel(model=m).mean()):.3f} + "
                f"{float(s['friction_hs'].sel(model=m).mean()):.3f})")

    row = (f"| {float(s['friction_mean'].sel(model='vhs')):.3f} | {mu('hybrid')} | "
           f"{float(s['contact_fraction_mean'].sel(model='vhs')):.4f} | "
           f"{float(s['contact_fraction_mean'].sel(model='hybrid')):.4f} |")
    if windowed:
        row += (f" {mu('hybrid-windowed')} | "
                f"{float(s['contact_fraction_mean'].sel(model='hybrid-windowed')):.4f} |")
    return row


_NUMBER_WORDS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight")


def asphalt_report(ds, wall, figs, msgs, level, short_share,
                   solves: list[dict] | None = None) -> list[str]:
    """Paper §4 on Table 2: the hybrid against the VHS, the law, the short waves' weight."""
    out = [render("validation_asphalt", "title"), "",
           render("validation_asphalt", "level", level=level,
                  realizations=ds.sizes["realization"], minutes=f"{wall / 60:.1f}")]
    win = "hybrid-windowed" in ds["model"].values
    out += ["", "| v [mm/s] | σ0 [MPa] | VHS μ | hybrid μ (μ_ls + μ_hs) | VHS A | hybrid A |"
            + (" windowed μ (μ_ls + μ_hs) | windowed A |" if win else ""),
            "|---|---|---|---|---|---|" + ("---|---|" if win else "")]
    for v in ds["velocity"].values:
        for p in ds["pressure"].values:
            out.append(f"| {v:g} | {p:g} " + _asphalt_row(ds.sel(velocity=v, pressure=p), win))
    out += ["", render("validation_asphalt", "fig7_intro"), "",
            "| v [mm/s] | p̄ [MPa] | FEM μ_hs | VHS μ | FEM α_hs |", "|---|---|---|---|---|"]
    for v in ds["velocity"].values:
        for p in ds["law_pressure"].values:
            s = ds.sel(velocity=v, law_pressure=p)
            out.append(f"| {v:g} | {p:g} | {float(s['law_friction']):.3f} | "
                       f"{float(s['law_vhs_friction']):.3f} | "
                       f"{float(s['law_contact_fraction']):.3f} |")
    kept = np.flatnonzero(ds["wavelength"].values > SHORT_WAVE_CUTOFF) + 1
    removed = int(ds.sizes["wave"] - kept.size)
    out += ["", render("validation_asphalt", "short_waves_intro",
                       removed=_NUMBER_WORDS[removed] if removed < len(_NUMBER_WORDS)
                       else removed, first=kept.min(), last=kept.max()), "",
            "| v [mm/s] | σ0 [MPa] | share |", "|---|---|---|"]
    for (v, p), share in short_share.items():
        out.append(f"| {v:g} | {p:g} | {100 * share:.0f} % |")
    out += ["", *cost_lines(ds), ""]
    if solves:
        out += [fem_solves_line(solves), ""]
    if law_lines(ds):
        out += [*law_lines(ds), ""]
    out += [f"![{f.stem}]({repo_path(f)})" for f in figs]
    return out + warning_lines(msgs) + [""]


def captif_report(ds, wall, figs, msgs, solves: list[dict] | None = None) -> list[str]:
    """The real CAPTIF road profiles end to end: the fitted series and every model."""
    surf = json.loads(ds.attrs["surface"])
    window = json.loads(ds.attrs["config"])["surface"]["profiles"].get("window") or 16.0
    out = [render("validation_captif", "title"), "",
           render("validation_captif", "fit", waves=ds.sizes["wave"], scans=surf.get("n_scans"),
                  window=f"{window:g}", dx=f"{surf.get('dx_mm', float('nan')):.4f}",
                  error=f"{surf.get('log10_rms_error', float('nan')):.3f}",
                  minutes=f"{wall / 60:.1f}"),
           "", "| λ [mm] | Δ [mm] | m2 | scale |", "|---|---|---|---|"]
    for lam, amp, m2, hs in zip(ds["wavelength"].values, ds["amplitude"].values,
                                ds["m2"].values, ds["high_slope"].values, strict=True):
        out.append(f"| {lam:g} | {amp:.4f} | {m2:.3f} | {'high' if hs else 'low'} |")
    out += ["", "| v [mm/s] | σ0 [MPa] | " + " | ".join(f"{m} μ | {m} A"
                                                       for m in ds["model"].values) + " |",
            "|---|---|" + "---|---|" * ds.sizes["model"]]
    for v in ds["velocity"].values:
        for p in ds["pressure"].values:
            s = ds.sel(velocity=v, pressure=p)
            cells = [f"{float(s['friction_mean'].sel(model=m)):.3f} | "
                     f"{float(s['contact_fraction_mean'].sel(model=m)):.4f}"
                     for m in ds["model"].values]
            out.append(f"| {v:g} | {p:g} | " + " | ".join(cells) + " |")
    if solves:
        out += ["", fem_solves_line(solves)]
    out += ["", *law_lines(ds)]
    out += [""] + [f"![{f.stem}]({repo_path(f)})" for f in figs]
    return out + warning_lines(msgs) + [""]
