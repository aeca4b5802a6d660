"""Assemble BENCHMARKS.md from the per-area tables the benchmark scripts write."""

from __future__ import annotations

from pathlib import Path

HERE = Path(__file__).resolve().parent
PARTS = [("halfspace.md", "Half-space (BEM) solver"),
         ("steady.md", "Steady FEM against the time-stepped test"),
         ("fem.md", "FEM sliding test (time-stepped)"),
         ("steep_grid.md", "The steep real-road law cell: station 1's law grid"),
         ("sweep.md", "Sweeps: Dask executor and result cache"),
         ("speed_sweep.md", "Speed sweeps: friction against speed from an empty cache"),
         ("halfspace_sweep.md", "Half-space part of a 15-speed curve, against a baseline"),
         ("make_run.md", "make run from an empty cache"),
         ("examples.md", "The examples from an empty cache against their estimate"),
         ("cost_model.md", "The cost model of run --check: where each constant was measured"),
         ("qs_tail.md", "The law cell's quasi-static point: fresh against continued"),
         ("prony_fit.md", "Prony fit of DMA data against pyvisco"),
         ("meanfield.md", "Mean-field model"),
         ("strips.md", "Mean-field strip cascade, against a baseline"),
         ("flash.md", "Mean-field flash temperature"),
         ("flash_run.md", "Flash temperature in a run, against the isothermal run"),
         ("flash_scales.md", "The hybrids' flash: each scale at its own temperature"),
         ("maps.md", "Areal maps: the 2D models")]


def main() -> None:
    out = ["# Benchmarks", "",
           "Latest measured figures, each section written by its script in `benchmarks/` "
           "(`make bench` reruns them all and regenerates this file). Each section states its "
           "machine, date and commit. Speed is measured here, never asserted in tests.", ""]
    for name, title in PARTS:
        path = HERE / name
        out.append(f"<!-- from benchmarks/{name} -->")
        if not path.exists():
            out += [f"# {title}", "", "(not measured yet)", ""]
            continue
        text = path.read_text().strip().splitlines()
        # Demote the part's headings one level under this file's title.
        out += [("#" + line) if line.startswith("#") else line for line in text] + [""]
    (HERE.parent / "BENCHMARKS.md").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
