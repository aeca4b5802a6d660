"""Master curve from isothermal frequency sweeps: horizontal shifts, then a shift law.

1. *Pairwise shifts*: for each pair of neighbouring isotherms, the horizontal shift
   ``Δ = log10 a_warm − log10 a_cold`` minimises the mean squared difference of
   ``log E'`` and ``log E''`` between the warm sweep moved by ``Δ`` and the cold sweep
   (linear interpolation in ``log ω``) over their overlap (at least 3 points): a grid
   search over ±``max_shift`` decades in 0.01-decade steps, then a bounded scalar
   minimisation around the best node.
2. The shifts are summed from the reference isotherm outward (``log10 a = 0`` there).
3. *Shift law*: WLF ``C1, C2`` by least squares on ``log10 a_T`` (started from the
   linearised form ``ΔT / log10 a = −C2/C1 − ΔT/C1``), or Arrhenius ``E_a`` by linear
   least squares in ``1/T − 1/T_ref``.

With ``vertical=True`` the moduli at ``T`` are first multiplied by ``T_ref/T`` (kelvin;
the ``ρT`` factor with the density change neglected).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from ..errors import InputError
from .dmadata import DMAData
from .shift import GAS_CONSTANT, WLF, ZERO_CELSIUS, Arrhenius, ShiftLaw

__all__ = ["MasterCurve", "master_curve"]


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """A master curve built from isotherms.

    Attributes
    ----------
    data
        The shifted data at the reference temperature, carrying the fitted shift law.
    temperatures
        Isotherm temperatures [°C], ascending.
    log10_shifts
        Measured horizontal shifts ``log10 a_T`` of each isotherm [-] (0 at the reference).
    law
        The fitted :class:`~rubbercontact.materials.WLF` or
        :class:`~rubbercontact.materials.Arrhenius` law.
    law_rms_error
        rms of ``log10 a_T`` (law) − measured over the isotherms [decades].
    """

    data: DMAData
    temperatures: np.ndarray
    log10_shifts: np.ndarray
    law: ShiftLaw
    law_rms_error: float


def _log_curves(iso: DMAData, b: float):
    return np.log10(iso.frequency), np.log10(iso.storage * b), np.log10(iso.loss * b)


def _mismatch(delta: float, cold, warm) -> float:
    """Mean squared log-modulus difference with the warm sweep moved by ``delta`` decades."""
    x = warm[0] + delta
    inside = (x >= cold[0][0]) & (x <= cold[0][-1])
    if inside.sum() < 3:
        return np.inf
    d1 = warm[1][inside] - np.interp(x[inside], cold[0], cold[1])
    d2 = warm[2][inside] - np.interp(x[inside], cold[0], cold[2])
    return float(np.mean(d1**2 + d2**2))


def _pair_shift(cold, warm, max_shift: float, label: str) -> float:
    grid = np.arange(-max_shift, max_shift + 1e-9, 0.01)
    cost = np.array([_mismatch(d, cold, warm) for d in grid])
    if not np.isfinite(cost).any():
        raise InputError(f"master curve: sweeps at {label} do not overlap within "
                         f"±{max_shift:g} decades; measure closer temperatures")
    k = int(np.argmin(cost))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    best = minimize_scalar(_mismatch, bounds=(lo, hi), args=(cold, warm), method="bounded",
                           options={"xatol": 1e-6})
    return float(best.x) if best.fun <= cost[k] else float(grid[k])


def _fit_wlf(dt: np.ndarray, y: np.ndarray) -> WLF:
    mask = dt != 0
    if mask.sum() < 2:
        raise InputError("master curve: WLF needs isotherms at >= 2 temperatures besides "
                         "the reference")
    slope, intercept = np.polyfit(dt[mask], dt[mask] / y[mask], 1)
    c1_0 = -1.0 / slope
    c2_0 = -intercept * c1_0
    c2_min = -dt.min() + 1e-6
    x0 = np.array([max(c1_0, 1e-3), max(c2_0, c2_min + 1.0)])

    def resid(p):
        return -p[0] * dt / (p[1] + dt) - y

    fit = least_squares(resid, x0, bounds=([1e-6, c2_min], [np.inf, np.inf]))
    return WLF(float(fit.x[0]), float(fit.x[1]), 0.0)


def master_curve(dma: DMAData, t_ref: float | None = None, *, law: str = "WLF",
                 vertical: bool = False, max_shift: float = 15.0) -> MasterCurve:
    """Shift isothermal sweeps onto one master curve and fit a shift law to the shifts.

    Parameters
    ----------
    dma
        Data with a temperature column (sweeps at >= 2 temperatures).
    t_ref
        Reference temperature [°C], one of the isotherms (default: the data's
        ``temperature``).
    law
        ``"WLF"`` (needs >= 3 isotherms) or ``"Arrhenius"``.
    vertical
        Apply the ``T_ref/T`` vertical factor before shifting.
    max_shift
        Largest pairwise shift searched [decades].

    Returns
    -------
    MasterCurve
    """
    temps = dma.isotherm_temperatures
    if temps.size < 2:
        raise InputError("master curve: needs isothermal sweeps at >= 2 temperatures "
                         "(a temperature column)")
    t_ref = dma.temperature if t_ref is None else float(t_ref)
    if t_ref is None:
        raise InputError("master curve: give the reference temperature (t_ref= or "
                         "read_dma(..., temperature=))")
    near = np.abs(temps - t_ref) < 1e-9
    if not near.any():
        raise InputError(f"master curve: t_ref {t_ref:g} °C is not one of the isotherms "
                         f"{temps.tolist()} °C")
    if law not in ("WLF", "Arrhenius"):
        raise InputError(f"law: expected 'WLF' or 'Arrhenius', got {law!r}")
    isos = dma.isotherms()
    kelvin = temps + ZERO_CELSIUS
    b = (t_ref + ZERO_CELSIUS) / kelvin if vertical else np.ones_like(temps)
    curves = [_log_curves(iso, bi) for iso, bi in zip(isos, b, strict=True)]
    steps = [_pair_shift(curves[i], curves[i + 1], max_shift,
                         f"{temps[i]:g} and {temps[i + 1]:g} °C")
             for i in range(temps.size - 1)]
    log_a = np.concatenate([[0.0], np.cumsum(steps)])
    i_ref = int(np.argmax(near))
    log_a -= log_a[i_ref]
    dt = temps - t_ref
    if law == "WLF":
        base = _fit_wlf(dt, log_a)
        fitted: ShiftLaw = WLF(base.c1, base.c2, t_ref)
    else:
        x = (1.0 / kelvin - 1.0 / (t_ref + ZERO_CELSIUS)) / np.log(10.0)
        ea = float(np.dot(x, log_a) / np.dot(x, x)) * GAS_CONSTANT
        if ea <= 0:
            raise InputError("master curve: the shifts grow with temperature; an Arrhenius "
                             "law needs them to fall")
        fitted = Arrhenius(ea, t_ref)
    rms = float(np.sqrt(np.mean((np.asarray(fitted.log10_shift(temps)) - log_a) ** 2)))
    a = 10.0 ** log_a
    w = np.concatenate([iso.frequency * ai for iso, ai in zip(isos, a, strict=True)])
    e1 = np.concatenate([iso.storage * bi for iso, bi in zip(isos, b, strict=True)])
    e2 = np.concatenate([iso.loss * bi for iso, bi in zip(isos, b, strict=True)])
    prov = {**dma.provenance, "master_curve": {
        "temperatures": temps.tolist(), "log10_shifts": log_a.tolist(),
        "law": fitted.as_dict(), "law_rms_error": rms, "vertical": bool(vertical)}}
    data = DMAData(w, e1, e2, temperature=t_ref, shift=fitted, source=dma.source,
                   frequency_unit=dma.frequency_unit, provenance=prov)
    return MasterCurve(data, temps, log_a, fitted, rms)
