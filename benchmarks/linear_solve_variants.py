"""Variants of the FEM's sparse linear solve, on tangents captured from a real sliding test.

Captures the first ``--captures`` Newton systems ``K dU = −r`` of the section 3 full FEM
(realization seed 2021, 0.35 MPa, 10 mm/s, 120 x 90 graded x4, 240 steps per period), drops
the press and settle phase (``--skip``), and times on the same systems:

1. the solver's own path: factorize every tangent (SuperLU, symmetric mode, MMD on A + Aᵀ);
2. keep one factorization and run CG preconditioned by it, refactorizing when CG needs more
   than ``maxit`` iterations (modified Newton with a Krylov correction);
3. optional, if installed: METIS nested dissection (``pymetis``) + SuperLU on the permuted
   matrix, and ``qdldl`` (LDLᵀ with AMD ordering).

Results in ``benchmarks/fem.md`` ("What did not make the linear solve cheaper"). Run::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/linear_solve_variants.py
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import rubbercontact as rc
import rubbercontact.fem.solver as fem_solver


class _Captured(Exception):
    pass


def capture(n: int) -> list[tuple[sp.csr_matrix, np.ndarray]]:
    """The first ``n`` (tangent, residual) pairs the Newton solver factorizes and solves."""
    systems = []
    original = fem_solver.factorize

    class Recorder:
        def __init__(self, K):
            self.K, self.factor = K.copy(), original(K)

        def solve(self, r):
            systems.append((self.K, r.copy()))
            if len(systems) >= n:
                raise _Captured
            return self.factor.solve(r)

    fem_solver.factorize = Recorder
    try:
        surf = rc.roughness.section3().realizations(1, seed=2021)[0]
        rc.fem.sliding_test(surf, rc.materials.sbr(), 0.35, 10.0, mesh=(120, 90),
                            grading=4.0, periods=2, steps_per_period=240, solver="transient")
    except _Captured:
        pass
    finally:
        fem_solver.factorize = original
    return systems


def direct(systems) -> tuple[float, list[np.ndarray]]:
    t0 = time.perf_counter()
    out = [fem_solver.factorize(K).solve(r) for K, r in systems]
    return time.perf_counter() - t0, out


def stale_factor_cg(systems, reference, maxit: int) -> dict:
    factor, factorizations, its, errors = None, 0, [], []
    t0 = time.perf_counter()
    for (K, r), x_ref in zip(systems, reference, strict=True):
        x = None
        if factor is not None:
            history: list[int] = []
            M = spla.LinearOperator(K.shape, matvec=factor.lu.solve)
            x, info = spla.cg(K, r, rtol=1e-9, maxiter=maxit, M=M,
                              callback=lambda _x, h=history: h.append(1))
            if info == 0:
                its.append(len(history))
            else:
                x = None
        if x is None:
            factor, factorizations = fem_solver.factorize(K), factorizations + 1
            x = factor.solve(r)
        errors.append(np.linalg.norm(x - x_ref) / np.linalg.norm(x_ref))
    return {"time": time.perf_counter() - t0, "factorizations": factorizations,
            "cg_iterations": float(np.mean(its)) if its else 0.0, "max_error": max(errors)}


def optional_orderings(K: sp.csr_matrix) -> list[str]:
    lines = []
    try:
        import pymetis
    except ImportError:
        lines.append("pymetis not installed: nested dissection skipped")
    else:
        G = (K != 0).astype(np.int8).tocsr()
        G.setdiag(0)
        G.eliminate_zeros()
        adj = [G.indices[G.indptr[i]:G.indptr[i + 1]] for i in range(K.shape[0])]
        perm = np.asarray(pymetis.nested_dissection(adjacency=adj)[0])
        Kp = sp.csc_matrix(K[perm][:, perm])
        ts = []
        for _ in range(5):
            t0 = time.perf_counter()
            lu = spla.splu(Kp, permc_spec="NATURAL", diag_pivot_thresh=0.0,
                           options={"SymmetricMode": True})
            ts.append(time.perf_counter() - t0)
        lines.append(f"METIS ND + SuperLU: {1e3 * np.median(ts):.0f} ms per factorization, "
                     f"nnz(L+U) = {lu.L.nnz + lu.U.nnz}")
    try:
        import qdldl
    except ImportError:
        lines.append("qdldl not installed: skipped")
    else:
        Kc = K.tocsc()
        solver = qdldl.Solver(Kc)
        ts = []
        for _ in range(5):
            t0 = time.perf_counter()
            solver.update(Kc)
            ts.append(time.perf_counter() - t0)
        lines.append(f"qdldl: {1e3 * np.median(ts):.0f} ms per refactorization")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--captures", type=int, default=400)
    ap.add_argument("--skip", type=int, default=100, help="press and settle systems to drop")
    args = ap.parse_args(argv)
    systems = capture(args.captures)[args.skip:]
    t_direct, reference = direct(systems)
    print(f"{len(systems)} systems, {reference[0].size} unknowns")
    print(f"factorize every tangent: {t_direct:.2f} s "
          f"({1e3 * t_direct / len(systems):.1f} ms each)")
    for maxit in (5, 10, 20, 40):
        r = stale_factor_cg(systems, reference, maxit)
        print(f"stale factor + CG, refactorize beyond {maxit} iterations: {r['time']:.2f} s, "
              f"{r['factorizations']} factorizations, {r['cg_iterations']:.1f} CG iterations "
              f"on average, max relative difference {r['max_error']:.1e}")
    for line in optional_orderings(systems[len(systems) // 2][0].tocsr()):
        print(line)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
