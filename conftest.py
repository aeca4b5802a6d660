"""Fixtures shared by the package's tests (``tests/``) and the studies' (``studies/tests/``).

Fixtures of one of the two live in its own ``conftest.py``; here only what both use, so that
one piece of code makes it (``tests/`` imports only the package, ``studies/tests/`` may
import ``studies``: neither can import the other's helpers).

- ``phase_data``: hand-made realizations in the layout of the phase-averaged eq. 28
  (:func:`rubbercontact.compare.phase_mean_curves`), whose answers are known in closed form.
"""

from __future__ import annotations

import numpy as np
import pytest


def _phase_data(pressures=(0.15, 0.35, 0.8), r: int = 10, n: int = 200,
                offset: float = 0.02) -> dict:
    """VHS-like curves varying with the phase at ``pressures`` [MPa]; FEM = VHS − ``offset``
    in friction, same area, on the first ``r`` realizations; every hybrid equal to the VHS
    on all ``n``. The phases depend on ``n`` only, so data at other loads (same ``n``)
    merge with the default's (:func:`rubbercontact.compare.merge_phase_data`)."""
    rng = np.random.default_rng(3)
    phi = rng.uniform(0, 2 * np.pi, n)
    p = np.asarray(pressures, float)
    area = 0.03 * p ** 0.8 * (1 + 0.1 * np.sin(phi))[:, None]
    mu = 0.4 + 0.5 * p ** 0.5 * (1 + 0.2 * np.cos(phi))[:, None]
    every = {m: (area, mu) for m in ("hybrid", "hybrid-windowed", "vhs")}
    return {"pressures": p, "fem": (area[:r], mu[:r] - offset),
            "paired": {m: (a[:r], x[:r]) for m, (a, x) in every.items()}, "all": every}


@pytest.fixture(scope="session")
def phase_data():
    """``phase_data(pressures=(0.15, 0.35, 0.8), r=10, n=200, offset=0.02)``: a fresh dict
    of hand-made phase realizations on every call (:func:`_phase_data`)."""
    return _phase_data
