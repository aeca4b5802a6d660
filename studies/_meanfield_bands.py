"""Where the strips' friction goes wrong at 500 mm/s: the dissipation by wavenumber band.

The exact identity ``μσ0 = Σ_k var σ_k · (−2 Im[1/E_r(kv)])`` (1D) splits the BEM's friction
into octave bands centred on the waves of a ladder and the bands above its cut-off; the
strip cascade's friction splits the same way (the loss set to zero outside a band). Part
``bands`` of studies/meanfield.py: the random 8-wave ladder (seed 3), the load of the
diffusion's 2 %, at 1 and 500 mm/s, 8 realizations (the study's 1D rows' BEM).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.meanfield.bands import (
    band_power,
    contact_patches,
    pressure_power,
    strip_bands,
)
from rubbercontact.meanfield.strips import strip_contact

from ._meanfield_cases import load_for_area, random_ladder
from ._rows import append_row

SBR = rc.materials.sbr()
LADDER = (8, 3)                   # (waves, seed): the ladder worst at 500 mm/s
SPEEDS = (1.0, 500.0)
TARGET, N, REALIZATIONS, SEED = 0.02, 16384, 8, 1
TAIL_OCTAVES = 6                  # bands above the cut-off, one octave each
TRUNCATED = (1, 2, 3, 4, 6, 8)    # the ladder's longest waves kept, at 500 mm/s
#: Two waves, the longest 4 mm (rms slope 0.3 each): wavelength ratios, speeds [mm/s] and the
#: diffusion's contact fractions at which the long strips' layer is checked.
LAYER_RATIOS, LAYER_SPEEDS, LAYER_TARGETS = (16.0, 4.0, 2.0), (1.0, 50.0), (0.06, 0.2)
#: The ladder's three longest waves (8, 4, 2 mm), by pairs and together, at 500 mm/s and
#: these loads [MPa]: where the cascade's error first appears.
TRIPLET_SUBSETS, TRIPLET_LOADS = ((8.0, 4.0), (8.0, 2.0), (4.0, 2.0), (8.0, 4.0, 2.0)), \
    (0.2, 0.4, 0.8)


def two_waves(ratio: float) -> rc.roughness.SineSeries:
    """A 4 mm wave and one ``ratio`` times shorter, rms slope 0.3 each."""
    lam = np.array([4.0, 4.0 / ratio])
    return rc.roughness.SineSeries(lam, 0.3 * np.sqrt(2) * lam / (2 * np.pi))


def _below(surf) -> float:
    """The band edge between the two waves, ``√(q1 q2)`` [rad/mm]."""
    return float(np.sqrt(np.prod(surf.wavenumbers)))


def band_edges(q: np.ndarray) -> np.ndarray:
    """Octave bands centred on the sorted wavenumbers ``q`` [rad/mm], then
    :data:`TAIL_OCTAVES` octaves above the last band; open at 0 and ∞."""
    return np.concatenate([[0.0], q * 2**-0.5, q[-1] * 2**0.5 * 2.0 ** np.arange(TAIL_OCTAVES),
                           [np.inf]])


def _loss(k: np.ndarray, v: float) -> np.ndarray:
    """``−2 Im[1/E_r(kv)]`` [1/MPa] (ν = 0.5), 0 at ``k = 0``."""
    out = -2.0 * np.imag(1.0 / (SBR.complex_modulus(k * v) / 0.75))
    return np.where(k > 0, out, 0.0)


def _bem_solves(surf, row: dict) -> tuple[float, list]:
    """The load of the diffusion's ``row["target"]`` contact fraction at ``row["v"]`` and
    the BEM's solves of :data:`REALIZATIONS` random-phase realizations there."""
    p = load_for_area(mf.PSD.from_sines(surf), SBR, row["v"], row["target"])
    return p, [rc.halfspace.solve_sliding(r, surf.period, SBR, row["v"], p, n=N)
               for r in surf.realizations(REALIZATIONS, SEED)]


def run_bands(rows_path: Path, done: set, key) -> None:
    """BEM pressure spectra pooled in the bands (dissipation and variance per band)."""
    m, seed = LADDER
    surf = random_ladder(m, seed)
    edges = band_edges(np.sort(surf.wavenumbers))
    rows = [{"kind": "bands", "case": f"random {m} waves (seed {seed})", "v": v,
             "target": TARGET, "n": N} for v in SPEEDS]
    for row in (r for r in rows if key(r) not in done):
        v = row["v"]
        p, solves = _bem_solves(surf, row)
        diss = band_power(solves, surf.period, edges, lambda k, v=v: _loss(k, v)) / p
        row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                   bem_mu=[res.friction for res in solves],
                   bem_A=[res.contact_fraction for res in solves], band_diss=diss.tolist(),
                   band_var=band_power(solves, surf.period, edges).tolist())
        append_row(rows_path, row)


def run_truncated(rows_path: Path, done: set, key) -> None:
    """The ladder's longest ``k`` waves (:data:`TRUNCATED`) at 500 mm/s and the full ladder's
    load: the BEM's pressure variance by band as the shorter waves are added."""
    m, seed = LADDER
    full = random_ladder(m, seed)
    order = np.argsort(full.wavenumbers)
    v = SPEEDS[-1]
    p = load_for_area(mf.PSD.from_sines(full), SBR, v, TARGET)
    for k in TRUNCATED:
        row = {"kind": "bands_truncated", "case": f"random {m} waves (seed {seed})", "v": v,
               "target": TARGET, "n": N, "seed": k}
        if key(row) in done:
            continue
        idx = np.sort(order[:k])
        surf = rc.roughness.SineSeries(np.asarray(full.wavelengths)[idx],
                                       np.asarray(full.amplitudes)[idx])
        solves = [rc.halfspace.solve_sliding(r, full.period, SBR, v, p, n=N)
                  for r in surf.realizations(REALIZATIONS, SEED)]
        var = band_power(solves, full.period, band_edges(np.sort(full.wavenumbers)))
        row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                   bem_A=[res.contact_fraction for res in solves], band_var=var.tolist())
        append_row(rows_path, row)


def run_layer(rows_path: Path, done: set, key) -> None:
    """The BEM's pressure variance below the shorter wave's band on :func:`two_waves`: what
    the long wave's strips carry once they sit on the short wave's strips."""
    for ratio in LAYER_RATIOS:
        surf = two_waves(ratio)
        rows = [{"kind": "layer", "case": f"2 waves, ratio {ratio:g}", "v": v,
                 "target": target, "n": N} for v in LAYER_SPEEDS for target in LAYER_TARGETS]
        for row in (r for r in rows if key(r) not in done):
            p, solves = _bem_solves(surf, row)
            var = [float(np.sum(power[k < _below(surf)])) for k, power in
                   (pressure_power(res.pressure, surf.period) for res in solves)]
            row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                       bem_A=[res.contact_fraction for res in solves], bem_var_long=var)
            append_row(rows_path, row)


def run_patches(rows_path: Path, done: set, key) -> None:
    """The BEM's contact patches on the worst ladder at the diffusion's 2 % load: how many
    per period and how wide, against the strips' final strips."""
    m, seed = LADDER
    surf = random_ladder(m, seed)
    rows = [{"kind": "patches", "case": f"random {m} waves (seed {seed})", "v": v,
             "target": TARGET, "n": N} for v in SPEEDS]
    for row in (r for r in rows if key(r) not in done):
        p, solves = _bem_solves(surf, row)
        row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                   bem_A=[res.contact_fraction for res in solves],
                   widths=[contact_patches(res.pressure, surf.period).tolist()
                           for res in solves])
        append_row(rows_path, row)


def patches_table(rows) -> str:
    """Patches per period and their area-weighted width: the BEM's and the strips'."""
    sel = sorted((r for r in rows if r["kind"] == "patches"), key=lambda r: r["v"])
    if not sel:
        return ""
    lines = ["| v [mm/s] | σ0 [MPa] | BEM A | strips A | BEM patches per period | strips "
             "per period | BEM width (area-weighted) [mm] | strips width [mm] |",
             "|---" * 8 + "|"]
    for r in sel:
        surf = rc.roughness.SineSeries(r["surface"]["wavelengths"], r["surface"]["amplitudes"])
        widths = np.concatenate([np.asarray(w) for w in r["widths"]])
        smp = strip_contact(surf.wavenumbers, surf.amplitudes, SBR, r["v"], r["p"]).samples
        full = 2 * smp.half_width
        lines.append(f"| {r['v']:g} | {r['p']:.4g} | {np.mean(r['bem_A']):.4f} | "
                     f"{smp.weight.sum():.4f} | {widths.size / len(r['widths']):.1f} | "
                     f"{np.sum(smp.weight / full) * surf.period:.1f} | "
                     f"{np.sum(widths**2) / np.sum(widths):.3f} | "
                     f"{np.sum(smp.weight * full) / smp.weight.sum():.3f} |")
    return "\n".join(lines)


def layer_table(rows) -> tuple[str, dict]:
    """BEM against strips: the variance below the shorter wave's band on two waves."""
    sel = [r for r in rows if r["kind"] == "layer"]
    if not sel:
        return "", {"layer_err": "–"}
    lines = ["| profile | v [mm/s] | σ0 [MPa] | BEM A | strips A | BEM var/σ0² below the "
             "short wave's band (± s.e.) | strips | error |", "|---" * 8 + "|"]
    errs = []
    for r in sel:
        surf = rc.roughness.SineSeries(r["surface"]["wavelengths"], r["surface"]["amplitudes"])
        p, var = r["p"], np.asarray(r["bem_var_long"]) / r["p"] ** 2
        edges = np.array([0.0, _below(surf), np.inf])
        strips = strip_bands(surf, SBR, r["v"], p, edges, unit=True)[0] / p**2
        area = strip_contact(surf.wavenumbers, surf.amplitudes, SBR, r["v"], p)
        errs.append(strips / var.mean() - 1)
        lines.append(f"| {r['case']} | {r['v']:g} | {p:.4g} | {np.mean(r['bem_A']):.4f} | "
                     f"{area.samples.weight.sum():.4f} | {var.mean():.3f} ± "
                     f"{var.std(ddof=1) / np.sqrt(var.size):.3f} | {strips:.3f} | "
                     f"{errs[-1]:+.0%} |".replace("%", " %"))
    e = np.array(errs) * 100
    return "\n".join(lines), {"layer_err": f"{e.mean():+.0f} % [{e.min():+.0f} %, "
                                            f"{e.max():+.0f} %]"}


def truncated_table(rows) -> tuple[str, dict]:
    """The pressure variance in the bands of the three longest waves as the ladder's shorter
    waves are added: the BEM's against the strips' (which book it when the wave is added)."""
    sel = sorted((r for r in rows if r["kind"] == "bands_truncated"), key=lambda r: r["seed"])
    if not sel:
        return "", {}
    m, seed = LADDER
    full = random_ladder(m, seed)
    q = np.sort(full.wavenumbers)
    edges = band_edges(q)
    lines = ["| waves kept (longest first) | BEM A | strips A | "
             + " | ".join(f"{2 * np.pi / q[b]:g} mm band: BEM var/σ0² | strips" for b in range(3))
             + " |", "|---" * 9 + "|"]
    first = last = None
    for r in sel:
        p = r["p"]
        surf = rc.roughness.SineSeries(r["surface"]["wavelengths"], r["surface"]["amplitudes"])
        strip = strip_bands(surf, SBR, r["v"], p, edges, unit=True) / p**2
        area = strip_contact(surf.wavenumbers, surf.amplitudes, SBR, r["v"], p)
        bem = np.asarray(r["band_var"]) / p**2
        cells = [f"{r['seed']}", f"{np.mean(r['bem_A']):.4f}",
                 f"{area.contact_fraction[np.argmax(surf.wavenumbers)]:.4f}"]
        for b in range(1, 4):
            cells += [f"{bem[b]:.2f}", f"{strip[b]:.2f}"]
        lines.append("| " + " | ".join(cells) + " |")
        first = first if first is not None else (bem[1:4].sum(), strip[1:4].sum())
        last = (bem[1:4].sum(), strip[1:4].sum())
    return "\n".join(lines), {"trunc_bem_first": f"{first[0]:.2f}",
                               "trunc_strips_first": f"{first[1]:.2f}",
                               "trunc_bem_last": f"{last[0]:.2f}",
                               "trunc_strips_last": f"{last[1]:.2f}"}


def bands_table(rows) -> tuple[str, dict]:
    """Per band (centred on a wave, then above the cut-off): the loss, the BEM's and the
    strips' friction and pressure variance, at each speed of the ``bands`` rows."""
    sel = sorted((r for r in rows if r["kind"] == "bands"), key=lambda r: r["v"])
    if not sel:
        return "", {}
    surf = rc.roughness.SineSeries(sel[0]["surface"]["wavelengths"],
                                   sel[0]["surface"]["amplitudes"])
    order = np.argsort(surf.wavenumbers)
    q = surf.wavenumbers[order]
    m2 = np.asarray(surf.rms_slopes())[order]
    edges = band_edges(q)
    head = "| band | " + " | ".join(
        f"{r['v']:g} mm/s: loss [1/MPa] | BEM μ | strips μ | BEM var/σ0² | strips var/σ0²"
        for r in sel) + " |"
    lines = [head, "|" + "---|" * (1 + 5 * len(sel))]
    cols, fields = [], {}
    centres = np.sqrt(edges[1:-2] * edges[2:-1])
    for r in sel:
        v, p = r["v"], r["p"]
        c = {"mu": strip_bands(surf, SBR, v, p, edges),
             "var": strip_bands(surf, SBR, v, p, edges, unit=True) / p**2,
             "bem_mu": np.asarray(r["band_diss"]), "bem_var": np.asarray(r["band_var"]) / p**2,
             "loss": _loss(np.concatenate([q, centres[q.size:]]), v)}
        cols.append(c)
        tag = "slow" if v <= 1.0 else "fast"
        long = slice(1, 4)                     # the bands of the three longest waves
        tail = slice(q.size + 1, None)
        fields.update({
            f"bands_mu_{tag}": f"{c['bem_mu'].sum():.3f}",
            f"bands_strips_{tag}": f"{c['mu'].sum():.3f}",
            f"bands_long_var_{tag}": f"{c['var'][long].sum() / c['bem_var'][long].sum():.1f}",
            f"bands_long_mu_{tag}": f"{c['mu'][long].sum() / c['bem_mu'][long].sum():.1f}",
            f"bands_tail_var_{tag}": f"{c['bem_var'][tail].sum() / c['bem_var'].sum():.0%}",
            f"bands_tail_strips_{tag}": f"{c['var'][tail].sum() / c['var'].sum():.0%}",
            f"bands_total_var_{tag}": f"{c['var'].sum() / c['bem_var'].sum():.2f}"})
    for b in range(1, edges.size - 1):
        label = (f"{2 * np.pi / q[b - 1]:g} mm (m2 = {m2[b - 1]:.2f})" if b <= q.size
                 else f"above the cut-off, × {2 ** (b - q.size)}")
        cells = [label]
        for c in cols:
            cells += [f"{c['loss'][b - 1]:.3f}" if b - 1 < c["loss"].size else "",
                      f"{c['bem_mu'][b]:.3f}", f"{c['mu'][b]:.3f}",
                      f"{c['bem_var'][b]:.2f}", f"{c['var'][b]:.2f}"]
        lines.append("| " + " | ".join(cells) + " |")
    cells = ["total"]
    for c in cols:
        cells += ["", f"{c['bem_mu'].sum():.3f}", f"{c['mu'].sum():.3f}",
                  f"{c['bem_var'].sum():.2f}", f"{c['var'].sum():.2f}"]
    lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines), fields


def _triplet_surface(keep) -> rc.roughness.SineSeries:
    full = random_ladder(*LADDER)
    lam = np.asarray(full.wavelengths)
    idx = [int(np.argmin(np.abs(lam - k))) for k in keep]
    return rc.roughness.SineSeries(lam[idx], np.asarray(full.amplitudes)[idx])


def _triplet_edges() -> np.ndarray:
    return band_edges(2 * np.pi / np.array([8.0, 4.0, 2.0]))


def run_triplets(rows_path: Path, done: set, key) -> None:
    """The BEM on the ladder's three longest waves, by pairs and together (8 mm period),
    with its pressure variance by band."""
    v, edges = SPEEDS[-1], _triplet_edges()
    for keep in TRIPLET_SUBSETS:
        for p in TRIPLET_LOADS:
            row = {"kind": "triplet", "case": " + ".join(f"{k:g}" for k in keep) + " mm",
                   "v": v, "target": p, "n": N}
            if key(row) in done:
                continue
            surf = _triplet_surface(keep)
            solves = [rc.halfspace.solve_sliding(r, 8.0, SBR, v, p, n=N)
                      for r in surf.realizations(REALIZATIONS, SEED)]
            row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                       bem_mu=[res.friction for res in solves],
                       bem_A=[res.contact_fraction for res in solves],
                       band_var=band_power(solves, 8.0, edges).tolist())
            append_row(rows_path, row)


def triplets_table(rows) -> tuple[str, dict]:
    """BEM against strips on the pairs and the triplet, and the strips without outer crests
    beside them; the 2 mm band and the octave above on the triplet."""
    sel = [r for r in rows if r["kind"] == "triplet"]
    if not sel:
        return "", {}
    edges = _triplet_edges()
    lines = ["| waves | σ0 [MPa] | BEM μ (± s.e.) | strips μ | error | without outer crests: "
             "μ | error | BEM A | strips A | 2 mm band: BEM var/σ0² | strips | next octave: "
             "BEM | strips |", "|---" * 13 + "|"]
    errs: dict[bool, list] = {True: [], False: []}
    nested_errs: dict[bool, list] = {True: [], False: []}
    ratios: list[tuple[float, float]] = []
    for r in sel:
        surf = rc.roughness.SineSeries(r["surface"]["wavelengths"], r["surface"]["amplitudes"])
        res, nested = (strip_contact(surf.wavenumbers, surf.amplitudes, SBR, r["v"], r["p"],
                                     outer_crests=outer) for outer in (True, False))
        mu, mu_nested = (float(x.friction_stress.sum()) / r["p"] for x in (res, nested))
        bem = np.asarray(r["bem_mu"])
        err, err_nested = mu / bem.mean() - 1, mu_nested / bem.mean() - 1
        three = surf.wavenumbers.size == 3
        errs[three].append(err)
        nested_errs[three].append(err_nested)
        cells = ["–"] * 4
        if three:
            strips = strip_bands(surf, SBR, r["v"], r["p"], edges, unit=True) / r["p"] ** 2
            bem_var = np.asarray(r["band_var"]) / r["p"] ** 2
            cells = [f"{bem_var[3]:.2f}", f"{strips[3]:.2f}", f"{bem_var[4]:.2f}",
                     f"{strips[4]:.2f}"]
            ratios.append((strips[3] / bem_var[3], strips[4] / bem_var[4]))
        lines.append(f"| {r['case']} | {r['p']:g} | {bem.mean():.3f} ± "
                     f"{bem.std(ddof=1) / np.sqrt(bem.size):.3f} | {mu:.3f} | "
                     f"{100 * err:+.0f} % | {mu_nested:.3f} | {100 * err_nested:+.0f} % | "
                     f"{np.mean(r['bem_A']):.3f} | "
                     f"{float(res.samples.weight.sum()):.3f} | " + " | ".join(cells) + " |")

    def pct(e):
        return f"{100 * min(e):+.0f} to {100 * max(e):+.0f} %"

    band, above = np.array(ratios).T if ratios else (np.ones(1), np.ones(1))
    return "\n".join(lines), {"pairs_err": pct(errs[False]), "triplet_err": pct(errs[True]),
                              "pairs_err_nested": pct(nested_errs[False]),
                              "triplet_err_nested": pct(nested_errs[True]),
                              "band2": f"{band.min():.1f}–{band.max():.1f}",
                              "above2": f"{above.min():.1f}–{above.max():.1f}"}
