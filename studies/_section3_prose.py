"""Section 3 of VALIDATION.md: the paragraphs before the eq. 28 table.

What the quick level reduces (meshes, time steps, realizations) and why, how this run's
FEM was solved (steady, fallen back, its bulk shear; against the time-stepped test), how
well the realizations pin down the FEM's friction and how eq. 28 moves with the FEM area.
"""

from __future__ import annotations

import json

import numpy as np

from ._compare import AREA_FACTORS, area_sensitivity, per_realization_errors
from ._section3_text import _s3
from ._validation_report import ROOT, joined, not_steady


def _sci(x: float) -> str:
    """``1.04e-4``: three digits, exponent without padding."""
    mantissa, exponent = f"{x:.2e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _mesh(m) -> str:
    return f"{m[0]} x {m[1]}"


#: The steady solver's time-step study (studies/steady_time_step.py), once it is written.
TIME_STEP_STUDY = ROOT / "docs" / "validation" / "steady_time_step.md"


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
        # the law cell's quasi-static check points are said by the run's law lines
        bad = not_steady(full + law)
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
