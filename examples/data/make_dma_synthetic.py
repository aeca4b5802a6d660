"""Write the synthetic DMA files of this folder from the paper's SBR Prony series (Table 1).

    python examples/data/make_dma_synthetic.py

* dma_synthetic_sbr.csv: a master curve, 1e-3 to 1e9 Hz, 8 points per decade (97 points),
  E' and E'' of ``rc.materials.sbr()`` each times an independent ``1 + 0.01 N(0, 1)``
  (1 % multiplicative Gaussian noise), numpy seed 20240527.
* dma_synthetic_sbr_isotherms.csv: isothermal sweeps 0.1 to 100 Hz, 5 points per decade
  (16 points), at -20, -10, ..., 60 °C, made by shifting the same series with
  WLF C1 = 8.86, C2 = 101.6 K referred to 20 °C (the "universal" constants, chosen for
  illustration: Table 1 states no temperature), same noise, seed 20240528.
"""

from pathlib import Path

import numpy as np

import rubbercontact as rc

HERE = Path(__file__).resolve().parent
NOISE = 0.01
WLF = rc.materials.WLF(c1=8.86, c2=101.6, t_ref=20.0)


def master(path: Path) -> None:
    f = np.logspace(-3, 9, 97)
    dma = rc.materials.dma_from_material(rc.materials.sbr(), 2 * np.pi * f, noise=NOISE,
                                         seed=20240527)
    dma.to_csv(path, frequency_unit="Hz", modulus_unit="MPa", header=(
        "Synthetic DMA master curve of the SBR of Table 1 (rc.materials.sbr()),\n"
        "1 % multiplicative Gaussian noise on E' and E'', seed 20240527;\n"
        "written by make_dma_synthetic.py. Young's moduli."))


def isotherms(path: Path) -> None:
    f = np.logspace(-1, 2, 16)
    rng = np.random.default_rng(20240528)
    temps = np.arange(-20.0, 61.0, 10.0)
    rows = []
    for t in temps:
        e = rc.materials.sbr().at_temperature(t, WLF).complex_modulus(2 * np.pi * f)
        e1 = e.real * (1 + NOISE * rng.standard_normal(f.size))
        e2 = e.imag * (1 + NOISE * rng.standard_normal(f.size))
        rows += [f"{t:g},{fi:.10g},{a:.10g},{b:.10g}" for fi, a, b in zip(f, e1, e2,
                                                                         strict=True)]
    header = ("# Synthetic isothermal DMA sweeps of the SBR of Table 1, shifted with WLF\n"
              "# C1 = 8.86, C2 = 101.6 K, T_ref = 20 °C; 1 % noise, seed 20240528;\n"
              "# written by make_dma_synthetic.py. Young's moduli.\n"
              "temperature [°C],frequency [Hz],E_storage [MPa],E_loss [MPa]\n")
    path.write_text(header + "\n".join(rows) + "\n", encoding="utf-8")


if __name__ == "__main__":
    master(HERE / "dma_synthetic_sbr.csv")
    isotherms(HERE / "dma_synthetic_sbr_isotherms.csv")
