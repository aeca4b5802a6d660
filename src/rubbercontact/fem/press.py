"""The steady press under displacement control: the plate's height as the parameter.

Under load control (:func:`.newton_krylov.follow` in the load) the press of a steep cell
can stall part-way where the load-height curve of the cell is flat or folds back (a
contact patch jumping to the next crest): a load step past that point has no nearby
solution. Holding the plate's height instead, every step is a problem with a solution
close to the last one (the rubber is pushed a little further onto the
surface), and the load is an output: the height is moved in adaptive steps until the
plate's reaction passes the target, then the target is found between the last two
heights by regula falsi (Illinois) on the height. A state whose reaction is within the
Newton tolerance of the target *is* the load-controlled solution (its residual with the
plate free is the held residual plus the load mismatch), so no load-controlled Newton
through a fold is needed. It does not help where Newton fails for any small step of
either parameter (a contact point switching state within the step; most stalled presses
of the steep CAPTIF cells, docs/validation/steep_cells.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .newton_krylov import Counters, NewtonOutcome, newton_krylov
from .options import SteadyOptions
from .steady import SteadyCell


@dataclass(frozen=True, eq=False)
class HeightPoint:
    """A converged state at a held plate height."""

    height: float        # the plate's vertical displacement [mm]
    load: float          # the plate's reaction, pushing the rubber down [N/mm]
    U: np.ndarray
    newton: int          # Newton iterations it took


@dataclass(frozen=True, eq=False)
class PressOutcome:
    """The end of a press by height: the state at the target load, or how far it got."""

    U: np.ndarray
    converged: bool
    reason: str
    steps: int           # heights solved (converged or cut)


def compression_ramp(cell: SteadyCell) -> np.ndarray:
    """The unknowns' change per unit of plate travel under uniform vertical compression
    (0 at the face, 1 at the plate): the predictor of the next height."""
    m = cell.model
    ramp = np.zeros(m.n)
    ydof = m.dof_map.reshape(-1, 2)[:, 1]
    own = (ydof >= 0) & (ydof < m.plate)
    y = m.cell.X[own, 1]
    ramp[ydof[own]] = (y - m.cell.y0) / m.cell.height
    ramp[m.plate] = 1.0
    return ramp


class HeightPress:
    """Solves the cell at held plate heights (see the module docstring).

    Parameters
    ----------
    cell
        The steady cell (kernel and all), plate free.
    load
        Target plate load [N/mm].
    atol
        Newton tolerance [N/mm] (also on the load mismatch at the end).
    """

    def __init__(self, cell: SteadyCell, load: float, atol: float, options: SteadyOptions,
                 counters: Counters) -> None:
        self.free = cell
        self.held = cell.holding(np.array([cell.model.plate]))
        self.load, self.atol = float(load), float(atol)
        self.options, self.counters = options, counters
        self.ramp = compression_ramp(cell)
        self.plate = cell.model.plate
        self.solves = 0

    def at(self, U: np.ndarray, height: float, prev: HeightPoint | None = None
           ) -> tuple[HeightPoint | None, NewtonOutcome]:
        """The state at ``height`` from ``U``: extrapolated along the secant from ``prev``
        if given, else moved there by the compression ramp."""
        dh = height - U[self.plate]
        if prev is not None and prev.height != U[self.plate]:
            V = U + dh / (U[self.plate] - prev.height) * (U - prev.U)
        else:
            V = U + dh * self.ramp
        res = newton_krylov(self.held, V, 0.0, 0.0, "face", self.atol, self.options,
                            self.counters)
        self.solves += 1
        self.counters.continuation_steps += 1
        if not res.converged:
            return None, res
        # evaluated with zero load, the plate's residual is minus its reaction
        return HeightPoint(height, -float(res.ev.forces[self.plate]), res.U,
                           len(res.residuals) - 1), res

    def run(self, U0: np.ndarray, first_step: float, min_step: float) -> PressOutcome:
        """From the state ``U0`` (at its plate height) to the target load: the plate is
        moved down while its reaction is below the target, up while above, until the
        target is bracketed. ``first_step`` and ``min_step`` are plate travels [mm]."""
        last, res = self.at(U0, float(U0[self.plate]))
        if last is None:
            return PressOutcome(U0, False, f"start: {res.reason}", self.solves)
        down = last.load < self.load
        step, prev, cut = first_step, None, False
        while self.solves < self.options.max_steps:
            if (last.load >= self.load) == down:     # passed the target
                return self._bracketed(prev or last, last)
            point, res = self.at(last.U, last.height + (-step if down else step), prev)
            if point is None:
                self.counters.cut_steps += 1
                cut = True
                step *= 0.5
                if step < min_step:
                    return PressOutcome(last.U, False, f"stopped at {last.load / self.load:.3g}"
                                        f" of the load (height step {step:.2g} mm): "
                                        f"{res.reason}", self.solves)
                continue
            prev, last = last, point
            if point.newton <= 5 and not cut:   # a step just cut is not grown again at once
                step *= 2.0
            cut = False
            # the secant stiffness of the last step: aim a little beyond the target (the
            # contact stiffens, so the secant over-estimates the travel that is left)
            slope = (last.load - prev.load) / (prev.height - last.height)
            if slope > 0:
                step = min(step, 1.25 * abs(self.load - last.load) / slope + min_step)
        return PressOutcome(last.U, False, f"{self.options.max_steps} heights solved, "
                            f"{last.load / self.load:.3g} of the load reached", self.solves)

    def _bracketed(self, a: HeightPoint, b: HeightPoint) -> PressOutcome:
        """Regula falsi (Illinois) on the height between ``a`` (below the load) and ``b``."""
        fa, fb = a.load - self.load, b.load - self.load
        for _ in range(self.options.newton_per_step):
            best = a if abs(fa) < abs(fb) else b
            if abs(best.load - self.load) <= 0.5 * self.atol:
                return self._release(best)
            if fb == fa:
                break
            h = b.height - fb * (b.height - a.height) / (fb - fa)
            t = (h - a.height) / (b.height - a.height)
            point, res = self.at(a.U + t * (b.U - a.U), h)
            if point is None:
                return PressOutcome(best.U, False, f"bracket: {res.reason}", self.solves)
            fc = point.load - self.load
            if fc * fb < 0:
                a, fa = b, fb
            else:
                fa *= 0.5          # Illinois: the end kept twice has its value halved
            b, fb = point, fc
        best = a if abs(fa) < abs(fb) else b
        return self._release(best)

    def _release(self, point: HeightPoint) -> PressOutcome:
        """The held state as the load-controlled solution: checked, and polished by the
        free Newton if its load mismatch is not yet within the tolerance."""
        res = newton_krylov(self.free, point.U, 0.0, self.load, "face", self.atol,
                            self.options, self.counters)
        if res.converged:
            return PressOutcome(res.U, True, "", self.solves)
        return PressOutcome(point.U, False, f"load {point.load / self.load:.6g} of the target "
                            f"at the last height; freeing the plate: {res.reason}",
                            self.solves)
