"""The law cell checks its own resolution: the quasi-static limit at every law pressure.

Slid slowly enough that the rubber is relaxed at the frequency of the shortest high-slope
wave, the cell is an elastic body in steady contact and dissipates nothing: the law's
friction must vanish there (μ_hs → 0 as v → 0). A mesh too coarse for its contact patches
keeps a friction of the lattice instead — contacts one or two columns wide that the face
catches on — so the friction left at that speed measures the cell's under-resolution at
that pressure (issue 41; docs/validation/steep_cells.md, part ``qs``). The check runs one
steady FEM point per law pressure on the law's own options and mesh, without the transient
fallback, continued down from a point pressed at :data:`TAIL_FROM` (cheaper than a press
at the quasi-static speed); a point that does not converge is recorded, not counted as a
pass.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..fem.options import FemOptions
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .batch import Batch
from .costmodel import quasi_static_seconds
from .setup import task_material

#: |μ_hs| at the quasi-static speed within which a law pressure passes (issue 41's
#: tolerance: a tenth of the smallest law friction worth tabulating on the CAPTIF cells).
QS_TOL = 0.005

#: Loss tangent of the rubber at the shortest high-slope wave's frequency below which the
#: cell counts as relaxed: the hysteretic friction of a slope-1 wave is of that order.
QS_LOSS_TANGENT = 1e-3

#: Label of the check's sweep tasks (followed by the pressure): FEM solves of the law cell
#: that are not law points (the validation report tells them apart by it).
QS_LABEL = "law cell quasi-static"

#: Slowest speed tried for the quasi-static point [mm/s] (decades down from 1 mm/s).
SLOWEST = 1e-12

#: Speed [mm/s] the quasi-static point is continued from: a steady point pressed there (the
#: middle of the speed range, where a press is cheapest), then the quasi-static speed from
#: its steady state (:func:`~rubbercontact.hybrid.tasks.fem_speed_path_task`); cheaper than
#: a fresh press at the quasi-static speed, with the same μ_hs (benchmarks/qs_tail.md).
TAIL_FROM = 10.0


def quasi_static_speed(material: GeneralizedMaxwell, wavelength: float,
                       loss_tangent: float = QS_LOSS_TANGENT) -> float:
    """The fastest decade speed [mm/s] (1, 0.1, …) below which the rubber's loss tangent
    at the frequency ``2π v/λ`` of ``wavelength`` λ [mm] stays at most ``loss_tangent``:
    the rubbery side of the loss peak (the glassy side is not relaxed however low its
    loss tangent).

    Raises
    ------
    ValueError
        If no speed down to :data:`SLOWEST` is that relaxed (a rubber with next to no
        equilibrium modulus has no quasi-static limit).
    """
    v = 10.0 ** -np.arange(int(round(-np.log10(SLOWEST))) + 1)      # 1 … SLOWEST, falling
    tan = np.asarray(material.loss_tangent(2 * np.pi * v / wavelength), float)
    # relaxed at v when every slower speed is too: the running maximum from the slow end
    relaxed = np.maximum.accumulate(tan[::-1])[::-1] <= loss_tangent
    if not relaxed.any():
        raise ValueError(f"no speed down to {SLOWEST:g} mm/s relaxes the rubber at the "
                         f"{wavelength:g} mm wave (loss tangent > {loss_tangent:g})")
    return float(v[np.argmax(relaxed)])


@dataclass(frozen=True)
class QuasiStaticCheck:
    """The law cell's friction at the quasi-static speed, per law pressure.

    Attributes
    ----------
    speed
        The quasi-static speed [mm/s] (:func:`quasi_static_speed`).
    pressure
        The law pressures checked [MPa], ascending.
    friction
        μ_hs at ``speed`` (NaN where the point did not converge).
    status
        ``"ok"`` or why the point stopped, per pressure.
    tol
        The tolerance on ``|friction|``.
    """

    speed: float
    pressure: np.ndarray
    friction: np.ndarray
    status: tuple[str, ...]
    tol: float = QS_TOL

    @property
    def failing(self) -> np.ndarray:
        """Pressures whose quasi-static friction exceeds the tolerance."""
        return np.isfinite(self.friction) & (np.abs(self.friction) > self.tol)

    @property
    def stopped(self) -> np.ndarray:
        """Pressures whose quasi-static point did not converge."""
        return ~np.isfinite(self.friction)

    def merged(self, other: QuasiStaticCheck) -> QuasiStaticCheck:
        """This check and ``other``'s pressures (another speed is an error)."""
        if other.speed != self.speed:
            raise ValueError("quasi-static checks at different speeds")
        p = np.concatenate([self.pressure, other.pressure])
        order = np.argsort(p, kind="stable")
        return QuasiStaticCheck(self.speed, p[order],
                                np.concatenate([self.friction, other.friction])[order],
                                tuple(np.array(self.status + other.status,
                                               dtype=object)[order]), self.tol)

    def describe(self) -> str:
        """One line: where the check passed, failed or stopped."""
        n = self.pressure.size
        passed = n - int(self.failing.sum()) - int(self.stopped.sum())
        text = (f"quasi-static check (μ_hs at {self.speed:g} mm/s within {self.tol:g} of 0): "
                f"{passed} of {n} law pressures pass")
        for name, mask in (("fail", self.failing), ("did not converge", self.stopped)):
            if mask.any():
                text += f"; {_pressures(self.pressure[mask])} MPa {name}"
        return text

    def warning(self) -> str | None:
        """One line if the cell is under-resolved at some pressure (None: it is not)."""
        if not self.failing.any():
            return None
        worst = int(np.nanargmax(np.where(self.failing, np.abs(self.friction), -np.inf)))
        return (f"law cell under-resolved: quasi-static friction {self.friction[worst]:.3g} "
                f"at {self.pressure[worst]:g} MPa (should vanish; tolerance {self.tol:g}) "
                f"at {_pressures(self.pressure[self.failing])} MPa; refine the cell "
                f"(fem.columns_per_wave) — docs/guide/law.md")

    def as_dataset(self) -> xr.Dataset:
        """On a ``law_pressure`` dimension, as a run's results carry it."""
        p = ("law_pressure", self.pressure, {"units": "MPa"})
        return xr.Dataset(
            {"law_quasi_static_friction": ("law_pressure", self.friction,
                                           {"units": "1", "velocity_mm_s": self.speed,
                                            "tolerance": self.tol,
                                            "long_name": "law cell friction at the "
                                                         "quasi-static speed"}),
             "law_quasi_static_status": ("law_pressure", np.array(self.status, dtype=str))},
            coords={"law_pressure": p})


def _pressures(p: np.ndarray) -> str:
    return ", ".join(f"{x:g}" for x in p)


def check_quasi_static(options: FemOptions, hs0: SineSeries, material: GeneralizedMaxwell,
                       pressures, runner) -> QuasiStaticCheck:
    """Run the quasi-static point of the law cell at each of ``pressures`` [MPa]: one
    cached sweep task each, on the law's FEM ``options`` without the transient fallback
    (``runner(tasks)`` returns the tasks' results in order)."""
    batch = quasi_static_batch(options, hs0, material, pressures)
    return batch.collect(runner(batch.tasks))


def quasi_static_batch(options: FemOptions, hs0: SineSeries, material: GeneralizedMaxwell,
                       pressures) -> Batch:
    """The tasks of :func:`check_quasi_static` and how to read the check from them, to run
    in one sweep with the law's own points (:func:`.batch.run_batches`)."""
    from ..sweep import Task

    p = np.sort(np.asarray(pressures, float))
    speed = quasi_static_speed(material, float(hs0.wavelengths.min()))
    opts = options.with_(steady={"fallback": False}).to_dict()
    # pressed at TAIL_FROM, then continued down to the quasi-static speed (in the path's
    # order: the faster speed, the middle of two, is pressed)
    tasks = [Task(function="rubbercontact.hybrid.tasks:fem_speed_path_task",
                  kwargs={"surface": hs0.as_dict(), "material": task_material(material),
                          "velocities": [speed, TAIL_FROM], "mean_pressure": float(pj),
                          "options": opts},
                  label=f"{QS_LABEL} p={pj:g} MPa",
                  cost=quasi_static_seconds(options, hs0, float(pj),
                                            material.equilibrium_modulus))
             # highest pressure first, as the law's own paths: the costliest point (up to
             # minutes on a graded cell) started last would run alone at the sweep's end
             for pj in p[::-1]]

    def collect(answers: list) -> QuasiStaticCheck:
        from .assemble import failure_message

        friction, status = [], []
        for res in answers[::-1]:                   # back to increasing pressure
            why = failure_message(res)
            if why is None:                         # the path's quasi-static point
                point = res.isel(velocity=0)
                why = None if str(point["status"].values) == "ok" else str(
                    point["status"].values)
            friction.append(np.nan if why else float(point["friction"]))
            status.append(why or "ok")
        return QuasiStaticCheck(speed, p, np.array(friction), tuple(status))

    return Batch(tasks, collect)


def add_quasi_static(ds: xr.Dataset, check: QuasiStaticCheck) -> xr.Dataset:
    """``ds`` with the check on its ``law_pressure`` (where it has one) and its line in
    ``attrs["law_quasi_static"]``; warns (:class:`~rubbercontact.hybrid.lawtable.LawWarning`,
    one line) if the cell is under-resolved at some pressure."""
    import warnings

    from ..hybrid.lawtable import LawWarning

    extra = check.as_dataset()
    if "law_pressure" in ds.coords:
        extra = extra.reindex(law_pressure=ds["law_pressure"].values)
    ds = ds.assign({k: extra[k] for k in extra.data_vars})
    ds.attrs["law_quasi_static"] = check.describe()
    message = check.warning()
    if message is not None:
        warnings.warn(message, LawWarning, stacklevel=3)
    return ds
