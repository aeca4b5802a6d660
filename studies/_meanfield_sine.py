"""The one-sine table of studies/meanfield.py's report: the exact 1D limit (Westergaard's
area, the patch spectrum's friction, the strips and the diffusion) against the BEM."""

from __future__ import annotations

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.meanfield.patches import westergaard_fraction
from rubbercontact.roughness import SineSeries

from ._meanfield_cases import westergaard_p_star

SBR = rc.materials.sbr()


def _pct(x: float) -> str:
    return f"{100 * x:+.0f} %"


def _rng(e: np.ndarray) -> str:
    return f"{_pct(e.mean())} [{_pct(e.min())}, {_pct(e.max())}]" if e.size else "–"


def _westergaard_friction(x: float, p_star: float, q: float, v: float) -> float:
    """First-order friction of one sine: Westergaard's pressure variance times the patch
    spectrum's loss, over ``σ0 = x p*`` (:mod:`rubbercontact.meanfield.patches`)."""
    from rubbercontact.meanfield import patches

    r = float(patches.westergaard_fraction(x))
    theta = 2 * np.pi * (np.arange(2**16) + 0.5) / 2**16 - np.pi
    var = np.var(patches.westergaard_pressure(theta, r)) * p_star**2
    return float(var * patches.patch_loss(np.array([r]), np.array([q]), SBR, v, 0.5)[0]
                 / (x * p_star))


def sine_table(rows) -> tuple[str, dict]:
    lines = ["| v [mm/s] | σ0/p* | BEM A | Westergaard A | strips A | diffusion A "
             "| BEM μ | Westergaard + patch spectrum μ | error | strips μ | error "
             "| diffusion μ, mode | error | diffusion μ, patch r = A | error |",
             "|---" * 15 + "|"]
    errs: dict[str, list] = {"west": [], "mode": [], "patch": [], "strips": [],
                             "strips_A": []}
    for r in sorted((r for r in rows if r["kind"] == "sine"), key=lambda r: (r["v"],
                                                                           r["target"])):
        surf = SineSeries(r["surface"]["wavelengths"], r["surface"]["amplitudes"],
                          r["surface"].get("phases"))
        psd, x, v = mf.PSD.from_sines(surf), r["target"], r["v"]
        mode, patch = (mf.solve(psd, SBR, v, r["p"], options=mf.MeanFieldOptions(
            correction=1.0, weighting="after", dissipation=d)) for d in ("mode", "patch"))
        strips = mf.solve(psd, SBR, v, r["p"], options=mf.StripOptions())
        mu, area = r["bem_mu"][0], r["bem_A"][0]
        west = float(westergaard_fraction(x))
        cols = [f"{v:g}", f"{x:g}", f"{area:.4f}", f"{west:.4f}",
                f"{strips.contact_fraction:.4f}", f"{mode.contact_fraction:.4f}"]
        if v == 0:
            lines.append("| " + " | ".join(cols + ["0"] + ["–"] * 8) + " |")
            continue
        errs["strips_A"].append((v, strips.contact_fraction / area - 1))
        wmu = _westergaard_friction(x, westergaard_p_star(surf, SBR, v),
                                    float(surf.wavenumbers[0]), v)
        for key, val in (("west", wmu), ("mode", mode.friction), ("patch", patch.friction),
                         ("strips", strips.friction)):
            errs[key].append((v, val / mu - 1))
        cols += [f"{mu:.4f}", f"{wmu:.4f}", _pct(wmu / mu - 1), f"{strips.friction:.4f}",
                 _pct(strips.friction / mu - 1), f"{mode.friction:.4f}",
                 _pct(mode.friction / mu - 1), f"{patch.friction:.4f}",
                 _pct(patch.friction / mu - 1)]
        lines.append("| " + " | ".join(cols) + " |")

    def span(key, slow):
        e = np.array([x for v, x in errs[key] if (v <= 1.0) == slow])
        return _rng(e) if e.size else "–"

    sliding = {k: _rng(np.array([x for _, x in errs[k]])) for k in ("strips", "strips_A")}
    return "\n".join(lines), {**{f"{k}_{t}": span(k, t == "slow") for k in errs
                                for t in ("slow", "fast")}, **sliding}
