"""
The effective law and a hybrid run on the paper's section 3 surface
====================================================================

The hybrid method in its four steps (paper §2.1), on the three-wave validation surface of
the paper's section 3:

1. split the surface at ``m2 = 1`` into a high-slope part (one wave, 0.0625 mm) and a
   low-slope part (0.125 and 0.25 mm);
2. run the FEM sliding test on the high-slope wave at a few pressures: the *effective
   interface law* ``σ_hs(ū), α_hs(ū), Δτ_hs(ū)`` (eqs. 1–3);
3. solve the half-space on the low-slope part with that law as its interaction law, and
   add the law's shear stress: ``μ = μ_ls + μ_hs`` (eqs. 4–8);
4. compare with the VHS on the whole surface and with the full FEM.

Reduced settings throughout (one realization, one load, coarse meshes): the validation
(``make validate``) runs the paper's comparison. ``RUBBERCONTACT_EXAMPLE_QUICK=1`` makes the
meshes coarser still.
"""

# %%
# Surface and material
# --------------------
import os

import matplotlib.pyplot as plt
import numpy as np

import rubbercontact as rc
from rubbercontact.sweep import ExecutorConfig, ResultCache, run_sweep

QUICK = os.environ.get("RUBBERCONTACT_EXAMPLE_QUICK") == "1"
law_mesh, full_mesh = ((24, 12), (96, 24)) if QUICK else ((60, 30), (240, 45))

surface = rc.roughness.section3()
sbr = rc.materials.sbr()
hs, ls = surface.partition(m2_threshold=1.0)
print("m2 per wave:", np.round(surface.rms_slopes(), 3), "-> high-slope:", hs.wavelengths)

# %%
# The effective law of the high-slope wave
# ----------------------------------------
# One steady FEM test per pressure (a sweep task each: cached, so a second run of this
# script reads them back). ``runner`` runs them in this process.


def in_this_process(tasks):
    return run_sweep(tasks, cache=ResultCache(), executor=ExecutorConfig(workers=1),
                     progress=False).results


law_pressures = [0.1, 0.3, 1.0, 3.0, 8.0]                    # MPa
velocity = 10.0                                             # mm/s
law = rc.hybrid.effective_law(hs, sbr, law_pressures, [velocity], mesh=law_mesh,
                              runner=in_this_process)
print(law[["mean_separation", "contact_fraction", "friction"]].to_dataframe().round(4))

# %%
# The models on one realization
# -----------------------------
# ``rc.pipeline.run`` takes the configuration as a mapping (or a TOML file, see
# ``examples/section3.toml``) and the law just computed, so that it runs no law FEM.
config = {
    "surface": {"preset": "section3"},
    "material": {"preset": "sbr"},
    "velocities": [velocity],
    "realizations": 1,
    "seed": 2021,
    "models": ["vhs", "hybrid", "hybrid-windowed", "fem"],
    "loads": {"pressures": [0.35]},
    "fem": {"mesh": list(law_mesh), "full_mesh": list(full_mesh)},
    "halfspace": {"n": 2048},
    "execution": {"workers": 1},
}
ds = rc.pipeline.run(config, law=law, progress=False)
point = ds.isel(velocity=0, realization=0, pressure=0)
for m in point["model"].values:
    print(f"{m:>16}: μ = {float(point['friction'].sel(model=m)):.3f}, "
          f"A = {float(point['contact_fraction'].sel(model=m)):.4f}")

# %%
# The law against the linear (VHS) law of the same wave
# -----------------------------------------------------
# The run adds the VHS solution of the high-slope wave alone at the law's pressures
# (``law_vhs_friction``): the gap between the two curves is the kinematic non-linearity
# the FEM is there for.
fem_mu = ds["law_friction"].sel(velocity=velocity).values
vhs_mu = ds["law_vhs_friction"].sel(velocity=velocity).values
fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
ax.semilogx(law_pressures, fem_mu, "o-", label="FEM (law)")
ax.semilogx(law_pressures, vhs_mu, "s--", label="VHS, same wave")
ax.set_xlabel("mean pressure p̄ [MPa]")
ax.set_ylabel("μ of the high-slope wave")
ax.legend()
rc.plotting.show(fig, "hybrid_section3.png")     # also a file: runs headless
