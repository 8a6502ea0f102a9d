"""The Monte Carlo engine: kernel correctness, reproducibility, sampling and statistics."""

import copy
import dataclasses

import numpy as np
import pytest
from scipy import stats
from tolerances import ROUNDING_SUM, assert_close

from mcsim import ParameterError
from mcsim.cli.options import LAW_SET_NAMES
from mcsim.engine.kernels import block_sums, block_sums_numpy
from mcsim.engine.montecarlo import BLOCK, run_sums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.distributions import GAUSSIAN
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import LAW_SETS, SEED
from mcsim.studies.simulation import simulate

SILICON = MATERIALS["silicon"]
SMOOTH = SURFACES["smooth"]


def spec(**kw):
    base = dict(
        surface=SMOOTH,
        material=SILICON,
        h=np.linspace(3, -1, 9),
        area=1e-9,
        realizations=3,
        entropy=1,
    )
    return MonteCarloSpec(**{**base, **kw})


@pytest.mark.parametrize("name", ["rough", "smooth", "super-smooth"])
def test_fused_kernel_matches_numpy_reference_to_1e12(name):
    surface = SURFACES[name]
    args = SEED.arguments(surface, SILICON)
    rng = np.random.default_rng(7)
    for _ in range(5):
        z = rng.standard_normal(rng.integers(1, 5000)) * surface.sigma
        h = np.sort(rng.uniform(-4, 4, rng.integers(1, 40)))[::-1]
        d = h * surface.sigma
        fast = block_sums(z, d, SEED, args)
        ref = block_sums_numpy(z, d, SEED, args)
        np.testing.assert_array_equal(fast[:, 0], ref[:, 0], err_msg="contact counts")
        # sums over < 5000 summits, in the kernel's order and NumPy's (pairwise); all terms of one sign
        np.testing.assert_allclose(fast, ref, rtol=ROUNDING_SUM, atol=0)


def test_kernel_counts_a_summit_exactly_at_the_separation_as_not_touching():
    z = np.array([1e-9, 2e-9])
    d = np.array([2e-9, 1e-9, 0.0])
    out = block_sums(z, d, SEED, SEED.arguments(SMOOTH, SILICON))
    np.testing.assert_array_equal(out[:, 0], [0, 1, 2])


def test_same_seed_gives_bit_identical_sums():
    a, b = run_sums(spec()), run_sums(spec())
    np.testing.assert_array_equal(a.sums, b.sums)
    np.testing.assert_array_equal(a.n_summits, b.n_summits)


def test_chunk_size_and_worker_count_do_not_change_a_single_bit():
    s = spec(area=4e-8, realizations=2)  # ~680k summits: several blocks per patch
    ref = run_sums(s, workers=1, chunk_size=1 << 20)
    assert ref.n_summits.min() > 4 * BLOCK
    for workers, chunk in [(2, 1), (3, BLOCK), (2, 3 * BLOCK + 5), (1, 10**9)]:
        other = run_sums(s, workers=workers, chunk_size=chunk)
        np.testing.assert_array_equal(
            other.sums, ref.sums, err_msg=f"workers={workers}, chunk={chunk}"
        )


def test_different_seeds_give_different_patches():
    assert not np.array_equal(run_sums(spec(entropy=1)).sums, run_sums(spec(entropy=2)).sums)


def test_separation_order_does_not_change_the_numbers():
    h = np.array([0.5, -1.0, 2.0, 1.0])
    a = run_sums(spec(h=h))
    order = np.argsort(-h)
    b = run_sums(spec(h=h[order]))
    np.testing.assert_array_equal(a.sums[:, order], b.sums)


def test_fixed_count_puts_round_eta_area_summits_in_every_patch():
    s = spec(count="fixed", area=1.03e-10)
    ens = run_sums(s)
    assert np.all(ens.n_summits == round(SMOOTH.eta * 1.03e-10))


def test_kept_heights_are_the_summits_above_the_lowest_separation():
    s = spec(h=[1.0, 0.5])
    ens = run_sums(s, keep_heights=True)
    for r, z in enumerate(ens.heights):
        assert np.all(z > 0.5 * SMOOTH.sigma)
        assert z.size == ens.sums[r, 1, 0]  # every kept summit touches at h = 0.5


@pytest.mark.parametrize("s_min", [-np.inf, -1.5, 0.0, 0.7, 3.0])
def test_truncated_gaussian_sampler_has_the_truncated_mean_and_variance(s_min):
    """E[S | S > a] = φ(a)/Q(a), Var = 1 + aφ/Q − (φ/Q)²; z of the sample mean < 5."""
    n = 200_000
    x = GAUSSIAN.sample_above(n, s_min, np.random.default_rng(3))
    assert x.size == n and np.all(x > s_min)
    dist = stats.truncnorm(s_min, np.inf)
    z = (x.mean() - dist.mean()) / (dist.std() / np.sqrt(n))
    assert abs(z) < 5
    ks = stats.kstest(x[:20_000], dist.cdf)
    assert ks.pvalue > 1e-4, "KS test: distribution shape"


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"area": 0.0}, r"area = 0.0 m\^2 is out of range \(allowed: > 0"),
        ({"area": -1e-9}, r"area = -1e-09"),
        ({"area": float("nan")}, "area = nan"),
        ({"realizations": 0}, r"realizations = 0 is out of range \(allowed: integer >= 1\)"),
        ({"realizations": 2.5}, "realizations = 2.5"),
        ({"h": []}, "h must be a non-empty list"),
        ({"h": [0.0, np.inf]}, "h must be finite"),
        ({"law": "dmtx"}, r"unknown law set 'dmtx' \(allowed: .*seed\); did you mean 'dmt'\?"),
        ({"count": "exact"}, "count = 'exact' is not one of poisson, fixed"),
        ({"count": "fixed", "area": 1e-15}, r"round\(eta\*area\) must be >= 1"),
    ],
)
def test_invalid_run_inputs_raise_a_parameter_error(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        spec(**kwargs)


def test_workers_and_chunk_size_must_be_positive():
    with pytest.raises(ParameterError, match="workers = 0"):
        run_sums(spec(), workers=0)
    with pytest.raises(ParameterError, match="chunk_size = 0"):
        run_sums(spec(), chunk_size=0)


# --- statistics against the GW integrals -----------------------------------------------


def test_acceptance_run_agrees_with_gw_within_5_standard_errors():
    """The issue's acceptance run: smooth, A = 1e-9 m², h = 3..-1 (9), 8 realizations, seed 1."""
    run = simulate(SMOOTH, SILICON, np.linspace(3, -1, 9), 1e-9, realizations=8, seed=1)
    table = run.compare()
    rated = table[table["note"] == ""]
    assert len(rated) >= 40
    assert np.all(np.abs(rated["z"]) < 5), rated.loc[np.abs(rated["z"]) >= 5]


@pytest.mark.parametrize("count", ["poisson", "fixed"])
def test_single_patch_standard_error_matches_the_spread_across_patches(count):
    """The summit-level SE of one patch predicts the across-patch std: ratio 1 within
    5 relative SEs of a sample std, 1/√(2(R−1))."""
    R = 300
    run = simulate(SMOOTH, SILICON, [0.0, 1.5], 2e-10, realizations=R, seed=11, count=count)
    for q in ("P", "F", "T", "mu"):
        single_se = run.summary.se[q] * np.sqrt(R)  # SE of one patch
        ratio = run.summary.std[q] / single_se
        np.testing.assert_allclose(ratio, 1.0, atol=5 / np.sqrt(2 * (R - 1)), err_msg=q)


def test_few_contacts_are_flagged_instead_of_given_a_z():
    run = simulate(SMOOTH, SILICON, [4.0, 0.0], 1e-10, realizations=1, seed=3)
    table = run.compare()
    high = table[table["h"] == 4.0]
    assert high["z"].isna().all()
    assert high["note"].str.startswith("few contacts").all()
    assert table[table["h"] == 0.0]["z"].notna().all()


def test_mu_is_undefined_not_zero_for_a_patch_without_contact():
    run = simulate(SMOOTH, SILICON, [6.0], 1e-11, realizations=2, seed=5)
    assert np.all(run.realizations["P"] == 0)
    assert np.all(np.isnan(run.realizations["mu"]))
    assert np.isnan(run.summary.mean["mu"][0])


def test_dask_local_cluster_gives_bit_identical_results(dask_local_client):
    """Two worker processes on a local Dask cluster reproduce the serial run exactly."""
    s = spec(area=2e-8, realizations=2)
    serial = run_sums(s, workers=1)
    assert len(dask_local_client.scheduler_info()["workers"]) == 2
    distributed = run_sums(s, client=dask_local_client, chunk_size=BLOCK)
    np.testing.assert_array_equal(distributed.sums, serial.sums)
    np.testing.assert_array_equal(distributed.n_summits, serial.n_summits)


def test_changing_a_law_compiles_a_new_kernel_instead_of_reusing_a_stale_cache(
    tmp_path, monkeypatch
):
    """The kernel's on-disk cache is stamped with the law sources: a kernel built from a
    law is loaded again while the law is unchanged, and never after it changed."""
    import importlib
    import inspect
    import sys

    from mcsim.engine import kernels
    from mcsim.physics.laws import LawSet, Output, seed

    monkeypatch.setenv("MCSIM_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.syspath_prepend(str(tmp_path))
    laws = tmp_path / "edited_laws.py"
    z, d = np.array([1e-9, 2e-9]), np.array([0.0])
    args = SEED.arguments(SMOOTH, SILICON)
    sums = []
    for edit in ("", "2 * "):
        laws.write_text(inspect.getsource(seed).replace(
            "return K * np.sqrt(R) * d * np.sqrt(d)", f"return {edit}K * np.sqrt(R) * d * np.sqrt(d)"
        ))  # fmt: skip
        sys.modules.pop("edited_laws", None)
        edited = importlib.import_module("edited_laws")
        law = LawSet("edited", "Hertz load, edited", (
            Output("P", "N", edited.hertz_load), Output("F", "N", edited.johnson_adhesion),
            Output("T", "N", edited.savkoor_briggs_friction)))  # fmt: skip
        for loaded in (False, True):  # compiled, then loaded from the cache by a new kernel
            kernels._kernel.cache_clear()
            sums.append(block_sums(z, d, law, args))
            stats = kernels._compiled(law).stats
            counts = sum(stats.cache_hits.values()), sum(stats.cache_misses.values())
            assert counts == ((1, 0) if loaded else (0, 1))
            np.testing.assert_array_equal(sums[-1], sums[-2 if loaded else -1])
    sys.modules.pop("edited_laws")
    kernels._kernel.cache_clear()
    # two summits, the same sums in two codes; ROUNDING_SUM: the same sums taken in two orders
    np.testing.assert_allclose(sums[0], block_sums_numpy(z, d, SEED, args), rtol=ROUNDING_SUM)
    np.testing.assert_allclose(sums[2][0, 1], 2 * sums[0][0, 1], rtol=ROUNDING_SUM)


def test_an_interruption_in_the_middle_of_adding_a_task_never_counts_a_block_twice(monkeypatch):
    """Ctrl-C may land between any two statements: the checkpoint it writes must hold
    whole tasks only, so that resuming from it reproduces the uninterrupted sums."""
    import mcsim.engine.montecarlo as mc

    s = spec(area=3e-8, realizations=1)  # ~8 blocks: several tasks of 2 blocks
    reference = run_sums(s, workers=1, chunk_size=2 * BLOCK)
    real_run_task = mc.run_task
    calls = []

    class InterruptedPartials(list):
        def __iter__(self):  # Ctrl-C after the first block of the task has been added
            yield self[0]
            raise KeyboardInterrupt

    def run_task(spec_, task, keep_heights=False):
        partials, blocks = real_run_task(spec_, task, keep_heights)
        calls.append(task)
        return (InterruptedPartials(partials) if len(calls) == 3 else partials), blocks

    monkeypatch.setattr(mc, "run_task", run_task)
    saved = []
    with pytest.raises(KeyboardInterrupt):
        run_sums(
            s,
            workers=1,
            chunk_size=2 * BLOCK,
            checkpoint=lambda st: saved.append(copy.deepcopy(st)),
        )
    monkeypatch.setattr(mc, "run_task", real_run_task)
    assert saved[-1].done_blocks[0] == 4, "two whole tasks done, the third not at all"
    resumed = run_sums(s, workers=1, chunk_size=2 * BLOCK, resume=saved[-1])
    np.testing.assert_array_equal(resumed.sums, reference.sums)


def test_threads_starting_together_on_a_cold_cache_build_the_kernel_once(monkeypatch, tmp_path):
    """Worker threads of one run that start together wait for one kernel (they used to
    race to write the same generated module: FileNotFoundError after installation)."""
    from concurrent.futures import ThreadPoolExecutor

    from mcsim.engine import kernels

    monkeypatch.setenv("MCSIM_CACHE_DIR", str(tmp_path / "cache"))
    kernels._kernel.cache_clear()
    try:
        with ThreadPoolExecutor(8) as pool:
            built = list(pool.map(lambda _: kernels._compiled(SEED), range(8)))
    finally:
        kernels._kernel.cache_clear()
    assert all(k is built[0] for k in built)


# --- law sets beyond the seed: cycles, attraction, hysteresis (test-local toy law set) ---


@pytest.fixture
def toy(monkeypatch, law_set_cache):
    """The toy law set registered, compiled into a throw-away cache."""
    import dataclasses

    from lawset_toy import TOY, TOY_APPROACH_ONLY

    from mcsim.physics.laws import LAW_SETS

    monkeypatch.setenv("MCSIM_CACHE_DIR", law_set_cache)
    monkeypatch.setitem(LAW_SETS, TOY.name, TOY)
    monkeypatch.setitem(LAW_SETS, TOY_APPROACH_ONLY.name, TOY_APPROACH_ONLY)
    return dataclasses.replace(SILICON, tau=1e8)


def test_a_cycle_has_approach_rows_then_retraction_rows_from_the_lowest_separation(toy):
    s = spec(h=[2.0, 0.5, 1.0], law="toy", cycle=True, material=toy)
    d, d_turn = s.rows()
    sigma = SMOOTH.sigma
    np.testing.assert_array_equal(d, np.array([2.0, 0.5, 1.0, 2.0, 0.5, 1.0]) * sigma)
    np.testing.assert_array_equal(d_turn, np.array([2.0, 0.5, 1.0, 0.5, 0.5, 0.5]) * sigma)
    assert list(s.row_branch) == ["approach"] * 3 + ["retract"] * 3
    assert s.branches == ("approach", "retract")


def test_sampling_reaches_down_to_the_lowest_threshold_of_the_law_set(toy):
    """Summits down to d_min + reach carry force (attraction): they must be sampled;
    the seed keeps sampling above min(h) exactly."""
    s = spec(h=[2.0, 0.5], law="toy", material=toy)
    reach = -2 * 0.3 * SMOOTH.sigma  # the toy's reach, -2c
    assert s.s_min == pytest.approx(0.5 + reach / SMOOTH.sigma, rel=1e-12)
    assert spec(h=[2.0, 0.5]).s_min == 0.5
    ens = run_sums(s, keep_heights=True)
    for z in ens.heights:
        assert z.min() < 0.5 * SMOOTH.sigma - 0.5 * abs(reach)  # attracted, not touching


def test_a_cycle_run_sums_every_row_of_every_sampled_summit(toy):
    from lawset_toy import TOY

    from mcsim.engine.kernels import block_sums_numpy

    s = spec(h=[1.5, 0.5, 0.0], law="toy", cycle=True, material=toy, realizations=2)
    ens = run_sums(s, keep_heights=True)
    d, d_turn = s.rows()
    args, edges = TOY.arguments(SMOOTH, toy), TOY.edges_for(SMOOTH, toy)
    for r, z in enumerate(ens.heights):
        ref = block_sums_numpy(z, d, TOY, args, d_turn=d_turn, edges=edges)
        np.testing.assert_array_equal(ens.sums[r, :, 0], ref[:, 0])
        # the same sums in two orders over ≤ ~17 000 summits (η A = 17e12 m⁻² × 1e-9 m²):
        # n·ε ≤ 4e-12 (Higham Eq. 4.4); absolute per column, scaled by its largest sum, as
        # the toy's attraction makes the load sums signed
        assert_close(ens.sums[r], ref, 1e-11 * np.abs(ref).max(axis=0), "toy sums")


def test_retraction_is_refused_for_a_law_set_without_a_retraction_branch(toy):
    with pytest.raises(ParameterError, match="law set 'toy-approach' has no retraction branch"):
        spec(law="toy-approach", cycle=True, material=toy)
    spec(law="toy-approach", material=toy)  # approach only is fine


def test_a_law_set_needing_a_material_field_refuses_a_material_without_it(toy, monkeypatch):
    import dataclasses

    from lawset_toy import TOY

    from mcsim.physics.laws import LAW_SETS

    monkeypatch.setitem(
        LAW_SETS, "toy-z0", dataclasses.replace(TOY, name="toy-z0", requires=("z0",))
    )
    with pytest.raises(ParameterError, match="needs material field 'z0'"):
        spec(law="toy-z0", material=dataclasses.replace(toy, z0=None))


def _gw_mean(o, args, sigma, d, dt, lo, pts):
    """∫ o(σx − d, σx − d_turn) φ(x) dx from ``lo`` (quadrature, test-only)."""
    from scipy import integrate

    def f(x):
        delta, dmax = np.array([sigma * x - d]), np.array([sigma * x - dt])
        v = o.law(delta, dmax, *args) if o.stateful else o.law(delta, *args)
        return float(v[0]) * stats.norm.pdf(x)

    return integrate.quad(f, lo, 9, points=pts, limit=200, epsabs=0, epsrel=1e-11)[0]


def toy_expected(s, material):
    """GW expectation of every toy quantity at every row, by adaptive quadrature over
    the Gaussian heights (test-only, independent of the engine's sampling and sums)."""
    from lawset_toy import TOY

    sigma, eta, K = s.surface.sigma, s.surface.eta, material.K
    args = TOY.arguments(s.surface, material)
    c = 0.3 * sigma
    d_rows, turn_rows = s.rows()
    out = {q: [] for q in ("contact_fraction", "load", "area", "grip", "friction", "mu")}
    for d, dt in zip(d_rows, turn_rows):
        lo = (d - 2 * c) / sigma
        kinks = sorted({(d + k * c) / sigma for k in (-2, -1, 0, 1, 2, 3)} | {dt / sigma})
        pts = [k for k in kinks if lo < k < 9]
        load, area, grip = (
            _gw_mean(TOY.outputs[i], args[i], sigma, d, dt, lo, pts) for i in range(3)
        )
        out["contact_fraction"].append(stats.norm.sf(max(dt / sigma, (d - c) / sigma)))
        out["load"].append(eta * load / K)
        out["area"].append(eta * area)
        out["grip"].append(eta * grip / K)
        out["friction"].append(eta * material.tau * area / K)
        out["mu"].append(material.tau * area / load if load > 0 else np.nan)
    return {q: np.array(v) for q, v in out.items()}


def test_monte_carlo_agrees_with_gw_quadrature_on_both_branches_for_a_law_set_with_hysteresis(toy):
    """|z| < 5 for every quantity and row with plentiful contacts, approach and retraction."""
    s = spec(h=[2.0, 1.0, 0.3, -0.2], law="toy", cycle=True, material=toy, area=2e-9,
             realizations=4, entropy=20261123)  # fmt: skip
    from mcsim.store.results import assemble

    run = assemble(run_sums(s))
    expected = toy_expected(s, toy)
    assert set(run.summary.mean) == set(expected)
    checked = 0
    for q, value in expected.items():
        ok = (run.summary.expected_contacts >= 100) & np.isfinite(value)
        z = (run.summary.mean[q][ok] - value[ok]) / run.summary.se[q][ok]
        assert np.all(np.abs(z) < 5), (q, z)
        checked += ok.sum()
    assert checked > 30
    # the retraction branch differs from the approach (hysteresis): both were checked
    M = s.h.size
    assert not np.allclose(expected["load"][:M], expected["load"][M:])


def test_pull_off_of_each_patch_is_its_most_tensile_retraction_load(toy):
    from lawset_toy import TOY

    from mcsim.engine.kernels import sum_columns
    from mcsim.store.results import assemble

    # 1700 summits a patch: the exact pull-off evaluates every summit at every edge of every
    # summit (quadratic in the count), which a 17 000-summit patch makes slow
    s = spec(h=[3.0, 0.0, -0.5, 2.0], law="toy", cycle=True, material=toy, area=1e-10)
    run = assemble(run_sums(s))
    po = run.pull_off()
    load = run.sums[:, 4:, sum_columns(TOY).index("load")]
    np.testing.assert_array_equal(po.grid_force, np.maximum(-load.min(axis=1), 0))
    np.testing.assert_array_equal(po.grid_h, s.h[load.argmin(axis=1)])
    assert np.all(po.grid_force > 0)
    # the exact minimum of each patch's own curve (engine.pads.curves) is at least as tensile
    assert np.all(po.force >= po.grid_force)
    np.testing.assert_allclose(po.normalised, po.force / (s.area * toy.K), rtol=1e-15)
    assert po.resolution == 2.0  # the widest step of the grid -0.5, 0, 2, 3
    with pytest.raises(ParameterError, match="pull-off needs a cycle run"):
        assemble(run_sums(spec(h=[1.0, 0.0]))).pull_off()


def test_mu_of_bowden_tabor_friction_is_undefined_where_the_load_is_tensile(toy):
    from mcsim.store.results import assemble

    s = spec(h=[1.2, -0.5], law="toy", material=toy, area=2e-9)
    run = assemble(run_sums(s))
    load, mu = run.summary.mean["load"], run.summary.mean["mu"]
    assert load[0] < 0 and np.isnan(mu[0])  # attraction dominates far out
    assert load[1] > 0 and mu[1] > 0
    table = run.compare()
    row = table[(table.quantity == "mu") & (table.h == 1.2)].iloc[0]
    assert "undefined" in row.note and np.isnan(row.z)


def test_the_seed_has_no_hysteresis_its_retraction_rows_equal_its_approach_rows_bit_for_bit():
    cycle = run_sums(spec(cycle=True))
    approach = run_sums(spec())
    M = approach.sums.shape[1]
    np.testing.assert_array_equal(cycle.sums[:, :M], approach.sums)
    np.testing.assert_array_equal(cycle.sums[:, M:], approach.sums)


@pytest.mark.parametrize("name", LAW_SET_NAMES)  # named: a dropped law set fails
def test_monte_carlo_agrees_with_the_analytic_curves_on_both_branches_for_every_law_set(name):
    """|z| < 5 against mcsim.gw_curves(branch=..., turn=...) for every quantity and row with
    plentiful contacts; a cycle for every law set with a retraction branch."""
    import inspect

    from mcsim.physics.analytic import gw_curves

    if name != "seed" and "branch" not in inspect.signature(gw_curves).parameters:
        pytest.skip("needs the analytic curves of law sets with edges and branches (gw_curves)")
    law = LAW_SETS[name]
    material = dataclasses.replace(SILICON, z0=0.3e-9, tau=1e8)
    run = simulate(SMOOTH, material, [2.5, 1.5, 0.5, 0.0, -0.5], 2e-9, realizations=4, seed=11,
                   law=name, cycle=law.retract)  # fmt: skip
    table = run.compare()
    finite = table[np.isfinite(table.z)]
    assert len(finite) >= 20
    assert np.all(np.abs(finite.z) < 5), finite[np.abs(finite.z) >= 5]
    assert set(finite.branch) == set(run.spec.branches)


@pytest.fixture(scope="module")
def toy_cycles_over_patches(law_set_cache):
    """The toy cycle (rows: h = 1 on approach, 0; retraction h = 1, 0, after the turn
    at 0) over N_PATCHES independent patches (the realizations of one run, each summarised
    on its own), and its quadrature expectations. Each z-score test below picks its
    quantity and row out of these same patches."""
    from lawset_toy import TOY
    from test_zscore_calibration import N_PATCHES, one_patch

    from mcsim.engine.statistics import summarize
    from mcsim.physics.laws import LAW_SETS

    material = dataclasses.replace(SILICON, tau=1e8)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("MCSIM_CACHE_DIR", law_set_cache)
        mp.setitem(LAW_SETS, TOY.name, TOY)
        base = spec(h=[1.0, 0.0], law="toy", cycle=True, material=material, area=2e-10,
                    realizations=N_PATCHES, entropy=7)  # fmt: skip
        ens = run_sums(base, workers=1)
        summaries = [summarize(one_patch(ens, r)) for r in range(N_PATCHES)]
        return toy_expected(base, material), summaries


@pytest.mark.parametrize(
    ("quantity", "row"),
    [("load", 0), ("load", 2), ("area", 2), ("contact_fraction", 2), ("friction", 0)],
)
def test_z_scores_of_a_law_set_with_hysteresis_over_independent_patches_are_calibrated(
    toy_cycles_over_patches, quantity, row
):
    """As for the seed (tests/engine/test_zscore_calibration.py), on both branches: one z per
    patch against the quadrature; mean 0 and mean square 1 within five of their own
    standard errors, a bound that SEs 15 % small or 20 % large fail."""
    from test_zscore_calibration import mean_square_is_one

    expected, summaries = toy_cycles_over_patches
    zs = np.array(
        [(s.mean[quantity][row] - expected[quantity][row]) / s.se[quantity][row] for s in summaries]
    )
    assert np.all(np.isfinite(zs))
    assert abs(zs.mean()) < 5 * zs.std(ddof=1) / np.sqrt(zs.size)
    assert mean_square_is_one(zs), f"mean z² = {np.mean(zs**2):.3f}"
    assert not mean_square_is_one(zs / 0.85) and not mean_square_is_one(zs / 1.2)


def test_a_spec_unpickled_again_in_one_process_is_the_same_object():
    # A worker process sent one chunk of pads after another holds one spec, which the pads'
    # caches find by identity (an equal but distinct one compares every field at each lookup).
    import pickle

    spec = MonteCarloSpec(SURFACES["smooth"], MATERIALS["silicon"], np.linspace(-1.0, 3.0, 5),
                          1e-10, 2, 7)  # fmt: skip
    first, again = pickle.loads(pickle.dumps(spec)), pickle.loads(pickle.dumps(spec))
    assert first is again and first == spec and first is not spec
    other = pickle.loads(pickle.dumps(dataclasses.replace(spec, entropy=8)))
    assert other is not first and other != first and copy.deepcopy(spec) == spec


def test_a_spec_is_its_own_copy_of_h_and_hashes_alike_in_another_process(tmp_path):
    # The spec's hash is computed once (the pads' caches look it up many times), so its h
    # is its own and read-only; pickled to another process (Dask's workers hash strings
    # with another seed) it hashes as an equal spec built there.
    import os
    import pickle
    import subprocess
    import sys

    h = np.linspace(-1.0, 3.0, 5)
    spec = MonteCarloSpec(SURFACES["smooth"], MATERIALS["silicon"], h, 1e-10, 2, 7)
    h[0] = 99.0
    assert spec.h[0] == -1.0 and not spec.h.flags.writeable
    path = tmp_path / "spec.pickle"
    hash(spec)  # as the caches do, before it is sent
    path.write_bytes(pickle.dumps(spec))
    code = (
        "import pickle, sys, numpy as np\n"
        "from mcsim.engine.spec import MonteCarloSpec\n"
        "from mcsim.model.presets import MATERIALS, SURFACES\n"
        "old = pickle.loads(open(sys.argv[1], 'rb').read())\n"
        "new = MonteCarloSpec(SURFACES['smooth'], MATERIALS['silicon'],"
        " np.linspace(-1.0, 3.0, 5), 1e-10, 2, 7)\n"
        "assert old == new and hash(old) == hash(new) and len({old, new}) == 1\n"
    )
    env = {**os.environ, "PYTHONHASHSEED": "12345"}
    done = subprocess.run([sys.executable, "-c", code, str(path)], env=env, capture_output=True)
    assert done.returncode == 0, done.stderr.decode()
