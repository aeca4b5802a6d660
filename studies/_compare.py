"""The comparisons of the validation: eq. 28 at equal area, its sampling intervals, the
phase-averaged FEM (control variate) and the section 3 variants the studies reuse.

Pure computations on the results of :func:`rubbercontact.pipeline.run` (``xarray`` datasets)
and on the arrays of :func:`phase_average_data`; the words around them are in
``_validation_report`` and ``templates/``.
"""

from __future__ import annotations

import warnings

import numpy as np

import rubbercontact as rc
from rubbercontact.hybrid.metrics import (
    bootstrap_interval,
    control_variate_by_column,
    interpolate_at_areas,
    mean_relative_error,
    rising_branch,
)
from rubbercontact.pipeline import make_runner

#: The paper's eq. 28 error of the hybrid against its full FEM, per velocity [mm/s].
PAPER_E = {10.0: 0.029, 50.0: 0.071}


#: The paper's number of random-phase realizations (its section 3 comparison).
PAPER_REALIZATIONS = 5
#: Bootstrap resamples and the two-sided level of every interval of eq. 28.
RESAMPLES = 2000
INTERVAL_LEVEL = 0.9
#: The VHS's weight of the short waves on Table 2: the waves up to this wavelength [mm].
SHORT_WAVE_CUTOFF = 0.25


def common_areas(curves: dict, points: int = 4):
    """``points`` areas log-spaced over the range every ``(area, μ)`` sweep covers, and
    each model's μ there (nothing extrapolated); None when the sweeps share no range.
    The sweeps come in increasing load; only their rising branch is used (a load whose
    area does not exceed a lower load's is left out, ``rising_branch``)."""
    curves = {m: (a[np.isfinite(a) & np.isfinite(mu)], mu[np.isfinite(a) & np.isfinite(mu)])
              for m, (a, mu) in curves.items()}    # failed loads (NaN) are left out
    for m, (a, mu) in curves.items():
        if a.size:   # per load, in increasing load: the index orders the loads
            keep = rising_branch(np.arange(a.size), a)
            curves[m] = (a[keep], mu[keep])
    if any(a.size < 2 for a, _ in curves.values()):
        return None
    lo = max(a.min() for a, _ in curves.values())
    hi = min(a.max() for a, _ in curves.values())
    if not hi > lo:
        return None
    areas = np.geomspace(lo, hi, points)
    return areas, {m: interpolate_at_areas(a, mu, areas) for m, (a, mu) in curves.items()}


def friction_at_common_areas(ds, points: int = 4) -> dict:
    """Per velocity: target areas and each model's mean friction there.

    With target areas in the config these are the config's (pipeline output); with loads
    given as pressures, ``points`` areas log-spaced over the range that every model's
    load sweep covers (so nothing is extrapolated).
    """
    models = list(ds["model"].values)
    out = {}
    for v in ds["velocity"].values:
        if "friction_at_area_mean" in ds:
            areas = ds["contact_area"].values
            mus = {m: ds["friction_at_area_mean"].sel(model=m, velocity=v).values
                   for m in models}
        else:
            s = ds.sel(velocity=v)
            common = common_areas({m: (s["contact_fraction_mean"].sel(model=m).values,
                                        s["friction_mean"].sel(model=m).values)
                                    for m in models}, points)
            if common is None:
                continue
            areas, mus = common
        ok = np.all([np.isfinite(mus[m]) for m in models], axis=0)
        out[float(v)] = (areas[ok], {m: mus[m][ok] for m in models})
    return out


def eq28_intervals(ds, models=("hybrid", "hybrid-windowed", "vhs"),
                   level: float = INTERVAL_LEVEL, resamples: int = RESAMPLES,
                   points: int = 4) -> dict:
    """``{v: {model: (low, high, used)}}``: the sampling uncertainty of eq. 28 at equal area.

    A paired bootstrap over realizations (``bootstrap_interval``): each resample redoes the
    mean curves of every model on the same drawn realizations, the common areas and the
    error, exactly as ``friction_at_common_areas`` does for the whole set.
    """
    models = [m for m in models if m in ds["model"].values]
    out = {}
    for v in ds["velocity"].values:
        s = ds.sel(velocity=v)
        if "friction_at_area" in ds:
            mu_k = {m: s["friction_at_area"].sel(model=m).transpose("realization", ...).values
                    for m in ds["model"].values}

            def stat(idx, m, mu_k=mu_k):
                mus = {k: x[idx].mean(axis=0) for k, x in mu_k.items()}
                ok = np.all([np.isfinite(x) for x in mus.values()], axis=0)
                return mean_relative_error(mus["fem"][ok], mus[m][ok]) if ok.any() else np.nan
        else:
            arr = {m: (s["contact_fraction"].sel(model=m).transpose("realization", ...).values,
                       s["friction"].sel(model=m).transpose("realization", ...).values)
                   for m in ds["model"].values}

            def stat(idx, m, arr=arr):
                return eq28_of_curves({k: (a[idx].mean(axis=0), mu[idx].mean(axis=0))
                                        for k, (a, mu) in arr.items()}, [m], points)[m]
        out[float(v)] = {m: bootstrap_interval(lambda idx, m=m: stat(idx, m),
                                               ds.sizes["realization"], resamples=resamples,
                                               level=level)
                         for m in models}
    return out


def hybrid_with_linear_law(ds, n: int = 4096) -> dict:
    """The hybrids with their FEM law replaced by the VHS solution of the high-slope wave.

    Separates the two approximations of the hybrid: the law (FEM vs linear) and the scale
    split itself (the high-slope wave homogenized under the low-slope contacts). With a
    linear law a hybrid would reproduce the VHS if the scales were well separated.
    Returns ``{(v, p): {"hybrid" | "hybrid-windowed": (mean μ, mean A)}}`` over the
    realizations.
    """
    from rubbercontact.hybrid.law import linear_law
    from rubbercontact.hybrid.tasks import halfspace_task
    from rubbercontact.roughness import SineSeries

    mat = rc.materials.sbr()
    hs_mask = ds["high_slope"].values.astype(bool)
    lam, amp = ds["wavelength"].values, ds["amplitude"].values
    readings = {"hybrid": None, "hybrid-windowed": float(lam[hs_mask].max())}
    out: dict = {}
    for v in ds["velocity"].values:
        vals: dict = {}
        for ir in range(ds.sizes["realization"]):
            ph = ds["phase"].isel(realization=ir).values
            hs = SineSeries(lam[hs_mask], amp[hs_mask], ph[hs_mask])
            ls = SineSeries(lam[~hs_mask], amp[~hs_mask], ph[~hs_mask])
            table = linear_law(hs, mat, float(v))
            for p in ds["pressure"].values:
                for name, window in readings.items():
                    res = halfspace_task(ls.as_dict(), float(ds.attrs["period_mm"]),
                                         mat.as_dict(), float(v), float(p), n=n,
                                         interface_law=table, hs_window=window)
                    vals.setdefault((float(p), name), []).append(
                        (float(res["friction"]), float(res["contact_fraction"])))
        for (p, name), rows in vals.items():
            out.setdefault((float(v), p), {})[name] = tuple(np.mean(rows, axis=0))
    return out


# FEM contact-area factors of the sensitivity check (about the resolution at h/a ~ 0.5-1)
AREA_FACTORS = (1.05, 1.0, 0.95, 0.9)


def with_realization_means(ds):
    """``ds`` with ``friction_mean`` and ``contact_fraction_mean`` redone from the
    realizations it holds (after a subset, a replaced model or a scaled area)."""
    return ds.assign(friction_mean=ds["friction"].mean("realization"),
                     contact_fraction_mean=ds["contact_fraction"].mean("realization"))


def eq28_at_equal_area(ds, models=("hybrid", "hybrid-windowed", "vhs")) -> dict:
    """``{v: (areas, {model: e})}``: eq. 28 against the FEM at the common areas of
    ``friction_at_common_areas`` (the comparison of VALIDATION.md)."""
    return {v: (areas, {m: mean_relative_error(mus["fem"], mus[m]) for m in models
                        if m in mus})
            for v, (areas, mus) in friction_at_common_areas(ds).items()}


def eq28_first(ds, k: int | None = None,
               models=("hybrid", "hybrid-windowed", "vhs")) -> dict:
    """``{v: (areas, {model: e}, {model: (low, high, used)})}``: eq. 28 at equal area over
    the first ``k`` realizations (all: None), with its bootstrap interval (none for one
    realization)."""
    sub = ds if k is None else with_realization_means(ds.isel(realization=slice(0, k)))
    ci = eq28_intervals(sub, models=models) if sub.sizes["realization"] >= 2 else {}
    return {v: (areas, e, ci.get(v, {}))
            for v, (areas, e) in eq28_at_equal_area(sub, models).items()}


#: Realizations of the cheap models (VHS, hybrids) behind the phase-averaged eq. 28.
PHASE_REALIZATIONS = 1000


CHEAP_MODELS = ("hybrid", "hybrid-windowed", "vhs")


def phase_average_data(ds, cfg, n: int = PHASE_REALIZATIONS) -> dict:
    """Per velocity, the arrays behind the phase-averaged eq. 28 (``eq28_phase_averaged``).

    The hybrid predicts the friction of the random-phase surface on average over the
    phases, and its cheap models can afford many realizations where the FEM cannot. This
    runs the VHS and the hybrids of ``cfg`` on ``n`` realizations (same seed, so the first
    R are those of ``ds``; checked value by value against ``ds``) through the cache, and
    returns ``{v: {"pressures", "fem": (A, μ), "paired": {m: (A, μ)}, "all": {m: (A, μ)}}}``
    with arrays ``(realization, pressure)``: the FEM and the cheap models on the R
    realizations of ``ds``, and the cheap models on all ``n``.
    """
    models = [m for m in CHEAP_MODELS if m in ds["model"].values]
    r = ds.sizes["realization"]
    if "vhs" not in models or "fem" not in ds["model"].values or n < r:
        return {}
    data = cfg.model_dump(mode="json", exclude_none=True)
    data.update(models=models, realizations=int(n))
    cheap_cfg = rc.config.parse_config(data, source=f"section3 ({n} realizations)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the same law and loads: ds's run has warned
        cheap = rc.pipeline.run(cheap_cfg, runner=make_runner(cheap_cfg, progress="log"))

    def arrays(d, m, v):
        return tuple(d[k].sel(model=m, velocity=v).transpose("realization", "pressure").values
                     for k in ("contact_fraction", "friction"))

    if not np.allclose(cheap["phase"].values[:r], ds["phase"].values, rtol=0, atol=1e-12):
        raise RuntimeError("phase average: the n-realization run does not start with the "
                           "realizations of the validation run (seed changed?)")
    out = {}
    for v in ds["velocity"].values:
        paired = {m: arrays(ds, m, v) for m in models}
        every = {m: arrays(cheap, m, v) for m in models}
        for m in models:      # the pairing the control variate relies on
            for x, y in zip(every[m], paired[m], strict=True):
                if not np.allclose(x[:r], y, rtol=1e-12, atol=0, equal_nan=True):
                    raise RuntimeError(f"phase average: {m} at {v:g} mm/s differs from the "
                                       "validation run on the same realizations")
        out[float(v)] = {"pressures": ds["pressure"].values, "fem": arrays(ds, "fem", v),
                         "paired": paired, "all": every}
    return out


def _column_mean(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)   # an all-failed load stays NaN
        return np.nanmean(x[idx], axis=0)


def phase_mean_curves(data: dict, idx_r=None, idx_n=None, beta: str = "difference") -> dict:
    """``{"plain": {m: (Ā, μ̄)}, "phase": {m: (Ā, μ̄)}}`` per load of one velocity.

    *plain*: every model averaged over the R realizations with a full FEM (VALIDATION's
    eq. 28); *phase*: the cheap models over all N, the FEM as ``mean_N(VHS) + mean_R(FEM −
    VHS)`` (``control_variate_mean``; a failed FEM test drops that realization at its load).
    ``idx_r`` / ``idx_n`` resample the R and the N realizations (bootstrap); ``beta``:
    ``"regression"`` fits the control's coefficient per load (``control_variate_by_column``).
    """
    fem = data["fem"]
    r, n = fem[0].shape[0], data["all"]["vhs"][0].shape[0]
    idx_r = np.arange(r) if idx_r is None else np.asarray(idx_r)
    idx_n = np.arange(n) if idx_n is None else np.asarray(idx_n)
    plain = {m: tuple(_column_mean(x, idx_r) for x in xs)
             for m, xs in [("fem", fem), *data["paired"].items()]}
    phase = {m: tuple(_column_mean(x, idx_n) for x in xs) for m, xs in data["all"].items()}
    cv = [control_variate_by_column(t[idx_r], c[idx_r], call[idx_n], beta)[0]
          for t, c, call in zip(fem, data["paired"]["vhs"], data["all"]["vhs"], strict=True)]
    phase["fem"] = tuple(cv)
    return {"plain": plain, "phase": phase}


def eq28_of_curves(curves: dict, models, points: int = 4) -> dict:
    """``{m: e}``: eq. 28 against ``curves["fem"]`` at the common areas of mean curves."""
    common = common_areas(curves, points)
    if common is None:
        return {m: np.nan for m in models}
    _, mus = common
    ok = np.all([np.isfinite(x) for x in mus.values()], axis=0)
    return {m: mean_relative_error(mus["fem"][ok], mus[m][ok]) if ok.any() else np.nan
            for m in models}


def eq28_phase_averaged(phase_data: dict, resamples: int = RESAMPLES,
                        level: float = INTERVAL_LEVEL,
                        seed: int = 0, beta: str = "difference") -> dict:
    """``{v: ({m: e}, {m: (low, high, used)})}``: eq. 28 at equal area against the
    phase-averaged FEM, with a two-sample bootstrap interval (the R FEM realizations and
    the N cheap ones resampled independently, ``resamples`` times; a fitted β is refitted
    in every resample)."""
    out = {}
    for v, data in phase_data.items():
        models = [m for m in CHEAP_MODELS if m in data["all"]]
        e = eq28_of_curves(phase_mean_curves(data, beta=beta)["phase"], models)
        r, n = data["fem"][0].shape[0], data["all"]["vhs"][0].shape[0]
        rng = np.random.default_rng(seed)
        draws = []
        for _ in range(int(resamples)):     # one resample serves every model (paired)
            d = eq28_of_curves(phase_mean_curves(
                data, rng.integers(0, r, r), rng.integers(0, n, n), beta)["phase"], models)
            draws.append([d[m] for m in models])
        draws = np.array(draws)
        ci = {}
        for j, m in enumerate(models):
            x = draws[:, j][np.isfinite(draws[:, j])]
            if x.size:
                low, high = np.quantile(x, [(1 - level) / 2, (1 + level) / 2])
                ci[m] = (float(low), float(high), int(x.size))
        out[v] = (e, ci)
    return out


#: Loads [MPa] added to section 3's three, per speed, so that the comparison spans the
#: paper's area range 0.01-0.1 (phase-averaged FEM areas 0.012-0.10 at 10 mm/s, 0.009-0.1
#: at 50 mm/s), each with the number of realizations (the first ones) its full FEM ran on.
#: A 50 mm/s, 2 MPa test costs about half an hour on one core.
EXTENDED_LOADS = {10.0: {0.05: 5, 0.1: 5, 1.2: 5}, 50.0: {0.1: 5, 2.0: 5}}


def merge_phase_data(a: dict, b: dict) -> dict:
    """One velocity's phase data (``phase_average_data``) over the loads of ``a`` and ``b``.

    Both come from the same seed and N; ``b`` may have fewer FEM realizations than ``a``
    (its FEM rows are padded with NaN, which ``phase_mean_curves`` leaves out at that load;
    the paired cheap models are the first R of the N, so they need no padding). Loads must
    not repeat; the result is sorted by load.
    """
    p = np.concatenate([a["pressures"], b["pressures"]])
    if np.unique(p).size != p.size:
        raise ValueError(f"merge_phase_data: loads repeat: {sorted(p.tolist())}")
    if set(a["all"]) != set(b["all"]) or a["all"]["vhs"][0].shape[0] != b["all"]["vhs"][0].shape[0]:
        raise ValueError("merge_phase_data: the two sets differ in models or in N")
    order = np.argsort(p)
    r = max(a["fem"][0].shape[0], b["fem"][0].shape[0])

    def pad(x):
        return np.vstack([x, np.full((r - x.shape[0], x.shape[1]), np.nan)])

    def join(xa, xb, fill):
        return np.hstack([fill(xa), fill(xb)])[:, order]

    every = {m: tuple(join(xa, xb, lambda x: x) for xa, xb in zip(a["all"][m], b["all"][m],
                                                                   strict=True))
             for m in a["all"]}
    return {"pressures": p[order],
            "fem": tuple(join(xa, xb, pad) for xa, xb in zip(a["fem"], b["fem"], strict=True)),
            "paired": {m: tuple(x[:r] for x in xs) for m, xs in every.items()},
            "all": every}


def extended_phase_data(cfg, phase_data: dict, used_keys: set[str] | None = None,
                        loads: dict | None = None) -> dict:
    """Section 3's phase data with the loads of ``loads`` (default :data:`EXTENDED_LOADS`:
    ``{velocity: {load: realizations}}``) added, per velocity.

    Runs every model at the added loads on the realizations given there (the full FEM is
    the dear part; the reference cache holds it), then the cheap models on the same N as
    ``phase_data``, and merges.
    """
    extra = EXTENDED_LOADS if loads is None else loads
    out = {}
    for v, data in phase_data.items():
        if v not in extra:
            continue
        n = data["all"]["vhs"][0].shape[0]
        merged = data
        for r in sorted(set(extra[v].values())):
            added = [p for p, k in extra[v].items() if k == r]
            base = cfg.model_dump(mode="json", exclude_none=True)
            base.update(velocities=[v], realizations=r, loads={"pressures": added})
            ext_cfg = rc.config.parse_config(base, source=f"section3 extended ({v:g} mm/s)")
            runner = make_runner(ext_cfg, progress="log")

            def recording(tasks, description="sweep", runner=runner):
                if used_keys is not None:
                    used_keys.update(t.key() for t in tasks)
                return runner(tasks, description)

            with warnings.catch_warnings():
                warnings.simplefilter("ignore")    # the law warned in the main run
                ds = rc.pipeline.run(ext_cfg, runner=recording)
            merged = merge_phase_data(merged, phase_average_data(ds, ext_cfg, n)[v])
        out[v] = merged
    return out


def without_model(data: dict, model: str) -> dict:
    return {**data, "paired": {m: x for m, x in data["paired"].items() if m != model},
            "all": {m: x for m, x in data["all"].items() if m != model}}


def phase_area_range(data: dict) -> tuple[float, float]:
    common = common_areas(phase_mean_curves(data)["phase"])
    return (np.nan, np.nan) if common is None else (common[0][0], common[0][-1])


def below_load(data: dict, pmax: float) -> dict:
    """``data`` at the loads below ``pmax`` only."""
    keep = data["pressures"] < pmax

    def cut(xs):
        return tuple(x[:, keep] for x in xs)

    return {"pressures": data["pressures"][keep], "fem": cut(data["fem"]),
            "paired": {m: cut(x) for m, x in data["paired"].items()},
            "all": {m: cut(x) for m, x in data["all"].items()}}


def with_area_factor(ds, factor: float):
    """``ds`` with the FEM's contact fractions multiplied by ``factor`` (friction unchanged)."""
    ds = ds.copy(deep=True)
    ds["contact_fraction"].loc[{"model": "fem"}] = ds["contact_fraction"].sel(model="fem") * factor
    return with_realization_means(ds)


def area_sensitivity(ds, models=("hybrid-windowed", "vhs")) -> dict:
    """``{factor: {v: {model: e}}}``: eq. 28 at equal area with every FEM contact fraction
    scaled by each of ``AREA_FACTORS``."""
    return {factor: {v: e for v, (_, e) in
                     eq28_at_equal_area(with_area_factor(ds, factor), models).items()}
            for factor in AREA_FACTORS}


def per_realization_errors(ds, models=("hybrid-windowed", "vhs"), points: int = 4) -> dict:
    """``{v: {model: [e_r]}}``: eq. 28 at equal area within each realization.

    The paper's eq. 28 compares realization means. This compares each realization's own
    load sweep (common areas as in ``common_areas``), so it says how well a model predicts
    one surface rather than the ensemble; NaN where that realization's sweeps share no area.
    """
    models = [m for m in models if m in ds["model"].values]
    out: dict = {}
    for v in ds["velocity"].values:
        s = ds.sel(velocity=v)
        errs: dict = {m: [] for m in models}
        for r in range(ds.sizes["realization"]):
            sr = s.isel(realization=r)
            common = common_areas({m: (sr["contact_fraction"].sel(model=m).values,
                                        sr["friction"].sel(model=m).values)
                                    for m in [*models, "fem"]}, points)
            for m in models:
                errs[m].append(np.nan if common is None
                               else mean_relative_error(common[1]["fem"], common[1][m]))
        out[float(v)] = errs
    return out


def short_wave_share(ds, cfg) -> dict:
    """VHS on Table 2 without its three shortest waves, at the same loads and phases."""
    from rubbercontact import halfspace
    from rubbercontact.roughness import SineSeries, asphalt_ac8

    base = asphalt_ac8()
    keep = base.wavelengths > SHORT_WAVE_CUTOFF
    out = {}
    mat = rc.materials.sbr()
    for v in ds["velocity"].values:
        for p in ds["pressure"].values:
            mus = []
            for ir in range(ds.sizes["realization"]):
                phases = ds["phase"].isel(realization=ir).values
                s = SineSeries(base.wavelengths[keep], base.amplitudes[keep], phases[keep])
                r = halfspace.solve_sliding(s, base.period, mat, float(v), float(p),
                                            law=halfspace.LennardJonesRepulsion(),
                                            n=cfg.halfspace.n)
                mus.append(r.friction)
            full = float(ds["friction_mean"].sel(model="vhs", velocity=v, pressure=p))
            out[(float(v), float(p))] = 1.0 - float(np.mean(mus)) / full
    return out

