"""Section 3 of VALIDATION.md (paper §3, the three-wave surface): the eq. 28 tables from the
results and the prose of ``templates/validation_section3.md`` filled with the numbers
computed here or in ``_compare``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.hybrid.metrics import mean_relative_error, regression_coefficient

from ._compare import (
    AREA_FACTORS,
    INTERVAL_LEVEL,
    PAPER_E,
    PAPER_REALIZATIONS,
    RESAMPLES,
    area_sensitivity,
    below_load,
    eq28_first,
    eq28_phase_averaged,
    friction_at_common_areas,
    hybrid_with_linear_law,
    per_realization_errors,
    phase_area_range,
    phase_mean_curves,
    without_model,
)
from ._templates import render
from ._validation_report import (
    MODELS,
    ROOT,
    cost_lines,
    interval_text,
    joined,
    not_steady,
    percent_off,
    repo_path,
    warning_lines,
)


def _sci(x: float) -> str:
    """``1.04e-4``: three digits, exponent without padding."""
    mantissa, exponent = f"{x:.2e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _mesh(m) -> str:
    return f"{m[0]} x {m[1]}"


#: The steady solver's time-step study (studies/steady_time_step.py), once it is written.
TIME_STEP_STUDY = ROOT / "docs" / "validation" / "steady_time_step.md"


def _s3(block: str, **fields) -> str:
    return render("validation_section3", block, **fields)


def _reduced_sentence(ds) -> str:
    """The quick level's reductions, with the meshes and the steady solver's time step."""
    cfg = json.loads(ds.attrs["config"])["fem"]
    period = float(ds.attrs["period_mm"])
    hs = ds["high_slope"].values.astype(bool)
    lam = float(ds["wavelength"].values[hs].min())
    law_cell = float(ds["wavelength"].values[hs].max())
    full_mesh = cfg.get("full_mesh") or cfg["mesh"]
    v_min, v_max = float(ds["velocity"].min()), float(ds["velocity"].max())
    h_full, h_law = period / full_mesh[0], law_cell / cfg["mesh"][0]
    time_step = _s3("time_step_study" if TIME_STEP_STUDY.exists() else "time_step_measured")
    return _s3("reduced", realizations=ds.sizes["realization"], loads=ds.sizes["pressure"],
               full_mesh=_mesh(full_mesh),
               full_grading=f"{cfg.get('full_grading') or cfg['grading']:g}",
               full_columns_per_wave=f"{full_mesh[0] * lam / period:g}", wavelength=f"{lam:g}",
               law_mesh=_mesh(cfg["mesh"]), law_grading=f"{cfg['grading']:g}",
               law_columns_per_wave=f"{cfg['mesh'][0] * lam / law_cell:g}",
               full_column=f"{1e3 * h_full:.3g}", law_column=f"{1e3 * h_law:.3g}",
               dt_full=_sci(h_full / v_min), dt_full_fast=_sci(h_full / v_max),
               dt_law=_sci(h_law / v_min), dt_law_fast=_sci(h_law / v_max),
               v_min=f"{v_min:g}", v_max=f"{v_max:g}", time_step=time_step)


def _fem_costs(ds) -> tuple[float, float]:
    """Median full-FEM test and mean law point [s] of this run (the original solves)."""
    t = ds["wall_time"].sel(model="fem").values
    cost = json.loads(ds.attrs["model_cpu_time_s"])
    n_law = ds.sizes["law_pressure"] * ds.sizes["velocity"]
    return float(np.median(t[np.isfinite(t)])), cost.get("law (FEM, counted once)", 0) / n_law


def versus_transient_text(pairs: list[dict]) -> str:
    """The steady full FEM against the time-stepped test of the same problem (measured)."""
    if not pairs:
        return ""
    parts = []
    for v in sorted({p["velocity"] for p in pairs}):
        sel = [p for p in pairs if p["velocity"] == v]
        mu = 100 * np.array([p["steady"][0] / p["transient"][0] - 1 for p in sel])
        a = 100 * np.array([p["steady"][1] / p["transient"][1] - 1 for p in sel])
        parts.append(_s3("versus_transient_velocity", velocity=f"{v:g}", n=len(sel),
                         mu_low=f"{mu.min():+.1f}", mu_high=f"{mu.max():+.1f}",
                         mu_median=f"{np.median(np.abs(mu)):.1f}", a_low=f"{a.min():+.1f}",
                         a_high=f"{a.max():+.1f}", a_median=f"{np.median(np.abs(a)):.1f}"))
    ratio = np.array([p["steady"][2] / p["transient"][2] for p in pairs])
    text = _s3("versus_transient", n=len(pairs), parts="; ".join(parts),
               cost=_s3("versus_transient_cost", ratio=f"{np.median(ratio):.2f}",
                        low=f"{ratio.min():.2f}", high=f"{ratio.max():.2f}"))
    worst = sorted(pairs, key=lambda p: -abs(p["steady"][0] / p["transient"][0] - 1))[:3]
    text += " " + _s3("versus_transient_creep", largest=", ".join(
        f"{p['label']} ({100 * (p['steady'][0] / p['transient'][0] - 1):+.1f} % in μ, "
        f"{100 * (p['steady'][1] / p['transient'][1] - 1):+.1f} % in A)" for p in worst))
    return text


def why240_sentence(ds) -> str:
    fem, law = _fem_costs(ds)
    return _s3("why240", law_cost=f"{law:.0f}", fem_cost=f"{fem:.0f}",
               law_share=f"{law / fem:.2f}")


def _rise_text(ds) -> str:
    """Where the law cell's ū rises with the load (the face lifting off), per speed."""
    parts = []
    p = ds["law_pressure"].values
    for v in ds["velocity"].values:
        u = ds["law_mean_separation"].sel(velocity=v).values
        up = np.flatnonzero(np.diff(u) >= 0)
        if up.size:
            k = int(up[0])
            sel = slice(max(k - 1, 0), None)
            parts.append(_s3("steady_rise", pressure=f"{p[k + 1]:g}", velocity=f"{v:g}",
                             separations=joined(1e3 * u[sel], ".1f"),
                             pressures=joined(p[sel], "g")))
    return "; ".join(parts) if parts else _s3("steady_rise_none")


def steady_sentence(ds, solves: list[dict] | None) -> str:
    """How the FEM of this run was solved: steady, fallen back, its settled bulk shear."""
    text = _s3("steady", solves="", shear="").rstrip()
    if solves:
        full = [s for s in solves if s["kind"] == "full"]
        law = [s for s in solves if s["kind"] == "law"]
        bad = not_steady(solves)
        newton = [s["newton_iterations"] for s in full if s["solver"] == "steady"]
        cases = "; ".join(f"{s['label']} ({s['solver']}: {s['status']})" for s in bad)
        text += " " + _s3(
            "steady_solves", n_full=len(full), n_law=len(law),
            full_steady=sum(s["solver"] == "steady" for s in full),
            law_steady=sum(s["solver"] == "steady" for s in law),
            full_newton=f"{np.median(newton):.0f}" if newton else "-",
            fallbacks=_s3("steady_fallbacks", count=len(bad), cases=cases) if bad
            else _s3("steady_no_fallback"))
    if "fem_bulk_shear" in ds and "law_bulk_shear" in ds:
        shear = ds["fem_bulk_shear"].values
        shear = shear[np.isfinite(shear)]
        law = ds["law_bulk_shear"]
        top = law["law_pressure"].values >= 4.0
        v = float(ds["velocity"].values[0])
        text += " " + _s3(
            "steady_shear", full_shear=f"{shear.min():.2f}-{shear.max():.2f}",
            law_shear=joined(law.sel(velocity=v).values[top], ".2f"),
            law_pressures=joined(law["law_pressure"].values[top], "g"),
            law_velocity=f"{v:g}", rise=_rise_text(ds))
    return text


def sampling_sentence(ds, target: float = 0.02) -> str:
    """How well the realizations pin down the FEM mean friction (measured spread)."""
    f = ds["friction"].sel(model="fem")
    n = ds.sizes["realization"]
    cv = (f.std("realization", ddof=1) / f.mean("realization")).max("pressure")
    parts = [_s3("sampling_velocity", velocity=f"{float(v):g}",
                 cv=f"{100 * float(cv.sel(velocity=v)):.0f}") for v in ds["velocity"].values]
    return _s3("sampling", parts=", ".join(parts), realizations=n,
               standard_error=f"{100 * float(cv.max()) / np.sqrt(n):.0f}",
               needed=int(np.ceil((float(cv.max()) / target) ** 2)),
               target=f"{100 * target:.0f}")


def per_realization_sentence(ds) -> str:
    """Eq. 28 within each realization, next to the paper's comparison of means (measured)."""
    if "pressure" not in ds.dims or "fem" not in ds["model"].values:
        return ""
    parts = []
    for v, errs in per_realization_errors(ds).items():
        cells = []
        for m, e in errs.items():
            e = np.asarray(e)
            ok = e[np.isfinite(e)]
            name = "windowed hybrid" if m == "hybrid-windowed" else "VHS"
            if not ok.size:
                cells.append(_s3("per_realization_undefined", model=name))
                continue
            partial = (_s3("per_realization_partial", defined=ok.size, realizations=e.size)
                       if ok.size < e.size else "")
            cells.append(_s3("per_realization_model", model=name,
                             median=f"{100 * np.median(ok):.1f}", low=f"{100 * ok.min():.1f}",
                             high=f"{100 * ok.max():.1f}", partial=partial))
        parts.append(_s3("per_realization_velocity", velocity=f"{v:g}", cells=", ".join(cells)))
    return _s3("per_realization", parts="; ".join(parts))


def area_sensitivity_text(ds) -> str:
    """How eq. 28 of the windowed hybrid moves with a bias in the FEM area (measured)."""
    sens = area_sensitivity(ds)
    v = max(sens[1.0])
    scaled = [f for f in AREA_FACTORS if f != 1.0]

    def errors(model):
        return " / ".join(f"{100 * sens[f][v][model]:.1f}" for f in scaled)

    return _s3("area_sensitivity", velocity=f"{v:g}", factors=joined(scaled, "g"),
               windowed=f"{100 * sens[1.0][v]['hybrid-windowed']:.1f}",
               windowed_scaled=errors("hybrid-windowed"),
               vhs=f"{100 * sens[1.0][v]['vhs']:.1f}", vhs_scaled=errors("vhs"))


def _fem_area_sentence(ds) -> str:
    cfg = json.loads(ds.attrs["config"])["fem"]
    return _s3("fem_area", sensitivity=area_sensitivity_text(ds),
               contact_points=cfg["contact_points"])


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


def area_at_equal_load_sentence(ds) -> str:
    """The windowed hybrid against the FEM at equal load, area and friction (measured)."""
    m = ds.sel(model="hybrid-windowed")
    f = ds.sel(model="fem")
    ra = m["contact_fraction_mean"] / f["contact_fraction_mean"]
    rm = m["friction_mean"] / f["friction_mean"]
    parts = "; ".join(_s3("area_not_friction_velocity", velocity=f"{float(v):g}",
                          area=percent_off(ra.sel(velocity=v).values),
                          mu=percent_off(rm.sel(velocity=v).values))
                      for v in ds["velocity"].values)
    return _s3("area_not_friction", loads=joined(ds["pressure"].values, "g"), parts=parts)


def spread_sentence(ds) -> str:
    """How far the models' friction varies between realizations at one load (measured)."""
    f = ds["friction"]
    spread = {m: float((f.sel(model=m).max("realization")
                        / f.sel(model=m).min("realization")).max())
              for m in ("fem", "vhs", "hybrid-windowed") if m in ds["model"].values}
    v = float(ds["velocity"].values[0])
    low = int(f.sel(model="fem", velocity=v).mean("pressure").argmin("realization"))
    cells = {m: "/".join(f"{x:.3f}" for x in f.sel(model=m, velocity=v, realization=low).values)
             for m in spread}
    return _s3("spread", fem=f"{spread['fem']:.2f}", vhs=f"{spread['vhs']:.2f}",
               windowed=f"{spread['hybrid-windowed']:.2f}", realization=low, velocity=f"{v:g}",
               fem_cells=cells["fem"], vhs_cells=cells["vhs"],
               windowed_cells=cells["hybrid-windowed"])


def linear_law_area_sentence(ds, lin: dict) -> str:
    """The windowed reading's area excess with the linear law, against the VHS (measured)."""
    vhs = ds["contact_fraction_mean"].sel(model="vhs")
    parts = [_s3("linear_law_area_velocity", velocity=f"{float(v):g}", excess=percent_off(
        [lin[(float(v), float(p))]["hybrid-windowed"][1] for p in ds["pressure"].values]
        / vhs.sel(velocity=v).values)) for v in ds["velocity"].values]
    text = _s3("linear_law_area", parts="; ".join(parts))
    if "fem" in ds["model"].values:
        r = ds["contact_fraction_mean"].sel(model="fem") / vhs
        text += " " + _s3("linear_law_area_fem", parts="; ".join(
            _s3("linear_law_area_velocity", velocity=f"{float(v):g}",
                excess=percent_off(r.sel(velocity=v).values)) for v in ds["velocity"].values))
    return text


def _eq28_table(ds, phase_data: dict | None) -> list[str]:
    """The eq. 28 table at equal area: all realizations, the paper's first 5, and the
    phase-averaged rows (difference and fitted-β control variate)."""
    at_areas = friction_at_common_areas(ds)
    phase = eq28_phase_averaged(phase_data) if phase_data else {}
    phase_beta = eq28_phase_averaged(phase_data, beta="regression") if phase_data else {}
    out = ["| velocity [mm/s] | realizations | hybrid vs FEM | windowed hybrid vs FEM "
           "| VHS vs FEM | paper (hybrid) |", "|---|---|---|---|---|---|"]
    n = ds.sizes["realization"]
    tables = [(n, eq28_first(ds))]
    if n > PAPER_REALIZATIONS:    # the paper's count, for comparison
        tables.append((f"first {PAPER_REALIZATIONS}", eq28_first(ds, PAPER_REALIZATIONS)))
    for v in at_areas:
        paper = PAPER_E.get(float(v))
        for k, (label, table) in enumerate(tables):
            if v not in table:
                continue
            _areas, e, ci = table[v]
            out.append(f"| {v:g} | {label} | " + " | ".join(
                f"{100 * e.get(m, np.nan):.1f} %"
                + (f" ({interval_text(*ci[m])})" if m in ci else "") for m in MODELS)
                + f" | {'' if paper is None or k else f'{100 * paper:.1f} %'} |")
        if v in phase:
            n_all = phase_data[v]["all"]["vhs"][0].shape[0]
            out.append(f"| {v:g} | phase-averaged (N = {n_all}) | "
                       + _eq28_cells(*phase[v], bold=True) + " | |")
            out.append(f"| {v:g} | phase-averaged, fitted β | "
                       + _eq28_cells(*phase_beta[v]) + " | |")
    return out


def _per_load_tables(ds) -> list[str]:
    models = list(ds["model"].values)
    out = ["", _s3("at_areas_intro"), "",
           "| v [mm/s] | A_c/A_0 | " + " | ".join(models) + " |",
           "|---|---|" + "---|" * len(models)]
    for v, (areas, mus) in friction_at_common_areas(ds).items():
        for k, a in enumerate(areas):
            out.append(f"| {v:g} | {a:.3f} | "
                       + " | ".join(f"{mus[m][k]:.3f}" for m in models) + " |")
    if "pressure" in ds.dims:
        out += ["", _s3("per_load_intro"), "",
                "| v [mm/s] | σ0 [MPa] | " + " | ".join(f"{m} μ | {m} A" for m in models)
                + " |", "|---|---|" + "---|---|" * len(models)]
        for v in ds["velocity"].values:
            for p in ds["pressure"].values:
                s = ds.sel(velocity=v, pressure=p)
                out.append(f"| {v:g} | {p:g} | " + " | ".join(
                    f"{float(s['friction_mean'].sel(model=m)):.3f} | "
                    f"{float(s['contact_fraction_mean'].sel(model=m)):.4f}" for m in models)
                    + " |")
    return out


def _linear_law_table(ds) -> list[str]:
    """The hybrids with the FEM law and with the linear law, next to the VHS (and FEM)."""
    models = list(ds["model"].values)
    fem = "fem" in models
    lin = hybrid_with_linear_law(ds)
    out = ["", _s3("linear_law", spread=spread_sentence(ds)), "",
           _s3("linear_law_table_intro"), "",
           "| v [mm/s] | σ0 [MPa] | hybrid (FEM law) | hybrid (linear law) "
           "| windowed (FEM law) | windowed (linear law) | VHS |" + (" FEM |" if fem else ""),
           "|---|---|---|---|---|---|---|" + ("---|" if fem else "")]
    for (v, p), lin_vp in lin.items():
        s = ds.sel(velocity=v, pressure=p)

        def cell(m, s=s):
            return (f"{float(s['friction_mean'].sel(model=m)):.3f} "
                    f"({float(s['contact_fraction_mean'].sel(model=m)):.4f})")

        out.append(f"| {v:g} | {p:g} | {cell('hybrid')} | "
                   f"{lin_vp['hybrid'][0]:.3f} ({lin_vp['hybrid'][1]:.4f}) | "
                   + (f"{cell('hybrid-windowed')} | " if "hybrid-windowed" in models else "| ")
                   + f"{lin_vp['hybrid-windowed'][0]:.3f} "
                   f"({lin_vp['hybrid-windowed'][1]:.4f}) | {cell('vhs')} |"
                   + (f" {cell('fem')} |" if fem else ""))
    if "hybrid-windowed" in models:
        out += ["", linear_law_area_sentence(ds, lin)]
    return out


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


def _section3_prose(ds, wall: float, level: str, solves: list[dict] | None,
                    pairs: list[dict] | None = None) -> list[str]:
    """The paragraphs before the eq. 28 table: what the quick level reduces and why."""
    out = [_s3("level", level=level, realizations=ds.sizes["realization"],
               velocities=ds["velocity"].values.tolist(),
               fem=json.loads(ds.attrs["config"])["fem"], minutes=f"{wall / 60:.1f}")]
    if level == "quick":
        out += ["", _reduced_sentence(ds), "", why240_sentence(ds), "",
                steady_sentence(ds, solves), *(["", versus_transient_text(pairs)] if pairs
                                               else []),
                "", sampling_sentence(ds), "", per_realization_sentence(ds),
                "", _fem_area_sentence(ds), "", _s3("below_vhs"), "", _s3("material_model")]
    return out


def section3_report(ds, wall, figs, msgs, level, phase_data: dict | None = None,
                    extended: dict | None = None,
                    solves: list[dict] | None = None,
                    pairs: list[dict] | None = None) -> list[str]:
    """Paper §3: eq. 28 of every model against the full FEM, and what limits it (``solves``:
    ``fem_solves`` of the run; ``pairs``: ``steady_vs_transient``)."""
    out = [_s3("title"), "", *_section3_prose(ds, wall, level, solves, pairs)]
    out += ["", _s3("eq28_intro", level=f"{100 * INTERVAL_LEVEL:.0f}", resamples=RESAMPLES,
                    paper_realizations=PAPER_REALIZATIONS), "", *_eq28_table(ds, phase_data)]
    extended_text = None
    if extended:
        mat = rc.materials.GeneralizedMaxwell(**json.loads(ds.attrs["material"]))
        rows, extended_text = extended_rows(extended, mat.equilibrium_modulus / 3)
        out += rows
        extended_text += " " + reach_sentence(ds, extended)
        if figs:
            fig = plot_phase_curves(extended, figs[0].parent / "fig5_phase_averaged.png")
            extended_text += " " + _s3("fig5_phase", stem=fig.stem, path=repo_path(fig))
    if phase_data:
        out += ["", phase_average_sentence(phase_data)]
    if extended_text:
        out += ["", extended_text]
    models = list(ds["model"].values)
    if "pressure" in ds.dims and "fem" in models:
        e_p = {m: [mean_relative_error(ds["friction_mean"].sel(model="fem", velocity=v).values,
                                       ds["friction_mean"].sel(model=m, velocity=v).values)
                   for v in ds["velocity"].values] for m in MODELS if m in models}
        out += ["", _s3("equal_sigma", parts="; ".join(
            f"{m} " + " / ".join(f"{100 * x:.1f} %" for x in vals) for m, vals in e_p.items()),
            velocities=ds["velocity"].values.tolist())]
        if "hybrid-windowed" in models:
            out += ["", area_at_equal_load_sentence(ds)]
    out += _per_load_tables(ds)
    if "pressure" in ds.dims and "hybrid" in models:
        out += _linear_law_table(ds)
    out += ["", *cost_lines(ds), ""]
    out += [f"![{f.stem}]({repo_path(f)})" for f in figs]
    return out + warning_lines(msgs) + [""]
