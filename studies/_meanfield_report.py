"""Report of studies/meanfield.py: the theory recomputed on the study's rows, tables,
figures and prose (studies/templates/meanfield.md)."""

from __future__ import annotations

import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.roughness import SineSeries

from ._meanfield_bands import (
    bands_table,
    layer_table,
    patches_table,
    triplets_table,
    truncated_table,
)
from ._meanfield_cases import (
    DIFFUSION,
    NESTED,
    SPEEDS,
    STRIPS,
    diffusion,
    make_map,
    previous_default,
    self_affine_profile,
)
from ._meanfield_diagnosis import broadband_table, diagnosis
from ._meanfield_gamma import gamma_table
from ._meanfield_sine import sine_table
from ._templates import render

SBR = rc.materials.sbr()
TARGET = 0.15
#: meanfield-hybrid with its defaults (Persson's S, the law layer) and a rigid interface.
HYBRID = mf.MeanFieldOptions(interface="law")
HYBRID_RIGID = mf.MeanFieldOptions(interface="rigid")
A_RANGE = (0.01, 0.5)


def _series(d: dict) -> SineSeries:
    return SineSeries(d["wavelengths"], d["amplitudes"], d.get("phases"))


def _psd(row: dict) -> mf.PSD:
    if row["kind"] == "2d":
        return mf.PSD.from_map(make_map(seed=row["seed"], **row["map"]), row["map"]["length"])
    if row["kind"] == "selfaffine":
        return self_affine_profile(n=4 * int(round(row["params"]["length"]
                                                   / row["params"]["lam_min"])),
                                   seed=row["seed"], **row["params"])[1]
    return mf.PSD.from_sines(_series(row["surface"]))


def _pct(x: float) -> str:
    return f"{100 * x:+.0f} %"


def _rng(e: np.ndarray) -> str:
    return f"{_pct(e.mean())} [{_pct(e.min())}, {_pct(e.max())}]" if e.size else "–"


def _se(values) -> float:
    """Standard error of the mean of the BEM's realizations (NaN for one)."""
    return np.std(values, ddof=1) / np.sqrt(len(values)) if len(values) > 1 else np.nan


def _points(rows, options=previous_default,
            kinds: tuple[str, ...] = ("1d", "selfaffine")) -> list[dict]:
    """Every 1D row of the ``kinds`` (sine series and self-affine profiles) with the theory's
    μ and A and the BEM means (and standard errors); ``options`` an options object or a
    function of the spectrum returning one."""
    out = []
    for r in rows:
        if r["kind"] not in kinds:
            continue
        psd = _psd(r)
        res = mf.solve(psd, SBR, r["v"], r["p"],
                       options=options(psd) if callable(options) else options)
        mu, area = np.mean(r["bem_mu"]), np.mean(r["bem_A"])
        out.append({**r, "mf_mu": res.friction, "mf_A": res.contact_fraction, "mu": mu,
                    "A": area, "mu_se": _se(r["bem_mu"]), "A_se": _se(r["bem_A"]),
                    "e_mu": res.friction / mu - 1,
                    "e_A": res.contact_fraction / area - 1,
                    "in_range": A_RANGE[0] <= area <= A_RANGE[1]})
    return out


def _is_random(case: str) -> bool:
    return case.startswith("random")


def _choices_table(rows, variants) -> str:
    lines = ["| variant | μ error, random ladders | μ within 15 % | μ error, section 3 "
             "| μ error, Table 2 | μ error, CAPTIF |", "|---|---|---|---|---|---|"]
    for label, opts in variants:
        pts = [p for p in _points(rows, opts, ("1d",)) if p["in_range"]]
        rnd = np.array([p["e_mu"] for p in pts if _is_random(p["case"])])
        cols = [_rng(rnd), f"{np.mean(np.abs(rnd) <= TARGET):.0%}" if rnd.size else "–"]
        for name in ("section 3", "Table 2", "CAPTIF fit"):
            cols.append(_rng(np.array([p["e_mu"] for p in pts if p["case"] == name])))
        lines.append(f"| {label} | " + " | ".join(cols) + " |")
    return "\n".join(lines)


def _ok(p: dict) -> bool:
    return abs(p["e_mu"]) <= TARGET and abs(p["e_A"]) <= TARGET


def _ok_sampled(p: dict) -> bool:
    """Within the target of the BEM's ensemble mean, given that the mean is known to its
    standard error only: ``|error| ≤ 15 % + 2 s.e.`` (relative) in μ and in A."""
    return (abs(p["e_mu"]) <= TARGET + 2 * p["mu_se"] / p["mu"]
            and abs(p["e_A"]) <= TARGET + 2 * p["A_se"] / p["A"])


def _validation_table(points, old) -> str:
    """Per surface: the strips (or S = 1 with the patch spectrum) against the BEM, and the
    diffusion with S = 1 (the earlier defaults)
    beside it (the same rows; continuous spectra have no strips, the two coincide)."""
    lines = ["| surface | waves | max m2 | points (BEM A in 1–50 %) | μ error mean [min, max] "
             "| A error mean [min, max] | μ and A within 15 % | diffusion, S = 1: "
             "μ error | A error | within 15 % |", "|---" * 10 + "|"]
    for case in dict.fromkeys(p["case"] for p in points):
        pts = [p for p in points if p["case"] == case and p["in_range"]]
        prev = [p for p in old if p["case"] == case and p["in_range"]]
        if not pts:
            continue
        first = pts[0]
        if "surface" in first:
            s = _series(first["surface"])
            waves, m2 = str(s.size), f"{s.rms_slopes().max():.2f}"
        else:
            waves, m2 = f"{int(round(first['params']['length'] / first['params']['lam_min']))} " \
                        "harmonics", "–"
        cols = []
        for sel in (pts, prev):
            cols += [_rng(np.array([p["e_mu"] for p in sel])),
                     _rng(np.array([p["e_A"] for p in sel])),
                     f"{np.mean([_ok(p) for p in sel]):.0%}"]
        lines.append(f"| {case} | {waves} | {m2} | {len(pts)} | " + " | ".join(cols) + " |")
    return "\n".join(lines)


def _share_table(points, old, nested) -> tuple[str, dict]:
    """Random-ladder points with μ and A within 15 %, by speed: the diffusion with S = 1,
    the strips without outer crests and the strips (``meanfield-strips``)."""
    lines = ["| v [mm/s] | points | BEM realizations | diffusion, S = 1 | "
             "strips without outer crests | strips | strips, within 15 % + 2 s.e. "
             "of the BEM mean |", "|---|---|---|---|---|---|---|"]
    fields = {}
    for v in (*SPEEDS, None):
        sel = [[p for p in pts if _is_random(p["case"]) and p["in_range"]
                and (v is None or p["v"] == v)] for pts in (old, nested, points)]
        shares = [np.mean([_ok(p) for p in s]) for s in sel]
        sampled = np.mean([_ok_sampled(p) for p in sel[2]])
        label = "all" if v is None else f"{v:g}"
        reals = sorted({len(p["bem_mu"]) for p in sel[2]})
        lines.append(f"| {label} | {len(sel[2])} | {'/'.join(map(str, reals))} | "
                     f"{shares[0]:.0%} | {shares[1]:.0%} | {shares[2]:.0%} | {sampled:.0%} |")
        fields[f"share_{label}"] = f"{shares[2]:.0%}"
        fields[f"share_old_{label}"] = f"{shares[0]:.0%}"
        fields[f"share_nested_{label}"] = f"{shares[1]:.0%}"
        fields[f"share_sampled_{label}"] = f"{sampled:.0%}"
    return "\n".join(lines), fields


def _speed_table(points) -> str:
    lines = ["| v [mm/s] | μ error, random ladders | A error, random ladders | μ error, all "
             "multi-wave | A error, all multi-wave |", "|---|---|---|---|---|"]
    for v in SPEEDS:
        rnd = [p for p in points if p["v"] == v and p["in_range"] and _is_random(p["case"])]
        allp = [p for p in points if p["v"] == v and p["in_range"] and p["kind"] == "1d"]
        cols = [_rng(np.array([p[k] for p in sel])) for sel in (rnd,) for k in ("e_mu", "e_A")]
        cols += [_rng(np.array([p[k] for p in allp])) for k in ("e_mu", "e_A")]
        lines.append(f"| {v:g} | " + " | ".join(cols) + " |")
    return "\n".join(lines)


def _speed_curve_table(rows) -> str:
    lines = ["| v [mm/s] | BEM μ (± s.e.) | theory μ | μ error | BEM A | theory A | A error "
             "| diffusion μ | error | diffusion A | error |", "|---" * 11 + "|"]
    for r in sorted((r for r in rows if r["kind"] == "speed"), key=lambda r: r["v"]):
        psd = mf.PSD.from_sines(_series(r["surface"]))
        res = mf.solve(psd, SBR, r["v"], r["p"], options=STRIPS)
        dif = mf.solve(psd, SBR, r["v"], r["p"], options=DIFFUSION)
        mu, area = np.mean(r["bem_mu"]), np.mean(r["bem_A"])
        se = np.std(r["bem_mu"], ddof=1) / np.sqrt(len(r["bem_mu"]))
        lines.append(f"| {r['v']:g} | {mu:.3f} ± {se:.3f} | {res.friction:.3f} | "
                     f"{_pct(res.friction / mu - 1)} | {area:.4f} | {res.contact_fraction:.4f} "
                     f"| {_pct(res.contact_fraction / area - 1)} | {dif.friction:.3f} | "
                     f"{_pct(dif.friction / mu - 1)} | {dif.contact_fraction:.4f} | "
                     f"{_pct(dif.contact_fraction / area - 1)} |")
    return "\n".join(lines)


def _area_bias(points) -> dict:
    rnd = [p for p in points if _is_random(p["case"]) and p["in_range"]]
    small = np.array([p["A"] / p["mf_A"] for p in rnd if p["A"] < 0.05])
    large = np.array([p["A"] / p["mf_A"] for p in rnd if p["A"] > 0.25])
    slow = np.array([p["A"] / p["mf_A"] for p in rnd if p["v"] <= 1.0])
    fast = np.array([p["A"] / p["mf_A"] for p in rnd if p["v"] >= 500.0])
    mu_slow = np.array([p["e_mu"] for p in rnd if p["v"] <= 1.0])
    mu_fast = np.array([p["e_mu"] for p in rnd if p["v"] >= 500.0])
    f = "{:.2f}".format
    return {"small_lo": f(small.min()), "small_hi": f(small.max()), "large_lo": f(large.min()),
            "large_hi": f(large.max()), "slow_ratio": f(slow.mean()), "fast_ratio": f(fast.mean()),
            "mu_slow": _pct(mu_slow.mean()), "mu_fast": _pct(mu_fast.mean())}


def _self_affine_table(points) -> tuple[str, dict]:
    lines = ["| v [mm/s] | σ0 [MPa] | N | realization | BEM μ | BEM A | theory μ | theory A "
             "| μ error | A error | μ, S = 1, mode dissipation | its error "
             "| μ with S = ½ + ½A² | its error | BEM time [s] |",
             "|---" * 15 + "|"]
    persson = mf.MeanFieldOptions(correction=0.5)
    old = mf.MeanFieldOptions(correction=1.0)
    e1, e2, e3 = [], [], []
    for p in sorted((p for p in points if p["kind"] == "selfaffine"),
                    key=lambda p: (p["v"], p["seed"], p["n"])):
        mu_s = mf.solve(_psd(p), SBR, p["v"], p["p"], options=persson).friction
        mu_o = mf.solve(_psd(p), SBR, p["v"], p["p"], options=old).friction
        e1.append(p["e_mu"])
        e2.append(mu_s / p["mu"] - 1)
        e3.append(mu_o / p["mu"] - 1)
        lines.append(f"| {p['v']:g} | {p['p']:.4g} | 2^{int(np.log2(p['n']))} | {p['seed']} "
                     f"| {p['mu']:.4f} | {p['A']:.4f} | {p['mf_mu']:.4f} | {p['mf_A']:.4f} "
                     f"| {_pct(p['e_mu'])} | {_pct(p['e_A'])} | {mu_o:.4f} | "
                     f"{_pct(e3[-1])} | {mu_s:.4f} | "
                     f"{_pct(e2[-1])} | {p['bem_time']:.0f} |")
    sa = [p for p in points if p["kind"] == "selfaffine"]
    t20 = [p["bem_time"] for p in sa if p["n"] == 2**20]
    t18 = [p["bem_time"] for p in sa if p["n"] == 2**18]
    return "\n".join(lines), {"sa_default": _rng(np.array(e1)), "sa_persson": _rng(np.array(e2)),
                               "sa_mode": _rng(np.array(e3)),
                               "t20": f"{max(t20) / 60:.0f}" if t20 else "–",
                               "t18": f"{max(t18) / 60:.1f}" if t18 else "–"}


def _spectrum_table(rows) -> tuple[str, dict]:
    lines = ["| v [mm/s] | σ0 [MPa] | BEM μ (4 realizations) | theory μ | BEM A / theory A "
             "| BEM / theory, dissipation in the wave bands | BEM share above the roughness's "
             "cut-off |", "|---|---|---|---|---|---|---|"]
    fields = {}
    for r in sorted((r for r in rows if r["kind"] == "spectrum"), key=lambda r: r["v"]):
        s = _series(r["surface"])
        res = mf.solve(mf.PSD.from_sines(s), SBR, r["v"], r["p"], options=DIFFUSION)
        bem_a = np.mean(r["bem_A"])
        bands = np.asarray(r["bem_bands"])
        total, in_band = bands.sum(), bands[1:-1].sum()
        tag = "slow" if r["v"] <= 1.0 else "fast"
        fields.update({f"band_{tag}": f"{in_band / res.friction:.2f}",
                       f"tail_{tag}": f"{bands[-1] / total:.0%}",
                       f"area_{tag}": f"{bem_a / res.contact_fraction:.2f}"})
        lines.append(f"| {r['v']:g} | {r['p']:.4g} | {total:.3f} | {res.friction:.3f} | "
                     f"{bem_a / res.contact_fraction:.2f} | {in_band / res.friction:.2f} | "
                     f"{bands[-1] / total:.0%} |")
    return "\n".join(lines), fields


def _hybrid_rows(rows) -> list[dict]:
    out = []
    for r in rows:
        if r["kind"] != "hybrid":
            continue
        s = _series(r["surface"])
        hs, ls = mf.PSD.from_sines(s).partition(1.0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", rc.hybrid.LawWarning)
            rigid = mf.solve(ls, SBR, r["v"], r["p"], law=r["law"], options=HYBRID_RIGID)
            layer = mf.solve(ls, SBR, r["v"], r["p"], law=r["law"], options=HYBRID)
        plain = mf.solve(mf.PSD.from_sines(s), SBR, r["v"], r["p"], options=STRIPS)
        out.append({**r, "win": (np.mean(r["win_mu"]), np.mean(r["win_A"])),
                    "vhs": (np.mean(r["bem_mu"]), np.mean(r["bem_A"])),
                    "rigid": (rigid.friction, rigid.contact_fraction),
                    "layer": (layer.friction, layer.contact_fraction),
                    "plain": (plain.friction, plain.contact_fraction)})
    return out


def _hybrid_table(hyb) -> tuple[str, dict]:
    """The hybrid rows beside hybrid-windowed and the VHS (the exact answer of the linear
    stand-in law), and the error ranges the prose quotes."""
    lines = ["| surface | v [mm/s] | σ0 [MPa] | VHS μ / A | hybrid-windowed μ / A | "
             "error vs VHS μ / A | meanfield-hybrid (law layer) μ / A | error vs windowed "
             "μ / A | error vs VHS μ / A | rigid interface μ / A | error vs windowed μ / A | "
             "meanfield μ / A |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def pair(x):
        return f"{x[0]:.3f} / {x[1]:.4f}"

    def err(x, ref):
        return f"{_pct(x[0] / ref[0] - 1)} / {_pct(x[1] / ref[1] - 1)}"

    for h in hyb:
        w, b = h["win"], h["vhs"]
        lines.append(f"| {h['case']} | {h['v']:g} | {h['p']:.4g} | {pair(b)} | {pair(w)} | "
                     f"{err(w, b)} | {pair(h['layer'])} | {err(h['layer'], w)} | "
                     f"{err(h['layer'], b)} | {pair(h['rigid'])} | {err(h['rigid'], w)} | "
                     f"{pair(h['plain'])} |")

    def ranges(sel, key, ref):
        e = np.array([[h[key][i] / h[ref][i] - 1 for i in (0, 1)] for h in sel]).reshape(-1, 2)
        return _rng(e[:, 0]), _rng(e[:, 1])

    sep = [h for h in hyb if h["case"].startswith("separated")]
    close = [h for h in hyb if not h["case"].startswith("separated")]
    fields = {}
    for tag, sel in (("sep", sep), ("close", close)):
        for key, ref in (("win", "vhs"), ("layer", "vhs"), ("layer", "win")):
            mu, area = ranges(sel, key, ref)
            fields[f"{tag}_{key}_{ref}_mu"], fields[f"{tag}_{key}_{ref}_A"] = mu, area
    return "\n".join(lines), fields


def _two_d_table(rows) -> tuple[str, list]:
    lines = ["| v [mm/s] | σ0 [MPa] | map | BEM μ | BEM A | theory μ (default) | theory A "
             "| μ error | A error | μ with S = 1 | its error | BEM time [s] |",
             "|---" * 12 + "|"]
    errs = []
    for r in sorted((r for r in rows if r["kind"] == "2d"), key=lambda r: (r["v"], r["p"])):
        res = mf.solve(_psd(r), SBR, r["v"], r["p"])
        one = mf.solve(_psd(r), SBR, r["v"], r["p"],
                       options=mf.MeanFieldOptions(correction=1.0)).friction
        e = (res.friction / r["bem_mu"][0] - 1, res.contact_fraction / r["bem_A"][0] - 1,
             one / r["bem_mu"][0] - 1)
        errs.append(e)
        lines.append(f"| {r['v']:g} | {r['p']:.4g} | {r['seed']} | {r['bem_mu'][0]:.4f} | "
                     f"{r['bem_A'][0]:.4f} | {res.friction:.4f} | {res.contact_fraction:.4f} "
                     f"| {_pct(e[0])} | {_pct(e[1])} | {one:.4f} | {_pct(e[2])} "
                     f"| {r['bem_time']:.1f} |")
    return "\n".join(lines), errs


def _log_ticks(ax) -> None:
    from matplotlib.ticker import FixedLocator, NullFormatter, ScalarFormatter

    ax.set_xscale("log")
    ax.xaxis.set_major_locator(FixedLocator([0.01, 0.02, 0.05, 0.1, 0.2, 0.5]))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())


def _figures(points, hyb, rows, folder: Path) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = []
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharex=True)
    cases = list(dict.fromkeys(p["case"] for p in points))
    marks = dict(zip(SPEEDS, "os^D", strict=True))
    for ci, case in enumerate(cases):
        for v in SPEEDS:
            sel = [p for p in points if p["case"] == case and p["v"] == v]
            if not sel:
                continue
            for ax, key in zip(axes, ("e_mu", "e_A"), strict=True):
                ax.plot([p["A"] for p in sel], [100 * p[key] for p in sel], marks.get(v, "x"),
                            color=f"C{ci}", ms=5, label=case if v == SPEEDS[1] else None)
    for ax, title in zip(axes, ("friction", "contact area"), strict=True):
        _log_ticks(ax)
        ax.axhspan(-100 * TARGET, 100 * TARGET, color="0.9")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xlabel("BEM contact fraction")
        ax.set_ylabel(f"theory / BEM − 1 [%] ({title})")
    axes[0].legend(fontsize=7, title="markers: 1, 10, 50, 500 mm/s = o s ^ D", title_fontsize=7)
    fig.tight_layout()
    fig.savefig(folder / "meanfield_errors.png", dpi=120)
    names.append("meanfield_errors.png")
    plt.close(fig)

    press = [r for r in rows if r["kind"] == "pressure"]
    if press:
        r = press[0]
        psd = mf.PSD.from_sines(_series(r["surface"]))
        d = mf.solve(psd, SBR, r["v"], r["p"], options=STRIPS).pressure_distribution
        dd = mf.solve(psd, SBR, r["v"], r["p"], options=DIFFUSION).pressure_distribution
        e = np.asarray(r["edges"])
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.stairs(r["density"], e, label="BEM (8 realizations, σ > 0)")
        ax.plot(d.sigma, d.density, label="strips (histogram of the local pressures)")
        ax.plot(dd.sigma, dd.density, "--", label="diffusion P(σ)")
        ax.set_xlim(0, e[-1])
        ax.set_xlabel("contact pressure σ [MPa]")
        ax.set_ylabel("P(σ) [1/MPa]")
        ax.set_title(f"{r['case']}, {r['v']:g} mm/s, σ0 = {r['p']:.3g} MPa", fontsize=9)
        ax.legend()
        fig.tight_layout()
        fig.savefig(folder / "meanfield_pressure.png", dpi=120)
        names.append("meanfield_pressure.png")
        plt.close(fig)

    if hyb:
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for ax, v in zip(axes, (10.0, 50.0), strict=True):
            for ci, case in enumerate(dict.fromkeys(h["case"] for h in hyb)):
                sel = [h for h in hyb if h["case"] == case and h["v"] == v]
                for key, mk, lab in (("win", "o-", "hybrid-windowed"),
                                     ("layer", "s--", "meanfield-hybrid (law layer)"),
                                     ("rigid", "^:", "meanfield-hybrid, rigid interface")):
                    ax.plot([h[key][1] for h in sel], [h[key][0] for h in sel], mk,
                                color=f"C{ci}", label=f"{case}: {lab}")
            ax.set_title(f"{v:g} mm/s, stand-in (linear) law", fontsize=9)
            _log_ticks(ax)
            ax.set_xlabel("contact fraction")
            ax.set_ylabel("friction μ")
        axes[0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(folder / "meanfield_hybrid.png", dpi=120)
        names.append("meanfield_hybrid.png")
        plt.close(fig)

    speed = sorted((r for r in rows if r["kind"] == "speed"), key=lambda r: r["v"])
    sa = [p for p in points if p["kind"] == "selfaffine" and p["seed"] == 1]
    v = np.logspace(-4, 6, 301)
    fig, ax = plt.subplots(figsize=(6.8, 4.4))
    if speed:
        p0 = speed[0]["p"]
        t2 = mf.PSD.from_sines(_series(speed[0]["surface"]))
        curve = mf.friction_curve(t2, SBR, v[::5], p0, options=STRIPS)
        ax.semilogx(v[::5], curve.friction, "C0", label=f"Table 2, σ0 = {p0:g} MPa: strips")
        curve = mf.friction_curve(t2, SBR, v, p0, options=DIFFUSION)
        ax.semilogx(v, curve.friction, "C0--", lw=1, label="Table 2: diffusion")
        ax.errorbar([r["v"] for r in speed], [np.mean(r["bem_mu"]) for r in speed],
                    yerr=[np.std(r["bem_mu"], ddof=1) / np.sqrt(len(r["bem_mu"]))
                          for r in speed], fmt="o", color="C0", label="Table 2: BEM")
    for i, p in enumerate(sorted({(p["v"], p["p"]) for p in sa})):
        curve = mf.friction_curve(_psd(sa[0]), SBR, v, p[1], options=diffusion(_psd(sa[0])))
        ax.semilogx(v, curve.friction, f"C{i + 1}", lw=1,
                    label=f"self-affine 4 decades, σ0 = {p[1]:.3g} MPa: theory")
        bem = sorted((q for q in sa if (q["v"], q["p"]) == p), key=lambda q: q["n"])[-1:]
        ax.plot([p[0]], [bem[0]["mu"]], "s", color=f"C{i + 1}",
                label=f"self-affine: BEM at {p[0]:g} mm/s, N = 2^{int(np.log2(bem[0]['n']))}")
    ax.set_xlabel("sliding speed v [mm/s]")
    ax.set_ylabel("friction μ")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(folder / "meanfield_speed.png", dpi=120)
    names.append("meanfield_speed.png")
    plt.close(fig)
    return names


def _cost(points) -> dict:
    psd = mf.PSD.self_affine(hurst=0.8, qr=2 * np.pi / 10, q1=2 * np.pi / 1e-4, rms_slope=0.7)
    v = np.logspace(-4, 6, 201)
    t0 = time.perf_counter()
    mf.friction_curve(psd, SBR, v, 0.3)
    sweep = time.perf_counter() - t0
    t2 = mf.PSD.from_sines(rc.roughness.asphalt_ac8())
    t0 = time.perf_counter()
    for _ in range(20):
        mf.solve(t2, SBR, 10.0, 0.3, options=DIFFUSION)
    one = (time.perf_counter() - t0) / 20
    t0 = time.perf_counter()
    for _ in range(5):
        mf.solve(t2, SBR, 10.0, 0.3, options=STRIPS)
    strips = (time.perf_counter() - t0) / 5
    bem = {k: np.mean([p["bem_time"] for p in points if p["case"] == k]) for k in
           ("Table 2", "self-affine 4 decades") if any(p["case"] == k for p in points)}
    return {"sweep": f"{sweep:.2f}", "sweep_nodes": psd.size, "one": f"{1e3 * one:.1f}",
            "one_strips": f"{strips:.2f}",
            "bem_t2": f"{bem.get('Table 2', np.nan):.2f}",
            "bem_sa": f"{bem.get('self-affine 4 decades', np.nan):.0f}"}


def report(rows, *, figures: Path, date: str, commit: str, wall: float, variants) -> str:
    points = _points(rows)
    old = _points(rows, diffusion)
    shares, share_fields = _share_table(points, old, _points(rows, NESTED, ("1d",)))
    hyb = _hybrid_rows(rows)
    hyb_table, hyb_fields = _hybrid_table(hyb)
    two_d, errs_2d = _two_d_table(rows)
    spec, spec_fields = _spectrum_table(rows)
    sa_table, sa_fields = _self_affine_table(points)
    sine_tab, sine_fields = sine_table(rows)
    bands, bands_fields = bands_table(rows)
    trunc, trunc_fields = truncated_table(rows)
    layer, layer_fields = layer_table(rows)
    trip_table, trip_fields = triplets_table(rows)
    scale, oracle, separation, log_area, diag_fields = diagnosis(rows)
    broad, broad_fields = broadband_table(rows)
    gamma_tab, gamma_fields = gamma_table(rows, _psd)
    names = _figures(points, hyb, rows, figures)
    rnd = [p for p in points if _is_random(p["case"]) and p["in_range"]]
    n_1d = sum(r["kind"] == "1d" for r in rows)
    out = [render("meanfield", "title"), "",
           render("meanfield", "intro", date=date, commit=commit, points=n_1d,
                  gamma=gamma_fields["gamma"], two_d_within=gamma_fields["two_d_within"],
                  wall=f"{wall / 60:.1f}", **share_fields, **bands_fields), "",
           render("meanfield", "theory"), "", render("meanfield", "strips"), "",
           render("meanfield", "sine", **sine_fields), "", sine_tab, "",
           render("meanfield", "choices", gamma=gamma_fields["gamma"]), "",
           _choices_table(rows, variants), "",
           render("meanfield", "gamma", **gamma_fields), "", gamma_tab, "",
           render("meanfield", "validation", n_random=len(rnd), **share_fields), "",
           _validation_table(points, old), "", shares, "",
           render("meanfield", "by_speed"), "", _speed_table(points), "",
           render("meanfield", "speed_curve",
                  load=next((f"{r['p']:g}" for r in rows if r["kind"] == "speed"), "–")), "",
           _speed_curve_table(rows), "",
           render("meanfield", "off", **_area_bias(old), **spec_fields), "", spec, "",
           render("meanfield", "diag_scale"), "", scale, "",
           render("meanfield", "diag_oracle", **diag_fields), "", oracle, "",
           render("meanfield", "diag_separation"), "", separation, "",
           render("meanfield", "diag_log"), "", log_area, "",
           render("meanfield", "few_waves"), "",
           render("meanfield", "bands", **bands_fields), "", bands, "",
           render("meanfield", "bands_truncated", **trunc_fields), "", trunc, "",
           render("meanfield", "layer", **layer_fields), "", layer, "",
           render("meanfield", "patches"), "", patches_table(rows), "",
           render("meanfield", "triplets", **trip_fields), "", trip_table, "",
           render("meanfield", "self_affine", t20=sa_fields["t20"], t18=sa_fields["t18"]), "",
           sa_table, "",
           render("meanfield", "broadband", sa_default=sa_fields["sa_default"],
                  sa_persson=sa_fields["sa_persson"], sa_mode=sa_fields["sa_mode"]), "",
           render("meanfield", "broadband_more", **broad_fields), "", broad, "",
           render("meanfield", "hybrid", gamma=gamma_fields["gamma"], **hyb_fields), "",
           hyb_table, "",
           render("meanfield", "two_d",
                  mu=_rng(np.array([e[0] for e in errs_2d])) if errs_2d else "–",
                  area=_rng(np.array([e[1] for e in errs_2d])) if errs_2d else "–",
                  mu_one=_rng(np.array([e[2] for e in errs_2d])) if errs_2d else "–",
                  gamma=f"{mf.DEFAULT_GAMMA:g}"), "",
           two_d, "", render("meanfield", "cost", **_cost(points)), ""]
    out += [f"![{n[:-4]}]({n})" for n in names]
    return "\n".join(out) + "\n"
