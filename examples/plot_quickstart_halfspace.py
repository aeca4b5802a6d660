"""
Quick start: the half-space on one sine wave
=============================================

The low-slope model of the method (paper §2.3) is a rigid periodic surface sliding in
steady state over a linear viscoelastic half-space, solved with FFTs by
:func:`rubbercontact.halfspace.solve_sliding`. On one sine wave it has two closed forms,
and this example checks the solver against both:

* elastic, partial contact (Westergaard): ``p̄ = π E_r Δ/λ · sin²(π a/λ)`` for a contact
  of width ``2a``;
* viscoelastic, full contact: ``μ = m2² Im E_r(qv) / (2 σ0)``, ``m2 = qΔ/√2``.

Units everywhere: mm, MPa, s, mm/s.
"""

# %%
# Elastic contact of a sine: Westergaard
# --------------------------------------
# A rubber with no viscous branches (``GeneralizedMaxwell.elastic``) at rest (``v = 0``):
# the contact fraction ``2a/λ`` found by the solver, put into Westergaard's formula, must
# give back the mean pressure that was imposed.
import matplotlib.pyplot as plt
import numpy as np

import rubbercontact as rc

wavelength, amplitude, modulus = 1.0, 0.01, 10.0          # mm, mm, MPa
sine = rc.roughness.SineSeries([wavelength], [amplitude])
elastic = rc.materials.GeneralizedMaxwell.elastic(modulus)
e_r = modulus / (1 - 0.5**2)                               # plane strain, ν = 1/2
p_full = np.pi * e_r * amplitude / wavelength              # pressure for full contact

pressures = p_full * np.array([0.02, 0.1, 0.3, 0.6, 0.9])
areas = np.array([rc.halfspace.solve_sliding(sine, sine.period, elastic, 0.0, p,
                                             n=4096).contact_fraction
                  for p in pressures])
westergaard = p_full * np.sin(np.pi * areas / 2) ** 2      # p̄ from the measured 2a/λ
westergaard_error = np.max(np.abs(westergaard / pressures - 1))
print(f"Westergaard: largest error in p̄ from the contact width {100 * westergaard_error:.2f} %")

# %%
# Viscoelastic friction in full contact
# -------------------------------------
# The SBR of the paper's Table 1 on the paper's high-slope wave (0.0625 mm, 0.01867 mm,
# ``m2 = 1.33``) at 10 mm/s, pressed hard enough to close every gap: the answer is linear
# in the surface and equals the closed form.
sbr = rc.materials.sbr()
wave = rc.roughness.high_slope_wave()
velocity = 10.0
q = 2 * np.pi / wave.wavelengths[0]
e_r_visco = complex(sbr.reduced_modulus(q * velocity))
sigma0 = 1.5 * abs(e_r_visco) * q * wave.amplitudes[0] / 2  # above full contact
res = rc.halfspace.solve_sliding(wave, wave.period, sbr, velocity, sigma0, n=1024)
mu_bem = res.friction
mu_closed_form = wave.rms_slopes()[0] ** 2 * e_r_visco.imag / (2 * sigma0)
print(f"full contact: μ = {mu_bem:.6f} (BEM), {mu_closed_form:.6f} (closed form), "
      f"contact fraction {res.contact_fraction:.3f}")

# %%
# The figure: mean pressure against contact fraction, solver and closed form.
a = np.linspace(0, 1, 200)
fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
ax.plot(a, np.sin(np.pi * a / 2) ** 2, label="Westergaard")
ax.plot(areas, pressures / p_full, "o", label="half-space solver")
ax.set_xlabel("contact fraction 2a/λ")
ax.set_ylabel("p̄ / p_full")
ax.legend()
rc.plotting.show(fig, "quickstart_halfspace.png")     # also a file: runs headless
