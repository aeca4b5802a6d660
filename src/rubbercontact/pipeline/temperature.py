"""Spread results computed at reduced speeds over the run's temperatures and speeds.

By time–temperature superposition (:mod:`.speeds`) the result at ``(T, v)`` is the result
at the reduced speed ``a_T v`` at the reference temperature: every variable on the
computed ``velocity`` dimension is read at each ``(temperature, velocity)``'s reduced speed.
The results gain the dimension ``temperature`` [°C] (before ``velocity``), the coordinate
``reduced_velocity (temperature, velocity)`` [mm/s] and ``shift_factor (temperature)``.
"""

from __future__ import annotations

import xarray as xr

from .speeds import SpeedPlan


def spread_over_temperatures(ds: xr.Dataset, plan: SpeedPlan) -> xr.Dataset:
    """``ds`` (``velocity`` = ``plan.computed``) on ``temperature, velocity`` (module
    docstring); an isothermal plan returns ``ds`` unchanged."""
    if plan.isothermal:
        return ds
    index = xr.DataArray(plan.index, dims=("temperature", "velocity"))
    out = ds.drop_vars("velocity").isel(velocity=index)
    out = out.assign_coords(
        temperature=("temperature", plan.temperatures, {"units": "degC",
                                                        "long_name": "temperature"}),
        velocity=("velocity", plan.velocities, {"units": "mm/s"}),
        reduced_velocity=(("temperature", "velocity"), plan.reduced(), {
            "units": "mm/s", "long_name": "reduced speed a_T v at the reference temperature "
                                          "(where each point was computed)"}),
        shift_factor=("temperature", plan.shift_factors, {
            "units": "1", "long_name": "time-temperature shift factor a_T"}),
    )
    out.attrs["reference_temperature_C"] = plan.reference_temperature
    return out
