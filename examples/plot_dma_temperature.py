"""
From DMA data to friction at two temperatures
==============================================

A rubber enters the method as a Prony series (generalized Maxwell model). Measured
dynamic mechanical analysis (DMA) data give it in three steps:

1. :func:`rubbercontact.materials.read_dma` reads a CSV of ``E'``, ``E''`` against
   frequency; :func:`~rubbercontact.materials.master_curve` shifts isothermal sweeps onto
   one curve and fits a WLF law to the shifts;
2. :func:`~rubbercontact.materials.fit_prony` fits a series with non-negative moduli;
3. :meth:`~rubbercontact.materials.GeneralizedMaxwell.at_temperature` moves the series to
   another temperature by time–temperature superposition (TTS).

The files in ``examples/data/`` are synthetic: the SBR of the paper's Table 1 with 1 %
noise, shifted with WLF ``C1 = 8.86``, ``C2 = 101.6 K`` at 20 °C — so every step can be
checked against the truth. On the half-space, TTS is an identity: the rubber at ``T``
sliding at ``v`` is the reference rubber at ``a_T v``.
"""

# %%
# The master curve and its Prony fit
# ----------------------------------
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import rubbercontact as rc

DATA = Path(__file__).resolve().parent / "data"
dma = rc.materials.read_dma(DATA / "dma_synthetic_sbr.csv", temperature=20.0)
fit = rc.materials.fit_prony(dma, report=True)
rubber = fit.material
print(fit.report.summary())

truth = rc.materials.sbr()       # the series the synthetic data were made from
omega = dma.frequency
fit_vs_truth = np.abs(rubber.complex_modulus(omega) / truth.complex_modulus(omega) - 1)
print(f"|E*| of the fit against the true series: max {100 * fit_vs_truth.max():.2f} %")

# %%
# The shift law from isothermal sweeps
# ------------------------------------
sweeps = rc.materials.read_dma(DATA / "dma_synthetic_sbr_isotherms.csv")
master = rc.materials.master_curve(sweeps, t_ref=20.0)
wlf = master.law
print(f"fitted {wlf}; rms misfit {master.law_rms_error:.3f} decades")
rubber = rubber.at_temperature(20.0, shift=wlf)   # attach the law (a no-op shift)

# %%
# Friction against speed at 0 °C and 40 °C on the half-space
# -----------------------------------------------------------
# A 0.125 mm sine with 2 µm amplitude at 0.1 MPa (partial contact).
sine = rc.roughness.SineSeries([0.125], [0.002])
speeds = np.geomspace(1e-3, 1e5, 25)                      # mm/s
temperatures = (0.0, 40.0)
friction = {}
for t in temperatures:
    warm = rubber.at_temperature(t)
    friction[t] = np.array([rc.halfspace.solve_sliding(sine, None, warm, v, 0.1,
                                                       n=512).friction for v in speeds])

# TTS on the half-space: at T and v the answer is the reference rubber's at a_T v.
a_t = wlf.shift(temperatures[0])
mu_cold = friction[temperatures[0]][12]
mu_reduced = rc.halfspace.solve_sliding(sine, None, rubber, a_t * speeds[12], 0.1,
                                        n=512).friction
print(f"a_T(0 °C) = {a_t:.3g}; μ at 0 °C, v = {speeds[12]:g} mm/s: {mu_cold:.6f}; "
      f"at 20 °C, a_T v: {mu_reduced:.6f}")

# %%
# The friction peak moves to higher speeds as the rubber warms.
fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
for t in temperatures:
    ax.semilogx(speeds, friction[t], label=f"{t:g} °C")
ax.set_xlabel("v [mm/s]")
ax.set_ylabel("μ")
ax.legend()
rc.plotting.show(fig, "dma_temperature.png")     # also a file: runs headless
