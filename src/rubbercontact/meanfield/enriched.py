r"""The mean-field theory enriched by the FEM law of the high-slope scale.

The split
---------
As in the hybrid, the roughness is partitioned by slope: the waves (or octave bands, for a
continuous spectrum) with ``m2 > m2_threshold`` form the high-slope scale, whose FEM law
``σ_hs(ū), α_hs(ū), Δτ_hs(ū)`` (paper eqs. 1–3) is computed once
(:func:`rubbercontact.hybrid.effective_law`); the rest is the low-slope spectrum
(:meth:`.PSD.partition`). The mean-field theory runs on the low-slope spectrum; the split
magnification is its end, ``ζ_s = q_max,ls/q0``. There the pressure distribution
``P(σ, ζ_s)`` (:mod:`.contact`) is the distribution of the low-slope pressure resolved down
to the shortest low-slope wavelength — the pressure a high-slope cell of that size is loaded
with — and it weighs the law:

.. math:: μ_{hs} = \frac{1}{σ_0} ∫ P(σ, ζ_s)\, Δτ_{hs}(σ)\, dσ,\qquad
          A_c = ∫ P(σ, ζ_s)\, α_{hs}(σ)\, dσ

(eqs. 6 and 8 in mean-field form), ``μ = μ_ls + μ_hs``; ``μ_ls`` is the theory's friction
of the low-slope spectrum. The law is read as a function of pressure through the hybrid's
own interpolant (:func:`rubbercontact.hybrid.windowing.law_in_pressure`), so at a uniform
pressure both give the same number; beyond its highest pressure ``α`` and ``Δτ`` are held
(a :class:`~rubbercontact.hybrid.LawWarning` says when that carries weight).

What the split assumes: scale separation — every high-slope wavelength is shorter than every
low-slope one, and a low-slope contact patch holds many high-slope cells at one pressure (the
law is the mean over a periodic array of cells at a uniform mean pressure). Reading the law at
``P(σ, ζ_s)`` rather than at the fully resolved pressure is the mean-field counterpart of the
hybrid's windowed reading (:mod:`rubbercontact.hybrid.windowing`): the pressure is averaged
over the smallest low-slope scale.

Closing the interface with the law (``interface="law"``, the default)
--------------------------------------------------------------------
Between the rubber and the low-slope surface the high-slope scale acts as a soft layer whose
compliance is the law's ``c(σ) = −dū/dσ_hs`` (the hybrid's BEM solves the low-slope scale
with that law as the interaction). In series with the half-space it lowers the pressure a
low-slope mode generates in full contact, ``T = 1/(M + c)`` (:mod:`.contact`), and with it
``G`` and ``μ_ls``. The layer's compliance depends on its pressure; at magnification ``ζ``
the theory takes it at the mean contact pressure ``σ0/A(ζ)`` of the contact resolved so far
(a march in ``ζ``). ``interface="rigid"`` neglects the layer: the low-slope contact is that
of the hard wall. Against the windowed hybrid with the same law the layer is the closer of
the two (docs/validation/meanfield.md).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .._validation import require_members
from ..errors import InputError
from ..hybrid.law import LawWarning, tabulated_law_from_dict
from ..hybrid.windowing import law_in_pressure
from .contact import (
    Compliance,
    ModalResponse,
    PressureDistribution,
    contact_fraction,
    modal_response,
)

#: Share of the contact whose pressure lies beyond the law table before a warning.
COVERAGE_WARN = 0.01
_TABLE_KEYS = ("separation", "pressure", "contact_fraction", "shear_stress")


@dataclass(frozen=True)
class PressureLaw:
    """The high-slope law as functions of the local pressure ``σ`` [MPa] (ascending).

    Attributes
    ----------
    pressure
        ``σ`` [MPa], strictly increasing, from 0.
    contact_fraction
        ``α_hs(σ)`` [-].
    shear_stress
        ``Δτ_hs(σ)`` [MPa].
    compliance
        ``c(σ) = −dū/dσ_hs`` [mm/MPa] of the law's own interpolant.
    """

    pressure: np.ndarray
    contact_fraction: np.ndarray
    shear_stress: np.ndarray
    compliance: np.ndarray

    @classmethod
    def from_table(cls, table: dict) -> PressureLaw:
        """From a law table at one speed (:func:`rubbercontact.hybrid.law_at_velocity`)."""
        if not isinstance(table, dict) or any(k not in table for k in _TABLE_KEYS):
            raise InputError(f"law: expected a law table at one speed, a dict with the keys "
                             f"{', '.join(_TABLE_KEYS)} (rubbercontact.hybrid.law_at_velocity)")
        if table["shear_stress"] is None or table["contact_fraction"] is None:
            raise InputError("law: the table needs contact_fraction and shear_stress columns")
        sig, alpha, tau = law_in_pressure(table)
        interp = tabulated_law_from_dict(table)
        u_tab = interp.separation
        u = np.union1d(u_tab, np.linspace(u_tab[0], u_tab[-1], 4096))
        p = interp.pressure(u)
        keep = np.concatenate([[True], p[1:] < p[:-1]])
        u, p = u[keep][::-1], p[keep][::-1]            # increasing in σ
        with np.errstate(divide="ignore"):
            c_u = 1.0 / interp.stiffness(u)
        comp = np.interp(sig, p, np.where(np.isfinite(c_u), c_u, 0.0))
        return cls(sig, alpha, tau, comp)

    @property
    def max_pressure(self) -> float:
        return float(self.pressure[-1])

    def at(self, sigma) -> tuple[np.ndarray, np.ndarray]:
        """``(α_hs, Δτ_hs)`` at ``σ`` (held beyond the table, 0 at 0)."""
        s = np.asarray(sigma, float)
        return (np.interp(s, self.pressure, self.contact_fraction),
                np.interp(s, self.pressure, self.shear_stress))

    def compliance_at(self, sigma) -> np.ndarray:
        """``c(σ)`` [mm/MPa], held at the table's end beyond its highest pressure."""
        s = np.asarray(sigma, float)
        return np.interp(s, self.pressure[1:], self.compliance[1:])


#: What the theory needs of a high-slope law as a function of pressure (a
#: :class:`PressureLaw` has them; any object with them is such a law).
_PRESSURE_LAW_MEMBERS = {
    "at": "a method sigma [MPa] -> (alpha_hs, delta_tau_hs [MPa])",
    "compliance_at": "a method sigma [MPa] -> c [mm/MPa] (NaN: none)",
    "max_pressure": "the table's highest pressure [MPa]",
}


def as_pressure_law(law, velocity: float) -> PressureLaw:
    """A :class:`PressureLaw` from a table dict or a law ``xarray.Dataset``; any object with
    the members of a pressure law (``at``, ``compliance_at``, ``max_pressure``) as it is.

    The last check is structural: the members are looked up, the class is not.
    """
    if isinstance(law, dict):
        return PressureLaw.from_table(law)
    import xarray as xr

    if isinstance(law, xr.Dataset):
        from ..hybrid.law import as_law, law_at_velocity

        return PressureLaw.from_table(law_at_velocity(as_law(law), velocity))
    require_members(law, _PRESSURE_LAW_MEMBERS, methods=("at", "compliance_at"), what="law",
                    kind="a pressure law",
                    hint="expected None, a law table (dict), a law xarray.Dataset or an "
                         "object with these members")
    return law


def theory_law(psd, material, velocity: float, pressures, nu: float = 0.5,
               options=None) -> PressureLaw:
    """The theory's own law of a spectrum: ``α(σ)``, ``Δτ(σ) = σ μ(σ)`` at ``pressures``.

    The mean-field counterpart of the VHS linear law (:func:`rubbercontact.hybrid.law.
    linear_law`): enriching the rest of a spectrum with it gives back the plain theory of
    the whole spectrum (rigid interface, ``S = 1``; Markov property of the diffusion). It has
    no separation, so no compliance (``interface="law"`` refuses it).
    """
    from .solve import solve

    p = np.sort(np.asarray(pressures, float))
    if p.ndim != 1 or p.size < 2 or np.any(p <= 0) or not np.all(np.isfinite(p)):
        raise InputError("pressures: expected at least 2 finite pressures > 0 MPa")
    res = [solve(psd, material, velocity, float(pi), nu=nu, options=options) for pi in p]
    alpha = np.array([r.contact_fraction for r in res])
    tau = np.array([r.friction * pi for r, pi in zip(res, p, strict=True)])
    return PressureLaw(np.concatenate([[0.0], p]), np.concatenate([[0.0], alpha]),
                       np.concatenate([[0.0], tau]), np.full(p.size + 1, np.nan))


def march_with_layer(comp: Compliance, mean_pressure: float, law: PressureLaw
                     ) -> tuple[np.ndarray, ModalResponse]:
    """``G`` after each node and the modal response with the law's layer in series.

    Node ``i`` sees the layer's compliance at ``σ0/A(ζ_{i−1})`` (module docstring).
    """
    n = comp.wavenumbers.size
    s, f = np.zeros(n), np.zeros(n)
    g, g_run = np.zeros(n), 0.0
    for i in range(n):
        local = mean_pressure / float(contact_fraction(g_run))
        # checked where it is read: a law without separations (a theory law) has none
        c_layer = law.compliance_at(local)
        if not np.all(np.isfinite(c_layer)):
            raise InputError("interface: 'law' needs the law's separations (its compliance); "
                             "this law has none (a theory law); use interface='rigid'")
        resp = modal_response(comp, c_layer, nodes=slice(i, i + 1))
        s[i], f[i] = resp.pressure_variance[0], resp.friction_stress[0]
        g_run += s[i] / (2.0 * mean_pressure**2)
        g[i] = g_run
    return g, ModalResponse(comp.wavenumbers, s, f)


def weigh_law(dist: PressureDistribution, law: PressureLaw) -> tuple[float, float]:
    """``(μ_hs, A_c)``: the law weighted by ``P(σ)`` (module docstring)."""
    alpha, tau = law.at(dist.sigma)
    mu_hs = dist.expect(tau) / dist.mean_pressure
    area = dist.expect(alpha)
    beyond = dist.sigma > law.max_pressure
    if beyond.any():
        share = dist.expect(beyond.astype(float)) / max(dist.contact_fraction, 1e-300)
        if share > COVERAGE_WARN:
            w = LawWarning(f"law: {100 * share:.1f} % of the low-slope contact is at pressures "
                           f"beyond the table's {law.max_pressure:.3g} MPa, where α_hs and "
                           f"Δτ_hs are held; extend the law to higher pressures")
            w.share = float(share)      # for callers that gather these (pipeline flash)
            warnings.warn(w, stacklevel=3)
    return mu_hs, area
