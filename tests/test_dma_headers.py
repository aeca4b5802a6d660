"""DMA files as instruments write them: headers, units, delimiters, decimal commas.

Every file is written here from the exact moduli of the SBR Prony series (closed form) in
the file's own units and layout; each read must give back those moduli in rad/s and MPa.
Numbers are written with 12 significant digits, so agreement is asked to ``rtol = 1e-10``
(a wrong unit factor is off by at least 2π, 3 or 10³).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.materials import read_dma

SBR = rc.materials.sbr()
HZ = np.logspace(-2, 6, 25)                 # the SBR's transition and both plateaus
OMEGA = 2 * np.pi * HZ
E = SBR.complex_modulus(OMEGA)
RTOL = 1e-10                                # 12 written digits (module docstring)


def _write(path: Path, lines: list[str], encoding: str = "utf-8") -> Path:
    path.write_text("\n".join(lines) + "\n", encoding=encoding)
    return path


def _rows(columns, sep: str = ",", decimal: str = ".") -> list[str]:
    return [sep.join(f"{v:.12g}".replace(".", decimal) for v in row)
            for row in zip(*columns, strict=True)]


def _same(dma, storage=E.real, loss=E.imag, omega=OMEGA):
    np.testing.assert_allclose(dma.frequency, omega, rtol=RTOL)
    np.testing.assert_allclose(dma.storage, storage, rtol=RTOL)
    np.testing.assert_allclose(dma.loss, loss, rtol=RTOL)


def test_the_plain_csv_with_units_as_suffixes(tmp_path):
    f = _write(tmp_path / "plain.csv",
               ["frequency_Hz,E_storage_MPa,E_loss_MPa", *_rows([HZ, E.real, E.imag])])
    _same(read_dma(f))
    _same(read_dma(f, frequency_unit="Hz"))     # the argument may repeat the header's unit
    with pytest.raises(InputError, match="is in Hz but frequency_unit='rad/s'"):
        read_dma(f, frequency_unit="rad/s")


def test_ta_trios_style_tabs_preamble_units_row_pascals_tan_delta(tmp_path):
    tan = E.imag / E.real
    lines = ["Filename\tsample_03.tri", "Instrument\tDMA 850", "",
             "[step]", "Frequency sweep (1)",
             "Angular frequency\tStorage modulus\tLoss modulus\tTan(delta)\tTemperature"
             "\tOscillation strain",
             "rad/s\tPa\tPa\t\t°C\t%",
             *_rows([OMEGA, 1e6 * E.real, 1e6 * E.imag, tan, np.full(HZ.size, 20.0),
                     np.full(HZ.size, 0.1)], sep="\t")]
    dma = read_dma(_write(tmp_path / "trios.txt", lines), modulus="E")
    _same(dma)
    assert dma.temperature == 20.0
    assert dma.provenance["delimiter"] == "tab" and dma.provenance["preamble_lines"] == 4
    assert dma.provenance["loss_column"] == "Loss modulus [Pa]"    # beats tan δ
    assert "Tan(delta)" in dma.provenance["ignored_columns"]


def test_netzsch_style_semicolons_decimal_comma_slash_units_tan_delta(tmp_path):
    lines = ["Frequency/Hz;E'/MPa;tan δ;Temp./°C",
             *_rows([HZ, E.real, E.imag / E.real, np.full(HZ.size, 23.0)], sep=";",
                    decimal=",")]
    dma = read_dma(_write(tmp_path / "netzsch.csv", lines))
    _same(dma)
    assert dma.provenance["decimal_comma"] and dma.provenance["delimiter"] == "semicolon"
    assert dma.temperature == 23.0


def test_anton_paar_style_shear_moduli_in_brackets_per_second_and_quotes(tmp_path):
    g = E / 3.0
    lines = ['"Angular Frequency [1/s]","Storage Modulus G\' [Pa]","Loss Modulus G\'\' [Pa]",'
             '"Loss Factor [1]"',
             *_rows([OMEGA, 1e6 * g.real, 1e6 * g.imag, g.imag / g.real])]
    dma = read_dma(_write(tmp_path / "rheo.csv", lines))
    _same(dma)                                  # E = 3 G at ν = 0.5
    assert "E = 3 G" in dma.provenance["conversion"]


def test_whitespace_columns_with_parenthesised_units(tmp_path):
    lines = ["Frequency (Hz)    E' (MPa)    E'' (MPa)    Temperature (K)",
             *_rows([HZ, E.real, E.imag, np.full(HZ.size, 293.15)], sep="   ")]
    dma = read_dma(_write(tmp_path / "cols.txt", lines))
    _same(dma)
    assert dma.temperature == pytest.approx(20.0, abs=1e-9)   # K → °C
    assert dma.provenance["delimiter"] == "whitespace"


def test_complex_modulus_with_tan_delta_gives_storage_and_loss(tmp_path):
    lines = ["f [Hz],|E*| [MPa],tan delta", *_rows([HZ, np.abs(E), E.imag / E.real])]
    _same(read_dma(_write(tmp_path / "cplx.csv", lines)))


def test_a_generic_storage_modulus_needs_e_or_g(tmp_path):
    lines = ["Frequency (Hz),Storage modulus (MPa),Loss modulus (MPa)",
             *_rows([HZ, E.real, E.imag])]
    f = _write(tmp_path / "generic.csv", lines)
    with pytest.raises(InputError, match="does not say E or G; pass modulus='E'"):
        read_dma(f)
    _same(read_dma(f, modulus="E"))
    # G with a stated Poisson ratio: E = 2 (1 + ν) G
    shear = read_dma(f, modulus="G", poisson_ratio=0.4)
    _same(shear, storage=2.8 * E.real, loss=2.8 * E.imag)
    assert "nu = 0.4: E = 2.8 G" in shear.provenance["conversion"]


def test_a_material_spec_passes_the_letter_on(tmp_path):
    lines = ["Frequency (Hz),Storage modulus (MPa),Loss modulus (MPa)",
             *_rows([HZ, E.real, E.imag])]
    _write(tmp_path / "generic.csv", lines)
    with pytest.raises(InputError, match="does not say E or G"):
        rc.materials.load_material({"dma": "generic.csv"}, base_dir=tmp_path)
    mat = rc.materials.load_material({"dma": "generic.csv", "modulus": "E"}, base_dir=tmp_path)
    # the fit's default tolerance is 1 % rms on exact data: 3 % bounds every point
    np.testing.assert_allclose(np.abs(mat.complex_modulus(OMEGA)), np.abs(E), rtol=0.03)
    with pytest.raises(InputError, match="apply to 'dma' only"):
        rc.materials.load_material({"preset": "sbr", "modulus": "G"})


@pytest.mark.parametrize("freq, fscale, mod, mscale", [
    ("Frequency (Hz)", 1 / (2 * np.pi), "Pa", 1e6),
    ("Frequency (kHz)", 1e-3 / (2 * np.pi), "kPa", 1e3),
    ("Angular frequency (rad/s)", 1.0, "GPa", 1e-3),
    ("omega", 1.0, "N/mm2", 1.0),               # ω without a unit is rad/s
])
def test_unit_conversions_against_the_same_data_in_base_units(tmp_path, freq, fscale, mod,
                                                              mscale):
    base = read_dma(_write(tmp_path / "base.csv", ["omega [rad/s],E' [MPa],E'' [MPa]",
                                                   *_rows([OMEGA, E.real, E.imag])]))
    other = read_dma(_write(tmp_path / "other.csv",
                            [f"{freq},E' [{mod}],E'' [{mod}]",
                             *_rows([OMEGA * fscale, E.real * mscale, E.imag * mscale])]))
    _same(other, base.storage, base.loss, base.frequency)


def test_storage_and_loss_in_different_units_are_each_converted(tmp_path):
    lines = ["f [Hz],E' [MPa],E'' [kPa]", *_rows([HZ, E.real, 1e3 * E.imag])]
    _same(read_dma(_write(tmp_path / "mixed.csv", lines)))


def test_omega_and_frequency_together_must_agree(tmp_path):
    good = ["Frequency (Hz),Angular frequency (rad/s),E' (MPa),E'' (MPa)",
            *_rows([HZ, OMEGA, E.real, E.imag])]
    dma = read_dma(_write(tmp_path / "both.csv", good))
    _same(dma)
    assert dma.provenance["frequency_column"] == "Angular frequency (rad/s)"
    bad = ["Frequency (Hz),Angular frequency (rad/s),E' (MPa),E'' (MPa)",
           *_rows([OMEGA, OMEGA, E.real, E.imag])]          # the Hz column holds rad/s
    with pytest.raises(InputError, match=r"line 2: columns .* disagree"):
        read_dma(_write(tmp_path / "clash.csv", bad))


def test_windows_encodings(tmp_path):
    lines = ["Frequency (Hz);E' (MPa);E'' (MPa);Temperature (°C)",
             *_rows([HZ, E.real, E.imag, np.full(HZ.size, -10.0)], sep=";", decimal=",")]
    for enc in ("cp1252", "utf-16"):
        dma = read_dma(_write(tmp_path / f"{enc}.csv", lines, encoding=enc))
        _same(dma)
        assert dma.temperature == -10.0


ROWS = _rows([HZ, E.real, E.imag])


@pytest.mark.parametrize("lines, kwargs, message", [
    (["Frequency (Hz),Stress (MPa),Strain (%)", *ROWS], {},
     r"no storage modulus column .* in the header \['Frequency \(Hz\)', 'Stress"),
    (["Frequency (Hz),Storage (MPa),Loss (MPa)", *ROWS], {}, r"'Storage \(MPa\)' does not "
     r"say E or G; pass modulus='E' \(tensile/bending DMA\) or modulus='G' \(shear\)"),
    (["Time (s),E' (MPa),E'' (MPa)", *ROWS], {}, r"no frequency column in the header"),
    (["Frequency (Hz),E' (MPa),Phase angle (°)", *ROWS], {},
     r"no E'' or tan δ column beside \"E' \(MPa\)\""),
    (["Frequency (Hz),|E*| (MPa),E'' (MPa)", *ROWS], {}, r"no tan δ column beside"),
    (["Frequency (Hz),E' (psi),E'' (psi)", *ROWS], {}, r"unknown unit 'psi'"),
    (["Frequency (1/s),E' (MPa),E'' (MPa)", *ROWS], {}, r"unknown unit '1/s'"),
    (["f (Hz),E' (MPa),E'' (MPa),T", *_rows([HZ, E.real, E.imag, HZ])], {},
     r"column 'T' states no unit"),
    (["f (Hz),E' (MPa),E'' (MPa)"], {}, r"no data rows below the header"),
    (["Frequency (Hz) E' (MPa) E'' (MPa)", *_rows([HZ, E.real, E.imag], sep=" ")], {},
     r"line 1: 1 column name\(s\) over 3 columns of numbers; separate the names by tabs"),
    (["f (Hz),E' (MPa),E'' (MPa)", "1,abc,2", *ROWS], {},
     r"line 2: '1,abc,2' is neither column names nor numbers"),
    (["Sample: SBR", "Operator: x"], {}, r"no line of numbers found"),
    (["f (Hz),E' (MPa),E'' (MPa)", *ROWS], {"modulus": "K"}, r"modulus: expected 'E' or"),
    (["f (Hz),G' (MPa),G'' (MPa)", *ROWS], {"poisson_ratio": 0.7}, r"poisson_ratio: must"),
    (["f (Hz),E' (MPa),E (MPa) storage", *ROWS], {}, r"no E'' or tan δ column"),
])
def test_bad_files_give_one_clear_line(tmp_path, lines, kwargs, message):
    f = _write(tmp_path / "bad.csv", lines)
    with pytest.raises(InputError, match=message) as err:
        read_dma(f, **kwargs)
    text = str(err.value)
    assert "\n" not in text and len(text) < 300


def test_a_binary_file_is_refused(tmp_path):
    f = tmp_path / "dma.xlsx"
    f.write_bytes(b"PK\x03\x04\x00\x00binary")
    with pytest.raises(InputError, match="not a text file"):
        read_dma(f)
