"""Crests rounded to a radius (rubbercontact.roughness.crests) against closed forms.

A disk of radius ``r`` under a parabolic crest ``z = -x²/(2R0)`` (``R0 < r``) touches it
where the slopes agree, at ``x_t = ±sqrt(r² - R0²)``, and its top lies
``δ = (r - R0)²/(2 R0)`` below the crest. A sine's crest is that parabola to the quartic
term of the cosine, a relative ``(q x)²/12``.
"""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.fem.options import FemOptions
from rubbercontact.roughness import SineSeries
from rubbercontact.roughness.crests import SMOOTHING, opening_lowering, round_crests

R = 0.0375                       # mm, the CAPTIF profiles' sampling interval
R0 = 0.010                       # mm, the crest radius of the sharp sine below
Q = 2 * np.pi                    # rad/mm, wavelength 1 mm
SHARP = SineSeries([1.0], [1.0 / (R0 * Q**2)])   # crest at x = 0.25 mm, radius R0


def _apex_lowering() -> float:
    return (R - R0) ** 2 / (2 * R0)


def test_the_opening_of_a_sharp_crest_is_the_disk_on_its_parabola():
    n = 2**16
    dx = 1.0 / n
    x = np.arange(n) * dx
    low = opening_lowering(SHARP.heights(x), dx, R)
    x_t = np.sqrt(R**2 - R0**2)
    # the cosine's quartic term: a relative (q x)²/12 of the parabola's drop over the
    # arc, x_t²/(2 R0), from the apex to the tangent points
    quartic = (Q * x_t) ** 2 / 12
    assert -low.min() == pytest.approx(_apex_lowering(), abs=quartic * x_t**2 / (2 * R0))
    assert x[np.argmin(low)] == pytest.approx(0.25, abs=dx)
    # flanks and valley untouched beyond the tangent points (grid step as margin)
    away = np.abs(x - 0.25) > x_t * (1 + quartic) + 2 * dx
    assert np.all(low[away] == 0.0)
    assert np.all(low <= 0.0)


def test_crests_blunter_than_the_radius_are_left_as_they_are():
    blunt = SineSeries([0.5, 1.0], [0.02, 0.05], [0.3, 1.1])   # crest radii > 0.1 mm
    rounded = round_crests(blunt, R)
    x = np.linspace(0, 1, 1001)
    assert rounded.lowering.size == 0 and rounded.offset == 0.0
    np.testing.assert_array_equal(rounded.heights(x), blunt.heights(x))
    np.testing.assert_array_equal(rounded.curvatures(x), blunt.curvatures(x))


def test_a_sharp_crest_is_rounded_to_about_the_radius_and_only_lowered():
    rounded = round_crests(SHARP, R)
    x = np.linspace(0, 1, 200_001)
    z, z0 = rounded.heights(x), SHARP.heights(x)
    i = np.argmax(z)
    # the smoothing of the lowering over s = SMOOTHING·r lowers its peak by about
    # ½ d''(0) s², with d'' = 1/R0 - 1/r the lowering's curvature at the apex
    s = SMOOTHING * R
    expected = _apex_lowering() - 0.5 * (1 / R0 - 1 / R) * s**2
    assert z0[i] - z[i] == pytest.approx(expected, rel=0.01)
    # apex radius: the arc's r, less what the smoothing takes off the lowering's curvature
    radius = -1.0 / rounded.curvatures(x[i])
    assert 0.9 * R < radius <= R
    # only ever lowered (to the Fourier truncation, HARMONIC_TOL of the largest harmonic)
    assert np.max(z - z0) < 1e-6 * np.max(z0 - z)
    # the band's slope bound Σ qΔ still holds (the FEM's contact search uses it)
    bound = float(np.sum(SHARP.wavenumbers * SHARP.amplitudes))
    assert np.max(np.abs(rounded.slopes(x))) <= bound * (1 + 1e-3)


def test_derivatives_of_the_rounded_profile_agree_with_its_heights():
    band = SineSeries([0.25, 0.5, 1.0], [0.158, 0.152, 0.235])   # CAPTIF station 1's band
    rounded = round_crests(band, R)
    x = np.linspace(0, 1, 4001)
    h = 1e-5
    fd = (rounded.heights(x + h) - rounded.heights(x - h)) / (2 * h)
    np.testing.assert_allclose(rounded.slopes(x), fd, atol=1e-5 * np.abs(fd).max())
    fd2 = (rounded.slopes(x + h) - rounded.slopes(x - h)) / (2 * h)
    np.testing.assert_allclose(rounded.curvatures(x), fd2, atol=1e-4 * np.abs(fd2).max())
    # the mesh rules follow the band's waves
    np.testing.assert_array_equal(rounded.wavelengths, band.wavelengths)
    assert rounded.period == band.period and rounded.as_dict()["crest_radius"] == R


def test_fem_options_take_a_positive_crest_radius_and_keep_old_keys_without_one():
    assert "crest_radius" not in FemOptions().to_dict()
    opts = FemOptions(crest_radius=R)
    assert FemOptions.from_dict(opts.to_dict()) == opts
    with pytest.raises(InputError, match="crest_radius"):
        FemOptions(crest_radius=-1.0)


def test_the_fem_on_blunt_crests_is_the_fem_on_the_surface_as_given():
    import rubbercontact as rc

    blunt = SineSeries([1.0], [0.02])                  # crest radius 1.3 mm
    sbr = rc.materials.sbr()
    plain = rc.fem.steady_sliding(blunt, sbr, 0.1, 1.0, mesh=(32, 24))
    rounded = rc.fem.steady_sliding(blunt, sbr, 0.1, 1.0, mesh=(32, 24), crest_radius=R)
    assert (rounded.friction, rounded.contact_fraction, rounded.mean_separation) == (
        plain.friction, plain.contact_fraction, plain.mean_separation)


def test_a_run_rounds_its_law_cell_and_says_so(tmp_path, capsys):
    # the preset's high-slope wave has crests of 5.3 µm: rounded to 10 µm, the run's law
    # point is the FEM test on the rounded cell, and the summary says so in one line
    import xarray as xr

    import rubbercontact as rc
    from rubbercontact.cli import main

    cfg = tmp_path / "rounded.toml"
    cfg.write_text("""
velocities = [10.0]
realizations = 1
models = ["vhs", "hybrid"]
[surface]
preset = "high_slope_wave"
[loads]
pressures = [1.0]
[halfspace]
n = 512
[fem]
mesh = [30, 23]
crest_radius = 0.01
[law]
pressures = [0.3, 1.0]
extend = false
[execution]
workers = 1
cache = "cache"
[output]
directory = "out"
""")
    assert main(["run", str(cfg), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "law cell: the high-slope crests rounded to 0.01 mm; the law's friction" in out
    law = xr.load_dataset(tmp_path / "out" / "results.nc")["law_friction"]
    from rubbercontact.roughness.presets import preset

    hs, _ = preset("high_slope_wave").partition(1.0)
    options = rc.config.load_config(cfg).fem.options(rc.materials.sbr())
    direct = rc.fem.steady_sliding(hs, rc.materials.sbr(), 1.0, 10.0, options=options)
    at = float(law.sel(velocity=10.0, law_pressure=1.0))
    assert at == pytest.approx(direct.friction, rel=1e-9)
