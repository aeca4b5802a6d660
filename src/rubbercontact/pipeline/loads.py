"""Loads given as target contact areas: the pressure sweep that brackets them, and the
friction interpolated at them."""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from ..config import RunConfig
from ..hybrid.metrics import interpolate_at_areas, rising_branch
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries


def load_count(cfg: RunConfig) -> int:
    """How many mean pressures a run sweeps: those of ``loads.pressures``, or for target
    contact areas ``loads.sweep_points`` (default two more than the targets, at least 6)."""
    if cfg.loads.pressures is not None:
        return len(cfg.loads.pressures)
    return cfg.loads.sweep_points or max(6, len(cfg.loads.contact_areas) + 2)


def pressure_grid_for_areas(cfg: RunConfig, surfaces: list[SineSeries],
                            material: GeneralizedMaxwell, velocities) -> np.ndarray:
    """Pressures spanning the target contact areas at every speed, estimated with the VHS.

    The area at a given load depends on the speed (the rubber stiffens with frequency),
    so the bounds are taken over all ``velocities`` (the computed speeds): the smallest
    pressure reaching the smallest target and the largest reaching the largest one. The
    hybrid and FEM contact areas differ from the VHS ones, so the grid extends a factor 2
    beyond on either side and is interpolated afterwards.
    """
    from scipy.optimize import brentq

    from .. import halfspace

    targets = np.asarray(cfg.loads.contact_areas)
    s0 = surfaces[0]
    n = min(cfg.halfspace.n, 2048)

    def area(logp: float, v: float) -> float:
        res = halfspace.solve_sliding(s0, s0.period, material, v, float(np.exp(logp)), n=n,
                                      nu=cfg.material.nu)
        return res.contact_fraction

    # full contact needs about E_r m2: bracket with the relaxed modulus below and the
    # modulus at the highest excitation frequency above
    slope = s0.rms_slope
    e_lo = float(abs(material.reduced_modulus(0.0, cfg.material.nu))) * slope
    w_max = float(np.max(s0.wavenumbers)) * max(velocities)
    e_hi = float(abs(material.reduced_modulus(w_max, cfg.material.nu))) * slope
    lo, hi = np.log(1e-6 * e_lo), np.log(2.0 * max(e_lo, e_hi))
    p_lo, p_hi = np.inf, -np.inf
    for v in sorted(set(float(x) for x in velocities)):
        p_lo = min(p_lo, brentq(lambda lp, v=v: area(lp, v) - targets.min(), lo, hi, xtol=1e-3))
        p_hi = max(p_hi, brentq(lambda lp, v=v: area(lp, v) - targets.max(), lo, hi, xtol=1e-3))
    return np.geomspace(np.exp(p_lo) / 2, np.exp(p_hi) * 2, load_count(cfg))


def run_pressures(setup) -> np.ndarray:
    """The mean pressures a run sweeps [MPa]: ``loads.pressures`` sorted, or the grid that
    brackets ``loads.contact_areas`` (:func:`pressure_grid_for_areas`, a few VHS solves).

    ``setup`` is the run's :class:`~.setup.RunSetup`; the same grid serves the run and
    ``run --check``'s estimate of it.
    """
    from .setup import pressure_array, task_material

    cfg = setup.config
    if cfg.loads.pressures is not None:
        return pressure_array(cfg.loads.pressures)
    material = GeneralizedMaxwell(**task_material(setup.material))   # the series at T_ref
    return pressure_grid_for_areas(cfg, setup.realizations, material, setup.speeds.computed)


def at_areas(ds: xr.Dataset, targets: np.ndarray, stacklevel: int = 2) -> xr.Dataset:
    """Friction at the target contact areas, per realization, by load-sweep interpolation.

    Adds ``friction_at_area`` (and ``friction_total_at_area`` when the run has an adhesive
    part). Only the loads on the sweep's rising branch are used (``rising_branch``); a load
    whose contact area does not exceed that of a lower load is left out and named in a
    warning.
    """
    names = [k for k in ("friction", "friction_total") if k in ds]
    out = {k: np.full((ds.sizes["model"], ds.sizes["velocity"], ds.sizes["realization"],
                       targets.size), np.nan) for k in names}
    p = ds["pressure"].values
    folded = []
    for im in range(ds.sizes["model"]):
        for iv in range(ds.sizes["velocity"]):
            for ir in range(ds.sizes["realization"]):
                sel = ds.isel(model=im, velocity=iv, realization=ir)
                a, mu = sel["contact_fraction"].values, sel["friction"].values
                ok = np.isfinite(a) & np.isfinite(mu)
                if ok.sum() < 2:
                    continue
                keep = rising_branch(p[ok], a[ok])
                # full contact repeated at higher loads is no fold: nothing to report
                fold = ~keep & (a[ok] < 1.0 - 1e-9)
                if fold.any():
                    folded.append(f"{ds['model'].values[im]} v={ds['velocity'].values[iv]:g} "
                                  f"r={ir}: σ0=" + ", ".join(f"{x:g}" for x in p[ok][fold]))
                for k in names:
                    y = sel[k].values[ok]
                    out[k][im, iv, ir] = interpolate_at_areas(a[ok][keep], y[keep], targets)
    if folded:
        n = len(folded)
        warnings.warn(f"friction at contact area: {n} load sweep{'s' if n > 1 else ''} "
                      f"ha{'ve' if n > 1 else 's'} loads whose "
                      "contact area does not exceed that at a lower load; those loads are "
                      "left out of the interpolation (the area stopped growing with the "
                      "load there, e.g. a full FEM cell sheared beyond 1): "
                      + "; ".join(folded), RuntimeWarning, stacklevel=stacklevel)
    ds = ds.assign_coords(contact_area=("contact_area", targets,
                                        {"units": "1", "long_name": "target A_c/A_0"}))
    dims = ("model", "velocity", "realization", "contact_area")
    for k in names:
        ds[f"{k}_at_area"] = (dims, out[k], {"units": "1"})
        ds[f"{k}_at_area_mean"] = ds[f"{k}_at_area"].mean("realization")
    return ds
