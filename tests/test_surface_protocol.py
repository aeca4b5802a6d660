"""Solvers take any surface with the members of the ``Surface`` protocol (issue 38 item 4).

The half-space solver dispatches on a surface's declared ``dimension``, not its class. A
profile class of the user's own (a plain dataclass with ``dimension``, ``period`` and
``sampled``) that computes one sine as :class:`SineSeries` does gives *bitwise* the
solution of the equivalent SineSeries; one that declares no waves at all (two modes, one a
cosine) gives the full-contact closed form ``μ = Σ q²Δ² Im E_r(qv) / (4σ0)`` to the
solver's tolerance. A map class of the user's own gives bitwise the solution of the
equivalent periodic :class:`HeightMap`, through ``solve_sliding`` and ``solve_map``
alike. The mean-field's sine tools and the FEM cell take a profile that declares its waves
(and, for the FEM, its analytic derivatives). A surface lacking what a solver needs gets
one :class:`InputError` line naming the missing member.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.errors import InputError
from rubbercontact.fem.sliding import check_test, make_options
from rubbercontact.halfspace import LennardJonesRepulsion, solve_sliding
from rubbercontact.hybrid import solve_map
from rubbercontact.meanfield.bands import strip_bands
from rubbercontact.roughness import HeightMap, SineSeries, check_surface, check_waves

MAT = rc.materials.GeneralizedMaxwell(3.0, [30.0, 300.0], [1e-2, 1e-4])


@dataclass(frozen=True)
class OneSine:
    """``a sin(2πx/λ)``, written as SineSeries evaluates one wave of phase 0."""

    wavelength: float
    amplitude: float
    dimension: ClassVar[int] = 1

    @property
    def period(self) -> float:
        return self.wavelength

    def sampled(self, length, n):
        x = np.arange(n) * (length / n)
        q = 2 * np.pi / np.array([self.wavelength])
        arg = x[:, None] * q + 0.0
        return ((self.amplitude * np.sin(arg)).sum(axis=-1),
                (self.amplitude * q * np.cos(arg)).sum(axis=-1))


@dataclass(frozen=True)
class TwoModes:
    """``a sin(qx) + b cos(2qx)`` with ``q = 2π/period``: no waves declared."""

    period: float
    a: float
    b: float
    dimension: ClassVar[int] = 1

    def sampled(self, length, n):
        x = np.arange(n) * (length / n)
        q = 2 * np.pi / self.period
        return (self.a * np.sin(q * x) + self.b * np.cos(2 * q * x),
                self.a * q * np.cos(q * x) - 2 * q * self.b * np.sin(2 * q * x))


@dataclass(frozen=True)
class MyMap:
    heights: np.ndarray
    lengths: tuple[float, float]
    dimension: ClassVar[int] = 2


def _map_heights(ny=32, nx=64):
    y, x = np.meshgrid(np.arange(ny) / ny, np.arange(nx) / nx, indexing="ij")
    return (0.01 * np.sin(2 * np.pi * x) * np.cos(2 * np.pi * y)
            + 0.004 * np.sin(6 * np.pi * x + 4 * np.pi * y + 0.3))


def _same(a, b):
    assert np.array_equal(a.pressure, b.pressure)
    assert np.array_equal(a.displacement, b.displacement)
    assert a.friction == b.friction and a.contact_fraction == b.contact_fraction


def test_builtin_surfaces_declare_their_dimension():
    assert check_surface(rc.roughness.section3()) == 1
    hm = HeightMap.from_array(_map_heights(), 1 / 64, periodic=True)
    assert check_surface(hm) == 2
    assert check_waves(rc.roughness.section3(), analytic=True) is not None


@pytest.mark.parametrize("velocity, law", [(0.0, None), (10.0, None),
                                           (10.0, LennardJonesRepulsion())])
def test_own_profile_is_bitwise_the_sine_series(velocity, law):
    lam, delta = 0.5, 0.01
    kw = dict(material=MAT, velocity=velocity, mean_pressure=0.3, law=law, n=256)
    _same(solve_sliding(OneSine(lam, delta), None, **kw),
          solve_sliding(SineSeries([lam], [delta]), None, **kw))
    # a multiple of the period, as for the series
    _same(solve_sliding(OneSine(lam, delta), 2 * lam, **kw),
          solve_sliding(SineSeries([lam], [delta]), 2 * lam, **kw))


@pytest.mark.parametrize("velocity", [0.1, 100.0])
def test_own_profile_without_waves_meets_the_full_contact_closed_form(velocity):
    period, a, b = 1.0, 0.002, 0.001
    q = 2 * np.pi / period
    er = MAT.complex_modulus(np.array([q, 2 * q]) * velocity) / 0.75      # ν = 0.5
    sigma0 = 3.0 * float(np.abs(er).max()) * q * (a + 2 * b)   # well above full contact
    res = solve_sliding(TwoModes(period, a, b), None, MAT, velocity, sigma0, n=128)
    assert res.contact_fraction == 1.0
    closed = float(np.sum(np.array([q, 2 * q]) ** 2 * np.array([a, b]) ** 2 * er.imag))
    # two exact Fourier modes on the grid: only the solver tolerance (1e-8) remains
    assert res.friction == pytest.approx(closed / (4 * sigma0), rel=1e-7)


def test_own_map_is_bitwise_the_height_map():
    z, lengths = _map_heights(), (0.5, 1.0)
    hm = HeightMap.from_array(z, 1.0 / 64, 0.5 / 32, periodic=True)
    assert hm.lengths == lengths
    mine = MyMap(z, lengths)
    ref = solve_sliding(z, lengths, MAT, 10.0, 0.2)
    _same(solve_sliding(mine, None, MAT, 10.0, 0.2), ref)
    _same(solve_sliding(hm, None, MAT, 10.0, 0.2), ref)
    _same(solve_sliding(hm, lengths, MAT, 10.0, 0.2), ref)
    _same(solve_map(mine, MAT, 10.0, 0.2), ref)


def _one_line(exc):
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


@pytest.mark.parametrize("surface, missing", [
    (object(), "dimension"),
    (type("P", (), {"dimension": 1, "period": 1.0})(), "sampled"),
    (type("P", (), {"dimension": 1, "sampled": lambda self, L, n: None})(), "period"),
    (type("M", (), {"dimension": 2, "lengths": (1.0, 1.0)})(), "heights"),
])
def test_missing_member_is_named_in_one_line(surface, missing):
    with pytest.raises(InputError) as exc:
        solve_sliding(surface, None, MAT, 10.0, 0.2)
    msg = _one_line(exc)
    assert msg.startswith("surface:") and f"missing {missing}:" in msg


def test_bad_declarations_and_samples_are_one_line():
    with pytest.raises(InputError, match="dimension must be 1") as exc:
        solve_sliding(type("S", (), {"dimension": 3})(), None, MAT, 10.0, 0.2)
    _one_line(exc)
    bad = type("P", (), {"dimension": 1, "period": 1.0,
                         "sampled": lambda self, L, n: (np.zeros(n - 1), np.zeros(n - 1))})()
    with pytest.raises(InputError, match=r"surface.sampled: expected .* shape \(64,\)"):
        solve_sliding(bad, None, MAT, 10.0, 0.2, n=64)
    with pytest.raises(InputError, match="not an integer multiple"):
        solve_sliding(TwoModes(1.0, 0.01, 0.0), 1.5, MAT, 10.0, 0.2, n=64)
    with pytest.raises(InputError, match="a map's lengths are its own"):
        solve_sliding(MyMap(_map_heights(), (0.5, 1.0)), 1.0, MAT, 10.0, 0.2)
    measured = HeightMap.from_array(_map_heights(), 1 / 64)
    with pytest.raises(InputError, match="periodized"):
        solve_sliding(measured, None, MAT, 10.0, 0.2)
    with pytest.raises(InputError, match="takes a map") as exc:
        solve_map(OneSine(0.5, 0.01), MAT, 10.0, 0.2)
    _one_line(exc)


@dataclass(frozen=True)
class MyWaves:
    """A profile declaring its sine waves (what the sine tools and the FEM read)."""

    wavelengths: np.ndarray
    amplitudes: np.ndarray
    dimension: ClassVar[int] = 1

    @property
    def wavenumbers(self):
        return 2 * np.pi / self.wavelengths

    @property
    def period(self):
        return float(np.max(self.wavelengths))

    def _series(self):
        return SineSeries(self.wavelengths, self.amplitudes)

    def heights(self, x):
        return self._series().heights(x)

    def slopes(self, x):
        return self._series().slopes(x)

    def curvatures(self, x):
        return self._series().curvatures(x)

    def as_dict(self):
        return self._series().as_dict()


def test_sine_tools_take_own_waves():
    ref = rc.roughness.section3()
    mine = MyWaves(ref.wavelengths, ref.amplitudes)
    a, b = mf.PSD.from_sines(mine), mf.PSD.from_sines(ref)
    assert np.array_equal(a.wavenumbers, b.wavenumbers)
    assert np.array_equal(a.variances, b.variances)
    edges = np.geomspace(ref.wavenumbers.min() / 2, ref.wavenumbers.max() * 2, 4)
    assert np.array_equal(strip_bands(mine, MAT, 10.0, 0.3, edges),
                          strip_bands(ref, MAT, 10.0, 0.3, edges))
    with pytest.raises(InputError, match="missing wavelengths:") as exc:
        mf.PSD.from_sines(OneSine(0.5, 0.01))
    _one_line(exc)


def test_fem_takes_own_analytic_profile_and_names_what_is_missing():
    ref = rc.roughness.section3()
    opts = make_options()
    mine = MyWaves(ref.wavelengths, ref.amplitudes)
    assert check_test(mine, MAT, 0.3, 10.0, opts) == check_test(ref, MAT, 0.3, 10.0, opts)
    with pytest.raises(InputError, match="missing wavelengths:") as exc:
        check_test(OneSine(0.5, 0.01), MAT, 0.3, 10.0, opts)
    _one_line(exc)
    no_curv = type("W", (), {k: getattr(mine, k) for k in
                             ("dimension", "wavelengths", "wavenumbers", "amplitudes",
                              "period")} | {"heights": mine.heights, "slopes": mine.slopes,
                                            "as_dict": mine.as_dict})()
    with pytest.raises(InputError, match="missing curvatures:"):
        check_test(no_curv, MAT, 0.3, 10.0, opts)
    with pytest.raises(InputError, match="profile of sine waves"):
        check_test(MyMap(_map_heights(), (0.5, 1.0)), MAT, 0.3, 10.0, opts)
