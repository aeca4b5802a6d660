"""The phase-averaged comparison: the FEM's mean over random phases by a control variate.

The hybrid predicts the friction of a random-phase surface on average over the phases, and
its cheap models (VHS, hybrids) afford many realizations N where the full FEM affords few
(R). The FEM's phase average is estimated as ``mean_N(VHS) + β mean_R(FEM − VHS)``
(:func:`rubbercontact.hybrid.metrics.control_variate_by_column`), and eq. 28 is taken at
equal area against it. ``data`` below is one velocity's arrays: ``{"pressures", "fem":
(A, μ), "paired": {model: (A, μ)}, "all": {model: (A, μ)}}``, arrays ``(realization,
pressure)`` — the FEM and the cheap models on the same R realizations, and the cheap models
on all N (the first R of which are the paired ones).
"""

from __future__ import annotations

import warnings

import numpy as np

from ..hybrid.metrics import control_variate_by_column
from .equal_area import INTERVAL_LEVEL, RESAMPLES, common_areas, eq28_bounds

#: The cheap models averaged over N realizations.
CHEAP_MODELS = ("hybrid", "hybrid-windowed", "vhs")


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


def eq28_phase_averaged(phase_data: dict, resamples: int = RESAMPLES,
                        level: float = INTERVAL_LEVEL,
                        seed: int = 0, beta: str = "difference") -> dict:
    """``{v: ({m: e}, {m: (low, high, used)})}``: eq. 28 at equal area against the
    phase-averaged FEM and the range of :class:`~.equal_area.Eq28` around it (the R FEM
    realizations and the N cheap ones resampled independently, ``resamples`` times; a
    fitted β is refitted in every resample)."""
    out = {}
    for v, data in phase_data.items():
        res = eq28_phase_bounds(data, resamples=resamples, level=level, seed=seed, beta=beta)
        out[v] = ({m: b.error for m, b in res.items()},
                  {m: (b.low, b.high, b.used) for m, b in res.items()})
    return out


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


def eq28_phase_bounds(data: dict, *, resamples: int = RESAMPLES, level: float = INTERVAL_LEVEL,
                      seed: int = 0, beta: str = "difference") -> dict:
    """``{model: Eq28}``: eq. 28 against the phase-averaged FEM with the signed errors'
    intervals (:func:`~.equal_area.eq28_bounds`), the R FEM realizations and the N cheap
    ones resampled independently."""
    r, n = data["fem"][0].shape[0], data["all"]["vhs"][0].shape[0]

    def curves_of(sample):
        idx_r, idx_n = (None, None) if sample is None else sample
        return phase_mean_curves(data, idx_r, idx_n, beta)["phase"]

    def draw(rng):
        return rng.integers(0, r, r), rng.integers(0, n, n)

    return eq28_bounds(curves_of, draw, [m for m in CHEAP_MODELS if m in data["all"]],
                       resamples=resamples, level=level, seed=seed)
