r"""Steady sliding of a rigid periodic surface on a viscoelastic half-space (paper §2.3).

Model (paper eqs. 18–24)
------------------------
A rigid surface ``z(x)`` (``<z> = 0``) slides at constant speed over a linear viscoelastic
half-space. In the frame of the surface all fields are steady. The local separation is

.. math:: u(x) = \bar u + w(x) - z(x)                                        \qquad (18)

with the surface displacement of the rubber (positive away from the surface) given in Fourier
space by

.. math:: w(q) = M(q)\,\sigma(q),\qquad M(q) = \frac{2}{|q|\,E_r(\omega)},\qquad
          E_r = \frac{E(\omega)}{1-\nu^2}                                   \qquad (21–23)

where ``σ >= 0`` is the compressive contact pressure [MPa]. The ``q = 0`` mode of ``w`` is 0:
the mean separation ``ū = <u>`` carries the mean, and the mean pressure ``σ0 = <σ>`` is imposed
(``ū`` is an unknown). In 2D, ``|q| = sqrt(q_x² + q_y²)`` and sliding is along ``x`` (last axis).

Interaction: either a hard wall (``law=None``: ``u >= 0``, ``σ >= 0``, ``u σ = 0``,
complementarity) or a local law ``σ = f(u)`` (eq. 24, :mod:`rubbercontact.halfspace.laws`).

Sign convention
---------------
Fourier modes are ``exp(+i q x)`` (numpy/scipy ``irfft``). ``velocity = v > 0`` means the *rubber*
moves in ``+x`` relative to the rigid surface; a rubber point then sees the mode ``exp(i q x)`` as
``exp(i q v t)``, so the frequency is ``ω = +q_x v`` (``q_x >= 0`` on the rfft half-grid). With
the material convention ``E(ω) = E∞ + Σ E_i iωτ_i/(1 + iωτ_i)`` (loss modulus >= 0 for ``ω > 0``)
the pressure is higher on the flanks with ``dz/dx > 0`` (the rubber runs into them) and the
hysteretic friction is positive. ``v = 0`` gives the relaxed (rubbery) elastic response ``E∞``.

Outputs and definitions
-----------------------
* ``friction_ls = <σ ∂z/∂x>/σ0`` (eq. 7), with the exact derivative of ``z`` (analytic for a
  :class:`~rubbercontact.roughness.SineSeries`, spectral for sampled heights). Energy balance:
  ``<σ ∂z/∂x> = <σ ∂w/∂x>`` since ``<f(u) ∂u/∂x> = 0`` for a periodic ``u``.
* ``friction_hs = <Δτ(u)>/σ0`` (eq. 6) when the law carries a shear-stress table, else 0.
* ``friction = friction_ls + friction_hs`` (total μ).
* ``contact_fraction``: hard wall: fraction of grid points with ``σ > 0``; a law carrying
  ``α(u)``: ``<H(σ) α(u)>`` (eq. 8); any other law: fraction of points where the law is in its
  repulsive contact range (``law.in_contact(u)``; e.g. ``u < 2ℓ`` for the Lennard-Jones wall).

Algorithms
----------
All operators are applied with one ``rfftn``/``irfftn`` pair on a precomputed kernel
(:mod:`~rubbercontact.halfspace.problem`), and every algorithm reduces to linear systems on a
contact set (:mod:`~rubbercontact.halfspace.contact_set`). Which one runs:

* hard wall, elastic material or ``v = 0``: the primal–dual active-set iteration (started
  from coarser grids on maps), or Polonsky–Keer with ``method="pk"``
  (:mod:`~rubbercontact.halfspace.hardwall`);
* hard wall, viscoelastic: the projection method in the metric of ``Re M`` with active-set
  polishing, started from coarser grids (:mod:`~rubbercontact.halfspace.hardwall`);
* a single law: Newton from the exact hard-wall solution, the mixed (inverse-law) Newton for a
  Lennard-Jones wall (:mod:`~rubbercontact.halfspace.newton`);
* a Lennard-Jones wall + soft law (the hybrid method's law): hard wall + soft law by a
  semismooth active-set Newton, then Newton on the full law; continuation in the soft member
  as the fallback (:mod:`~rubbercontact.halfspace.walls`).

The switches between the fast paths and the plain ones they replace are the fields of
:class:`~rubbercontact.halfspace.options.SolverOptions`. Iteration counts and timings are
measured in ``benchmarks/halfspace.md`` (``benchmarks/bench_halfspace.py``).

Resolution note: for a viscoelastic material whose glassy relaxation length ``v τ_min`` is far
below the grid step, the leading contact edge is not resolved and the pressure shows
grid-scale (odd–even) oscillations there; integral quantities (μ, area, ``ū``) converge under
refinement (tested).

Failures raise :class:`~rubbercontact.errors.ConvergenceError` with the iteration history and the
last state (a :class:`SlidingResult` with ``converged=False``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from .._validation import positive_scalar
from ..errors import ConvergenceError, InputError
from ..materials.protocol import Material, check_material
from . import kernels as kn
from .hardwall import (
    hard_wall_active_set,
    hard_wall_elastic,
    hard_wall_pk,
    hard_wall_viscoelastic,
)
from .laws import InteractionLaw, Law, check_law
from .newton import solve_single_law
from .options import SolverOptions
from .problem import Grid, Problem, Solution, sample_surface
from .walls import solve_wall_soft, split_law

__all__ = ["SlidingResult", "SolverOptions", "solve_sliding"]


@dataclass(frozen=True, eq=False)
class SlidingResult:
    """Steady sliding solution on the half-space (arrays on the grid, units mm / MPa).

    Attributes
    ----------
    x, y
        Grid coordinates [mm] (``y`` is ``None`` for a 1D profile).
    heights
        ``z`` [mm] (mean removed).
    pressure
        ``σ`` [MPa], compressive >= 0.
    separation
        ``u = ū + w − z`` [mm].
    displacement
        ``w`` [mm], zero mean.
    mean_separation
        ``ū = <u>`` [mm].
    mean_pressure
        ``σ0`` [MPa] (imposed).
    velocity
        ``v`` [mm/s].
    contact_fraction
        See the module docstring for the definition per interaction law.
    friction, friction_ls, friction_hs
        Total μ, ``<σ ∂z/∂x>/σ0`` and ``<Δτ(u)>/σ0``.
    iterations
        Outer iterations (active-set updates, PK or Newton steps).
    matvecs
        Number of FFT-pair operator applications.
    residual
        Final residual (definition depends on the method, see module docstring).
    converged
        Whether the tolerance was met.
    method
        Algorithm used.
    """

    x: np.ndarray
    y: np.ndarray | None
    heights: np.ndarray
    pressure: np.ndarray
    separation: np.ndarray
    displacement: np.ndarray
    mean_separation: float
    mean_pressure: float
    velocity: float
    contact_fraction: float
    friction: float
    friction_ls: float
    friction_hs: float
    iterations: int
    matvecs: int
    residual: float
    converged: bool
    method: str
    elapsed: float = 0.0
    info: dict = field(default_factory=dict)

    def to_dataset(self):
        """Fields and scalars as an :class:`xarray.Dataset` (units in ``attrs``)."""
        import xarray as xr

        dims = ("x",) if self.y is None else ("y", "x")
        coords = {"x": ("x", self.x, {"units": "mm"})}
        if self.y is not None:
            coords["y"] = ("y", self.y, {"units": "mm"})
        data = {
            "heights": (dims, self.heights, {"units": "mm", "long_name": "surface height z"}),
            "pressure": (dims, self.pressure, {"units": "MPa", "long_name": "contact pressure"}),
            "separation": (dims, self.separation, {"units": "mm", "long_name": "separation u"}),
            "displacement": (dims, self.displacement,
                             {"units": "mm", "long_name": "surface displacement w"}),
        }
        attrs = {
            "mean_separation": self.mean_separation, "mean_separation_units": "mm",
            "mean_pressure": self.mean_pressure, "mean_pressure_units": "MPa",
            "velocity": self.velocity, "velocity_units": "mm/s",
            "contact_fraction": self.contact_fraction, "friction": self.friction,
            "friction_ls": self.friction_ls, "friction_hs": self.friction_hs,
            "iterations": self.iterations, "matvecs": self.matvecs,
            "residual": self.residual, "converged": int(self.converged), "method": self.method,
        }
        return xr.Dataset(data, coords=coords, attrs=attrs)



def solve_sliding(surface, period, material: Material, velocity: float,
                  mean_pressure: float, law: Law | None = None, n: int = 4096,
                  nu: float = 0.5, tol: float = 1e-8, max_iter: int = 200,
                  method: str = "auto", options: SolverOptions | None = None,
                  start: np.ndarray | None = None) -> SlidingResult:
    """Steady sliding contact of a rigid periodic surface on a viscoelastic half-space.

    Parameters
    ----------
    surface
        A :class:`~rubbercontact.roughness.Surface`, dispatched on its declared
        ``dimension``: a profile (e.g. a :class:`~rubbercontact.roughness.SineSeries`)
        sampled by its ``sampled`` on ``n`` points over ``period``, or a map (e.g. a periodic
        :class:`~rubbercontact.roughness.HeightMap`) on its own grid; or heights [mm]: a 1D
        profile ``(n,)`` or a 2D map ``(ny, nx)`` sliding along ``x`` (last axis). The mean
        height is removed.
    period
        Periodic length [mm] along ``x`` (``None`` → the profile's ``period``); must be an
        integer multiple of it (of every wavelength, when the profile declares them). For
        heights of a 2D map a scalar (square pixels) or ``(Ly, Lx)``; for a map surface
        ``None`` (its ``lengths``).
    material
        Young's moduli: a :class:`~rubbercontact.materials.GeneralizedMaxwell` or any
        :class:`~rubbercontact.materials.Material` (``complex_modulus``, ``is_elastic``).
    velocity
        Sliding speed ``v`` [mm/s] of the rubber relative to the surface (sign convention in the
        module docstring; ``v = 0`` is the relaxed elastic limit).
    mean_pressure
        Imposed mean pressure ``σ0`` [MPa], > 0.
    law
        ``None``: hard wall (exact complementarity). Otherwise an
        :class:`~rubbercontact.halfspace.laws.InteractionLaw` or any object with the members
        of :class:`~rubbercontact.halfspace.laws.Law` (``kind``, ``pressure``,
        ``stiffness``); unset Lennard-Jones parameters are resolved from the surface's rms
        height and ``σ0``.
    n
        Grid points for a profile surface (ignored for maps and sampled heights).
    nu
        Poisson's ratio in ``E_r = E/(1 − ν²)``.
    tol
        Relative tolerance (see the docstring of each algorithm's module).
    max_iter
        Maximum outer iterations (active-set updates, PK iterations ×10, Newton steps).
    method
        ``"auto"`` (active set for the hard wall, Newton for laws), ``"active-set"`` or ``"pk"``
        (hard wall, elastic material or ``v = 0`` only).
    options
        Algorithm switches (:class:`~rubbercontact.halfspace.options.SolverOptions`);
        ``None``: the defaults.
    start
        A pressure field [MPa] on the grid to start from, e.g. the solve of the same
        surface at a nearby speed: the viscoelastic hard wall (alone, or as a law's
        initial guess) is first polished from it
        (:func:`~rubbercontact.halfspace.hardwall.hard_wall_viscoelastic`), then, if that
        fails, solved as without it. The same solution to the linear tolerance.

    Returns
    -------
    SlidingResult

    Raises
    ------
    InputError
        Bad input (field named in the message).
    ConvergenceError
        Not converged; ``.last_state`` is the last :class:`SlidingResult`.
    """
    t0 = time.perf_counter()
    velocity, sigma0, tol, law = _check_inputs(material, velocity, mean_pressure, nu, tol,
                                               max_iter, method, law)
    if options is None:
        options = SolverOptions()
    elif not isinstance(options, SolverOptions):
        raise InputError(f"options: expected None or a SolverOptions, got {options!r}")
    grid = sample_surface(surface, period, n)
    kernel = kn.response_kernel(material, grid.shape, grid.lengths, velocity, nu)
    zf = grid.heights.ravel().astype(float)
    prob = Problem(grid.shape, grid.lengths, zf - zf.mean(), grid.slope.ravel().astype(float),
                   kernel, sigma0, options)
    elastic = not np.iscomplexobj(kernel)
    hrms = float(np.sqrt(np.mean(prob.z**2)))
    if hrms == 0.0:
        raise InputError("surface: flat surface (zero rms height); nothing to solve")

    if law is None:
        if method == "pk":
            if not elastic:
                raise InputError("method: 'pk' needs a symmetric operator (elastic material or "
                                 "velocity 0); use 'active-set'")
            out = hard_wall_pk(prob, tol, 10 * max_iter)
            name = "polonsky-keer"
        elif elastic:
            out = hard_wall_elastic(prob, tol, max_iter)
            name = "active-set"
        else:
            out = hard_wall_viscoelastic(prob, tol, max_iter, _start(start, prob))
            name = "projection+active-set"
        used_law = None
    else:
        if method == "pk":
            raise InputError("method: 'pk' is for the hard wall only (law=None)")
        used_law = law.resolve(hrms, sigma0)
        out = _solve_law(prob, used_law, tol, max_iter, elastic, _start(start, prob))
        name = "newton"

    result = _make_result(prob, grid, out, velocity, used_law, name, time.perf_counter() - t0)
    if not out.converged:
        raise ConvergenceError(
            f"halfspace {name} solver did not converge in {out.iterations} iterations "
            f"(residual {out.residual:.3g}, tol {tol:g})",
            diagnostics={"iterations": out.iterations, "residual": out.residual, **out.info},
            last_state=result)
    return result


def _check_inputs(material, velocity, mean_pressure, nu, tol, max_iter, method,
                  law) -> tuple[float, float, float, InteractionLaw | None]:
    """Validate the arguments of :func:`solve_sliding` but the surface and options; return
    ``v``, ``σ0``, ``tol`` and the law as the solvers use it (:func:`.laws.check_law`)."""
    check_material(material)
    if isinstance(velocity, bool) or not isinstance(velocity, int | float | np.floating |
                                                    np.integer):
        raise InputError(f"velocity: expected a number in mm/s, got {velocity!r}")
    velocity = float(velocity)
    if not np.isfinite(velocity):
        raise InputError(f"velocity: must be finite, got {velocity} mm/s")
    sigma0 = positive_scalar("mean_pressure", mean_pressure, unit="MPa")
    if not (isinstance(nu, int | float) and 0.0 <= nu <= 0.5):
        raise InputError(f"nu: Poisson's ratio must lie in [0, 0.5], got {nu!r}")
    tol = positive_scalar("tol", tol)
    if int(max_iter) != max_iter or max_iter < 1:
        raise InputError(f"max_iter: must be an integer >= 1, got {max_iter!r}")
    if method not in ("auto", "active-set", "pk"):
        raise InputError(f"method: expected 'auto', 'active-set' or 'pk', got {method!r}")
    return velocity, sigma0, tol, None if law is None else check_law(law)


def _start(start: np.ndarray | None, prob: Problem) -> np.ndarray | None:
    """``start`` flattened, checked against the grid (None stays None)."""
    if start is None:
        return None
    flat = np.asarray(start, float).ravel()
    if flat.size != prob.size or not np.all(np.isfinite(flat)):
        raise InputError(f"start: expected a finite pressure field of {prob.shape} points")
    return np.maximum(flat, 0.0)


def _solve_law(prob: Problem, law: InteractionLaw, tol: float, max_iter: int,
               elastic: bool, start: np.ndarray | None = None) -> Solution:
    """A resolved law: wall + soft (:mod:`.walls`) or a single law (:mod:`.newton`).

    Both start from the exact hard-wall solution when they need it (computed once, then
    ``info["initial_active_set_iterations"]`` holds its iterations).
    """
    hw_its = []

    def hard_wall() -> Solution:
        hw_tol = max(tol, 1e-8)
        out = (hard_wall_active_set(prob, hw_tol, max_iter) if elastic
               else hard_wall_viscoelastic(prob, hw_tol, max_iter, start))
        if not out.converged:
            raise ConvergenceError("hard-wall initial guess did not converge",
                                   diagnostics=out.info)
        hw_its.append(out.iterations)
        return out

    parts = split_law(law)
    if parts.stiff is not None and parts.soft is not None:
        out = solve_wall_soft(prob, law, parts, tol, max_iter, hard_wall)
    else:
        out = solve_single_law(prob, law, tol, max_iter, hard_wall())
    if hw_its:
        out = replace(out, info={**out.info, "initial_active_set_iterations": hw_its[0]})
    return out


def _make_result(prob: Problem, grid: Grid, out: Solution, velocity: float,
                 law: InteractionLaw | None, name: str, elapsed: float) -> SlidingResult:
    shape = prob.shape
    sigma0 = prob.sigma0
    sigma, u = out.sigma, out.u
    mu_ls = float(np.mean(sigma * prob.slope)) / sigma0
    mu_hs = 0.0
    if law is None:
        area = float(np.mean(sigma > 0))
    else:
        alpha = law.contact_fraction(u)
        if alpha is not None:
            area = float(np.mean((sigma > 0) * alpha))
        else:
            area = float(np.mean(law.in_contact(u)))
        tau = law.shear_stress(u)
        if tau is not None:
            mu_hs = float(np.mean(tau)) / sigma0
    info = dict(out.info)
    if law is not None:
        info["law"] = law.describe()
    return SlidingResult(
        x=grid.x, y=grid.y, heights=prob.z.reshape(shape), pressure=sigma.reshape(shape),
        separation=u.reshape(shape), displacement=out.w.reshape(shape),
        mean_separation=float(np.mean(u)), mean_pressure=sigma0, velocity=velocity,
        contact_fraction=area, friction=mu_ls + mu_hs, friction_ls=mu_ls, friction_hs=mu_hs,
        iterations=int(out.iterations), matvecs=int(prob.matvecs),
        residual=float(out.residual), converged=bool(out.converged), method=name,
        elapsed=elapsed, info=info)
