"""
The steady FEM on the paper's high-slope wave
==============================================

One point of the effective interface law (paper §2.4): a periodic plane-strain cell of
finite-strain viscoelastic SBR pressed with 1 MPa onto the paper's steepest wave
(0.0625 mm, ``m2 = 1.33``) and slid at 10 mm/s.

:func:`rubbercontact.fem.steady_sliding` solves the steady state directly, in the frame of
the surface; :func:`rubbercontact.fem.sliding_test` with ``solver="transient"`` time-steps
the press / settle / slide protocol until it stops changing. The two are the same discrete
problem, so the transient test, once settled, must land on the steady answer.

``RUBBERCONTACT_EXAMPLE_QUICK=1`` runs a coarse cell (24 × 12) and a shorter transient,
as the docs build and the tests do.
"""

# %%
# Settings
# --------
import os
import time
import warnings

import matplotlib.pyplot as plt

import rubbercontact as rc

QUICK = os.environ.get("RUBBERCONTACT_EXAMPLE_QUICK") == "1"
mesh, grading = ((24, 12), 1.0) if QUICK else ((120, 23), 8.0)
periods = 20 if QUICK else 120      # transient sliding distance, in cell periods

wave = rc.roughness.high_slope_wave()
sbr = rc.materials.sbr()
pressure, velocity = 1.0, 10.0      # MPa, mm/s

# %%
# The steady solve
# ----------------
# Newton–Krylov on the whole steady problem, with continuation in load on a coarse
# mesh first; ``stats`` says what it did.
t0 = time.perf_counter()
steady = rc.fem.steady_sliding(wave, sbr, pressure, velocity, mesh=mesh, grading=grading)
steady_time = time.perf_counter() - t0
print(f"steady:    μ = {steady.friction:.5f}, A = {steady.contact_fraction:.4f}, "
      f"ū = {1e3 * steady.mean_separation:.3f} µm  ({steady_time:.1f} s, "
      f"{steady.stats.newton_iterations} Newton iterations)")

# %%
# The transient test, started where the steady solution sits
# ----------------------------------------------------------
# One column of travel per time step (the steady solver's history step), slid many of
# the SBR's longest retardation times (16 ms) so that the cell's creep has settled.
t0 = time.perf_counter()
with warnings.catch_warnings():
    warnings.simplefilter("ignore", RuntimeWarning)    # "not steady" before the last period
    transient = rc.fem.sliding_test(wave, sbr, pressure, velocity, mesh=mesh,
                                    grading=grading, solver="transient", periods=periods,
                                    min_periods=periods, steady_tol=1e-12,
                                    surface_offset=steady.stats.surface_offset)
transient_time = time.perf_counter() - t0
history = transient.history
sliding = history["phase"] == 2
last_period = {k: history[k][sliding][-mesh[0]:].mean()
               for k in ("friction", "contact_fraction", "mean_separation")}
print(f"transient: μ = {last_period['friction']:.5f}, "
      f"A = {last_period['contact_fraction']:.4f}, "
      f"ū = {1e3 * last_period['mean_separation']:.3f} µm  (last period; {transient_time:.1f} s)")

# %%
# The friction of the transient test along its sliding distance, and the steady answer.
fig, (ax, ax2) = plt.subplots(1, 2, figsize=(9, 3.5), layout="constrained")
ax.plot(history["sliding_distance"][sliding] / wave.period, history["friction"][sliding],
        lw=0.8, label="transient")
ax.axhline(steady.friction, color="k", ls="--", label="steady")
ax.set_xlabel("sliding distance / period")
ax.set_ylabel("μ")
ax.legend()
prof = steady.pressure_profile
ax2.plot(prof.x / wave.period, prof.pressure)
ax2.set_xlabel("x / λ")
ax2.set_ylabel("contact pressure [MPa]")
ax2.set_title("steady face pressure")
rc.plotting.show(fig, "steady_fem.png")     # also a file: runs headless
