"""
The mean-field (Persson) model against the half-space BEM
==========================================================

:mod:`rubbercontact.meanfield` is Persson's theory of rubber friction (with his
correction ``S = γ + (1 − γ)A²``, ``γ = 0.8`` by default): it sees the surface only through
its power spectrum and costs microseconds per speed, where the BEM solves each random-phase
realization on a grid. It is the model for roughness over many decades, where no grid
reaches. (On a 1D sine series the strip cascade, ``StripOptions`` / the model
``meanfield-strips``, is closer to the BEM.)

Two checks against the BEM (:func:`rubbercontact.halfspace.solve_sliding`):

* one sine in full contact, where both are exact: ``μ = m2² Im E_r(qv)/(2σ0)``;
* the paper's Table 2 asphalt at 10 mm/s and 0.4 MPa, BEM averaged over random-phase
  realizations; ``docs/validation/meanfield.md`` gives the theory's error there.

``RUBBERCONTACT_EXAMPLE_QUICK=1`` averages the BEM over fewer realizations on a coarser
grid (4 on 4096 points instead of 8 on 16384).
"""

# %%
# One sine in full contact
# ------------------------
import os

import matplotlib.pyplot as plt
import numpy as np

import rubbercontact as rc

QUICK = os.environ.get("RUBBERCONTACT_EXAMPLE_QUICK") == "1"
sbr = rc.materials.sbr()
sine = rc.roughness.SineSeries([0.125], [0.002])
q, velocity = 2 * np.pi / 0.125, 10.0
e_r = complex(sbr.reduced_modulus(q * velocity))
# five times the BEM's full-contact pressure |E_r|qΔ/2: the theory's Gaussian P(σ) then
# has no weight below σ = 0 either (its contact fraction is 1 to 1e-12)
sigma0_full = 5 * abs(e_r) * q * 0.002 / 2
theory_sine = rc.meanfield.solve(rc.meanfield.PSD.from_sines(sine), sbr, velocity,
                                 sigma0_full)
bem_sine = rc.halfspace.solve_sliding(sine, None, sbr, velocity, sigma0_full, n=1024)
print(f"one sine, full contact: μ theory {theory_sine.friction:.6f}, "
      f"BEM {bem_sine.friction:.6f}, A theory {theory_sine.contact_fraction:.4f}")

# %%
# Table 2 at 10 mm/s, 0.4 MPa
# ---------------------------
surface = rc.roughness.asphalt_ac8()
psd = rc.meanfield.PSD.from_sines(surface)
sigma0 = 0.4
theory = rc.meanfield.solve(psd, sbr, velocity, sigma0)
n_real, n_grid = (4, 4096) if QUICK else (8, 16384)
bem = [rc.halfspace.solve_sliding(r, r.period, sbr, velocity, sigma0, n=n_grid)
       for r in surface.realizations(n_real, seed=1)]
bem_mu = np.array([r.friction for r in bem])
bem_area = np.array([r.contact_fraction for r in bem])
bem_mu_se = bem_mu.std(ddof=1) / np.sqrt(n_real)
print(f"Table 2: μ theory {theory.friction:.3f}, BEM {bem_mu.mean():.3f} ± {bem_mu_se:.3f} "
      f"({n_real} realizations); A theory {theory.contact_fraction:.4f}, "
      f"BEM {bem_area.mean():.4f}")

# %%
# μ(v) over ten decades in one vectorised call
# ---------------------------------------------
speeds = np.geomspace(1e-4, 1e6, 201)
curve = rc.meanfield.friction_curve(psd, sbr, speeds, sigma0)
fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
ax.semilogx(curve.velocities, curve.friction, label="mean-field theory")
ax.errorbar([velocity], [bem_mu.mean()], yerr=[2 * bem_mu_se], fmt="o",
            label=f"BEM, {n_real} realizations")
ax.set_xlabel("v [mm/s]")
ax.set_ylabel("μ")
ax.set_title("Table 2 asphalt, σ0 = 0.4 MPa")
ax.legend()
rc.plotting.show(fig, "meanfield_vs_bem.png")     # also a file: runs headless
