"""A run on an areal height map (``[surface.map]``): the VHS, the mean-field theory and the
hybrids with the linear law of the map's high-slope cell.

The map is read (:func:`rubbercontact.io.read_map`, detrended, periodized as the table says)
or synthesized (:func:`rubbercontact.roughness.self_affine_map`, periodic), then at every
speed and mean pressure of the run:

- ``vhs``: the 2D half-space on the map (:func:`rubbercontact.hybrid.solve_map`) with the
  run's ``halfspace.law`` and ``halfspace.tol``;
- ``meanfield``: Persson's theory on the map's spectrum
  (:func:`rubbercontact.roughness.mapstats.map_psd`: the radially pooled 2D periodogram),
  with the run's ``[meanfield]`` options;
- ``hybrid``, ``hybrid-windowed``: the map split at ``surface.m2_threshold``
  (:func:`rubbercontact.roughness.split_map`) and the hybrid on maps
  (:func:`rubbercontact.hybrid.solve_map_hybrid`, pointwise or with the law read at the
  pressure averaged over one high-slope period), the high-slope law being, in this step, the
  **linear** law of the cell (:func:`rubbercontact.hybrid.linear_law_map`, one per speed),
  not the FEM's. A map without a high-slope band has ``z_ls = z``: the hybrid is the VHS.

The solves run one after the other in this process (no task cache, no Dask workers).
What a map run does not do yet (the ``fem`` and ``meanfield-hybrid`` models, a ``[law]``
table, ``halfspace.n``, target contact areas, temperatures, realizations, adhesion, the
flash temperature) is refused when the config is loaded
(:class:`rubbercontact.config.RunConfig`). The results have dims ``model, velocity,
pressure``, the map's provenance and statistics in ``attrs["surface"]`` and, per model,
where the run leaves its validated class in ``attrs["validity_<model>"]``
(:mod:`rubbercontact.validity.maps`).
"""

from __future__ import annotations

import json
import time
from dataclasses import replace

import numpy as np
import xarray as xr

from ..config import MAP_DEFAULT_MODELS, RunConfig
from ..errors import ConvergenceError, InputError
from ..inputs import MapInput, build_material

#: Result variables of a map run: (units, long name).
MAP_VARIABLES = {
    "friction": ("1", "hysteretic friction coefficient mu"),
    "contact_fraction": ("1", "normalized real contact area A_c/A_0"),
    "mean_separation": ("mm", "mean interface separation (vhs)"),
    "wall_time": ("s", "wall time of the solve"),
}


def is_map_run(cfg: RunConfig) -> bool:
    """Whether ``cfg`` runs on a height map."""
    return cfg.surface.map is not None


def build_map(spec: MapInput):
    """The periodic :class:`~rubbercontact.roughness.HeightMap` a ``[surface.map]`` table
    describes (heights and lengths in mm)."""
    if spec.synthetic is not None:
        from ..roughness import self_affine_map

        s = spec.synthetic
        if s.kind == "from-profiles":
            return profiles_map(s)
        return self_affine_map((s.points, s.points), s.size, s.hurst,
                               rms_gradient=s.rms_gradient, seed=s.seed)
    from ..io.mapload import load_map

    return load_map(spec.file, fmt=spec.format, unit=spec.unit, dx=spec.dx, nan=spec.nan,
                    detrend=spec.detrend, periodize=spec.periodize)[1]


def profiles_map(spec):
    """The periodic map of a ``kind = "from-profiles"`` synthetic table: the line scans'
    pooled periodogram (:meth:`~rubbercontact.meanfield.PSD.from_profiles`) made an
    isotropic 2D spectrum (:func:`~rubbercontact.roughness.isotropic_from_line_psd`, which
    assumes no lay), its rings outside ``lower_cutoff``–``upper_cutoff`` dropped (after
    the inversion: a scan's spectrum holds the shorter waves' projections), realized on the
    ``points``² lattice of side ``size`` with random phases."""
    import numpy as np

    from ..inputs import read_profile_input
    from ..meanfield.psd import PSD
    from ..roughness import isotropic_from_line_psd, synthetic_map

    p = spec.profiles
    scans = read_profile_input(p)
    if len({z.size for z in scans.profiles}) > 1:   # one periodogram needs equal lengths
        scans = scans.windows(min(z.size for z in scans.profiles) * scans.dx)
    ring = isotropic_from_line_psd(PSD.from_profiles(scans))
    q = ring.wavenumbers
    keep = np.ones(q.size, bool)
    if p.lower_cutoff is not None:
        keep &= q <= 2 * np.pi / p.lower_cutoff
    if p.upper_cutoff is not None:
        keep &= q >= 2 * np.pi / p.upper_cutoff
    if not keep.any():
        raise InputError("surface.map.synthetic.profiles: no wavelength of the scans lies "
                         "between lower_cutoff and upper_cutoff")
    ring = PSD(q[keep], ring.variances[keep], 2, source=ring.source)
    hmap = synthetic_map(ring, (spec.points, spec.points), spec.size, seed=spec.seed)
    return replace(hmap, source={**hmap.source, "files": [str(f) for f in p.files],
                                 "n_scans": len(scans.profiles),
                                 "isotropy": "2D spectrum from the line scans', assuming "
                                             "isotropy (no lay)"})


def map_models(cfg: RunConfig) -> list[str]:
    """The models of a map run: the config's, or :data:`MAP_DEFAULT_MODELS` when it names
    none."""
    return list(cfg.models) if "models" in cfg.model_fields_set else list(MAP_DEFAULT_MODELS)


def map_info(hmap, threshold: float) -> dict:
    """The map's provenance and statistics (plain data, for ``attrs["surface"]``)."""
    from ..roughness.mapsplit import octave_bands
    from ..roughness.mapstats import anisotropy, rms_gradient, rms_height, rms_slope_x

    bands = octave_bands(hmap, threshold)
    high = bands["wavelength"].values[bands["high_slope"].values == 1]
    return {"source": "map", "map": dict(hmap.source), "shape": list(hmap.shape),
            "lengths_mm": list(hmap.lengths), "rms_height_mm": rms_height(hmap),
            "rms_gradient": rms_gradient(hmap), "rms_slope_x": rms_slope_x(hmap),
            "anisotropy": anisotropy(hmap)[0], "m2_threshold": threshold,
            "high_slope_wavelengths_mm": [float(w) for w in high]}


def _meanfield_options(cfg: RunConfig):
    return cfg.meanfield.options("meanfield")


def _hybrid(model: str, cfg: RunConfig, hmap, material, laws: dict):
    """The map hybrid's ``solve(v, σ0)``; ``laws`` caches the linear law per speed."""
    from ..hybrid.maps import MapHybridOptions, linear_law_map, solve_map_hybrid
    from ..roughness import split_map

    split = split_map(hmap, cfg.surface.m2_threshold)
    if split.cell is None:
        return _solver("vhs", cfg, hmap, material)
    opts = MapHybridOptions(law=cfg.halfspace.law, window=model == "hybrid-windowed",
                            nu=cfg.material.nu, tol=cfg.halfspace.tol)

    def hybrid(v: float, p: float) -> tuple[float, float, float]:
        if v not in laws:
            laws[v] = linear_law_map(split.cell, material, v, nu=cfg.material.nu)
        r = solve_map_hybrid(split, laws[v], material, v, p, opts)
        return r.friction, r.contact_fraction, r.mean_separation
    return hybrid


def _solver(model: str, cfg: RunConfig, hmap, material, laws: dict | None = None,
            keep: dict | None = None):
    """``solve(v, σ0) -> (μ, A_c/A_0, ū)`` of one model on the map; the VHS puts its last
    solution in ``keep["result"]`` and the note of each solve whose grid does not resolve
    the contact in ``keep["notes"]``
    (:func:`~rubbercontact.validity.halfspace.resolution_note`)."""
    if model in ("hybrid", "hybrid-windowed"):
        return _hybrid(model, cfg, hmap, material, {} if laws is None else laws)
    if model == "vhs":
        from ..halfspace import LennardJonesRepulsion
        from ..hybrid.maps import solve_map
        from ..validity.halfspace import resolution_note

        law = LennardJonesRepulsion() if cfg.halfspace.law == "lennard-jones" else None
        kept = {} if keep is None else keep

        def vhs(v: float, p: float) -> tuple[float, float, float]:
            r = solve_map(hmap, material, v, p, law, nu=cfg.material.nu, tol=cfg.halfspace.tol)
            kept["result"] = r
            note = resolution_note(r)
            if note is not None:
                kept.setdefault("notes", []).append(note)
            return r.friction, r.contact_fraction, r.mean_separation
        return vhs
    from ..meanfield import solve
    from ..roughness.mapstats import map_psd

    psd, opts = map_psd(hmap), _meanfield_options(cfg)

    def meanfield(v: float, p: float) -> tuple[float, float, float]:
        r = solve(psd, material, v, p, nu=cfg.material.nu, options=opts)
        return r.friction, r.contact_fraction, np.nan
    return meanfield


def run_map(cfg: RunConfig) -> xr.Dataset:
    """Run the map models of ``cfg`` (module docstring) and return the results dataset."""
    from .limits import check_pressures

    t_start = time.perf_counter()
    material = build_material(cfg.material)
    pressures = np.asarray(cfg.loads.pressures, float)
    check_pressures(pressures, material, "loads.pressures")
    speeds = np.asarray(cfg.velocities, float)
    hmap = build_map(cfg.surface.map)
    models = map_models(cfg)
    shape = (len(models), speeds.size, pressures.size)
    data = {k: np.full(shape, np.nan) for k in MAP_VARIABLES}
    status = np.full(shape, "ok", dtype=object)
    laws: dict = {}                          # the linear law per speed, shared by the hybrids
    keep: dict = {}
    contact = None                           # the VHS solution kept for the contact map
    for i, m in enumerate(models):
        solve = _solver(m, cfg, hmap, material, laws, keep)
        for j, v in enumerate(speeds):
            for k, p in enumerate(pressures):
                t0 = time.perf_counter()
                try:
                    out = solve(float(v), float(p))
                except ConvergenceError as exc:
                    status[i, j, k] = f"failed: {exc}"
                    continue
                for key, val in zip(("friction", "contact_fraction", "mean_separation"), out,
                                    strict=True):
                    data[key][i, j, k] = val
                data["wall_time"][i, j, k] = time.perf_counter() - t0
                if m == "vhs" and (j, k) == contact_point(speeds, pressures):
                    contact = keep["result"]
    ds = _dataset(cfg, hmap, material, models, speeds, pressures, data, status,
                  time.perf_counter() - t_start)
    ds = _with_validity(ds, hmap, material, cfg.surface.m2_threshold, keep.get("notes", ()))
    return _with_fields(ds, hmap, contact)


def _with_validity(ds: xr.Dataset, hmap, material, threshold: float,
                   solved: tuple | list = ()) -> xr.Dataset:
    """Each model's notes where the run leaves its validated class, one line a model, in
    ``attrs["validity_<model>"]`` as a 1D run has them (:mod:`rubbercontact.validity.maps`:
    every model's class was measured in 1D, so each has at least that note), with the
    notes of the solves themselves (``solved``: the VHS's unresolved contacts)."""
    from ..validity import as_attrs
    from ..validity.halfspace import worst_per_speed
    from ..validity.maps import assess_map_run

    notes = (*assess_map_run(ds, hmap, material, threshold), *worst_per_speed(solved))
    for m in ds["model"].values:
        ds.attrs.update(as_attrs(str(m), notes))
    return ds


def contact_point(speeds: np.ndarray, pressures: np.ndarray) -> tuple[int, int]:
    """Indices (speed, pressure) of the VHS solution kept as the run's contact map: the
    middle speed and the middle pressure."""
    return (speeds.size - 1) // 2, (pressures.size - 1) // 2


def _with_fields(ds: xr.Dataset, hmap, contact) -> xr.Dataset:
    """The map's heights and, when the VHS ran, its contact pressure at one speed and load
    (:func:`contact_point`), on dims ``y, x`` [mm]."""
    ds = ds.assign_coords(x=("x", hmap.x, {"units": "mm"}), y=("y", hmap.y, {"units": "mm"}))
    ds["heights"] = (("y", "x"), hmap.heights, {"units": "mm", "long_name": "surface height"})
    if contact is not None:
        ds["contact_pressure"] = (("y", "x"), np.asarray(contact.pressure), {
            "units": "MPa", "long_name": "contact pressure of the VHS",
            "velocity": contact.velocity, "mean_pressure": contact.mean_pressure,
            "friction": contact.friction, "contact_fraction": contact.contact_fraction})
    return ds


def _dataset(cfg, hmap, material, models, speeds, pressures, data, status, total
             ) -> xr.Dataset:
    from .. import __version__
    from .execute import RESULTS_FORMAT

    dims = ("model", "velocity", "pressure")
    ds = xr.Dataset({k: (dims, v, {"units": MAP_VARIABLES[k][0],
                                   "long_name": MAP_VARIABLES[k][1]})
                     for k, v in data.items()},
                    coords={"model": list(models),
                            "velocity": ("velocity", speeds, {"units": "mm/s"}),
                            "pressure": ("pressure", pressures, {"units": "MPa"})})
    ds["status"] = (dims, status.astype(str))
    ds.attrs.update({
        "title": "rubbercontact results on a height map",
        "rubbercontact_version": __version__,
        "surface_kind": "map",
        # with the models it ran: the dump re-parses to the same run
        "config": cfg.model_copy(update={"models": list(models)}).model_dump_json(),
        "surface": json.dumps(map_info(hmap, cfg.surface.m2_threshold), default=str),
        "material": json.dumps(material.as_dict()),
        "timings_s": json.dumps({"total": total}),
        "results_format": RESULTS_FORMAT,
    })
    if any(m.startswith("hybrid") for m in models):
        ds.attrs["high_slope_law"] = ("linear: the 2D half-space on the map's high-slope "
                                      "cell (linear_law_map), one per speed")
    return ds


def map_summary(ds: xr.Dataset) -> str:
    """μ and ``A_c/A_0`` of a map run per model, speed and pressure, as text."""
    info = json.loads(ds.attrs["surface"])
    ny, nx = info["shape"]
    ly, lx = info["lengths_mm"]
    lines = [f"map: {ny} x {nx} points, {ly:.4g} x {lx:.4g} mm, rms gradient "
             f"{info['rms_gradient']:.4g}, rms slope along x {info['rms_slope_x']:.4g}, "
             f"anisotropy {info['anisotropy']:.3g}",
             f"{'model':>15} {'v [mm/s]':>10} {'sigma0 [MPa]':>12} {'mu':>9} {'A/A0':>8} "
             f"{'time [s]':>9}"]
    for m in ds["model"].values:
        for v in ds["velocity"].values:
            for p in ds["pressure"].values:
                r = ds.sel(model=m, velocity=v, pressure=p)
                lines.append(f"{m:>15} {v:10.4g} {p:12.4g} {float(r['friction']):9.5f} "
                             f"{float(r['contact_fraction']):8.4f} "
                             f"{float(r['wall_time']):9.3g}")
    notes = [line for k, v in ds.attrs.items() if k.startswith("validity_")
             for line in str(v).splitlines() if line]
    if notes:    # results written before the map runs had notes have none
        lines += ["", "outside the validated class (docs/guide/models.md, 'Where each model "
                      "was validated'):", *(f"  {n}" for n in notes)]
    return "\n".join(lines)


def describe_map_plan(cfg: RunConfig) -> str:
    """What a map run of ``cfg`` will compute (the map is built: a file is read)."""
    hmap = build_map(cfg.surface.map)
    ny, nx = hmap.shape
    return "\n".join([
        f"config ok: a run on a height map, models {', '.join(map_models(cfg))}",
        f"map: {ny} x {nx} points, {hmap.lengths[0]:.4g} x {hmap.lengths[1]:.4g} mm "
        f"({hmap.source.get('path') or hmap.source.get('synthetic')})",
        f"speeds: {len(cfg.velocities)}; pressures: "
        f"{', '.join(f'{p:g}' for p in cfg.loads.pressures)} MPa; solved one after the "
        f"other in this process"])
