"""``mcsim plot``: the README's commands work as written, and a run without adhesion plots
(issue 33)."""

from __future__ import annotations

import numpy as np
from conftest import run_cli

import mcsim
from mcsim.model.params import Material


def test_plot_kind_lines_after_the_default_plot_writes_its_own_file(capsys, tmp_path, monkeypatch):
    """As the README: `mcsim plot map.h5 --out map.png`, then `mcsim plot map.h5 --kind lines`
    (which used to refuse: map.png exists)."""
    monkeypatch.chdir(tmp_path)
    mcsim.sweep("smooth", "silicon", {"sigma": ["0.5nm", "2nm"], "gamma": [0.1, 0.5]},
                law="dmt", h=np.linspace(3, -1, 9), out="map.h5", workers=1)  # fmt: skip
    assert run_cli(capsys, "plot", "map.h5", "--out", "map.png")[0] == 0
    code, _, err = run_cli(capsys, "plot", "map.h5", "--kind", "lines")
    assert code == 0, err
    assert "wrote map-lines.png" in err and (tmp_path / "map-lines.png").stat().st_size > 0
    assert run_cli(capsys, "plot", "map.h5", "--kind", "map")[0] == 0
    assert (tmp_path / "map-map.png").exists()


def test_a_seed_run_without_adhesion_plots(capsys, tmp_path):
    """F, T = 0 and mu undefined everywhere: linear axes, no log scale of nothing (which
    raised ValueError: Data cannot be log-scaled)."""
    material = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.0)
    mcsim.simulate("smooth", material, [1.0, 0.0], "2um^2", realizations=2, seed=1, workers=1,
                   out=tmp_path / "w0.h5")  # fmt: skip
    code, _, err = run_cli(capsys, "plot", tmp_path / "w0.h5")
    assert code == 0, err
    assert (tmp_path / "w0.png").stat().st_size > 0


def test_a_cycle_run_of_measured_heights_plots_and_says_why_no_gaussian_comparison(
    capsys, tmp_path
):
    """A jkr cycle run on a measured histogram (the README's ingest, then simulate --cycle):
    the comparison against the Gaussian GW curves draws the seed's panels on approach, which
    raised a broadcast error for two branches; it is left out, and said so."""
    import dataclasses

    from mcsim.model.presets import SURFACES
    from mcsim.topography.empirical import Empirical

    heights = Empirical.from_samples(np.random.default_rng(3).standard_normal(500) * 1e-9)
    surface = dataclasses.replace(SURFACES["smooth"], heights=heights, name="measured")
    mcsim.simulate(surface, "silicon", np.linspace(3, -1, 9), area="30 um^2", realizations=3,
                   seed=1, law="jkr", cycle=True, out=tmp_path / "c.h5")  # fmt: skip
    code, _, err = run_cli(capsys, "plot", str(tmp_path / "c.h5"), "--out", str(tmp_path / "c.png"))
    assert code == 0, err
    assert (tmp_path / "c.png").stat().st_size > 0 and not (tmp_path / "c-vs-gaussian.png").exists()
    assert "drawn for runs of the seed law set without --cycle only" in err
