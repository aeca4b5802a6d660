"""The summary table leads with the phase average over the realizations and its spread."""

import numpy as np
import xarray as xr

from rubbercontact.plotting.summary import summary_table


def test_summary_prints_the_phase_average_and_the_spread():
    mu = np.array([[[[0.40], [0.50], [0.60], [0.70]]]])         # model, v, realization, p
    area = np.full_like(mu, 0.02)
    dims = ("model", "velocity", "realization", "pressure")
    ds = xr.Dataset({"friction": (dims, mu), "contact_fraction": (dims, area)},
                    coords={"model": ["vhs"], "velocity": [10.0], "realization": range(4),
                            "pressure": [0.3]})
    for k in ("friction", "contact_fraction"):
        ds[f"{k}_mean"] = ds[k].mean("realization")
    text = summary_table(ds)
    assert "phase average over 4 realizations" in text
    row = next(line for line in text.splitlines() if line.strip().startswith("0.3"))
    assert row.split()[:2] == ["0.3", "vhs"]
    # mean 0.55, population standard deviation sqrt(0.0125) = 0.1118
    assert "0.5500 ±0.11" in row
    # no spread to state for a quantity equal in every realization: ±0
    assert row.endswith("0.0200 ±0")
