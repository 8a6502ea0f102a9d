"""Figures of sweep files (``mcsim plot SWEEP.h5``, :func:`mcsim.figures.sweeps.sweep_figure`):
design curves against one input with units and log axes for log grids, design maps over
two inputs with the adhesion-map regime boundaries, the output rule, one-line errors."""

import dataclasses

import numpy as np
import pytest
from conftest import run_cli

from mcsim.figures.grid import is_log_grid
from mcsim.figures.style import save
from mcsim.figures.sweeps import sweep_figure
from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import DMT_BELOW, JKR_ABOVE, maugis_parameter
from mcsim.store.sweepfile import read_sweep
from mcsim.studies.sweeps import sweep

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
H = [2.0, 1.0, 0.0]
#: w at which Maugis' λ of the smooth surface on silicon is DMT_BELOW (λ ∝ w^(2/3)).
W_DMT = 0.5 * (DMT_BELOW / maugis_parameter(SMOOTH, SILICON)) ** 1.5


@pytest.fixture(scope="module")
def map_file(tmp_path_factory):
    """σ (log, 3 values) × w (both sides of the DMT boundary λ = 0.1), dmt, as a file."""
    path = tmp_path_factory.mktemp("plots") / "map.h5"
    vary = {"sigma": "0.5nm:2nm:3:log", "gamma": [W_DMT / 3, W_DMT * 3]}
    sweep(SMOOTH, SILICON, vary, law="dmt", h=H, out=path, workers=2)
    return path


@pytest.fixture(scope="module")
def gamma_file(tmp_path_factory):
    """A linear w grid (dmt), as a file."""
    path = tmp_path_factory.mktemp("plots") / "gamma.h5"
    sweep(SMOOTH, SILICON, {"gamma": "0.2:0.6:3"}, law="dmt", h=H, out=path, workers=2)
    return path


def test_a_log_sigma_grid_is_plotted_against_sigma_in_nm_on_a_log_axis_with_pressure_and_energy_units(
    map_file,
):
    fig = sweep_figure(map_file, kind="lines")
    axes = fig.axes
    assert "Pa" in axes[0].get_ylabel() and "J/m$^2$" in axes[1].get_ylabel()
    for ax in axes:
        assert ax.get_xscale() == "log"
        assert "(nm)" in ax.get_xlabel() and "sigma" in ax.get_xlabel()
    assert len(axes[0].get_lines()) >= 2  # one line per value of w


def test_a_linear_grid_is_plotted_on_a_linear_axis(gamma_file):
    fig = sweep_figure(gamma_file)
    assert fig.axes[0].get_xscale() == "linear"
    assert "J/m$^2$" in fig.axes[0].get_xlabel()
    assert not is_log_grid(np.linspace(0.2, 0.6, 3)) and is_log_grid(np.geomspace(0.3e-9, 2e-8, 4))


def test_a_sigma_by_w_map_draws_the_regime_boundary_of_the_adhesion_map_and_names_the_regions(
    map_file,
):
    fig = sweep_figure(map_file)
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and "(nm)" in ax.get_xlabel() and "J/m$^2$" in ax.get_ylabel()
    boundaries = [c for c in ax.collections if c.get_gid() == "regime-boundaries"]
    assert len(boundaries) == 1 and list(boundaries[0].levels) == [DMT_BELOW]
    names = {t.get_text() for t in ax.texts}
    assert {"DMT", "Maugis–Dugdale"} <= names and "JKR" not in names
    colourbar_labels = [a.get_ylabel() for a in fig.axes[len(fig.axes) // 2 :]]
    assert any("(Pa)" in label for label in colourbar_labels)


def test_the_jkr_boundary_is_the_choose_law_threshold():
    lam = maugis_parameter(SMOOTH, SILICON)
    w_jkr = 0.5 * (JKR_ABOVE / lam) ** 1.5
    result = sweep(SMOOTH, SILICON, {"sigma": [1e-9, 2e-9], "gamma": [w_jkr / 2, w_jkr * 2]},
                   law="dmt", h=H, workers=2)  # fmt: skip
    ax = sweep_figure(result).axes[0]
    (boundary,) = [c for c in ax.collections if c.get_gid() == "regime-boundaries"]
    assert list(boundary.levels) == [JKR_ABOVE]
    assert "JKR" in {t.get_text() for t in ax.texts}


def test_mcsim_plot_writes_a_png_of_a_sweep_and_refuses_to_overwrite_it_without_overwrite(
    capsys, map_file, tmp_path
):
    out = tmp_path / "map.png"
    code, _, stderr = run_cli(capsys, "plot", str(map_file), "--out", str(out))
    assert code == 0 and out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and f"wrote {out}" in stderr
    before = out.read_bytes()
    code, _, err = run_cli(capsys, "plot", str(map_file), "--out", str(out))
    assert code != 0 and "file exists" in err and len(err.strip().splitlines()) == 1
    assert out.read_bytes() == before
    code, _, _ = run_cli(capsys, "plot", str(map_file), "--out", str(out), "--overwrite")
    assert code == 0


def test_mcsim_plot_never_writes_onto_the_sweep_file_itself(capsys, tmp_path):
    sweep_png = (
        tmp_path / "named-like-a-figure.png"
    )  # a sweep file whose name passes the .png check
    sweep(SMOOTH, SILICON, {"gamma": "0.2:0.4:2"}, law="dmt", h=H, out=sweep_png)
    before = sweep_png.read_bytes()
    code, _, err = run_cli(capsys, "plot", str(sweep_png), "--out", str(sweep_png), "--overwrite")
    assert code != 0 and "is an input of this command" in err and len(err.strip().splitlines()) == 1
    assert sweep_png.read_bytes() == before
    with pytest.raises(MCSimError, match="is an input"):
        save(sweep_figure(sweep_png), sweep_png, overwrite=True, inputs=[sweep_png])


def test_a_sweep_of_three_varied_inputs_is_a_one_line_error_naming_them(capsys, tmp_path):
    path = tmp_path / "cube.h5"
    vary = {"sigma": "1nm,2nm", "gamma": "0.2,0.4", "R": "1um,2um"}
    sweep(SMOOTH, SILICON, vary, law="seed", h=H, out=path)
    code, _, err = run_cli(capsys, "plot", str(path), "--out", str(tmp_path / "cube.png"))
    assert code != 0 and len(err.strip().splitlines()) == 1
    assert "varies 3 inputs (sigma, gamma, R)" in err and "1 or 2" in err
    assert not (tmp_path / "cube.png").exists()


def test_a_seed_sweep_has_no_pull_off_so_its_figure_shows_the_seed_curves_at_named_separations():
    result = sweep(SMOOTH, SILICON, {"sigma": "0.5nm:5nm:4:log"}, law="seed", h=H)
    assert "pull_off" not in result.data
    axes = sweep_figure(result, h=(0.0, 1.0)).axes
    labels = [ax.get_ylabel() for ax in axes]
    assert [label.split(" $")[0] for label in labels] == [
        "Adhesion term",
        "Friction force",
        "Friction coefficient",
    ]
    legend = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert legend == ["$d/\\sigma$ = 0", "$d/\\sigma$ = 1"]  # one line per separation, named


def test_points_with_nothing_to_pull_off_are_counted_on_the_log_axes_not_dropped_silently():
    # rough surface, jkr: the approach load is never tensile, so the surfaces rest apart
    # and nothing pulls off: 0, which a log axis cannot show
    result = sweep(SURFACES["rough"], SILICON, {"gamma": "0.2,0.3"}, law="jkr", h=H)
    assert np.all(result.data["pull_off"] == 0)
    fig = sweep_figure(result)
    note = fig.axes[0].get_title()  # above the panel, where it hides no curve
    assert "0 at 2 of 2 points" in note, note


def test_a_sweep_with_no_value_to_plot_is_a_one_line_error(monkeypatch):
    import mcsim.studies.sweeppoint

    def failing(*args, **kwargs):
        raise ParameterError("no root found (injected)")

    monkeypatch.setattr(mcsim.studies.sweeppoint, "adhesion_summary", failing)
    # jkr points go to the compiled fast path first: fail it too (its points then fall back
    # to adhesion_summary)
    monkeypatch.setattr(mcsim.studies.sweeppoint, "jkr_summaries", failing)
    # every adhesion summary fails, and jkr without tau has no seed curves or friction
    result = sweep(SMOOTH, SILICON, {"gamma": "0.2,0.3"}, law="jkr", h=H)
    assert np.all(np.isnan(result.data["pull_off"]))
    with pytest.raises(ParameterError, match="nothing to plot") as err:
        sweep_figure(result)
    assert "\n" not in str(err.value)


def test_a_map_of_a_single_input_or_of_the_law_set_is_a_one_line_error(gamma_file):
    with pytest.raises(ParameterError, match="a map needs two numeric inputs"):
        sweep_figure(gamma_file, kind="map")
    result = sweep(SMOOTH, SILICON, {"law": "dmt,jkr", "gamma": "0.3,0.5"}, h=H)
    with pytest.raises(ParameterError, match="a map needs two numeric inputs"):
        sweep_figure(result, kind="map")
    fig = sweep_figure(result)  # auto: lines over w, one per law set
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == ["dmt", "jkr"]


def test_monte_carlo_points_of_a_sweep_are_drawn_with_error_bars():
    material = dataclasses.replace(SILICON, tau=1e8)
    result = sweep(SMOOTH, material, {"sigma": "1nm,2nm"}, law="dmt", h=H, mc=True,
                   area="20um^2", realizations=3, seed=7)  # fmt: skip
    fig = sweep_figure(result, h=(0.0,))
    mu = fig.axes[-1]
    assert mu.get_ylabel().startswith("Friction coefficient")
    assert "Monte Carlo mean ± 2 SE" in [t.get_text() for t in mu.get_legend().get_texts()]
    assert mu.containers, "error bars drawn"
    mc_mu = result.data["mc_mu"][:, H.index(0.0)]
    assert np.isfinite(mc_mu).any()
    np.testing.assert_array_equal(mu.containers[0].lines[0].get_ydata(), mc_mu[np.isfinite(mc_mu)])


def test_read_sweep_and_the_result_give_the_same_figure_axes(map_file):
    a = sweep_figure(read_sweep(map_file))
    b = sweep_figure(map_file)
    assert [ax.get_ylabel() for ax in a.axes] == [ax.get_ylabel() for ax in b.axes]


def test_a_sweep_file_is_plotted_on_its_own(capsys, map_file, gamma_file, tmp_path):
    out = str(tmp_path / "x.png")
    code, _, err = run_cli(capsys, "plot", str(map_file), str(gamma_file), "--out", out)
    assert code != 0 and "plot it on its own" in err and len(err.strip().splitlines()) == 1


def test_an_incomplete_sweep_checkpoint_is_plotted_only_with_partial(capsys, tmp_path, monkeypatch):
    import mcsim.studies.sweeppoint as sweeps

    evaluate = sweeps.evaluate

    def stop_at_point_2(point, config):
        if point.index == 2:
            raise KeyboardInterrupt
        return evaluate(point, config)

    monkeypatch.setattr(sweeps, "evaluate", stop_at_point_2)
    with pytest.raises(KeyboardInterrupt):
        sweep(
            SMOOTH,
            SILICON,
            {"gamma": "0.2:0.6:4"},
            law="dmt",
            h=H,
            workers=1,
            out=tmp_path / "s.h5",
        )
    partial, out = tmp_path / "s.partial.h5", tmp_path / "s.png"
    code, _, err = run_cli(capsys, "plot", str(partial), "--out", str(out))
    assert code != 0 and "incomplete sweep" in err and "--partial" in err
    assert len(err.strip().splitlines()) == 1 and not out.exists()
    code, _, _ = run_cli(capsys, "plot", str(partial), "--out", str(out), "--partial")
    assert code == 0 and out.is_file()
    fig = sweep_figure(partial)
    assert "incomplete sweep" in fig.get_suptitle()
    assert np.isfinite(fig.axes[0].get_lines()[0].get_ydata()).sum() == 2  # the completed points


def test_kind_is_refused_for_a_run_file(capsys, tmp_path):
    run = tmp_path / "r.h5"
    code, _, _ = run_cli(capsys, "simulate", "--surface", "smooth", "--area", "1um^2", "--h=1,0",
                         "--seed", "1", "--out", str(run), "--quiet")  # fmt: skip
    assert code == 0
    code, _, err = run_cli(
        capsys, "plot", str(run), "--out", str(tmp_path / "r.png"), "--kind", "map"
    )
    assert code != 0 and "applies to sweep files" in err and len(err.strip().splitlines()) == 1


def test_a_monte_carlo_sweep_without_friction_draws_its_points_on_the_net_load():
    """Without tau there is no mu to carry the Monte Carlo points: they go on the load panel."""
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"sigma": "1.5nm,2nm"}, law="jkr",
                   h=[2.0, 1.0, 0.0], mc=True, area="3 um^2", realizations=2, seed=1)  # fmt: skip
    fig = sweep_figure(result)
    load = next(ax for ax in fig.axes if ax.get_ylabel().startswith("Net load"))
    drawn = np.concatenate([c.lines[0].get_data()[1] for c in load.containers])
    expected = np.asarray(result.data["mc_load"], dtype=float).ravel()  # every point and h
    np.testing.assert_array_equal(np.sort(drawn), np.sort(expected[np.isfinite(expected)]))


def test_many_lines_get_a_colour_bar_instead_of_a_long_legend():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"],
                   {"sigma": "1nm,2nm", "gamma": "0.05:1:13"}, law="dmt", h=[1.0, 0.0])  # fmt: skip
    fig = sweep_figure(result, kind="lines")
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    bars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    assert len(bars) == len(panels)  # one colour bar per panel
    assert all(ax.get_legend() is None for ax in panels)
    assert all("work of adhesion" in bar.get_ylabel() for bar in bars)
    assert len(panels[0].get_lines()) >= 13  # every value of gamma is still drawn


def test_a_few_lines_keep_their_legend():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"],
                   {"sigma": "1nm,2nm", "gamma": "0.1,0.5"}, law="dmt", h=[1.0, 0.0])  # fmt: skip
    fig = sweep_figure(result, kind="lines")
    assert all(ax.get_label() != "<colorbar>" for ax in fig.axes)
    assert len(fig.axes[0].get_legend().get_texts()) == 2
