"""Section 3 of VALIDATION.md (paper §3, the three-wave surface): the eq. 28 tables from the
results and the prose of ``templates/validation_section3.md`` filled with the numbers
computed here or in ``_compare``.

This module holds the eq. 28 tables, the comparisons at equal load and with the linear
law, and :func:`section3_report`, which puts the section together; the paragraphs before
the table are ``_section3_prose``, the phase-averaged FEM over the extended loads
``_section3_phase``.
"""

from __future__ import annotations

import json

import numpy as np

import rubbercontact as rc
from rubbercontact.hybrid.metrics import mean_relative_error

from ._compare import (
    INTERVAL_LEVEL,
    PAPER_E,
    PAPER_REALIZATIONS,
    RESAMPLES,
    eq28_first,
    eq28_phase_averaged,
    friction_at_common_areas,
    hybrid_with_linear_law,
)
from ._section3_phase import (
    _eq28_cells,
    beta_text,
    extended_rows,
    phase_average_sentence,
    plot_phase_curves,
    reach_sentence,
)
from ._section3_prose import _section3_prose, per_realization_sentence
from ._section3_text import _s3
from ._validation_report import (
    MODELS,
    cost_lines,
    interval_text,
    joined,
    law_lines,
    percent_off,
    repo_path,
    warning_lines,
)

__all__ = ["section3_report", "extended_rows", "plot_phase_curves", "beta_text",
           "per_realization_sentence"]


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
    if law_lines(ds):
        out += [*law_lines(ds), ""]
    out += [f"![{f.stem}]({repo_path(f)})" for f in figs]
    return out + warning_lines(msgs) + [""]
