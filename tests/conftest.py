"""Fixtures shared by several test files.

- ``repo_root``: the repository (examples, docs, README live there).
- ``sbr``, ``high_slope_wave``: the paper's Table 1 rubber and its steepest wave
  (0.0625 mm, 0.01867 mm, m2 = 1.33); both are frozen, so one instance serves a session.
- ``closed_forms``: the closed forms that tests compare the solvers against.
- ``hand_made_law``: an interface-law table with known derivatives (for the mean-field
  enrichment and its task).
- ``cole_cole``: a Cole–Cole (fractional Zener) solid in closed form, a material that is
  not a Prony series (the solvers take materials by their members).
- ``step_shear``: the FEM constitutive law's shear stress after a step of simple shear,
  held (to compare with a Prony series' closed-form relaxation modulus).
- ``run_example``: runs ``examples/NAME.py`` as a script on its reduced settings and
  returns its global variables.
"""

from __future__ import annotations

import os
import runpy
import warnings
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import rubbercontact as rc

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def sbr():
    return rc.materials.sbr()


@pytest.fixture(scope="session")
def high_slope_wave():
    return rc.roughness.high_slope_wave()


def _westergaard_pressure(contact_fraction, wavelength, amplitude, reduced_modulus):
    """Mean pressure [MPa] of an elastic sine in contact over ``2a = contact_fraction λ``
    (Westergaard; Johnson 1985): ``p̄ = π E_r Δ/λ · sin²(π a/λ)``."""
    return (np.pi * reduced_modulus * amplitude / wavelength
            * np.sin(np.pi * contact_fraction / 2) ** 2)


def _full_contact_friction(material, wavelength, amplitude, velocity, mean_pressure, nu=0.5):
    """μ of one sine in full steady-sliding contact on a linear viscoelastic half-space
    (plane strain): ``q²Δ² Im E_r(qv)/(4σ0) = m2² Im E_r/(2σ0)``."""
    q = 2 * np.pi / wavelength
    e_r = complex(material.complex_modulus(q * velocity)) / (1 - nu**2)
    return q**2 * amplitude**2 * e_r.imag / (4 * mean_pressure)


@pytest.fixture(scope="session")
def closed_forms():
    return SimpleNamespace(westergaard_pressure=_westergaard_pressure,
                           full_contact_friction=_full_contact_friction)


@pytest.fixture(scope="session")
def hand_made_law():
    """``hand_made_law(n)``: a law table on ``n`` pressures from 10 to 0 MPa, ordered as
    ``law_at_velocity`` orders it: ``σ = 20(1 − u)``, ``Δτ = 0.3σ²``, ``α = σ/(1+σ)``."""
    def table(n: int = 2001) -> dict:
        sig = np.linspace(10.0, 0.0, n)
        return {"separation": list(1.0 - sig / 20), "pressure": list(sig),
                "contact_fraction": list(sig / (1 + sig)),
                "shear_stress": list(0.3 * sig**2)}

    return table


@dataclass(frozen=True)
class ColeCole:
    """``E(ω) = E_r + (E_u − E_r) (iωτ)^a / (1 + (iωτ)^a)`` [MPa]: no finite Prony series
    for ``a < 1``; ``a = 1`` is the standard linear solid."""

    relaxed: float = 3.0
    unrelaxed: float = 300.0
    tau: float = 1e-4
    exponent: float = 0.4
    name: str = "Cole-Cole"
    is_elastic: bool = False

    def complex_modulus(self, omega) -> np.ndarray:
        # principal branch of the power: (−iy)^a = conj((iy)^a), so E(−ω) = conj E(ω)
        x = (1j * np.asarray(omega, dtype=float) * self.tau) ** self.exponent
        return self.relaxed + (self.unrelaxed - self.relaxed) * x / (1.0 + x)


@pytest.fixture(scope="session")
def cole_cole():
    """``cole_cole(relaxed=3, unrelaxed=300, tau=1e-4, exponent=0.4)``: a :class:`ColeCole`
    solid (the class itself; instances are frozen)."""
    return ColeCole


def _step_shear(material, holds, shear: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """``(t, σ_xy(t))`` [s, MPa] of one material point of the FEM's constitutive law: simple
    shear ``γ = shear`` applied in a step of 1e-15 s (glassy), then held for the steps
    ``holds`` [s]. For the neo-Hookean branches ``σ_xy = γ E(t)/3`` exactly."""
    from rubbercontact.fem.constitutive import (
        MaterialParameters,
        ViscousState,
        cauchy_from_pk2,
        update_stress,
    )

    par = MaterialParameters.from_material(material)
    F = np.array([[[1.0, shear], [0.0, 1.0]]])
    p = np.zeros(1)
    st = ViscousState.zeros((1,), par.n_branches)
    S, _, _, _, st = update_stress(par, F, p, st, 1e-15)
    t, times, sxy = 1e-15, [], []
    for dt in holds:
        S, _, _, _, st = update_stress(par, F, p, st, dt)
        t += dt
        times.append(t)
        sxy.append(cauchy_from_pk2(F, S)[0, 2])
    return np.array(times), np.array(sxy)


@pytest.fixture(scope="session")
def step_shear():
    """``step_shear(material, holds, shear=0.5) -> (t, σ_xy)`` (:func:`_step_shear`)."""
    return _step_shear


@pytest.fixture
def run_example(monkeypatch, tmp_path):
    """``run_example("plot_x")`` runs ``examples/plot_x.py`` with
    ``RUBBERCONTACT_EXAMPLE_QUICK=1`` (its reduced settings), its result cache in
    ``tmp_path`` and matplotlib on Agg, and returns the script's globals."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.setenv("RUBBERCONTACT_EXAMPLE_QUICK", "1")
    monkeypatch.setenv("RUBBERCONTACT_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("MPLBACKEND", "Agg")

    def run(name: str) -> dict:
        path = ROOT / "examples" / f"{name}.py"
        old = os.getcwd()
        try:
            os.chdir(tmp_path)       # whatever a script writes lands in the test's folder
            with warnings.catch_warnings():
                # plt.show() on Agg would warn that it cannot show: a headless run must not
                warnings.filterwarnings("error", "FigureCanvasAgg is non-interactive")
                script_globals = runpy.run_path(str(path), run_name="__main__")
            # run headless, as the gallery header tells users to, it writes its figure
            figure = tmp_path / "results" / "examples" / f"{name.removeprefix('plot_')}.png"
            assert figure.stat().st_size > 1000, f"{name} wrote no figure"
            return script_globals
        finally:
            os.chdir(old)
            plt.close("all")

    return run
