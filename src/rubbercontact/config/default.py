"""The built-in default run of ``rubbercontact run`` (no config given)."""

from __future__ import annotations

from .parse import parse_config
from .run import RunConfig


def default_config() -> RunConfig:
    """Built-in default of ``rubbercontact run``: a reduced paper §3 case at the paper's two
    speeds, by the VHS, both hybrids and the full FEM."""
    return parse_config(DEFAULT_CONFIG, source="<built-in default>")


#: Reduced section 3 validation (paper §3): three waves, coarse FEM, sized for 2 cores and
#: an empty result cache. Both FEM uses (the law cell and the full cell) solve the steady
#: state directly (fem.solver = "steady"): creep-settled by construction. The law stops at
#: 2 MPa: at 4 MPa its cell sheared as a whole (a friction stress above E∞/3) and the points
#: were excluded as non-monotone, so the table ended at 2 MPa anyway. The full FEM runs on
#: one realization, the cheap models on eight: the FEM's phase average is estimated with
#: the VHS as control variate (fem.realizations),
#: the workflow that makes the FEM comparison affordable. The eq. 28 figures the default
#: prints are a demonstration (one FEM realization, three loads), not the validation
#: (VALIDATION.md).
DEFAULT_CONFIG: dict = {
    "surface": {"preset": "section3"},
    "material": {"preset": "sbr"},
    "loads": {"pressures": [0.15, 0.25, 0.35]},
    "velocities": [10.0, 50.0],          # the paper's two speeds
    "realizations": 8,
    "seed": 2021,
    "models": ["vhs", "hybrid", "hybrid-windowed", "fem"],
    "halfspace": {"n": 2048},
    # law: 40 elements per 0.0625 mm wavelength; full FEM: 16 per 0.0625 mm wavelength
    "fem": {"mesh": [40, 30], "full_mesh": [64, 48], "realizations": 1},
    "law": {"pressures": [0.05, 0.1, 0.2, 0.5, 1.0, 2.0]},
    "execution": {"workers": 2},
    "output": {"directory": "results"},
}
