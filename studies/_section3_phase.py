"""Section 3 of VALIDATION.md: the phase-averaged FEM over the extended loads.

The eq. 28 rows over the paper's area range and the sentences that explain them (the
control variate's β, the loads where the FEM cell shears, whether the area reaches the
paper's), and Fig. 5 over the extended loads.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rubbercontact.hybrid.metrics import regression_coefficient

from ._compare import (
    RESAMPLES,
    below_load,
    eq28_phase_averaged,
    phase_area_range,
    phase_mean_curves,
    without_model,
)
from ._section3_text import _s3
from ._validation_report import MODELS, interval_text, joined


def beta_text(phase_data: dict) -> str:
    """``β (s.d. of FEM − VHS → of FEM − β VHS)`` per velocity and load, for μ."""
    parts = []
    for v, data in phase_data.items():
        t, c = data["fem"][1], data["paired"]["vhs"][1]
        items = []
        for k in range(t.shape[1]):
            ok = np.isfinite(t[:, k]) & np.isfinite(c[:, k])
            tk, ck = t[ok, k], c[ok, k]
            b = regression_coefficient(tk, ck)
            items.append(_s3("beta_item", beta=f"{b:.2f}",
                             sd_difference=f"{np.std(tk - ck, ddof=1):.3f}",
                             sd_residual=f"{np.std(tk - b * ck, ddof=1):.3f}"))
        parts.append(_s3("beta_velocity", velocity=f"{v:g}", items=" / ".join(items)))
    return _s3("beta", parts="; ".join(parts))


def phase_average_sentence(phase_data: dict) -> str:
    """What the phase-averaged row of the eq. 28 table is, with the spreads that justify it."""
    def sd(x):
        return np.nanstd(x, axis=0, ddof=1)

    parts = []
    for v, data in phase_data.items():
        fem_mu, vhs_mu = data["fem"][1], data["paired"]["vhs"][1]
        win = data["paired"].get("hybrid-windowed", (None, None))[1]
        text = _s3("phase_average_velocity", velocity=f"{v:g}", sd_fem=joined(sd(fem_mu), ".3f"),
                   sd_difference=joined(sd(fem_mu - vhs_mu), ".3f"))
        if win is not None:
            corr = [np.corrcoef(fem_mu[:, k], win[:, k])[0, 1] for k in range(win.shape[1])]
            text += _s3("phase_average_correlation", correlations=joined(corr, ".2f"))
        parts.append(text)
    first = next(iter(phase_data.values()))
    return _s3("phase_average", n=first["all"]["vhs"][0].shape[0], r=first["fem"][0].shape[0],
               loads=joined(first["pressures"], "g"), parts="; ".join(parts),
               resamples=RESAMPLES, beta=beta_text(phase_data))


def sheared_fem_text(extended: dict, relaxed_shear_modulus: float) -> str:
    """The loads where the FEM's phase-averaged friction stress μσ0 exceeds the relaxed
    shear modulus: there its cell shears by more than 1 and creeps (the caveat)."""
    parts = []
    for v, data in extended.items():
        curves = phase_mean_curves(data)["phase"]
        fem, vhs, p = curves["fem"][1], curves["vhs"][1], data["pressures"]
        for k in np.flatnonzero(fem * p > relaxed_shear_modulus):
            text = _s3("sheared", velocity=f"{v:g}", pressure=f"{p[k]:g}",
                       stress=f"{fem[k] * p[k]:.2f}", modulus=f"{relaxed_shear_modulus:.2f}")
            if k > 0:
                text += _s3("sheared_step", previous=f"{p[k - 1]:g}",
                            fem_previous=f"{fem[k - 1]:.3f}", fem=f"{fem[k]:.3f}",
                            vhs_previous=f"{vhs[k - 1]:.3f}", vhs=f"{vhs[k]:.3f}")
            parts.append(text)
    if not parts:
        return ""
    text = "; ".join(parts)
    return (" " + text[0].upper() + text[1:] + ". " + _s3("extended_fem_caveat")
            + settled_estimate_text(extended))


#: The loads [MPa] at 50 mm/s of the time-stepped validation's settled estimate
#: (docs/validation/settled_loads.md), quoted in ``settled_estimate``.
SETTLED_ESTIMATE_LOADS = (0.8, 2.0)


def settled_estimate_text(extended: dict, velocity: float = 50.0) -> str:
    """The steady FEM's phase averages where the transient validation estimated them."""
    if velocity not in extended:
        return ""
    data = extended[velocity]
    curves = phase_mean_curves(data)["phase"]
    p = np.asarray(data["pressures"])
    ks = [np.flatnonzero(np.isclose(p, q)) for q in SETTLED_ESTIMATE_LOADS]
    if any(k.size == 0 for k in ks):
        return ""
    (low,), (high,) = ks
    area, mu = curves["fem"]
    return " " + _s3("settled_estimate", mu_low=f"{mu[low]:.3f}", mu_high=f"{mu[high]:.3f}",
                     area_high=f"{area[high]:.3f}")


def reach_sentence(ds, extended: dict, target: float = 0.1) -> str:
    """Whether the steady FEM's area reaches ``target`` at each speed: its phase average
    over the extended loads where there are some, else its realization mean."""
    parts, verdicts = [], []
    for v in ds["velocity"].values:
        v = float(v)
        if v in extended:
            area = phase_mean_curves(extended[v])["phase"]["fem"][0]
            p = np.asarray(extended[v]["pressures"])
        else:
            area = ds["contact_fraction_mean"].sel(model="fem", velocity=v).values
            p = ds["pressure"].values
        ok = np.isfinite(area)
        a, pk = area[ok], p[ok]
        k = int(np.argmax(a))
        if k < a.size - 1:
            trend = f"the largest is {a[k]:.3f} at {pk[k]:g} MPa: the area stops growing"
        elif a.size > 1:
            trend = f"up from {a[-2]:.3f} at {pk[-2]:g} MPa"
        else:
            trend = "the only load"
        parts.append(_s3("reach_velocity", area=f"{a[-1]:.3f}", velocity=f"{v:g}",
                         pressure=f"{pk[-1]:g}", trend=trend))
        if a.max() >= 0.95 * target:
            verdicts.append(_s3("reach_yes", velocity=f"{v:g}", target=f"{target:g}"))
        elif k < a.size - 1:
            verdicts.append(_s3("reach_saturated", velocity=f"{v:g}", target=f"{target:g}",
                                area=f"{a[k]:.3f}", pressure=f"{pk[k]:g}"))
        else:
            verdicts.append(_s3("reach_growing", velocity=f"{v:g}", target=f"{target:g}",
                                pressure=f"{pk[-1]:g}"))
    return _s3("reach", parts="; ".join(parts), verdict=" ".join(verdicts))


def _eq28_cells(e: dict, ci: dict, bold: bool = False) -> str:
    mark = "**" if bold else ""
    return " | ".join(f"{mark}{100 * e[m]:.1f} %{mark} ({interval_text(*ci[m])})"
                      if m in ci else "-" for m in MODELS)


def extended_rows(extended: dict, relaxed_shear_modulus: float) -> tuple[list[str], str]:
    """Eq. 28 table rows over the paper's area range, and the sentence that explains them
    (``relaxed_shear_modulus`` E∞/3 [MPa] of the rubber marks the loads where the FEM cell
    creeps into a bulk shear above 1)."""
    rows, ranges = [], []
    for v, data in extended.items():
        top = float(data["pressures"].max())
        for label, d in (("all models", data), ("without the pointwise hybrid",
                                                without_model(data, "hybrid")),
                         (f"below the top load ({top:g} MPa)", below_load(data, top))):
            e, ci = eq28_phase_averaged({v: d})[v]
            lo, hi = phase_area_range(d)
            rows.append(f"| {v:g} | extended loads, {label}: A = {lo:.3f}-{hi:.3f} | "
                        + _eq28_cells(e, ci) + " | |")
        r_fem = np.isfinite(data["fem"][1]).sum(axis=0)
        ranges.append(_s3("extended_velocity", velocity=f"{v:g}", loads=", ".join(
            f"{p:g} ({k})" for p, k in zip(data["pressures"], r_fem, strict=True))))
    n = next(iter(extended.values()))["all"]["vhs"][0].shape[0]
    text = (_s3("extended", ranges="; ".join(ranges), n=n)
            + sheared_fem_text(extended, relaxed_shear_modulus))
    return rows, text


def plot_phase_curves(extended: dict, path: Path) -> Path:
    """Fig. 5 over the extended loads: phase-averaged μ against A, every model.

    The FEM's points are the control-variate estimates, with ±1 standard error bars in μ
    (``control_variate_by_column``); the cheap models are means over all N.
    """
    from rubbercontact.hybrid.metrics import control_variate_by_column
    from rubbercontact.plotting.figures import _COLORS, _LABELS, _plt

    plt = _plt()
    nv = len(extended)
    fig, axes = plt.subplots(1, nv, figsize=(5.2 * nv, 4), squeeze=False)
    for ax, (v, data) in zip(axes[0], extended.items(), strict=True):
        curves = phase_mean_curves(data)["phase"]
        _, se = control_variate_by_column(data["fem"][1], data["paired"]["vhs"][1],
                                          data["all"]["vhs"][1])
        for m in ("vhs", "hybrid", "hybrid-windowed", "fem"):
            if m not in curves:
                continue
            a, mu = curves[m]
            ax.errorbar(a, mu, yerr=se if m == "fem" else None, fmt="o-",
                        color=_COLORS.get(m), label=_LABELS.get(m, m), capsize=3)
        ax.set_xscale("log")
        ax.set_xlabel("normalized contact area A_c/A_0 [-]")
        ax.set_ylabel("friction coefficient μ [-]")
        ax.set_title(f"v = {v:g} mm/s, phase averages (loads "
                     + ", ".join(f"{p:g}" for p in data["pressures"]) + " MPa)", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path
