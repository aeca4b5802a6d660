"""The run's figures, inspected as matplotlib objects: every model drawn, legends inside
their axes and over no data point, no text outside the figure or over another text.

The datasets are built here with the results file's layout (the figures read only that):
smooth made-up curves, so that the checks are about the drawing, not the physics.
"""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
import xarray as xr  # noqa: E402

from rubbercontact.plotting import figures, speed  # noqa: E402

MODELS = ["vhs", "hybrid", "hybrid-windowed", "fem"]


def results(models=MODELS, velocities=(10.0, 50.0), pressures=(0.15, 0.25, 0.35),
            temperatures=None, law=True) -> xr.Dataset:
    nm, nv, nr, npr = len(models), len(velocities), 3, len(pressures)
    rng = np.random.default_rng(1)
    p = np.asarray(pressures, float)
    base = 0.4 + 0.2 * np.log10(p / p[0] + 1)
    dims = ("model", "velocity", "realization", "pressure")
    mu = (base[None, None, None, :] + 0.05 * np.arange(nm)[:, None, None, None]
          + 0.02 * rng.standard_normal((nm, nv, nr, npr)))
    area = 0.1 * p[None, None, None, :] * (1 + 0.1 * np.arange(nm)[:, None, None, None]) \
        * np.ones((nm, nv, nr, npr))
    ds = xr.Dataset({"friction": (dims, mu), "contact_fraction": (dims, area)},
                    coords={"model": models, "velocity": list(velocities),
                            "realization": np.arange(nr), "pressure": p})
    for k in ("friction", "contact_fraction"):
        ds[f"{k}_mean"] = ds[k].mean("realization")
        ds[f"{k}_std"] = ds[k].std("realization")
    for k in ("friction_ls", "friction_hs"):
        ds[f"{k}_mean"] = ds["friction_mean"] / 2
    if "fem" in models:
        others = [m for m in models if m != "fem"]
        ds["error_vs_fem"] = (("compared_model", "velocity"),
                              np.full((len(others), nv), 0.123), {"compared_over": "pressure"})
        ds = ds.assign_coords(compared_model=others)
    x = np.linspace(0, 0.25, 64, endpoint=False)
    ds = ds.assign_coords(x=x)
    ds["heights"] = ("x", 0.01 * np.sin(2 * np.pi * x / 0.25))
    for m in models:
        if m in ("vhs", "hybrid", "hybrid-windowed"):
            prof = np.clip(np.sin(2 * np.pi * x / 0.25), 0, None) * (1 + models.index(m))
            ds[f"pressure_profile_{m}"] = (("velocity", "pressure", "x"),
                                           np.broadcast_to(prof, (nv, npr, x.size)).copy())
    if law:
        lp = np.array([0.1, 0.3, 1.0, 3.0])
        shape = (nv, lp.size)
        ds = ds.assign_coords(law_pressure=lp)
        ld = ("velocity", "law_pressure")
        ds["law_mean_separation"] = (ld, np.broadcast_to(0.02 / (1 + lp), shape).copy())
        ds["law_contact_fraction"] = (ld, np.broadcast_to(lp / 4, shape).copy())
        ds["law_shear_stress"] = (ld, np.broadcast_to(0.3 * lp, shape).copy())
        fr = np.broadcast_to(np.array([-0.05, 0.2, 0.4, 0.5]), shape).copy()
        ds["law_friction"] = (ld, fr)
        ds["law_vhs_friction"] = (ld, fr + 0.05)
        status = np.full(shape, "ok", dtype=object)
        status[:, -1] = "not monotone"
        ds["law_status"] = (ld, status.astype(str))
    if temperatures is not None:
        ds = ds.expand_dims(temperature=list(temperatures)).transpose("model", "temperature", ...)
        ds.attrs["reference_temperature_C"] = float(temperatures[0])
    return ds


@pytest.fixture
def captured(monkeypatch):
    """The figures the plotting functions save, kept open for inspection."""
    figs = {}

    def keep(fig, path, legends=(), **legend_kw):
        from rubbercontact.plotting.layout import legend_clear_of_data

        fig.tight_layout()
        for ax in legends:
            legend_clear_of_data(ax, **({"fontsize": 8} | legend_kw))
        fig.canvas.draw()
        figs[str(path)] = fig
        return path

    monkeypatch.setattr(figures, "_save", keep)
    monkeypatch.setattr(speed, "_save", keep)
    yield figs
    plt.close("all")


def _points(ax) -> np.ndarray:
    """Display coordinates of every data point of ``ax`` (markers and line vertices)."""
    pts = [ax.transData.transform(np.asarray(line.get_xydata(), float).reshape(-1, 2))
           for line in ax.lines]
    pts = [p[np.isfinite(p).all(axis=1)] for p in pts if p.size]
    return np.concatenate(pts) if pts else np.empty((0, 2))


def check_layout(fig) -> None:
    renderer = fig.canvas.get_renderer()
    frame = fig.bbox
    # everything drawn (tick labels of ticks in view included) lies inside the figure
    tight = fig.get_tightbbox(renderer)
    w, h = fig.get_size_inches()
    assert tight.x0 >= -0.01 and tight.y0 >= -0.01 and tight.x1 <= w + 0.01 \
        and tight.y1 <= h + 0.01, f"drawing beyond the figure: {tight} in a {w} x {h} in figure"
    texts = [fig._suptitle] if fig._suptitle is not None else []
    for ax in fig.axes:
        texts += [ax.title, ax.xaxis.label, ax.yaxis.label]
    for t in texts:
        if not (t.get_visible() and t.get_text().strip()):
            continue
        box = t.get_window_extent(renderer)
        assert (box.x0 >= frame.x0 - 1 and box.x1 <= frame.x1 + 1 and box.y0 >= frame.y0 - 1
                and box.y1 <= frame.y1 + 1), f"text clipped: {t.get_text()!r}"
    titles = [ax.title for ax in fig.axes if ax.get_title()]
    for i, a in enumerate(titles):
        for b in titles[i + 1:]:
            assert not a.get_window_extent(renderer).overlaps(b.get_window_extent(renderer)), \
                f"titles collide: {a.get_text()!r} / {b.get_text()!r}"
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is None:
            continue
        lb, ab = leg.get_window_extent(renderer), ax.get_window_extent(renderer)
        assert ab.x0 - 1 <= lb.x0 and lb.x1 <= ab.x1 + 1 and ab.y0 - 1 <= lb.y0 \
            and lb.y1 <= ab.y1 + 1, "legend outside its axes"
        xy = _points(ax)
        covered = ((xy[:, 0] > lb.x0) & (xy[:, 0] < lb.x1) & (xy[:, 1] > lb.y0)
                   & (xy[:, 1] < lb.y1))
        assert not covered.any(), f"legend covers {int(covered.sum())} data points"


def labels(ax) -> list[str]:
    leg = ax.get_legend()
    return [t.get_text() for t in leg.get_texts()] if leg is not None else []


def test_fig5_and_fig9_draw_every_model_named_as_in_the_config(captured, tmp_path):
    ds = results()
    figures.plot_friction_vs_area(ds, tmp_path / "fig5.png")
    figures.plot_friction_vs_pressure(ds, tmp_path / "fig9.png")
    for fig in captured.values():
        check_layout(fig)
        for ax in fig.axes:
            names = [t.split(" ")[0].rstrip(",") for t in labels(ax)]
            assert names == MODELS
            # one error-bar curve per model, every load drawn
            assert len(ax.containers) == len(MODELS)
            assert all(len(c.lines[0].get_xdata()) == ds.sizes["pressure"]
                       for c in ax.containers)


def test_one_load_is_one_panel_with_a_point_per_model_and_speed(captured, tmp_path):
    ds = results(pressures=(0.2,), velocities=(1.0, 10.0, 100.0))
    figures.plot_friction_vs_area(ds, tmp_path / "fig5.png")
    fig = captured[str(tmp_path / "fig5.png")]
    check_layout(fig)
    (ax,) = fig.axes
    assert len(ax.containers) == len(MODELS) * 3
    assert {t.split(",")[0].split(" (")[0] for t in labels(ax)} >= set(MODELS)
    assert "v = 1 mm/s" in labels(ax) and "v = 100 mm/s" in labels(ax)


def test_fig8_draws_every_model_with_a_profile(captured, tmp_path):
    models = ["vhs", "hybrid-windowed"]
    figures.plot_pressure_profiles(results(models=models), tmp_path / "fig8.png")
    fig = captured[str(tmp_path / "fig8.png")]
    check_layout(fig)
    main_axes = [ax for ax in fig.axes if ax.get_legend() is not None]
    assert main_axes and all(labels(ax) == models for ax in main_axes)
    assert all("[mm]" in ax.get_ylabel() for ax in fig.axes if "height" in ax.get_ylabel())


def test_fig7_marks_excluded_points_and_negative_friction(captured, tmp_path):
    ds = results()
    figures.plot_high_slope_friction(ds, tmp_path / "fig7.png")
    fig = captured[str(tmp_path / "fig7.png")]
    check_layout(fig)
    ax = fig.axes[0]
    by_label = {line.get_label(): line for line in ax.lines}
    excluded = by_label["FEM, excluded from the law"]
    np.testing.assert_array_equal(excluded.get_xdata(), [3.0])       # status not ok
    kept = by_label["FEM (the law)"]
    assert 3.0 not in kept.get_xdata()
    negative = next(v for k, v in by_label.items() if k.startswith("μ_hs < 0"))
    np.testing.assert_array_equal(negative.get_ydata(), [-0.05])


def test_law_figure_separation_in_mm(captured, tmp_path):
    ds = results()
    figures.plot_law(ds, tmp_path / "fig2.png")
    fig = captured[str(tmp_path / "fig2.png")]
    check_layout(fig)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "mean separation ū [mm]"
    kept = ds["law_status"].isel(velocity=0).values == "ok"
    np.testing.assert_allclose(ax.lines[0].get_xdata(),
                               ds["law_mean_separation"].isel(velocity=0).values[kept])


def test_friction_vs_temperature_is_not_a_strip_and_rounds_speeds(captured, tmp_path):
    v = np.geomspace(0.1, 1000.0, 9)             # 0.316228... among them
    ds = results(models=["vhs", "hybrid"], velocities=tuple(v), pressures=(0.2,),
                 temperatures=(20.0, 0.0, 40.0), law=False)
    speed.plot_friction_vs_temperature(ds, tmp_path / "t.png")
    fig = captured[str(tmp_path / "t.png")]
    check_layout(fig)
    w, h = fig.get_size_inches()
    assert 0.5 <= w / h <= 2.0
    for ax in fig.axes:
        if ax.get_visible():
            text = ax.get_title().split("v = ")[1].split(" ")[0]
            # three significant digits, written out (1000, not 1e+03)
            assert float(text) == float(f"{float(text):.3g}") and "e" not in text, text


def test_speed_figures(captured, tmp_path):
    ds = results(models=["vhs", "hybrid-windowed"], velocities=tuple(np.geomspace(1, 1e3, 7)),
                 pressures=(0.1, 0.3), law=False)
    speed.plot_friction_vs_speed(ds, tmp_path / "mu.png")
    speed.plot_contact_vs_speed(ds, tmp_path / "a.png")
    for fig in captured.values():
        check_layout(fig)


def test_the_layout_check_catches_a_covering_legend_and_a_clipped_title():
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot(np.linspace(0, 1, 11), np.ones(11), "o-", label="a curve")
    ax.legend(loc="center left")
    fig.tight_layout()
    fig.canvas.draw()
    with pytest.raises(AssertionError, match="legend covers"):
        check_layout(fig)
    ax.get_legend().remove()
    ax.set_title("a title far too long for a figure three inches wide, so it runs off")
    fig.canvas.draw()
    with pytest.raises(AssertionError, match="beyond the figure|clipped"):
        check_layout(fig)


def test_four_speeds_make_a_grid_not_a_strip(captured, tmp_path):
    ds = results(velocities=(1.0, 3.0, 10.0, 30.0))
    figures.plot_friction_vs_pressure(ds, tmp_path / "fig9.png")
    figures.plot_high_slope_friction(ds, tmp_path / "fig7.png")
    for fig in captured.values():
        check_layout(fig)
        w, h = fig.get_size_inches()
        assert 0.5 <= w / h <= 2.0
        assert sum(ax.get_visible() for ax in fig.axes) == 4
