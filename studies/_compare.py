"""The runs behind the validation's comparisons: the cheap models on many realizations,
the extended loads, the paper's figures to compare with.

The comparisons themselves (eq. 28 at equal area, its intervals, the phase-averaged FEM)
are the library's, :mod:`rubbercontact.compare`, re-exported here for the studies; the
words around them are in ``_validation_report`` and ``templates/``.
"""

from __future__ import annotations

import warnings

import numpy as np

import rubbercontact as rc
from rubbercontact.compare import (  # noqa: F401 - the studies read them as compare.NAME
    AREA_FACTORS,
    CHEAP_MODELS,
    INTERVAL_LEVEL,
    RESAMPLES,
    area_sensitivity,
    below_load,
    common_areas,
    eq28_at_equal_area,
    eq28_first,
    eq28_intervals,
    eq28_of_curves,
    eq28_phase_averaged,
    eq28_phase_bounds,
    eq28_realization_bounds,
    friction_at_common_areas,
    merge_phase_data,
    per_realization_errors,
    phase_area_range,
    phase_mean_curves,
    with_area_factor,
    with_realization_means,
    without_model,
)
from rubbercontact.pipeline import make_runner

#: The paper's eq. 28 error of the hybrid against its full FEM, per velocity [mm/s].
PAPER_E = {10.0: 0.029, 50.0: 0.071}


#: The paper's number of random-phase realizations (its section 3 comparison).
PAPER_REALIZATIONS = 5
#: The VHS's weight of the short waves on Table 2: the waves up to this wavelength [mm].
SHORT_WAVE_CUTOFF = 0.25


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


#: Realizations of the cheap models (VHS, hybrids) behind the phase-averaged eq. 28.
PHASE_REALIZATIONS = 1000


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


#: Loads [MPa] added to section 3's three, per speed, so that the comparison spans the
#: paper's area range 0.01-0.1 (phase-averaged FEM areas 0.012-0.10 at 10 mm/s, 0.009-0.1
#: at 50 mm/s), each with the number of realizations (the first ones) its full FEM ran on.
#: A 50 mm/s, 2 MPa test costs about half an hour on one core.
EXTENDED_LOADS = {10.0: {0.05: 5, 0.1: 5, 1.2: 5}, 50.0: {0.1: 5, 2.0: 5}}


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

