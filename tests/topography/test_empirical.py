"""Empirical (histogram) height distributions: exact moments, sampling, GW integrals, TOML."""

import numpy as np
import pytest
from scipy import integrate, special, stats
from tolerances import QUAD_RTOL, ROUNDING_FEW, ROUNDING_FORMULA

from mcsim import Surface, gw_curves
from mcsim.model.distributions import HeightDistribution
from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import get_law_set
from mcsim.store.config import load_surface, surface_from_table
from mcsim.topography.empirical import Empirical

SILICON = MATERIALS["silicon"]


def skewed() -> Empirical:
    """An irregular, skewed histogram with uneven bins and an empty bin inside (nm)."""
    edges = np.array([-3.0, -2.0, -1.2, -0.5, 0.0, 0.4, 1.0, 1.5, 2.5, 4.0]) * 1e-9
    counts = np.array([2.0, 10, 30, 55, 60, 0, 25, 12, 3])
    return Empirical.from_histogram(edges, counts, source="skewed")


def gaussian_histogram(width: float, limit: float = 10.0) -> tuple[np.ndarray, np.ndarray]:
    """Bins of ``width`` on [−limit, limit] with exact standard-normal probabilities."""
    edges = np.linspace(-limit, limit, round(2 * limit / width) + 1)
    return edges, np.diff(special.ndtr(edges))


def test_empirical_implements_the_height_distribution_protocol():
    assert isinstance(skewed(), HeightDistribution)


def test_moments_are_those_of_the_piecewise_uniform_density():
    """Two bins [0,1], [1,3] with counts 1, 1: mean 1.25, E[z²] = ½·⅓ + ½·(1+3+9)/3 = 7/3."""
    emp = Empirical.from_histogram([0.0, 1.0, 3.0], [1, 1])
    assert emp.mean == pytest.approx(1.25, rel=ROUNDING_FEW)
    assert emp.sigma == pytest.approx(np.sqrt(7 / 3 - 1.25**2), rel=ROUNDING_FEW)


def test_standardized_density_has_zero_mean_unit_variance():
    emp = skewed()
    m1 = integrate.quad(lambda s: s * emp.pdf(s), -10, 10, points=emp.edges, limit=200)[0]
    m2 = integrate.quad(lambda s: s * s * emp.pdf(s), -10, 10, points=emp.edges, limit=200)[0]
    # in units of σ, absolute (the mean is zero): quad splits at the bin edges, where the
    # integrands are polynomials of degree ≤ 2: exact per panel but for rounding
    np.testing.assert_allclose([m1, m2], [0.0, 1.0], atol=1e-12)


def test_densities_and_counts_give_the_same_distribution():
    edges = np.array([0.0, 1.0, 3.0, 4.0])
    counts = np.array([2.0, 4.0, 1.0])
    a = Empirical.from_histogram(edges, counts)
    b = Empirical.from_histogram(edges, counts / np.diff(edges), density=True)
    np.testing.assert_allclose(a.densities, b.densities, rtol=ROUNDING_FORMULA)


def test_empty_outer_bins_are_dropped():
    emp = Empirical.from_histogram([0.0, 1, 2, 3, 4], [0, 1, 1, 0])
    assert emp.densities.size == 2


def test_sf_is_one_minus_integrated_pdf():
    emp = skewed()
    s = np.linspace(-4, 4, 57)
    expected = [integrate.quad(emp.pdf, x, 10, points=emp.edges, limit=200)[0] for x in s]
    # probabilities in [0, 1], absolute: quad of a piecewise-constant pdf split at its
    # edges: exact per panel but for rounding (measured 2.2e-16)
    np.testing.assert_allclose(emp.sf(s), expected, atol=1e-13)


def test_sf_is_one_below_and_zero_above_the_support():
    emp = skewed()
    np.testing.assert_array_equal(emp.sf([emp.edges[0] - 1, emp.edges[-1] + 1]), [1.0, 0.0])


def test_samples_above_threshold_follow_truncated_sf():
    """KS test of 20 000 draws against the exact truncated sf; p > 1e-3 fails 1 in 1000 seeds."""
    emp = skewed()
    s_min = 0.2
    draws = emp.sample_above(20_000, s_min, np.random.default_rng(1))
    assert draws.min() > s_min
    result = stats.kstest(draws, lambda x: 1 - emp.sf(x) / emp.sf(s_min) + 0 * x)
    assert result.pvalue > 1e-3


def test_samples_avoid_bins_with_zero_probability():
    emp = skewed()
    draws = emp.sample_above(50_000, -np.inf, np.random.default_rng(2))
    empty = np.flatnonzero(emp.densities == 0)[0]
    assert not np.any((draws > emp.edges[empty]) & (draws < emp.edges[empty + 1]))


def test_sampling_above_the_support_raises():
    emp = skewed()
    with pytest.raises(MCSimError, match="no summit heights above s = 10"):
        emp.sample_above(5, 10.0, np.random.default_rng(0))


def _brute_force(emp: Empirical, g, h: float) -> np.ndarray:
    """Adaptive quadrature bin by bin in u = √(s − h), tolerance 1e-13 (independent reference)."""
    total = 0.0
    for a, b, f in zip(emp.edges[:-1], emp.edges[1:], emp.densities):
        if b <= h or f == 0:
            continue
        lo, hi = np.sqrt(max(a - h, 0.0)), np.sqrt(b - h)
        total = total + np.array(
            [
                integrate.quad(lambda u, i=i, f=f: g(np.array(u * u))[i] * 2 * u * f, lo, hi,
                               epsabs=0, epsrel=1e-13, limit=200)[0]
                for i in range(3)
            ]
        )  # fmt: skip
    return total


@pytest.mark.parametrize("preset", ["rough", "super-smooth"])
def test_gw_integrals_match_brute_force_quadrature_to_1e10(preset):
    emp = skewed()
    surface = Surface(sigma=SURFACES[preset].sigma, R=SURFACES[preset].R, eta=1e12, heights=emp)
    laws = get_law_set("seed")
    args = laws.arguments(surface, SILICON)

    def g(delta):
        return np.stack([f(surface.sigma * delta, *a) for f, a in zip(laws.laws, args)])

    h = np.array([-5.0, -1.3, -0.5, 0.0, 0.37, 1.0, 2.0, 3.5])
    scale, integral = emp.gw_integrals(g, h)
    for i, hi in enumerate(h):
        np.testing.assert_allclose(
            scale[i] * integral[:, i], _brute_force(emp, g, hi), rtol=QUAD_RTOL, err_msg=f"h={hi}"
        )


def test_a_band_skips_the_bins_above_it_and_gets_the_same_bits():
    # A band's integrand is zero above its top (Band.gw_integrals); told so by ``upper``,
    # the histogram skips the pieces that start above it, which added exactly zero.
    from mcsim.model.distributions import Band

    band = Band(skewed(), -0.4, 0.9)
    h = np.array([-5.0, -1.3, -0.5, 0.0, 0.37, 0.9, 2.0])
    breaks = np.stack([np.zeros_like(h), np.full_like(h, 0.3), 1.1 - h], axis=1)
    seen = []

    def g(delta, rows):
        seen.append(delta.size)
        return np.stack([delta**1.5, np.sqrt(1 + delta)])

    _, banded = band.gw_integrals(g, h, breaks)
    skipped = seen[0]
    cut = 0.9 - h

    def zero_above(delta, rows):
        seen.append(delta.size)
        return np.where(delta <= cut[rows][:, None], g(delta, rows), 0.0)

    columns = np.column_stack([np.maximum(breaks[:, 0], -0.4 - h), breaks[:, 1:], cut])
    seen.clear()
    _, whole = skewed().gw_integrals(zero_above, h, columns)  # every piece evaluated
    assert np.array_equal(banded, whole)
    assert skipped < seen[0]  # and it evaluated fewer quadrature points


def test_gw_integrals_vanish_above_the_support():
    _, integral = skewed().gw_integrals(lambda d: np.stack([d, d]), np.array([3.0, 10.0]))
    assert integral[:, 1].tolist() == [0.0, 0.0]


def test_binned_exact_gaussian_matches_gaussian_curves_within_binning_bound():
    """Bins of width w from the exact normal cdf: p̂ is p averaged over each bin.

    With G(z) = g(z − d)·1{z > d} (non-decreasing for the seed laws),
    E = ∫ G (p̂ − p) = Σ_k ∫_k (G − G(c_k))(p̂ − p), and |p̂ − p| ≤ w sup_k |p'|, so

        |E| ≤ Σ_k w² sup_k|p'| (G(b_k) − G(a_k)),   p'(z) = −z φ(z),

    in units of σ. Truncation at ±10σ adds < 1e-20. Heights are compared at the same
    physical separation d = h σ (the empirical σ carries Sheppard's w²/12).
    """
    width = 0.05
    edges, probabilities = gaussian_histogram(width)
    sigma0 = SURFACES["rough"].sigma
    emp = Empirical.from_histogram(edges * sigma0, probabilities)
    gauss = SURFACES["rough"]
    surface = Surface(sigma=emp.sigma, R=gauss.R, eta=gauss.eta, heights=emp)
    h = np.array([-2.0, -1.0, 0.0, 1.0, 2.0, 3.0])
    ref = gw_curves(gauss, SILICON, h)
    got = gw_curves(surface, SILICON, (h * sigma0 - emp.mean) / emp.sigma)

    a, b = edges[:-1], edges[1:]
    peak = np.maximum(np.abs(a) * stats.norm.pdf(a), np.abs(b) * stats.norm.pdf(b))
    peak = np.where((a < 1) & (b > -1) & ((a < -1) | (b > 1)), stats.norm.pdf(1.0), peak)
    laws = get_law_set("seed")
    for i, hi in enumerate(h):

        def G(z, hi=hi):
            delta = sigma0 * np.clip(z - hi, 0, None)
            return (z > hi) * laws.forces(delta, gauss, SILICON) * gauss.eta / SILICON.K

        bound = np.sum(width**2 * peak * (G(b) - G(a)), axis=-1)
        for q, k in (("P", 0), ("F", 1), ("T", 2)):
            error = abs(getattr(got, q)[i] - getattr(ref, q)[i])
            assert error <= bound[k], f"{q} at h={hi}: error {error:.3g} > bound {bound[k]:.3g}"
            assert bound[k] < 5e-2 * getattr(ref, q)[i], "bound too loose to mean anything"


def test_surface_with_empirical_heights_gives_finite_curves():
    surface = Surface(sigma=1e-9, R=1e-6, eta=1e13, heights=skewed())
    curves = gw_curves(surface, SILICON, np.linspace(-3, 3, 13))
    assert np.all(np.isfinite(curves.P)) and np.all(curves.P >= 0)


def test_dict_round_trip_is_exact():
    emp = skewed()
    again = Empirical.from_dict(emp.to_dict())
    assert again == emp and hash(again) == hash(emp) and again.source == "skewed"


def test_from_dict_refuses_other_schemas():
    with pytest.raises(MCSimError, match="not a stored empirical distribution"):
        Empirical.from_dict({"schema": "other"})


def test_equal_histograms_are_equal_and_hash_alike():
    assert skewed() == skewed() and hash(skewed()) == hash(skewed())


def test_different_histograms_are_not_equal():
    assert skewed() != Empirical.from_histogram([0.0, 1, 2], [1, 2])


def test_empirical_is_immutable():
    emp = skewed()
    with pytest.raises(AttributeError, match="immutable"):
        emp.sigma = 2.0
    with pytest.raises(ValueError, match="read-only"):
        emp.densities[0] = 1.0


def test_from_samples_recovers_sample_moments():
    """Fine bins: Sheppard's correction w²/12 is below 1e-4 of the variance here."""
    z = np.random.default_rng(3).normal(5e-9, 2e-9, 100_000)
    emp = Empirical.from_samples(z, bins=400)
    # w²/12 (Sheppard) below 1e-4 of the variance, 1e-3 of σ is 20× it (measured 4e-5)
    assert emp.sigma == pytest.approx(z.std(), rel=1e-3)
    # absolute (a mean can be zero), 5e-4 σ: the binned mean differs from the sample mean by
    # the mean offset within 4.5e-11 m bins, measured 1e-14 m
    assert emp.mean == pytest.approx(z.mean(), abs=1e-12)


@pytest.mark.parametrize(
    ("edges", "weights", "message"),
    [
        ([0.0, 1.0], [1.0], "at least two bins"),
        ([0.0, 1.0, 2.0, 3.0], [1.0, 1.0], "needs 3 edges, got 4"),
        ([0.0, 2.0, 1.0], [1.0, 1.0], "strictly increasing"),
        ([0.0, 1.0, 2.0], [1.0, -1.0], "non-negative"),
        ([0.0, 1.0, 2.0], [0.0, 0.0], "all zero"),
        ([0.0, 1.0, 2.0], [np.nan, 1.0], "finite"),
        ([0.0, 1.0, 2.0, 3.0], [0.0, 5.0, 0.0], "single occupied bin"),
    ],
)
def test_bad_histograms_are_refused(edges, weights, message):
    with pytest.raises(ParameterError, match=message):
        Empirical.from_histogram(edges, weights)


def test_constructor_refuses_unstandardized_densities():
    with pytest.raises(ParameterError, match="not a standardized distribution"):
        Empirical([0.0, 1.0, 2.0], [0.5, 0.5], sigma=1e-9)


def test_from_samples_refuses_nan():
    with pytest.raises(ParameterError, match="must be finite"):
        Empirical.from_samples([1.0, np.nan, 2.0])


# -- TOML surfaces with measured heights ---------------------------------------------


def test_toml_heights_gaussian_is_the_default_surface():
    table = {"sigma": "1 nm", "R": "1 um", "eta": "10 um^-2"}
    assert surface_from_table({**table, "heights": "gaussian"}) == surface_from_table(table)


def test_toml_inline_histogram_defaults_sigma_to_its_std():
    table = {
        "R": "1 um",
        "eta": "10 um^-2",
        "heights": {"edges": [0, 1, 3], "counts": [1, 1], "unit": "nm"},
    }
    surface = surface_from_table(table)
    assert surface.sigma == pytest.approx(np.sqrt(7 / 3 - 1.25**2) * 1e-9, rel=ROUNDING_FORMULA)
    assert isinstance(surface.heights, Empirical)


def test_toml_histogram_file_is_relative_to_the_toml_folder(tmp_path):
    (tmp_path / "hist.csv").write_text("z [nm], count\n-1, 1\n0, 3\n1, 1\n")
    table = {"sigma": "2 nm", "R": "1 um", "eta": "10 um^-2", "heights": "hist.csv"}
    surface = surface_from_table(table, base_dir=tmp_path)
    assert surface.sigma == 2e-9 and surface.heights.densities.size == 3


def test_toml_file_with_heights_table_loads(tmp_path):
    (tmp_path / "h.txt").write_text("-1 1\n0 3\n1 1\n")
    path = tmp_path / "s.toml"
    path.write_text(
        f'[surface]\nR = "1 um"\neta = "10 um^-2"\n[surface.heights]\nfile = "{tmp_path / "h.txt"}"\nunit = "nm"\n'
    )
    assert isinstance(load_surface(path).heights, Empirical)


def test_toml_missing_histogram_file_names_the_table():
    with pytest.raises(ParameterError, match=r"^surface: heights: .*nope.csv: no such file"):
        surface_from_table({"R": 1e-6, "eta": 1e13, "heights": "nope.csv"})


def test_toml_heights_unknown_key_is_refused():
    with pytest.raises(ParameterError, match="heights: unknown key"):
        surface_from_table({"R": 1e-6, "eta": 1e13, "heights": {"edge": [0, 1]}})


def test_toml_heights_need_counts_or_densities():
    with pytest.raises(ParameterError, match="edges with one of counts or densities"):
        surface_from_table({"R": 1e-6, "eta": 1e13, "heights": {"edges": [0, 1, 2]}})


def test_toml_heights_of_wrong_type_is_refused():
    with pytest.raises(ParameterError, match="heights must be 'gaussian'"):
        surface_from_table({"R": 1e-6, "eta": 1e13, "heights": 3})


def test_toml_gaussian_surface_still_requires_sigma():
    with pytest.raises(ParameterError, match="missing key 'sigma'"):
        surface_from_table({"R": 1e-6, "eta": 1e13})


def test_gw_integrals_agree_with_monte_carlo_sums():
    """E[g(S−h); S>h] = sf(h)·E[g | S>h]; 100 000 draws, |z| < 4 (fails 6e-5 of seeds)."""
    emp, h = skewed(), 0.37
    rng = np.random.default_rng(4)
    draws = emp.sample_above(100_000, h, rng)
    values = np.stack([(draws - h) ** 1.5, np.sqrt(1 + (draws - h) ** 1.5)])
    scale, integral = emp.gw_integrals(lambda d: np.stack([d**1.5, np.sqrt(1 + d**1.5)]), [h])
    mc = emp.sf(h) * values.mean(axis=1)
    se = emp.sf(h) * values.std(axis=1) / np.sqrt(draws.size)
    assert np.all(np.abs(mc - scale * integral[:, 0]) < 4 * se)
