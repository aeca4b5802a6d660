r"""Synthetic isotropic height maps from a spectrum, and the isotropic spectrum of a line scan.

A synthetic map is a random-phase trigonometric polynomial on the map's lattice: each mode
``k`` gets the variance ``P_k`` the spectrum assigns it and a random phase (the phases of
the FFT of Gaussian white noise, so that ``ẑ_{−k} = ẑ_k*`` and the map is real). The power
per mode is exact, not random: the map's periodogram is the target on the lattice, so its
rms height and rms gradient are the spectrum's (restricted to the lattice's wavenumbers).

From a line-scan spectrum (e.g. the CAPTIF road's), :func:`isotropic_from_line_psd` assumes
the surface is **isotropic** — a line scan in any direction has the same statistics — and
recovers the 2D spectrum whose line scans have it (the discrete inverse Abel transform): a
ring of variance ``V`` at ``|q| = k`` puts ``(2/π) V dq_x/sqrt(k² − q_x²)`` into the line
scan's spectrum on ``0 <= q_x < k``. A real road with a lay (longitudinal texture) is not
isotropic; measure a map when that matters.
"""

from __future__ import annotations

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from .maps import HeightMap


def _shape_lengths(shape, lengths) -> tuple[tuple[int, int], tuple[float, float]]:
    if np.ndim(shape) != 1 or len(shape) != 2 or any(int(n) != n or n < 4 for n in shape):
        raise InputError(f"shape: expected (ny, nx), integers >= 4, got {shape!r}")
    if np.ndim(lengths) == 0:
        lx = positive_scalar("lengths", lengths, unit="mm")
        lens = (lx * shape[0] / shape[1], lx)
    elif len(lengths) == 2:
        lens = tuple(positive_scalar(n, v, unit="mm")
                     for n, v in zip(("Ly", "Lx"), lengths, strict=True))
    else:
        raise InputError(f"lengths: expected Lx or (Ly, Lx) in mm, got {lengths!r}")
    return (int(shape[0]), int(shape[1])), lens


def _lattice(shape, lengths) -> np.ndarray:
    """``|q|`` [rad/mm] on the full FFT grid (numpy order)."""
    qy = 2 * np.pi * np.fft.fftfreq(shape[0], lengths[0] / shape[0])
    qx = 2 * np.pi * np.fft.fftfreq(shape[1], lengths[1] / shape[1])
    return np.hypot(*np.meshgrid(qy, qx, indexing="ij"))


def realize(power: np.ndarray, seed: int | None) -> np.ndarray:
    """The real map whose modes have the variances ``power`` (full FFT grid, ``P(−k) =
    P(k)``) and random phases (of white noise's FFT, seeded)."""
    rng = np.random.default_rng(seed)
    w = np.fft.fft2(rng.standard_normal(power.shape))
    phase = w / np.where(np.abs(w) > 0, np.abs(w), 1.0)
    return np.fft.ifft2(np.sqrt(power) * phase).real * power.size


def synthetic_map(spectrum, shape, lengths, seed: int | None = 0) -> HeightMap:
    """A periodic isotropic map with the spectrum ``spectrum`` (module docstring).

    Parameters
    ----------
    spectrum
        A :class:`rubbercontact.meanfield.PSD`: 2D (isotropic), or 1D (a line scan's,
        turned 2D by :func:`isotropic_from_line_psd`, which assumes isotropy). Each node
        ``(q_i, v_i)`` gives its variance to the lattice shell (the modes of one ``|q|``)
        nearest to it in ``log q``, whose modes share it equally: the variance is kept
        exactly, the slope up to the shift from ``q_i`` to the shell (small where the
        shells are dense, i.e. everywhere but the lowest few modes).
    shape, lengths
        ``(ny, nx)`` points and ``Lx`` or ``(Ly, Lx)`` [mm] (the period).
    seed
        Of the phases.

    Returns
    -------
    HeightMap
        Periodic. ``source["variance_on_lattice"]`` is the fraction of the spectrum's
        variance the lattice holds (nodes more than half a shell spacing below the
        lowest or above the highest lattice wavenumber are left out).
    """
    from ..meanfield.psd import PSD

    if not isinstance(spectrum, PSD):
        raise InputError(f"spectrum: expected a meanfield.PSD, got {type(spectrum).__name__}")
    shape, lengths = _shape_lengths(shape, lengths)
    note = {}
    if spectrum.dimension == 1:
        spectrum = isotropic_from_line_psd(spectrum)
        note["isotropy"] = "2D spectrum from a line scan's, assuming isotropy"
    power, held = _shell_power(spectrum.wavenumbers, spectrum.variances,
                               _lattice(shape, lengths))
    z = realize(power, seed)
    src = {"synthetic": spectrum.source, "seed": seed, "variance_on_lattice": held, **note}
    return HeightMap(z, lengths, periodic=True, source=src)


def self_affine_map(shape, lengths, hurst: float, *, rms_gradient: float | None = None,
                    rms_height: float | None = None, q_roll: float | None = None,
                    q_cut: float | None = None, seed: int | None = 0) -> HeightMap:
    """A periodic isotropic self-affine map: ``C(q) ∝ q^−2(1+H)`` on ``[q_roll, q_cut]``,
    flat below ``q_roll``, 0 above ``q_cut``, scaled to the exact rms gradient (or rms
    height) on the lattice.

    Parameters
    ----------
    shape, lengths
        ``(ny, nx)`` and ``Lx`` or ``(Ly, Lx)`` [mm].
    hurst
        ``H`` in (0, 1).
    rms_gradient, rms_height
        Exactly one: ``sqrt(<|∇z|²>)`` [-] or ``sqrt(<z²>)`` [mm].
    q_roll, q_cut
        Roll-off and cut-off [rad/mm]; defaults ``2π/max(Lx, Ly)`` and the Nyquist
        wavenumber ``π/max(dx, dy)``.
    seed
        Of the phases.
    """
    shape, lengths = _shape_lengths(shape, lengths)
    h = positive_scalar("hurst", hurst)
    if not h < 1:
        raise InputError(f"hurst: must lie in (0, 1), got {hurst}")
    if (rms_gradient is None) == (rms_height is None):
        raise InputError("self_affine_map: give exactly one of rms_gradient and rms_height")
    k = _lattice(shape, lengths)
    qr = (2 * np.pi / max(lengths) if q_roll is None
          else positive_scalar("q_roll", q_roll, unit="rad/mm"))
    qc = (np.pi / max(lengths[0] / shape[0], lengths[1] / shape[1]) if q_cut is None
          else positive_scalar("q_cut", q_cut, unit="rad/mm"))
    if not qr < qc:
        raise InputError(f"q_roll: {qr:g} rad/mm must be below q_cut {qc:g} rad/mm")
    power = np.where((k > 0) & (k <= qc * (1 + 1e-12)),
                     np.maximum(k, qr) ** (-2 * (1 + h)), 0.0)
    if not power.any():
        raise InputError("q_cut: no lattice mode below the cut-off")
    if rms_gradient is not None:
        power *= positive_scalar("rms_gradient", rms_gradient) ** 2 / np.sum(k**2 * power)
    else:
        power *= positive_scalar("rms_height", rms_height, unit="mm") ** 2 / power.sum()
    src = {"synthetic": f"self-affine H={h:g}, q_roll={qr:g}, q_cut={qc:g} rad/mm",
           "seed": seed}
    return HeightMap(realize(power, seed), lengths, periodic=True, source=src)


def _shell_power(q: np.ndarray, v: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, float]:
    """Mode variances on the lattice ``|q| = k`` from the nodes ``(q, v)``, and the fraction
    of ``Σ v`` kept (:func:`synthetic_map`)."""
    radii, shell = np.unique(np.round(k, 12), return_inverse=True)
    shell = shell.reshape(k.shape)
    r = np.log(radii[1:])                      # radii[0] is the mean mode
    if r.size < 2:
        raise InputError("shape: the lattice needs at least two distinct wavenumbers")
    mid = np.concatenate([[1.5 * r[0] - 0.5 * r[1]], 0.5 * (r[1:] + r[:-1]),
                          [1.5 * r[-1] - 0.5 * r[-2]]])
    idx = np.digitize(np.log(q), mid) - 1
    ok = (idx >= 0) & (idx < r.size)
    shell_var = np.zeros(radii.size)
    np.add.at(shell_var, idx[ok] + 1, v[ok])
    count = np.bincount(shell.ravel(), minlength=radii.size)
    return (shell_var / np.maximum(count, 1))[shell], float(v[ok].sum() / v.sum())


def _cell_edges(q: np.ndarray) -> np.ndarray:
    """Radial cell edges: geometric midpoints, the outer ones mirrored (as PSD.density)."""
    if q.size == 1:
        return np.array([q[0] / np.sqrt(2.0), q[0] * np.sqrt(2.0)])
    return np.concatenate([[q[0] ** 1.5 / q[1] ** 0.5], np.sqrt(q[1:] * q[:-1]),
                           [q[-1] ** 1.5 / q[-2] ** 0.5]])


def isotropic_from_line_psd(psd):
    """The isotropic 2D spectrum whose line scans have the 1D spectrum ``psd``.

    Rings at the 1D nodes ``q_i`` with variances ``V_i >= 0`` solve
    ``Σ_i A_ji V_i = v_j`` from the highest node down (the discrete inverse Abel
    transform), ``A_ji`` the share of ring ``i``'s variance that a line scan sees in the 1D
    cell ``j`` (module docstring; the lowest cell reaches down to 0). Each 1D cell is then
    matched exactly, unless its ring would be negative — a line-scan spectrum that falls
    faster towards low ``q`` than an isotropic surface's can — where the ring is set to 0
    (the source says how much of the variance is kept). On a power law ``C1 ∝ q^−(1+2H)``
    the result is the closed form ``C = C1 Γ(H+1)/(2√π q Γ(H+½))`` to 0.5 % with 32 nodes
    per decade (tested). Assumes isotropy (module docstring).

    Returns
    -------
    rubbercontact.meanfield.PSD
        ``dimension=2``, on the same nodes.
    """
    from ..meanfield.psd import PSD

    if not isinstance(psd, PSD) or psd.dimension != 1:
        raise InputError("psd: expected a 1D (line-scan) meanfield.PSD")
    q, v = psd.wavenumbers, psd.variances
    edges = _cell_edges(q)
    edges[0] = 0.0
    lo, hi = edges[:-1, None], edges[1:, None]
    k = q[None, :]
    # a ring reaches only the cells below it: A is upper triangular
    a = (2 / np.pi) * (np.arcsin(np.minimum(hi, k) / k) - np.arcsin(np.minimum(lo, k) / k))
    rings = np.zeros(q.size)
    for i in range(q.size - 1, -1, -1):
        rings[i] = max(0.0, (v[i] - a[i, i + 1:] @ rings[i + 1:]) / a[i, i])
    kept = float(rings.sum() / v.sum())
    return PSD(q, rings, 2, source=f"isotropic 2D spectrum of {psd.source or 'a line scan'} "
                                   f"(variance kept {kept:.3g})")
