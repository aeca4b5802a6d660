"""A run plans its tasks by asking the model registry (issue 38 item 2).

The task arguments are the cache keys: the expectation here is written independently of
the models' planning, from the task functions' signatures and the config, as the pipeline
wrote them when it chose tasks by model name.
"""

from __future__ import annotations

import copy
import dataclasses
import importlib
import inspect

import numpy as np
import pytest

from rubbercontact.config import DEFAULT_CONFIG, MODELS, parse_config
from rubbercontact.hybrid.grid import low_slope_points
from rubbercontact.models import registry
from rubbercontact.models.planning import PER, Planning, RunPoint
from rubbercontact.pipeline.plan import model_tasks
from rubbercontact.pipeline.setup import (
    resolve,
    static_series,
    task_material,
    translated_to_zero_phase,
)

ALL = ["vhs", "hybrid", "hybrid-windowed", "fem", "meanfield", "meanfield-hybrid",
       "meanfield-strips"]
TABLE = {"separation": [0.01, 0.02], "pressure": [1.0, 0.0], "contact_fraction": [0.5, 0.0],
         "shear_stress": [0.3, 0.0]}


def _configs() -> dict:
    every = copy.deepcopy(DEFAULT_CONFIG) | {"models": ALL, "realizations": 3, "meanfield": {
        "gamma": 0.6, "interface": "rigid", "outer_crests": False}}
    gentle = {"surface": {"wavelengths": [0.25, 1.0], "amplitudes": [0.01, 0.04]},
              "loads": {"pressures": [0.1, 0.3]}, "velocities": [10.0, 100.0],
              "realizations": 2, "models": ALL, "fem": {"mesh": [40, 30]},
              "halfspace": {"n": 512, "hybrid_n": 256, "tol": 1e-6}}
    steep = {"surface": {"wavelengths": [0.0625], "amplitudes": [0.02]},
             "loads": {"pressures": [0.2]}, "velocities": [10.0], "realizations": 2,
             "models": ALL, "halfspace": {"n": 256}, "fem": {"mesh": [40, 30]}}
    return {"default": copy.deepcopy(DEFAULT_CONFIG), "every model": every,
            "no high-slope wave": gentle, "all high-slope": steep}


def _halfspace(cfg, setup, m, ir, mat, v, pressures, table) -> dict:
    real, parts = setup.realizations[ir], setup.parts[ir]
    hsc, high = cfg.halfspace, parts.high.size > 0
    hybrid = m in ("hybrid", "hybrid-windowed")
    kw = {"surface": (parts.low if hybrid and high else real).as_dict(),
          "period": float(setup.base.period), "material": task_material(mat),
          "velocity": v, "mean_pressures": [float(p) for p in pressures],
          "n": (hsc.hybrid_n or low_slope_points(hsc.n, real, parts.low)) if hybrid and high
          else hsc.n, "nu": cfg.material.nu, "law": hsc.law, "tol": hsc.tol,
          "interface_law": table if hybrid else None, "keep_profile": ir == 0}
    if m == "hybrid-windowed" and high:
        kw["hs_window"] = float(setup.hs0.period)
    return kw


def _meanfield(cfg, setup, m, mat, v, p, table) -> tuple[str, dict]:
    series = static_series(setup.base)
    high, low = series.partition(cfg.surface.m2_threshold)
    surface = (low if high.size else series) if m == "meanfield-hybrid" else series
    law = table if m == "meanfield-hybrid" else None
    if law is not None and low.size == 0:
        return "rubbercontact.hybrid.tasks:halfspace_task", {
            "surface": surface.as_dict(), "period": setup.base.period,
            "material": task_material(mat), "velocity": v, "mean_pressure": p,
            "n": cfg.halfspace.n, "nu": cfg.material.nu, "law": cfg.halfspace.law,
            "interface_law": law}
    opts = cfg.meanfield.options("meanfield" if m == "meanfield-hybrid" and law is None
                                 else m)
    return "rubbercontact.meanfield.tasks:meanfield_task", {
        "surface": surface.as_dict(), "material": task_material(mat), "velocity": v,
        "mean_pressure": p, "nu": cfg.material.nu, "interface_law": law,
        "options": opts.to_dict()}


def _expected(cfg, setup, pressures, tables) -> list[tuple]:
    """(model, iv, ir, ip, function, kwargs) of every task, by model name."""
    out, mat = [], setup.material
    for m in setup.models:
        for iv, v in enumerate(float(v) for v in setup.speeds.computed):
            table = tables.get(v)
            if m in ("vhs", "hybrid", "hybrid-windowed"):
                out += [(m, iv, ir, None, "rubbercontact.hybrid.tasks:halfspace_loads_task",
                         _halfspace(cfg, setup, m, ir, mat, v, pressures, table))
                        for ir in range(len(setup.realizations))]
            elif m == "fem":
                out += [(m, iv, ir, ip, "rubbercontact.hybrid.tasks:fem_task", {
                    "surface": translated_to_zero_phase(setup.realizations[ir]).as_dict(),
                    "material": task_material(mat), "velocity": v, "mean_pressure": float(p),
                    "options": cfg.fem.options(mat, full=True).to_dict()})
                    for ip, p in enumerate(pressures) for ir in range(setup.n_fem)]
            else:
                out += [(m, iv, None, ip, *_meanfield(cfg, setup, m, mat, v, float(p), table))
                        for ip, p in enumerate(pressures)]
    return out


@pytest.mark.parametrize("name", list(_configs()))
@pytest.mark.parametrize("with_law", [False, True])
def test_the_registry_plans_the_tasks_the_model_names_did(name, with_law):
    cfg = parse_config(_configs()[name])
    setup = resolve(cfg)
    pressures = np.asarray(cfg.loads.pressures, float)
    tables = {float(v): dict(TABLE) for v in setup.speeds.computed} if with_law else {}
    slots, tasks = model_tasks(setup, setup.material, pressures, tables)
    got = [(*s, t.function, t.kwargs) for s, t in zip(slots, tasks, strict=True)]
    want = _expected(cfg, setup, pressures, tables)
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert g[:5] == w[:5]
        # equal and in the same key order: the arguments are the cache keys
        assert list(g[5].items()) == list(w[5].items()), g[:4]


@pytest.mark.parametrize("model", MODELS)
def test_every_plannable_model_plans_tasks_its_function_accepts(model):
    assert MODELS == registry.plannable()
    how = registry.planning(model)
    assert isinstance(how, Planning) and how.per in PER
    # the full FEM on a subset of the realizations needs the VHS as its control variate
    cfg = parse_config(copy.deepcopy(DEFAULT_CONFIG) | {"models": list({model, "vhs"})})
    setup = resolve(cfg)
    cls = registry.model_class(model)
    table = dict(TABLE) if how.reads_law else None
    point = RunPoint(setup, setup.material, 10.0, np.array([0.2]), table,
                     None if how.per == "load" else 0, cls.run_data(model, setup))
    fn, kw = cls.run_task(model, point)
    module, name = fn.split(":")
    func = getattr(importlib.import_module(module), name)
    inspect.signature(func).bind(**kw)          # every argument is one the task takes


def test_a_registered_model_is_planned_without_touching_the_pipeline(monkeypatch):
    # one class with a planning and a registration is all a run needs
    from rubbercontact.models.halfspace import VHS

    class Coarse(VHS):
        name = "vhs-coarse"

    monkeypatch.setitem(registry._MODELS, "vhs-coarse", (Coarse, {}))
    cfg = parse_config(copy.deepcopy(DEFAULT_CONFIG) | {"models": ["vhs"]})
    setup = resolve(cfg)
    setup = dataclasses.replace(setup, models=["vhs", "vhs-coarse"])
    slots, tasks = model_tasks(setup, setup.material, np.array([0.2]), {})
    by = {m: [t.kwargs for s, t in zip(slots, tasks, strict=True) if s.model == m]
          for m in setup.models}
    assert by["vhs-coarse"] == by["vhs"] and len(by["vhs"]) == 2 * cfg.realizations
    assert not registry.needs_law("vhs-coarse") and not setup.needs_law
