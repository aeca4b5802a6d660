"""
A real road: fitting sine waves to CAPTIF profiles
===================================================

The method starts from a measured surface reduced to a sum of sine waves, one per octave,
whose amplitudes are fitted to the measured height-difference correlation (HDC,
``R_zz(λ) = <(z(x+λ) − z(x))²>``, paper eqs. 9–17, 29–30).

The two profiles in ``examples/data/real_surfaces/`` are laser-profilometer line scans of
a chipseal road (CAPTIF, MIT licence; provenance in that folder's README). The reader
trims the instrument's reference plates and cuts 16 mm windows free of laser dropouts.
"""

# %%
# Read the scans
# --------------
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.io import read_captif
from rubbercontact.plotting import plot_hdc

DATA = Path(__file__).resolve().parent / "data" / "real_surfaces"
scans = read_captif(DATA / "captif_20211011_aylesbury_dec_station_0.dat", window=16.0)
print(f"{len(scans)} windows of {scans.lengths[0]:.1f} mm at dx = {scans.dx:.4f} mm")
_, (rzz_1mm, rzz_8mm) = rc.roughness.hdc(scans, None, [1.0, 8.0])
print(f"R_zz(1 mm) = {rzz_1mm:.3f} mm², R_zz(8 mm) = {rzz_8mm:.2f} mm²")

# %%
# Fit one wave per octave
# -----------------------
# From four samples per wavelength (the shortest the sampling resolves) up to the window.
wavelengths = rc.roughness.octave_wavelengths(4 * scans.dx, 16.0)
fit = rc.roughness.fit_hdc_details(scans, None, wavelengths)
series = fit.series
print(rc.roughness.format_table(fit))
data_rms = rc.roughness.rms_height(scans)
print(f"rms height: series {series.rms_height:.3f} mm, data {data_rms:.3f} mm")

# %%
# The split at m2 = 1: the steep short octaves go to the FEM, the rest to the half-space.
hs, ls = series.partition(m2_threshold=1.0)
print("high-slope wavelengths [mm]:", np.round(hs.wavelengths, 3))
print("low-slope wavelengths [mm]: ", np.round(ls.wavelengths, 3))

# %%
# The HDC figure (paper Fig. 6 style).
fig = plot_hdc(fit, title="CAPTIF station 0: HDC and its sine-series fit")
rc.plotting.show(fig, "captif_road.png")     # also a file: runs headless
