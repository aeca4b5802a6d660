"""How many columns per shortest wave the law cell needs: the automatic mesh's N.

The question (issue 41, item 2): on a steep real-road cell — the high-slope part of both
CAPTIF stations, 0.25 + 0.5 mm waves, m2 = 2.3 and 1.1 — how do the friction μ and the
contact fraction A of one steady sliding test change with the automatic mesh's columns per
shortest wave, N = 8 … 256? Each mesh is the rule's
(:func:`rubbercontact.fem.resolution.auto_mesh`) made explicit, so that no point refines
itself; every row records its narrowest contact patch in columns, which sizes the per-point
check (``FemOptions.patch_columns``). Then the same point, and the quasi-static limit (1 MPa
at 1e-3 mm/s, where μ must vanish: within 0.005 of zero), as a law point runs them
(``mesh = "auto"`` with the check and its one refinement), against the explicit mesh with
twice the columns it ended on: the default N and patch width are those whose answer lies
within 2 % of that.

The penalty contact first; where it stops, the barrier with 60 Newton iterations per
continuation step (docs/validation/steep_cells.md). Resumable, one JSON line per case in
``docs/validation/mesh_resolution.jsonl``; about ten minutes single-threaded (the
N = 256 mesh, 512 × 23, takes 2–3 of them)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies mesh_resolution

``--part hard`` runs the points of docs/validation/steep_cells.md that stopped, fell back
or were impaled there, on the automatic mesh with the library's defaults (10-20 minutes).
"""

from __future__ import annotations

import argparse
import datetime
import itertools
import os
import re
import subprocess
import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.config import load_config, parse_config
from rubbercontact.fem.resolution import auto_mesh
from rubbercontact.inputs import build_surface

from ._rows import append_row, publish, read_rows

DESCRIPTION = "Columns per shortest wave of the automatic FEM mesh: μ and A against N."

ROOT = Path(__file__).resolve().parents[1]
ROWS = ROOT / "docs" / "validation" / "mesh_resolution.jsonl"
REPORT = ROOT / "docs" / "validation" / "mesh_resolution.md"
#: The steep point (the law grid's, converged steady at 40 x 30 in steep_cells.md).
POINT = (1.0, 10.0)
#: The quasi-static limit: the same load at a speed where the loss tangent is 1e-4.
QUASI_STATIC = (1.0, 1e-3)
COLUMNS = (8, 16, 32, 64, 128, 256)
#: Columns per wave and patch width of the automatic mesh with its per-point check, run as
#: a law point runs (``mesh = "auto"``: refined once where the narrowest patch is narrow).
PROCEDURE = ((32, 4), (64, 4))
#: The nested iteration of the finest meshes starts here (their own press costs minutes).
COARSEST = 64
#: Part ``hard``: points of docs/validation/steep_cells.md that stopped, fell back or
#: converged only impaled there (40 x 30; station 1 also at 128 x 30 graded x4), run as a
#: law point runs them on the automatic mesh with the defaults (penalty contact), no
#: transient fallback.
HARD_POINTS = (("stations 0+1", 0.1, 10.0), ("stations 0+1", 3.0, 10.0),
               ("stations 0+1", 3.0, 30.0), ("stations 0+1", 10.0, 1.0),
               ("stations 0+1", 10.0, 10.0), ("station 1", 0.3, 1.0),
               ("station 1", 1.0, 10.0), ("station 1", 3.0, 10.0), ("station 1", 10.0, 1.0))
QUASI_STATIC_COLUMNS = (16, 32, 64)
TOLERANCE = 0.02
QUASI_STATIC_TOLERANCE = 0.005
CONTACTS = {"penalty": {}, "barrier, 60 Newton": {"contact": "barrier",
                                                  "newton_per_step": 60}}


#: What the tables say (the numbers are in the tables and the result line above it).
READING = (
    "**Reading.** The friction converges from below and slowly: on coarse meshes the "
    "contact is a lattice of one or two columns and μ is far off (at 16 and 32 columns per "
    "wave the quasi-static friction, which must vanish, is +0.14 and −0.09). The contact "
    "fraction is the slower of the two: at N = 64 the contact at the steep point is split "
    "into a main patch and a patch 2.5 columns wide, which is one patch at N = 128, and that "
    "costs A its last 3 %. The per-point check is made for exactly this: a patch under 4 "
    "columns is refined, and the refined point lands on the N = 128 mesh, within 2 % of "
    "N = 256. A check of the patch alone would not do — at N = 32 the narrowest patch is 5 "
    "columns and μ, A are still 4 % and 17 % off — hence both: N = 64 columns per shortest "
    "wave (`FemOptions.columns_per_wave`, `fem.columns_per_wave`) and 4 columns per patch "
    "(`patch_columns`). The quasi-static check is a study check, not a per-point one (it "
    "costs a second solve per point); it passes on the default mesh. Open: the convergence "
    "is measured at one steep point of one cell; the station 1 cell (1 mm wide, three "
    "waves) gets 256 × 19 at N = 64, and its hard points below are not all resolved.")


def cell(files: list[int] | None = None) -> rc.roughness.SineSeries:
    """The high-slope part of the CAPTIF fits (both stations, or the profiles ``files``
    of examples/captif_road.toml), shortest wave at phase 0."""
    cfg = load_config(ROOT / "examples" / "captif_road.toml")
    data = cfg.model_dump(mode="json", exclude_none=True)
    if files is not None:
        prof = data["surface"]["profiles"]
        prof["files"] = [prof["files"][i] for i in files]
    surf = build_surface(parse_config(data).surface).series
    hs, _ = surf.partition(data["surface"]["m2_threshold"])
    x0 = -hs.phases[0] / hs.wavenumbers[0]
    return hs.with_phases(hs.phases + hs.wavenumbers * x0)


def run_case(surface, p: float, v: float, n: int) -> dict:
    """One test on the rule's mesh for ``n`` columns per wave: the penalty, else the
    barrier with 60 Newton iterations per step."""
    m = auto_mesh(surface, 0.75, n)
    row = {"pressure": p, "velocity": v, "columns_per_wave": n, "mesh": [m.nx, m.ny],
           "grading": m.grading}
    tried = []
    for name, extra in CONTACTS.items():
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                res = rc.fem.steady_sliding(surface, rc.materials.sbr(), p, v,
                                            mesh=(m.nx, m.ny), grading=m.grading,
                                            coarse_elements=min(n, COARSEST),
                                            fallback=False, **extra)
            except rc.errors.ConvergenceError as exc:
                tried.append(f"{name}: {str(exc)[:160]} ({time.process_time() - t0:.0f} s)")
                continue
        s = res.stats
        return {**row, "contact": name, "friction": res.friction,
                "contact_fraction": res.contact_fraction, "patch_columns": s.patch_columns,
                "impaled": s.impaled, "cpu_s": time.process_time() - t0,
                "tried": tried}
    return {**row, "contact": "stopped", "tried": tried}


def run_hard(name: str, surface, p: float, v: float) -> dict:
    """One hard point on the automatic mesh with the library's defaults."""
    t0 = time.process_time()
    row = {"part": "hard", "cell": name, "pressure": p, "velocity": v}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            res = rc.fem.steady_sliding(surface, rc.materials.sbr(), p, v, mesh="auto",
                                        fallback=False)
        except rc.errors.ConvergenceError as exc:
            return {**row, "stopped": str(exc)[:200], "cpu_s": time.process_time() - t0}
    s = res.stats
    return {**row, "mesh": list(res.mesh), "friction": res.friction,
            "contact_fraction": res.contact_fraction, "patch_columns": s.patch_columns,
            "refined": s.refined, "under_resolved": s.under_resolved, "impaled": s.impaled,
            "cpu_s": time.process_time() - t0, "first": s.tried[0] if s.tried else "",
            "warnings": sorted({str(w.message)[:100] for w in caught})}


def hard_lines(rows: list[dict]) -> list[str]:
    """The hard points' table."""
    hard = [r for r in rows if r.get("part") == "hard"]
    if not hard:
        return []
    out = ["", "**Hard points of steep_cells.md on the automatic mesh** (the library's "
               "defaults: penalty contact, 15 Newton iterations per step, no transient "
               "fallback; the steady solver's barrier rescue of commit 56aa586, which tries "
               "the barrier where the penalty stops, was in the working tree; what the points "
               "did in steep_cells.md in the last column).", "",
           "| cell | p̄ [MPa] | v [mm/s] | final mesh | refined | narrowest patch | μ | A | "
           "CPU [s] | steep_cells.md |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in hard:
        was = STEEP_CELLS_OUTCOME.get((r["cell"], r["pressure"], r["velocity"]), "")
        if "stopped" in r:
            out.append(f"| {r['cell']} | {r['pressure']:g} | {r['velocity']:g} | — | — | — | "
                       f"stopped: {r['stopped'][:110]} | | {r['cpu_s']:.0f} | {was} |")
            continue
        flags = " (impaled)" if r["impaled"] else ""
        out.append(f"| {r['cell']} | {r['pressure']:g} | {r['velocity']:g} | "
                   f"{r['mesh'][0]} × {r['mesh'][1]} | {'yes' if r['refined'] else 'no'} | "
                   f"{r['patch_columns']:.1f} | {r['friction']:.3f}{flags} | "
                   f"{r['contact_fraction']:.3f} | {r['cpu_s']:.0f} | {was} |")
    have = {(r["cell"], r["pressure"], r["velocity"]) for r in hard}
    for name, p, v in HARD_POINTS:
        if (name, p, v) not in have:
            out.append(f"| {name} | {p:g} | {v:g} | not run (the run was stopped after 12 "
                       f"CPU minutes on it) | | | | | | {STEEP_CELLS_OUTCOME[(name, p, v)]} |")
    out += ["", "A point refined but still under-resolved ('no' with a patch under 4 "
                "columns) is one whose refinement failed: it keeps its first answer, flagged "
                "(stats.under_resolved), and says so in stats.tried and a warning."]
    return out


#: What the hard points did in docs/validation/steep_cells.md (penalty unless said).
STEEP_CELLS_OUTCOME = {
    ("stations 0+1", 0.1, 10.0): "μ 0.272, A 0.039 (40 × 30)",
    ("stations 0+1", 3.0, 10.0): "stopped (40 × 30); transient μ 0.625, A 0.094",
    ("stations 0+1", 3.0, 30.0): "stopped; transient failed",
    ("stations 0+1", 10.0, 1.0): "μ 0.239, A 0.418 impaled (40 × 30)",
    ("stations 0+1", 10.0, 10.0): "stopped; transient unusable (μ 1.98)",
    ("station 1", 0.3, 1.0): "stopped (40 × 30 and 128 × 30 ×4, both contacts)",
    ("station 1", 1.0, 10.0): "stopped (40 × 30 and 128 × 30 ×4, both contacts)",
    ("station 1", 3.0, 10.0): "stopped (40 × 30 and 128 × 30 ×4, both contacts)",
    ("station 1", 10.0, 1.0): "stopped (40 × 30 and 128 × 30 ×4, both contacts)",
}


def run_procedure(surface, p: float, v: float, n: int, patch: int) -> dict:
    """One test as a law point runs it: ``mesh = "auto"`` with the resolution check."""
    row = {"pressure": p, "velocity": v, "procedure": [n, patch]}
    for name, extra in CONTACTS.items():
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                res = rc.fem.steady_sliding(surface, rc.materials.sbr(), p, v, mesh="auto",
                                            columns_per_wave=n, patch_columns=patch,
                                            fallback=False, **extra)
            except rc.errors.ConvergenceError as exc:
                row.setdefault("tried", []).append(f"{name}: {str(exc)[:160]}")
                continue
        s = res.stats
        return {**row, "contact": name, "mesh": list(res.mesh), "friction": res.friction,
                "contact_fraction": res.contact_fraction, "patch_columns": s.patch_columns,
                "refined": s.refined, "under_resolved": s.under_resolved,
                "cpu_s": time.process_time() - t0}
    return {**row, "contact": "stopped"}


def _rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b) if b else np.inf


def convergence(rows: list[dict]) -> list[dict]:
    """Per N of the steep point: μ, A and their change to 2N."""
    by_n = {r["columns_per_wave"]: r for r in rows
            if (r["pressure"], r["velocity"]) == POINT and "friction" in r
            and "columns_per_wave" in r}
    out = []
    for n in sorted(by_n):
        r, f = by_n[n], by_n.get(2 * n)
        dmu = _rel(r["friction"], f["friction"]) if f else np.nan
        da = _rel(r["contact_fraction"], f["contact_fraction"]) if f else np.nan
        out.append({**r, "dmu": dmu, "da": da})
    return out


def chosen(table: list[dict]) -> int | None:
    """The smallest N within the tolerance of 2N in both μ and A."""
    ok = [t["columns_per_wave"] for t in table
          if t["dmu"] <= TOLERANCE and t["da"] <= TOLERANCE]
    return min(ok) if ok else None


def _cell(r: dict | None, key: str, fmt: str) -> str:
    return "—" if r is None or key not in r or r[key] is None else format(r[key], fmt)


def report(rows: list[dict], meta: dict) -> str:
    table = convergence(rows)
    n = chosen(table)
    lines = ["# Columns per shortest wave of the law cell (the automatic mesh)", "",
             "Generated by `studies/mesh_resolution.py`. The high-slope cell of both CAPTIF "
             "stations (examples/captif_road.toml: 0.25 mm, m2 = 2.26 and 0.5 mm, m2 = 1.07; "
             "cell 0.5 mm wide), SBR, steady solver, each mesh the automatic rule's for N "
             "columns per shortest wave (`rubbercontact.fem.resolution.auto_mesh`: face rows "
             "1.5 columns tall, graded up to rows of an eighth of the width at the plate), "
             "made explicit so that no point refines itself; the nested iteration's coarsest "
             "mesh is the test's own. Penalty contact, else the barrier with 60 Newton "
             "iterations per step where the penalty stops (column 'contact'). "
             f"{meta['runs']}", "",
             f"**Steep point: p̄ = {POINT[0]:g} MPa, v = {POINT[1]:g} mm/s.** Change to 2N: "
             "|x_N − x_2N| / x_2N.", "",
             "| N | mesh (grading) | contact | μ | A | narrowest patch [columns] | Δμ to 2N "
             "| ΔA to 2N | CPU [s] |", "|---|---|---|---|---|---|---|---|---|"]
    for t in table:
        lines.append(
            f"| {t['columns_per_wave']} | {t['mesh'][0]} × {t['mesh'][1]} "
            f"({t['grading']:.2f}) | {t['contact']} | {t['friction']:.4f} | "
            f"{t['contact_fraction']:.4f} | {_cell(t, 'patch_columns', '.1f')} | "
            f"{_pct(t['dmu'])} | {_pct(t['da'])} | {t['cpu_s']:.0f} |")
    for r in rows:
        if "friction" not in r and "columns_per_wave" in r:
            lines.append(f"| {r['columns_per_wave']} | {r['mesh'][0]} × {r['mesh'][1]} | "
                         f"stopped ({'; '.join(r['tried'])}) | | | | | | |")
    lines += _procedure_lines(rows, table)
    qs = [r for r in rows if (r["pressure"], r["velocity"]) == QUASI_STATIC
          and "columns_per_wave" in r]
    lines += ["", f"**Quasi-static limit: p̄ = {QUASI_STATIC[0]:g} MPa, v = "
                  f"{QUASI_STATIC[1]:g} mm/s** (the friction must vanish; tolerance "
                  f"{QUASI_STATIC_TOLERANCE}).", "",
              "| N | mesh | contact | μ | A | CPU [s] |", "|---|---|---|---|---|---|"]
    for r in sorted(qs, key=lambda r: r["columns_per_wave"]):
        lines.append(f"| {r['columns_per_wave']} | {r['mesh'][0]} × {r['mesh'][1]} | "
                     f"{r['contact']} | {_cell(r, 'friction', '.4f')} | "
                     f"{_cell(r, 'contact_fraction', '.4f')} | {_cell(r, 'cpu_s', '.0f')} |")
    verdict = (f"the smallest N whose own mesh is within {100 * TOLERANCE:g} % of 2N in "
               f"both μ and A is N = {n}" if n else
               f"no N within {100 * TOLERANCE:g} % of 2N")
    lines += ["", f"**Result:** {verdict}; {_procedure_verdict(rows, table)}", "",
              READING]
    lines += hard_lines(rows) + [""]
    return "\n".join(lines)


def _procedure_lines(rows: list[dict], table: list[dict]) -> list[str]:
    """The automatic mesh with its per-point check, against the explicit mesh twice as
    fine as the one it ended on."""
    by_nx = {t["mesh"][0]: t for t in table}
    out = ["", "**The same points as a law point runs them** (`mesh = \"auto\"`: the "
               "narrowest patch checked, refined once to 2 nx where it is narrower than "
               "`patch_columns`); change against the explicit mesh with twice the final "
               "columns.", "",
           "| N, patch_columns | p̄ [MPa] | v [mm/s] | final mesh | refined | narrowest "
           "patch | μ | A | Δμ | ΔA | CPU [s] |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in (r for r in rows if "procedure" in r and "friction" in r):
        ref = by_nx.get(2 * r["mesh"][0]) if r["velocity"] == POINT[1] else None
        dmu = _rel(r["friction"], ref["friction"]) if ref else np.nan
        da = _rel(r["contact_fraction"], ref["contact_fraction"]) if ref else np.nan
        out.append(f"| {r['procedure'][0]}, {r['procedure'][1]} | {r['pressure']:g} | "
                   f"{r['velocity']:g} | {r['mesh'][0]} × {r['mesh'][1]} | "
                   f"{'yes' if r['refined'] else 'no'} | {r['patch_columns']:.1f} | "
                   f"{r['friction']:.4f} | {r['contact_fraction']:.4f} | {_pct(dmu)} | "
                   f"{_pct(da)} | {r['cpu_s']:.0f} |")
    return out


def _procedure_verdict(rows: list[dict], table: list[dict]) -> str:
    """What the default (the law point's procedure at ``FemOptions``' N and patch width)
    gives at both points."""
    opts = rc.fem.FemOptions()
    key = [opts.columns_per_wave, opts.patch_columns]
    by_nx = {t["mesh"][0]: t for t in table}
    mine = {(r["pressure"], r["velocity"]): r for r in rows
            if r.get("procedure") == key and "friction" in r}
    steep, qs = mine.get(POINT), mine.get(QUASI_STATIC)
    if steep is None or qs is None:
        return f"the default (N = {key[0]}, patch {key[1]} columns) not run yet."
    ref = by_nx.get(2 * steep["mesh"][0])
    diff = (f"{_pct(_rel(steep['friction'], ref['friction']))} in μ and "
            f"{_pct(_rel(steep['contact_fraction'], ref['contact_fraction']))} in A from the "
            f"mesh twice as fine" if ref else "no mesh twice as fine run")
    return (f"the default, N = {key[0]} with the patch check at {key[1]} columns, ends the "
            f"steep point on {steep['mesh'][0]} × {steep['mesh'][1]} "
            f"({'refined' if steep['refined'] else 'not refined'}), {diff}, and gives "
            f"μ = {qs['friction']:.4f} at the quasi-static point on "
            f"{qs['mesh'][0]} × {qs['mesh'][1]} (tolerance ±{QUASI_STATIC_TOLERANCE}).")


def _pct(x: float) -> str:
    return "—" if not np.isfinite(x) else f"{100 * x:.1f} %"


def _meta() -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    load = os.getloadavg()[0]
    now = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    return f"Run {now} at commit {commit} (plus the working tree), load average {load:.1f}."


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--rows", type=Path, default=ROWS)
    ap.add_argument("--report", type=Path, default=REPORT)
    ap.add_argument("--report-only", action="store_true")
    ap.add_argument("--part", choices=("convergence", "hard"), default="convergence",
                    help="the convergence study (default), or the hard points of "
                         "steep_cells.md on the automatic mesh")
    args = ap.parse_args(argv)
    if args.part == "hard" and not args.report_only:
        cells = {"stations 0+1": cell(), "station 1": cell([1])}
        have = {(r["cell"], r["pressure"], r["velocity"]) for r in read_rows(args.rows)
                if r.get("part") == "hard"}
        for name, p, v in HARD_POINTS:
            if (name, p, v) not in have:
                append_row(args.rows, {**run_hard(name, cells[name], p, v), "run": _meta()})
        args.report_only = True
    rows = read_rows(args.rows)
    done = {(r["pressure"], r["velocity"], r.get("columns_per_wave"),
             tuple(r.get("procedure", ()))) for r in rows}
    surface = cell()
    cases = ([(*POINT, n) for n in COLUMNS] + [(*QUASI_STATIC, n)
                                               for n in QUASI_STATIC_COLUMNS])
    if not args.report_only:
        for p, v, n in cases:
            if (p, v, n, ()) not in done:
                append_row(args.rows, {**run_case(surface, p, v, n), "run": _meta()})
        for (p, v), (n, patch) in itertools.product((POINT, QUASI_STATIC), PROCEDURE):
            if (p, v, None, (n, patch)) not in done:
                append_row(args.rows, {**run_procedure(surface, p, v, n, patch),
                                       "run": _meta()})
        rows = read_rows(args.rows)
    return publish(report(rows, {"runs": _runs(rows)}), args.report)


def _runs(rows: list[dict]) -> str:
    """The rows' runs in one sentence: time span, commits, load averages."""
    found = [re.match(r"Run (.+) UTC at commit (\w+) .*load average (\d+\.\d)", r["run"])
             for r in rows if "run" in r]
    found = [m for m in found if m]
    if not found:
        return ""
    times = sorted(m[1] for m in found)
    commits = list(dict.fromkeys(m[2] for m in found))
    loads = sorted(float(m[3]) for m in found)
    return (f"Runs {times[0]} to {times[-1][-5:]} UTC at commits {', '.join(commits)} with "
            f"this study's library changes in the working tree (one job at a time, "
            f"single-threaded; load average {loads[0]:g}-{loads[-1]:g} on the shared 2-core "
            f"machine, so CPU times are on the high side).")
