"""Speeds and temperatures of a run, and the reduced speeds at which they are computed.

Every model of the pipeline is linear viscoelastic in time with one relaxation spectrum
(an isothermal-shift, "thermorheologically simple" material): at temperature ``T`` the
relaxation times are ``a_T τ_i``, so a test at speed ``v`` and ``T`` is the same problem as
the test at the *reduced speed* ``a_T v`` at the reference temperature ``T_ref``
(time–temperature superposition, exact for the half-space, the FEM and the mean-field
models alike). A run with ``temperatures`` therefore solves each distinct reduced speed
once, with the material at ``T_ref``, and reads every ``(T, v)`` from it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..materials import GeneralizedMaxwell

#: Reduced speeds closer than this (relative) are one speed (round-off of ``a_T v``).
DEDUPE_RTOL = 1e-9


@dataclass(frozen=True)
class SpeedPlan:
    """Where each (temperature, speed) of a run is computed.

    Attributes
    ----------
    velocities
        The run's sliding speeds [mm/s], in config order.
    computed
        The speeds solved at the reference temperature [mm/s]: ``velocities`` themselves
        for an isothermal run, else the distinct reduced speeds ``a_T v``, ascending.
    temperatures
        The run's temperatures [°C], or None (isothermal: no temperature dimension).
    reference_temperature
        ``T_ref`` [°C] of the material's shift law (None without one).
    shift_factors
        ``a_T`` per temperature [-] (None for an isothermal run).
    index
        ``(n_T, n_v)`` positions in ``computed`` of each (T, v) (None for an isothermal
        run: position i is speed i).
    """

    velocities: np.ndarray
    computed: np.ndarray
    temperatures: np.ndarray | None = None
    reference_temperature: float | None = None
    shift_factors: np.ndarray | None = None
    index: np.ndarray | None = None

    @property
    def isothermal(self) -> bool:
        return self.temperatures is None

    def reduced(self) -> np.ndarray:
        """``a_T v`` [mm/s], shape ``(n_T, n_v)`` (``(1, n_v)`` for an isothermal run)."""
        if self.isothermal:
            return self.velocities[None, :]
        return self.shift_factors[:, None] * self.velocities[None, :]


def plan_speeds(velocities, temperatures, material: GeneralizedMaxwell,
                rtol: float = DEDUPE_RTOL) -> SpeedPlan:
    """The :class:`SpeedPlan` of a run.

    Raises
    ------
    InputError
        ``temperatures`` with a material that has no shift law (naming the fix), or a
        temperature outside the shift law's range.
    """
    v = np.asarray(velocities, float)
    law = material.shift
    t_ref = None if law is None else float(law.t_ref)
    if temperatures is None:
        return SpeedPlan(velocities=v, computed=v.copy(), reference_temperature=t_ref)
    if law is None:
        raise InputError("temperatures: the material has no time-temperature shift law; add "
                         "[material.shift] law = 'WLF' with c1, c2 [K] (and "
                         "material.reference_temperature [°C]), or law = 'Arrhenius' with "
                         "activation_energy [J/mol]; or remove temperatures")
    t = np.asarray(temperatures, float)
    try:
        a_t = np.array([float(law.shift(float(x))) for x in t])
    except InputError as exc:
        raise InputError(f"temperatures: {exc}") from None
    reduced = a_t[:, None] * v[None, :]
    computed, index = _distinct(reduced, exact=np.isclose(a_t, 1.0, rtol=0, atol=0), rtol=rtol)
    return SpeedPlan(velocities=v, computed=computed, temperatures=t, reference_temperature=t_ref,
                     shift_factors=a_t, index=index)


def _distinct(reduced: np.ndarray, exact: np.ndarray, rtol: float
              ) -> tuple[np.ndarray, np.ndarray]:
    """Distinct values of ``reduced`` (within ``rtol``) and each entry's position among them.

    A group containing a speed at ``a_T = 1`` (row flagged in ``exact``) takes that speed
    exactly, so the reference temperature's results are those of an isothermal run.
    """
    flat = reduced.ravel()
    at_ref = np.repeat(exact, reduced.shape[1])
    order = np.argsort(flat, kind="stable")
    groups: list[list[int]] = []
    for k in order:
        if groups and abs(flat[k] - flat[groups[-1][0]]) <= rtol * max(abs(flat[k]),
                                                                    abs(flat[groups[-1][0]])):
            groups[-1].append(k)
        else:
            groups.append([k])
    computed = np.empty(len(groups))
    index = np.empty(flat.size, int)
    for g, members in enumerate(groups):
        ref = [k for k in members if at_ref[k]]
        computed[g] = flat[ref[0] if ref else members[0]]
        index[members] = g
    return computed, index.reshape(reduced.shape)
