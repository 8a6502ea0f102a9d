"""Stiction statistics of finite pads (issue 11, §2): mcsim.studies.pads and `mcsim pads`."""

import json
import math

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

from mcsim.cli.main import main
from mcsim.model.errors import MCSimError, ParameterError, UnitError
from mcsim.model.units import parse_quantity
from mcsim.studies.intervals import CONFIDENCE, clopper_pearson
from mcsim.studies.pads import analytic_pad_pull_off, pad_statistics

KEYS = ["pads", "mean", "se", "std", "q05", "q50", "q95"]


# --- statistics on known arrays ----------------------------------------------------------


def test_pad_statistics_equal_the_direct_numpy_computations():
    rng = np.random.default_rng(5)
    force = rng.gamma(4.0, 2e-6, size=37)
    s = pad_statistics(force)
    assert s.pads == 37
    assert s.mean == np.mean(force)
    assert s.std == np.std(force, ddof=1)
    assert s.se == np.std(force, ddof=1) / math.sqrt(37)
    assert (s.q05, s.q50, s.q95) == tuple(np.quantile(force, [0.05, 0.5, 0.95]))
    assert s.p_stick is None and set(s.to_dict()) == set(KEYS)


def test_quantiles_of_a_known_small_array_interpolate_linearly_between_order_statistics():
    s = pad_statistics([4.0, 1.0, 3.0, 2.0, 0.0])  # sorted 0..4: the q-quantile is 4q
    assert (s.q05, s.q50, s.q95) == pytest.approx((0.2, 2.0, 3.8), abs=1e-15)
    assert s.mean == 2.0 and s.std == pytest.approx(math.sqrt(2.5), rel=1e-15)


def test_p_stick_counts_pads_whose_pull_off_exceeds_the_restoring_force_strictly():
    s = pad_statistics([1.0, 2.0, 2.0, 3.0], restoring_force=2.0)
    assert s.p_stick == 0.25 and s.p_stick_ci == clopper_pearson(1, 4)
    d = s.to_dict()
    assert list(d) == [*KEYS, "p_stick", "p_stick_ci"] and d["p_stick_ci"] == list(s.p_stick_ci)


def test_one_pad_has_an_undefined_spread():
    s = pad_statistics([3e-6])
    assert s.mean == 3e-6 and math.isnan(s.std) and math.isnan(s.se)


@pytest.mark.parametrize(
    "force, fr, match",
    [([], None, "no pads"), ([1.0, -1.0], None, ">= 0"), ([1.0, np.nan], None, "finite"),
     ([1.0], -1.0, "restoring_force"), ([1.0], math.inf, "restoring_force"),
     ([1.0], True, "restoring_force must be a number"), ([1.0], "2 m", "unknown unit 'm'")],
)  # fmt: skip
def test_bad_pull_off_forces_or_restoring_force_are_parameter_errors(force, fr, match):
    with pytest.raises(MCSimError, match=match):
        pad_statistics(force, fr)


# --- Clopper-Pearson ----------------------------------------------------------------------


def test_clopper_pearson_reproduces_closed_forms_and_the_textbook_value():
    # k = 0 and k = n: (α/2)^(1/n) closed forms; k = 1: the lower bound solves
    # 1 − (1 − p)^n = α/2. 5 of 10: (0.1871, 0.8129) (e.g. Brown, Cai & DasGupta 2001).
    assert clopper_pearson(0, 10) == (0.0, pytest.approx(1 - 0.025 ** (1 / 10), rel=1e-12))
    assert clopper_pearson(10, 10) == (pytest.approx(0.025 ** (1 / 10), rel=1e-12), 1.0)
    assert clopper_pearson(1, 20)[0] == pytest.approx(1 - 0.975 ** (1 / 20), rel=1e-10)
    assert clopper_pearson(19, 20)[1] == pytest.approx(0.975 ** (1 / 20), rel=1e-10)
    lo, hi = clopper_pearson(5, 10)
    assert (round(lo, 4), round(hi, 4)) == (0.1871, 0.8129)


def test_clopper_pearson_is_symmetric_under_swapping_successes_and_failures():
    for k in range(0, 31, 3):
        lo, hi = clopper_pearson(k, 30)
        lo2, hi2 = clopper_pearson(30 - k, 30)
        # probabilities in [0, 1] (near 0 or 1 at the ends): absolute; two beta quantiles by
        # scipy, each within ~1e-15 (measured 5.6e-17 apart)
        assert lo == pytest.approx(1 - hi2, abs=1e-13) and hi == pytest.approx(1 - lo2, abs=1e-13)


def test_the_intervals_are_scipy_stats_own_quantiles_to_the_bit():
    # mcsim.studies.intervals calls the function scipy.stats.beta.ppf and norm.ppf call,
    # without importing scipy.stats (half a second of each command's start): the same bits,
    # fractional effective counts (importance sampling's n*) and the domain's edges included
    from scipy.stats import beta, norm

    from mcsim.studies.intervals import _beta_ppf, effective_clopper_pearson, wilson

    alpha = 1 - CONFIDENCE
    for k, n in [(1, 4), (0, 7), (7, 7), (3, 2000), (1999, 2000), (40, 41)]:
        a = (0.0 if k == 0 else float(beta.ppf(alpha / 2, k, n - k + 1)),
             1.0 if k == n else float(beta.ppf(1 - alpha / 2, k + 1, n - k)))  # fmt: skip
        assert clopper_pearson(k, n) == a
        z = float(norm.ppf(1 - alpha / 2))
        p = k / n
        centre = (p + z * z / (2 * n)) / (1 + z * z / n)
        half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
        assert wilson(k, n) == (max(0.0, centre - half), min(1.0, centre + half))
    q, se = 3.2e-4, 2.2e-5
    m = q * (1 - q) / se**2
    expected = (float(beta.ppf(0.025, q * m, m - q * m + 1)),
                float(beta.ppf(0.975, q * m + 1, m - q * m)))  # fmt: skip
    assert effective_clopper_pearson(q, se, 0, 500) == expected
    for q, a, b in [(0.0, 2, 3), (1.0, 2, 3), (0.5, 0.0, 3), (1.5, 2, 3), (0.3, 2.5, 1e6)]:
        assert _beta_ppf(q, a, b) == pytest.approx(float(beta.ppf(q, a, b)), abs=0, nan_ok=True)


@pytest.mark.parametrize("p, n", [(0.1, 50), (0.02, 200), (0.5, 20)])
def test_clopper_pearson_interval_covers_the_true_probability_at_least_95_percent(p, n):
    """Simulated coverage over 4000 binomial samples (fixed seed) is never below 95 %
    by more than 5 binomial standard errors (the interval is exact: coverage ≥ 95 %)."""
    trials = 4000
    k = np.random.default_rng(2026).binomial(n, p, size=trials)
    covered = np.mean([lo <= p <= hi for lo, hi in (clopper_pearson(int(x), n) for x in k)])
    se = math.sqrt(CONFIDENCE * (1 - CONFIDENCE) / trials)
    assert (covered - CONFIDENCE) / se > -5


@pytest.mark.parametrize("k, n", [(-1, 5), (6, 5), (0, 0), (1.5, 5)])
def test_clopper_pearson_refuses_impossible_counts(k, n):
    with pytest.raises(ParameterError):
        clopper_pearson(k, n)


# --- units --------------------------------------------------------------------------------


def test_forces_are_read_with_their_units():
    assert parse_quantity("2uN", "force", "--restoring-force") == pytest.approx(2e-6, rel=1e-15)
    assert parse_quantity("500 nN", "force", "f") == pytest.approx(5e-7, rel=ROUNDING_FEW)
    assert parse_quantity("3", "force", "f") == 3.0
    with pytest.raises(UnitError, match="--restoring-force: unknown unit 'um' for a force"):
        parse_quantity("2um", "force", "--restoring-force")


# --- the command --------------------------------------------------------------------------


def simulate(path, *extra):
    code = main(["simulate", "--surface", "smooth", "--law", "jkr", "--area", "1.5um^2",
                 "--h=2:-1:16", "--realizations", "40", "--seed", "3", "--workers", "1",
                 "--quiet", "--out", str(path), *extra])  # fmt: skip
    assert code == 0
    return path


@pytest.fixture(scope="module")
def cycle_run(tmp_path_factory):
    return simulate(tmp_path_factory.mktemp("pads") / "c.h5", "--cycle")


def test_pads_json_has_exactly_the_statistics_of_the_runs_per_pad_pull_off(cycle_run, capsys):
    from mcsim.store.runfile import read_run

    code, out, _ = run_cli(capsys, "pads", cycle_run, "--format", "json")
    data = json.loads(out)
    extra = ["analytic_mean", "interval", "pull_off_method", "units"]
    assert code == 0 and list(data) == [*KEYS, *extra]
    run = read_run(cycle_run)
    expected = pad_statistics(run.pull_off().force).to_dict()
    # JSON keeps repr: exact, within ROUNDING_FEW
    assert {k: data[k] for k in KEYS} == pytest.approx(expected, rel=ROUNDING_FEW)
    assert data["pads"] == 40 and data["mean"] > 0
    assert data["analytic_mean"] == pytest.approx(analytic_pad_pull_off(run.spec), rel=ROUNDING_FEW)
    assert data["interval"].startswith("Clopper-Pearson") and data["units"]["mean"] == "N"


def test_pads_with_a_restoring_force_adds_p_stick_and_its_interval(cycle_run, capsys):
    from mcsim.store.runfile import read_run

    force = read_run(cycle_run).pull_off().force
    fr = float(np.median(force))
    code, out, _ = run_cli(capsys, "pads", cycle_run, f"--restoring-force={fr * 1e6!r}uN",
                           "--format", "json")  # fmt: skip
    data = json.loads(out)
    stick = ["restoring_force", "p_stick", "p_stick_ci_low", "p_stick_ci_high", "p_stick_model"]
    assert code == 0 and list(data)[: len(KEYS) + 5] == [*KEYS, *stick]
    assert 0 <= data["p_stick_model"] <= 1
    # repr(fr·1e6) uN back to N: two roundings
    assert data["restoring_force"] == pytest.approx(fr, rel=ROUNDING_FEW)
    k = int(np.count_nonzero(force > fr * 1e6 * 1e-6))
    assert data["p_stick"] == k / 40
    ci = [data["p_stick_ci_low"], data["p_stick_ci_high"]]
    assert ci == pytest.approx(list(clopper_pearson(k, 40)), rel=ROUNDING_FEW)


def test_pads_table_names_the_analytic_mean_and_how_the_pull_off_was_found(cycle_run, capsys):
    code, out, _ = run_cli(capsys, "pads", cycle_run, "--restoring-force", "1nN")
    assert code == 0
    assert "continuous h" in out and "turn h = -1" in out and "p_stick_ci_high" in out
    assert "analytic_mean" in out and "Clopper-Pearson" in out


def test_analytic_pad_pull_off_is_the_adhesion_summary_times_the_pad_area(cycle_run):
    from mcsim.physics.adhesion import adhesion_summary
    from mcsim.store.runfile import read_run

    spec = read_run(cycle_run).spec
    with pytest.warns(UserWarning):
        s = adhesion_summary(spec.surface, spec.material, "jkr", turn=-1.0)
    # the same product in the same order: ROUNDING_FEW (measured equal)
    assert analytic_pad_pull_off(spec) == pytest.approx(
        s.pull_off * spec.material.K * spec.area, rel=ROUNDING_FEW
    )


def test_pads_plot_writes_a_png_and_never_replaces_a_file_without_overwrite(cycle_run, capsys):
    out = cycle_run.with_name("pads.png")
    code, _, _ = run_cli(capsys, "pads", cycle_run, "--plot", out, "--restoring-force", "2uN")
    assert code == 0 and out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, _, err = run_cli(capsys, "pads", cycle_run, "--plot", out)
    assert code == 2 and err.count("\n") == 1 and "file exists" in err
    code, _, err = run_cli(capsys, "pads", cycle_run, "--plot", cycle_run.with_name("p.pdf"))
    assert code == 2 and err.count("\n") == 1 and ".png" in err


def one_line_error(capsys, *argv):
    code, out, err = run_cli(capsys, *argv)
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith("mcsim: error: ")
    return err


def test_a_run_without_a_cycle_is_a_one_line_error_naming_the_file(tmp_path, capsys):
    path = simulate(tmp_path / "approach.h5")
    err = one_line_error(capsys, "pads", path)
    assert str(path) in err and "cycle" in err


def test_a_missing_file_is_a_one_line_error_naming_it(tmp_path, capsys):
    err = one_line_error(capsys, "pads", tmp_path / "none.h5")
    assert str(tmp_path / "none.h5") in err


def half_done_checkpoint(path):
    """A checkpoint of a jkr cycle run of 4 pads (smooth, 1e-12 m², seed 9) holding its
    first two; returns the partial sums written."""
    from mcsim.engine.montecarlo import EnsembleSums, run_sums
    from mcsim.engine.spec import MonteCarloSpec
    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.store.runfile import write_checkpoint

    spec = MonteCarloSpec(SURFACES["smooth"], MATERIALS["silicon"], np.array([1.0, 0.0]), 1e-12,
                          4, 9, law="jkr", cycle=True)  # fmt: skip
    full = run_sums(spec)
    partial = EnsembleSums.start(spec)
    partial.sums[:2], partial.done_blocks[:2] = full.sums[:2], full.n_blocks[:2]
    write_checkpoint(path, partial, command="test")
    return partial


def test_an_incomplete_cycle_run_is_a_one_line_error_naming_the_file(tmp_path, capsys):
    half_done_checkpoint(tmp_path / "p.h5")
    err = one_line_error(capsys, "pads", tmp_path / "p.h5")
    assert str(tmp_path / "p.h5") in err and "incomplete run" in err


@pytest.mark.parametrize(
    "value, match",
    [("2um", "unknown unit 'um' for a force"), ("-1uN", "negative"), ("lots", "cannot read")],
)
def test_a_bad_restoring_force_is_a_one_line_error(cycle_run, capsys, value, match):
    err = one_line_error(capsys, "pads", cycle_run, f"--restoring-force={value}")
    assert "--restoring-force" in err and match in err


def test_across_pad_spread_matches_the_prediction_from_summit_moments_for_large_pads():
    """Acceptance (issue 11 §2): pads with ≥ 100 expected contacts (super-smooth, 10 µm²,
    ηA = 260), 300 pads: the sample standard deviation of the pull-off agrees with
    :func:`moment_std` within 5 of its standard errors, SE(s) = s/√(2(n − 1)) (normal
    approximation: the pull-off is a sum of hundreds of summit terms)."""
    import warnings

    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.physics.adhesion import RegimeWarning
    from mcsim.studies.pads import moment_std
    from mcsim.studies.simulation import simulate as run_simulate

    h = np.round(np.arange(3.0, -0.05, -0.1), 10)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        run = run_simulate(SURFACES["super-smooth"], MATERIALS["silicon"], h, 1e-11,
                           realizations=300, seed=11, law="maugis-dugdale", cycle=True, workers=1)  # fmt: skip
    assert run.spec.expected_summits >= 100
    s = pad_statistics(run.pull_off().force)
    predicted = moment_std(run)
    assert abs(s.std - predicted) / (s.std / math.sqrt(2 * (s.pads - 1))) < 5


def test_moment_std_refuses_a_run_without_a_cycle(tmp_path):
    from mcsim.store.runfile import read_run
    from mcsim.studies.pads import moment_std

    with pytest.raises(ParameterError, match="cycle"):
        moment_std(read_run(simulate(tmp_path / "a.h5")))


# --- Wilson interval, per-pad CSV, incomplete runs -----------------------------------------


def test_wilson_interval_reproduces_the_closed_form_and_a_textbook_value():
    # k = 0: the upper bound is z²/(n + z²); 5 of 10: (0.2366, 0.7634) (Brown, Cai &
    # DasGupta 2001; Newcombe 1998, method 3).
    from scipy.stats import norm

    from mcsim.studies.intervals import wilson

    z = norm.ppf(0.975)
    # the closed form, a few roundings and norm.ppf's own: ROUNDING_FORMULA
    assert wilson(0, 10) == (0.0, pytest.approx(z * z / (10 + z * z), rel=ROUNDING_FORMULA))
    lo, hi = wilson(5, 10)
    assert (round(lo, 4), round(hi, 4)) == (0.2366, 0.7634)
    lo, hi = wilson(3, 30)
    lo2, hi2 = wilson(27, 30)
    # probabilities: absolute, as above
    assert lo == pytest.approx(1 - hi2, abs=1e-13) and hi == pytest.approx(1 - lo2, abs=1e-13)
    with pytest.raises(ParameterError):
        wilson(6, 5)


def test_wilson_is_shorter_than_clopper_pearson_and_both_contain_the_estimate():
    from mcsim.studies.intervals import wilson

    for k, n in [(1, 40), (5, 40), (20, 40), (3, 300)]:
        w, c = wilson(k, n), clopper_pearson(k, n)
        assert w[0] <= k / n <= w[1] and c[0] <= k / n <= c[1]
        assert w[1] - w[0] < c[1] - c[0]


def test_pads_interval_wilson_replaces_the_interval_and_names_it(cycle_run, capsys):
    from mcsim.store.runfile import read_run
    from mcsim.studies.intervals import wilson

    force = read_run(cycle_run).pull_off().force
    fr = float(np.median(force))
    code, out, err = run_cli(capsys, "pads", cycle_run, f"--restoring-force={fr!r}",
                             "--interval", "wilson", "--format", "json")  # fmt: skip
    data = json.loads(out)
    k = int(np.count_nonzero(force > fr))
    ci = [data["p_stick_ci_low"], data["p_stick_ci_high"]]
    assert code == 0 and ci == pytest.approx(list(wilson(k, 40)), rel=ROUNDING_FEW)
    assert data["interval"].startswith("Wilson") and "Clopper" not in err
    code, out, _ = run_cli(capsys, "pads", cycle_run, "--restoring-force=1nN", "--interval",
                           "wilson")  # fmt: skip
    assert code == 0 and "Wilson 95 % interval" in out
    err = one_line_error(capsys, "pads", cycle_run, "--interval", "agresti")
    assert "--interval" in err and "wilson" in err


def test_pads_csv_has_one_row_per_pad_with_the_pull_off_in_newtons(cycle_run, capsys):
    import csv
    import io

    from mcsim.store.runfile import read_run

    code, out, err = run_cli(capsys, "pads", cycle_run, "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    pull_off = read_run(cycle_run).pull_off()
    assert code == 0 and out.splitlines()[0] == ("pad,pull_off_N,h_pull_off,h_turn,turn_load_N,"
                                                 "grid_pull_off_N,grid_h_pull_off")  # fmt: skip
    assert [int(r["pad"]) for r in rows] == list(range(40))
    assert [float(r["pull_off_N"]) for r in rows] == pull_off.force.tolist()
    assert [float(r["h_pull_off"]) for r in rows] == pull_off.h.tolist()
    assert [float(r["h_turn"]) for r in rows] == [-1.0] * 40
    assert [float(r["grid_pull_off_N"]) for r in rows] == pull_off.grid_force.tolist()
    assert "pull_off_N" in err and "N)" in err


def test_pads_partial_reads_the_completed_pads_of_a_checkpoint_and_says_how_many(tmp_path, capsys):
    from mcsim.store.results import assemble

    partial = half_done_checkpoint(tmp_path / "p.partial.h5")
    err = one_line_error(capsys, "pads", tmp_path / "p.partial.h5")
    assert "--partial" in err and "--resume" in err
    code, out, err = run_cli(capsys, "pads", tmp_path / "p.partial.h5", "--partial", "--format",
                             "json")  # fmt: skip
    expected = pad_statistics(assemble(partial.completed()).pull_off().force).to_dict()
    data = json.loads(out)
    # JSON keeps repr: the same numbers, within ROUNDING_FEW
    assert code == 0 and {k: data[k] for k in KEYS} == pytest.approx(
        expected, rel=ROUNDING_FEW, nan_ok=True
    )
    assert json.loads(out)["pads"] == 2 and "2 completed pad(s) of 4" in err


# --- force control: simulate --cycle --preload (issue 23) -------------------------------------


@pytest.fixture(scope="module")
def preload_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("preload") / "fc.h5"
    code = main(["simulate", "--surface", "smooth", "--law", "jkr", "--area", "3um^2", "--h=3:-1:9",
                 "--cycle", "--preload", "1MPa", "--realizations", "60", "--seed", "5",
                 "--workers", "1", "--quiet", "--out", str(path)])  # fmt: skip
    assert code == 0
    return path


def test_each_pad_turns_where_its_own_approach_load_reaches_the_preload(preload_run):
    from mcsim.engine.pads import load as padload
    from mcsim.store.runfile import read_run

    run = read_run(preload_run)
    pull = run.pull_off()
    spec, force = run.spec, 1e6 * 3e-12
    assert run.attrs["preload"] == 1e6 and pull.preload == 1e6
    assert np.all(pull.turn_load >= force) and np.ptp(pull.h_turn) > 0.1
    for r in range(3):
        z = padload.patch_heights(spec, r)
        above = (pull.h_turn[r] + 1e-6) * spec.surface.sigma
        assert padload.pad_load(spec, z, [above])[0] < force


def test_pad_turns_scatter_about_the_mean_field_turn(preload_run):
    from mcsim.store.runfile import read_run

    run = read_run(preload_run)
    t = run.pull_off().h_turn
    # To first order h_t - h_mean = (P A - F_a)/F_a' has mean zero (docs/physics.md, 'The stiction model').
    z = (t.mean() - run.attrs["preload_turn_mean_field"]) / (t.std(ddof=1) / math.sqrt(t.size))
    assert abs(z) < 5


def test_pads_of_a_preloaded_run_report_the_preload_and_the_turns(preload_run, capsys):
    code, out, _ = run_cli(capsys, "pads", preload_run, "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["preload"] == 1e6 and "force control" in data["pull_off_method"]
    assert data["h_turn_min"] <= data["h_turn_mean_field"] <= data["h_turn_max"]


def test_a_preload_without_a_cycle_or_beyond_the_grid_is_a_one_line_error(tmp_path, capsys):
    base = ["simulate", "--surface", "smooth", "--law", "jkr", "--area", "3um^2",
            "--preload", "1MPa", "--out", str(tmp_path / "x.h5")]  # fmt: skip
    err = one_line_error(capsys, *base, "--h=3:-1:5")
    assert "--cycle" in err
    err = one_line_error(capsys, *base, "--h=3:2.5:3", "--cycle")
    assert "extend h (--h) down" in err
