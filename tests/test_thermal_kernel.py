"""The moving heat source on a half-space: FFT solution against Jaeger's closed forms.

References: J. C. Jaeger, "Moving sources of heat and the temperature at sliding contacts",
Proc. R. Soc. N.S.W. 76, 203 (1942); H. S. Carslaw & J. C. Jaeger, *Conduction of Heat in
Solids*, 2nd ed. (1959), §10.7 (moving line and point sources). Péclet number
``Pe = v a/(2D)``, ``a`` the source's half-width or radius.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import i0e, k0e, zeta

from rubbercontact.errors import InputError
from rubbercontact.thermal import (
    FILLED_SBR,
    ThermalProperties,
    band_centre_temperature,
    band_mean_temperature,
    disc_centre_temperature,
    subsurface_temperature,
    surface_temperature,
)

TH = FILLED_SBR
K, D = TH.conductivity_package, TH.diffusivity
A = 0.01                       # source half-width / radius [mm]
CELLS = 16                     # grid cells per half-width


def _speed(pe: float) -> float:
    return pe * 2 * D / A


# -- the closed forms (spots.py) against direct quadrature of the moving sources ----------
@pytest.mark.parametrize("pe", [1e-3, 0.1, 1.0, 10.0, 100.0])
def test_closed_forms_integrate_the_moving_line_and_point_sources(pe):
    """The three Bessel-function closed forms against quadrature of Carslaw & Jaeger's
    line source ``(1/πK) e^{ux} K0(u|x|)`` and point source ``e^{−u(r−x)}/(2πKr)``;
    quadrature in ``ln s`` (tolerance 1e-12; the part below 1e-14 a is dropped) bounds
    the difference by 1e-8."""
    v, u = _speed(pe), _speed(pe) / (2 * D)

    def cosh_k0(s):               # cosh(us) K0(us), exponentially scaled against overflow
        return 0.5 * k0e(u * s) * (1 + np.exp(-2 * u * s))

    def integral(f, upper):       # in ln s: K0's log singularity at 0 becomes smooth
        return quad(lambda t: f(np.exp(t)) * np.exp(t), np.log(1e-14 * A), np.log(upper),
                    limit=500, epsrel=1e-12)[0]

    band_mean = integral(lambda s: (2 * A - s) * cosh_k0(s), 2 * A) / (np.pi * K * A)
    band_centre = 2 / (np.pi * K) * integral(cosh_k0, A)
    disc_centre = integral(lambda r: i0e(u * r), A) / K
    assert band_mean_temperature(A, v, TH) == pytest.approx(band_mean, rel=1e-8)
    assert band_centre_temperature(A, v, TH) == pytest.approx(band_centre, rel=1e-8)
    assert disc_centre_temperature(A, v, TH) == pytest.approx(disc_centre, rel=1e-8)


def test_jaeger_band_asymptotes():
    """Low speed: ``(2Qa/πK)(ln(2D/va) + 3/2 − γ)`` (error O(Pe² ln Pe)); high speed: the
    1D transient ``(4Q/3K)√(2aD/πv)`` (relative error O(1/Pe): 0.2 % at Pe = 100)."""
    v_lo, v_hi = _speed(1e-3), _speed(1e3)
    low = 2 * A / (np.pi * K) * (np.log(2 * D / (v_lo * A)) + 1.5 - np.euler_gamma)
    high = 4 / (3 * K) * np.sqrt(2 * A * D / (np.pi * v_hi))
    assert band_mean_temperature(A, v_lo, TH) == pytest.approx(low, rel=1e-5)
    assert band_mean_temperature(A, v_hi, TH) == pytest.approx(high, rel=1e-3)
    # the disc: stationary centre Q R/K; high speed the same transient as the band's centre
    assert disc_centre_temperature(A, 0.0, TH) == pytest.approx(A / K, rel=1e-14)
    centre_hi = 2 / K * np.sqrt(A * D / (np.pi * v_hi))
    assert disc_centre_temperature(A, v_hi, TH) == pytest.approx(centre_hi, rel=1e-3)
    assert band_centre_temperature(A, v_hi, TH) == pytest.approx(centre_hi, rel=1e-3)


# -- the FFT solution -------------------------------------------------------------------
def _band(n: int) -> tuple[np.ndarray, float]:
    """A unit-flux band of half-width A on n cells (edge cells at half weight: the band's
    edges fall on grid points), and the period."""
    dx = A / CELLS
    x = (np.arange(n) - n // 2) * dx
    q = (np.abs(x) < A - 1e-9 * dx).astype(float)
    q[np.isclose(np.abs(x), A)] = 0.5
    return q, n * dx


@pytest.mark.parametrize("pe, n", [(0.01, 2**21), (1.0, 2**17), (100.0, 2**14)])
def test_fft_band_mean_temperature_is_jaegers(pe, n):
    """Periodic bands (period L ≫ a) against Jaeger's isolated band plus the images.

    The periodic solution is a Riemann sum of the isolated one's Fourier integral; its
    integrand ``∝ |k|^{-1/2}`` at small k (``1/√(ikv/D)``) makes the sum differ by the
    zeta term ``(2Qa/K) ζ(1/2) √(D/πvL)`` (Euler–Maclaurin; the next term is smaller by
    ``~2πD/(vL)`` < 1e-3 here). What is left is the grid's: 0.1–0.2 % at 16 cells per
    half-width (converging as ~h^1.7, the band's flux jump), so 0.5 %."""
    v = _speed(pe)
    q, period = _band(n)
    t = surface_temperature(q, period, v, TH)
    mean = np.sum(t * q) / q.sum()
    images = 2 * A / K * zeta(0.5) * np.sqrt(D / (np.pi * v * period))
    assert mean == pytest.approx(band_mean_temperature(A, v, TH) + images, rel=5e-3)


def test_the_wake_is_downstream_and_the_mean_is_removed():
    """The rubber moves to +x: the heated rubber leaves the band at +x, so 3 half-widths
    downstream is warmer than 3 upstream; the period's mean rise is 0 (background)."""
    q, period = _band(2**12)
    t = surface_temperature(q, period, _speed(10.0), TH)
    c, off = q.size // 2, 3 * CELLS
    assert t[c + off] > t[c - off] + 0.1 * (t.max() - t.min())
    assert abs(t.mean()) < 1e-12 * np.abs(t).max()


def test_a_map_uniform_across_the_sliding_direction_is_the_profile():
    """A 2D flux uniform in y is a band source (2D conduction): the 2D kernel gives the 1D
    answer to round-off, so the Jaeger band tests above hold in 2D as well."""
    q, period = _band(2**12)
    v = _speed(3.0)
    t1 = surface_temperature(q, period, v, TH)
    t2 = surface_temperature(np.tile(q, (8, 1)), (0.37, period), v, TH)
    np.testing.assert_allclose(t2, np.tile(t1, (8, 1)), rtol=0, atol=1e-12 * np.abs(t1).max())


def _disc(shape: tuple[int, int], cells: int = CELLS) -> tuple[np.ndarray, tuple]:
    """A unit-flux disc of radius A, each cell weighted by its covered share (4×4 points)."""
    dx = A / cells
    ny, nx = shape
    y = (np.arange(ny) - ny // 2) * dx
    x = (np.arange(nx) - nx // 2) * dx
    yy, xx = np.meshgrid(y, x, indexing="ij")
    sub = (np.arange(4) + 0.5) / 4 - 0.5
    f = sum(((yy + a * dx) ** 2 + (xx + b * dx) ** 2 < A**2).astype(float)
            for a in sub for b in sub) / 16
    return f, (ny * dx, nx * dx)


def test_stationary_disc_centre_is_qr_over_k():
    """v = 0: the centre of a uniform disc is ``QR/K``. On an L×L periodic grid the images
    (a lattice of sources with the mean removed) add ``c P/(K L)`` to leading order, so two
    periods eliminate it (the next term is O((R/L)³)); the disc's staircase edge leaves
    < 0.3 % at 16 cells per radius."""
    centres = []
    for n in (256, 512):
        f, lens = _disc((n, n))
        centres.append(surface_temperature(f, lens, 0.0, TH)[n // 2, n // 2])
    extrapolated = 2 * centres[1] - centres[0]
    assert extrapolated == pytest.approx(A / K, rel=3e-3)


def test_fast_disc_centre_is_the_closed_form():
    """Pe = 100: the disc's centre against ``(R/K)e^{−uR}(I0 + I1)``. The images in a long
    period (8192 cells along x, 128 across) add < 1 % (their wakes; measured 0.8 %), so 2 %."""
    v = _speed(100.0)
    f, lens = _disc((128, 8192))
    centre = surface_temperature(f, lens, v, TH)[64, 4096]
    assert centre == pytest.approx(disc_centre_temperature(A, v, TH), rel=2e-2)


def test_heat_flux_sign_and_linearity():
    """Temperature is linear in the flux and an upward flux (negative) cools the pattern."""
    q, period = _band(2**10)
    t = surface_temperature(q, period, 1.0, TH)
    np.testing.assert_allclose(surface_temperature(-2.5 * q, period, 1.0, TH), -2.5 * t,
                               atol=1e-14 * np.abs(t).max())


def test_bad_input_is_one_clear_error():
    with pytest.raises(InputError, match="flux"):
        surface_temperature(np.array([1.0, np.nan, 0.0]), 1.0, 1.0)
    with pytest.raises(InputError, match="lengths"):
        surface_temperature(np.ones((4, 4)), (1.0, 2.0, 3.0), 1.0)
    with pytest.raises(InputError, match="velocity"):
        surface_temperature(np.ones(4), 1.0, float("inf"))


def test_thermal_properties_units_and_errors():
    """K [W/(m·K)] is the same number in mW/(mm·K); ρc [J/(m³K)] × 1e-6 in MPa/K; so D of the
    default compound is 0.25/(1150·1800·1e-6) mm²/s = 1.21e-7 m²/s."""
    th = ThermalProperties(0.25, 1150.0, 1800.0)
    assert th.diffusivity == pytest.approx(0.25 / 2.07, rel=1e-12)
    assert ThermalProperties.from_dict(th.as_dict()) == th
    assert ThermalProperties.from_dict({"conductivity": 0.3}).density == 1150.0
    with pytest.raises(InputError, match="conductivity"):
        ThermalProperties(conductivity=-1.0)
    with pytest.raises(InputError, match="unknown"):
        ThermalProperties.from_dict({"conductance": 1.0})


def test_material_spec_carries_a_thermal_table():
    """``[material.thermal]`` is read by load_thermal and accepted by load_material."""
    from rubbercontact.materials.spec import load_material, load_thermal

    spec = {"preset": "sbr", "thermal": {"conductivity": 0.3, "specific_heat": 1700.0}}
    th = load_thermal(spec)
    assert (th.conductivity, th.density, th.specific_heat) == (0.3, 1150.0, 1700.0)
    assert load_thermal({"preset": "sbr"}) == FILLED_SBR
    assert load_material(spec).name == load_material({"preset": "sbr"}).name
    with pytest.raises(InputError, match="thermal.density"):
        load_thermal({"preset": "sbr", "thermal": {"density": "heavy"}})


@pytest.mark.parametrize("shape", [(256,), (32, 64)])
def test_the_field_solves_the_heat_equation_with_the_given_flux(shape):
    """Against the PDE itself, not the kernel's formula: under a random periodic flux the
    field at depth satisfies the steady advection–diffusion ``v ∂T/∂x = D ∇²T`` (x, y
    derivatives spectral, z by 4th-order central differences with h = 1e-3/k_max: error
    ~h⁴ ~ 1e-12 relative), and Fourier's law ``−K ∂T/∂z`` at the surface (one-sided
    4th-order differences) returns the flux with its mean removed: the energy that enters
    is the energy given, the mean going to the background. The flux is random but
    band-limited (no mode beyond half the grid's Nyquist: a real field's Nyquist mode
    cannot carry the complex response of a sliding mode)."""
    rng = np.random.default_rng(4)
    spec = np.fft.fftn(rng.random(shape))
    for axis, n in enumerate(shape):
        far = np.abs(np.fft.fftfreq(n) * n) > n // 4
        spec[(slice(None),) * axis + (far,)] = 0.0
    flux = 1.0 + np.real(np.fft.ifftn(spec))
    lens = (0.4, 1.0)[-len(shape):]
    v = 30.0
    k_max = 0.5 * np.pi * shape[-1] / lens[-1]
    h = 1e-3 / k_max

    def field(z):
        return subsurface_temperature(flux, lens, v, z, TH)

    z0 = 0.2 / k_max
    t = [field(z0 + j * h) for j in (-2, -1, 0, 1, 2)]
    d2z = (-t[0] + 16 * t[1] - 30 * t[2] + 16 * t[3] - t[4]) / (12 * h**2)
    spec = np.fft.fftn(t[2])
    ks = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(n, ln / n) for n, ln in
                       zip(shape, lens, strict=True)], indexing="ij")
    lap_xy = np.real(np.fft.ifftn(-sum(k**2 for k in ks) * spec))
    d_x = np.real(np.fft.ifftn(1j * ks[-1] * spec))
    scale = np.abs(D * d2z).max()
    np.testing.assert_allclose(v * d_x, D * (lap_xy + d2z), atol=1e-6 * scale)
    s = [field(j * h) for j in range(5)]
    dtdz = (-25 * s[0] + 48 * s[1] - 36 * s[2] + 16 * s[3] - 3 * s[4]) / (12 * h)
    np.testing.assert_allclose(-K * dtdz, flux - flux.mean(), atol=1e-6 * np.abs(flux).max())
    np.testing.assert_allclose(s[0], surface_temperature(flux, lens, v, TH), rtol=1e-14,
                               atol=1e-14 * np.abs(s[0]).max())


def test_the_rise_bound_holds_for_any_non_negative_flux_at_any_speed():
    """rise_bound: |T| ≤ <Q>(L/πK)(ln(N/2) + 1) for Q ≥ 0 on N ≤ points (every mode's
    admittance |λ| ≥ |k|, |Q̂_k| ≤ <Q>); tight within a factor of a few for a comb of
    narrow spikes, whose modes all have |Q̂_k| = <Q>, at rest."""
    from rubbercontact.thermal import FILLED_SBR, surface_temperature
    from rubbercontact.thermal.kernel import rise_bound

    rng = np.random.default_rng(3)
    n, length = 1024, 2.0
    for flux in (rng.random(n) ** 8, (rng.random(n) > 0.97).astype(float),
                 np.eye(1, n).ravel()):
        bound = rise_bound(flux.mean(), length, FILLED_SBR, points=n)
        for v in (0.0, 1e-2, 1.0, 1e2, 1e4):
            peak = np.abs(surface_temperature(flux, length, v, FILLED_SBR)).max()
            assert peak <= bound
    spike = np.eye(1, n).ravel()
    at_rest = np.abs(surface_temperature(spike, length, 0.0, FILLED_SBR)).max()
    assert at_rest > rise_bound(spike.mean(), length, FILLED_SBR, points=n) / 3
