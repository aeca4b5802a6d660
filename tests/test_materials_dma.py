"""DMA data: reading, the Prony fit against a known series, master curves, TOML, the CLI."""

from __future__ import annotations

import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.cli import main
from rubbercontact.errors import InputError
from rubbercontact.materials import (
    WLF,
    DMAData,
    DMAWarning,
    GeneralizedMaxwell,
    dma_from_material,
    fit_prony,
    master_curve,
    read_dma,
)

SBR = rc.materials.sbr()
EXAMPLES = Path(__file__).resolve().parents[1] / "examples" / "data"
#: 1e-3 to 1e9 Hz, 8 points per decade: the SBR's whole transition and both plateaus
OMEGA = 2 * np.pi * np.logspace(-3, 9, 97)


def _dense(dma: DMAData) -> np.ndarray:
    return np.geomspace(dma.frequency.min(), dma.frequency.max(), 2000)


def _write(path: Path, header: str, rows: np.ndarray) -> Path:
    lines = [header] + [",".join(f"{v:.12g}" for v in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def sbr_rows():
    """Exact SBR data: frequency [Hz], E' [MPa], E'' [MPa]."""
    e = SBR.complex_modulus(OMEGA)
    return np.column_stack([OMEGA / (2 * np.pi), e.real, e.imag])


# --- the fit against a known series ------------------------------------------------------------
def test_fit_recovers_the_series_within_one_percent():
    # 0.5 % multiplicative Gaussian noise on E' and E'' (seed 7). Least squares averages it:
    # the fitted curve's error is ~ σ √(P/2N) = 0.5 % √(19/194) = 0.16 % rms for P = 19
    # unknowns (9 branches) and 2N = 194 values, a few times that at worst inside the range;
    # the model family contains the truth, so there is no bias: 1 % is 2-5x the expected
    # worst case (measured: |E*| 0.20 %, E' 0.21 %, E'' 0.23 %).
    dma = dma_from_material(SBR, OMEGA, noise=0.005, seed=7)
    fit = fit_prony(dma, report=True)
    w = _dense(dma)
    true, got = SBR.complex_modulus(w), fit.material.complex_modulus(w)
    assert np.max(np.abs(got - true) / np.abs(true)) < 0.01
    assert np.max(np.abs(got.real / true.real - 1)) < 0.01
    assert np.max(np.abs(got.imag / true.imag - 1)) < 0.01
    # the residual against the data is the noise itself: σ √(1 − P/2N) = 0.48 % (P = 17)
    # (measured 0.42 %: the refined times absorb a little more of the scatter than P counts)
    assert 0.7 * 0.005 < fit.report.rms_error < 1.05 * 0.005
    assert fit.report.n_points == 97 and fit.material.n_branches == fit.report.terms_kept


def test_noise_free_series_is_recovered_to_solver_precision():
    # exact Prony data: the refined fit reproduces E(ω) to the optimiser's tolerance
    # (measured 4e-11)
    dma = dma_from_material(SBR, OMEGA)
    mat = fit_prony(dma)
    w = _dense(dma)
    err = np.abs(mat.complex_modulus(w) / SBR.complex_modulus(w) - 1)
    assert err.max() < 1e-6
    assert mat.equilibrium_modulus == pytest.approx(4.17, rel=1e-4)


def test_given_terms_and_plain_nnls():
    dma = dma_from_material(SBR, OMEGA, noise=0.005, seed=7)
    with pytest.warns(DMAWarning, match="rms residual .* with 4 terms"):
        few = fit_prony(dma, terms=4, report=True)     # 4 times over 12 decades: too few
    assert few.report.terms == 4 and few.material.n_branches <= 4
    assert few.report.rule.startswith("given")
    # a fixed grid at 2 per decade cannot place the loss peaks: NNLS alone is worse than the
    # refined fit on the same grid, but every modulus stays positive
    nnls = fit_prony(dma, terms=25, refine=False, report=True)
    refined = fit_prony(dma, terms=25, report=True)
    assert refined.report.rms_error < nnls.report.rms_error
    assert np.all(nnls.material.moduli > 0)


def test_rule_picks_fewer_terms_for_a_simpler_material():
    single = GeneralizedMaxwell(2.0, [10.0], [1e-3])
    dma = dma_from_material(single, 2 * np.pi * np.logspace(-1, 5, 49))
    mat = fit_prony(dma)
    assert mat.n_branches == 1
    assert mat.relaxation_times[0] == pytest.approx(1e-3, rel=1e-6)
    assert mat.moduli[0] == pytest.approx(10.0, rel=1e-6)


def test_fit_provenance_and_shift_law():
    dma = dma_from_material(SBR, OMEGA, noise=0.005, seed=7)
    dma = DMAData(dma.frequency, dma.storage, dma.loss, temperature=20.0,
                  shift=WLF(8.86, 101.6, 20.0), source="bench.csv")
    mat = fit_prony(dma)
    assert mat.shift == WLF(8.86, 101.6, 20.0)
    assert mat.provenance["source"] == "bench.csv"
    assert mat.provenance["reference_temperature"] == 20.0
    assert mat.provenance["fit"]["terms_kept"] == mat.n_branches
    assert GeneralizedMaxwell(**mat.as_dict()).as_dict() == mat.as_dict()


# --- too few points and non-physical data ------------------------------------------------------
def test_too_few_points():
    dma = dma_from_material(SBR, 2 * np.pi * np.logspace(0, 4, 6))
    with pytest.raises(InputError, match="too few for 8 terms"):
        fit_prony(dma, terms=8)
    fit_prony(dma, terms=5)                    # 6 frequencies, 11 unknowns for 12 values
    with pytest.raises(InputError, match="too few"):
        fit_prony(dma_from_material(SBR, [1.0, 10.0]))
    with pytest.raises(InputError, match="one frequency"):
        fit_prony(dma_from_material(SBR, [5.0, 5.0, 5.0]))


def test_falling_storage_modulus_warns():
    dma = dma_from_material(SBR, OMEGA, noise=0.01, seed=1)
    assert dma.physical_problems() == []          # 1 % scatter on a plateau is not a fall
    falling = DMAData(dma.frequency, dma.storage * np.where(OMEGA > 1e6, (OMEGA / 1e6)**-0.3,
                                                            1.0), dma.loss)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fit_prony(falling)
    messages = [str(w.message) for w in caught if issubclass(w.category, DMAWarning)]
    assert any("E' falls by" in m for m in messages)
    assert any("rms residual" in m for m in messages)     # and the fit cannot follow it


def test_negative_loss_modulus_is_an_error(tmp_path, sbr_rows):
    sbr_rows[5, 2] = -0.01
    f = _write(tmp_path / "neg.csv", "frequency [Hz],E' [MPa],E'' [MPa]", sbr_rows)
    with pytest.raises(InputError, match=r"neg.csv, line 7: column \"E''"):
        read_dma(f)


# --- reading: units and columns ----------------------------------------------------------------
def test_units_from_header_and_arguments_agree(tmp_path, sbr_rows):
    ref = read_dma(_write(tmp_path / "a.csv", "frequency [Hz],E_storage [MPa],E_loss [MPa]",
                          sbr_rows))
    pa = sbr_rows * [2 * np.pi, 1e6, 1e6]      # rad/s and Pa
    b = read_dma(_write(tmp_path / "b.csv", "omega,E' (Pa),E'' (Pa)", pa))
    c = read_dma(_write(tmp_path / "c.csv", "f,E',E''", sbr_rows), frequency_unit="Hz",
                 modulus_unit="MPa")
    for other in (b, c):
        np.testing.assert_allclose(other.frequency, ref.frequency, rtol=1e-11)
        np.testing.assert_allclose(other.storage, ref.storage, rtol=1e-11)
        np.testing.assert_allclose(other.loss, ref.loss, rtol=1e-11)
    np.testing.assert_allclose(ref.frequency, OMEGA, rtol=1e-11)
    assert b.provenance["modulus_unit"] == "Pa" and b.provenance["frequency_unit"] == "rad/s"


def test_shear_moduli_and_tan_delta(tmp_path, sbr_rows):
    g = sbr_rows / [1, 3, 3]
    shear = read_dma(_write(tmp_path / "g.csv", "freq [Hz],G' [MPa],G'' [MPa]", g))
    np.testing.assert_allclose(shear.storage, sbr_rows[:, 1], rtol=1e-11)   # E = 3 G
    assert "E = 3 G" in shear.provenance["conversion"]
    tan = np.column_stack([sbr_rows[:, :2], sbr_rows[:, 2] / sbr_rows[:, 1]])
    td = read_dma(_write(tmp_path / "t.csv", "frequency [Hz],E' [MPa],tan delta", tan))
    np.testing.assert_allclose(td.loss, sbr_rows[:, 2], rtol=1e-11)


@pytest.mark.parametrize("header, kwargs, message", [
    ("frequency,E' [MPa],E'' [MPa]", {}, r"column 'frequency' states no unit"),
    ("frequency [Hz],E',E''", {}, r"column \"E'\" states no unit"),
    ("frequency [Hz],E' [MPa],E'' [MPa]", {"modulus_unit": "Pa"}, r"is in MPa but"),
    ("frequency [Hz],E' [MPa],E'' [MPa]", {"frequency_unit": "rad/s"}, r"is in Hz but"),
    ("frequency [1/s],E' [MPa],E'' [MPa]", {}, r"unknown unit '1/s'"),
    ("frequency [Hz],E' [MPa],G'' [MPa]", {}, r"E and G cannot be mixed"),
    ("frequency [Hz],modulus [MPa],E'' [MPa]", {}, r"no storage modulus column"),
    ("Hz,E' [MPa],E'' [MPa]", {}, r"no frequency column"),
    ("frequency [Hz],E' [MPa],tan delta [MPa]", {}, r"tan δ is dimensionless"),
])
def test_unit_and_column_mistakes(tmp_path, sbr_rows, header, kwargs, message):
    f = _write(tmp_path / "bad.csv", header, sbr_rows)
    with pytest.raises(InputError, match=message) as err:
        read_dma(f, **kwargs)
    text = str(err.value)
    assert "\n" not in text and len(text) < 300 and "bad.csv" in text


def test_pascals_labelled_megapascals(tmp_path, sbr_rows):
    f = _write(tmp_path / "pa.csv", "frequency [Hz],E' [MPa],E'' [MPa]",
               sbr_rows * [1, 1e6, 1e6])
    with pytest.raises(InputError, match="stiffer than diamond"):
        read_dma(f)


def test_file_mistakes(tmp_path, sbr_rows):
    with pytest.raises(InputError, match="not found"):
        read_dma(tmp_path / "missing.csv")
    f = _write(tmp_path / "nohead.csv", "1,2,3", sbr_rows)
    with pytest.raises(InputError, match="add a header"):
        read_dma(f)
    text = "frequency [Hz],E' [MPa],E'' [MPa]\n1,4.2,0.1\n2,abc,0.2\n"
    (tmp_path / "nan.csv").write_text(text)
    with pytest.raises(InputError, match=r"nan.csv, line 3: column \"E' \[MPa\]\": 'abc' is not"):
        read_dma(tmp_path / "nan.csv")


# --- master curve from isotherms ---------------------------------------------------------------
def test_master_curve_recovers_wlf_and_the_series():
    # isotherms from -20 to 60 °C shifted with a known WLF, 0.1-100 Hz, 0.5 % noise (seed 3).
    # The pairwise shifts come from interpolating sweeps at 5 points per decade: noise-free
    # they are within 0.003 decades; with noise within 0.01. WLF C1, C2 from 9 shifts.
    law = WLF(8.86, 101.6, 20.0)
    temps = np.arange(-20.0, 61.0, 10.0)
    f = 2 * np.pi * np.logspace(-1, 2, 16)
    rng = np.random.default_rng(3)
    parts = []
    for t in temps:
        e = SBR.at_temperature(t, law).complex_modulus(f)
        parts.append((f, e.real * (1 + 0.005 * rng.standard_normal(f.size)),
                      e.imag * (1 + 0.005 * rng.standard_normal(f.size)), np.full(f.size, t)))
    w, e1, e2, tt = (np.concatenate(x) for x in zip(*parts, strict=True))
    dma = DMAData(w, e1, e2, temperature=20.0, temperatures=tt)
    with pytest.raises(InputError, match="master curve first"):
        fit_prony(dma)
    mc = master_curve(dma)
    np.testing.assert_allclose(mc.log10_shifts, law.log10_shift(temps), atol=0.01)
    assert mc.law.c1 == pytest.approx(8.86, rel=0.01)
    assert mc.law.c2 == pytest.approx(101.6, rel=0.01)
    mat = fit_prony(mc.data)
    assert mat.shift == mc.law
    wd = _dense(mc.data)
    # shifts off by <= 0.01 decade move E by <= 0.01 x its log-slope (<= 1) in log: ~2 %
    err = np.abs(mat.complex_modulus(wd) / SBR.complex_modulus(wd) - 1)
    assert err.max() < 0.02


# --- save and load -----------------------------------------------------------------------------
def test_toml_round_trip_is_exact(tmp_path):
    dma = dma_from_material(SBR, OMEGA, noise=0.005, seed=7)
    dma = DMAData(dma.frequency, dma.storage, dma.loss, shift=WLF(8.86, 101.6, 20.0),
                  source="x.csv")
    mat = fit_prony(dma)
    path = mat.to_toml(tmp_path / "fitted.toml")
    back = GeneralizedMaxwell.from_file(path)
    assert back == mat and back.as_dict() == mat.as_dict()
    assert back.name == mat.name and back.shift == mat.shift
    np.testing.assert_array_equal(back.relaxation_times, mat.relaxation_times)
    assert tomllib.loads(path.read_text())["shift"]["law"] == "WLF"
    # a plain series stays plain
    plain = SBR.to_toml(tmp_path / "sbr.toml")
    assert GeneralizedMaxwell.from_file(plain).as_dict() == SBR.as_dict()


def test_presets_as_dict_unchanged():
    # the cache keys of existing runs hash as_dict(): the paper's Table 1, written out here
    assert SBR.as_dict() == {
        "name": "SBR (Table 1)", "equilibrium_modulus": 4.17,
        "moduli": [1.72, 7.36, 70.98, 505.87, 1125.85, 1185.94],
        "relaxation_times": [1.134e-02, 2.628e-04, 1.316e-05, 1.295e-06, 7.708e-08, 4.2e-10]}
    assert GeneralizedMaxwell.elastic(5.0).as_dict() == {
        "name": "elastic", "equilibrium_modulus": 5.0, "moduli": [], "relaxation_times": []}
    assert hash(GeneralizedMaxwell(**SBR.as_dict())) == hash(SBR)


def test_provenance_is_read_only_plain_data():
    mat = GeneralizedMaxwell(1.0, [2.0], [1e-3], provenance={"a": [1, 2], "b": {"c": "d"}})
    with pytest.raises(TypeError):
        mat.provenance["a"] = 3
    assert mat.as_dict()["provenance"] == {"a": [1, 2], "b": {"c": "d"}}
    assert mat.as_dict(provenance=False).keys() == SBR.as_dict().keys()
    with pytest.raises(InputError, match="provenance.x"):
        GeneralizedMaxwell(1.0, provenance={"x": None})


# --- the shipped file and the CLI --------------------------------------------------------------
def test_shipped_file_fits_within_its_noise():
    # 1 % noise, 97 points: the fitted curve is within ~0.3 % rms of the Table 1 series
    # (measured max 0.5 %); 1 % bounds it
    dma = read_dma(EXAMPLES / "dma_synthetic_sbr.csv")
    assert dma.n_points == 97
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mat = fit_prony(dma)
    w = _dense(dma)
    assert np.max(np.abs(mat.complex_modulus(w) / SBR.complex_modulus(w) - 1)) < 0.01


def test_cli_fit_writes_toml_and_plot(tmp_path, capsys):
    out, png = tmp_path / "fit.toml", tmp_path / "fig" / "fit.png"
    code = main(["material", "fit", str(EXAMPLES / "dma_synthetic_sbr.csv"), "--temperature",
                 "20", "--wlf", "8.86,101.6", "-o", str(out), "--plot", str(png)])
    cap = capsys.readouterr()
    assert code == 0, cap.err
    assert "fit:" in cap.out and "tau_i [s]" in cap.out
    mat = GeneralizedMaxwell.from_file(out)
    assert mat.shift == WLF(8.86, 101.6, 20.0)
    assert mat.provenance["reference_temperature"] == 20.0
    assert png.stat().st_size > 10_000


def test_cli_fit_builds_master_curve(tmp_path, capsys):
    code = main(["material", "fit", str(EXAMPLES / "dma_synthetic_sbr_isotherms.csv"),
                 "--temperature", "20", "--json"])
    cap = capsys.readouterr()
    assert code == 0, cap.err
    import json

    record = json.loads(cap.out)
    assert record["material"]["shift"]["law"] == "WLF"
    assert record["material"]["shift"]["c1"] == pytest.approx(8.86, rel=0.02)


@pytest.mark.parametrize("args, message", [
    (["--frequency-unit", "rpm"], "unknown unit 'rpm'"),
    (["--wlf", "8.86"], "expected 'C1,C2'"),
    (["--terms", "500"], "too few for 500 terms"),
])
def test_cli_bad_input_exits_2_with_one_line(args, message, capsys):
    code = main(["material", "fit", str(EXAMPLES / "dma_synthetic_sbr.csv"),
                 "--temperature", "20", *args])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and err.startswith("error:") and message in err


# --- a config's [material] table ---------------------------------------------------------------
def test_load_material_from_spec():
    from rubbercontact.materials import load_material

    assert load_material({"preset": "sbr"}).as_dict() == SBR.as_dict()
    wlf = {"law": "WLF", "c1": 8.86, "c2": 101.6}
    mat = load_material({"dma": "dma_synthetic_sbr.csv", "reference_temperature": 20.0,
                         "shift": wlf}, base_dir=EXAMPLES)
    assert mat.shift == WLF(8.86, 101.6, 20.0)
    assert mat.provenance["reference_temperature"] == 20.0
    master = load_material({"dma": "dma_synthetic_sbr_isotherms.csv",
                            "reference_temperature": 20.0}, base_dir=EXAMPLES)
    assert master.shift.c1 == pytest.approx(8.86, rel=0.02)
    inline = load_material({"equilibrium_modulus": 2.0, "moduli": [1.0],
                            "relaxation_times": [1e-3], "shift": {**wlf, "t_ref": 0.0}})
    assert inline.at_temperature(10.0).relaxation_times[0] == pytest.approx(
        1e-3 * WLF(8.86, 101.6, 0.0).shift(10.0), rel=1e-14)
    for bad, message in (({"preset": "sbr", "dma": "x.csv"}, "exactly one"),
                         ({"preset": "sbr", "terms": 3}, "apply to 'dma' only"),
                         ({"preset": "sbr", "shift": wlf}, "give t_ref"),
                         ({"preset": "sbr", "colour": 1}, "unknown key")):
        with pytest.raises(InputError, match=message):
            load_material(bad)
