"""Persson's ``S = γ + (1 − γ)A²`` against the BEM rows of studies/meanfield.py, by γ.

The model ``meanfield`` (Persson's diffusion, his own-wavenumber dissipation, the cell
weighting of his integral) at each γ of :data:`GAMMAS` on every stored 1D and 2D point with
the BEM's contact fraction in 1–50 %: the default γ (``meanfield.DEFAULT_GAMMA``) is chosen
here.
"""

from __future__ import annotations

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf

from ._meanfield_cases import self_affine_profile

SBR = rc.materials.sbr()
GAMMAS = (0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
TARGET = 0.15
A_RANGE = (0.01, 0.5)
#: Surface classes, in the table's order.
CLASSES = ("random ladders", "section 3", "Table 2", "CAPTIF fit", "broadband profiles",
           "4-decade profile", "2D map")


def _class(row: dict) -> str | None:
    if row["kind"] == "1d":
        return "random ladders" if row["case"].startswith("random") else row["case"]
    return {"broadband": "broadband profiles", "selfaffine": "4-decade profile",
            "2d": "2D map"}.get(row["kind"])


def _points(rows, psd_of) -> list[tuple[str, dict, mf.PSD, float]]:
    out = []
    for r in rows:
        cls = _class(r)
        if cls is None or not A_RANGE[0] <= np.mean(r["bem_A"]) <= A_RANGE[1]:
            continue
        if r["kind"] == "broadband":     # the spectrum is the same for every seed and grid
            par = r["params"]
            psd = self_affine_profile(n=4 * int(round(par["length"] / par["lam_min"])),
                                      seed=r["seed"], **par)[1]
        else:
            psd = psd_of(r)
        out.append((cls, r, psd, float(np.mean(r["bem_mu"]))))
    return out


def gamma_table(rows, psd_of) -> tuple[str, dict]:
    """The μ error of ``meanfield`` per surface class and γ, and the prose's fields."""
    pts = _points(rows, psd_of)
    err = {g: {c: [] for c in CLASSES} for g in GAMMAS}
    for g in GAMMAS:
        opts = mf.MeanFieldOptions(correction=g)
        for cls, r, psd, mu in pts:
            err[g][cls].append(mf.solve(psd, SBR, r["v"], r["p"], options=opts).friction / mu
                               - 1)
    head = "| surface class | points | " + " | ".join(f"γ = {g:g}" for g in GAMMAS) + " |"
    lines = [head, "|---|---|" + "---|" * len(GAMMAS)]
    for c in CLASSES:
        cells = [f"{100 * np.mean(err[g][c]):+.0f} % ({np.mean(np.abs(err[g][c]) <= TARGET):.0%})"
                 for g in GAMMAS]
        lines.append(f"| {c} | {len(err[GAMMAS[0]][c])} | " + " | ".join(cells) + " |")
    share = {g: np.mean(np.abs(np.concatenate(list(err[g].values()))) <= TARGET)
             for g in GAMMAS}
    rms = {g: np.mean([np.sqrt(np.mean(np.square(e))) for e in err[g].values()])
           for g in GAMMAS}
    lines.append("| all points within 15 % | " + f"{len(pts)} | "
                 + " | ".join(f"{share[g]:.0%}" for g in GAMMAS) + " |")
    lines.append("| rms error, mean over the classes | | "
                 + " | ".join(f"{100 * rms[g]:.0f} %" for g in GAMMAS) + " |")
    d = mf.DEFAULT_GAMMA
    two_d = np.array(err[d]["2D map"])
    fields = {"gamma": f"{d:g}", "n_points": len(pts), "share": f"{share[d]:.0%}",
              "best": f"{max(GAMMAS, key=lambda g: share[g]):g}",
              "share_half": f"{share[0.5]:.0%}", "share_one": f"{share[1.0]:.0%}",
              "two_d_within": f"{int(np.sum(np.abs(two_d) <= TARGET))} of {two_d.size}",
              "two_d": f"{100 * two_d.mean():+.0f} %",
              "ladders": f"{100 * np.mean(err[d]['random ladders']):+.0f} %",
              "ladders_half": f"{100 * np.mean(err[0.5]['random ladders']):+.0f} %",
              "two_d_half": f"{100 * np.mean(err[0.5]['2D map']):+.0f} %"}
    return "\n".join(lines), fields
