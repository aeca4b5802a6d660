"""Steadiness diagnostics of the FEM sliding tests behind a law or a results table.

The variables kept per test (:data:`STEADINESS_VARIABLES`) and the warnings that name the
tests that did not reach steady sliding, slid too briefly for the bulk to stop creeping,
or sheared as a whole.
"""

from __future__ import annotations

import numpy as np

from ..fem.result import BULK_SHEAR_LIMIT, BULK_SHEAR_STUDY
from ..materials import GeneralizedMaxwell

#: Diagnostics of an FEM sliding test (steadiness, shear, impalement) kept in the law and
#: results tables.
STEADINESS_VARIABLES = {
    "steady": "successive sliding periods agreed within the steadiness tolerance "
              "(1/0; NaN: failed or not recorded)",
    "period_change": "relative change of the friction over the last sliding period",
    "period_area_change": "relative change of the contact fraction over the last sliding "
                          "period",
    "sliding_time": "sliding time of the test (NaN: not recorded)",
    "bulk_shear": "mean shear strain of the cell at the end of the test, |mean face "
                  "x-displacement| / H (NaN: not recorded)",
    "impaled": "the surface passed through the rubber face between nodes, so friction and "
               "contact fraction are not meaningful (1/0; NaN: failed or not recorded)",
    "patch_columns": "narrowest contact patch in columns of the mesh (inf: no patch edge; "
                     "NaN: not measured)",
    "under_resolved": "narrowest contact patch below FemOptions.patch_columns columns (1/0; "
                      "NaN: not measured)",
    "refined": "the automatic mesh was refined once (nx doubled) by the resolution check "
               "(1/0; NaN: not recorded)",
}
#: Units of ``STEADINESS_VARIABLES`` other than "1".
STEADINESS_UNITS = {"sliding_time": "s"}
#: Sliding, in longest retardation times, below which a test is called creep-unsettled.
CREEP_SETTLED_TIMES = 3.0


def creep_unsettled_message(diag: dict, material: GeneralizedMaxwell, label, what: str,
                            times: float = CREEP_SETTLED_TIMES) -> str | None:
    """One warning naming the FEM tests of ``diag`` that slid less than ``times`` longest
    retardation times of ``material`` (shortest first, at most 6 named), or None.

    The period rule (two successive period averages within 1 %) can pass while the cell
    still creeps in shear under the friction stress on that time, which is slower than a
    period at high speed (docs/validation/creep_settled.md). Tests whose sliding time was
    not recorded (NaN) or that did not slide (0) are not counted; an elastic material does
    not creep.
    """
    lam = material.retardation_times()
    t = np.asarray(diag.get("sliding_time", np.nan), float)
    if lam.size == 0 or not np.any(np.isfinite(t)):
        return None
    short = sorted(map(tuple, np.argwhere(np.isfinite(t) & (t > 0) & (t < times * lam.max()))),
                   key=lambda idx: t[idx])
    if not short:
        return None
    where = ", ".join(f"{label(*idx)} ({1e3 * t[idx]:.1f} ms)" for idx in short[:6])
    ran = int(np.isfinite(t).sum())
    return (f"{what}: {len(short)} of {ran} time-stepped FEM tests (fem.solver = "
            f"'transient', or fallbacks of the steady solver) slid less than {times:g} "
            f"retardation times ({1e3 * lam.max():.1f} ms), shortest first: {where}"
            f"{', ...' if len(short) > 6 else ''}; the bulk may still creep although periods "
            f"agree: fem.min_creep_times slides them longer (docs/validation/creep_settled.md)")


def sheared_cells_message(diag: dict, label, what: str,
                          limit: float = BULK_SHEAR_LIMIT) -> str | None:
    """One warning naming the FEM tests of ``diag`` whose cell sheared as a whole by more
    than ``limit`` (largest first, at most 6 named), or None.

    Under a friction stress above the relaxed shear modulus the cell's bulk shear exceeds
    1, it creeps for several retardation times, and until it has settled the result
    depends on the cell height, which the paper fixes at H/L0 = 0.75
    (docs/validation/cell_creep.md). Tests cached before the shear was recorded (NaN) are
    not counted.
    """
    g = np.asarray(diag.get("bulk_shear", np.nan), float)
    big = sorted(map(tuple, np.argwhere(np.isfinite(g) & (g > limit))), key=lambda i: -g[i])
    if not big:
        return None
    where = ", ".join(f"{label(*idx)} ({g[idx]:.2f})" for idx in big[:6])
    return (f"{what}: {len(big)} of {int(np.isfinite(g).sum())} FEM tests sheared as a whole "
            f"by more than {limit:g} (mean face displacement / cell height), largest first: "
            f"{where}{', ...' if len(big) > 6 else ''}: the friction stress exceeds E∞/3 there "
            f"({BULK_SHEAR_STUDY})")


def impaled_tests(diag: dict, label) -> tuple[int, str]:
    """The FEM tests of ``diag`` whose rubber face was impaled: their number and
    ``"label; label; ..."`` (at most 6 named). Tests cached before the flag (NaN) are not
    counted."""
    hit = [tuple(i) for i in np.argwhere(np.asarray(diag.get("impaled", np.nan)) == 1.0)]
    where = "; ".join(label(*idx) for idx in hit[:6]) + ("; ..." if len(hit) > 6 else "")
    return len(hit), where


def describe_unsteady(diag: dict, label) -> tuple[int, str, bool]:
    """The FEM tests of ``diag`` (arrays of ``STEADINESS_VARIABLES``) that were not steady.

    Returns their number, ``"label (μ 1.2 %, A 7.0 %), ..."`` with ``label(*index)`` naming
    each and its changes over the last period where recorded, and whether any was recorded
    (results cached before the changes existed have only the flag).
    """
    items, recorded = [], False
    bad = np.argwhere(diag["steady"] == 0)
    for idx in map(tuple, bad):
        parts = [f"{name} {100 * diag[k][idx]:.1f} %"
                 for name, k in (("μ", "period_change"), ("A", "period_area_change"))
                 if np.isfinite(diag[k][idx])]
        recorded |= bool(parts)
        items.append(label(*idx) + (f" ({', '.join(parts)})" if parts else ""))
    return len(bad), ", ".join(items), recorded
