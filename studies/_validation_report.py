"""The words of VALIDATION.md shared by its cases, and the asphalt and CAPTIF reports:
tables from the results, prose from ``templates/validation*.md`` (section 3:
``_section3_report``).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

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


def asphalt_report(ds, wall, figs, msgs, level, short_share) -> list[str]:
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
    out += [f"![{f.stem}]({repo_path(f)})" for f in figs]
    return out + warning_lines(msgs) + [""]


def captif_report(ds, wall, figs, msgs) -> list[str]:
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
    out += [""] + [f"![{f.stem}]({repo_path(f)})" for f in figs]
    return out + warning_lines(msgs) + [""]
