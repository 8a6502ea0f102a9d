"""The humidity figure (issue 22): regimes bounded where the capillary work reaches 10 % and
90 % of the ceiling, drawn by `mcsim plot` from an rh sweep."""

import math

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FORMULA

from mcsim.figures.environment import humidity_figure, regime_bounds
from mcsim.model.errors import ParameterError


def test_regime_bounds_interpolate_between_the_points():
    rh = np.array([0.1, 0.5, 0.9])
    dry, saturated = regime_bounds(rh, np.array([0.0, 0.2, 1.0]), 1.0)
    assert dry == pytest.approx(0.1 + 0.1 / 0.2 * 0.4, rel=ROUNDING_FORMULA)
    assert saturated == pytest.approx(0.5 + 0.7 / 0.8 * 0.4, rel=ROUNDING_FORMULA)


def test_regime_bounds_outside_the_sweep():
    dry, saturated = regime_bounds(np.array([0.1, 0.5]), np.array([0.2, 0.5]), 1.0)
    assert dry == -math.inf and math.isnan(saturated)


def test_plot_of_an_rh_sweep_is_the_humidity_figure(capsys, tmp_path):
    out, png = tmp_path / "rh.h5", tmp_path / "rh.png"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "maugis-dugdale",
                           "--vary", "rh=0.3,0.9", "--hamaker", "1.6e-19 J", "--h=1,0",
                           "--out", out, "--quiet")  # fmt: skip
    assert code == 0, err
    code, _, err = run_cli(capsys, "plot", out, "--out", png)
    assert code == 0 and png.stat().st_size > 0, err
    from mcsim.store.sweepfile import read_sweep

    fig = humidity_figure(read_sweep(out))
    ax = fig.axes[0]
    assert ax.get_xlabel() == "Relative humidity RH (%)"
    assert ax.get_ylabel() == r"Work of separation (J/m$^2$)"
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    # the contacts give back more than they take at rest here (their work <= 0): not drawn,
    # and the title says so
    # nothing condenses at RH 0.3 (the films' onset): that point is not drawn, and counted
    assert labels[:3] == ["total", "van der Waals (gaps)",
                          "capillary (menisci); 1 of 2 RH ≤ 0 (not drawn)"]  # fmt: skip
    assert "0.144 J/m$^2$" in labels[3]
    assert "contact (summits): <= 0 at every RH" in ax.title.get_text()


def test_the_humidity_figure_needs_an_rh_sweep(tmp_path, capsys):
    out = tmp_path / "g.h5"
    run_cli(capsys, "sweep", "--surface", "smooth", "--law", "dmt", "--vary", "gamma=0.3,0.5",
            "--h=1,0", "--out", out, "--quiet")  # fmt: skip
    from mcsim.store.sweepfile import read_sweep

    with pytest.raises(ParameterError, match="varies rh alone"):
        humidity_figure(read_sweep(out))
