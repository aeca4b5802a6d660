r"""Flash temperature: μ(v) of a rubber that heats up at its contact spots.

Which variant, and why
----------------------
Persson (J. Phys.: Condens. Matter 18, 7789, 2006) gives each magnification ``ζ = q/q0`` its
own contact temperature ``T_q``: the frictional heat of the scales that form the contact
spots seen at ``ζ`` is released in those spots and diffuses into the rubber, and each
scale dissipates with the modulus at its own temperature, ``E(q v cos φ, T_q) =
E_ref(a_T(T_q) q v cos φ)``; the whole is solved self-consistently with ``μ``. We follow
that structure — the per-scale temperature through the shift law (used here in the
pressure power that sets the contact area as well as in the friction), the
self-consistency, the run's temperature as the background (the mean flux heats the whole
tread, which a steady half-space cannot describe) — but take the diffusion step from the
exact moving heat source (:mod:`rubbercontact.thermal`) instead of Persson's approximate
diffusion factor, through the model of the contact below: the theory then reduces to
closed forms we can test (Jaeger's moving sources) and has one constant, the spot size.
We chose it over transcribing the paper because its every step is checked here; the
price is that the spot size is a modelling choice (Persson's, half a wavelength across).

The contact as a cascade of spots
---------------------------------
Let ``χ_i(x)`` be the indicator of the contact at node ``i`` (:mod:`.contact`: fraction
``A_i``). Node ``j`` dissipates ``w_j = μ_j σ0 v`` per unit nominal area (:mod:`.friction`,
``μ = Σ μ_j``) inside its contact, the flux ``(w_j/A_j) χ_j``; all of it enters the rubber
(the dissipation is in the rubber's bulk; the road's conduction is neglected). The mean
temperature rise over the spots of node ``i`` is then

.. math:: ΔT_i = Σ_j \frac{w_j}{A_i A_j} ∫ d^dr\, G(r)\, \mathrm{cov}[χ_i(x), χ_j(x + r)],

``G`` the surface temperature of a unit moving source (the kernel of :mod:`.thermal.kernel`,
mean removed: the covariance has no mean). The mean-field closure: the spots of the finer
node lie inside those of the coarser one, each node keeping the fraction ``A_l/A_{l−1}`` of
its parent's contact independently, and a node's spots decorrelate beyond their radius
``R_l = (π/2)/q_l`` (half a wavelength across, Persson's size of a contact region at
``ζ_l``; :attr:`FlashOptions.spot_radius`). The covariance is then
``A_iA_j (1/A(min(q_m, 1/r)) − 1)``, ``m = min(i, j)``; written level by level it is a sum of
top-hats ``|r| < R_l``, and

.. math:: ΔT_i = Σ_{l ≤ i} \Big(\frac{1}{A_l} − \frac{1}{A_{l−1}}\Big)\, Γ_l\, W_l,
          \qquad W_l = Σ_{j ≥ l} w_j,\quad A_0 = 1,

with ``Γ_l`` the centre temperature of a uniform unit-flux spot of radius ``R_l`` sliding at
``v``: a disc in 2D, a band in 1D (plane strain), in closed form (:mod:`.thermal.spots`).
Read it as: the heat of every scale ``≥ l`` is released inside the spots of level ``l``;
concentrating it from the area ``A_{l−1}`` into ``A_l`` raises the flux density by
``W_l(1/A_l − 1/A_{l−1})`` on spots of radius ``R_l``, whose flash the spots of all finer
levels ``i ≥ l`` sit in. It depends on the spectrum's nodes only through ``dA``, so it has
a limit as the nodes get dense.

Where it holds, and what it leaves out: the spots' temperature is their surface
temperature (the rubber a scale deforms lies within ``~1/q`` of the surface; at high
Péclet number the flash of the finest spots is thinner than that and this overstates
their heating); the heat is released uniformly in the contact of its node (in full
contact, ``A = 1``, there is no flash, only the background); the spot size is a constant
of the model. The heating of the tread as a whole is the background's: by default the
run's temperature; with :attr:`FlashOptions.contact_time` ``t_c`` (a tread element's time
in the footprint, a lab test's sliding time) the mean flux ``μσ0v`` heats the nominal
contact as a half-space under a uniform flux, ``2μσ0v√(Dt/π)/K`` at the time ``t``
(Carslaw & Jaeger §2.9), on average over the contact ``(4/3)μσ0v√(Dt_c/π)/K``, added
to every node (the background heating of Fortunato et al., J. Phys.: Condens. Matter 27,
175008, 2015, in its simplest form). The limits are exact: an infinitely conducting rubber, or one
whose modulus does not depend on temperature, gives the isothermal theory.

One scale, in closed form (tests/test_meanfield_flash_laws.py): a single node and a
power-law rubber ``E ∝ (iω)^n``, whose shift multiplies the modulus by the real ``a_T^n``;
the theory depends on ``σ0/E`` only, so ``ΔT = (1/A − 1) Γ μ σ0 v`` with μ, A the
isothermal theory's at the load ``σ0 a_T(T0 + ΔT)^{−n}``: a scalar equation. At small
loads (``A ∝ σ0/|E|``, μ fixed by the loss angle), an exponential shift ``log10 a_T =
−sΔT`` and high speed (``Γ → (2/K)√(RD/πv)``), the rise without feedback is ``ΔT0 = Γ μ
σ0 v/A ∝ v^{1/2+n}`` and with it ``ΔT = ΔT0 e^{−kΔT}``, ``k = n s ln 10``: ``ΔT =
W(kΔT0)/k`` (Lambert's W), growing only as ``ln(v)/k`` once ``kΔT0 ≫ 1``.

Solution
--------
A fixed point on the node temperatures ``T_i``, ``T = T0 + ΔT(T)``, by Anderson mixing
(:func:`_iterate`) until the residual ``max_i |T0 + ΔT_i(T) − T_i|`` is below
:attr:`FlashOptions.tolerance` [K] at every speed, continued in the speed from the slowest
along a ladder of speeds (:func:`_continuation`). Each step reads the modulus off tables
in ``log ω`` (:class:`.moduli.ModulusTables`: cubic, < 1e-9 relative; the patch spectrum's loss on
the very nodes of :mod:`.patches`), since every node has its own shift at every step;
the isothermal theory beside it is read off the same tables (it is
:func:`.friction_curve`'s to 1e-8, tests/test_meanfield_flash.py).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import partial

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import ConvergenceError, InputError
from ..materials.shift import ShiftLaw, shift_law_from_dict
from ..thermal.properties import FILLED_SBR, ThermalProperties
from ..thermal.spots import band_centre_temperature, disc_centre_temperature
from .contact import contact_fraction, g_cumulative
from .friction import friction_contributions
from .moduli import ModulusTables
from .options import MeanFieldOptions
from .patches import _rows
from .psd import PSD
from .solve import _check

#: Hottest node temperature above the background [K] the tables cover.
HOTTEST = 1e4
#: Highest harmonic of a node the patch table covers (the patch table's, :mod:`.patches`,
#: times the Hertzian rescaling below its smallest fraction, with a margin).
HARMONICS = 2.0**15 * 1e3
#: Spacing of the continuation's ladder of speeds [decades] (:func:`_continuation`).
LADDER_STEP = 0.25
#: Steps the Anderson mixing remembers.
MEMORY = 5
#: Contact temperature [°C] above which a warning says the compound degrades.
DEGRADATION_TEMPERATURE = 250.0


class FlashWarning(UserWarning):
    """The flash temperature left the range where the model or the compound holds."""


@dataclass(frozen=True)
class FlashOptions:
    """The thermal side of :func:`flash_friction_curve` (one object, passed as is).

    Attributes
    ----------
    thermal
        The compound's :class:`~rubbercontact.thermal.ThermalProperties`.
    temperature
        Background (road and tread) temperature ``T0`` [°C]; default: the shift law's
        reference temperature.
    shift
        Time–temperature shift law; default: the material's own ``shift``.
    spot_radius
        ``q R`` of a contact spot at the node ``q`` [-] (module docstring; π/2: half a
        wavelength across).
    contact_time
        Time the rubber slides in nominal contact [s] (module docstring); ``None``: the
        background is the run's temperature, not heated by the sliding.
    relaxation
        Initial under-relaxation of the fixed point, in (0, 1].
    tolerance
        Largest change of a node temperature [K] accepted as converged (1e-3 K moves a
        WLF shift by ~1e-4 decades).
    max_iterations
        Fixed-point steps before giving up (:class:`~rubbercontact.errors.ConvergenceError`).
    """

    thermal: ThermalProperties = FILLED_SBR
    temperature: float | None = None
    shift: ShiftLaw | dict | None = None
    spot_radius: float = np.pi / 2
    contact_time: float | None = None
    relaxation: float = 0.5
    tolerance: float = 1e-3
    max_iterations: int = 500

    def __post_init__(self) -> None:
        if not isinstance(self.thermal, ThermalProperties):
            raise InputError(f"thermal: expected ThermalProperties, got "
                             f"{type(self.thermal).__name__}")
        positive_scalar("spot_radius", self.spot_radius)
        if self.contact_time is not None:
            positive_scalar("contact_time", self.contact_time, unit="s")
        positive_scalar("tolerance", self.tolerance, unit="K")
        if not (isinstance(self.relaxation, int | float) and 0 < self.relaxation <= 1):
            raise InputError(f"relaxation: must lie in (0, 1], got {self.relaxation!r}")
        if isinstance(self.max_iterations, bool) or int(self.max_iterations) < 1:
            raise InputError(f"max_iterations: must be >= 1, got {self.max_iterations!r}")
        if self.temperature is not None:
            if isinstance(self.temperature, bool) or not isinstance(self.temperature,
                                                                     int | float):
                raise InputError(f"temperature: expected a number in °C, got "
                                 f"{self.temperature!r}")
            positive_scalar("temperature", self.temperature + 273.15, unit="K")


@dataclass(frozen=True)
class FlashCurve:
    """``μ(v)`` with the flash temperature, and the isothermal theory at ``T0`` beside it.

    Attributes
    ----------
    velocities
        Sliding speeds [mm/s].
    friction, friction_isothermal
        ``μ`` [-] with the flash temperature and at the background temperature.
    contact_fraction, contact_fraction_isothermal
        ``A/A0`` [-] at the spectrum's last node, likewise.
    wavenumbers
        The nodes ``q_i`` [rad/mm].
    node_temperature
        ``T_i`` [°C], shape ``(speeds, nodes)``: the contact temperature at each node.
    flash_temperature
        ``T_i − T0`` at the last node [K] per speed: the rise of the finest contact spots.
    heat_flux
        ``Σ_j w_j = μ σ0 v`` [mW/mm²] per speed: the frictional power into the rubber per
        unit nominal area.
    tread_rise
        The background's rise ``(4/3)μσ0v√(Dt_c/π)/K`` [K] per speed (0 without
        ``contact_time``), included in ``node_temperature`` and ``flash_temperature``.
    background_temperature
        ``T0`` [°C].
    mean_pressure
        ``σ0`` [MPa].
    iterations
        Fixed-point steps per speed (of the last stage of the continuation).
    residual
        ``max_i |T_i − T0 − ΔT_i(T)|`` [K] per speed at the end (below the tolerance).
    inputs
        Options of the mean field and of the flash, the thermal properties.
    """

    velocities: np.ndarray
    friction: np.ndarray
    friction_isothermal: np.ndarray
    contact_fraction: np.ndarray
    contact_fraction_isothermal: np.ndarray
    wavenumbers: np.ndarray
    node_temperature: np.ndarray
    flash_temperature: np.ndarray
    heat_flux: np.ndarray
    tread_rise: np.ndarray
    background_temperature: float
    mean_pressure: float
    iterations: np.ndarray
    residual: np.ndarray
    inputs: dict = field(default_factory=dict)


@dataclass(frozen=True)
class _Problem:
    psd: PSD
    velocities: np.ndarray
    sigma0: float
    nu: float
    opts: MeanFieldOptions
    law: ShiftLaw
    t0: float
    spot_rise: np.ndarray          # Γ_l [K per mW/mm²], (speeds, nodes)
    tread_rise: float              # background rise per unit mean flux [K per mW/mm²]
    tables: ModulusTables
    spot_of: Callable              # speeds [mm/s] (column) -> Γ_l at those speeds

    def omega(self, temperature: np.ndarray, rows) -> np.ndarray:
        a = 10.0 ** np.asarray(self.law.log10_shift(temperature))
        return a * self.psd.wavenumbers * self.velocities[rows, None]

    def state(self, temperature: np.ndarray, rows=slice(None)):
        """``(μ_i, A_i)`` at the node temperatures of the speeds ``rows``: the pressure
        power ``s_i = v_i q_i² <|E_r|²>/4`` and the full-contact friction stress
        ``f_i = v_i q_i² <cos φ Im E_r>/2`` of :mod:`.contact` at each node's own
        ``ω_i = a_T(T_i) q_i v``, then :mod:`.friction` as in the isothermal theory."""
        omega = self.omega(temperature, rows)
        q2v = self.psd.wavenumbers**2 * self.psd.variances
        s, f = q2v / 4 * self.tables("power", omega), q2v / 2 * self.tables("loss", omega)
        g = g_cumulative(s, self.sigma0)
        diss = self.opts.dissipation
        if diss.kind != "mode":    # the patch spectrum (:mod:`.patches`) at the node's own ω
            n, h = _rows(diss.local_fraction(g))
            f = s * np.sum(h * self.tables.patch_loss(n * omega[..., None]), axis=-1)
        parts = friction_contributions(f, g, self.sigma0, self.opts.correction,
                                       self.opts.cell_points, self.opts.weighting)
        return parts, contact_fraction(g)

    def rise(self, parts: np.ndarray, area: np.ndarray, rows=slice(None)) -> np.ndarray:
        """``ΔT_i`` [K] from the node frictions and areas (module docstring)."""
        return cascade_rise(parts * self.sigma0 * self.velocities[rows, None], area,
                            self.spot_rise[rows], self.tread_rise)

    def residual(self, temperature: np.ndarray, rows):
        """``T0 + ΔT(T) − T`` [K] at the speeds ``rows``."""
        return self.t0 + self.rise(*self.state(temperature, rows), rows) - temperature


def tread_rise(flash: FlashOptions) -> float:
    """``t`` [K per mW/mm²]: the background's rise per unit mean flux over the tread
    element's ``contact_time`` (0 without one; module docstring)."""
    if flash.contact_time is None:
        return 0.0
    th = flash.thermal
    return 4 / 3 * np.sqrt(th.diffusivity * flash.contact_time / np.pi) / th.conductivity_package


def cascade_rise(heat: np.ndarray, area: np.ndarray, spot_rise: np.ndarray,
                 tread_rise: float = 0.0) -> np.ndarray:
    """``ΔT_i = Σ_{l ≤ i} (1/A_l − 1/A_{l−1}) Γ_l W_l + t W_1`` [K] (module docstring).

    Parameters
    ----------
    heat
        ``w_j`` [mW/mm²]: each node's frictional power per nominal area, ``(..., nodes)``.
    area
        ``A_l`` [-], the contact fraction after each node, same shape.
    spot_rise
        ``Γ_l`` [K per mW/mm²], the centre temperature of a unit-flux spot of the node.
    tread_rise
        ``t`` [K per mW/mm²]: the background's rise per unit mean flux.
    """
    cum = np.cumsum(heat[..., ::-1], axis=-1)[..., ::-1]                   # W_l
    before = np.concatenate([np.ones_like(area[..., :1]), area[..., :-1]], axis=-1)
    area = np.maximum(area, 1e-300)         # erf underflows only at absurd G
    step = np.maximum(1.0 / area - 1.0 / before, 0.0)
    return np.cumsum(step * spot_rise * cum, axis=-1) + tread_rise * cum[..., :1]


def _anderson_step(x, f, dxs, dfs, beta: float) -> np.ndarray:
    """Anderson mixing (type II) of each row with its history of steps ``dxs``, residual
    changes ``dfs`` (lists of ``(rows, nodes)``); without history the damped step."""
    beta = np.asarray(beta, float)[:, None]
    if not dfs:
        return x + beta * f
    df = np.stack(dfs, axis=-1)                                   # (rows, nodes, m)
    dx = np.stack(dxs, axis=-1)
    gram = np.einsum("rnm,rnk->rmk", df, df)
    scale = np.trace(gram, axis1=1, axis2=2)[:, None, None] / df.shape[-1] + 1e-300
    gram = gram + 1e-10 * scale * np.eye(df.shape[-1])          # regularised: steps may align
    gamma = np.linalg.solve(gram, np.einsum("rnm,rn->rm", df, f)[..., None])[..., 0]
    return x + beta * f - np.einsum("rnm,rm->rn", dx + beta[..., None] * df, gamma)


def _iterate(prob: _Problem, temp: np.ndarray, fopts: FlashOptions, rows: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fixed point ``T = T0 + ΔT(T)`` by Anderson mixing (memory :data:`MEMORY`) for
    the speeds ``rows``, only those not yet converged evaluated. Safeguards: a step moves
    no node by more than twice the largest residual; a speed whose residual grows past
    4 × its best (Anderson's residuals are not monotone) goes back to its best iterate,
    drops its history and halves its mixing. A converged speed keeps the map's image
    ``T0 + ΔT(T)``. Returns (T, residual, steps) per row."""
    temp = temp.copy()
    n_v = temp.shape[0]
    resid, its = np.full(n_v, np.inf), np.zeros(n_v, int)
    best, best_x = np.full(n_v, np.inf), temp.copy()
    beta = np.full(n_v, float(fopts.relaxation))
    active = np.arange(n_v)
    dxs: list[np.ndarray] = []
    dfs: list[np.ndarray] = []
    prev_x = prev_f = None
    for _ in range(fopts.max_iterations):
        x = temp[active]
        f = prob.residual(x, rows[active])
        r = np.max(np.abs(f), axis=-1)
        its[active] += 1
        grew = r > 4.0 * best[active]
        better = r < best[active]
        best[active[better]], best_x[active[better]] = r[better], x[better]
        if prev_f is not None:
            dxs, dfs = [*dxs, x - prev_x][-MEMORY:], [*dfs, f - prev_f][-MEMORY:]
        if grew.any():
            back = active[grew]
            beta[back] = np.maximum(beta[back] / 2, 1.0 / 64)
            x[grew] = best_x[back]
            f[grew] = prob.residual(x[grew], rows[back])
            r[grew] = np.max(np.abs(f[grew]), axis=-1)
            dxs = [np.where(grew[:, None], 0.0, d) for d in dxs]
            dfs = [np.where(grew[:, None], 0.0, d) for d in dfs]
        resid[active] = r
        keep = r > fopts.tolerance
        temp[active[~keep]] = np.maximum(x[~keep] + f[~keep], prob.t0)   # the map's image
        if not keep.any():
            return temp, resid, its
        x, f, r, act = x[keep], f[keep], r[keep], active[keep]
        dxs, dfs = [d[keep] for d in dxs], [d[keep] for d in dfs]
        step = _anderson_step(x, f, dxs, dfs, beta[act]) - x
        step = np.where(np.isfinite(step), step, beta[act, None] * f)
        size = np.max(np.abs(step), axis=-1)
        step *= np.minimum(1.0, 2.0 * r / np.maximum(size, 1e-300))[:, None]
        temp[act] = np.maximum(x + step, prob.t0)           # frictional heat only warms
        prev_x, prev_f, active = x, f, act
    raise ConvergenceError(
        f"flash temperature: the fixed point did not converge in {fopts.max_iterations} "
        f"steps (largest residual {resid.max():.3g} K at "
        f"{prob.velocities[rows[np.argmax(resid)]]:.3g} mm/s, "
        f"mixing down to {beta.min():.3g}); raise max_iterations or lower relaxation",
        diagnostics={"residual": resid, "mixing": beta, "iterations": its}, last_state=temp)


def _continuation(prob: _Problem, fopts: FlashOptions) -> tuple[np.ndarray, np.ndarray,
                                                                  np.ndarray]:
    """The fixed point at every speed, by continuation in the speed.

    A ladder of speeds :data:`LADDER_STEP` decades apart across the requested range is
    solved rung by rung from the slowest, each rung started from the previous one's rise
    scaled by ``√(v/v_prev)`` (the high-speed law ``ΔT ∝ μ√v``); then the requested speeds
    together, started from the ladder's temperatures interpolated in ``log v``. Started
    from the isothermal heat instead, a fast speed overshoots by orders of magnitude (its
    isothermal μ belongs to the cold rubber) and the mixing wanders; from a rung two
    decades below, it takes hundreds of steps. Returns (T, residual, steps of the last
    stage) per requested speed."""
    v = prob.velocities
    lo, hi = np.log10(v.min()), np.log10(v.max())
    rungs = np.logspace(lo, hi, max(2, int(np.ceil((hi - lo) / LADDER_STEP)) + 1))
    ladder = replace(prob, velocities=rungs, spot_rise=prob.spot_of(rungs[:, None]))
    temps = np.full((rungs.size, prob.psd.size), prob.t0)
    rise = np.zeros(prob.psd.size)
    for k in range(rungs.size):
        guess = prob.t0 + (rise * np.sqrt(rungs[k] / rungs[k - 1]) if k else rise)
        temps[k] = _iterate(ladder, guess[None], fopts, np.array([k]))[0][0]
        rise = temps[k] - prob.t0
    x, xp = np.log(v), np.log(rungs)
    guess = np.stack([np.interp(x, xp, temps[:, i]) for i in range(prob.psd.size)], axis=-1)
    return _iterate(prob, guess, fopts, np.arange(v.size))


def _setup(psd, material, velocities, mean_pressure, nu, options, flash) -> _Problem:
    sigma0 = _check(psd, material, mean_pressure, nu)
    v = finite_array("velocities", velocities, ndim=1)
    if np.any(v <= 0):
        raise InputError("velocities: the flash temperature needs speeds > 0 mm/s (the "
                         "heat is μσ0v; at rest there is none)")
    opts = options or MeanFieldOptions()
    if not isinstance(opts, MeanFieldOptions):
        raise InputError(f"options: the flash temperature couples to Persson's theory "
                         f"(MeanFieldOptions), got {type(opts).__name__}")
    opts.dissipation.check(psd.dimension)
    opts.interface_for(False)
    raw = flash.shift if flash.shift is not None else getattr(material, "shift", None)
    if raw is None:
        raise InputError("flash temperature: the material has no shift law; give it one "
                         "(material.shift) or FlashOptions(shift=WLF(c1, c2, t_ref))")
    law = shift_law_from_dict(raw)
    t0 = law.t_ref if flash.temperature is None else float(flash.temperature)
    law.log10_shift(t0)                                     # validity at T0
    spot = partial(disc_centre_temperature if psd.dimension == 2 else band_centre_temperature,
                   flash.spot_radius / psd.wavenumbers, thermal=flash.thermal)
    tread = tread_rise(flash)
    tables = _tables(psd, material, v, float(nu), opts.angles, law, t0)
    return _Problem(psd, v, sigma0, float(nu), opts, law, t0, spot(v[:, None]), tread, tables,
                    spot)


def _tables(psd: PSD, material, velocities: np.ndarray, nu: float, angles: int,
            law: ShiftLaw, t0: float) -> ModulusTables:
    """Tables spanning every frequency the iterations can reach: node temperatures lie
    between ``T0`` (heat only warms) and ``T0 +`` :data:`HOTTEST` K, and the patch
    spectrum reads harmonics up to :data:`HARMONICS` of a node. Beyond the ends the tables
    hold their end values."""
    a_cold, a_hot = (10.0 ** float(law.log10_shift(t)) for t in (t0, t0 + HOTTEST))
    q = psd.wavenumbers
    lo = np.log10(q[0] * velocities.min() * min(a_hot, a_cold)) - 0.1
    hi = np.log10(q[-1] * velocities.max() * max(a_hot, a_cold)) + 0.1
    return ModulusTables(material, nu, psd.dimension, angles, lo, hi, np.log10(HARMONICS))


def flash_friction_curve(psd: PSD, material, velocities, mean_pressure: float,
                         nu: float = 0.5, options: MeanFieldOptions | None = None,
                         flash: FlashOptions | None = None) -> FlashCurve:
    """``μ(v)`` of the mean-field theory with the flash temperature (module docstring).

    Parameters
    ----------
    psd
        Roughness spectrum (continuous, or a sine series).
    material
        Rubber at the shift law's reference temperature, with a ``shift`` law (or
        ``flash.shift``).
    velocities
        Sliding speeds [mm/s], > 0.
    mean_pressure
        ``σ0`` [MPa].
    nu
        Poisson's ratio.
    options
        :class:`~rubbercontact.meanfield.MeanFieldOptions` (Persson's theory).
    flash
        :class:`FlashOptions` (thermal properties, background temperature, tolerance).

    Returns
    -------
    FlashCurve
        With the isothermal theory at the background temperature beside it.

    Raises
    ------
    ConvergenceError
        When the fixed point does not converge (residuals, relaxations in its diagnostics).
    """
    flash = flash or FlashOptions()
    if not isinstance(flash, FlashOptions):
        raise InputError(f"flash: expected FlashOptions, got {type(flash).__name__}")
    prob = _setup(psd, material, velocities, mean_pressure, nu, options, flash)
    iso_parts, iso_area = prob.state(np.full((prob.velocities.size, psd.size), prob.t0))
    temp, resid, its = _continuation(prob, flash)
    parts, area = prob.state(temp)
    mu = parts.sum(axis=-1)
    if temp.max() > DEGRADATION_TEMPERATURE:
        warnings.warn(f"flash temperature: the contact reaches {temp.max():.0f} °C at "
                      f"{prob.velocities[np.argmax(temp.max(axis=-1))]:.3g} mm/s, where a "
                      f"tread compound degrades and the shift law is extrapolated",
                      FlashWarning, stacklevel=2)
    inputs = {"nu": float(nu), "dimension": psd.dimension, "psd": psd.source,
              "material": getattr(material, "name", ""), **prob.opts.to_dict(),
              "correction": prob.opts.correction.describe(),
              "thermal": flash.thermal.as_dict(), "shift": prob.law.as_dict(),
              "spot_radius": flash.spot_radius, "tolerance_K": flash.tolerance,
              "contact_time_s": flash.contact_time}
    return FlashCurve(
        prob.velocities, mu, iso_parts.sum(axis=-1), area[:, -1], iso_area[:, -1],
        psd.wavenumbers, temp, temp[:, -1] - prob.t0,
        mu * prob.sigma0 * prob.velocities, prob.tread_rise * mu * prob.sigma0 * prob.velocities,
        prob.t0, prob.sigma0, its, resid,
        inputs)
