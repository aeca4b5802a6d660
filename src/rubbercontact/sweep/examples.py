"""Small pure task functions for tests, benchmarks and documentation.

:func:`toy_kernel` evaluates, per sine wave, the full-contact steady-sliding
hysteretic friction of a viscoelastic half-space (SPEC check,
``μ_i = m2_i² Im E_r(q_i v) / (2 σ0)``) with the generalized Maxwell material
of :mod:`rubbercontact.materials`. Options add deterministic CPU work, a sleep
or a forced :class:`~rubbercontact.errors.ConvergenceError`, so the sweep
machinery can be exercised without the FEM or BEM kernels.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from ..errors import ConvergenceError, InputError
from ..materials import GeneralizedMaxwell, sbr

__all__ = ["toy_kernel"]

#: Section 3 validation surface: first three waves of Table 2 (mm).
_WAVELENGTHS = (0.0625, 0.125, 0.25)
_AMPLITUDES = (0.01867, 0.02648, 0.02939)


def _busy(work: int, seed_value: float) -> float:
    # Deterministic FFT smoothing iterations: real numpy work (~0.3 ms per iteration on one
    # core), reduced to one number so the work cannot be skipped.
    n = 1 << 15
    x = np.sin(np.arange(n) * (0.001 + 1e-6 * seed_value))
    kernel = 1.0 / (1.0 + (np.arange(n // 2 + 1) / 64.0) ** 2)
    for _ in range(work):
        x = np.tanh(np.fft.irfft(np.fft.rfft(x) * kernel, n) * 1.5 + 0.1)
    return float(np.sum(x))


def toy_kernel(velocity: float, pressure: float,
               wavelengths: Sequence[float] = _WAVELENGTHS,
               amplitudes: Sequence[float] = _AMPLITUDES,
               material: Mapping[str, Any] | None = None, nu: float = 0.5,
               work: int = 0, sleep: float = 0.0, fail: bool = False,
               calls_log: str | None = None) -> xr.Dataset:
    """Full-contact hysteretic friction per wave, as an ``xarray.Dataset``.

    Parameters
    ----------
    velocity
        Sliding speed v [mm/s].
    pressure
        Mean pressure σ0 [MPa], > 0.
    wavelengths, amplitudes
        Sine waves λ_i [mm] and Δ_i [mm].
    material
        ``{"equilibrium_modulus": ..., "moduli": [...], "relaxation_times": [...]}``
        [MPa, s]; default the SBR of Table 1.
    nu
        Poisson's ratio.
    work
        Iterations of deterministic FFT work (≈0.3 ms each) added to the task,
        reported as ``work_checksum``; for benchmarks.
    sleep
        Seconds to sleep (not CPU work); for kill/resume tests.
    fail
        Raise :class:`~rubbercontact.errors.ConvergenceError` with diagnostics.
    calls_log
        Test hook: append one line to this file per call, to count executions.
        (The only side effect; it does not change the result.)

    Returns
    -------
    xarray.Dataset
        ``friction(wavelength)`` [-], ``storage_modulus``, ``loss_modulus`` [MPa]
        at ω = q v, ``m2`` [-], ``work_checksum``; scalar coordinates
        ``velocity`` [mm/s] and ``pressure`` [MPa].
    """
    if calls_log is not None:
        with open(calls_log, "a", encoding="utf-8") as fh:
            fh.write(f"{velocity} {pressure}\n")
    if not pressure > 0:
        raise InputError(f"pressure: must be > 0 MPa, got {pressure}")
    lam = np.asarray(wavelengths, dtype=float)
    amp = np.asarray(amplitudes, dtype=float)
    if lam.shape != amp.shape or lam.ndim != 1:
        raise InputError(f"wavelengths and amplitudes: expected equal-length 1-D lists, "
                         f"got {lam.shape} and {amp.shape}")
    mat = sbr() if material is None else GeneralizedMaxwell(**dict(material))
    if sleep > 0:
        time.sleep(sleep)
    checksum = _busy(int(work), float(velocity) + float(pressure))
    if fail:
        raise ConvergenceError(f"toy kernel: forced failure at v={velocity}, p={pressure}",
                               diagnostics={"iterations": 50, "residual": [1.0, 0.1, 0.03],
                                            "velocity": velocity, "pressure": pressure})
    q = 2.0 * np.pi / lam
    e_r = mat.complex_modulus(q * float(velocity)) / (1.0 - nu**2)
    m2 = q * amp / np.sqrt(2.0)
    friction = m2**2 * e_r.imag / (2.0 * float(pressure))
    return xr.Dataset(
        {"friction": ("wavelength", friction, {"units": "1"}),
         "storage_modulus": ("wavelength", e_r.real * (1.0 - nu**2), {"units": "MPa"}),
         "loss_modulus": ("wavelength", e_r.imag * (1.0 - nu**2), {"units": "MPa"}),
         "m2": ("wavelength", m2, {"units": "1"}),
         "work_checksum": ((), checksum)},
        coords={"wavelength": ("wavelength", lam, {"units": "mm"}),
                "velocity": ((), float(velocity), {"units": "mm/s"}),
                "pressure": ((), float(pressure), {"units": "MPa"})},
        attrs={"kernel": "toy_kernel", "nu": float(nu)})
