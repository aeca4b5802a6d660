"""Fit a generalized Maxwell (Prony) series to DMA data.

Method, in two steps, on ``E'`` and ``E''`` together with each residual relative to its
datum (``E'_fit/E' − 1`` and ``E''_fit/E'' − 1``, so a low-loss decade counts as much as
the glassy peak):

1. *NNLS*: the relaxation times are fixed, ``n`` log-spaced over the data's range
   ``[1/ω_max, 1/ω_min]``; the equilibrium modulus ``E_∞`` and the branch moduli ``E_i``
   enter linearly and are found by non-negative least squares. Branches whose modulus
   comes out 0 are dropped. This is global and robust, but a fixed grid cannot place a
   loss peak between its nodes: at 2 times per decade it leaves errors of a few % in
   ``E''`` even on data that are exactly a Prony series.
2. *Refinement* (``refine=True``, default): the kept ``E_∞, E_i, τ_i`` are refined
   together by nonlinear least squares (trust region, analytic Jacobian) in
   ``log E`` and ``log τ`` — so the moduli stay positive — with ``τ_i`` bounded to
   ``[0.1/ω_max, 10/ω_min]``. The result is never worse than step 1. Branches the
   refinement drives within 1 % of one time are merged, those below 1e-6 of the data
   everywhere dropped, and the rest refined once more.

Rule for the number of terms (``terms=None``): fit with 0.5, 1, 1.5 and 2 grid times per
decade (``n = round(density · decades) + 1``), in that order, and take the first whose rms
relative residual is within ``tolerance`` (default 1 %) or within 10 % of the next denser
one's (the noise floor: more terms then only fit the scatter); else the densest.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares, nnls

from ..errors import InputError
from .dmadata import DMAData, DMAWarning
from .maxwell import GeneralizedMaxwell

__all__ = ["FitReport", "PronyFit", "fit_prony", "DENSITIES"]

#: Relaxation times per decade tried by the ``terms=None`` rule.
DENSITIES = (0.5, 1.0, 1.5, 2.0)
#: rms relative residual above which the fit warns that data and model disagree.
WARN_RMS = 0.05
RULE = ("first of {0.5, 1, 1.5, 2} log-spaced relaxation times per decade over "
        "[1/omega_max, 1/omega_min] (NNLS, then refined) whose rms relative residual of "
        "E' and E'' is <= tolerance or <= 1.1 x the next denser fit's; else the densest")


@dataclass(frozen=True)
class FitReport:
    """How well a Prony series fits DMA data (relative errors over the data points).

    Attributes
    ----------
    terms
        Relaxation times in the basis (requested or chosen by the rule).
    terms_kept
        Branches with a non-zero modulus (the material's ``n_branches``).
    per_decade
        Basis relaxation times per decade of frequency.
    rule
        How ``terms`` was chosen (``"given"`` or the rule text).
    tolerance
        The rule's target rms relative residual [-].
    rms_error
        rms over points of the fitted residual, ``(E'_fit/E' − 1)`` and
        ``(E''_fit/E'' − 1)`` together [-].
    storage_rms_error, storage_max_error, loss_rms_error, loss_max_error
        rms and max of ``|E'_fit/E' − 1|`` and ``|E''_fit/E'' − 1|`` [-].
    modulus_rms_error, modulus_max_error
        rms and max of ``|E*_fit − E*|/|E*|`` [-].
    frequency_range
        ``(ω_min, ω_max)`` of the data [rad/s].
    n_points
        Data points.
    candidates
        ``(terms, rms_error)`` of every basis tried.
    """

    terms: int
    terms_kept: int
    per_decade: float
    rule: str
    tolerance: float
    rms_error: float
    storage_rms_error: float
    storage_max_error: float
    loss_rms_error: float
    loss_max_error: float
    modulus_rms_error: float
    modulus_max_error: float
    frequency_range: tuple[float, float]
    n_points: int
    candidates: tuple[tuple[int, float], ...]

    def as_dict(self) -> dict:
        d = {k: getattr(self, k) for k in self.__dataclass_fields__}
        d["frequency_range"] = list(self.frequency_range)
        d["candidates"] = [list(c) for c in self.candidates]
        return d

    def summary(self) -> str:
        return (f"{self.terms_kept} branches (basis {self.terms}, {self.per_decade:.2g}/decade) "
                f"over {self.n_points} points: |E*| rms {100 * self.modulus_rms_error:.2f} %, "
                f"max {100 * self.modulus_max_error:.2f} %; E' max "
                f"{100 * self.storage_max_error:.2f} %, E'' max {100 * self.loss_max_error:.2f} %")


@dataclass(frozen=True)
class PronyFit:
    """The fitted material and its report (``fit_prony(..., report=True)``)."""

    material: GeneralizedMaxwell
    report: FitReport


@dataclass(frozen=True)
class _Solution:
    terms: int
    e_inf: float
    moduli: np.ndarray
    times: np.ndarray
    rms: float


def _basis_times(w_min: float, w_max: float, n: int) -> np.ndarray:
    if n == 1:
        return np.array([1.0 / np.sqrt(w_min * w_max)])
    return np.geomspace(1.0 / w_max, 1.0 / w_min, n)


def _nnls(dma: DMAData, n: int, e_inf_fixed: float | None) -> _Solution:
    w, e1, e2 = dma.frequency, dma.storage, dma.loss
    tau = _basis_times(float(w.min()), float(w.max()), n)
    wt = w[:, None] * tau
    d = 1.0 + wt**2
    a1 = (wt**2 / d) / e1[:, None]
    a2 = (wt / d) / e2[:, None]
    rhs = np.concatenate([np.ones_like(e1), np.ones_like(e2)])
    if e_inf_fixed is None:
        a1 = np.hstack([1.0 / e1[:, None], a1])
        a2 = np.hstack([np.zeros((w.size, 1)), a2])
    else:
        rhs[: w.size] -= e_inf_fixed / e1
    a = np.vstack([a1, a2])
    scale = np.linalg.norm(a, axis=0)            # column scaling: NNLS on O(1) columns
    scale[scale == 0] = 1.0
    x, res = nnls(a / scale, rhs, maxiter=50 * a.shape[1])
    x = x / scale
    e_inf = float(e_inf_fixed) if e_inf_fixed is not None else float(x[0])
    moduli = x if e_inf_fixed is not None else x[1:]
    keep = moduli > 0
    return _Solution(n, e_inf, moduli[keep], tau[keep], float(res / np.sqrt(rhs.size)))


def _residual_and_jacobian(x: np.ndarray, dma: DMAData, n: int, e_inf_fixed: float | None):
    """Relative residuals of E' and E'' and their derivatives in (log E∞, log E_i, log τ_i)."""
    free = e_inf_fixed is None
    e_inf = np.exp(x[0]) if free else e_inf_fixed
    e_i = np.exp(x[int(free):int(free) + n])
    u = dma.frequency[:, None] * np.exp(x[int(free) + n:])
    d = 1.0 + u**2
    g1, g2 = u**2 / d, u / d
    r1 = (e_inf + g1 @ e_i) / dma.storage - 1.0
    r2 = (g2 @ e_i) / dma.loss - 1.0
    inv1, inv2 = 1.0 / dma.storage[:, None], 1.0 / dma.loss[:, None]
    j1 = [g1 * e_i * inv1, 2 * u**2 / d**2 * e_i * inv1]
    j2 = [g2 * e_i * inv2, u * (1 - u**2) / d**2 * e_i * inv2]
    if free:
        j1.insert(0, e_inf * inv1)
        j2.insert(0, np.zeros_like(inv2))
    return np.concatenate([r1, r2]), np.vstack([np.hstack(j1), np.hstack(j2)])


def _refine(dma: DMAData, sol: _Solution, e_inf_fixed: float | None) -> _Solution:
    n = sol.moduli.size
    if n == 0 or sol.e_inf <= 0:
        return sol
    free = e_inf_fixed is None
    w_min, w_max = float(dma.frequency.min()), float(dma.frequency.max())
    lo_t, hi_t = np.log(0.1 / w_max), np.log(10.0 / w_min)
    x0 = np.concatenate([[np.log(sol.e_inf)] if free else [], np.log(sol.moduli),
                         np.clip(np.log(sol.times), lo_t, hi_t)])
    lower = np.concatenate([np.full(int(free) + n, -np.inf), np.full(n, lo_t)])
    upper = np.concatenate([np.full(int(free) + n, np.inf), np.full(n, hi_t)])
    cache: dict = {}

    def evaluate(x):
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = _residual_and_jacobian(x, dma, n, e_inf_fixed)
        return cache[key]

    out = least_squares(lambda x: evaluate(x)[0], x0, jac=lambda x: evaluate(x)[1],
                        bounds=(lower, upper), method="trf", x_scale="jac", xtol=1e-8,
                        ftol=1e-9, max_nfev=50 * x0.size)
    rms = float(np.sqrt(np.mean(out.fun**2)))
    if not rms < sol.rms:
        return sol
    e_inf = float(np.exp(out.x[0])) if free else float(e_inf_fixed)
    moduli = np.exp(out.x[int(free):int(free) + n])
    times = np.exp(out.x[int(free) + n:])
    return _Solution(sol.terms, e_inf, moduli, times, rms)


def _merge(dma: DMAData, sol: _Solution, rel: float = 0.01) -> _Solution:
    """Drop branches below 1e-6 of E' and of E'' at every data point; merge branches whose
    times differ by < ``rel`` (1 %): sum the moduli, take the modulus-weighted geometric
    mean time (the refinement drives redundant branches together or to zero; the data
    cannot tell them apart)."""
    u = dma.frequency[:, None] * sol.times
    share = np.maximum(sol.moduli * u**2 / (1 + u**2) / dma.storage[:, None],
                       sol.moduli * u / (1 + u**2) / dma.loss[:, None]).max(axis=0)
    keep = share >= 1e-6
    order = np.argsort(sol.times[keep])
    times, moduli = sol.times[keep][order], sol.moduli[keep][order]
    groups = np.concatenate([[0], np.cumsum(np.diff(np.log(times)) > rel)])
    ids = np.unique(groups)
    e = np.array([moduli[groups == g].sum() for g in ids])
    t = np.array([np.exp(np.average(np.log(times[groups == g]), weights=moduli[groups == g]))
                  for g in ids])
    return _Solution(sol.terms, sol.e_inf, e, t, sol.rms)


def _solve(dma: DMAData, n: int, e_inf_fixed: float | None, refine: bool) -> _Solution:
    sol = _nnls(dma, n, e_inf_fixed)
    if not refine:
        return sol
    sol = _refine(dma, sol, e_inf_fixed)
    merged = _merge(dma, sol)
    if merged.moduli.size == sol.moduli.size:
        return sol
    if merged.moduli.size == 0:
        return merged
    again = _refine(dma, replace(merged, rms=np.inf), e_inf_fixed)
    return again if again.moduli.size else sol


def fit_prony(dma: DMAData, terms: int | None = None, *, tolerance: float = 0.01,
              equilibrium_modulus: float | None = None, refine: bool = True,
              name: str | None = None, report: bool = False) -> GeneralizedMaxwell | PronyFit:
    """Fit a generalized Maxwell series with non-negative moduli to DMA data.

    Parameters
    ----------
    dma
        :class:`~rubbercontact.materials.DMAData` at one temperature (a master curve or an
        isotherm; build a master curve from isotherms with
        :func:`~rubbercontact.materials.master_curve` first).
    terms
        Number of log-spaced relaxation times of the NNLS grid over the data's frequency
        range (the material keeps those with a non-zero modulus); default: the rule in
        the module docstring. At least ``terms + 1`` frequencies are needed: the fit has
        ``2 terms + 1`` unknowns (``E_i``, ``τ_i``, ``E_∞``) for ``2 N`` data values.
    tolerance
        The rule's target rms relative residual [-].
    equilibrium_modulus
        Fix ``E_∞`` [MPa] instead of fitting it (for data that stop short of the rubbery
        plateau).
    refine
        Refine moduli and relaxation times by nonlinear least squares after the NNLS
        (step 2 of the module docstring).
    name
        Material name (default: from the data's source).
    report
        Return a :class:`PronyFit` (material and report) instead of the material.

    Returns
    -------
    GeneralizedMaxwell or PronyFit
        The material carries the data's shift law and, in ``provenance``, the source,
        reference temperature and the :class:`FitReport` as a table (``provenance["fit"]``).

    Raises
    ------
    InputError
        Too few points for the terms, data at several temperatures, zero fitted ``E_∞``.

    Warns
    -----
    DMAWarning
        ``E'`` falling with frequency beyond 3 %, or an rms residual above 5 %.
    """
    if not isinstance(dma, DMAData):
        raise InputError(f"dma: expected DMAData (rc.materials.read_dma), got "
                         f"{type(dma).__name__}")
    if not dma.is_isothermal:
        raise InputError(f"dma: {dma.source or 'data'} holds sweeps at "
                         f"{dma.isotherm_temperatures.size} temperatures; build the master "
                         f"curve first (rc.materials.master_curve)")
    if not (isinstance(tolerance, float | int) and 0 < tolerance < 1):
        raise InputError(f"tolerance: expected a relative error in (0, 1), got {tolerance!r}")
    if equilibrium_modulus is not None and not equilibrium_modulus > 0:
        raise InputError(f"equilibrium_modulus: must be > 0 MPa, got {equilibrium_modulus!r}")
    w = dma.frequency
    decades = float(np.log10(w.max() / w.min()))
    if decades < 1e-6:
        raise InputError(f"dma: {dma.source or 'data'}: all {w.size} points at one frequency; "
                         f"a Prony fit needs a frequency range")
    unknowns = 1 if equilibrium_modulus is None else 0
    for problem in dma.physical_problems():
        warnings.warn(f"{dma.source or 'DMA data'}: {problem}", DMAWarning, stacklevel=2)
    if terms is not None:
        if isinstance(terms, bool) or int(terms) != terms or terms < 1:
            raise InputError(f"terms: expected an integer >= 1, got {terms!r}")
        if w.size < terms + unknowns:
            raise InputError(f"dma: {w.size} frequencies are too few for {terms} terms "
                             f"(need >= {terms + unknowns}: {2 * terms + unknowns} unknowns for "
                             f"2 values per frequency)")
        best = _solve(dma, int(terms), equilibrium_modulus, refine)
        candidates, rule = [best], "given" + (", NNLS then refined" if refine else ", NNLS")
    else:
        sizes = sorted({max(2, int(round(d * decades)) + 1) for d in DENSITIES})
        sizes = [n for n in sizes if n + unknowns <= w.size]
        if not sizes:
            raise InputError(f"dma: {w.size} frequencies are too few for a fit "
                             f"(need >= {2 + unknowns})")
        candidates = []
        for n in sizes:   # stop as soon as the rule has decided
            candidates.append(_solve(dma, n, equilibrium_modulus, refine))
            if candidates[-1].rms <= tolerance:
                break
            if len(candidates) > 1 and candidates[-2].rms <= 1.1 * candidates[-1].rms:
                break
        floor = 1.1 * min(c.rms for c in candidates)
        best = next(c for c in candidates if c.rms <= max(tolerance, floor))
        rule = RULE
    if best.e_inf <= 0:
        raise InputError(f"dma: {dma.source or 'data'}: the fitted equilibrium modulus is 0 "
                         f"(no rubbery plateau at low frequency); extend the data or pass "
                         f"equilibrium_modulus=")
    label = name or (f"Prony fit of {Path(dma.source).name}" if dma.source else "Prony fit")
    fitted = GeneralizedMaxwell(best.e_inf, best.moduli, best.times, name=label)
    rep = _report(dma, fitted, best, candidates, rule, tolerance, decades)
    if rep.rms_error > WARN_RMS:
        warnings.warn(f"{dma.source or 'DMA data'}: Prony fit rms residual "
                      f"{100 * rep.rms_error:.1f} % (> {100 * WARN_RMS:g} %) with {rep.terms} "
                      f"terms: too few terms, noisy data, or not a linear viscoelastic "
                      f"solid; see the fit plot",
                      DMAWarning, stacklevel=2)
    provenance = {"source": dma.source} if dma.source else {}
    if dma.temperature is not None:
        provenance["reference_temperature"] = dma.temperature
    provenance["data"] = {k: v for k, v in dma.provenance.items() if k != "source"}
    provenance["fit"] = rep.as_dict()
    mat = GeneralizedMaxwell(best.e_inf, best.moduli, best.times, name=label,
                             shift=dma.shift, provenance=provenance)
    return PronyFit(mat, rep) if report else mat


def _report(dma: DMAData, mat: GeneralizedMaxwell, sol: _Solution, candidates, rule: str,
            tolerance: float, decades: float) -> FitReport:
    e = mat.complex_modulus(dma.frequency)
    r1 = np.abs(e.real / dma.storage - 1.0)
    r2 = np.abs(e.imag / dma.loss - 1.0)
    rm = np.abs(e - dma.complex_modulus) / np.abs(dma.complex_modulus)

    def rms(x):
        return float(np.sqrt(np.mean(x**2)))

    return FitReport(
        terms=sol.terms, terms_kept=mat.n_branches,
        per_decade=float((sol.terms - 1) / decades) if sol.terms > 1 else 1.0 / decades,
        rule=rule, tolerance=float(tolerance),
        rms_error=float(np.sqrt((np.sum(r1**2) + np.sum(r2**2)) / (2 * r1.size))),
        storage_rms_error=rms(r1), storage_max_error=float(r1.max()),
        loss_rms_error=rms(r2), loss_max_error=float(r2.max()),
        modulus_rms_error=rms(rm), modulus_max_error=float(rm.max()),
        frequency_range=(float(dma.frequency.min()), float(dma.frequency.max())),
        n_points=dma.n_points, candidates=tuple((c.terms, c.rms) for c in candidates))
