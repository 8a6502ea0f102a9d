"""Figures of run files of any law set (``mcsim plot RUN.h5``): what is drawn is what was
computed, axes carry names and units, decades get log axes, and cycle runs overlay."""

import numpy as np
import pytest

from mcsim import simulate
from mcsim.figures.runs import BRANCH_LABELS, run_figure
from mcsim.model.errors import MCSimError
from mcsim.model.presets import MATERIALS, SURFACES

H = np.linspace(3.0, -0.5, 8)


@pytest.fixture(scope="module")
def cycles():
    """Two small jkr cycle runs of the smooth surface (seeds 1, 2) and one seed run."""
    smooth, silicon = SURFACES["smooth"], MATERIALS["silicon"]
    jkr = [simulate(smooth, silicon, H, "30 um^2", realizations=3, seed=s, law="jkr",
                    cycle=True, workers=1) for s in (1, 2)]  # fmt: skip
    seed = simulate(smooth, silicon, H, "30 um^2", realizations=3, seed=3, workers=1)
    return jkr, seed


def mc_points(ax) -> np.ndarray:
    """(x, y) of every Monte Carlo marker of a panel (bars: ``errorbar`` containers), sorted."""
    xy = [np.column_stack(c.lines[0].get_data()) for c in ax.containers]
    xy = np.concatenate(xy)
    return xy[np.lexsort(xy.T[::-1])]


def test_a_cycle_run_draws_its_own_means_on_both_branches(cycles):
    run = cycles[0][0]
    fig = run_figure(run)
    h = np.tile(run.spec.h, 2)  # approach rows, then retraction rows
    for ax, q in zip(fig.axes, run.quantities):
        mean = run.summary.mean[q]
        keep = np.isfinite(mean) & ((mean > 0) if ax.get_yscale() == "log" else True)
        expected = np.column_stack([h[keep], mean[keep]])
        np.testing.assert_array_equal(mc_points(ax), expected[np.lexsort(expected.T[::-1])])


def test_axes_are_named_with_their_normalisation_and_decades_are_on_log_axes(cycles):
    run = cycles[0][0]
    fig = run_figure(run)
    labels = {q: ax.get_ylabel() for ax, q in zip(fig.axes, run.quantities)}
    assert labels == {q: BRANCH_LABELS[q] for q in run.quantities}
    scales = {q: ax.get_yscale() for ax, q in zip(fig.axes, run.quantities)}
    assert scales["contact_fraction"] == "log" and scales["area"] == "log"  # 1e-3 .. 0.7
    assert scales["load"] == "linear"  # signed
    for ax in fig.axes[: len(run.quantities)]:
        assert ax.get_xlabel() == r"Dimensionless mean separation $h = d/\sigma$"


def test_cycle_runs_overlay_both_branches_of_each_run(cycles):
    a, b = cycles[0]
    fig = run_figure([a, b])
    # one legend, in the spare panel beside the inputs: it covers no curve
    legend = [t.get_text() for t in fig.axes[-1].get_legend().get_texts()]
    assert sum("retract" in t for t in legend) == 4  # analytic + MC, two runs
    assert mc_points(fig.axes[0]).shape[0] == 2 * 2 * H.size  # every row of both runs


def test_runs_of_different_law_sets_are_not_overlaid(cycles):
    with pytest.raises(MCSimError, match="overlay runs of one law set"):
        run_figure([cycles[0][0], cycles[1]])
