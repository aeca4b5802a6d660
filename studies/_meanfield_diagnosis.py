"""Why the 1D mean-field theory misses on the random ladders (studies/meanfield.py report).

Three measurements on the cached BEM rows, no new solve:

* the *area scale* the BEM needs: the factor ``c`` on ``1/(2√G)`` with which Persson's
  ``erf(c/(2√G))`` equals the BEM's contact fraction, by speed and load;
* the friction with the BEM's own area imposed (``G`` of every node divided by ``c²``): what
  is left of the friction error once the area is right, for each dissipation rule;
* the Westergaard cascade (each wave one exact sine step at the local pressure the longer
  waves leave, :func:`westergaard_cascade_area`) against the elastic BEM on two- and
  four-wave profiles with and without scale separation;
* one speed-independent 1D area correction, ``c = 1 + β ln(1/A)`` (the logarithmic growth of
  a line contact's area per load as the patches shrink), over a few β: what a fitted
  constant could and could not do.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq
from scipy.special import erf

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.meanfield.contact import (
    contact_fraction,
    g_cumulative,
    half_space_compliance,
    modal_response,
)
from rubbercontact.meanfield.options import Dissipation
from rubbercontact.meanfield.patches import patch_loss

SBR = rc.materials.sbr()
BETAS = (0.0, 0.06, 0.09, 0.12)
RULES = ("mode", "cascade", "patch")


def _ladder_points(rows) -> list[dict]:
    """Random-ladder rows with the BEM area in 1–50 %, with the theory's nodes."""
    out = []
    for r in rows:
        if r["kind"] != "1d" or not r["case"].startswith("random"):
            continue
        area, mu = float(np.mean(r["bem_A"])), float(np.mean(r["bem_mu"]))
        if not 0.01 <= area <= 0.5:
            continue
        s = r["surface"]
        psd = mf.PSD.from_sines(rc.roughness.SineSeries(s["wavelengths"], s["amplitudes"]))
        resp = modal_response(half_space_compliance(psd.wavenumbers, psd.variances, 1, SBR,
                                                    r["v"], 0.5))
        out.append({"v": r["v"], "target": r["target"], "p": r["p"], "A": area, "mu": mu,
                    "psd": psd, "resp": resp,
                    "g": g_cumulative(resp.pressure_variance, r["p"])})
    return out


def _friction(pt, g, area, rule: str) -> float:
    if rule == "mode":
        f = pt["resp"].friction_stress
    else:
        f = pt["resp"].pressure_variance * patch_loss(
            Dissipation(rule).local_fraction(g) if area is None else _local(area, rule),
            pt["psd"].wavenumbers, SBR, pt["v"], 0.5)
    a = contact_fraction(g) if area is None else area
    return float(np.sum(f * a) / pt["p"])


def _local(area, rule):
    if rule == "patch":
        return area
    return np.minimum(area / np.concatenate([[1.0], area[:-1]]), 1.0)


def westergaard_cascade_area(psd: mf.PSD, mean_pressure: float, velocity: float = 0.0,
                             samples: int = 64, bins: int = 600) -> float:
    """Contact fraction when each wave, longest first, acts as Westergaard's sine at the
    local pressure the longer waves leave (scale separation; Archard's picture made exact
    per step). The local pressures are carried as weighted samples, re-binned on a log grid
    (load conserved to 1e-3)."""
    amp = np.sqrt(2 * psd.variances)
    e_r = np.abs(SBR.complex_modulus(psd.wavenumbers * abs(velocity))) / 0.75
    sig, w = np.array([float(mean_pressure)]), np.array([1.0])
    t = (np.arange(samples) + 0.5) / samples
    for p_star in psd.wavenumbers * amp * e_r / 2:
        full = sig >= p_star
        s_full = (sig[full, None] + p_star * np.cos(np.pi * t)).ravel()
        alpha = 2 * np.arcsin(np.sqrt(sig[~full] / p_star))[:, None]
        th = alpha * t
        s_part = (2 * p_star * np.cos(th / 2)
                  * np.sqrt(np.maximum(np.sin(alpha / 2) ** 2 - np.sin(th / 2) ** 2, 0))).ravel()
        w_all = np.concatenate([np.repeat(w[full] / samples, samples),
                                np.repeat(w[~full] * alpha[:, 0] / np.pi / samples,
                                          samples)])
        s_all = np.concatenate([s_full, s_part])
        keep = (w_all > 0) & (s_all > 0)
        s_all, w_all = s_all[keep], w_all[keep]
        edges = np.geomspace(s_all.max() * 1e-9, s_all.max() * (1 + 1e-9), bins + 1)
        idx = np.clip(np.searchsorted(edges, s_all) - 1, 0, bins - 1)
        wb, sb = np.bincount(idx, w_all, bins), np.bincount(idx, w_all * s_all, bins)
        sig, w = sb[wb > 0] / wb[wb > 0], wb[wb > 0]
    return float(w.sum())


def separation_table(rows) -> str:
    """Persson, the Westergaard cascade and the elastic BEM on the separation profiles."""
    lines = ["| profile | Persson A | Westergaard cascade A | strips A | BEM A "
             "(8 realizations) | Persson error | cascade error | strips error |",
             "|---|---|---|---|---|---|---|---|"]
    for r in (r for r in rows if r["kind"] == "separation"):
        s = r["surface"]
        psd = mf.PSD.from_sines(rc.roughness.SineSeries(s["wavelengths"], s["amplitudes"]))
        casc = westergaard_cascade_area(psd, r["p"])
        strips = mf.solve(psd, SBR, 0.0, r["p"], options=mf.StripOptions()).contact_fraction
        bem = float(np.mean(r["bem_A"]))
        lines.append(f"| {r['case']} | {r['target']:.3f} | {casc:.3f} | {strips:.3f} | "
                     f"{bem:.3f} | {_pct(r['target'] / bem - 1)} | {_pct(casc / bem - 1)} | "
                     f"{_pct(strips / bem - 1)} |")
    return "\n".join(lines)


def broadband_table(rows) -> tuple[str, dict]:
    """Self-affine profiles over 2 and 3 decades: S = 1 with the patch spectrum against
    Persson's dissipation, BEM averaged over the realizations."""
    from ._meanfield_cases import self_affine_profile

    groups: dict[tuple, list] = {}
    for r in (r for r in rows if r["kind"] == "broadband"):
        groups.setdefault((r["case"], r["v"], r["target"]), []).append(r)
    lines = ["| profile | v [mm/s] | BEM μ | BEM A | theory A | A error | μ, patch spectrum "
             "(S = 1) | error | μ, Persson's dissipation (S = 1) | error |", "|---" * 10 + "|"]
    errs: dict[str, list] = {"patch": [], "mode": [], "area": []}
    for (case, v, _), rs in groups.items():
        par = rs[0]["params"]
        psd = self_affine_profile(n=4 * int(round(par["length"] / par["lam_min"])), seed=1,
                                  **par)[1]
        mu, area = np.mean([x["bem_mu"][0] for x in rs]), np.mean([x["bem_A"][0] for x in rs])
        res = {d: mf.solve(psd, SBR, v, rs[0]["p"],
                           options=mf.MeanFieldOptions(correction=1.0, dissipation=d))
               for d in ("patch", "mode")}
        for d in res:
            errs[d].append((v, res[d].friction / mu - 1))
        errs["area"].append((v, res["patch"].contact_fraction / area - 1))
        lines.append(f"| {case} | {v:g} | {mu:.3f} | {area:.3f} | "
                     f"{res['patch'].contact_fraction:.3f} | "
                     f"{_pct(res['patch'].contact_fraction / area - 1)} | "
                     f"{res['patch'].friction:.3f} | {_pct(res['patch'].friction / mu - 1)} | "
                     f"{res['mode'].friction:.3f} | {_pct(res['mode'].friction / mu - 1)} |")

    def span(key, slow=None):
        e = np.array([x for v, x in errs[key] if slow is None or (v <= 1.0) == slow])
        return f"{_pct(e.mean())} [{_pct(e.min())}, {_pct(e.max())}]" if e.size else "–"

    def share(key):
        return f"{np.mean([abs(x) <= 0.15 for _, x in errs[key]]):.0%}" if errs[key] else "–"

    fields = {"bb_patch": span("patch"), "bb_mode": span("mode"), "bb_area": span("area"),
              "bb_patch_slow": span("patch", True), "bb_mode_slow": span("mode", True),
              "bb_patch_fast": span("patch", False), "bb_mode_fast": span("mode", False),
              "bb_patch_share": share("patch"), "bb_mode_share": share("mode")}
    return "\n".join(lines), {**fields, **broadband_oracle(rows)}


def broadband_oracle(rows) -> dict:
    """μ error on the continuous profiles with the BEM's own area imposed (``G / c²``)."""
    from rubbercontact.meanfield.contact import cell_average

    from ._meanfield_cases import self_affine_profile

    groups: dict[tuple, list] = {}
    for r in (r for r in rows if r["kind"] in ("broadband", "selfaffine")):
        groups.setdefault((r["case"], r["v"], r["target"]), []).append(r)
    errs: dict[str, list] = {"mode": [], "patch": []}
    for rs in groups.values():
        r, par = rs[0], rs[0]["params"]
        psd = self_affine_profile(n=4 * int(round(par["length"] / par["lam_min"])), seed=1,
                                  **par)[1]
        mu, area = np.mean([x["bem_mu"][0] for x in rs]), np.mean([x["bem_A"][0] for x in rs])
        resp = modal_response(half_space_compliance(psd.wavenumbers, psd.variances, 1, SBR,
                                                    r["v"], 0.5))
        g = g_cumulative(resp.pressure_variance, r["p"])
        c = brentq(lambda c, g_end=g[-1], a=area: contact_fraction(g_end / c**2) - a, 0.2, 5.0)
        g = g / c**2
        weight = cell_average(contact_fraction, np.concatenate([[0.0], g[:-1]]), g)
        for rule in errs:
            f = resp.friction_stress if rule == "mode" else resp.pressure_variance * patch_loss(
                contact_fraction(g), psd.wavenumbers, SBR, r["v"], 0.5)
            errs[rule].append(float(np.sum(f * weight) / r["p"]) / mu - 1)
    return {f"bbo_{k}": f"{_pct(np.mean(e))} [{_pct(min(e))}, {_pct(max(e))}]"
            for k, e in errs.items() if e}


def _pct(x: float) -> str:
    return f"{100 * x:+.0f} %"


def area_scale_table(points) -> str:
    """The factor ``c`` the BEM's area asks of ``1/(2√G)``, by speed and theory's area."""
    lines = ["| v [mm/s] | " + " | ".join(f"c at theory's A = {t:.0%}" for t in
                                          (0.02, 0.06, 0.2, 0.45)) + " |", "|---" * 5 + "|"]
    for v in sorted({p["v"] for p in points}):
        cols = []
        for t in (0.02, 0.06, 0.2, 0.45):
            cs = [brentq(lambda c, p=p: contact_fraction(p["g"][-1] / c**2) - p["A"], 0.2, 5.0)
                  for p in points if p["v"] == v and p["target"] == t]
            cols.append(f"{min(cs):.2f}–{max(cs):.2f}" if cs else "–")
        lines.append(f"| {v:g} | " + " | ".join(cols) + " |")
    return "\n".join(lines)


def oracle_table(points) -> tuple[str, dict]:
    """μ error with the BEM's own area imposed, per dissipation rule and speed."""
    lines = ["| dissipation | " + " | ".join(f"μ error at {v:g} mm/s" for v in
                                            sorted({p["v"] for p in points}))
             + " | μ within 15 % |", "|---" * (len({p["v"] for p in points}) + 2) + "|"]
    share = {}
    for rule in RULES:
        errs = []
        for p in points:
            c = brentq(lambda c, p=p: contact_fraction(p["g"][-1] / c**2) - p["A"], 0.2, 5.0)
            g = p["g"] / c**2
            errs.append((p["v"], _friction(p, g, None, rule) / p["mu"] - 1))
        cols = []
        for v in sorted({p["v"] for p in points}):
            e = np.array([x for w, x in errs if w == v])
            cols.append(f"{_pct(e.mean())} [{_pct(e.min())}, {_pct(e.max())}]")
        share[rule] = np.mean([abs(x) <= 0.15 for _, x in errs])
        lines.append(f"| {rule} | " + " | ".join(cols) + f" | {share[rule]:.0%} |")
    return "\n".join(lines), {f"oracle_{k}": f"{v:.0%}" for k, v in share.items()}


def log_area_table(points) -> str:
    """``A = erf(c/(2√G))``, ``c = 1 + β ln(1/A_Persson)`` per node, Persson's dissipation."""
    speeds = sorted({p["v"] for p in points})
    lines = ["| β | " + " | ".join(f"μ / A error at {v:g} mm/s" for v in speeds)
             + " | μ and A within 15 % |", "|---" * (len(speeds) + 2) + "|"]
    for beta in BETAS:
        errs = []
        for p in points:
            g = p["g"]
            a0 = contact_fraction(g)
            area = erf(0.5 / np.sqrt(g) * (1 + beta * np.log(1 / a0)))
            errs.append((p["v"], _friction(p, g, area, "mode") / p["mu"] - 1,
                         area[-1] / p["A"] - 1))
        cols = [f"{_pct(np.mean([e[1] for e in errs if e[0] == v]))} / "
                f"{_pct(np.mean([e[2] for e in errs if e[0] == v]))}" for v in speeds]
        both = np.mean([abs(e[1]) <= 0.15 and abs(e[2]) <= 0.15 for e in errs])
        lines.append(f"| {beta:g} | " + " | ".join(cols) + f" | {both:.0%} |")
    return "\n".join(lines)


def diagnosis(rows) -> tuple[str, str, str, str, dict]:
    """The four tables (area scale, friction with the BEM's area, separation, log area
    correction)."""
    points = _ladder_points(rows)
    oracle, fields = oracle_table(points)
    return (area_scale_table(points), oracle, separation_table(rows), log_area_table(points),
            fields)
