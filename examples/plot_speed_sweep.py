"""
Friction against speed by continuation
======================================

:func:`rubbercontact.fem.steady_sweep` follows a path of steady FEM problems, speed by
speed: each solution starts the next, which costs a fraction of a fresh solve.

Two sweeps:

* a gentle wave (``m2 = 0.1``) pressed into full contact, where linear theory is exact
  to first order in the slope: ``μ(v) = m2² Im E_r(qv) / (2 σ0)``;
* the paper's high-slope wave (``m2 = 1.33``) at 1 MPa, one column of the effective law,
  beside the linear (VHS) answer on the same wave: their gap is the kinematic
  non-linearity that the hybrid method puts into its law.

``RUBBERCONTACT_EXAMPLE_QUICK=1`` uses fewer speeds and coarser cells.
"""

# %%
# A gentle wave in full contact against the closed form
# -----------------------------------------------------
import os

import matplotlib.pyplot as plt
import numpy as np

import rubbercontact as rc

QUICK = os.environ.get("RUBBERCONTACT_EXAMPLE_QUICK") == "1"
sbr = rc.materials.sbr()
wavelength = 0.0625                                     # mm
q = 2 * np.pi / wavelength
amplitude = 0.1 * np.sqrt(2) / q                        # m2 = qΔ/√2 = 0.1
gentle = rc.roughness.SineSeries([wavelength], [amplitude])

speeds = np.geomspace(1e-2, 10.0, 4 if QUICK else 7)    # mm/s
e_r = sbr.reduced_modulus(q * speeds)
# twice the full-contact pressure π|E_r|Δ/λ of the stiffest speed: full contact everywhere
sigma0 = 2 * np.pi * np.abs(e_r).max() * amplitude / wavelength
sweep = rc.fem.steady_sweep(gentle, sbr, sigma0, speeds, mesh=(32, 24))
mu_fem = np.array([r.friction for r in sweep])
mu_linear = 0.1**2 * e_r.imag / (2 * sigma0)
print("σ0 =", round(float(sigma0), 3), "MPa; FEM / linear theory:", np.round(mu_fem / mu_linear, 4))

# %%
# One column of the effective law: the high-slope wave at 1 MPa
# -------------------------------------------------------------
wave = rc.roughness.high_slope_wave()
law_speeds = np.geomspace(1e-3, 1e3, 7 if QUICK else 13)
law_sweep = rc.fem.steady_sweep(wave, sbr, 1.0, law_speeds,
                                mesh=(24, 12) if QUICK else (60, 30))
mu_law = np.array([r.friction for r in law_sweep])
mu_vhs = np.array([rc.halfspace.solve_sliding(wave, wave.period, sbr, v, 1.0,
                                              n=2048).friction for v in law_speeds])
for v, a, b in zip(law_speeds, mu_law, mu_vhs, strict=True):
    print(f"v = {v:8.3g} mm/s: μ FEM {a:.3f}, VHS {b:.3f}")

# %%
# The two sweeps
fig, (ax, ax2) = plt.subplots(1, 2, figsize=(9, 3.5), layout="constrained")
ax.loglog(speeds, mu_fem, "o", label="steady FEM sweep")
dense = np.geomspace(speeds[0], speeds[-1], 200)
ax.loglog(dense, 0.1**2 * sbr.reduced_modulus(q * dense).imag / (2 * sigma0),
          label="m2² Im E_r / (2σ0)")
ax.set_xlabel("v [mm/s]")
ax.set_ylabel("μ")
ax.set_title("m2 = 0.1, full contact")
ax.legend()
ax2.semilogx(law_speeds, mu_law, "o-", label="FEM (steady sweep)")
ax2.semilogx(law_speeds, mu_vhs, "s--", label="VHS")
ax2.set_xlabel("v [mm/s]")
ax2.set_title("m2 = 1.33, p̄ = 1 MPa")
ax2.legend()
rc.plotting.show(fig, "speed_sweep.png")     # also a file: runs headless
