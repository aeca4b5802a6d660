"""Prony fit of DMA data: rubbercontact's fit_prony against pyvisco, on the shipped file.

    python benchmarks/bench_prony_fit.py [--pyvisco-python /path/to/venv/bin/python]

Both fit ``examples/data/dma_synthetic_sbr.csv`` (Table 1's SBR with 1 % noise); each
fitted E(ω) is compared with the exact Table 1 series over the data's range (max and rms
of ``|E_fit − E|/|E|``, and of E'' alone), with the wall time of the fit. pyvisco
(PyPI) is not a dependency: it runs in a separate interpreter, a throwaway venv with
``pip install pyvisco`` (its notebook dependencies are not needed for this:
``pip install --no-deps pyvisco numpy scipy pandas matplotlib`` suffices); without
``--pyvisco-python`` only rubbercontact's row is printed.

pyvisco's frequency-domain fit (``opt=True``) minimises the residual of ``E'/E_0`` and
``E''/E_0`` (absolute, normalised by the glassy modulus) on 1 time per decade, so its
relative error is largest in the rubbery decades where E'' is small; fit_prony weights each
datum relatively and refines the times.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import rubbercontact as rc

DATA = Path(__file__).resolve().parents[1] / "examples" / "data" / "dma_synthetic_sbr.csv"

_PYVISCO = r"""
import json, sys, time
from pyvisco import load, master, prony
t0 = time.perf_counter()
df_master, units = load.user_master(load.file(sys.argv[1]), "freq", 20.0, "E")
df_master = master.smooth(df_master, 1)     # window 1: no filtering
df_dis = prony.discretize(df_master)
fit, _ = prony.fit(df_dis, df_master, opt=True)
terms = fit["df_terms"]
print(json.dumps({"E_0": float(fit["E_0"]), "alpha": terms["alpha_i"].tolist(),
                  "tau": terms["tau_i"].tolist(), "time": time.perf_counter() - t0}))
"""


def _errors(mat, w):
    true = rc.materials.sbr().complex_modulus(w)
    got = mat.complex_modulus(w)
    rel = np.abs(got - true) / np.abs(true)
    loss = np.abs(got.imag / true.imag - 1)
    return rel.max(), np.sqrt(np.mean(rel**2)), loss.max()


def run_pyvisco(python: str, dma) -> tuple[rc.materials.GeneralizedMaxwell, float]:
    with tempfile.TemporaryDirectory() as tmp:
        csv = Path(tmp) / "master.csv"
        f = dma.frequency / (2 * np.pi)
        rows = "\n".join(f"{a:.10g},{b:.10g},{c:.10g}" for a, b, c in
                         zip(f, dma.storage, dma.loss, strict=True))
        csv.write_text("f,E_stor,E_loss\nHz,MPa,MPa\n" + rows + "\n")
        script = Path(tmp) / "fit.py"
        script.write_text(_PYVISCO)
        out = subprocess.run([python, str(script), str(csv)], capture_output=True, text=True,
                             check=True)
    res = json.loads(out.stdout.strip().splitlines()[-1])
    alpha, tau = np.array(res["alpha"]), np.array(res["tau"])
    keep = alpha > 0
    mat = rc.materials.GeneralizedMaxwell(res["E_0"] * (1 - alpha.sum()),
                                          res["E_0"] * alpha[keep], tau[keep], name="pyvisco")
    return mat, res["time"]


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pyvisco-python", help="interpreter of a venv with pyvisco installed")
    args = ap.parse_args(argv)
    dma = rc.materials.read_dma(DATA)
    w = np.geomspace(dma.frequency.min(), dma.frequency.max(), 2000)
    rows = []
    t0 = time.perf_counter()
    fit = rc.materials.fit_prony(dma, report=True)
    rows.append(("rubbercontact fit_prony", fit.material, time.perf_counter() - t0))
    t0 = time.perf_counter()
    nnls = rc.materials.fit_prony(dma, terms=25, refine=False, report=True)
    rows.append(("rubbercontact NNLS only, 2/decade", nnls.material, time.perf_counter() - t0))
    if args.pyvisco_python:
        mat, seconds = run_pyvisco(args.pyvisco_python, dma)
        rows.append(("pyvisco (discretize + fit, opt=True)", mat, seconds))
    print(f"{DATA.name}: {dma.n_points} points, 1e-3 to 1e9 Hz, 1 % noise; errors against "
          f"Table 1 over the data range")
    loss_head = "max E'' err"
    print(f"{'method':40s} {'branches':>8s} {'max |dE|/|E|':>13s} {'rms':>8s} "
          f"{loss_head:>12s} {'time [s]':>9s}")
    for label, mat, seconds in rows:
        mx, rms, loss = _errors(mat, w)
        print(f"{label:40s} {mat.n_branches:8d} {100 * mx:12.2f}% {100 * rms:7.2f}% "
              f"{100 * loss:11.2f}% {seconds:9.3f}")


if __name__ == "__main__":
    main()
