"""Entry points: :func:`solve` (one speed and load, optionally enriched by the FEM law) and
:func:`friction_curve` (the vectorised path: many speeds at once).

The theory is in :mod:`.contact` (contact mechanics) and :mod:`.friction` (friction); the
enrichment in :mod:`.enriched`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError
from ..materials.protocol import Material, check_material
from .contact import (
    ANGLES_2D,
    AreaCurve,
    PressureDistribution,
    contact_fraction,
    g_cumulative,
    half_space_compliance,
    modal_response,
    pressure_distribution,
)
from .enriched import as_pressure_law, march_with_layer, weigh_law
from .friction import friction_contributions
from .options import Dissipation, MeanFieldOptions, StripOptions
from .patches import patch_loss
from .psd import PSD
from .strips import StripContact, strip_contact

#: Bins of the strip cascade's pressure histogram (:attr:`MeanFieldResult.pressure_distribution`).
HISTOGRAM_BINS = 200
Options = MeanFieldOptions | StripOptions


def _friction_stress(resp, g, psd: PSD, material, velocity, nu,
                     dissipation: Dissipation) -> np.ndarray:
    """Each node's full-contact friction stress [MPa], or with a patch spectrum its pressure
    power times the patch spectrum's loss at the node's local contact fraction."""
    if dissipation.kind == "mode":
        return resp.friction_stress
    return resp.pressure_variance * patch_loss(dissipation.local_fraction(g), psd.wavenumbers,
                                               material, velocity, nu)


def _strips(psd: PSD, material, velocity: float, sigma0: float, nu: float,
            opts: StripOptions) -> StripContact:
    """The strip cascade on the spectrum's nodes (one wave each, amplitude ``√(2 v_i)``)."""
    return strip_contact(psd.wavenumbers, np.sqrt(2.0 * psd.variances), material, velocity,
                         sigma0, nu, outer_crests=opts.outer_crests)


def _histogram(strips: StripContact, g: float, sigma0: float, q: np.ndarray
               ) -> PressureDistribution:
    """The strip cascade's local pressures as a density on :data:`HISTOGRAM_BINS` bins."""
    smp = strips.samples
    edges = np.linspace(0.0, float(smp.pressure.max()) * (1 + 1e-9), HISTOGRAM_BINS + 1)
    weight, _ = np.histogram(smp.pressure, bins=edges, weights=smp.weight)
    return PressureDistribution(0.5 * (edges[1:] + edges[:-1]), weight / np.diff(edges),
                                float(q[-1]), float(q[-1] / q[0]), float(g), sigma0,
                                fraction=float(smp.weight.sum()))


def _options(options, psd: PSD, law: bool) -> Options:
    """The options object, checked against the input (one line when it does not apply)."""
    opts = MeanFieldOptions() if options is None else options
    if not isinstance(opts, MeanFieldOptions | StripOptions):
        raise InputError(f"options: expected MeanFieldOptions or StripOptions, got "
                         f"{type(opts).__name__}")
    if isinstance(opts, StripOptions):
        if psd.dimension != 1 or psd.waves is None or law:
            raise InputError("StripOptions (meanfield-strips): the strips need a 1D sine "
                             "series (PSD.from_sines) and no law; use MeanFieldOptions")
        return opts
    opts.dissipation.check(psd.dimension)
    opts.interface_for(law)
    return opts


def _angles(opts: Options) -> int:
    """Direction points of the 2D angle averages (the strips are 1D: unused there)."""
    return opts.angles if isinstance(opts, MeanFieldOptions) else ANGLES_2D


def _inputs(opts: Options, law: bool) -> dict:
    """The options as they were used (provenance)."""
    if isinstance(opts, StripOptions):
        return {"model": "strips", "outer_crests": opts.outer_crests}
    return {**opts.to_dict(), "correction": opts.correction.describe(),
            "interface": opts.interface_for(law)}


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
        dict), a law ``xarray.Dataset`` (:func:`rubbercontact.hybrid.effective_law`), or
        a pressure law: a :class:`.PressureLaw` or any object with its ``at``,
        ``compliance_at`` and ``max_pressure``.
    options
        :class:`MeanFieldOptions` (Persson's theory, default) or :class:`StripOptions`
        (the strip cascade of a 1D sine series, without a law).

    Returns
    -------
    MeanFieldResult
    """
    t0 = time.perf_counter()
    sigma0 = _check(psd, material, mean_pressure, nu)
    v = _speed(velocity)
    plaw = None if law is None else as_pressure_law(law, v)
    if plaw is not None and psd.dimension != 1:
        raise InputError("law: the FEM law is a plane-strain (1D) result; enrich 1D spectra")
    opts = _options(options, psd, plaw is not None)
    comp = half_space_compliance(psd.wavenumbers, psd.variances, psd.dimension, material,
                                 v, nu, _angles(opts))
    if plaw is not None and opts.interface_for(True) == "law":
        g, resp = march_with_layer(comp, sigma0, plaw)
    else:
        resp = modal_response(comp)
        g = g_cumulative(resp.pressure_variance, sigma0)
    q = psd.wavenumbers
    if isinstance(opts, StripOptions):
        strips = _strips(psd, material, v, sigma0, nu, opts)
        parts, area_curve = strips.friction_stress / sigma0, strips.contact_fraction
        dist = _histogram(strips, g[-1], sigma0, q)
    else:
        fstress = _friction_stress(resp, g, psd, material, v, nu, opts.dissipation)
        parts = friction_contributions(fstress, g, sigma0, opts.correction,
                                       opts.cell_points, opts.weighting)
        area_curve = contact_fraction(g)
        dist = pressure_distribution(float(g[-1]), sigma0, q[-1], q[-1] / q[0],
                                     opts.pressure_points)
    mu_ls = float(parts.sum())
    area_ls = dist.contact_fraction
    mu_hs, area = (0.0, area_ls) if plaw is None else weigh_law(dist, plaw)
    inputs = {"velocity": v, "mean_pressure": sigma0, "nu": float(nu),
              "dimension": psd.dimension, "psd": psd.source, "law": plaw is not None,
              "material": material.name, **_inputs(opts, plaw is not None)}
    return MeanFieldResult(
        friction=mu_ls + mu_hs, friction_ls=mu_ls, friction_hs=float(mu_hs),
        contact_fraction=float(area), contact_fraction_ls=area_ls,
        friction_full=float(resp.friction_stress.sum() / sigma0), pressure_distribution=dist,
        area=AreaCurve(q, q / q[0], area_curve, g),
        friction_spectrum=(q, parts), inputs=inputs, elapsed=time.perf_counter() - t0)


def friction_curve(psd: PSD, material: Material, velocities, mean_pressure: float,
                   nu: float = 0.5, options: Options | None = None) -> FrictionCurve:
    """``μ(v)``, ``A(v)`` of the plain theory for many speeds in one vectorised pass.

    The same numbers as :func:`solve` at each speed (no law: a law table belongs to one
    speed). Cost: one complex modulus per node, speed and direction, then cumulative sums;
    the strip cascade (:class:`StripOptions`) runs speed by speed.
    """
    sigma0 = _check(psd, material, mean_pressure, nu)
    v = finite_array("velocities", velocities, ndim=1)
    opts = _options(options, psd, False)
    comp = half_space_compliance(psd.wavenumbers, psd.variances, psd.dimension, material,
                                 v, nu, _angles(opts))
    resp = modal_response(comp)
    g = g_cumulative(resp.pressure_variance, sigma0)
    if isinstance(opts, StripOptions):
        runs = [_strips(psd, material, float(vi), sigma0, nu, opts) for vi in v]
        mu = np.array([r.friction_stress.sum() / sigma0 for r in runs])
        area = np.array([r.contact_fraction[-1] for r in runs])
    else:
        fstress = _friction_stress(resp, g, psd, material, v, nu, opts.dissipation)
        mu = friction_contributions(fstress, g, sigma0, opts.correction,
                                    opts.cell_points, opts.weighting).sum(axis=-1)
        area = contact_fraction(g[..., -1])
    return FrictionCurve(v, mu, area, resp.friction_stress.sum(axis=-1) / sigma0, sigma0,
                         {"nu": float(nu), "dimension": psd.dimension, "psd": psd.source,
                          "material": material.name, **_inputs(opts, False)})
