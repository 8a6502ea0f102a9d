"""Figures of contact law sets: the approach/retraction cycle and the Fuller–Tabor plot."""

import numpy as np
import pytest
from tolerances import ROUNDING_FEW
from toy_laws import MATERIAL, TOY

from mcsim.figures.adhesion import adhesion_figure, fuller_tabor_figure
from mcsim.model.presets import SURFACES
from mcsim.physics.adhesion import adhesion_summary


@pytest.fixture(scope="module")
def cycle():
    surface = SURFACES["super-smooth"]
    summary = adhesion_summary(surface, MATERIAL, TOY)
    return summary, adhesion_figure(surface, MATERIAL, TOY, summary, points=100)


def test_cycle_figure_marks_the_pull_off_in_mpa(cycle):
    summary, fig = cycle
    ax = fig.axes[0]
    (marker,) = [line for line in ax.lines if line.get_marker() == "o"]
    x, y = marker.get_data()
    assert x[0] == summary.h_pull_off
    assert y[0] == pytest.approx(-summary.pull_off_pressure / 1e6, rel=ROUNDING_FEW)
    assert "pull-off" in marker.get_label()


def test_cycle_figure_shows_both_branches_with_physical_axes(cycle):
    summary, fig = cycle
    ax = fig.axes[0]
    labels = [line.get_label() for line in ax.lines]
    assert "approach (loading)" in labels
    assert any(label.startswith("retraction from") for label in labels)
    assert "MPa" in ax.get_ylabel() and "h = d/" in ax.get_xlabel()
    assert ax.get_xlim()[0] > ax.get_xlim()[1]  # h decreasing left to right
    assert ax.get_xlim()[1] == pytest.approx(summary.turn, rel=ROUNDING_FEW)


def test_fuller_tabor_figure_has_one_curve_per_turn_on_a_log_axis():
    theta = np.logspace(-1, 1, 5)
    fig = fuller_tabor_figure(theta, {"a": np.linspace(1, 0, 5), "b": np.linspace(1, 0.2, 5)})
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and len(ax.lines) == 2
    assert "theta" in ax.get_xlabel()
