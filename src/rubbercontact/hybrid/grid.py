r"""The grid of the hybrid's low-slope half-space solve.

The VHS solves the whole surface ``z`` on ``n`` points per period; its resolution is set
by the shortest wave of ``z``, which gets ``n λ_min(z) / L`` points. The hybrid's
half-space solve sees only the low-slope waves ``z_ls`` (the high-slope ones are carried
by the law), whose shortest wave is longer: the same number of points per *its* shortest
wave needs a coarser grid. That is the rule here, a default of the method:

.. math:: n_{ls} = n / 2^k, \qquad \text{the largest } k \ge 0 \text{ with }
          n_{ls} \ge n\,\frac{\lambda_{min}(z)}{\lambda_{min}(z_{ls})}
          \text{ and } n_{ls} \ge n_{min}

i.e. ``n`` halved as long as the low-slope shortest wave keeps at least the points per
wave that the VHS grid gives the surface's shortest wave (so ``n_ls`` keeps the factors of
``n``, and powers of two stay powers of two), and never below ``n_min`` points. On the
octave-spaced Table 2 asphalt with its shortest wave alone high-slope, ``n = 8192``
gives ``n_ls = 4096``: 64 points per shortest wave in both solves.

Why it is enough: the low-slope contact patches are spans of the ``z_ls`` crests, and the
low-slope solve's μ and contact area converge with the points per low-slope wave (measured
on the asphalt, ``docs/findings.md``: within 0.5 % of n = 32768 at 64 points per
0.125 mm wave). The hybrid's answer can differ from its answer on the VHS grid only by
that discretization error (``tests/test_hybrid_grid.py``; the side-by-side on the 15-speed
asphalt curve is in ``benchmarks/halfspace_sweep.md``). ``halfspace.hybrid_n`` in the
run config overrides the rule (``hybrid_n = n`` is the old behaviour, one grid for both).
"""

from __future__ import annotations

from ..errors import InputError
from ..roughness import SineSeries

#: Fewest points of a derived low-slope grid (the config's smallest ``halfspace.n``).
MIN_LOW_SLOPE_POINTS = 64


def low_slope_points(n: int, surface: SineSeries, low: SineSeries,
                     n_min: int = MIN_LOW_SLOPE_POINTS) -> int:
    """Points per period of the hybrid's low-slope solve, by the equal-points-per-wave rule.

    Parameters
    ----------
    n
        Points per period of the VHS grid (``halfspace.n``) [-].
    surface
        The whole surface ``z`` (wavelengths [mm], shortest first).
    low
        Its low-slope part ``z_ls`` (a subset of the waves of ``surface``).
    n_min
        Fewest points of the derived grid [-] (``n`` itself if smaller).

    Returns
    -------
    int
        ``n_ls <= n``: ``n`` halved while ``n_ls λ_min(z_ls) >= n λ_min(z)`` (equal or
        more points per low-slope shortest wave than the VHS grid gives the shortest
        wave of ``z``) and ``n_ls >= n_min``. ``n`` when ``low`` is empty (flat: solved
        without a grid) or has the same shortest wave as ``surface``.
    """
    n = int(n)
    if n < 1:
        raise InputError(f"n: must be a positive number of grid points, got {n}")
    if low.size == 0 or surface.size == 0:
        return n
    lam_z, lam_ls = float(surface.wavelengths[0]), float(low.wavelengths[0])
    if lam_ls < lam_z * (1 - 1e-12):
        raise InputError(f"low: shortest wave {lam_ls} mm is shorter than the surface's "
                         f"{lam_z} mm (not a part of it)")
    need = n * lam_z / lam_ls            # points that keep the VHS's points per wave
    floor = min(n, int(n_min))
    m = n
    while m % 2 == 0 and m // 2 >= floor and m // 2 >= need * (1 - 1e-12):
        m //= 2
    return m
