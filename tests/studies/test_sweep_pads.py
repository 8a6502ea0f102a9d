"""``mcsim sweep --pads`` (issue 23): finite pads at every grid point, each point from its own
stream; ``sweep --preload``: the adhesion summary's turn balances the preload."""

import dataclasses
import json
import math

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FEW

from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import adhesion_summary
from mcsim.physics.analytic import gw_curves
from mcsim.physics.loadcontrol import preload_turn
from mcsim.store.sweepfile import read_sweep
from mcsim.store.sweepvariables import PADS
from mcsim.studies.sweeppoint import pads_seed
from mcsim.studies.sweeps import sweep

SMOOTH = dataclasses.replace(SURFACES["smooth"], sigma=2.5e-9)
SILICON = MATERIALS["silicon"]
#: Separations of the pads' specs (and of `simulate --h`): the turns lie near h = 2.
H = "4:-1:51"
PADS_OPTIONS = {"law": "jkr", "area": "30um^2", "restoring_force": "20uN", "preload": "1MPa"}


@pytest.fixture(scope="module")
def pads_sweep(tmp_path_factory):
    """Two σ points, 60 pads of 30 µm² each under a 1 MPa preload, written to a file."""
    path = tmp_path_factory.mktemp("pads") / "pads.h5"
    result = sweep(SMOOTH, SILICON, {"sigma": "2.5nm,3nm"}, pads=60, seed=7, out=path, workers=1,
                   **PADS_OPTIONS)  # fmt: skip
    return result, path


def _pads_json(capsys, tmp_path, seed, sigma, pads=60):
    """`mcsim simulate --cycle --preload` + `mcsim pads --format json` at one point (σ, m)."""
    surface, run = tmp_path / "smooth.toml", tmp_path / f"run{seed % 1000}.h5"
    surface.write_text(
        f'[surface]\nsigma = "{sigma!r} m"\nR = "{SMOOTH.R!r} m"\neta = "{SMOOTH.eta!r} m^-2"\n'
    )
    code, _, err = run_cli(capsys, "simulate", "--surface", surface, "--law", "jkr",
                           "--h", H, "--area", "30um^2", "--realizations", pads, "--seed", seed,
                           "--cycle", "--preload", "1MPa", "--out", run, "--quiet")  # fmt: skip
    assert code == 0, err
    code, out, err = run_cli(capsys, "pads", run, "--restoring-force", "20uN", "--format", "json")
    assert code == 0, err
    return json.loads(out)


def test_the_sweep_stores_every_pads_variable_with_its_unit(pads_sweep):
    result, path = pads_sweep
    on_disk = read_sweep(path)
    for name, (unit, _) in PADS.items():
        assert on_disk.units[name] == unit and on_disk.data[name].shape == (2,)
        assert np.all(np.isfinite(on_disk.data[name])), name
    assert on_disk.attrs["pads"] == 60 and on_disk.attrs["restoring_force"] == pytest.approx(
        20e-6, rel=ROUNDING_FEW
    )
    d = result.data
    assert np.all((d["p_stick_low"] <= d["p_stick"]) & (d["p_stick"] <= d["p_stick_high"]))
    assert np.all(
        (d["pull_off_q05"] <= d["pull_off_q50"]) & (d["pull_off_q50"] <= d["pull_off_q95"])
    )


def test_a_points_pads_are_simulate_cycle_preload_and_pads_with_the_points_own_seed(
    pads_sweep, tmp_path, capsys
):
    result, _ = pads_sweep
    seed = pads_seed(int(result.attrs["seed_entropy"]), 0)
    stats = _pads_json(capsys, tmp_path, seed, float(result.coords["sigma"][0]))
    d = result.data
    assert (stats["p_stick"], stats["mean"], stats["std"], stats["q50"]) == (
        d["p_stick"][0], d["pull_off_mean"][0], d["pull_off_std"][0], d["pull_off_q50"][0])  # fmt: skip
    assert [stats["p_stick_ci_low"], stats["p_stick_ci_high"]] == [
        d["p_stick_low"][0],
        d["p_stick_high"][0],
    ]


def test_simulate_cycle_preload_and_pads_with_another_seed_agree_within_the_statistics(
    pads_sweep, tmp_path, capsys
):
    result, _ = pads_sweep
    stats = _pads_json(capsys, tmp_path, 12345, float(result.coords["sigma"][0]))
    d = result.data
    # Independent samples of 60 pads: the difference of the means over its standard error,
    # and of the fractions over the binomial one (pooled p), are each below 5 in magnitude.
    se_mean = math.hypot(stats["se"], d["pull_off_std"][0] / math.sqrt(60))
    assert abs(stats["mean"] - d["pull_off_mean"][0]) < 5 * se_mean
    p = (stats["p_stick"] + d["p_stick"][0]) / 2
    assert abs(stats["p_stick"] - d["p_stick"][0]) < 5 * math.sqrt(2 * p * (1 - p) / 60)


def test_pads_do_not_depend_on_the_workers(pads_sweep):
    result, _ = pads_sweep
    again = sweep(
        SMOOTH, SILICON, {"sigma": "2.5nm,3nm"}, pads=60, seed=7, workers=2, **PADS_OPTIONS
    )
    for name in PADS:
        np.testing.assert_array_equal(again.data[name], result.data[name], err_msg=name)


def test_an_interrupted_pads_sweep_resumes_to_the_uninterrupted_one(
    pads_sweep, tmp_path, monkeypatch
):
    import mcsim.studies.sweeppoint as sweeps

    evaluate, path = sweeps.evaluate, tmp_path / "resumed.h5"

    def stop_at_point_1(point, config):
        if point.index == 1:
            raise KeyboardInterrupt
        return evaluate(point, config)

    monkeypatch.setattr(sweeps, "evaluate", stop_at_point_1)
    with pytest.raises(KeyboardInterrupt):
        sweep(SMOOTH, SILICON, {"sigma": "2.5nm,3nm"}, pads=60, seed=7, out=path, workers=1, **PADS_OPTIONS)  # fmt: skip
    monkeypatch.setattr(sweeps, "evaluate", evaluate)
    with pytest.raises(ParameterError, match="cannot resume"):  # other pads: another sweep
        sweep(SMOOTH, SILICON, {"sigma": "2.5nm,3nm"}, pads=61, out=path, resume=True, **PADS_OPTIONS)  # fmt: skip
    resumed = sweep(SMOOTH, SILICON, {"sigma": "2.5nm,3nm"}, pads=60, out=path, resume=True, **PADS_OPTIONS)  # fmt: skip
    for name in PADS:
        np.testing.assert_array_equal(resumed.data[name], pads_sweep[0].data[name], err_msg=name)


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
def test_sweep_preload_turns_where_the_mean_approach_load_balances_it_at_every_point():
    result = sweep(SMOOTH, SILICON, {"sigma": "1.4nm,2.5nm,5nm"}, law="jkr", preload="1MPa")
    for i, sigma in enumerate(result.coords["sigma"]):
        surface = dataclasses.replace(SMOOTH, sigma=float(sigma))
        turn = result.data["turn"][i]
        assert turn == preload_turn(surface, SILICON, 1e6, "jkr")
        load = gw_curves(surface, SILICON, np.array([turn]), "jkr").values["load"][0]
        assert load * SILICON.K == pytest.approx(1e6, rel=1e-6)  # load/(A K) times K: P
        assert (
            result.data["pull_off"][i] == adhesion_summary(surface, SILICON, "jkr", turn).pull_off
        )
    assert result.attrs["preload"] == 1e6


@pytest.mark.parametrize(
    "options, match",
    [({"pads": 10, "area": "30um^2"}, "restoring force"),
     ({"restoring_force": "1uN"}, "restoring_force applies to the pads only"),
     ({"pads": 0, "area": "30um^2", "restoring_force": "1uN"}, "pads = 0"),
     ({"pads": 10, "restoring_force": "1uN"}, "pads needs the patch area"),
     ({"preload": "1MPa", "turn": 1.0}, "turn and preload"),
     ({"preload": "-1MPa"}, "preload"),
     ({"pads": 10, "area": "30um^2", "restoring_force": "-1uN"}, "restoring_force"),
     ({"floor": 1e-6}, "floor applies to the pads only"),
     *(({"pads": 10, "area": "30um^2", "restoring_force": "1uN", "floor": f},
        rf"floor = {f!r}: out of range \(allowed: a probability in \[0, 1\)\)")
       for f in (-1e-6, 1.0, math.nan, True, "1e-6"))],
)  # fmt: skip
def test_bad_pads_options_are_one_line_errors_naming_the_field(options, match):
    with pytest.raises(MCSimError, match=match):
        sweep(SMOOTH, SILICON, {"sigma": "2nm"}, law="jkr", **options)


def test_cli_pads_sweep_warns_once_when_pads_touch_with_few_summits(tmp_path, capsys):
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary", "sigma=3nm",
                           "--pads", 5, "--area", "30um^2", "--restoring-force", "20uN", "--preload",
                           "1MPa", "--seed", 1, "--out", tmp_path / "few.h5", "--quiet")  # fmt: skip
    assert code == 0, err
    few = [line for line in err.splitlines() if "fewer than 10 summits" in line]
    assert len(few) == 1 and "1 of 1 points" in few[0]


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
def test_p_stick_model_agrees_with_brute_force_where_pads_touch_with_over_a_hundred_summits():
    # σ = 1.4 nm, 30 µm², 5 MPa: ~125 summits touch each pad. 150 pads: the model lies within
    # 5 binomial standard errors (at the model's p) of the Monte Carlo fraction.
    surface = SURFACES["smooth"]
    result = sweep(surface, SILICON, {"sigma": [surface.sigma]}, law="jkr", pads=150, seed=3,
                   area="30um^2", restoring_force="150uN", preload="5MPa")  # fmt: skip
    d = {k: float(v[0]) for k, v in result.data.items() if k in PADS}
    assert d["contacting_summits"] > 100
    p = d["p_stick_model"]
    assert 1e-3 <= p <= 1 - 1e-3
    assert abs(d["p_stick"] - p) < 5 * math.sqrt(p * (1 - p) / 150), d


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
def test_p_stick_model_agrees_with_brute_force_at_a_common_turn_where_the_extremum_matters():
    # No preload: every pad retracts from h = 0 (~255 summits touch a 30 µm² pad). The pads'
    # extrema lie well above their values at any one separation (max over h of P(X(h) > F)
    # was 0.53 here against a brute-force 0.69): the copula of the offsets must close the gap.
    surface = SURFACES["smooth"]
    result = sweep(surface, SILICON, {"sigma": [surface.sigma]}, law="jkr", pads=400, seed=3,
                   area="30um^2", restoring_force="210uN", turn=0.0)  # fmt: skip
    d = {k: float(v[0]) for k, v in result.data.items() if k in PADS}
    assert d["contacting_summits"] > 200
    p = d["p_stick_model"]
    assert 0.1 <= p <= 0.9
    assert abs(d["p_stick"] - p) < 5 * math.sqrt(p * (1 - p) / 400), d


def _union_of(p, g):
    from mcsim.studies.stiction import _union

    return _union(np.asarray(g, float), np.ones(np.shape(g)[1]), np.asarray(p, float))


def test_union_of_uncorrelated_offsets_is_one_minus_the_product_of_the_complements():
    # g_k on disjoint nodes: the compound-Poisson sums are uncorrelated, the copula independent.
    # abs 1e-5: ten times the absolute error asked of Genz's algorithm (abseps 1e-6).
    p = [0.2, 0.3, 0.1]
    assert _union_of(p, np.eye(3)) == pytest.approx(1 - 0.8 * 0.7 * 0.9, abs=1e-5)


def test_union_of_identical_offsets_is_their_common_probability_and_never_below_the_largest():
    same = np.ones((4, 5))
    assert _union_of([0.3] * 4, same) == pytest.approx(0.3, abs=1e-5)  # Genz: abseps 1e-6, x10
    # The chain bound: with the neighbours' correlation clipped to 1 − ε (ε = 1e-12), each of
    # the 3 pairs leaves P(A_k) − P(A_k ∩ A_k+1) ≈ φ(b)√(ε/π) = 2.5e-11 (b = Φ⁻¹(1e-5)): 7.6e-6
    # relative in all.
    assert _union_of([1e-5] * 4, same) == pytest.approx(1e-5, rel=1e-5)
    rng = np.random.default_rng(0)
    for _ in range(5):
        p, g = rng.uniform(0, 0.5, 6), rng.standard_normal((6, 8))
        # max p <= P(union) exactly (the model never returns less), <= Σp (Boole) up to
        # Genz's absolute error 1e-6
        assert p.max() <= _union_of(p, g) <= min(p.sum(), 1) + 1e-6


# --- the restoring force as a varied input (issue 33) ------------------------------------------


def test_a_varied_restoring_force_gives_each_point_the_pads_of_a_fixed_one(pads_sweep, tmp_path):
    """Point 0 (20 uN, σ = 2.5 nm) draws the pads of the fixed-force sweep's point 0 (same
    seed, same index, same inputs): the same numbers; no pad holds 1 N."""
    fixed, _ = pads_sweep
    options = {k: v for k, v in PADS_OPTIONS.items() if k != "restoring_force"}
    out = tmp_path / "force.h5"
    varied = sweep(SMOOTH, SILICON, {"restoring_force": "20uN,1N"}, pads=60, seed=7, out=out,
                   workers=1, **options)  # fmt: skip
    # 20 x 1e-6 from the unit table: one rounding
    assert varied.coords["restoring_force"] == pytest.approx([20e-6, 1.0], rel=ROUNDING_FEW)
    for name in PADS:
        assert varied.data[name][0] == fixed.data[name][0], name
    assert varied.data["p_stick"][1] == 0 and varied.data["p_stick_high"][1] < 0.1
    on_disk = read_sweep(out)
    assert on_disk.units["restoring_force"] == "N" and "restoring_force" not in on_disk.attrs


PADS_CLI = ("--pads", 5, "--area", "30um^2", "--restoring-force", "20uN", "--seed", 1)


@pytest.mark.parametrize(
    ("options", "scheduler", "workers"),
    [
        ([*PADS_CLI], "processes", None),  # pads: worker processes of this machine
        ([*PADS_CLI, "--workers", 2], "processes", 2),
        ([*PADS_CLI, "--workers", 1], None, 1),  # in this process
        ([*PADS_CLI, "--dask", "local", "--workers", 2], "local", 2),
        ([*PADS_CLI, "--scheduler", "tcp://host:8786"], "tcp://host:8786", None),
        ([], None, None),  # no pads: threads
    ],
)
def test_the_cli_sweeps_points_run_where_asked(monkeypatch, capsys, tmp_path, options, scheduler,
                                              workers):  # fmt: skip
    import mcsim.studies.sweeps

    asked = []

    def stop(*args, **kwargs):
        asked.append((kwargs["scheduler"], kwargs["workers"]))
        raise KeyboardInterrupt

    monkeypatch.setattr(mcsim.studies.sweeps, "sweep", stop)
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary",
                           "sigma=3nm,4nm", *options, "--out", tmp_path / "s.h5", "--quiet")  # fmt: skip
    assert code == 130 and asked == [(scheduler, workers)], err


@pytest.mark.parametrize("grid", [{"sigma": "3nm"}, {"sigma": "3nm,4nm,5nm"}])
def test_one_task_or_a_few_pads_on_processes_run_in_this_process(monkeypatch, grid):
    # a pool would only add its processes' start: one point (or points whose pads act
    # alike, one task), or 15 pads in all where no importance sampling can run (fewer than
    # POOL_PADS), run here, with the numbers of threads
    import mcsim.studies.sweeps

    def no_pool(workers):
        raise AssertionError("a process pool was started for one task or a few pads")

    options = {"pads": 5, "seed": 3, **PADS_OPTIONS}
    assert 3 * options["pads"] < mcsim.studies.sweeps.POOL_PADS
    threads = sweep(SMOOTH, SILICON, grid, **options)
    monkeypatch.setattr(mcsim.studies.sweeps, "process_pool", no_pool)
    here = sweep(SMOOTH, SILICON, grid, scheduler="processes", **options)
    for name in threads.data:
        np.testing.assert_array_equal(here.data[name], threads.data[name], err_msg=name)
    # the same points with more pads than that, or importance sampling possible, do start one
    monkeypatch.setattr(mcsim.studies.sweeps, "POOL_PADS", 15)
    if len(grid["sigma"].split(",")) > 1:
        with pytest.raises(AssertionError, match="process pool was started"):
            sweep(SMOOTH, SILICON, grid, scheduler="processes", **options)


def test_cli_sweep_varies_the_restoring_force_and_plots_it(tmp_path, capsys):
    out = tmp_path / "f.h5"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary",
                           "restoring_force=1uN:10uN:2", "--pads", 3, "--area", "1um^2", "--seed", 1,
                           "--h=2,0", "--out", out, "--quiet")  # fmt: skip
    assert code == 0, err
    code, _, err = run_cli(capsys, "plot", out, "--out", tmp_path / "f.png")
    assert code == 0 and (tmp_path / "f.png").exists(), err


@pytest.mark.parametrize(
    "options, match",
    [({}, "vary restoring_force: it applies to the pads only"),
     ({"pads": 3, "area": "1um^2", "restoring_force": "1uN"},
      "restoring_force: given both as a value and as a varied input"),
     ({"pads": 3, "area": "1um^2", "vary": "-1uN,1uN"}, "vary restoring_force: -1e-06 N is out of range")],
)  # fmt: skip
def test_a_varied_restoring_force_is_checked_in_one_line(options, match):
    vary = {"restoring_force": options.pop("vary", "1uN,2uN")}
    with pytest.raises(MCSimError, match=match):
        sweep(SMOOTH, SILICON, vary, law="jkr", **options)


def test_a_failed_worker_process_stops_the_sweep_where_a_failed_point_is_recorded(monkeypatch):
    # a point whose computation fails keeps its outputs so far and says why in "error"; the
    # pads' worker processes failing (killed, out of memory, a script each worker runs
    # again) is the machine's failure, not the point's: the sweep raises it
    import mcsim.studies.sweeppoint
    from mcsim.model.errors import WorkerError

    def failing(error):
        def _evaluate(point, config, out):
            raise error

        return _evaluate

    options = {"pads": 3, "seed": 3, **PADS_OPTIONS}
    monkeypatch.setattr(mcsim.studies.sweeppoint, "_evaluate", failing(ParameterError("bad")))
    result = sweep(SMOOTH, SILICON, {"sigma": "3nm"}, **options)
    assert list(result.data["error"].ravel()) == ["ParameterError: bad"]
    monkeypatch.setattr(mcsim.studies.sweeppoint, "_evaluate", failing(WorkerError("ended")))
    with pytest.raises(WorkerError, match="ended"):
        sweep(SMOOTH, SILICON, {"sigma": "3nm"}, **options)
