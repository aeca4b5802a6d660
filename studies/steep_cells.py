"""The steady FEM on steep real waves: the CAPTIF fits' high-slope cells over the law's range.

The question (issue 26): does the steady solver converge on the steepest cells a real road
gives — the high-slope part of the CAPTIF fits, both stations together (0.25 + 0.5 mm
waves, m2 = 2.3 and 1.1) and station 1 alone (three waves 0.25-1 mm, m2 up to 2.8) — at the
law's pressures up to 10 MPa and speeds 1-100 mm/s? Each point either converges, or says
why and falls back to the transient test; the report gives which, how, and how long.

Resumable: one JSON line per finished point in ``docs/validation/steep_cells.jsonl``. About
half an hour single-threaded::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies steep_cells
"""

from __future__ import annotations

import argparse
import re
import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.config import load_config
from rubbercontact.inputs import build_surface
from rubbercontact.pipeline.setup import translated_to_zero_phase

from ._rows import append_row, publish, read_rows
from ._steep_strain import run_strain, strain_report
from ._templates import render

DESCRIPTION = "The steady FEM on the CAPTIF fits' steep high-slope cells over the law's range."

ROOT = Path(__file__).resolve().parents[1]
ROWS = ROOT / "docs" / "validation" / "steep_cells.jsonl"
REPORT = ROOT / "docs" / "validation" / "steep_cells.md"
PRESSURES = (0.1, 0.3, 1.0, 3.0, 10.0)
VELOCITIES = (1.0, 3.0, 10.0, 30.0, 100.0)
MESH = (40, 30)
#: Part ``contact``: the hard points of the law grid, penalty against barrier contact, on a
#: mesh that resolves each cell (station 1: 32 columns per 0.25 mm wave, graded ×4 toward
#: the face; stations 0+1: the grid's 40 × 30), and the quasi-static limit (1e-3 mm/s,
#: where the friction must vanish) at one pressure on the same mesh.
CONTACT_POINTS = (("station 1", 0.3, 1.0), ("station 1", 1.0, 10.0), ("station 1", 3.0, 10.0),
                  ("station 1", 10.0, 1.0), ("station 1", 0.3, 1e-3),
                  ("stations 0+1", 3.0, 10.0), ("stations 0+1", 10.0, 1.0),
                  ("stations 0+1", 10.0, 10.0), ("stations 0+1", 3.0, 30.0),
                  ("stations 0+1", 1.0, 1e-3))
CONTACT_MESH = {"station 1": {"mesh": (128, 30), "grading": 4.0},
                "stations 0+1": {"mesh": (40, 30), "grading": 1.0}}
#: The contact variants side by side: the barrier's Newton iterations per continuation
#: step also at 60 (the log barrier's Newton takes many short steps near the surface).
CONTACTS = {"penalty": {"contact": "penalty"}, "barrier": {"contact": "barrier"},
            "barrier, 60 Newton": {"contact": "barrier", "newton_per_step": 60}}
#: Part ``defaults``: the law grid with the library's defaults for a run's law cell — the
#: mesh the surface sets (``mesh = "auto"``), penalty contact rescued by the barrier — and
#: no transient fallback, so the table shows how often the fallback would still run.
DEFAULTS = {"mesh": "auto"}
#: Part ``rounded``: the same with the crests rounded to the CAPTIF profiles' sampling
#: interval, as a run's law cell of a measured road now has it (``fem.crest_radius``).
CREST_RADIUS = 0.0375
ROUNDED = {**DEFAULTS, "crest_radius": CREST_RADIUS}
#: Part ``radius``: how far μ and A move with the rounding's radius, at a low and a high load
#: on each cell (the crests as fitted: part ``defaults``; at the sampling: part ``rounded``).
RADII = (0.025, 0.05)
#: Part ``qs``: the quasi-static limit (the friction must vanish: within QS_TOL of zero) on
#: the rounded cells' own meshes, at a low and a high load.
QS_SPEED = 1e-3
QS_TOL = 0.005
QS_POINTS = (("station 1", 0.3), ("station 1", 1.0), ("stations 0+1", 1.0))
#: Part ``mesh``: mesh convergence at a steep point of the rounded station 1 cell, on the
#: automatic rule's mesh for the default 64 columns per shortest wave and for twice that.
MESH_POINT = ("station 1", 1.0, 10.0)
MESH_COLUMNS = (64, 128)
RADIUS_POINTS = (("stations 0+1", 0.1, 10.0), ("stations 0+1", 1.0, 10.0),
                 ("station 1", 0.3, 10.0), ("station 1", 1.0, 10.0))
#: Part ``settle``: steady = settled transient at the issue's two steep points, on the
#: defaults' mesh; the transient slides SETTLE_TIMES of the SBR's longest retardation time
#: from the steady solution's surface offset.
SETTLE_POINTS = (("stations 0+1", 3.0, 10.0), ("stations 0+1", 10.0, 1.0))
SETTLE_TIMES = 6
SETTLED = ("friction", "contact_fraction", "mean_separation")


def cells() -> dict[str, rc.roughness.SineSeries]:
    """The high-slope parts of the CAPTIF fits: both stations, and station 1 alone."""
    cfg = load_config(ROOT / "examples" / "captif_road.toml")
    out = {}
    for name, files in (("stations 0+1", None), ("station 1", [1])):
        data = cfg.model_dump(mode="json", exclude_none=True)
        if files is not None:
            prof = data["surface"]["profiles"]
            prof["files"] = [prof["files"][i] for i in files]
        surf = build_surface(rc.config.parse_config(data).surface).series
        hs, _ = surf.partition(data["surface"]["m2_threshold"])
        out[name] = translated_to_zero_phase(hs)
    return out


def run_point(cell: str, surface, p: float, v: float, fallback: bool = True,
              **options) -> dict:
    """One point; with ``fallback=False`` a steady failure is recorded as ``steady failed``
    (the library would then run the transient test, minutes per point on these cells).
    ``options`` change the FEM options (default: the grid's mesh)."""
    if "options" not in options:       # a FemOptions given whole keeps its own mesh
        options = {"mesh": MESH, **options}
    t0 = time.process_time()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            res = rc.fem.steady_sliding(surface, rc.materials.sbr(), p, v, fallback=fallback,
                                        **options)
        except rc.errors.RubberContactError as exc:
            steady = isinstance(exc, rc.errors.ConvergenceError) and not fallback
            tried = (getattr(exc, "diagnostics", None) or {}).get("tried", [])
            return {"cell": cell, "pressure": p, "velocity": v,
                    "solver": "steady failed" if steady else "failed",
                    "status": str(exc)[:300], "cpu_s": time.process_time() - t0,
                    "tried": "; ".join(tried)}
    s = res.stats
    return {"cell": cell, "pressure": p, "velocity": v, "solver": s.solver,
            "status": s.status, "cpu_s": time.process_time() - t0, "impaled": s.impaled,
            "friction": res.friction, "contact_fraction": res.contact_fraction,
            "mean_separation": res.mean_separation, "surface_offset": s.surface_offset,
            "bulk_shear": s.bulk_shear, "newton": s.newton_iterations,
            "continuation_steps": s.continuation_steps, "tried": "; ".join(s.tried),
            "warnings": sorted({str(w.message)[:120] for w in caught})}


def report(rows: list[dict], surfaces: dict) -> str:
    lines = [render("steep_cells", "header", mesh=f"{MESH[0]} x {MESH[1]}"), ""]
    for name, surf in surfaces.items():
        waves = ", ".join(f"{lam:g} mm (m2 = {m:.2f})"
                          for lam, m in zip(surf.wavelengths, surf.rms_slopes(), strict=True))
        mine = [r for r in rows if r["cell"] == name and "part" not in r]
        ok = [r for r in mine if r["solver"] == "steady"]
        cpu = np.array([r["cpu_s"] for r in ok]) if ok else np.array([np.nan])
        lines += [render("steep_cells", "cell", cell_name=name, waves=waves, period=surf.period,
                         points=len(mine), steady=len(ok),
                         fallback=sum(r["solver"].startswith("transient") for r in mine),
                         failed=sum(r["solver"] == "failed" for r in mine),
                         unsolved=sum(r["solver"] == "steady failed" for r in mine),
                         median=f"{np.median(cpu):.1f}", worst=f"{np.max(cpu):.1f}"), "",
                  "| p̄ [MPa] | " + " | ".join(f"{v:g} mm/s" for v in VELOCITIES) + " |",
                  "|---|" + "---|" * len(VELOCITIES)]
        for p in PRESSURES:
            cells_ = []
            for v in VELOCITIES:
                r = next((r for r in mine if r["pressure"] == p and r["velocity"] == v), None)
                if r is None:
                    cells_.append("–")
                elif r["solver"] == "steady":
                    cells_.append(f"μ {r['friction']:.3f}, A {r['contact_fraction']:.3f}, "
                                  f"{r['cpu_s']:.0f} s")
                elif r["solver"].startswith("transient"):
                    cells_.append(f"fell back: transient μ {r['friction']:.3f}, "
                                  f"A {r['contact_fraction']:.3f}, {r['cpu_s']:.0f} s")
                else:
                    cells_.append(f"{r['solver']}: {r['status'][:80]}")
            lines.append(f"| {p:g} | " + " | ".join(cells_) + " |")
        lines.append("")
    lines.append(render("steep_cells", "footer"))
    lines += ["", *contact_report([r for r in rows if r.get("part") == "contact"])]
    lines += ["", *defaults_report([r for r in rows if r.get("part") == "defaults"],
                                   surfaces)]
    lines += ["", *settle_report([r for r in rows if r.get("part") == "settle"])]
    lines += ["", *strain_report([r for r in rows if r.get("part") == "strain"])]
    rounded = [r for r in rows if r.get("part") == "rounded"]
    lines += ["", *defaults_report(rounded, surfaces, "rounded")]
    if rounded:
        lines += [render("steep_cells", "rounded_footer")]
    lines += ["", *qs_report(rows, surfaces)]
    lines += ["", *mesh_report(rows)]
    lines += ["", *radius_report(rows)]
    return "\n".join(lines) + "\n"


def defaults_report(rows: list[dict], surfaces: dict, block: str = "defaults") -> list[str]:
    """Part ``defaults`` (or ``rounded``): the law grid with the library's defaults (and the
    crests rounded), per cell."""
    if not rows:
        return []
    lines = [render("steep_cells", block), ""]
    for name in surfaces:
        mine = [r for r in rows if r["cell"] == name]
        if not mine:
            continue
        rescued = sum(r["solver"] == "steady (barrier rescue)" for r in mine)
        steady = sum(r["solver"].startswith("steady") and r["solver"] != "steady failed"
                     for r in mine)
        lines += [f"**{name}** ({mine[0].get('mesh', '?')}): {len(mine)} of "
                  f"{len(PRESSURES) * len(VELOCITIES)} points run, {steady} steady "
                  f"({rescued} by the barrier rescue), "
                  f"{sum(r['solver'] == 'steady failed' for r in mine)} would fall back to "
                  f"the transient test.", "",
                  "| p̄ [MPa] | " + " | ".join(f"{v:g} mm/s" for v in VELOCITIES) + " |",
                  "|---|" + "---|" * len(VELOCITIES)]
        for p in PRESSURES:
            got = [next((r for r in mine if (r["pressure"], r["velocity"]) == (p, v)), None)
                   for v in VELOCITIES]
            lines.append(f"| {p:g} | " + " | ".join(_default_outcome(r) for r in got) + " |")
        lines.append("")
    return lines


def _default_outcome(r: dict | None) -> str:
    if r is None or r["solver"] == "steady failed":
        return _outcome(r)
    how = " (rescue)" if "rescue" in r["solver"] else ""
    flag = " (impaled)" if r.get("impaled") else ""
    return (f"μ {r['friction']:.3f}, A {r['contact_fraction']:.3f}{flag}{how}, "
            f"{r['cpu_s']:.0f} s")


def _outcome(r: dict | None) -> str:
    if r is None:
        return "–"
    if r["solver"] != "steady":
        # "steady FEM solve failed: memory 64x30: stopped at λ = 0.46 (step ...): why"
        stop = re.search(r"failed: (.+?): stopped at λ = ([0-9.e-]+) \(step [^)]*\): (.*)",
                         r["status"])
        what = (f"{stop[1]} at λ = {float(stop[2]):.3g} ({stop[3]})" if stop
                else r["status"][:80])
        return f"stopped: {what}, {r['cpu_s']:.0f} s"
    flag = " (impaled)" if r.get("impaled") else ""
    return f"μ {r['friction']:.3f}, A {r['contact_fraction']:.3f}{flag}, {r['cpu_s']:.0f} s"


def contact_report(rows: list[dict]) -> list[str]:
    """Part ``contact``: penalty against barrier at the hard points, side by side."""
    head = "| cell, mesh | p̄ [MPa] | v [mm/s] | " + " | ".join(CONTACTS) + " |"
    lines = [render("steep_cells", "contact"), "", head, "|---|---|---|" + "---|" * len(CONTACTS)]
    for name, p, v in CONTACT_POINTS:
        m = CONTACT_MESH[name]
        mesh = f"{m['mesh'][0]} × {m['mesh'][1]}" + (f" ×{m['grading']:g}"
                                                      if m["grading"] != 1 else "")
        got = [next((r for r in rows if (r["cell"], r["pressure"], r["velocity"],
                                         r["contact"]) == (name, p, v, c)), None)
               for c in CONTACTS]
        lines.append(f"| {name}, {mesh} | {p:g} | {v:g} | "
                     + " | ".join(_outcome(r) for r in got) + " |")
    lines += ["", render("steep_cells", "contact_footer")]
    return lines


def run_contact(path: Path, surfaces: dict, done: set) -> None:
    """Part ``contact`` (resumable, one row per point and contact)."""
    for name, p, v in CONTACT_POINTS:
        for contact in CONTACTS:
            if (name, p, v, contact) in done:
                continue
            row = run_point(name, surfaces[name], p, v, False, **CONTACTS[contact],
                            **CONTACT_MESH[name])
            append_row(path, {**row, "part": "contact", "contact": contact})


def run_defaults(path: Path, surfaces: dict, only: str | None, done: set,
                 part: str = "defaults") -> None:
    """Part ``defaults`` or ``rounded`` (resumable): every grid point with the library's
    defaults (``rounded``: and the crests rounded), the transient fallback off; the row
    records the mesh the surface set."""
    from rubbercontact.fem.options import FemOptions

    options = ROUNDED if part == "rounded" else DEFAULTS
    for name, surf in surfaces.items():
        if only is not None and name != only:
            continue
        mesh = FemOptions(**options).resolved(surf).mesh
        # load by load: the points above E∞ (the slowest, outside the cell's range) last
        for p in PRESSURES:
            for v in VELOCITIES:
                if (name, p, v) not in done:
                    row = run_point(name, surf, p, v, False, **options)
                    append_row(path, {**row, "part": part,
                                      "mesh": f"{mesh[0]} x {mesh[1]} (auto)"})


def run_radius(path: Path, surfaces: dict, done: set) -> None:
    """Part ``radius`` (resumable): the points of RADIUS_POINTS rounded to each of RADII."""
    for r in (*RADII, CREST_RADIUS):
        for name, p, v in RADIUS_POINTS:
            if (name, p, v, r) not in done:
                row = run_point(name, surfaces[name], p, v, False,
                                **{**DEFAULTS, "crest_radius": r})
                append_row(path, {**row, "part": "radius", "crest_radius": r})


def run_quasistatic(path: Path, surfaces: dict, done: set) -> None:
    """Part ``qs`` (resumable): the quasi-static limit on the rounded cells' own meshes."""
    for name, p in QS_POINTS:
        if (name, p, QS_SPEED) not in done:
            row = run_point(name, surfaces[name], p, QS_SPEED, False, **ROUNDED)
            append_row(path, {**row, "part": "qs", "crest_radius": CREST_RADIUS})


def qs_report(rows: list[dict], surfaces: dict) -> list[str]:
    """Part ``qs``: μ at the quasi-static speed against the tolerance."""
    from rubbercontact.fem.options import FemOptions

    qs = [{"mesh": "{} × {}".format(*FemOptions(**ROUNDED).resolved(surfaces[r["cell"]]).mesh),
           **r} for r in rows if r.get("part") == "qs"]
    if not qs:
        return []
    lines = [render("steep_cells", "qs", speed=f"{QS_SPEED:g}", tol=f"{QS_TOL:g}"), "",
             "| cell | p̄ [MPa] | μ | A | within ±" + f"{QS_TOL:g}" + " | mesh | CPU [s] |",
             "|---|---|---|---|---|---|---|"]
    for r in qs:
        ok = r["solver"] != "steady failed" and abs(r["friction"]) <= QS_TOL
        res = (f"{r['friction']:.4f} | {r['contact_fraction']:.3f}"
               if r["solver"] != "steady failed" else f"{_outcome(r)} | –")
        lines.append(f"| {r['cell']} | {r['pressure']:g} | {res} | {'yes' if ok else 'no'} | "
                     f"{_final_mesh(r)} | {r['cpu_s']:.0f} |")
    return lines + ["", render("steep_cells", "qs_footer")]


def _final_mesh(r: dict) -> str:
    """The mesh a point ended on (the refined one where its stages say so)."""
    m = re.search(r"refined to (\d+x\d+)", r.get("tried", ""))
    return m[1].replace("x", " × ") if m else r.get("mesh", "?")


def run_mesh(path: Path, surfaces: dict, done: set) -> None:
    """Part ``mesh`` (resumable): the steep point on the automatic rule's mesh for N and 2N
    columns per shortest wave, made explicit (no refinement), crests rounded."""
    from rubbercontact.fem.resolution import auto_mesh

    name, p, v = MESH_POINT
    for n in MESH_COLUMNS:
        if n not in done:
            m = auto_mesh(surfaces[name], 0.75, n)
            row = run_point(name, surfaces[name], p, v, False, mesh=(m.nx, m.ny),
                            grading=m.grading, crest_radius=CREST_RADIUS)
            append_row(path, {**row, "part": "mesh", "columns_per_wave": n,
                              "mesh": f"{m.nx} × {m.ny} (grading {m.grading:.1f})"})


def mesh_report(rows: list[dict]) -> list[str]:
    """Part ``mesh``: μ and A of the steep point against the columns per wave."""
    got = sorted((r for r in rows if r.get("part") == "mesh"),
                 key=lambda r: r["columns_per_wave"])
    if not got:
        return []
    lines = [render("steep_cells", "mesh", cell=MESH_POINT[0], p=f"{MESH_POINT[1]:g}",
                    v=f"{MESH_POINT[2]:g}"), "",
             "| columns per wave | mesh | μ | A | Δμ to the finest | ΔA to the finest | CPU [s] |",
             "|---|---|---|---|---|---|---|"]
    fine = got[-1]
    for r in got:
        if r["solver"] == "steady failed":
            lines.append(f"| {r['columns_per_wave']} | {r['mesh']} | {_outcome(r)} | | | | |")
            continue
        dmu = abs(r["friction"] / fine["friction"] - 1)
        da = abs(r["contact_fraction"] / fine["contact_fraction"] - 1)
        lines.append(f"| {r['columns_per_wave']} | {r['mesh']} | {r['friction']:.4f} | "
                     f"{r['contact_fraction']:.4f} | {dmu:.1%} | {da:.1%} | "
                     f"{r['cpu_s']:.0f} |")
    return lines


def radius_report(rows: list[dict]) -> list[str]:
    """Part ``radius``: μ and A of each point against the crest radius."""
    radius = [r for r in rows if r.get("part") == "radius"]
    if not radius:
        return []
    radii = ("none", *sorted({*RADII, CREST_RADIUS}))
    lines = [render("steep_cells", "radius"), "",
             "| cell | p̄ [MPa] | v [mm/s] | " + " | ".join(
                 "as fitted" if r == "none" else f"r = {r * 1e3:g} µm" for r in radii) + " |",
             "|---|---|---|" + "---|" * len(radii)]
    for name, p, v in RADIUS_POINTS:
        got = []
        for r in radii:
            parts = {"none": ("defaults",), CREST_RADIUS: ("rounded", "radius")}.get(
                r, ("radius",))
            row = next((x for x in rows if x.get("part") in parts and x["cell"] == name
                        and (x["pressure"], x["velocity"]) == (p, v)
                        and x.get("crest_radius", r) == r), None)
            got.append(_default_outcome(row))
        lines.append(f"| {name} | {p:g} | {v:g} | " + " | ".join(got) + " |")
    return lines + ["", render("steep_cells", "radius_footer")]


def run_settle(path: Path, surfaces: dict, done: set) -> None:
    """Part ``settle`` (resumable): the steady solve with the defaults, then — where it is
    steady and not impaled — the transient test on the same mesh from its offset."""
    from rubbercontact.fem.options import FemOptions

    mat = rc.materials.sbr()
    for name, p, v in SETTLE_POINTS:
        if (name, p, v) in done:
            continue
        opts = FemOptions(**DEFAULTS).resolved(surfaces[name])
        row = {**run_point(name, surfaces[name], p, v, False, options=opts), "part": "settle",
               "mesh": f"{opts.mesh[0]} x {opts.mesh[1]} (auto)"}
        if row["solver"] == "steady" and not row["impaled"]:
            row.update(_settled(surfaces[name], mat, p, v, opts, row["surface_offset"]))
        append_row(path, row)


def _settled(surface, mat, p: float, v: float, opts, offset: float) -> dict:
    """The transient's last-period means and their drift over the last period."""
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        tr = rc.fem.sliding_test(surface, mat, p, v, options=opts, solver="transient",
                                 min_sliding_time=SETTLE_TIMES * float(
                                     mat.retardation_times().max()),
                                 periods=500, steady_tol=1e-12, surface_offset=offset)
    n, h = opts.mesh[0], tr.history
    slide = h["phase"] == 2
    out = {"transient_cpu_s": time.process_time() - t0, "transient_periods": tr.stats.periods}
    for key in SETTLED:
        series = h[key][slide]
        last, before = series[-n:].mean(), series[-2 * n:-n].mean()
        out[f"transient_{key}"] = float(last)
        out[f"drift_{key}"] = float(max(abs(last - before), np.ptp(series[-n:])) / abs(last))
    return out


def settle_report(rows: list[dict]) -> list[str]:
    """Part ``settle``: the steady answer beside the settled transient's."""
    if not rows:
        return []
    lines = [render("steep_cells", "settle"), "",
             "| cell, mesh | p̄ [MPa] | v [mm/s] | steady μ / A / u [mm] | transient μ / A / u "
             "| rel. difference | transient drift | CPU steady / transient |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        head = f"| {r['cell']}, {r['mesh']} | {r['pressure']:g} | {r['velocity']:g} | "
        if "transient_friction" not in r:
            lines.append(head + f"{_default_outcome(r)} (no transient: not a steady, "
                                f"unimpaled solution) | – | – | – | {r['cpu_s']:.0f} s / – |")
            continue
        st = " / ".join(f"{r[k]:.5g}" for k in SETTLED)
        tr = " / ".join(f"{r['transient_' + k]:.5g}" for k in SETTLED)
        diff = " / ".join(f"{abs(r[k] - r['transient_' + k]) / abs(r['transient_' + k]):.1e}"
                          for k in SETTLED)
        drift = " / ".join(f"{r['drift_' + k]:.1e}" for k in SETTLED)
        lines.append(head + f"{st} | {tr} | {diff} | {drift} | {r['cpu_s']:.0f} s / "
                            f"{r['transient_cpu_s']:.0f} s ({r['transient_periods']} periods) |")
    return lines + [""]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--rows", type=Path, default=ROWS)
    ap.add_argument("--report", type=Path, default=REPORT)
    ap.add_argument("--report-only", action="store_true")
    ap.add_argument("--no-fallback", dest="fallback", action="store_false",
                    help="record a steady failure without running the transient fallback")
    ap.add_argument("--part", choices=("grid", "contact", "defaults", "rounded", "qs",
                                       "mesh", "radius", "settle", "strain"),
                    default="grid",
                    help="the law grid (default), penalty against barrier at hard points, "
                         "the law grid with the library's defaults (auto mesh, rescue), "
                         "the same with the crests rounded to the sampling interval, "
                         "its quasi-static limit, mesh convergence and sensitivity to the "
                         "radius, "
                         "steady = settled transient at two steep points, or what stops "
                         "the 10 MPa press (mesh by mesh)")
    ap.add_argument("--cell", choices=("stations 0+1", "station 1"), default=None,
                    help="parts defaults, rounded: one cell only")
    args = ap.parse_args(argv)
    surfaces = cells()
    rows = read_rows(args.rows)
    done = {(r["cell"], r["pressure"], r["velocity"]) for r in rows if "part" not in r}
    if args.part == "contact" and not args.report_only:
        run_contact(args.rows, surfaces, {(r["cell"], r["pressure"], r["velocity"],
                                           r["contact"]) for r in rows
                                          if r.get("part") == "contact"})
    elif args.part in ("defaults", "rounded") and not args.report_only:
        run_defaults(args.rows, surfaces, args.cell, {
            (r["cell"], r["pressure"], r["velocity"]) for r in rows
            if r.get("part") == args.part}, args.part)
    elif args.part == "mesh" and not args.report_only:
        run_mesh(args.rows, surfaces, {r["columns_per_wave"] for r in rows
                                       if r.get("part") == "mesh"})
    elif args.part == "qs" and not args.report_only:
        run_quasistatic(args.rows, surfaces, {(r["cell"], r["pressure"], r["velocity"])
                                              for r in rows if r.get("part") == "qs"})
    elif args.part == "radius" and not args.report_only:
        run_radius(args.rows, surfaces, {(r["cell"], r["pressure"], r["velocity"],
                                          r.get("crest_radius", CREST_RADIUS)) for r in rows
                                         if r.get("part") in ("radius", "rounded")})
    elif args.part == "settle" and not args.report_only:
        run_settle(args.rows, surfaces, {(r["cell"], r["pressure"], r["velocity"])
                                         for r in rows if r.get("part") == "settle"})
    elif args.part == "strain" and not args.report_only:
        run_strain(args.rows, surfaces, {(r["nx"], r["ny"], r["grading"]) for r in rows
                                         if r.get("part") == "strain"})
    elif not args.report_only:
        for name, surf in surfaces.items():
            for v in VELOCITIES:
                for p in PRESSURES:
                    if (name, p, v) in done:
                        continue
                    row = run_point(name, surf, p, v, args.fallback)
                    append_row(args.rows, row)
    return publish(report(read_rows(args.rows), surfaces), args.report)
