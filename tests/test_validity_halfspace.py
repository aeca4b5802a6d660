"""The half-space friction's resolution check (validity/halfspace.py) and its line in
``rubbercontact halfspace``: the slope form ``<σ ∂z/∂x>`` against the dissipation form
``<σ ∂w/∂x>``, checked against a closed form (full contact, where the two are one),
passivity (the dissipation is ``>= 0`` on any grid) and the limit of a resolved profile."""

from __future__ import annotations

import json

import numpy as np
import pytest

from rubbercontact.cli import main
from rubbercontact.halfspace import LennardJonesRepulsion, solve_sliding
from rubbercontact.io import write_map
from rubbercontact.materials import GeneralizedMaxwell, sbr
from rubbercontact.roughness import HeightMap, SineSeries
from rubbercontact.validity.halfspace import dissipation_friction, resolution_note

MAT = sbr()


def _white_noise(n=16, dx=0.06, seed=0):
    """A map of independent heights (0–4 mm in steps of 1): every pixel its own asperity,
    rms slope along x about 20."""
    z = np.random.default_rng(seed).integers(0, 5, (n, n)).astype(float)
    return z - z.mean(), (n * dx, n * dx)


def test_full_contact_makes_both_forms_one_closed_form():
    # an oblique sine in full contact: u = 0 everywhere, so <σ ∂u/∂x> = 0 and both forms
    # are μ = |q| q_x Δ² Im E_r(q_x v)/(4σ0)
    n, amp = 32, 0.002
    x = np.arange(n) / n
    qx, qy = 2 * np.pi * 2, 2 * np.pi
    z = amp * np.sin(qx * x[None, :] + qy * x[:, None])
    q = np.hypot(qx, qy)
    er = complex(MAT.reduced_modulus(qx * 10.0, 0.5))
    sigma0 = amp * q * abs(er)                   # twice the pressure amplitude
    res = solve_sliding(HeightMap(z, (1.0, 1.0), periodic=True), None, MAT, 10.0, sigma0)
    assert res.contact_fraction == 1.0
    closed = q * qx * amp**2 * er.imag / (4 * sigma0)
    assert dissipation_friction(res) == pytest.approx(closed, rel=1e-8)
    assert res.friction_ls == pytest.approx(closed, rel=1e-8)
    assert resolution_note(res) is None


def test_a_resolved_profile_has_no_note():
    # the limit of a resolved grid: a sine series on 4096 points, partial contact
    surf = SineSeries([1.0, 0.1, 0.01], [0.05, 0.005, 0.0005])
    for v in (0.01, 10.0, 1000.0):
        res = solve_sliding(surf, None, MAT, v, 0.3, law=LennardJonesRepulsion())
        assert 0 < res.contact_fraction < 1
        assert dissipation_friction(res) == pytest.approx(res.friction_ls, rel=1e-2)
        assert resolution_note(res) is None


def test_an_elastic_rubber_is_noted_only_where_unresolved():
    # no dissipation: μ_w is round-off on any grid; on a resolved profile μ is solver
    # noise around 0 too (below the floor: no note), on white noise it is of order one
    elastic = GeneralizedMaxwell.elastic(10.0)
    surf = SineSeries([1.0, 0.1], [0.05, 0.005])
    res = solve_sliding(surf, None, elastic, 10.0, 0.3, law=LennardJonesRepulsion())
    assert abs(res.friction_ls) < 1e-6 and abs(dissipation_friction(res)) < 1e-10
    assert resolution_note(res) is None
    z, lengths = _white_noise()
    res = solve_sliding(z, lengths, elastic, 10.0, 0.3)
    assert abs(dissipation_friction(res)) < 1e-10 < abs(res.friction_ls)
    assert resolution_note(res) is not None


@pytest.mark.parametrize("law", [None, LennardJonesRepulsion()])
def test_white_noise_converges_to_a_negative_slope_friction_and_is_noted(law):
    # the solver converges, the slope form is negative, the dissipation is not (passivity)
    z, lengths = _white_noise()
    res = solve_sliding(z, lengths, MAT, 10.0, 0.3, law=law)
    assert res.converged and res.residual <= 1e-8
    assert res.friction_ls < 0
    for v in (0.1, 10.0, 1000.0):
        assert dissipation_friction(solve_sliding(z, lengths, MAT, v, 0.3, law=law)) > 0
    note = resolution_note(res)
    assert note is not None and note.condition == "resolution"
    assert "negative" in note.text and "\n" not in note.text
    assert note.text.startswith("vhs at 10 mm/s: ")


def test_halfspace_command_says_so_in_one_line(capsys, tmp_path):
    z, lengths = _white_noise()
    path = write_map(HeightMap(z, lengths, periodic=True), tmp_path / "noise.npy")
    args = ["halfspace", "--map", str(path), "--map-dx", repr(lengths[0] / 16),
            "--periodize", "none", "--velocity", "10", "--pressure", "0.3"]
    assert main(args) == 0
    out = capsys.readouterr().out
    notes = [line for line in out.splitlines() if line.startswith("note: ")]
    assert len(notes) == 1 and "negative" in notes[0] and "resolve" in notes[0]
    assert main([*args, "--json"]) == 0
    row = json.loads(capsys.readouterr().out)
    assert row["friction"] < 0 and "negative" in row["validity"]


def test_a_map_run_on_white_noise_notes_the_vhs(tmp_path):
    # the run's VHS solves carry the same check: in validity_vhs's one line (the worst load
    # per speed, folded over the speeds); the mean-field solves no grid
    from rubbercontact.config import load_config
    from rubbercontact.pipeline import run

    z, lengths = _white_noise()
    write_map(HeightMap(z, lengths, periodic=True), tmp_path / "noise.txt")
    path = tmp_path / "run.toml"
    path.write_text('models = ["vhs", "meanfield"]\nvelocities = [1.0, 10.0]\n[loads]\n'
                    'pressures = [0.1, 0.3]\n[surface.map]\nfile = "noise.txt"\n'
                    'periodize = "none"\n')
    ds = run(load_config(path))
    lines = [x for x in ds.attrs["validity_vhs"].split("\n") if "resolve the contact" in x]
    assert len(lines) == 1 and lines[0].startswith("vhs: outside its")
    assert "; at 2 speeds (1 … 10 mm/s), worst at 10 mm/s: σ0 = " in lines[0], lines[0]
    assert "resolve the contact" not in ds.attrs["validity_meanfield"]
