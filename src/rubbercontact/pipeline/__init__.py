"""The run pipeline: a config's models on its surfaces, speeds, temperatures and loads.

``run(config)`` builds the surface (preset, sine table, or a fit of measured profiles),
draws random-phase realizations, partitions each into high- and low-slope parts, computes
the effective law of the high-slope scale with the FEM, and runs, on the same loads:

- ``vhs``: the viscoelastic half-space on the whole surface;
- ``hybrid``: the half-space on ``z_ls`` with the integrated-LJ + ``σ_hs`` law,
  ``μ = μ_ls + μ_hs`` (eqs. 5–7) and ``A_c`` by eq. 8;
- ``hybrid-windowed``: the same solve, with ``μ_hs`` and ``A_c`` reading the law at the
  low-slope pressure averaged over one high-slope period
  (:mod:`rubbercontact.hybrid.windowing`);
- ``fem``: the FEM sliding test on the whole surface (cell width = longest wavelength);
- ``meanfield``: Persson's theory on the surface's spectrum (:mod:`rubbercontact.meanfield`);
- ``meanfield-hybrid``: the theory on the low-slope spectrum, enriched by the same law.

The result is one ``xarray.Dataset`` (:func:`run`). Modules: :mod:`.setup` (surfaces,
material, checks), :mod:`.speeds` (temperatures and reduced speeds), :mod:`.loads`,
:mod:`.lawstage`, :mod:`.plan` (the tasks), :mod:`.assemble`, :mod:`.adhesion`,
:mod:`.statistics`, :mod:`.temperature`, :mod:`.execute` (the run itself).

The package sits above :mod:`rubbercontact.hybrid`, :mod:`rubbercontact.meanfield` and
:mod:`rubbercontact.io`, which do not import it.
"""

from .execute import RESULTS_FORMAT, Runner, as_config, make_runner, run
from .setup import RunSetup, resolve
from .speeds import SpeedPlan, plan_speeds
from .statistics import Peak, friction_peak

__all__ = ["run", "make_runner", "as_config", "Runner", "RESULTS_FORMAT", "resolve",
           "RunSetup", "SpeedPlan", "plan_speeds", "Peak", "friction_peak"]
