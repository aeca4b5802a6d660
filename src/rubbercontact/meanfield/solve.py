"""Entry points: :func:`solve` (one speed and load, optionally enriched by the FEM law) and
:func:`friction_curve` (the vectorised path: many speeds at once).

The theory is in :mod:`.contact` (contact mechanics) and :mod:`.friction` (friction); the
enrichment in :mod:`.enriched`.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError
from ..materials.protocol import Material, check_material
from .contact import (
    ANGLES_2D,
    CELL_POINTS,
    AreaCurve,
    PressureDistribution,
    contact_fraction,
    g_cumulative,
    half_space_compliance,
    modal_response,
    pressure_distribution,
)
from .enriched import as_pressure_law, check_interface, march_with_layer, weigh_law
from .friction import (
    PERSSON_GAMMA,
    FrictionCorrection,
    check_dissipation,
    check_weighting,
    friction_contributions,
    local_fraction,
)
from .patches import patch_loss
from .psd import PSD
from .strips import StripContact, strip_contact

#: ``dissipation="auto"`` on a sine series (docs/validation/meanfield.md).
AUTO_DISSIPATION_SINES = "mode"
GEOMETRIES = ("auto", "diffusion", "strips", "nested-strips")
#: The geometries of the strip cascade (:mod:`.strips`).
STRIP_GEOMETRIES = ("strips", "nested-strips")
#: Bins of the strip cascade's pressure histogram (:attr:`MeanFieldResult.pressure_distribution`).
HISTOGRAM_BINS = 200


def _friction_stress(resp, g, psd: PSD, material, velocity, nu, kind: str) -> np.ndarray:
    """Each node's full-contact friction stress, or with ``kind != "mode"`` its pressure
    power times the patch spectrum's loss at the node's local contact fraction."""
    if kind == "mode":
        return resp.friction_stress
    return resp.pressure_variance * patch_loss(local_fraction(g, kind), psd.wavenumbers,
                                               material, velocity, nu)


def _strips(psd: PSD, material, velocity: float, sigma0: float, nu: float,
            geometry: str) -> StripContact:
    """The strip cascade on the spectrum's nodes (one wave each, amplitude ``√(2 v_i)``);
    ``geometry="nested-strips"`` keeps every wave's contact inside the longer waves' strips."""
    return strip_contact(psd.wavenumbers, np.sqrt(2.0 * psd.variances), material, velocity,
                         sigma0, nu, outer_crests=geometry == "strips")


def _histogram(strips: StripContact, g: float, sigma0: float, q: np.ndarray
               ) -> PressureDistribution:
    """The strip cascade's local pressures as a density on :data:`HISTOGRAM_BINS` bins."""
    smp = strips.samples
    edges = np.linspace(0.0, float(smp.pressure.max()) * (1 + 1e-9), HISTOGRAM_BINS + 1)
    weight, _ = np.histogram(smp.pressure, bins=edges, weights=smp.weight)
    return PressureDistribution(0.5 * (edges[1:] + edges[:-1]), weight / np.diff(edges),
                                float(q[-1]), float(q[-1] / q[0]), float(g), sigma0,
                                fraction=float(smp.weight.sum()))


@dataclass(frozen=True)
class MeanFieldOptions:
    """Modelling and discretisation choices (one object, passed as is).

    Attributes
    ----------
    correction
        Persson's ``S(q)``: ``"none"`` (S = 1, default) or ``"persson"`` (:mod:`.friction`).
    gamma
        ``γ`` of the ``"persson"`` correction.
    weighting
        Contact fraction weighing each node's friction: ``"auto"`` (default: ``"after"``
        for a sine series, ``"cell"`` for a continuous spectrum), ``"after"`` or ``"cell"``
        (:mod:`.friction`).
    dissipation
        Where a mode in partial contact dissipates (:mod:`.patches`, 1D only): ``"auto"``
        (default: ``"patch"`` for a continuous 1D spectrum, ``"mode"`` for a sine series
        and in 2D), ``"mode"`` (at its own wavenumber, Persson's), ``"patch"`` or
        ``"cascade"`` (spread over the harmonics of its contact patches).
    geometry
        The contact's geometry: ``"auto"`` (default: ``"strips"`` for a 1D sine series
        without a law, ``"diffusion"`` otherwise), ``"diffusion"`` (Persson's
        ``P(σ)``, :mod:`.contact`), ``"strips"`` (the cascade of Westergaard strips of
        :mod:`.strips`, which gives the area and the friction of a 1D sine series; the
        options ``correction``, ``weighting`` and ``dissipation`` are then not used) or
        ``"nested-strips"`` (the same cascade with each wave's contact kept inside the
        longer waves' strips, no outer crests, :mod:`.outer`: the previous default, for
        comparison).
    interface
        With a law: ``"law"`` (default: the law's compliance in series with the
        half-space, :mod:`.enriched`) or ``"rigid"`` (hard-wall low-slope contact).
    angles
        Gauss–Legendre points over the wave-vector direction (2D).
    cell_points
        Gauss–Legendre points per node for the friction weights.
    pressure_points
        Samples of ``P(σ)``.
    """

    correction: str = "none"
    gamma: float = PERSSON_GAMMA
    weighting: str = "auto"
    dissipation: str = "auto"
    geometry: str = "auto"
    interface: str = "law"
    angles: int = ANGLES_2D
    cell_points: int = CELL_POINTS
    pressure_points: int = 801

    def __post_init__(self) -> None:
        FrictionCorrection(self.correction, self.gamma)   # validates both
        check_interface(self.interface)
        check_weighting(self.weighting)
        check_dissipation(self.dissipation)
        if self.geometry not in GEOMETRIES:
            raise InputError(f"geometry: expected one of {', '.join(GEOMETRIES)}, got "
                             f"{self.geometry!r}")
        for name in ("angles", "cell_points", "pressure_points"):
            val = getattr(self, name)
            if isinstance(val, bool) or int(val) != val or val < 2:
                raise InputError(f"{name}: must be an integer >= 2, got {val!r}")

    @property
    def friction_correction(self) -> FrictionCorrection:
        return FrictionCorrection(self.correction, self.gamma)

    def weighting_for(self, psd: PSD) -> str:
        """The node weighting used for ``psd`` (``"auto"`` resolved)."""
        if self.weighting != "auto":
            return self.weighting
        return "after" if psd.waves is not None else "cell"

    def geometry_for(self, psd: PSD, law: bool = False) -> str:
        """The geometry used for ``psd`` (``"auto"`` resolved): the strips need the waves
        of a 1D sine series (they are the exact 1D limit there) and no law."""
        strips_apply = psd.dimension == 1 and psd.waves is not None and not law
        if self.geometry == "auto":
            return "strips" if strips_apply else "diffusion"
        if self.geometry in STRIP_GEOMETRIES and not strips_apply:
            raise InputError(f"geometry={self.geometry!r}: needs a 1D sine series "
                             "(PSD.from_sines) and no law; use 'diffusion'")
        return self.geometry

    def dissipation_for(self, psd: PSD) -> str:
        """The dissipation used for ``psd`` (``"auto"`` resolved; 2D: ``"mode"``)."""
        if self.dissipation != "auto":
            if psd.dimension != 1 and self.dissipation != "mode":
                raise InputError(f"dissipation={self.dissipation!r}: the patch spectrum is "
                                 "the 1D (plane-strain) sine's; use 'mode' in 2D")
            return self.dissipation
        if psd.dimension != 1:
            return "mode"
        return AUTO_DISSIPATION_SINES if psd.waves is not None else "patch"


@dataclass(frozen=True)
class MeanFieldResult:
    """Friction and contact of the mean-field theory at one speed and load.

    Attributes
    ----------
    friction, friction_ls, friction_hs
        Total ``μ`` and its low-slope (the theory's hysteresis) and high-slope (the law,
        0 without one) parts [-].
    contact_fraction
        ``A/A0`` [-]: ``A(ζ_max)`` without a law, ``∫P α_hs dσ`` with one.
    contact_fraction_ls
        ``A(ζ_max)`` of the spectrum given (the low-slope contact, with a law) [-].
    friction_full
        The full-contact limit ``Σ f_i/σ0`` [-].
    pressure_distribution
        ``P(σ)`` at the end of the spectrum (the split magnification, with a law).
    area
        Contact fraction against magnification.
    friction_spectrum
        ``(q_i, μ_i)``: each node's part of ``friction_ls``.
    inputs
        Velocity, mean pressure, ν, dimension, the spectrum's source, the options, and
        whether a law was used.
    """

    friction: float
    friction_ls: float
    friction_hs: float
    contact_fraction: float
    contact_fraction_ls: float
    friction_full: float
    pressure_distribution: PressureDistribution
    area: AreaCurve
    friction_spectrum: tuple[np.ndarray, np.ndarray]
    inputs: dict = field(default_factory=dict)
    elapsed: float = 0.0


@dataclass(frozen=True)
class FrictionCurve:
    """``μ(v)`` and ``A(v)`` of the plain theory at one load (arrays over ``velocities``)."""

    velocities: np.ndarray
    friction: np.ndarray
    contact_fraction: np.ndarray
    friction_full: np.ndarray
    mean_pressure: float
    inputs: dict = field(default_factory=dict)


def _check(psd, material, mean_pressure, nu):
    if not isinstance(psd, PSD):
        raise InputError(f"psd: expected a rubbercontact.meanfield.PSD, got "
                         f"{type(psd).__name__}")
    check_material(material)
    sigma0 = positive_scalar("mean_pressure", mean_pressure, unit="MPa")
    if isinstance(nu, bool) or not (isinstance(nu, int | float) and 0.0 <= nu <= 0.5):
        raise InputError(f"nu: Poisson's ratio must lie in [0, 0.5], got {nu!r}")
    return sigma0


def _speed(velocity) -> float:
    if isinstance(velocity, bool) or not isinstance(velocity, int | float | np.integer |
                                                    np.floating):
        raise InputError(f"velocity: expected a number in mm/s, got {velocity!r}")
    if not np.isfinite(velocity):
        raise InputError(f"velocity: must be finite, got {velocity} mm/s")
    return float(velocity)


def solve(psd: PSD, material: Material, velocity: float, mean_pressure: float,
          nu: float = 0.5, law=None, options: MeanFieldOptions | None = None
          ) -> MeanFieldResult:
    """Hysteretic friction and contact area of the mean-field theory.

    Parameters
    ----------
    psd
        Roughness spectrum (:class:`.PSD`); with a ``law``, the *low-slope* spectrum
        (``psd.partition(m2_threshold)[1]``), the law standing for the scales beyond it.
    material
        Rubber (Young's moduli): any :class:`~rubbercontact.materials.Material`.
    velocity
        Sliding speed [mm/s] (sign as in :func:`rubbercontact.halfspace.solve_sliding`).
    mean_pressure
        ``σ0`` [MPa], > 0.
    nu
        Poisson's ratio in ``E_r = E/(1 − ν²)``.
    law
        ``None`` (plain theory), or the high-slope law: a table at this speed
        (:func:`rubbercontact.hybrid.law_at_velocity`; the hybrid's ``interface_law``
        dict) or a law ``xarray.Dataset`` (:func:`rubbercontact.hybrid.effective_law`).
    options
        :class:`MeanFieldOptions`.

    Returns
    -------
    MeanFieldResult
    """
    t0 = time.perf_counter()
    sigma0 = _check(psd, material, mean_pressure, nu)
    v = _speed(velocity)
    opts = options or MeanFieldOptions()
    if opts is not None and not isinstance(opts, MeanFieldOptions):
        raise InputError(f"options: expected MeanFieldOptions, got {type(opts).__name__}")
    plaw = None if law is None else as_pressure_law(law, v)
    if plaw is not None and psd.dimension != 1:
        raise InputError("law: the FEM law is a plane-strain (1D) result; enrich 1D spectra")
    comp = half_space_compliance(psd.wavenumbers, psd.variances, psd.dimension, material,
                                 v, nu, opts.angles)
    if plaw is not None and opts.interface == "law":
        g, resp = march_with_layer(comp, sigma0, plaw)
    else:
        resp = modal_response(comp)
        g = g_cumulative(resp.pressure_variance, sigma0)
    q = psd.wavenumbers
    geometry = opts.geometry_for(psd, plaw is not None)
    if geometry in STRIP_GEOMETRIES:
        strips = _strips(psd, material, v, sigma0, nu, geometry)
        parts, area_curve = strips.friction_stress / sigma0, strips.contact_fraction
        dist = _histogram(strips, g[-1], sigma0, q)
    else:
        fstress = _friction_stress(resp, g, psd, material, v, nu, opts.dissipation_for(psd))
        parts = friction_contributions(fstress, g, sigma0, opts.friction_correction,
                                       opts.cell_points, opts.weighting_for(psd))
        area_curve = contact_fraction(g)
        dist = pressure_distribution(float(g[-1]), sigma0, q[-1], q[-1] / q[0],
                                     opts.pressure_points)
    mu_ls = float(parts.sum())
    area_ls = dist.contact_fraction
    mu_hs, area = (0.0, area_ls) if plaw is None else weigh_law(dist, plaw)
    inputs = {"velocity": v, "mean_pressure": sigma0, "nu": float(nu),
              "dimension": psd.dimension, "psd": psd.source, "law": plaw is not None,
              "material": material.name, **asdict(opts),
              "weighting": opts.weighting_for(psd), "dissipation": opts.dissipation_for(psd),
              "geometry": geometry}
    return MeanFieldResult(
        friction=mu_ls + mu_hs, friction_ls=mu_ls, friction_hs=float(mu_hs),
        contact_fraction=float(area), contact_fraction_ls=area_ls,
        friction_full=float(resp.friction_stress.sum() / sigma0), pressure_distribution=dist,
        area=AreaCurve(q, q / q[0], area_curve, g),
        friction_spectrum=(q, parts), inputs=inputs, elapsed=time.perf_counter() - t0)


def friction_curve(psd: PSD, material: Material, velocities, mean_pressure: float,
                   nu: float = 0.5, options: MeanFieldOptions | None = None) -> FrictionCurve:
    """``μ(v)``, ``A(v)`` of the plain theory for many speeds in one vectorised pass.

    The same numbers as :func:`solve` at each speed (no law: a law table belongs to one
    speed). Cost: one complex modulus per node, speed and direction, then cumulative sums;
    the strip cascade of a sine series (``geometry``) runs speed by speed.
    """
    sigma0 = _check(psd, material, mean_pressure, nu)
    v = finite_array("velocities", velocities, ndim=1)
    opts = options or MeanFieldOptions()
    comp = half_space_compliance(psd.wavenumbers, psd.variances, psd.dimension, material,
                                 v, nu, opts.angles)
    resp = modal_response(comp)
    g = g_cumulative(resp.pressure_variance, sigma0)
    geometry = opts.geometry_for(psd)
    if geometry in STRIP_GEOMETRIES:
        runs = [_strips(psd, material, float(vi), sigma0, nu, geometry) for vi in v]
        mu = np.array([r.friction_stress.sum() / sigma0 for r in runs])
        area = np.array([r.contact_fraction[-1] for r in runs])
    else:
        fstress = _friction_stress(resp, g, psd, material, v, nu, opts.dissipation_for(psd))
        mu = friction_contributions(fstress, g, sigma0, opts.friction_correction,
                                    opts.cell_points, opts.weighting_for(psd)).sum(axis=-1)
        area = contact_fraction(g[..., -1])
    return FrictionCurve(v, mu, area, resp.friction_stress.sum(axis=-1) / sigma0, sigma0,
                         {"nu": float(nu), "dimension": psd.dimension, "psd": psd.source,
                          "material": material.name, **asdict(opts), "geometry": geometry})
