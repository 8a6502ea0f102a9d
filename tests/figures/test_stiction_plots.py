"""``mcsim plot`` of a pads sweep (issue 23): p_stick with its interval and the model, or a map."""

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FEW

from mcsim.figures.stiction import stiction_figure
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.sweepfile import read_sweep
from mcsim.studies.sweeps import sweep

OPTIONS = {"law": "jkr", "pads": 8, "seed": 1, "area": "30um^2", "restoring_force": "20uN",
           "preload": "1MPa"}  # fmt: skip


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
def test_a_1d_pads_sweep_draws_p_stick_with_its_interval_and_the_model_on_a_log_axis():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"sigma": "1.5nm,2.5nm"}, **OPTIONS)
    fig = stiction_figure(result)
    ax = fig.axes[0]
    assert ax.get_yscale() == "log" and "p_stick" in ax.get_ylabel() and "(nm)" in ax.get_xlabel()
    # one legend below the axes (inside it covered the bars at the floor)
    assert ax.get_legend() is None and len(fig.legends) == 1
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any("Clopper-Pearson" in t for t in labels) and any("model" in t for t in labels)


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
def test_a_pads_sweep_at_one_value_of_its_input_is_drawn_as_its_one_point():
    # a report at one humidity draws this figure (it used to stop after all its work)
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"sigma": "2nm"}, **OPTIONS)
    ax = stiction_figure(result).axes[0]
    assert "(nm)" in ax.get_xlabel()
    drawn = [line.get_xdata() for line in ax.get_lines() if line.get_transform() == ax.transData]
    assert drawn and all(np.allclose(x, 2.0) for x in drawn)  # the point, its bar, its model


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
@pytest.mark.filterwarnings("error::RuntimeWarning")  # the model's tails leak no overflow
def test_cli_plot_of_a_2d_pads_sweep_writes_a_map_with_a_log_colour_bar(tmp_path, capsys):
    path = tmp_path / "map.h5"
    sweep(SURFACES["smooth"], MATERIALS["silicon"], {"sigma": "1.5nm,2.5nm", "gamma": "0.1,0.3"},
          out=path, **OPTIONS)  # fmt: skip
    code, _, err = run_cli(capsys, "plot", path, "--out", tmp_path / "map.png")
    assert code == 0, err
    assert (tmp_path / "map.png").stat().st_size > 0
    fig = stiction_figure(read_sweep(path))
    colourbar = fig.axes[1]
    assert colourbar.get_yscale() == "log" and "p_stick" in colourbar.get_ylabel()


def test_the_pads_figure_shows_p_stick_and_its_interval_at_the_restoring_force():
    from mcsim.figures.stiction import pads_figure
    from mcsim.studies.pads import pad_statistics

    force = np.random.default_rng(1).normal(5e-6, 1e-6, 200)
    stats = pad_statistics(force, 5.5e-6)
    low, high = stats.p_stick_ci
    fig = pads_figure(force, 5e-6, restoring_force=5.5e-6, p_stick=stats.p_stick,
                      interval=(low, high), interval_name="Clopper-Pearson 95 %")  # fmt: skip
    ecdf = fig.axes[1]
    (bars,) = ecdf.containers
    x, y = bars.lines[0].get_data()
    # the plotted numbers: N to µN, one rounding; the probability itself, not 1 − p
    assert x[0] == pytest.approx(5.5, rel=ROUNDING_FEW) and y[0] == stats.p_stick
    (segment,) = bars.lines[2][0].get_segments()
    assert sorted(segment[:, 1]) == pytest.approx([low, high], abs=ROUNDING_FEW)
    # and it lies on the drawn fraction of pads with a pull-off above F, at F = F_r
    (step,) = [line for line in ecdf.get_lines() if line.get_drawstyle() == "steps-post"]
    xs, ys = step.get_data()
    assert ys[np.searchsorted(xs, 5.5, side="right") - 1] == pytest.approx(stats.p_stick, abs=1e-12)
    assert any("p_{stick}" in t.get_text() for t in fig.legends[0].get_texts())
    assert ecdf.get_xlabel() == "pad pull-off force F (µN)"
