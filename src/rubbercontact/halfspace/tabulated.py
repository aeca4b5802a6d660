"""The tabulated interaction law: ``σ = f(u)`` interpolated from monotone samples, with the
hybrid's companion tables ``α(u)`` and ``Δτ(u)`` (the FEM high-slope law, paper eqs. 6-8).

The law's interface and the other laws are in :mod:`.laws`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import PchipInterpolator

from .._validation import finite_array
from ..errors import InputError
from .laws import InteractionLaw

__all__ = ["TabulatedLaw"]

#: E-folds of the exponential continuation below a table before it turns linear.
_MAX_EFOLDS = 20.0


def _pchip_with_slopes(x: np.ndarray, y: np.ndarray) -> PchipInterpolator:
    return PchipInterpolator(x, y, extrapolate=False)


#: Largest lookup grid of :class:`_Pieces` (cells); a table with breakpoints closer than
#: its span over this many halves is searched by bisection instead.
_MAX_CELLS = 4096


class _Pieces:
    """The piece of a PCHIP holding each point: ``j`` with ``x_j <= u < x_{j+1}`` (the last
    piece at the last breakpoint, the end pieces outside), as ``np.searchsorted`` finds it.

    A uniform grid of cells at most half the smallest breakpoint spacing wide, each
    holding the piece of its left end: a point's cell, then one comparison with the
    breakpoint on either side (a rounded cell is off by at most one breakpoint), cheaper
    than bisection of unsorted points (``benchmarks/maps.md``).
    """

    def __init__(self, x: np.ndarray) -> None:
        self.x = x
        span = float(x[-1] - x[0])
        cells = int(np.ceil(2.0 * span / float(np.diff(x).min())))
        self.lut = None
        if cells <= _MAX_CELLS:
            self.scale = cells / span
            left = x[0] + np.arange(cells + 1) / self.scale
            self.lut = np.clip(np.searchsorted(x, left, side="right") - 1, 0, x.size - 2)

    def __call__(self, u: np.ndarray) -> np.ndarray:
        x, last = self.x, self.x.size - 2
        if self.lut is None:
            return np.clip(np.searchsorted(x, u, side="right") - 1, 0, last)
        # a NaN has no cell (its piece is arbitrary, its value unused): mode "clip"
        with np.errstate(invalid="ignore"):
            cell = np.clip((u - x[0]) * self.scale, 0, self.lut.size - 1).astype(np.intp)
        j = self.lut.take(cell, mode="clip")
        j += u >= x.take(j + 1, mode="clip")
        j -= u < x.take(j, mode="clip")
        return np.clip(j, 0, last)


def _ppoly(pp: PchipInterpolator, u: np.ndarray, j: np.ndarray) -> np.ndarray:
    """``pp(u)`` on the pieces ``j``, with scipy's own operations in its order (the local
    power series ``c_k + c_{k-1} s + c_{k-2} s² + …``, ``s = u − x_j``, powers by repeated
    products): the same numbers as ``pp(u)`` inside its range, vectorised, where
    ``PPoly``'s scalar loop searches the interval of each point anew
    (``benchmarks/maps.md``)."""
    coef = pp.c
    s = u - pp.x.take(j)
    res = coef[-1].take(j)
    power = s
    for kp in range(1, coef.shape[0]):
        res = res + coef[-1 - kp].take(j) * power
        if kp < coef.shape[0] - 1:
            power = power * s
    return res


@dataclass(frozen=True, eq=False)
class TabulatedLaw(InteractionLaw):
    """Law interpolated from monotone samples ``(u_j, σ_j)`` (e.g. the FEM high-slope law).

    Parameters
    ----------
    separation
        ``u_j`` [mm], strictly increasing, at least 2 samples.
    pressure
        ``σ_j`` [MPa], >= 0 and non-increasing in ``u``.
    contact_fraction, shear_stress
        Optional companion tables ``α_j`` (in [0, 1]) and ``Δτ_j`` [MPa] at the same ``u_j``.

    Notes
    -----
    Interpolation (monotone by construction, so ``k = −dσ/du >= 0`` everywhere):

    * where ``σ_j > 0``: PCHIP (Fritsch–Carlson, shape preserving) in ``log σ``, which is
      exact for exponential laws and keeps ``σ > 0``;
    * from the last positive sample to the first zero sample: PCHIP in ``σ`` on that segment
      (monotone, reaches 0); ``σ = 0`` (and ``k = 0``) beyond the first ``u_j`` with ``σ_j = 0``;
    * below ``u_0``: stiff continuation, ``log σ`` extended linearly with the end slope of the
      log-PCHIP, but at least as steep as ``d log σ/du = −9/u_0`` when that slope is flatter —
      pressure keeps rising, never a plateau;
    * above the last sample when the table never reaches 0: ``log σ`` extended linearly with
      the end slope (exponential decay; constant only if the table ends flat).

    Companion tables use PCHIP in linear space (no overshoot), are held at their first value
    below ``u_0`` and at their last value above the table, and are 0 where ``σ = 0``. A held
    ``Δτ`` beyond the highest tabulated pressure is the linear theory's full-contact limit
    (there ``Δτ`` no longer depends on ``σ``) and a lower bound while ``Δτ`` still grows
    with ``σ``. The hybrid therefore first continues its FEM law to near full contact
    (:func:`rubbercontact.hybrid.law.continue_with_linear_shape`), so that this hold only
    applies where it is the right limit.
    """

    separation: np.ndarray
    pressure_table: np.ndarray
    contact_fraction_table: np.ndarray | None = None
    shear_stress_table: np.ndarray | None = None
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def __init__(self, separation, pressure, contact_fraction=None, shear_stress=None) -> None:
        u = finite_array("separation", separation, ndim=1, min_size=2)
        s = finite_array("pressure", pressure, ndim=1, min_size=2)
        if s.shape != u.shape:
            raise InputError(f"pressure: expected {u.size} values like separation, got {s.size}")
        du = np.diff(u)
        if np.any(du <= 0):
            i = int(np.argmax(du <= 0))
            raise InputError(f"separation: must be strictly increasing, got u[{i}]={u[i]} >= "
                             f"u[{i + 1}]={u[i + 1]}")
        if np.any(s < 0):
            i = int(np.argmax(s < 0))
            raise InputError(f"pressure: must be >= 0 MPa, got pressure[{i}]={s[i]}")
        ds = np.diff(s)
        if np.any(ds > 0):
            i = int(np.argmax(ds > 0))
            raise InputError(f"pressure: must be non-increasing in separation, got "
                             f"pressure[{i}]={s[i]} < pressure[{i + 1}]={s[i + 1]}")
        if s[0] <= 0:
            raise InputError("pressure: the first sample must be > 0 MPa")
        tables = {}
        for name, tab in (("contact_fraction", contact_fraction), ("shear_stress", shear_stress)):
            if tab is None:
                tables[name] = None
                continue
            t = finite_array(name, tab, ndim=1, min_size=2)
            if t.shape != u.shape:
                raise InputError(f"{name}: expected {u.size} values like separation, got {t.size}")
            if name == "contact_fraction" and (np.any(t < 0) or np.any(t > 1)):
                raise InputError(f"{name}: values must lie in [0, 1], got {t.min()}..{t.max()}")
            tables[name] = t
        object.__setattr__(self, "separation", u)
        object.__setattr__(self, "pressure_table", s)
        object.__setattr__(self, "contact_fraction_table", tables["contact_fraction"])
        object.__setattr__(self, "shear_stress_table", tables["shear_stress"])
        object.__setattr__(self, "_cache", {})
        self._build()

    def _build(self) -> None:
        u, s = self.separation, self.pressure_table
        zero = np.flatnonzero(s == 0)
        npos = int(zero[0]) if zero.size else u.size
        c = self._cache
        c["npos"] = npos
        c["u_zero"] = float(u[npos]) if zero.size else np.inf
        if npos >= 2:
            logp = _pchip_with_slopes(u[:npos], np.log(s[:npos]))
            d0 = float(logp.derivative()(u[0]))
            d1 = float(logp.derivative()(u[npos - 1]))
        else:
            logp = None
            d0 = d1 = 0.0
        c["logp"] = logp
        c["pieces"] = None if logp is None else _Pieces(logp.x)
        # derivatives built once: PPoly.derivative() builds a new polynomial on every call
        c["dlogp"] = None if logp is None else logp.derivative()
        # stiff continuation below the table: never flatter than the first secant nor than
        # one e-fold over the table's span (a strictly rising pressure, no plateau)
        secant = (np.log(s[1]) - np.log(s[0])) / (u[1] - u[0]) if s[1] > 0 else 0.0
        c["slope_lo"] = min(d0, secant, -1.0 / (u[-1] - u[0]))
        c["slope_hi"] = min(d1, 0.0)
        # last segment (last positive sample -> first zero sample), linear-space PCHIP
        c["tail"] = (_pchip_with_slopes(u[npos - 1:npos + 1], s[npos - 1:npos + 1])
                     if zero.size else None)
        c["dtail"] = None if c["tail"] is None else c["tail"].derivative()
        c["companions"] = {}
        for name, tab in (("alpha", self.contact_fraction_table),
                          ("tau", self.shear_stress_table)):
            c["companions"][name] = None if tab is None else _pchip_with_slopes(u, tab)

    # -- evaluation ----------------------------------------------------------------
    def _eval(self, u: np.ndarray, stiffness: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``(σ(u), k(u) = −σ'(u))``; ``k`` is left 0 unless ``stiffness`` (the law is
        evaluated on the whole grid in every Newton and line-search step).

        A table that reaches ``σ = 0`` is evaluated only where ``u`` is below that
        separation (its support): on a rough surface a few percent of the grid, so the
        whole-grid work is one comparison and the scatter of the results.
        """
        c = self._cache
        u = np.asarray(u, dtype=float)
        sig = np.zeros(u.shape)
        k = np.zeros(u.shape)
        flat = u.reshape(-1)
        if np.isfinite(c["u_zero"]):
            idx = np.flatnonzero(flat < c["u_zero"])
            if idx.size == 0:
                return sig, k
            s_in, k_in = self._eval_flat(flat.take(idx), stiffness)
            sig.reshape(-1)[idx] = s_in
            k.reshape(-1)[idx] = k_in
            return sig, k
        s_in, k_in = self._eval_flat(flat, stiffness)
        return s_in.reshape(u.shape), k_in.reshape(u.shape)

    def _eval_flat(self, u: np.ndarray, stiffness: bool) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_eval` on a 1-D array of separations."""
        c = self._cache
        tab_u, tab_s = self.separation, self.pressure_table
        npos = c["npos"]
        sig = np.zeros(u.shape)
        k = np.zeros(u.shape)
        u0, s0 = tab_u[0], tab_s[0]
        lo = u < u0
        if np.any(lo):
            a = -c["slope_lo"]
            t = a * (u0 - u[lo])
            # exponential rise for 20 e-folds, then linear (C1), so far extrapolation stays
            # finite and monotone
            tc = np.minimum(t, _MAX_EFOLDS)
            sig[lo] = s0 * np.exp(tc) * (1.0 + (t - tc))
            k[lo] = a * s0 * np.exp(tc)
        upos = tab_u[npos - 1]
        mid = (u >= u0) & (u <= upos)
        if np.any(mid) and c["logp"] is not None:
            # the log-PCHIP on every point (those outside its range are overwritten below):
            # one interval search for the value and the slope, no masked gathers
            if c.get("pieces") is None:   # a law pickled before the lookup existed
                c["pieces"] = _Pieces(c["logp"].x)
            j = c["pieces"](u)
            # the cubic extrapolated far outside may overflow there: discarded below
            with np.errstate(over="ignore", invalid="ignore"):
                s_all = np.exp(_ppoly(c["logp"], u, j))
                k_all = -_ppoly(c["dlogp"], u, j) * s_all if stiffness else None
            sig = np.where(mid, s_all, sig)
            if stiffness:
                k = np.where(mid, k_all, k)
        elif np.any(mid):  # single positive sample: only u == u0 can land here
            sig[mid] = s0
        if c["tail"] is not None:
            seg = (u > upos) & (u < c["u_zero"])
            if np.any(seg):
                sig[seg] = c["tail"](u[seg])
                if stiffness:
                    k[seg] = -c["dtail"](u[seg])
        else:
            hi = u > upos
            if np.any(hi):
                sig[hi] = tab_s[npos - 1] * np.exp(c["slope_hi"] * (u[hi] - upos))
                k[hi] = -c["slope_hi"] * sig[hi]
        return np.maximum(sig, 0.0), np.maximum(k, 0.0)

    def pressure(self, u):
        return self._eval(u, stiffness=False)[0]

    def stiffness(self, u):
        return self._eval(u)[1]

    def pressure_and_stiffness(self, u):
        return self._eval(u)   # the stiffness is computed with the pressure anyway

    def _companion(self, name: str, u) -> np.ndarray | None:
        interp = self._cache["companions"][name]
        if interp is None:
            return None
        u = np.asarray(u, dtype=float)
        tab = self.contact_fraction_table if name == "alpha" else self.shear_stress_table
        uc = np.clip(u, self.separation[0], self.separation[-1])
        out = interp(uc)
        out = np.where(u < self.separation[0], tab[0], out)
        out = np.where(u > self.separation[-1], tab[-1], out)
        out = np.where(u >= self._cache["u_zero"], 0.0, out)
        if name == "alpha":
            out = np.clip(out, 0.0, 1.0)
        return out

    def contact_fraction(self, u):
        return self._companion("alpha", u)

    def shear_stress(self, u):
        return self._companion("tau", u)

    def in_contact(self, u):
        return self.pressure(u) > 0

    def describe(self) -> dict:
        return {"law": "TabulatedLaw", "samples": int(self.separation.size),
                "separation_range": [float(self.separation[0]), float(self.separation[-1])],
                "has_contact_fraction": self.contact_fraction_table is not None,
                "has_shear_stress": self.shear_stress_table is not None}
