"""The linear (VHS) law of the high-slope wave.

:func:`linear_law` stands in for the FEM law (the hybrid's error is then its scale split
alone); :func:`continue_with_linear_shape` continues an FEM law past its highest pressure
with the linear law's shape.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .lawtable import max_height


def linear_law(hs_surface: SineSeries, material: GeneralizedMaxwell, velocity: float, *,
               n: int = 2048, nu: float = 0.5, points: int = 80) -> dict:
    """The VHS (linear) law of the high-slope wave alone, as a table like :func:`law_at_velocity`.

    Hard-wall VHS solves at ``points`` pressures from 1e-3 to 50 MPa (geometric), up to
    full contact, plus the zero-load anchor ``(max z_hs, 0, 0, 0)``. With it in place of
    the FEM law the hybrid's remaining error is its scale split alone.
    """
    from .. import halfspace

    rows = []
    for p in np.geomspace(1e-3, 50.0, int(points)):
        r = halfspace.solve_sliding(hs_surface, hs_surface.period, material, velocity,
                                    float(p), n=n, nu=nu)
        if r.contact_fraction >= 0.999:   # full contact: u stops changing
            break
        rows.append((r.mean_separation, p, r.contact_fraction, r.friction * p))
    u, sig, alpha, tau = (np.array(c) for c in zip(*sorted(rows), strict=True))
    return {"separation": [*u, max_height(hs_surface)], "pressure": [*sig, 0.0],
            "contact_fraction": [*alpha, 0.0], "shear_stress": [*tau, 0.0]}


def continue_with_linear_shape(table: dict, hs_surface: SineSeries,
                               material: GeneralizedMaxwell, velocity: float, *,
                               n: int = 2048, nu: float = 0.5, factor: float = 1.25,
                               max_rows: int = 40) -> dict:
    """Continue a law table past its highest FEM pressure with the shape of the linear law.

    The FEM cell of a steep wave is crushed beyond ~1.5 E∞, while the low-slope solve may
    load the high-slope scale locally to several times that. Beyond the last FEM point
    ``(σ₀, ū₀, α₀, Δτ₀)`` the rows follow the viscoelastic half-space (VHS) law of the same
    wave, anchored multiplicatively at that point::

        ū(σ) = ū₀ ū_V(σ)/ū_V(σ₀),  α(σ) = min(1, α₀ α_V(σ)/α_V(σ₀)),
        Δτ(σ) = Δτ₀ Δτ_V(σ)/Δτ_V(σ₀),

    at ``σ = σ₀ factor^k`` until the VHS reaches 99 % contact (``max_rows`` at most). The
    continuation is exact when the FEM law equals the VHS law, keeps ``ū > 0`` and
    decreasing, and reaches the linear theory's full-contact behaviour (``Δτ`` independent
    of ``σ``) instead of holding ``Δτ`` or ``Δτ/σ`` at the last FEM value. It is an
    extrapolation all the same: :func:`check_coverage` still warns when it is used.

    Parameters
    ----------
    table
        Output of :func:`law_at_velocity` (``u`` ascending, highest pressure first).
    hs_surface, material, velocity
        The high-slope wave, the rubber and the speed [mm/s] of the table.
    n, nu
        Grid points and Poisson ratio of the VHS solves (hard wall).
    factor
        Pressure ratio between continuation rows (> 1).
    max_rows
        Most rows added.

    Returns
    -------
    dict
        The table with the continuation rows prepended (same keys).
    """
    from .. import halfspace

    u = np.asarray(table["separation"], float)
    sig = np.asarray(table["pressure"], float)
    alpha = np.asarray(table["contact_fraction"], float)
    tau = np.asarray(table["shear_stress"], float)
    if not factor > 1:
        raise InputError(f"factor: must be > 1, got {factor}")

    def vhs(p):
        r = halfspace.solve_sliding(hs_surface, hs_surface.period, material, velocity, p,
                                    law=None, n=n, nu=nu)
        return r.mean_separation, r.contact_fraction, r.friction * p

    if material.is_elastic:
        return table        # no hysteresis: no shear stress to borrow the shape of
    s0 = float(sig[0])
    ref = vhs(s0)
    if not (ref[0] > 0 and ref[1] > 0 and ref[2] > 0 and tau[0] > 0):
        return table        # no shape to borrow (full contact at σ₀)
    rows = []
    p, u_last = s0, ref[0]
    for _ in range(int(max_rows)):
        p *= factor
        uv, av, tv = vhs(p)
        # stop at (near) full contact, where the VHS separation stops decreasing
        if av >= 0.99 or not 0 < uv < u_last:
            break
        u_last = uv
        rows.append((u[0] * uv / ref[0], p, min(1.0, alpha[0] * av / ref[1]),
                     tau[0] * tv / ref[2]))
    ext = np.array(rows[::-1]).reshape(-1, 4)   # ascending in u
    return {"separation": [*ext[:, 0], *u], "pressure": [*ext[:, 1], *sig],
            "contact_fraction": [*ext[:, 2], *alpha], "shear_stress": [*ext[:, 3], *tau]}


def linear_law_table(hs_surface: SineSeries, material: GeneralizedMaxwell,
                     velocities, pressures, *, n: int = 1024, nu: float = 0.5):
    """The VHS law as a run's law table (``xarray.Dataset`` on ``velocity × pressure``, as
    a run's ``law.nc``), e.g. for ``pipeline.run(cfg, law=...)`` without the FEM.

    Points in (near) full contact (``A >= 0.99``) have the status ``"excluded: full
    contact"``, where the mean separation stops changing with the pressure.
    """
    import json

    import xarray as xr

    from .. import halfspace

    v, p = np.asarray(velocities, float), np.asarray(pressures, float)
    names = ("mean_separation", "contact_fraction", "shear_stress", "friction", "wall_time")
    data = {k: np.zeros((v.size, p.size)) for k in names}
    for i, vi in enumerate(v):
        for j, pj in enumerate(p):
            r = halfspace.solve_sliding(hs_surface, hs_surface.period, material, float(vi),
                                        float(pj), n=n, nu=nu)
            for k, x in zip(names, (r.mean_separation, r.contact_fraction, r.friction * pj,
                                    r.friction, 0.0), strict=True):
                data[k][i, j] = x
    law = xr.Dataset({k: (("velocity", "pressure"), a) for k, a in data.items()},
                     coords={"velocity": v, "pressure": p})
    law["status"] = (("velocity", "pressure"),
                     np.where(data["contact_fraction"] >= 0.99, "excluded: full contact", "ok"))
    law.attrs.update({"hs_wavelengths_mm": hs_surface.wavelengths.tolist(),
                      "hs_amplitudes_mm": hs_surface.amplitudes.tolist(),
                      "hs_phases_rad": hs_surface.phases.tolist(),
                      "hs_max_height_mm": float(max_height(hs_surface)),
                      "material": json.dumps(material.as_dict())})
    return law
