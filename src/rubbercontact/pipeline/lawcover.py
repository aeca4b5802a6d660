"""A law that covers the run: its FEM pressures extended until the low-slope solve's local
pressures lie inside them (issue 41, item 3).

The hybrid models read the high-slope law at the local pressures of their low-slope solve;
beyond the law's highest successful FEM point the law follows the linear law's shape
anchored there (:func:`~rubbercontact.hybrid.law.continue_with_linear_shape`), an
extrapolation. After the models ran, :func:`coverage` compares, per computed speed, the
highest local pressure of the law models with the law's top; :func:`plan_extension` puts
new FEM pressures on a half-decade ladder above the top at each speed that is not covered,
up to the first rung at or above the local pressure, and :func:`describe` says in one line
what was extended and what could not be. A speed stops extending where a FEM point above
its top was tried and did not give a law point (failed, impaled, non-monotone): the FEM
cell says there where it stops holding, and the run says so instead of trying again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..fem.loadrange import outside_range
from ..fem.result import BULK_SHEAR_LIMIT, BULK_SHEAR_STUDY
from ..hybrid.lawtable import NOT_COMPUTED, law_top
from ..models.registry import needs_law

#: Rungs per decade of the pressure ladder the law is extended on (1, 3.16, 10, … MPa).
RUNGS_PER_DECADE = 2

#: Relative excess of the local pressure over the law's top that counts as covered: the
#: low-slope solve's peak is read to its solver tolerance, and a top equal to it is covered.
COVERED_RTOL = 0.02

#: Rounds of extension (each round: FEM at the new pressures, then the law models again).
MAX_ROUNDS = 3

#: Status of a law grid point that was not computed (its speed did not need the pressure).
NOT_NEEDED = NOT_COMPUTED


@dataclass(frozen=True)
class Coverage:
    """Per computed speed, the law models' highest local pressure against the law's top.

    Attributes
    ----------
    speeds
        Computed speeds [mm/s] (the reduced speeds of a run with temperatures).
    reached
        Highest local pressure of the low-slope solves of the law models [MPa] (NaN where
        none converged).
    tops
        Highest pressure of the law's successful FEM points at that speed [MPa].
    """

    speeds: np.ndarray
    reached: np.ndarray
    tops: np.ndarray

    @property
    def uncovered(self) -> np.ndarray:
        """Mask of the speeds whose local pressures go beyond the law's FEM points."""
        with np.errstate(invalid="ignore"):
            return self.reached > self.tops * (1 + COVERED_RTOL)


@dataclass(frozen=True)
class Extension:
    """New FEM law points and the speeds that could not be extended.

    Attributes
    ----------
    points
        ``{pressure [MPa]: speeds [mm/s]}``: the FEM points to add.
    stopped
        ``{speed [mm/s]: reason}``: speeds not covered that are not extended (a FEM point
        above the top was tried and did not give a law point, or the next rung is beyond
        the bound).
    """

    points: dict[float, list[float]]
    stopped: dict[float, str]


def coverage(ds: xr.Dataset, law: xr.Dataset) -> Coverage:
    """:class:`Coverage` of a run's assembled results ``ds`` (dims ``model, velocity, ...``,
    with ``max_local_pressure``) by the screened law table ``law``."""
    speeds = np.asarray(ds["velocity"].values, float)
    models = [m for m in ds["model"].values if needs_law(str(m))]
    reached = np.full(speeds.size, np.nan)
    if models:
        local = ds["max_local_pressure"].sel(model=models)
        other = [d for d in local.dims if d != "velocity"]
        with np.errstate(invalid="ignore"):
            values = local.transpose("velocity", *other).values.reshape(speeds.size, -1)
        finite = np.isfinite(values)
        reached = np.where(finite.any(axis=1),
                           np.nanmax(np.where(finite, values, -np.inf), axis=1), np.nan)
    tops = np.array([law_top(law, float(v)) for v in speeds])
    return Coverage(speeds, reached, tops)


def ladder_above(top: float, needed: float) -> list[float]:
    """Rungs of the half-decade ladder above ``top`` up to the first at or above ``needed``
    [MPa]."""
    k = math.floor(RUNGS_PER_DECADE * math.log10(top) + 1e-9) + 1
    rungs = []
    while True:
        p = round(10 ** (k / RUNGS_PER_DECADE), 12)
        rungs.append(p)
        if p >= needed:
            return rungs
        k += 1


def plan_extension(cov: Coverage, law: xr.Dataset, max_pressure: float,
                   relaxed_modulus: float) -> Extension:
    """The FEM points that extend the law over ``cov``'s uncovered speeds.

    A speed is not extended past a FEM point above its top that was tried and gave no law
    point (its status says why), nor to a pressure where the cell would shear as a whole
    beyond :data:`~rubbercontact.fem.result.BULK_SHEAR_LIMIT`: the bulk shear grows
    as the friction stress ``μ p̄`` (docs/validation/cell_creep.md), so the top point's
    shear scaled by the pressure ratio predicts it.

    Parameters
    ----------
    cov
        The run's coverage.
    law
        The screened law table (every FEM point tried, with its status).
    max_pressure
        Highest pressure a law point may have [MPa] (``law.max_pressure``; inf: none).
    relaxed_modulus
        The rubber's relaxed modulus ``E∞`` [MPa]: a law point's pressure stays at or below
        it. The cell's mean compression is static in steady sliding, so above ``E∞`` its
        strains are very large and the FEM warns of slow or failing convergence; on the
        steep CAPTIF cell the low speeds (μ small, so no bulk shear to stop the ladder)
        otherwise climbed to 31.6 MPa, where the steady solve and its rescue failed.
    """
    points: dict[float, list[float]] = {}
    stopped: dict[float, str] = {}
    bad = cov.uncovered
    for v, reached, top in zip(cov.speeds[bad], cov.reached[bad], cov.tops[bad], strict=True):
        row = law.sel(velocity=float(v), method="nearest")
        reason = _stop_reason(row, top)
        for p in [] if reason else ladder_above(top, reached):
            reason = _beyond_bounds(row, top, p, max_pressure, relaxed_modulus)
            if reason:
                break
            points.setdefault(p, []).append(float(v))
        if reason and not any(float(v) in vs for vs in points.values()):
            stopped[float(v)] = reason
    return Extension(points, stopped)


def _stop_reason(row: xr.Dataset, top: float) -> str | None:
    """Why the law at this speed is not extended past ``top`` (None: it can be)."""
    if top <= 0:
        return "the law has no FEM point at this speed"
    p, status = row["pressure"].values, row["status"].values
    failed = [j for j in np.argsort(p) if p[j] > top and status[j] != "ok"
              and not str(status[j]).startswith(NOT_NEEDED)]
    if failed:
        return f"FEM at {p[failed[0]]:g} MPa: {_short(str(status[failed[0]]))}"
    return None


def _beyond_bounds(row: xr.Dataset, top: float, rung: float, max_pressure: float,
                   relaxed_modulus: float) -> str | None:
    """Why the rung ``rung`` [MPa] above ``top`` is not computed (None: it is)."""
    if rung > max_pressure:
        return f"{rung:.3g} MPa is beyond law.max_pressure = {max_pressure:g} MPa"
    outside = outside_range(rung, relaxed_modulus)
    if outside:
        return outside
    predicted = predicted_shear(row, rung)
    if predicted > BULK_SHEAR_LIMIT:
        return (f"at {rung:.3g} MPa the cell would shear as a whole by about {predicted:.2g} "
                f"(friction stress above E∞/3; {BULK_SHEAR_STUDY})")
    return None


def predicted_shear(row: xr.Dataset, pressure: float) -> float:
    """The cell's bulk shear at ``pressure`` [MPa] from the law's two highest successful
    points at one speed (NaN when not recorded).

    The shear grows as the friction stress ``μ p̄``, and μ itself grows with the load, so
    the power law through the two points is extrapolated, with an exponent of at least 1
    (on the section 3 cell, 0.2 → 0.5 → 1 MPa gave 1.55 and 1.31).
    """
    if "bulk_shear" not in row:
        return np.nan
    ok = (row["status"].values == "ok") & np.isfinite(row["bulk_shear"].values)
    p, g = row["pressure"].values[ok], row["bulk_shear"].values[ok]
    if p.size == 0:
        return np.nan
    order = np.argsort(p)[-2:]
    p, g = p[order], g[order]
    k = 1.0
    if p.size == 2 and g[0] > 0 and g[1] > 0:
        k = max(1.0, math.log(g[1] / g[0]) / math.log(p[1] / p[0]))
    return float(g[-1] * (pressure / p[-1]) ** k)


def merge_points(raw: xr.Dataset, new: xr.Dataset) -> xr.Dataset:
    """The law table ``raw`` with the computed points of ``new`` (same speeds) put in: on
    the union of their pressures, ``new``'s point wherever it was computed."""
    p = np.union1d(raw["pressure"].values, new["pressure"].values)
    old_r, new_r = (_on_pressures(t, p) for t in (raw, new))
    computed = ~np.char.startswith(new_r["status"].values.astype(str), NOT_NEEDED)
    out = old_r.copy()
    for k in new_r.data_vars:
        if k in out:
            out[k] = (out[k].dims, np.where(computed, new_r[k].values, out[k].values),
                      out[k].attrs)
    return out


def _on_pressures(table: xr.Dataset, p: np.ndarray) -> xr.Dataset:
    """``table`` on the pressures ``p``, the added points not computed."""
    return table.reindex(pressure=p, fill_value={"status": NOT_NEEDED})


def _short(text: str, n: int = 90) -> str:
    text = " ".join(text.split())
    return text if len(text) <= n else text[: n - 1] + "…"


def describe(cov: Coverage, added: list[float], stopped: dict[float, str],
             rounds: int) -> str:
    """One line (lower case, for ``law: …``): what the extension added and whether the law
    now covers the run."""
    done = (f"extended in {rounds} round(s) by FEM points at "
            f"{', '.join(f'{p:.3g}' for p in sorted(added))} MPa; " if added else "")
    bad = cov.uncovered
    if not bad.any():
        return f"{done}the law covers the local pressures at every speed"
    worst = int(np.nanargmax(np.where(bad, cov.reached / np.maximum(cov.tops, 1e-300), -1)))
    v = float(cov.speeds[worst])
    reason = stopped.get(v, f"not extended after {MAX_ROUNDS} rounds")
    text = (f"{done}at {int(bad.sum())} of {bad.size} speeds the local pressures exceed the "
            f"law's FEM points, the law is extrapolated (worst v = {v:.3g} mm/s: "
            f"{cov.reached[worst]:.3g} MPa against {cov.tops[worst]:.3g} MPa; {reason})")
    return text
