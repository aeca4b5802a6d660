"""How well does the FEM resolve a small contact area? Against closed forms and the VHS.

Eq. 28 compares the models at equal contact area, and at the smallest areas of paper §3
(A ≈ 0.01: 3 µm of contact in a 0.25 mm cell) a few per cent of area move the comparison
by several points (``fem_reference_mesh.py``). This study measures the FEM's contact
fraction against references that are exact or converged, as a function of the element
width ``h`` over the contact half-width ``a``:

1. **Static, elastic, small slope** against Westergaard's closed form
   ``p̄/p_full = sin²(πa/λ)``: the contact edge falls anywhere within an element, so each
   mesh is run at three offsets of the sine against the nodes (0, 1/4, 1/2 element).
2. **Steady viscoelastic sliding, small slope** (m2 = 0.25, where the FEM and the VHS
   agree within 1 % in friction; ``slope_nonlinearity.py``) against the VHS at n = 8192,
   whose area is converged: the viscoelastic contact is asymmetric (a sharp leading edge, a
   slowly opening trailing gap), which the static case does not test.
3. **Sensitivity of the estimator** to the contact penalty (``penalty_factor`` 100, the
   default, and 1000) and to its threshold: contact is counted where the gap is below
   ``c`` times the local chord sag, ``c = 1`` in the package. Inside a contact on a crest
   a straight segment touches near its middle and its nodes lift off by about one sag, so
   ``c = 1`` sits on the edge of that classification. The variants are computed from the
   same solves by wrapping ``fem.transient.face_contact_fraction`` here (the package is not
   changed).

Cases run with ``--contact-points`` per face segment (default 4, the package's and the
validation's); the report lists every finished case with its count. Each case appends one
JSON line to ``--out`` when it finishes; finished cases are skipped on
a rerun (resumable). Run (about 30 min on one core)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies contact_area_resolution \
        --out docs/validation/contact_area_resolution.jsonl \
        --report docs/validation/contact_area_resolution.md
"""

from __future__ import annotations

import argparse
import inspect
import subprocess
import time
import warnings
from datetime import UTC, datetime
from fractions import Fraction
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.fem import transient as fem_sliding
from rubbercontact.fem.contact import contact_fraction

from ._rows import append_row, read_rows
from ._templates import render

DESCRIPTION = ("How well does the FEM resolve a small "
               "contact area? Against closed forms and the VHS.")

# Westergaard: unit wavelength, small slope (m2 = 0.044), elastic
W_E, W_LAM, W_AMP = 4.0, 1.0, 0.01
W_FRACTION = 0.04                    # 2a/λ
W_NX = (25, 50, 100, 200, 400)
OFFSETS = (0.0, 0.25, 0.5)           # of an element
# sliding: the paper's high-slope wavelength at m2 = 0.25, SBR, 50 mm/s
S_LAM, S_M2, S_VELOCITY = 0.0625, 0.25, 50.0
S_PRESSURE = 0.06                    # [MPa]: A_VHS ≈ 0.03, a ≈ 0.9 µm
S_NX = (60, 120, 240, 480)
# estimator sensitivity: sag multiples c of the contact threshold, penalties, meshes
SAG_FACTORS = (1.0, 1.5, 2.0)          # the first is the package's
PENALTIES = (100.0, 1000.0)
T_STATIC_NX = (100, 200, 400)
T_SLIDING_NX = (60, 120, 240)
GRADING = 4.0                        # rows graded toward the face
VHS_N = 8192                         # grid of the converged VHS reference


def _with_threshold_variants(run):
    """Run ``run()`` recording, at every step, the contact fraction for each ``c``.

    Returns ``(result, {c: mean over the result's averaging window})``: the window is the
    trailing run of steps whose mean is the result's own contact fraction (``c = 1``).
    """
    original = fem_sliding.face_contact_fraction
    record: dict[float, list[float]] = {c: [] for c in SAG_FACTORS}

    def variants(surface, shift, cs, width):
        m = cs.points_per_segment
        x = cs.point_x
        dx = np.diff(np.append(x[::m], x[0] + width))
        sag = np.repeat(dx, m) ** 2 * np.abs(surface.curvatures(x + shift)) / 8.0
        for c in SAG_FACTORS:
            record[c].append(contact_fraction(x, cs.gap - c * sag, width))
        return original(surface, shift, cs, width)

    fem_sliding.face_contact_fraction = variants
    try:
        out = run()
    finally:
        fem_sliding.face_contact_fraction = original
    history = np.asarray(out.history["contact_fraction"])
    for w in range(1, history.size + 1):
        if abs(history[-w:].mean() - out.contact_fraction) <= 1e-12:
            return out, {c: float(np.mean(record[c][-w:])) for c in SAG_FACTORS}
    raise RuntimeError("could not locate the averaging window of the contact fraction")


def threshold_case(kind: str, nx: int, penalty: float, m: int) -> dict:
    if kind == "threshold-static":
        p_full = np.pi * (4 * W_E / 3) * W_AMP / W_LAM
        pbar = p_full * np.sin(np.pi * W_FRACTION / 2) ** 2
        areas = {}
        for offset in OFFSETS:
            surf = rc.roughness.SineSeries(
                [W_LAM], [W_AMP], [np.pi / 2 + 2 * np.pi * offset / nx])
            _, a = _with_threshold_variants(lambda s=surf: rc.fem.sliding_test(
                s, rc.materials.GeneralizedMaxwell.elastic(W_E), pbar, 0.0, mesh=(nx, 45),
                grading=GRADING, contact_points=m, penalty_factor=penalty, solver="transient"))
            areas[str(offset)] = {str(c): v for c, v in a.items()}
        return {"case": kind, "nx": nx, "offset": penalty, "penalty": penalty,
                "contact_points": m,
                "reference": W_FRACTION, "areas": areas,
                "h_over_a": W_LAM / nx / (W_FRACTION * W_LAM / 2)}
    amp = S_M2 * np.sqrt(2) * S_LAM / (2 * np.pi)
    surf = rc.roughness.SineSeries([S_LAM], [amp])
    mat = rc.materials.sbr()
    vhs = rc.halfspace.solve_sliding(surf, None, mat, S_VELOCITY, S_PRESSURE, n=VHS_N)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out, a = _with_threshold_variants(lambda: rc.fem.sliding_test(
            surf, mat, S_PRESSURE, S_VELOCITY, mesh=(nx, 45), grading=GRADING, contact_points=m,
            periods=4, penalty_factor=penalty, solver="transient"))
    return {"case": kind, "nx": nx, "offset": penalty, "penalty": penalty,
            "contact_points": m,
            "reference": vhs.contact_fraction, "areas": {"0": {str(c): v for c, v in a.items()}},
            "fem_friction": out.friction, "vhs_friction": vhs.friction,
            "h_over_a": S_LAM / nx / (vhs.contact_fraction * S_LAM / 2)}


def westergaard_case(nx: int, offset: float, m: int) -> dict:
    p_full = np.pi * (4 * W_E / 3) * W_AMP / W_LAM
    a = W_FRACTION * W_LAM / 2
    pbar = p_full * np.sin(np.pi * a / W_LAM) ** 2
    h = W_LAM / nx
    surf = rc.roughness.SineSeries([W_LAM], [W_AMP], [np.pi / 2 + 2 * np.pi * offset * h / W_LAM])
    t0 = time.perf_counter()
    out = rc.fem.sliding_test(surf, rc.materials.GeneralizedMaxwell.elastic(W_E), pbar, 0.0,
                              mesh=(nx, 45), grading=GRADING, contact_points=m, solver="transient")
    return {"case": "westergaard", "nx": nx, "offset": offset, "h_over_a": h / a,
            "contact_points": m,
            "reference": W_FRACTION, "fem": out.contact_fraction,
            "wall_s": time.perf_counter() - t0}


def sliding_case(nx: int, m: int) -> dict:
    amp = S_M2 * np.sqrt(2) * S_LAM / (2 * np.pi)
    surf = rc.roughness.SineSeries([S_LAM], [amp])
    mat = rc.materials.sbr()
    vhs = rc.halfspace.solve_sliding(surf, None, mat, S_VELOCITY, S_PRESSURE, n=VHS_N)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fem = rc.fem.sliding_test(surf, mat, S_PRESSURE, S_VELOCITY, mesh=(nx, 45),
                                  grading=GRADING, contact_points=m, periods=4, solver="transient")
    a = vhs.contact_fraction * S_LAM / 2
    return {"case": "sliding", "nx": nx, "offset": 0.0, "h_over_a": S_LAM / nx / a,
            "contact_points": m,
            "reference": vhs.contact_fraction, "fem": fem.contact_fraction,
            "fem_friction": fem.friction, "vhs_friction": vhs.friction,
            "steady": bool(fem.stats.steady), "wall_s": time.perf_counter() - t0}


def report(rows: list[dict]) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    default_points = inspect.signature(rc.fem.sliding_test).parameters["contact_points"]
    out = [render("contact_area_resolution", "title"), "",
           render("contact_area_resolution", "intro", date=f"{datetime.now(UTC):%Y-%m-%d %H:%M}",
                  commit=commit, default_points=default_points.default,
                  grading=f"{GRADING:g}"), "",
           render("contact_area_resolution", "westergaard", fraction=f"{W_FRACTION:g}",
                  m2=f"{W_AMP * 2 * np.pi / W_LAM / np.sqrt(2):.3f}"), "",
           "| m | nx | h/a | " + " | ".join(f"A/A_W, offset {o:g} h" for o in OFFSETS)
           + " | largest error [elements] |", "|---|---|---|" + "---|" * len(OFFSETS) + "---|"]
    west = [r for r in rows if r["case"] == "westergaard"]
    for m, nx in sorted({(_m(r), r["nx"]) for r in west}):
        rs = {r["offset"]: r for r in west if r["nx"] == nx and _m(r) == m}
        err = max(abs(r["fem"] - r["reference"]) * nx for r in rs.values())
        out.append(f"| {m} | {nx} | {next(iter(rs.values()))['h_over_a']:.3g} | "
                   + " | ".join(f"{rs[o]['fem'] / rs[o]['reference']:.3f}" if o in rs else ""
                                for o in OFFSETS) + f" | {err:.2f} |")
    slide = sorted((r for r in rows if r["case"] == "sliding"), key=lambda r: (_m(r), r["nx"]))
    if slide:
        out += ["", render("contact_area_resolution", "sliding", velocity=f"{S_VELOCITY:g}",
                           wavelength=S_LAM, m2=f"{S_M2:g}", pressure=f"{S_PRESSURE:g}",
                           vhs_n=VHS_N), "",
                "| m | nx | h/a | A_FEM | A_VHS | A FEM/VHS | error [elements] | μ FEM/VHS "
                "| wall [s] |", "|---|---|---|---|---|---|---|---|---|"]
        for r in slide:
            out.append(f"| {_m(r)} | {r['nx']} | {r['h_over_a']:.3g} | {r['fem']:.4f} | "
                       f"{r['reference']:.4f} | {r['fem'] / r['reference']:.3f} | "
                       f"{(r['fem'] - r['reference']) * r['nx']:+.2f} | "
                       f"{r['fem_friction'] / r['vhs_friction']:.3f} | {r['wall_s']:.0f} |"
                       + ("" if r["steady"] else " not steady"))
    thresh = sorted((r for r in rows if r["case"].startswith("threshold")),
                    key=lambda r: (r["case"], _m(r), r["nx"], r["penalty"]))
    if thresh:
        out += ["", render("contact_area_resolution", "threshold"), "",
                render("contact_area_resolution", "threshold_intro",
                       package_factor=f"{SAG_FACTORS[0]:g}",
                       offsets=", ".join(str(Fraction(o)) for o in OFFSETS)), "",
                "| case | m | nx | h/a | penalty factor | "
                + " | ".join(f"c = {c:g}" for c in SAG_FACTORS) + " |",
                "|---|---|---|---|---|" + "---|" * len(SAG_FACTORS)]
        for r in thresh:
            cells = ["/".join(f"{v[str(c)] / r['reference']:.3f}" for v in r["areas"].values())
                     for c in SAG_FACTORS]
            out.append(f"| {r['case'].split('-')[1]} | {_m(r)} | {r['nx']} | {r['h_over_a']:.3g} | "
                       f"{r['penalty']:g} | " + " | ".join(cells) + " |")
    return "\n".join(out) + "\n"


def _m(row: dict) -> int:
    """Contact points per segment of a row (the first rows, without the key, used 2)."""
    return int(row.get("contact_points", 2))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--out", type=Path, default=Path("contact_area_resolution.jsonl"))
    ap.add_argument("--report", type=Path)
    ap.add_argument("--skip-sliding", action="store_true")
    ap.add_argument("--contact-points", type=int, default=4,
                    help="contact points per face segment of the cases run")
    ap.add_argument("--cases", default="westergaard,threshold-static,sliding,threshold-sliding",
                    help="comma-separated case kinds to run (the report shows all finished)")
    args = ap.parse_args(argv)
    rows = read_rows(args.out)
    m = args.contact_points
    done = {(r["case"], r["nx"], r["offset"], _m(r)) for r in rows}
    todo = [("westergaard", nx, o) for nx in W_NX for o in OFFSETS]
    todo += [("threshold-static", nx, pf) for nx in T_STATIC_NX for pf in PENALTIES]
    if not args.skip_sliding:
        todo += [("sliding", nx, 0.0) for nx in S_NX]
        todo += [("threshold-sliding", nx, pf) for nx in T_SLIDING_NX for pf in PENALTIES]
    kinds = {k.strip() for k in args.cases.split(",")}
    for case, nx, offset in todo:
        if (case, nx, offset, m) in done or case not in kinds:
            continue
        if case.startswith("threshold"):
            row = threshold_case(case, nx, offset, m)
        else:
            row = (westergaard_case(nx, offset, m) if case == "westergaard"
                   else sliding_case(nx, m))
        append_row(args.out, row)
        rows.append(row)
    if args.report:
        args.report.write_text(report(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
