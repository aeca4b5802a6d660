"""The validated classes of the models, and the notes of a run outside them.

The classes are data read from the validation reports; these tests check them on surfaces
whose place is known independently of the code (the surfaces the reports measured, a
gentle sine every model handles, the CAPTIF road that the mean-field's target class
excludes), the loss-peak frequency against a standard linear solid's closed form, the
speed bounds against the studies' own wavelengths and speeds, and the time-temperature
equivalence of the speed notes.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact import validity as va
from rubbercontact.errors import InputError
from rubbercontact.roughness import SineSeries
from rubbercontact.validity import classes

DATA = Path(__file__).resolve().parents[1] / "examples" / "data" / "real_surfaces"
SBR_PEAK = va.loss_peak_frequency(rc.materials.sbr())


def _sine(wavelength: float, m2: float) -> tuple[float, float]:
    """(wavelength, amplitude) of a wave of rms slope ``m2 = qΔ/√2``."""
    return wavelength, m2 * math.sqrt(2) * wavelength / (2 * math.pi)


def _series(*waves: tuple[float, float]) -> SineSeries:
    lam, m2 = zip(*waves, strict=True)
    return SineSeries(*zip(*map(_sine, lam, m2), strict=True))


def _point(v: float, contact=(0.03, 0.06), mu=(), mu_vhs=(), local=None, top=None):
    return va.SpeedPoint(v, contact=tuple(contact), friction=tuple(mu),
                         friction_vhs=tuple(mu_vhs), local_pressure=local, law_top=top)


def _captif() -> SineSeries:
    """The CAPTIF fit of examples/captif_road.toml (octaves of the two stations' scans)."""
    prof = rc.io.read_profiles(sorted(DATA.glob("captif_*.dat")), format="captif",
                               window=16.0, despike=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rc.roughness.RoughnessWarning)
        return rc.roughness.fit_hdc(prof, wavelengths=rc.roughness.octave_wavelengths(0.15, 8.0))


def _one_line(notes) -> None:
    for text in [n.text for n in notes] + list(va.summarize(notes)):
        assert "\n" not in text and text.strip() == text and text


def test_section3_inside_windowed_hybrid_class():
    """The §3 surface at the paper's speeds, areas and a covered law: the windowed hybrid
    was validated there (VALIDATION.md); the pointwise hybrid's split (ratio 2) is not."""
    stats = va.SurfaceStats.from_series(rc.roughness.section3())
    points = [_point(v, contact=(0.012, 0.05, 0.09), mu=(0.5, 0.7, 0.8),
                     mu_vhs=(0.52, 0.72, 0.85), local=1.5, top=2.0) for v in (10.0, 50.0)]
    assert va.assess("hybrid-windowed", stats, points, SBR_PEAK) == ()
    notes = va.assess("hybrid", stats, points, SBR_PEAK)
    assert [n.condition for n in notes] == ["split_ratio"]
    assert "scale_separation.md" in notes[0].text and notes[0].velocity is None


def test_scale_separated_two_waves_inside_pointwise_hybrid_class():
    """A 1 mm low-slope wave over the 1/16 mm high-slope wave (ratio 16) is inside the
    pointwise hybrid's class; at ratio 4 the split is outside it (ratio >= 8 measured)."""
    points = [_point(v, contact=(0.02, 0.06), local=0.4, top=1.0) for v in (10.0, 50.0)]
    steep = rc.roughness.high_slope_wave()           # the studies' 1/16 mm wave
    separated = va.SurfaceStats.from_series(_series((1.0, 0.3)) + steep)
    assert va.assess("hybrid", separated, points, SBR_PEAK) == ()
    close = va.SurfaceStats.from_series(_series((0.25, 0.3)) + steep)
    (note,) = va.assess("hybrid", close, points, SBR_PEAK)
    assert note.condition == "split_ratio" and math.isclose(note.excess, 2.0)
    assert "4" in note.text and "≥ 8" in note.text


def test_captif_outside_meanfield_class_naming_the_slopes():
    """The CAPTIF fit has waves steeper than the random ladders' m2 <= 0.6: outside the
    mean-field's target class at any speed, and at 10 m/s (the speed sweep's top) its
    shortest waves leave the measured frequency band too; a μ nine times the VHS's there
    is said in the same line as the class."""
    stats = va.SurfaceStats.from_series(_captif(), 1.0)
    assert max(stats.m2) > classes.LADDER_SLOPE
    notes = va.assess("meanfield", stats, [_point(10.0), _point(1e4, mu=(3.6,),
                                                                mu_vhs=(0.4,))], SBR_PEAK)
    by = {(n.condition, n.velocity) for n in notes}
    assert ("m2", None) in by and ("frequency", 1e4) in by and ("vhs", 1e4) in by
    assert ("frequency", 10.0) not in by
    m2 = next(n for n in notes if n.condition == "m2")
    assert "random octave ladders" in m2.text and "m2 up to 2.26" in m2.text
    assert "docs/validation/meanfield.md" in m2.text
    vhs = next(n for n in notes if n.condition == "vhs")
    assert "μ 3.6 departs from the VHS's 0.4" in vhs.text
    assert "outside its validated class" in vhs.text
    _one_line(notes)


def test_captif_hybrids_outside_on_the_steep_law_cell():
    """CAPTIF's high-slope waves (m2 up to 2.26) are steeper than the section 3 law cell the
    FEM law was validated on: both hybrids say so."""
    stats = va.SurfaceStats.from_series(_captif(), 1.0)
    for model in ("hybrid", "hybrid-windowed", "meanfield-hybrid"):
        conditions = {n.condition for n in va.assess(model, stats)}
        assert "m2_high" in conditions


def test_gentle_sine_inside_every_class():
    """One sine of m2 = 0.1 (1 mm) at 10 mm/s, 3 and 6 % contact, μ as the VHS's: no model
    has anything to say (no high-slope wave: the split's conditions do not apply)."""
    stats = va.SurfaceStats.from_series(_series((1.0, 0.1)))
    point = _point(10.0, contact=(0.03, 0.06), mu=(0.1, 0.12), mu_vhs=(0.1, 0.12))
    for model in va.CLASSES:
        assert va.assess(model, stats, [point], SBR_PEAK) == (), model


def test_speed_bounds_follow_the_studies_wavelengths_and_speeds():
    """The mean-field's band is that of the ladders (8 mm … 8/2⁹ mm at 1 … 500 mm/s): one
    1 mm sine is inside from 1·(1/8) to 500·(8/2⁹)⁻¹·1 mm/s and outside just beyond."""
    stats = va.SurfaceStats.from_series(_series((1.0, 0.1)))
    lo, hi = 1.0 / 8.0, 500.0 * 512 / 8.0
    for v, outside in ((lo * 0.98, True), (lo * 1.02, False), (hi * 0.98, False),
                       (hi * 1.02, True)):
        notes = va.assess("meanfield", stats, [_point(v)], SBR_PEAK)
        assert bool(notes) is outside, v
    (note,) = va.assess("meanfield", stats, [_point(hi * 2)], SBR_PEAK)
    assert math.isclose(note.excess, 2.0, rel_tol=1e-9)
    assert f"{lo:.3g}–{hi:.3g} mm/s" in note.text


def test_speed_notes_follow_the_rubbers_loss_peak():
    """Time-temperature superposition: the rubber at T slides at v as the reference rubber
    at a_T v, so the notes agree (the shift moves the loss peak by a_T)."""
    shift = rc.materials.WLF(8.86, 101.6, 20.0)
    cold = rc.materials.sbr().at_temperature(0.0, shift=shift)
    a_t = SBR_PEAK / va.loss_peak_frequency(cold)
    assert a_t > 10                              # colder: slower relaxation
    stats = va.SurfaceStats.from_series(_series((1.0, 0.1)))
    v = 2e4 / a_t                                # inside at T_ref only if not shifted
    shifted = va.assess("meanfield", stats, [_point(v)], va.loss_peak_frequency(cold))
    reduced = va.assess("meanfield", stats, [_point(a_t * v)], SBR_PEAK)
    assert [n.excess for n in shifted] == pytest.approx([n.excess for n in reduced])
    assert va.assess("meanfield", stats, [_point(v)], SBR_PEAK) == ()


def test_loss_peak_of_a_standard_linear_solid():
    """E = E0 + E1 iωτ/(1 + iωτ): tan δ peaks at ωτ = √(E0/(E0 + E1))."""
    mat = rc.materials.GeneralizedMaxwell(2.0, moduli=(6.0,), relaxation_times=(1e-3,))
    assert va.loss_peak_frequency(mat) == pytest.approx(math.sqrt(2.0 / 8.0) / 1e-3, rel=1e-3)
    with pytest.raises(InputError, match="loss factor"):
        va.loss_peak_frequency(rc.materials.GeneralizedMaxwell(2.0))


def test_departure_inside_the_class_and_the_reference():
    """Inside its class a model departing from the VHS beyond its tolerance is flagged as
    such; within the tolerance it is not; the VHS is the reference and never departs."""
    stats = va.SurfaceStats.from_series(_series((1.0, 0.1)))
    tol = va.CLASSES["meanfield"].tolerance
    near = _point(10.0, mu=(1.0 + 0.9 * tol,), mu_vhs=(1.0,))
    far = _point(10.0, mu=(1.0 + 1.1 * tol,), mu_vhs=(1.0,))
    assert va.assess("meanfield", stats, [near], SBR_PEAK) == ()
    (note,) = va.assess("meanfield", stats, [far], SBR_PEAK)
    assert note.condition == "vhs" and "inside its validated class" in note.text
    assert note.excess == pytest.approx(1.1 * tol / (tol + classes.MU_NOISE))
    assert va.assess("vhs", stats, [_point(10.0, mu=(5.0,), mu_vhs=(1.0,))], SBR_PEAK) == ()


def test_departure_names_the_runs_under_resolved_fem():
    """A departure inside the class but with the run's FEM under-resolved (a note of the
    run, not of the surface) names that as where the run leaves the class, instead of
    "inside its validated class: check the run"; the run note itself is not returned."""
    stats = va.SurfaceStats.from_series(rc.roughness.section3())
    far = _point(10.0, mu=(0.34,), mu_vhs=(0.46,))
    (inside,) = va.assess("fem", stats, [far], SBR_PEAK)
    assert "inside its validated class" in inside.text
    coarse = va.Note("fem", "fem_resolution", "6 of 6 FEM tests under-resolved",
                     detail="6 of 6 FEM tests under-resolved")
    (note,) = va.assess("fem", stats, [far], SBR_PEAK, [coarse])
    assert note.condition == "vhs" and "inside its validated class" not in note.text
    assert "outside its validated class" in note.text
    assert note.text.endswith("6 of 6 FEM tests under-resolved")


def test_departure_of_vanishing_friction_is_noise():
    """At the slowest speeds μ ~ 1e-5 on both sides is the grids' noise, not a departure; a
    hybrid keeping μ = 0.04 where the VHS has 4e-4 (issue 41) is one."""
    stats = va.SurfaceStats.from_series(_series((1.0, 0.1)))
    noise = _point(10.0, mu=(1.4e-5,), mu_vhs=(-1.6e-5,))
    assert va.assess("meanfield", stats, [noise], SBR_PEAK) == ()
    section3 = va.SurfaceStats.from_series(rc.roughness.section3())
    (note,) = va.assess("hybrid-windowed", section3,
                        [_point(10.0, mu=(0.04,), mu_vhs=(4e-4,))], SBR_PEAK)
    assert note.condition == "vhs" and "inside its validated class" in note.text


def test_law_coverage_and_summary_fold_the_speeds():
    """Local pressures past the law's FEM points are a note per speed; the summary folds
    them into the model's line, naming the speeds and the worst."""
    stats = va.SurfaceStats.from_series(rc.roughness.section3())
    points = [_point(v, local=p, top=1.0) for v, p in ((10.0, 3.0), (20.0, 1.9e3),
                                                       (50.0, 0.5))]
    notes = [n for n in va.assess("hybrid-windowed", stats, points, SBR_PEAK)
             if n.condition == "law_pressure"]
    assert [n.velocity for n in notes] == [10.0, 20.0]
    (line,) = [x for x in va.summarize(notes)]
    assert line.startswith("hybrid-windowed: outside its validated class (")
    assert "): at 2 speeds (10 … 20 mm/s), worst at 20 mm/s: local pressures reach" in line
    assert "1.9e+03 MPa" in line
    attrs = va.as_attrs("hybrid-windowed", notes)
    assert attrs == {"validity_hybrid-windowed": line}


def test_meanfield_class_is_octave_ladders():
    """Waves of 3 and 1 mm, a ratio of 3: outside the ladders' octave spacing; 2 and 1 mm
    are inside."""
    point = _point(10.0)
    third = va.SurfaceStats.from_series(_series((3.0, 0.2), (1.0, 0.2)))
    (note,) = va.assess("meanfield", third, [point], SBR_PEAK)
    assert note.condition == "spacing" and "ratio up to 3," in note.text
    octave = va.SurfaceStats.from_series(_series((2.0, 0.2), (1.0, 0.2)))
    assert va.assess("meanfield", octave, [point], SBR_PEAK) == ()


def test_condition_excess():
    """The factor by which the worst value lies outside; 1 inside or without values."""
    c = va.Condition("contact", 0.01, 0.1)
    assert c.excess(np.array([0.02, 0.3])) == pytest.approx(3.0)
    assert c.excess(np.array([0.005, 0.05])) == pytest.approx(2.0)
    assert c.excess(np.array([0.0])) == math.inf
    assert c.excess(np.array([])) == 1.0 and c.excess(np.array([0.05])) == 1.0


@pytest.mark.parametrize("call, match", [
    (lambda: va.assess("persson", va.SurfaceStats((1.0,), (0.1,))), "unknown model"),
    (lambda: va.SurfaceStats((1.0, -2.0), (0.1, 0.2)), "wavelengths must be positive"),
    (lambda: va.SurfaceStats((1.0,), (0.1, 0.2)), "one length"),
    (lambda: va.SurfaceStats((1.0,), (-0.1,)), "m2 must be >= 0"),
    (lambda: va.SurfaceStats((1.0,), (0.1,), m2_threshold=0.0), "m2_threshold"),
    (lambda: va.SpeedPoint(0.0), "must be > 0"),
    (lambda: va.SpeedPoint(1.0, contact=(1.5,)), r"\[0, 1\]"),
    (lambda: va.SpeedPoint(1.0, friction=(0.1,)), "one value per load"),
    (lambda: va.SpeedPoint(1.0, local_pressure=2.0), "together"),
    (lambda: va.assess("meanfield", va.SurfaceStats((1.0,), (0.1,)), [_point(1.0)]),
     "loss-peak frequency"),
])
def test_bad_input_is_one_clear_error(call, match):
    with pytest.raises(InputError, match=match) as info:
        call()
    assert "\n" not in str(info.value)
