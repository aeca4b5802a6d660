"""The validity notes of small pipeline runs (``rubbercontact.validity.assess_run``).

Expectations come from outside the code: the section 3 surface's steepest wave against the
mean-field's target class (m2 <= 0.6) and the ladders' frequency band, time-temperature
superposition (the shift factor the run reports moves the band by a_T), a gentle sine every
model holds on (the law's FEM points against the stored local pressures:
tests/test_pipeline_lawcover.py).
"""

from __future__ import annotations

import math

import rubbercontact as rc
from rubbercontact import validity as va
from rubbercontact.pipeline.execute import as_config
from rubbercontact.pipeline.setup import resolve
from rubbercontact.validity import classes

WLF = {"law": "WLF", "c1": 8.86, "c2": 101.6}
#: The ladders' highest frequency q v [rad/s] (8/2⁹ mm at 500 mm/s), the SBR's scale.
LADDER_TOP = 2 * math.pi / classes.LADDER_WAVELENGTHS[0] * classes.LADDER_SPEEDS[1]


def _config(tmp_path, **over) -> dict:
    cfg = {"surface": {"preset": "section3"}, "loads": {"pressures": [0.3, 1.0]},
           "velocities": [10.0, 1e4], "realizations": 2, "seed": 3,
           "models": ["vhs", "meanfield"], "halfspace": {"n": 1024},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    cfg.update(over)
    return cfg


def _notes(cfg: dict) -> tuple[rc.validity.Note, ...]:
    ds = rc.pipeline.run(cfg, progress=False)
    return ds, va.assess_run(ds, resolve(as_config(cfg)))


def test_section3_run_meanfield_outside_vhs_inside(tmp_path):
    """Section 3's 1/16 mm wave (m2 = 1.33) is steeper than the ladders' 0.6, and at 10 m/s
    its frequency (100 rad/mm · 1e4 mm/s) is past the ladders' top; the VHS is inside."""
    ds, notes = _notes(_config(tmp_path))
    assert not [n for n in notes if n.model == "vhs"]
    found = {(n.condition, n.velocity) for n in notes if n.model == "meanfield"}
    assert ("m2", None) in found and ("frequency", 1e4) in found
    assert ("frequency", 10.0) not in found
    contact_low = float(ds["contact_fraction"].sel(model="meanfield", velocity=1e4)
                        .mean("realization").min()) < classes.LADDER_CONTACT[0]
    assert (("contact", 1e4) in found) is contact_low
    # one line per model, each condition once in it (the brief: "says so in the run, in
    # one line"), the speeds folded
    (line,) = va.summarize(notes)
    assert "\n" not in line and line.startswith("meanfield: outside its validated class (")
    assert line.count("m2 up to") == 1 and "q·v leave the measured band" in line
    assert va.as_attrs("meanfield", notes) == {"validity_meanfield": line}


def test_temperature_run_moves_the_band_by_the_shift_factor(tmp_path):
    """At 0 °C the SBR is a_T times slower: 100 mm/s on the 1/16 mm wave leaves the
    ladders' band there and not at 20 °C (the reference temperature)."""
    cfg = _config(tmp_path, velocities=[10.0, 100.0], temperatures=[0.0, 20.0],
                  material={"preset": "sbr", "reference_temperature": 20.0, "shift": WLF})
    ds, notes = _notes(cfg)
    q = 2 * math.pi / float(rc.roughness.section3().wavelengths.min())
    freq = {(n.temperature, n.velocity) for n in notes if n.condition == "frequency"}
    for t in (0.0, 20.0):
        a_t = float(ds["shift_factor"].sel(temperature=t))
        for v in (10.0, 100.0):
            assert ((t, v) in freq) is (q * a_t * v > LADDER_TOP), (t, v)
    assert (0.0, 100.0) in freq and (20.0, 100.0) not in freq
    # the surface's note is given once, not once per temperature
    assert sum(n.condition == "m2" for n in notes) == 1


def test_gentle_sine_run_inside_every_class(tmp_path):
    """One 1 mm sine of m2 = 0.1: no high-slope wave, small slopes, contact within every
    class's range at 10 mm/s: no note for any model. (The strips are the mean-field model
    of a sine series; Persson's diffusion is 4 times the VHS's μ on one sine, and says so.)"""
    amplitude = 0.1 * math.sqrt(2) / (2 * math.pi)
    cfg = _config(tmp_path, surface={"wavelengths": [1.0], "amplitudes": [amplitude]},
                  loads={"pressures": [0.003, 0.01]}, velocities=[10.0],
                  models=["vhs", "hybrid", "hybrid-windowed", "meanfield-strips"])
    ds, notes = _notes(cfg)
    assert float(ds["contact_fraction"].min()) > 0.01
    assert notes == ()


def test_a_run_says_where_a_model_left_its_class(tmp_path):
    # The run itself carries the notes (results attrs, one line each) and its summary prints
    # them: the mean-field on section 3 (m2 1.33 > 0.6), nothing for the VHS.
    from rubbercontact.io.results import read_results, write_results
    from rubbercontact.plotting.summary import summary_table

    ds = rc.pipeline.run(_config(tmp_path, velocities=[10.0]), progress=False)
    assert ds.attrs["validity_vhs"] == ""
    (line,) = ds.attrs["validity_meanfield"].splitlines()
    assert line.startswith("meanfield: outside its validated class") and "m2" in line
    path = write_results(ds, tmp_path / "r.nc")
    assert line in summary_table(read_results(path))
