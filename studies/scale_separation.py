"""When does the hybrid's scale split hold? Linear-law hybrid against the VHS on two waves.

The hybrid homogenizes the high-slope wave into an interface law and applies it, point by
point, under the low-slope contact. With a *linear* law (the VHS solution of the
high-slope wave alone) the hybrid should reproduce the VHS on the two-wave surface when
the scales are separated; the difference measures the scale-split error alone, free of
any FEM or finite-strain effect. The windowed hybrid (law read at the low-slope pressure
averaged over one high-slope period, ``rubbercontact.hybrid.windowing``) is run on the
same solves, and two more readings of the same law:

- *law at the VHS crest loads* (diagnostic): the load the VHS puts on each high-slope
  crest cell, read through the law. It tells whether the law per crest is right, so that
  what is left of a hybrid's error is how its low-slope solve shares the load among the
  discrete crests;
- *crest-resolved* (experimental, :func:`crest_resolved_loads`): a small half-space
  solve with one cell per crest that predicts those loads without the VHS.

High-slope wave: the paper's (0.0625 mm, m2 = 1.33). Low-slope wave: wavelength ``λ_ls``
and slope ``m2_ls`` varied; SBR, 10 mm/s, random phases (4 realizations, seeded),
hard-wall VHS with n = 4096 points per period.

Run (about 15 s on one core)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies scale_separation \
        --report docs/validation/scale_separation.md
"""

from __future__ import annotations

import argparse
import subprocess
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

import rubbercontact as rc
from rubbercontact.errors import ConvergenceError, InputError
from rubbercontact.halfspace import kernels
from rubbercontact.hybrid.law import linear_law, tabulated_law_from_dict
from rubbercontact.hybrid.tasks import halfspace_task
from rubbercontact.hybrid.windowing import law_in_pressure
from rubbercontact.roughness import SineSeries

DESCRIPTION = ("When does the hybrid's scale split hold? "
               "Linear-law hybrid against the VHS on two waves.")

HS_WAVELENGTH, HS_AMPLITUDE = 0.0625, 0.01867
CASES = [(0.125, 0.3), (0.125, 0.94), (0.25, 0.3), (0.25, 0.52), (0.25, 0.94),
         (0.5, 0.3), (0.5, 0.94), (1.0, 0.3), (1.0, 0.94)]
PRESSURES = (0.15, 0.35)


def crest_cells(hs: SineSeries, period: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """High-slope cells (one ``λ_hs`` centred on a crest) on ``n`` uniform points over ``period``.

    Returns the cell index of every grid point and the grid index of each cell's crest (the
    grid maxima of ``hs``), so the diagnostic and the crest-resolved solve share one definition.
    """
    lam = hs.period
    m = int(round(period / lam))
    per_cell = n // m
    if m * per_cell != n or abs(m * lam - period) > 1e-9 * period:
        raise InputError(f"period {period} mm: must be a multiple of the high-slope cell "
                         f"{lam} mm, and n = {n} a multiple of the {m} cells")
    i0 = int(np.argmax(hs.heights(np.arange(per_cell) * (lam / per_cell))))
    cells = ((np.arange(n) - i0 + per_cell // 2) // per_cell) % m
    return cells, (i0 + np.arange(m) * per_cell) % n


def crest_loads(pressure: np.ndarray, hs: SineSeries, period: float) -> np.ndarray:
    """Mean pressure [MPa] on each high-slope cell of a periodic profile over ``period``."""
    cells, _ = crest_cells(hs, period, pressure.size)
    return np.bincount(cells, weights=pressure) / np.bincount(cells)


def crest_resolved_loads(ls: SineSeries, hs: SineSeries, period: float, table: dict,
                         material, velocity: float, mean_pressure: float, n: int = 4096
                         ) -> np.ndarray:
    """Experimental: share the load among the discrete high-slope crests [MPa per cell].

    One cell of width ``λ_hs`` per crest (centred on the maxima of ``hs``); the law
    ``σ_hs(g)`` is each cell's local response to its mean gap ``g_k``; the cells interact
    through the half-space (the cell mean of the viscoelastic steady-sliding response to a
    pressure uniform over one cell):

        g_k = ū + Σ_j C_kj P_j − z_ls(x_k),   P_k = σ_hs(g_k),   <P> = σ0.

    A uniform load on every cell moves nothing but ``ū`` (``C·1 = 0``), so at uniform
    pressure the law is read at ``σ0`` as in the paper. Newton on ``(g, ū)`` from the
    Winkler start (no interaction), with backtracking.
    """
    cells, crests = crest_cells(hs, period, n)
    m = crests.size
    # response to a unit pressure on cell 0, averaged over every cell: a circulant matrix
    kernel = kernels.response_kernel(material, (n,), (period,), velocity)
    w = kernels.apply_kernel(kernel, (cells == 0).astype(float))
    col = np.bincount(cells, weights=w) / np.bincount(cells)
    C = col[(np.arange(m)[:, None] - np.arange(m)[None, :]) % m]
    z = ls.heights(crests * (period / n))
    law = tabulated_law_from_dict(table)
    u_lo, u_hi = table["separation"][0], table["separation"][-1]

    def winkler(ub):
        return law.pressure(ub - z).mean() - mean_pressure

    lo = u_lo + z.min() - (u_hi - u_lo)
    while winkler(lo) < 0:
        lo -= u_hi - u_lo
    ubar = brentq(winkler, lo, u_hi + z.max(), xtol=1e-14)
    g = ubar - z
    scale = np.r_[np.full(m, 1e-3), mean_pressure]   # 1 µm in gap, σ0 in force balance

    def residual(g, ubar):
        s = law.pressure(g)
        return np.concatenate([g - ubar - C @ s + z, [s.mean() - mean_pressure]]) / scale, s

    r, s = residual(g, ubar)
    for _ in range(100):
        norm = np.linalg.norm(r)
        if norm < 1e-10:
            return s
        k = law.stiffness(g)
        J = np.zeros((m + 1, m + 1))
        J[:m, :m] = np.eye(m) + C * k[None, :]
        J[:m, m] = -1.0
        J[m, :m] = -k / m
        d = np.linalg.solve(J / scale[:, None], -r)
        a = 1.0
        for _ in range(40):
            r_new, s_new = residual(g + a * d[:m], ubar + a * d[m])
            if np.linalg.norm(r_new) < (1 - 1e-4 * a) * norm:
                break
            a *= 0.5
        g, ubar, r, s = g + a * d[:m], ubar + a * d[m], r_new, s_new
    raise ConvergenceError(f"crest-resolved load sharing: no convergence in 100 Newton "
                           f"iterations (scaled residual {norm:.2e}, tolerance 1e-10)")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--velocity", type=float, default=10.0)
    ap.add_argument("--realizations", type=int, default=4)
    ap.add_argument("--report", type=Path)
    args = ap.parse_args(argv)
    mat, v = rc.materials.sbr(), args.velocity
    table = linear_law(SineSeries([HS_WAVELENGTH], [HS_AMPLITUDE]), mat, v)
    rng = np.random.default_rng(2021)
    lines = ["# Scale separation of the hybrid: linear-law hybrid against the VHS", "",
             "Generated by `studies/scale_separation.py` "
             f"({datetime.now(UTC):%Y-%m-%d %H:%M UTC}, commit "
             + subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip() + "). High-slope wave 0.0625 mm, "
             f"m2 = 1.33; one low-slope wave; SBR, {v:g} mm/s; mean of "
             f"{args.realizations} random-phase realizations. The error is the hybrid's "
             "scale split alone (the law is the linear solution of the high-slope wave).", "",
             "Columns: the paper's pointwise hybrid; the windowed hybrid (law read at the "
             "low-slope pressure averaged over λ_hs); *crest-resolved* (experimental, this "
             "script: the hybrid's μ_ls plus the law read at crest loads from a half-space "
             "solve with one cell per high-slope crest); *law at VHS crest loads* (diagnostic: "
             "the hybrid's μ_ls plus the law read at the VHS's own load on each crest cell); "
             "crest-load concentration <P²>/σ0² over the cells (1: equal shares; λ_ls/λ_hs: "
             "one crest carries all) of the VHS, the hybrid's σ_ls and the crest-resolved "
             "solve.", "",
             "| λ_ls/λ_hs | m2_ls | σ0 [MPa] | VHS μ (A) | hybrid μ (A) | error "
             "| windowed μ (A) | error | crest-resolved μ (A) | error "
             "| law at VHS crest loads μ | error | concentration VHS / hybrid / crest |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    sig_law, alpha_law, tau_law = law_in_pressure(table)

    def read(loads):   # the law per crest cell: (μ_hs σ0, A)
        return (float(np.mean(np.interp(loads, sig_law, tau_law))),
                float(np.mean(np.interp(loads, sig_law, alpha_law))))

    names = ("hybrid", "windowed", "crest-resolved", "VHS crest loads")
    errors = {k: [] for k in names}
    hs = SineSeries([HS_WAVELENGTH], [HS_AMPLITUDE])
    for lam, m2 in CASES:
        amp = m2 * np.sqrt(2) * lam / (2 * np.pi)
        acc = {p: [] for p in PRESSURES}
        for ph_hs, ph_ls in rng.uniform(0, 2 * np.pi, (args.realizations, 2)):
            ls = SineSeries([lam], [amp], [ph_ls])
            full = SineSeries([HS_WAVELENGTH, lam], [HS_AMPLITUDE, amp], [ph_hs, ph_ls])
            for p in PRESSURES:
                vh = rc.halfspace.solve_sliding(full, lam, mat, v, p, n=4096)
                hy = halfspace_task(ls.as_dict(), lam, mat.as_dict(), v, p, n=4096,
                                    interface_law=table, keep_profile=True)
                hw = halfspace_task(ls.as_dict(), lam, mat.as_dict(), v, p, n=4096,
                                    interface_law=table, hs_window=HS_WAVELENGTH)
                mu_ls = float(hy["friction_ls"])
                # If the law read at the VHS's own crest loads matches the VHS, the law
                # per crest is right and what is left of a hybrid's error is how its
                # low-slope solve shares the load among the crests.
                hs_r = hs.with_phases([ph_hs])
                vhs_loads = crest_loads(np.asarray(vh.pressure), hs_r, lam)
                hyb_loads = crest_loads(hy["pressure_profile"].values, hs_r, lam)
                res_loads = crest_resolved_loads(ls, hs_r, lam, table, mat, v, p)
                tau_c, area_c = read(res_loads)
                acc[p].append((
                    vh.friction, vh.contact_fraction,
                    float(hy["friction"]), float(hy["contact_fraction"]),
                    float(hw["friction"]), float(hw["contact_fraction"]),
                    mu_ls + tau_c / p, area_c,
                    mu_ls + read(vhs_loads)[0] / p,
                    *(np.mean(c**2) / p**2 for c in (vhs_loads, hyb_loads, res_loads))))
        for p, vals in acc.items():
            mv, av, mh, ah, mw, aw, mc, ac, mo, cv, ch, cc = np.mean(vals, axis=0)
            for k, mu in zip(names, (mh, mw, mc, mo), strict=True):
                errors[k].append((lam, mu / mv - 1))
            row = (f"| {lam / HS_WAVELENGTH:g} | {m2:g} | {p:g} | {mv:.3f} ({av:.3f}) | "
                   f"{mh:.3f} ({ah:.3f}) | {100 * (mh / mv - 1):+.0f} % | "
                   f"{mw:.3f} ({aw:.3f}) | {100 * (mw / mv - 1):+.0f} % | "
                   f"{mc:.3f} ({ac:.3f}) | {100 * (mc / mv - 1):+.0f} % | "
                   f"{mo:.3f} | {100 * (mo / mv - 1):+.0f} % | "
                   f"{cv:.2f} / {ch:.2f} / {cc:.2f} |")
            print(row, flush=True)
            lines.append(row)
    lines += ["", "Mean |μ error| per wavelength ratio (largest in brackets):", "",
              "| λ_ls/λ_hs | " + " | ".join(names) + " |", "|---|---|---|---|---|"]
    for lam in sorted({c[0] for c in CASES}):
        cells = []
        for k in names:
            e = [abs(x) for la, x in errors[k] if la == lam]
            cells.append(f"{100 * np.mean(e):.1f} % ({100 * max(e):.0f} %)")
        lines.append(f"| {lam / HS_WAVELENGTH:g} | " + " | ".join(cells) + " |")
    print("\n".join(lines[-7:]))
    if args.report:
        args.report.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
