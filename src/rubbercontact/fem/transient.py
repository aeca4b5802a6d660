"""The time-stepped sliding test (paper §2.4, Fig. 4): press, settle, slide.

1. *Press*: the rigid plate on the top edge is loaded from 0 to ``p̄ L0`` in a few
   steps (the face starts touching the highest surface point).
2. *Settle*: the load is held while the viscous branches relax (default ``5 τ_max``
   before sliding, ``100 τ_max`` for ``v = 0``), with geometrically growing steps —
   exact for the exponential integrator.
3. *Slide*: the surface moves by ``L0/steps_per_period`` per step (``dt =
   L0/(steps_per_period · v)``; default one element of travel per step), the state one
   element back shifted with the surface as predictor. After each whole period the
   period averages are compared; once friction and contact fraction of two successive
   periods agree within ``steady_tol`` the last period is the result.

The bulk creeps in shear on the material's longest retardation time, more slowly than
successive period averages reveal; ``min_sliding_time`` slides longer, and the steady
solver (:mod:`.steady_solver`) solves the settled state directly.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, replace

import numpy as np

from ..errors import ConvergenceError
from .cell import Evaluation
from .constitutive import ViscousState, cauchy_from_pk2
from .contact import face_contact_fraction, mean_separation, segment_penetration
from .options import FemOptions
from .result import (
    BULK_SHEAR_LIMIT,
    SEGMENT_PENETRATION_LIMIT,
    SlidingTestResult,
    SolverStats,
    bulk_shear_message,
    face_profile,
    impaled_message,
)
from .setup import CellSetup, build_cell
from .solver import NewtonFailure, SolverCounters, newton

PHASES = ("press", "settle", "slide")
HISTORY_KEYS = ("time", "sliding_distance", "phase", "friction", "friction_top",
                "contact_fraction", "mean_separation", "plate_displacement", "load",
                "max_penetration", "segment_penetration", "newton_iterations", "face_shift")


@dataclass
class _State:
    U: np.ndarray
    visc: ViscousState
    t: float
    s: float
    load: float
    ev: Evaluation | None = None


class TransientTest:
    """One time-stepped sliding test: :meth:`press`, :meth:`settle`, :meth:`slide`, then
    :meth:`result` (or :meth:`run` for all four).

    Parameters
    ----------
    surface, material, mean_pressure, velocity
        The test (checked by :func:`rubbercontact.fem.sliding_test`).
    options
        Cell, numerics and the transient controls (``options.transient``).
    progress
        Optional callable ``progress(phase, step, time, friction)``.
    newton_budget
        Newton iterations the whole test may spend (None: no bound beyond its periods);
        past them it stops with a :class:`~rubbercontact.errors.ConvergenceError` that
        says how far it slid (the steady solve's fallback, ``steady.fallback_budget``).
    """

    def __init__(self, surface, material, mean_pressure: float, velocity: float,
                 options: FemOptions, progress=None, newton_budget: int | None = None
                 ) -> None:
        self.wall0 = time.perf_counter()
        self.newton_budget = newton_budget
        self.surface, self.material = surface, material
        self.p, self.v = float(mean_pressure), float(velocity)
        self.options, self.opts = options, options.transient
        self.progress = progress
        self.spp = options.steps_per_period
        L0 = surface.period
        periods, min_periods = self.opts.periods, self.opts.min_periods
        if self.v > 0 and self.opts.min_sliding_time > 0:
            # whole periods: the steadiness check compares period averages
            need = int(np.ceil(self.opts.min_sliding_time * self.v / L0 - 1e-9))
            min_periods = max(min_periods, need)
            periods = max(periods, min_periods)
        self.periods, self.min_periods = periods, min_periods
        self.setup: CellSetup = build_cell(surface, material, self.p, self.v, options,
                                           steps_per_period=self.spp)
        self.model = self.setup.model
        params = self.setup.params
        self.tau_max = float(params.tau.max()) if params.n_branches else 0.0
        self.dt_slide = self.setup.dt if self.v > 0 else None
        self.dt_press = self.dt_slide if self.v > 0 else (
            self.tau_max / 100 if self.tau_max > 0 else 1.0)
        self.counters = SolverCounters()
        self.hist: dict[str, list] = {k: [] for k in HISTORY_KEYS}
        self.info = {"cutbacks": 0, "max_pen": 0.0, "max_seg_pen": 0.0, "steps": 0,
                     "impaled": False}
        self.n_periods = 0
        self.steady = self.v == 0
        self.period_change = self.area_change = np.nan
        # Converged sliding states of the last element width of travel, by sliding
        # distance: in steady sliding the field at s is the field at s − h shifted by one
        # whole column, an exact roll, a far better predictor than interpolating the last
        # state by a fraction of a column (measured at 120 x 90, 240 steps per period:
        # 8.6 Newton iterations per step with the interpolation).
        self.recent: dict[int, np.ndarray] = {}
        s0 = float(self.opts.surface_offset)
        self.state = _State(np.zeros(self.model.n), self.model.new_state(), 0.0, s0, 0.0)

    # -- the protocol ------------------------------------------------------------------
    def press(self) -> None:
        n = self.opts.press_steps
        for _ in range(n):
            self.state, it = self._advance(self.state, self.dt_press, 0.0,
                                           self.setup.load / n, 0, False)
            self._record(self.state, 0, it)

    def settle(self) -> None:
        settle_time = self.opts.settle_time
        if settle_time is None:
            settle_time = (5.0 if self.v > 0 else 100.0) * self.tau_max
        if settle_time <= 0 or not self.setup.params.n_branches:
            return
        t_end = self.state.t + settle_time
        dt = 2 * self.dt_press
        while self.state.t < t_end * (1 - 1e-12):
            self.state, it = self._advance(self.state, min(dt, t_end - self.state.t), 0.0, 0.0,
                                           0, False)
            self._record(self.state, 1, it)
            dt *= 3.0

    def slide(self) -> None:
        if self.v <= 0:
            return
        self._slow_branch_start()
        nx = self.setup.cell.nx
        ds = self.surface.period / self.spp
        means = []
        for k in range(self.periods):
            for _ in range(self.spp):
                self.state, it = self._advance(self.state, self.dt_slide, ds, 0.0, 0, True)
                self.recent[round(self.state.s / self.setup.cell.hx * 1e6)] = self.state.U
                self._forget_old()
                self._record(self.state, 2, it)
            self.n_periods = k + 1
            sl = slice(-self.spp, None)
            means.append((np.mean(self.hist["friction"][sl]),
                          np.mean(self.hist["contact_fraction"][sl])))
            if self.n_periods >= max(self.min_periods, 2):
                (m0, a0), (m1, a1) = means[-2], means[-1]
                # Relative agreement with absolute floors for (near-)zero friction; α moves
                # in jumps of the face nodes: allow a quarter of one element's share.
                if (abs(m1 - m0) <= self.opts.steady_tol * abs(m1) + 1e-4
                        and abs(a1 - a0) <= max(self.opts.steady_tol * abs(a1), 0.25 / nx)):
                    self.steady = True
                    break
        if len(means) >= 2:
            (m0, a0), (m1, a1) = means[-2], means[-1]
            self.period_change = abs(m1 - m0) / max(abs(m1), 1e-12)
            self.area_change = abs(a1 - a0) / max(abs(a1), 1e-12)
        if not self.steady:
            warnings.warn(f"FEM sliding test: period averages still change by "
                          f"{100 * self.period_change:.1f} % (μ) after {self.periods} periods "
                          f"(p̄ = {self.p:g} MPa, v = {self.v:g} mm/s); slide longer or use "
                          f"the steady solver", RuntimeWarning, stacklevel=3)

    def run(self) -> SlidingTestResult:
        self.press()
        self.settle()
        self.slide()
        return self.result()

    # -- steps -------------------------------------------------------------------------
    def _slow_branch_start(self) -> None:
        """Branches much slower than a period see, in steady sliding, the oscillation of
        ``S_iso`` about its row average: start them there instead of from the static
        imprint of the pressed peak, which would decay only as ``exp(−t/τ)``. Only the
        initial condition changes (Simo's stress-like variables only)."""
        params = self.setup.params
        if not (self.opts.slow_branch_start and params.n_branches
                and params.viscous_model == "simo"):
            return
        slow = params.tau > 0.1 * self.surface.period / self.v
        if not np.any(slow):
            return
        st = self.state
        nx, ny = self.setup.cell.nx, self.setup.cell.ny
        s_iso = st.visc.s_iso.reshape(ny, nx, 4, 3)
        dev = (s_iso - s_iso.mean(axis=1, keepdims=True)).reshape(st.visc.s_iso.shape)
        q = st.visc.q.copy()
        q[slow] = params.beta[slow, None, None, None] * dev[None]
        self.state = _State(st.U, replace(st.visc, q=q), st.t, st.s, st.load, st.ev)

    def _forget_old(self) -> None:
        hx = self.setup.cell.hx
        for key in [k for k in self.recent if k * hx / 1e6 < self.state.s - 1.01 * hx]:
            del self.recent[key]

    def _predict(self, st: _State, ds: float, depth: int) -> np.ndarray:
        hx = self.setup.cell.hx
        key = round((st.s + ds - hx) / hx * 1e6)
        # not inside cut-backs: a step that needed halving is not steady, and there the
        # progress of the last sub-step is worth more than the state one element back
        if depth == 0 and key in self.recent:
            return self.model.predictor(self.recent[key], hx, key * hx / 1e6)
        return self.model.predictor(st.U, ds, st.s)

    def _advance(self, st: _State, dt: float, ds: float, dload: float, depth: int,
                 predictor_shift: bool) -> tuple[_State, int]:
        U0 = self._predict(st, ds, depth) if (predictor_shift and ds != 0) else st.U
        self._check_budget(st)

        def res(U, tangent):
            return self.model.evaluate(U, st.visc, dt, st.s + ds, st.load + dload, tangent)

        try:
            U, ev, h = newton(res, U0, atol=self.setup.atol, max_iter=self.options.max_newton,
                              counters=self.counters,
                              max_step=self.opts.newton_max_step * self.setup.h_min)
        except NewtonFailure as fail:
            if depth >= self.opts.max_cutbacks:
                raise ConvergenceError(
                    f"FEM step failed after {self.opts.max_cutbacks} cut-backs at t = "
                    f"{st.t:.6g} s (s = {st.s:.6g} mm, dt = {dt:.3g} s): {fail.reason}",
                    diagnostics={"step": self.info["steps"], "time": st.t, "dt": dt,
                                 "sliding_distance": st.s, "residual_history": fail.history,
                                 "cutbacks": self.info["cutbacks"]},
                    last_state=self._snapshot(st)) from None
            self.info["cutbacks"] += 1
            mid, n1 = self._advance(st, dt / 2, ds / 2, dload / 2, depth + 1, predictor_shift)
            end, n2 = self._advance(mid, dt / 2, ds / 2, dload / 2, depth + 1, predictor_shift)
            return end, n1 + n2
        return (_State(U, ev.elements.state, st.t + dt, st.s + ds, st.load + dload, ev),
                len(h) - 1)

    def _check_budget(self, st: _State) -> None:
        """Stop, keeping the last state, once the Newton budget is spent."""
        spent = self.counters.newton_iterations
        if self.newton_budget is None or spent < self.newton_budget:
            return
        slid = st.s - self.opts.surface_offset
        if slid > 0:
            where = f"after {slid / self.surface.period:.2f} of {self.periods} periods slid"
        else:
            where = "while settling" if st.load >= self.setup.load * (1 - 1e-12) else (
                "while pressing")
        raise ConvergenceError(
            f"transient test stopped: its budget of {self.newton_budget} Newton iterations "
            f"is spent {where}",
            diagnostics={"newton_iterations": spent, "time": st.t, "sliding_distance": st.s,
                         "periods_slid": self.n_periods, "cutbacks": self.info["cutbacks"]},
            last_state=self._snapshot(st))

    def _snapshot(self, st: _State) -> dict:
        return {"U": st.U.copy(), "time": st.t, "sliding_distance": st.s, "load": st.load,
                "history": {k: np.asarray(v) for k, v in self.hist.items()}}

    def _record(self, st: _State, phase: int, iters: int) -> None:
        model, hist, L0 = self.model, self.hist, self.surface.period
        cs = st.ev.contact
        pos = model.face_positions(st.ev.u_full)
        f_full = model.asm.full_vector(st.ev.elements.fe)
        pen = float(np.max(-cs.gap[cs.active], initial=0.0))
        self.info["max_pen"] = max(self.info["max_pen"], pen)
        seg_pen = segment_penetration(self.surface, st.s, pos, L0)
        self.info["max_seg_pen"] = max(self.info["max_seg_pen"], seg_pen)
        load_full = self.setup.load
        row = {"time": st.t, "sliding_distance": st.s, "phase": phase,
               "friction": -float(cs.force[:, 0].sum()) / load_full,
               "friction_top": float(f_full[2 * self.setup.cell.top_nodes].sum()) / load_full,
               "contact_fraction": face_contact_fraction(self.surface, st.s, cs, L0),
               "mean_separation": mean_separation(pos[:, 0], pos[:, 1], L0),
               "plate_displacement": float(st.U[model.plate]), "load": st.load / L0,
               "max_penetration": pen, "segment_penetration": seg_pen,
               "newton_iterations": iters,
               # the top edge is held at x = 0: the face's mean x-displacement is the
               # cell's bulk shear lag (times H)
               "face_shift": float(np.mean(pos[:, 0] - model.X_face[:, 0]))}
        for k, val in row.items():
            hist[k].append(val)
        hx = self.setup.cell.hx
        # A smooth face misses a curved surface by its chord sag; half an element means an
        # asperity has gone through the face between two nodes: the rubber is impaled.
        if phase == 2 and seg_pen > SEGMENT_PENETRATION_LIMIT * hx and not self.info["impaled"]:
            self.info["impaled"] = True
            warnings.warn(impaled_message(seg_pen, hx, self.p, self.v), RuntimeWarning,
                          stacklevel=4)
        self.info["steps"] += 1
        if self.progress is not None:
            self.progress(PHASES[phase], self.info["steps"], st.t, hist["friction"][-1])

    # -- result ------------------------------------------------------------------------
    def result(self) -> SlidingTestResult:
        H = self.setup.cell.height
        spp = self.spp
        shift = np.asarray(self.hist["face_shift"])
        bulk_shear = float(abs(shift[-1]) / H)
        bulk_change = (float((abs(shift[-1]) - abs(shift[-spp - 1])) / H)
                       if self.v > 0 and self.n_periods >= 1 else np.nan)
        if bulk_shear > BULK_SHEAR_LIMIT:
            warnings.warn(bulk_shear_message(bulk_shear, self.p, self.v, "transient"),
                          RuntimeWarning, stacklevel=3)
        hist = {k: np.asarray(v, dtype=int if k in ("phase", "newton_iterations") else float)
                for k, v in self.hist.items()}
        window = slice(-spp, None) if self.v > 0 else slice(-1, None)
        mu = float(np.mean(hist["friction"][window]))
        st = self.state
        out = st.ev.elements
        c = self.counters
        stats = SolverStats(
            solver="transient", newton_iterations=c.newton_iterations,
            factorizations=c.factorizations, wall_time=time.perf_counter() - self.wall0,
            assembly_time=c.assembly_time, solve_time=c.solve_time, n_unknowns=self.model.n,
            steady=bool(self.steady), max_penetration=self.info["max_pen"],
            max_segment_penetration=self.info["max_seg_pen"], bulk_shear=bulk_shear,
            impaled=bool(self.info["impaled"]),
            surface_offset=float(self.opts.surface_offset), steps=self.info["steps"],
            cutbacks=self.info["cutbacks"], line_search_cuts=c.line_search_cuts,
            periods=self.n_periods, period_change=float(self.period_change),
            period_area_change=float(self.area_change), bulk_shear_change=bulk_change)
        ue = st.ev.u_full[self.model.asm.edofs].reshape(-1, 4, 2)
        return SlidingTestResult(
            friction=mu, shear_stress=mu * self.p,
            contact_fraction=float(np.mean(hist["contact_fraction"][window])),
            mean_separation=float(np.mean(hist["mean_separation"][window])),
            mean_pressure=self.p, velocity=self.v,
            pressure_profile=face_profile(self.model, st.ev.contact, st.ev.u_full, st.s),
            history=hist, stats=stats, width=self.surface.period, height=H,
            mesh=tuple(self.options.mesh), material=self.material.as_dict(),
            surface=self.surface.as_dict(), element_coordinates=self.setup.cell.Xe + ue,
            element_stress=cauchy_from_pk2(out.F, out.S).mean(axis=1), sliding_distance=st.s)
