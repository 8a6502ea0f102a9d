"""Importance sampling of pads (issue 31): p_stick in the tail, with intervals that cover.

The sampling (tilted law, likelihood ratio, cross-entropy stages, estimate) is checked on
events of the pads' summits whose probability is exact: a Poisson count, so no pad curve is
evaluated and a test repeats it a hundred times. The event is not monotone in the heights,
as sticking under force control is not: at least m summits in a band (s_a, s_b] and none
above s_b, probability P(Poisson(λ_band) ≥ m)·exp(−λ_above). The pads' own pull-off against
brute force is validation/tail_benchmark.py's (thousands of pads).
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.stats import poisson

from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.studies.intervals import clopper_pearson, effective_clopper_pearson
from mcsim.studies.pads import finite_pads, pad_statistics, tail_p_stick
from mcsim.studies.rareevent import MIN_ESS, MIN_TAIL_PADS, SWITCH, rare_event
from mcsim.studies.tail import CHAINS, CONFIRM, FITTED, STAGES, importance_p_stick, mixture
from mcsim.studies.tiltlaw import RATIO_FLOOR, Law, Tilt, cut

#: The few-summit case of the issue: smooth at σ = 3 nm, 30 µm² (λ = 510 summits).
SURFACE = dataclasses.replace(SURFACES["smooth"], sigma=3e-9)
SILICON = MATERIALS["silicon"]
H = np.linspace(4, -1, 51)
#: Mean-field turn d/σ of that case under 1 MPa (mcsim.physics.loadcontrol.preload_turn, computed once).
TURN = 2.1279
#: The band of the exact event (σ), on edges of the tilt's bins: 13 summits per pad in it, 2.2 above it.
BAND = (TURN - 1 + 0.75, TURN - 1 + 1.5)


def _spec(seed, pads=10, area=30e-12):
    return MonteCarloSpec(SURFACE, SILICON, H, area, pads, seed, "jkr", cycle=True)


def _band_score(s):
    """Summits in the band, minus 1000 for each above it: > m − 1/2 is the exact event."""
    return np.count_nonzero((s > BAND[0]) & (s <= BAND[1])) - 1000.0 * np.count_nonzero(s > BAND[1])


def _exact(m, area=30e-12):
    lam = SURFACE.eta * area
    sf = SURFACE.heights.sf
    return float(
        poisson.sf(m - 1, lam * (sf(BAND[0]) - sf(BAND[1]))) * math.exp(-lam * sf(BAND[1]))
    )


def _estimate(seed, m, pads, pilot, **options):
    return importance_p_stick(_spec(seed), m - 0.5, turn=TURN, pads=pads, pilot=pilot,
                              score=_band_score, **options)  # fmt: skip


def test_likelihood_ratio_has_mean_one_under_the_tilted_law():
    # E_q[L] = 1 for any tilt q: 4000 pads of a mild tilt (ratios 0.8 … 1.25, light-tailed
    # weights); |z| < 5 against the sample's standard error.
    spec = _spec(1)
    law = Law(spec, cut(spec, TURN))
    tilt = Tilt(tuple(np.linspace(0.8, 1.25, 16)))
    highs = law.draw(tilt, 4000, np.random.default_rng(5))[1]
    weights = np.exp(law.log_ratio(tilt, law.bins(highs)))
    se = weights.std(ddof=1) / math.sqrt(weights.size)
    assert abs(weights.mean() - 1) < 5 * se, (weights.mean(), se)


def test_tilted_pads_below_the_cut_keep_the_nominal_count():
    # Summits below the cut are drawn untilted: their mean count is λ(S(s_min) − S(s_c)),
    # within 5 Poisson standard errors of the mean of 2000 pads.
    spec = _spec(1)
    law = Law(spec, cut(spec, TURN))
    tilt = Tilt((3.0,) * 16)
    pads, _ = law.draw(tilt, 2000, np.random.default_rng(6))
    low = [np.count_nonzero(s <= law.cut) for s in pads]
    lam = (
        SURFACE.eta
        * spec.area
        * float(SURFACE.heights.sf(spec.s_min) - SURFACE.heights.sf(law.cut))
    )
    assert abs(np.mean(low) - lam) < 5 * math.sqrt(lam / 2000)


def test_effective_clopper_pearson_is_the_plain_one_for_unweighted_pads():
    # 0/1 values: se² = q(1 − q)/n gives n* = n and x* = k, Clopper–Pearson of k in n.
    for k, n in ((3, 100), (57, 2000), (1, 10)):
        q = k / n
        got = effective_clopper_pearson(q, math.sqrt(q * (1 - q) / n), 0, 1)
        np.testing.assert_allclose(got, clopper_pearson(k, n), rtol=1e-9)


def test_without_an_effective_sample_size_the_interval_is_the_nominal_pads_own():
    # No pad in the event, or all weights alike: Clopper–Pearson of the nominal pads alone,
    # plain pads whatever the tilts drew; with none in the event [0, 1 − 0.025^(1/n0)] ≈ 3.7/n0
    # with n0 = ⌈0.2 n⌉, not the 3.7/n of n plain pads.
    n0 = mixture(2000)[0]
    assert n0 == 400
    assert effective_clopper_pearson(0.0, 0.0, 0, n0) == clopper_pearson(0, n0)
    assert effective_clopper_pearson(0.0, 0.0, 0, n0)[1] == pytest.approx(3.69 / n0, rel=0.01)
    assert effective_clopper_pearson(1.2, 0.0, 400, n0) == clopper_pearson(400, n0)


def test_the_reported_effective_sample_size_is_the_one_the_interval_takes():
    # ESS = n*·p̂ with n* = p̂(1 − p̂)/se²: the interval is Clopper–Pearson's of x* = ESS in n*.
    e = _estimate(3, 19, pads=400, pilot=200)
    n = e.p_stick * (1 - e.p_stick) / e.se**2
    assert e.ess == pytest.approx(n * e.p_stick, rel=1e-12)
    np.testing.assert_allclose((e.low, e.high), effective_clopper_pearson(e.p_stick, e.se, 0, 1))


def test_mixture_shares_the_final_pads_between_the_nominal_law_and_each_chain():
    for pads in (8, 400, 2001, 12_000):
        n = mixture(pads)
        assert len(n) == 1 + 2 * CHAINS and sum(n) == pads and min(n) >= 1
        assert n[0] == math.ceil(0.2 * pads)


def test_estimate_is_unbiased_for_an_exact_event_near_1e_2():
    m = 19
    p = _exact(m)
    assert 3e-3 < p < 3e-2
    e = _estimate(3, m, pads=2000, pilot=300)
    # |z| < 5 against the estimate's own standard error (a chance failure: 6e-7).
    assert abs(e.p_stick - p) < 5 * e.se, (e, p)
    assert e.event == "stick" and e.reached and e.hits > 100


def test_intervals_cover_an_exact_event_near_1e_2_in_at_least_90_percent_of_runs():
    # 100 independent runs (seeds from SeedSequence.spawn): a 95 % interval covers 95 of them
    # on average, binomial SE √(0.95·0.05/100) = 2.2 runs; 90 lies 2.3 SE below, so a correct
    # interval fails this check with probability ~1 %, one that covers 85 % fails it with
    # probability ~90 %. (A standard error 20 % too small, coverage ~88 %, passed it once: the
    # unbiasedness and the likelihood-ratio tests are the finer checks.)
    m = 19
    p = _exact(m)
    seeds = [int(c.generate_state(1)[0]) for c in np.random.SeedSequence(31).spawn(100)]
    covered = sum(
        e.low <= p <= e.high for e in (_estimate(s, m, pads=400, pilot=200) for s in seeds)
    )
    assert covered >= 90, covered


def test_estimate_reaches_1e_6_with_a_relative_half_width_under_20_percent():
    m = 32
    p = _exact(m)
    assert 5e-7 < p < 2e-6
    e = _estimate(4, m, pads=2000, pilot=1000)
    assert abs(e.p_stick - p) < 5 * e.se, (e, p)
    assert (e.high - e.low) / 2 <= 0.2 * e.p_stick, e
    assert e.evaluations <= 20_000


def test_a_rare_release_is_estimated_as_one_minus_its_probability():
    # Score: the summits in the band. Fewer than 4 of them (Poisson mean 13) is the rare side.
    lam = SURFACE.eta * 30e-12 * float(SURFACE.heights.sf(BAND[0]) - SURFACE.heights.sf(BAND[1]))
    p = float(poisson.sf(3, lam))
    assert 1 - p < 1e-2

    def band(s):
        return float(np.count_nonzero((s > BAND[0]) & (s <= BAND[1])))

    e = importance_p_stick(_spec(7), 3.5, turn=TURN, pads=2000, pilot=300, score=band,
                           event="release")  # fmt: skip
    assert e.event == "release" and e.hits > 100
    assert abs(e.p_stick - p) < 5 * e.se and e.low <= e.p_stick <= e.high <= 1.0, (e, p)


def test_a_floor_above_the_event_bounds_it_after_fewer_pads():
    # p ≈ 2.5e-10 and a floor of 1e-4: every chain's stages show the event below the floor
    # (the interval of a level the event lies within) and stop there, in each of 12 seeds:
    # p_stick 0, its interval [0, bound] with p <= bound < floor, no final pads.
    m = 40
    p = _exact(m)
    full = _estimate(0, m, pads=2000, pilot=300)
    assert not full.bounded and full.low <= p <= full.high
    for seed in range(12):
        e = _estimate(seed, m, pads=2000, pilot=300, floor=1e-4)
        assert e.bounded and e.p_stick == 0 == e.low and p <= e.high < 1e-4, (seed, e)
        assert e.ess >= MIN_ESS and e.pads == 0 and e.evaluations < full.evaluations, (seed, e)
        assert all(c[2] <= e.high for c in e.chains) and not e.reached


def test_a_floor_below_the_event_changes_nothing():
    # p ≈ 1.3e-4 above a floor of 1e-6: the same estimate, bit for bit, as without a floor.
    m = 26
    assert _exact(m) > 1e-5
    assert _estimate(3, m, pads=1000, pilot=300, floor=1e-6) == _estimate(3, m, pads=1000,
                                                                          pilot=300)  # fmt: skip


def test_a_release_below_the_floor_is_bounded_from_one():
    # Score: the summits in the band; fewer than 1 (Poisson mean 13: 1 − p ≈ 2e-6) is the
    # rare side, below a floor of 1e-2: p_stick 1, its interval [1 − bound, 1].
    lam = SURFACE.eta * 30e-12 * float(SURFACE.heights.sf(BAND[0]) - SURFACE.heights.sf(BAND[1]))
    q = math.exp(-lam)
    assert q < 1e-5

    def band(s):
        return float(np.count_nonzero((s > BAND[0]) & (s <= BAND[1])))

    e = importance_p_stick(_spec(7), 0.5, turn=TURN, pads=2000, pilot=300, score=band,
                           event="release", floor=1e-2)  # fmt: skip
    assert e.bounded and e.event == "release" and e.p_stick == 1 == e.high, e
    assert 1 - 1e-2 < e.low <= 1 - q, (e, q)


def test_same_seed_is_bit_identical_whatever_the_workers():
    one = _estimate(9, 19, pads=300, pilot=200)
    two = _estimate(9, 19, pads=300, pilot=200, workers=2)
    assert one == two


def test_bad_requests_are_one_line_errors():
    with pytest.raises(ParameterError, match="pilot >= 10"):
        _estimate(1, 19, pads=100, pilot=5)
    with pytest.raises(ParameterError, match="event"):
        _estimate(1, 19, pads=100, pilot=100, event="both")
    fixed = dataclasses.replace(_spec(1), count="fixed")
    with pytest.raises(ParameterError, match="Poisson"):
        importance_p_stick(fixed, 1.0, turn=TURN, pads=100, pilot=100, score=_band_score)


def _pads(fr, n, tail=None, seed=2, area=3e-12):
    """Plain pads of a small area (51 summits) under 1 MPa, with ``tail``."""
    spec = _spec(seed, pads=n, area=area)
    return finite_pads(spec, fr, preload=1e6, turn=TURN, h_pull_off=2.3, tail=tail)


def test_plain_pads_are_kept_bit_for_bit_where_enough_lie_on_either_side():
    # 3 µN: about half of the 100 pads stick; tail None leaves the plain numbers as tail False.
    auto, plain = _pads(3e-6, 100), _pads(3e-6, 100, tail=False)
    assert auto["p_stick_method"] == "pads" and auto == plain
    assert auto["p_stick_ess"] == min(auto["p_stick"], 1 - auto["p_stick"]) * 100


def test_few_sticking_pads_switch_to_importance_sampling_or_stay_with_a_note_below_100_pads():
    s = pad_statistics(np.r_[np.full(95, 1.0), np.full(5, 3.0)], 2.0)
    spec = _spec(2, pads=100, area=3e-12)
    out = tail_p_stick(spec, s, 2.0, turn=TURN, preload=None, tail=False)
    assert out["p_stick_method"] == "pads" and out["p_stick"] == 0.05
    small = pad_statistics(np.r_[np.full(95, 1.0), np.full(4, 3.0)], 2.0)
    assert (
        tail_p_stick(spec, small, 2.0, turn=TURN, preload=None, tail=None)["p_stick_method"]
        == "pads"
    )
    with pytest.raises(ParameterError, match=f"at least {MIN_TAIL_PADS} pads"):
        tail_p_stick(spec, small, 2.0, turn=TURN, preload=None, tail=True)


def test_sweep_never_stores_a_model_probability_outside_0_1():
    # Issue 31: a pad of 1e-40 m² with F_r = 0 stored p_stick_model = 1.07e13.
    from mcsim.studies.sweeps import sweep

    result = sweep(SURFACE, SILICON, {"sigma": [3e-9]}, law="jkr", pads=3, seed=1,
                   area="1e-40 m^2", restoring_force=0.0)  # fmt: skip
    assert 0.0 <= result.data["p_stick_model"][0] <= 1.0
    assert result.data["p_stick_method"][0] == "pads"


@pytest.mark.slow  # importance sampling of 2000 final pads: ~10–30 s
def test_cli_sweep_tail_stores_the_method_its_effective_sample_size_and_draws_them(
    tmp_path, capsys
):
    from conftest import run_cli

    from mcsim.figures.stiction import stiction_figure
    from mcsim.store.sweepfile import read_sweep

    out = tmp_path / "tail.h5"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary",
                           "sigma=2.8nm,3nm", "--preload", "1MPa", "--pads", 100, "--area", "3um^2",
                           "--restoring-force", "6uN", "--seed", 1, "--tail", "--out", out, "--quiet")  # fmt: skip
    assert code == 0, err
    result = read_sweep(out)
    d = result.data
    assert list(d["p_stick_method"]) == ["importance"] * 2 and np.all(d["p_stick_ess"] >= 30)
    assert np.all((0 <= d["p_stick_low"]) & (d["p_stick_low"] <= d["p_stick"]))
    assert np.all((d["p_stick"] <= d["p_stick_high"]) & (d["p_stick_high"] <= 1))
    assert "p_stick by importance sampling at 2 of 2 points" in err
    # p_stick_model (~0.06) lies outside the intervals here: one warning line says so
    assert sum("p_stick_model lies outside" in line for line in err.splitlines()) == 1
    labels = [t.get_text() for t in stiction_figure(result).legends[0].get_texts()]
    assert any("importance sampling" in t for t in labels), labels


def test_cli_tail_with_too_few_pads_is_a_one_line_error(tmp_path, capsys):
    from conftest import run_cli

    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary", "sigma=3nm",
                           "--pads", 50, "--area", "3um^2", "--restoring-force", "6uN", "--tail",
                           "--out", tmp_path / "few.h5")  # fmt: skip
    assert (
        code != 0 and f"needs at least {MIN_TAIL_PADS} pads" in err and len(err.splitlines()) == 1
    )


@pytest.mark.slow  # importance sampling of 2000 final pads: ~10–30 s
def test_cli_pads_tail_reports_the_method_beside_the_run_pads_statistics(tmp_path, capsys):
    import json

    from conftest import run_cli

    run, surface = tmp_path / "run.h5", tmp_path / "smooth.toml"
    surface.write_text(
        f'[surface]\nsigma = "3 nm"\nR = "{SURFACE.R!r} m"\neta = "{SURFACE.eta!r} m^-2"\n'
    )
    code, _, err = run_cli(capsys, "simulate", "--surface", surface, "--law", "jkr",
                           "--h", "4:-1:51", "--area", "3um^2", "--realizations", 100, "--seed", 1,
                           "--cycle", "--preload", "1MPa", "--out", run, "--quiet")  # fmt: skip
    assert code == 0, err
    code, out, err = run_cli(
        capsys, "pads", run, "--restoring-force", "6uN", "--tail", "--format", "json"
    )
    assert code == 0, err
    data = json.loads(out)
    plain = json.loads(
        run_cli(capsys, "pads", run, "--restoring-force", "6uN", "--format", "json")[1]
    )
    assert data["p_stick_method"] == "importance" and plain["p_stick_method"] == "pads"
    assert data["mean"] == plain["mean"] and data["p_stick"] != plain["p_stick"]
    assert "importance sampling" in data["interval"]


@pytest.mark.slow  # importance sampling of 2000 final pads: ~10–30 s
def test_few_sticking_pads_switch_to_importance_sampling_by_themselves():
    # 100 pads of 3 µm² under 1 MPa, F_r = 18 µN: fewer than SWITCH stick, so tail=None takes
    # importance sampling, as tail=True does; the pull-off statistics stay those of the plain
    # pads, bit for bit.
    auto, plain = _pads(18e-6, 100), _pads(18e-6, 100, tail=False)
    assert round(plain["p_stick"] * 100) < SWITCH and plain["p_stick_method"] == "pads"
    assert auto["p_stick_method"] == "importance" and auto["p_stick_ess"] >= MIN_ESS
    assert auto["p_stick_low"] <= auto["p_stick"] <= auto["p_stick_high"]
    assert auto == _pads(18e-6, 100, tail=True)
    assert {k: v for k, v in auto.items() if not k.startswith("p_stick")} == {
        k: v for k, v in plain.items() if not k.startswith("p_stick")
    }


def test_defensive_mixture_is_unbiased_where_the_tilt_alone_has_heavy_weights():
    # The event of the band with a second way in, as sticking has on few-summit pads: m summits
    # in the band and none above it, or m + 7 in it with some above (11 % of the event). The
    # tilt thins the summits above the band, so the second way's pads carry large weights
    # L; the mixture's weights are at most 1/DEFENSIVE. Mean of 30 runs against the exact
    # probability, |z| < 5 with the runs' own spread (a chance failure: 6e-7).
    m, extra = 19, 7
    lam = SURFACE.eta * 30e-12
    sf = SURFACE.heights.sf
    band, above = lam * (sf(BAND[0]) - sf(BAND[1])), lam * sf(BAND[1])
    p = float(poisson.sf(m - 1, band) * math.exp(-above)
              + poisson.sf(m + extra - 1, band) * -math.expm1(-above))  # fmt: skip

    def score(s):
        n = np.count_nonzero((s > BAND[0]) & (s <= BAND[1]))
        return float(n - extra * bool(np.any(s > BAND[1])))

    seeds = [int(c.generate_state(1)[0]) for c in np.random.SeedSequence(32).spawn(30)]
    runs = [importance_p_stick(_spec(s), m - 0.5, turn=TURN, pads=400, pilot=200, score=score)
            for s in seeds]  # fmt: skip
    q = np.array([e.p_stick for e in runs])
    assert abs(q.mean() - p) < 5 * q.std(ddof=1) / math.sqrt(q.size), (q.mean(), p)


def test_the_automatic_switch_gives_up_where_the_stages_cannot_reach_the_event():
    # The summit count in the band reaches ~3x its mean in no pad: with give_up the stages stop
    # where their level rises too slowly and no final pads are drawn (p NaN, ESS 0: the plain
    # fraction stays); without it, every stage and the final pads run.
    def count(s):
        return float(np.count_nonzero(s > BAND[0]))

    far = 1e6
    quick = importance_p_stick(_spec(3), far, turn=TURN, pads=400, pilot=100, score=count,
                               give_up=True)  # fmt: skip
    assert math.isnan(quick.p_stick) and quick.ess == 0 and quick.pads == 0
    assert not quick.reached and quick.evaluations < CHAINS * 100 * (STAGES + 1)
    assert quick.evaluations <= 100 * (STAGES + 1)  # the first chain's stages alone
    full = importance_p_stick(_spec(3), far, turn=TURN, pads=400, pilot=100, score=count)
    assert full.pads == 400 and full.evaluations == CHAINS * 100 * (STAGES + 1) + 400
    assert full.p_stick == 0 and full.ess == 0
    # no pad in the event: the nominal pads' own bound, 0 in ⌈0.2 · 400⌉ = 80 final ones and
    # the chains' stages 0 of 100 each
    assert (full.low, full.high) == clopper_pearson(0, 80 + CHAINS * 100)


def test_a_later_chain_that_stalls_keeps_the_first_ones_estimate(monkeypatch):
    # The second chain, kept off the first one's way in under force control, may find no
    # other and stall: that ends its own stages, not the search (the report's pads at RH 0
    # fell back to their plain 0 [0, 0.036] this way). Its last tilt joins the mixture.
    import mcsim.studies.tail as tail

    real = tail._cross_entropy

    def second_stalls(law, c, *args, **kwargs):
        chain = real(law, c, *args, **kwargs)
        return dataclasses.replace(chain, reached=False) if c else chain

    options = dict(turn=TURN, pads=400, pilot=100, score=_band_score, give_up=True)
    both = importance_p_stick(_spec(2), 18.5, **options)
    monkeypatch.setattr(tail, "_cross_entropy", second_stalls)
    stalled = importance_p_stick(_spec(2), 18.5, **options)
    assert both.reached and not stalled.reached
    assert stalled.p_stick == both.p_stick and stalled.pads == 400 and stalled.ess > 0


def test_pads_from_the_tilt_refitted_to_every_pad_in_the_event_join_the_estimate(monkeypatch):
    # After the final pads, ⌈FITTED · pads⌉ more are drawn from one tilt fitted (unsmoothed)
    # to every pad in the event so far, both chains' and the final ones, each weighted by the
    # mixture of every law drawn: its ratio in each bin is their weighted mean count over the
    # nominal one. They join the estimate and its evaluations (issue 44, the reach point's
    # heavy pads); with no pad in the event none are drawn.
    import mcsim.studies.tail as tail

    drawn, real = [], tail._stage

    def record(law, tilt, n, key, scores):
        out = real(law, tilt, n, key, scores)
        drawn.append((tilt, n, key, *out))
        return out

    monkeypatch.setattr(tail, "_stage", record)
    e = _estimate(3, 19, pads=400, pilot=200)
    final = [d for d in drawn if d[2][0] == CHAINS]
    assert [d[1] for d in final] == [*mixture(400), math.ceil(FITTED * 400)]
    assert final[-1][2] == (CHAINS, len(mixture(400)))
    stages = sum(d[1] for d in drawn if d[2][0] < CHAINS)
    assert e.evaluations == stages + 400 + math.ceil(FITTED * 400)
    # the refitted tilt from the pads before it, weighted as the estimate weights them
    law = Law(_spec(3), cut(_spec(3), TURN))
    laws = [d[0] for d in drawn[:-1]]
    sizes = [d[1] for d in drawn[:-1]]
    counts = np.vstack([d[3] for d in drawn[:-1]])
    y = (np.concatenate([d[4] for d in drawn[:-1]]) > 18.5) * law.weight(laws, sizes, counts)
    expected = (y @ counts) / (y.sum() * law.mass)
    ratio = np.asarray(final[-1][0].ratio)
    live = law.mass > 0
    # the same weighted sums in another order: rounding only, ~1e-15 relative
    assert np.allclose(ratio[live], np.maximum(expected[live], RATIO_FLOOR), rtol=1e-9)
    drawn.clear()
    none = _estimate(3, 1000, pads=400, pilot=200)  # 1000 summits in the band: no pad has them
    assert none.hits == 0 and [d[1] for d in drawn if d[2][0] == CHAINS] == list(mixture(400))


def test_where_the_chains_disagree_the_plain_fraction_stays(monkeypatch):
    # rare_event keeps the plain fraction (it cannot tell) where the two tilts' own estimates
    # disagree, however large the effective sample size.
    import mcsim.studies.rareevent as rareevent

    real = rareevent.importance_p_stick

    def disagreeing(*args, **kwargs):
        return dataclasses.replace(real(*args, **kwargs), agree=False)

    plain = ("p_stick", 100, 0.03, clopper_pearson(3, 100), 18.5)
    options = dict(turn=TURN, preload=None, tail=True, score=_band_score)
    out = rare_event(_spec(2), *plain, **options)
    assert out["p_stick_method"] == "importance" and out["p_stick_ess"] >= MIN_ESS
    monkeypatch.setattr(rareevent, "importance_p_stick", disagreeing)
    out = rare_event(_spec(2), *plain, **options)
    assert out["p_stick_method"] == "pads" and out["p_stick"] == 0.03
    assert (out["p_stick_low"], out["p_stick_high"]) == clopper_pearson(3, 100)


def test_a_chain_needs_confirm_effective_events_for_an_interval_within_a_factor_of_7():
    # CONFIRM's reason: a chain's own interval on 5 effective events spans a factor of 7
    # (Poisson's [1.62, 11.67]), on 2 a factor of 30, wide enough to agree with anything
    def span(ess, q=1e-5):
        low, high = effective_clopper_pearson(q, q * math.sqrt((1 - q) / ess), 0, 100)
        return high / low

    assert CONFIRM == 5 and 7 < span(CONFIRM) < 7.5 and 29 < span(2) < 31


def test_a_sticking_with_a_second_tall_way_in_is_estimated_or_flagged():
    # Two disjoint ways into a rare "sticking" (validation/tail_benchmark.py's TwoWays): A, at
    # least 26 summits in the band and none above it (62 % of p), or B, at least 6 summits
    # above 3σ, as force-controlled pads (a preload marks them). The score rises through B
    # first, so the first chain raises the summits above the turn; the second may not, and
    # looks for A, which the score hides until a pad is almost in it. In every run of the size
    # a sweep uses, the interval holds p or the run says it cannot tell: the chains disagree,
    # or one rests on fewer than CONFIRM effective events. With both chains free none did and
    # all lay at 0.27–0.44 p; with the second kept off the tall way but any chain counted, one
    # of these ten (0.37 p) and 6 of 30 agreed on B alone (validation/README.md).
    m, m_tall, tall = 26, 6, 3.0
    lam, sf = SURFACE.eta * 30e-12, SURFACE.heights.sf
    p = _exact(m) + float(poisson.sf(m_tall - 1, lam * sf(tall)))

    def score(s):
        return max(_band_score(s), float(np.count_nonzero(s > tall) + m - m_tall))

    seeds = [int(c.generate_state(1, np.uint64)[0]) for c in np.random.SeedSequence(21).spawn(10)]
    runs = [importance_p_stick(_spec(s), m - 0.5, turn=TURN, preload=1e6, pads=2000, pilot=300,
                               score=score)  # force control: the second chain's restriction
            for s in seeds]  # fmt: skip
    told = [e.low <= p <= e.high or not e.agree for e in runs]
    assert all(told), [(e.p_stick / p, e.low / p, e.high / p, e.agree) for e in runs]


def test_a_signal_ends_the_pads_and_their_importance_sampling_in_a_worker_thread():
    # Ctrl-C of `mcsim report` waited minutes for the importance sampling of the humidities
    # running in the sweep's worker threads to end by itself; a recorded signal now ends the
    # plain pads and the stages at the next pad, no pad evaluated after it.
    import signal
    from concurrent.futures import ThreadPoolExecutor

    from mcsim.engine import interrupt

    scored = []

    def band(s):
        scored.append(s)
        return _band_score(s)

    with interrupt.interruptible(), ThreadPoolExecutor(1) as pool:
        signal.raise_signal(signal.SIGINT)
        with pytest.raises(interrupt.Interrupted):
            pool.submit(importance_p_stick, _spec(1), 25.5, turn=TURN, pads=1000, pilot=300,
                        score=band).result()  # fmt: skip
        with pytest.raises(interrupt.Interrupted):
            pool.submit(finite_pads, _spec(1, pads=5), 1e-6, turn=TURN,
                        h_pull_off=math.nan).result()  # fmt: skip
    assert scored == []
