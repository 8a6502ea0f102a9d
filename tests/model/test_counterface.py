"""Two rough surfaces (mcsim.model.counterface; docs/physics.md, 'Two rough surfaces'):
the combination rule's exact limits, Table 1, and synthesised maps."""

import math

import numpy as np
import pytest
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

import mcsim
from mcsim.model.counterface import (
    combine,
    combined_rms,
    difference_moment,
    spectral_moments,
    summits_of,
)
from mcsim.model.distributions import Gaussian
from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.params import RadiusByHeight, Surface, combine_surfaces
from mcsim.model.presets import PAPER_PAIRS, SURFACES
from mcsim.physics.gapheights import nayak_heights
from mcsim.topography import summits
from mcsim.topography.empirical import Empirical
from mcsim.topography.synthesis import synthesize, wavevectors

SMOOTH, ROUGH = SURFACES["smooth"], SURFACES["rough"]
A, B = SURFACES["deposited-polysilicon"], SURFACES["typical-substrate"]


def test_combine_is_the_public_api():
    assert mcsim.combine is combine


def test_no_counter_surface_returns_the_surface_itself():
    assert combine(SMOOTH) is SMOOTH
    assert combine(SMOOTH, None, 0.0) is SMOOTH
    assert combine(SMOOTH, "flat", 0) is SMOOTH
    assert combine("smooth") is SMOOTH


def test_two_identical_independent_surfaces_give_root_two_rq():
    c = combine(SMOOTH, SMOOTH, 0.0)
    rq = nayak_heights(SMOOTH.sigma, SMOOTH.R, SMOOTH.eta).rq
    assert c.rq == pytest.approx(math.sqrt(2) * rq, rel=ROUNDING_FORMULA)
    # every moment doubles: sigma_s x sqrt 2, R / sqrt 2, the same eta, alpha unchanged
    assert c.sigma == pytest.approx(math.sqrt(2) * SMOOTH.sigma, rel=ROUNDING_FORMULA)
    assert c.R == pytest.approx(SMOOTH.R / math.sqrt(2), rel=ROUNDING_FORMULA)
    assert c.eta == pytest.approx(SMOOTH.eta, rel=ROUNDING_FORMULA)
    offset = nayak_heights(SMOOTH.sigma, SMOOTH.R, SMOOTH.eta).summit_offset
    assert c.summit_offset == pytest.approx(math.sqrt(2) * offset, rel=ROUNDING_FORMULA)


def test_anticorrelated_surfaces_add_their_rms():
    c = combine(A, B, -1.0)
    rq_a, rq_b = (nayak_heights(s.sigma, s.R, s.eta).rq for s in (A, B))
    assert c.rq == pytest.approx(rq_a + rq_b, rel=ROUNDING_FORMULA)
    assert combined_rms(3.0, 4.0, -1.0) == pytest.approx(7.0, rel=ROUNDING_FEW)
    assert combined_rms(3.0, 4.0, 0.0) == pytest.approx(5.0, rel=ROUNDING_FEW)
    assert combined_rms(3.0, 4.0, 1.0) == pytest.approx(1.0, rel=ROUNDING_FORMULA)


@pytest.mark.parametrize("rho", [-1.0, -0.4, 0.0, 0.3, 0.9])
def test_the_order_of_the_two_surfaces_does_not_matter(rho):
    one, two = combine(A, B, rho), combine(B, A, rho)
    for name in ("sigma", "R", "eta", "rq", "summit_offset"):
        assert getattr(one, name) == pytest.approx(getattr(two, name), rel=ROUNDING_FEW), name


def test_the_moments_combine_as_the_heights():
    rho = 0.35
    one, two = spectral_moments(A.sigma, A.R, A.eta), spectral_moments(B.sigma, B.R, B.eta)
    c = combine(A, B, rho)
    want = summits_of(*(a + b - 2 * rho * math.sqrt(a * b) for a, b in zip(one, two)))
    for name in ("sigma", "R", "eta", "rq", "summit_offset"):
        assert getattr(c, name) == pytest.approx(getattr(want, name), rel=ROUNDING_FEW), name


def test_rq_falls_as_the_correlation_rises():
    rq = [combine(A, B, rho).rq for rho in np.linspace(-1, 0.99, 12)]
    assert np.all(np.diff(rq) < 0)


def test_spectral_moments_and_summits_invert_each_other():
    for s in (SMOOTH, ROUGH, A, B):
        back = summits_of(*spectral_moments(s.sigma, s.R, s.eta))
        assert back.sigma == pytest.approx(s.sigma, rel=ROUNDING_FORMULA)
        assert back.R == pytest.approx(s.R, rel=ROUNDING_FORMULA)
        assert back.eta == pytest.approx(s.eta, rel=ROUNDING_FORMULA)
        estimate = nayak_heights(s.sigma, s.R, s.eta)
        assert (back.rq, back.summit_offset, back.alpha) == tuple(estimate)


@pytest.mark.parametrize("combined, pair", PAPER_PAIRS.items())
def test_independent_pairs_of_table_1_give_its_combined_rows(combined, pair):
    """Table 1's combined sigma, R and eta, within the rounding of its 2-3 digit values:
    1.0 nm and 0.3 nm (two digits) are up to 5 % apart from the values they round, and
    sqrt(2) x 1.0 = 1.414 against the table's 1.4 is 1.0 %."""
    c, table = combine(*pair, 0.0), SURFACES[combined]
    for name in ("sigma", "R", "eta"):
        assert getattr(c, name) == pytest.approx(getattr(table, name), rel=0.011), name
    # the curvatures add at rho = 0: the paper's rule for R, which combine_surfaces applies
    first, second = (SURFACES[p] for p in pair)
    rule = combine_surfaces(first, second, eta=c.eta)
    assert c.R == pytest.approx(rule.R, rel=ROUNDING_FORMULA)


def test_a_perfect_replica_is_refused_as_flat():
    with pytest.raises(ParameterError, match="the combined surface is flat"):
        combine(SMOOTH, SMOOTH, 1.0)
    with pytest.raises(ParameterError, match="the combined surface is flat"):
        combine(SMOOTH, Surface(sigma=SMOOTH.sigma, R=SMOOTH.R, eta=SMOOTH.eta), 1.0)
    # surfaces that differ leave a gap even at rho = 1
    assert combine(A, B, 1.0).rq > 0


def test_combined_moments_without_summits_are_refused():
    # the same slopes and curvatures, other heights: at rho = 1 they cancel
    other = Surface(sigma=2 * SMOOTH.sigma, R=SMOOTH.R, eta=SMOOTH.eta)
    with pytest.raises(ParameterError, match="slopes and curvatures cancel"):
        combine(SMOOTH, other, 1.0)


@pytest.mark.parametrize("rho", [1.5, -1.0001, math.nan, math.inf, "x", True, None])
def test_a_correlation_outside_minus_one_to_one_is_refused(rho):
    with pytest.raises(MCSimError, match=r"^correlation"):
        combine(SMOOTH, ROUGH, rho)


def test_a_correlation_needs_a_counter_surface():
    with pytest.raises(ParameterError, match=r"correlation = 0\.2 needs a counter-surface"):
        combine(SMOOTH, None, 0.2)


def test_an_unknown_counter_surface_is_refused():
    with pytest.raises(ParameterError, match="counter-surface must be a Surface or a preset"):
        combine(SMOOTH, "smoth", 0.0)


@pytest.mark.parametrize(
    "change, why",
    [
        ({"heights": Empirical.from_histogram([-2, 0, 2], [1, 1])}, "measured summit heights"),
        ({"radius_by_height": RadiusByHeight((-1.0, 0.0, 1.0), (1.2, 0.8))}, "radius by height"),
        ({"rq": 1.6e-9}, "gives rq"),
        ({"summit_offset": 1.5e-9}, "gives summit_offset"),
        ({"map_heights": Gaussian()}, "gives map_heights"),
    ],
)
def test_measured_surfaces_are_refused_with_what_is_supported(change, why):
    import dataclasses

    measured = dataclasses.replace(SMOOTH, name="measured", **change)
    for first, second in ((measured, ROUGH), (ROUGH, measured)):
        with pytest.raises(ParameterError, match=why) as err:
            combine(first, second, 0.0)
        assert "only two Gaussian GW surfaces" in str(err.value)
        assert "--counter-surface MAP2" in str(err.value)


def test_difference_moment_never_goes_negative():
    assert difference_moment(2.0, 2.0, 1.0) == 0.0
    assert difference_moment(1.0, 4.0, 1.0) == pytest.approx(1.0, rel=ROUNDING_FEW)


# --- synthesised maps ------------------------------------------------------------------

PIXEL = 10e-9
SHAPE = (256, 256)


def _self_affine(c0, q_r=2e7, hurst=0.8):
    def psd(q):
        return c0 * np.minimum(1.0, (np.asarray(q) / q_r) ** (-2 * (1 + hurst)))

    return psd


def _weights(shape, dx):
    """Transfer functions |D(q)|^2, averaged over x and y, of the finite differences of
    summits.spectral_moments: 1 (heights), forward differences (slopes), central second
    differences (curvatures)."""
    q = wavevectors(shape, dx)  # |q|; the components from the FFT frequencies
    ny, nx = shape
    qy, qx = np.meshgrid(
        2 * np.pi * np.fft.fftfreq(ny, dx), 2 * np.pi * np.fft.fftfreq(nx, dx), indexing="ij"
    )
    first = [(2 * np.sin(k * dx / 2) / dx) ** 2 for k in (qx, qy)]
    second = [(4 * np.sin(k * dx / 2) ** 2 / dx**2) ** 2 for k in (qx, qy)]
    return q, (np.ones(shape), sum(first) / 2, sum(second) / 2)


def test_two_independent_synthesised_maps_combine_by_the_rule():
    """The difference of two independent periodic Gaussian maps (fixed seed): each spectral
    moment of the difference is the sum of the two maps' moments, m_n(a - b) = m_n(a) + m_n(b)
    - 2 X_n, up to the sample cross term X_n = <D a . D b> of zero mean and variance
    sum_q W_q^2 P_a(q) P_b(q) (P = C/A, the power of one mode; W the difference's transfer
    function): within 4 standard errors. The rms of the difference is then sqrt(rq_a^2 + rq_b^2)."""
    psd_a, psd_b = _self_affine(1e-34), _self_affine(0.4e-34, hurst=0.6)
    a = synthesize(SHAPE, PIXEL, psd_a, rng=np.random.SeedSequence(2024))[0]
    b = synthesize(SHAPE, PIXEL, psd_b, rng=np.random.SeedSequence(2025))[0]
    area = SHAPE[0] * SHAPE[1] * PIXEL**2
    q, weights = _weights(SHAPE, PIXEL)
    power = [np.where(q > 0, psd(np.where(q > 0, q, 1.0)), 0.0) / area for psd in (psd_a, psd_b)]
    ma, mb, md = (summits.spectral_moments(z, PIXEL, PIXEL, periodic=True) for z in (a, b, a - b))
    for n, w in zip(("m0", "m2", "m4"), weights):
        se = math.sqrt(float(np.sum(w**2 * power[0] * power[1])))
        cross = (getattr(ma, n) + getattr(mb, n) - getattr(md, n)) / 2
        assert abs(cross) < 4 * se, (n, cross / se)
        assert se < 0.05 * math.sqrt(getattr(ma, n) * getattr(mb, n))  # the test has power
    rq_a, rq_b = math.sqrt(ma.m0), math.sqrt(mb.m0)
    se_rms = math.sqrt(float(np.sum(power[0] * power[1]))) / math.hypot(rq_a, rq_b)
    assert np.sqrt(np.mean((a - b) ** 2)) == pytest.approx(math.hypot(rq_a, rq_b), abs=4 * se_rms)
    # combine(): the two maps' spectral-route surfaces at rho = 0 are the summits of the summed
    # moments (the round trip through sigma_s, R, eta is exact to rounding)
    surfaces = [summits.spectral_summits(m, area) for m in (ma, mb)]
    gw = [Surface(sigma=s.sigma_s, R=s.R, eta=s.eta) for s in surfaces]
    c = combine(*gw, 0.0)
    want = summits_of(ma.m0 + mb.m0, ma.m2 + mb.m2, ma.m4 + mb.m4)
    for name in ("sigma", "R", "eta", "rq"):
        assert getattr(c, name) == pytest.approx(getattr(want, name), rel=1e-12), name


def test_a_turned_over_counter_map_and_the_measured_correlation():
    """facing_gap is map - flipped counter; the measured rho gives the gap's rms exactly."""
    rng = np.random.default_rng(7)
    z = rng.normal(size=(32, 48))
    counter = 0.5 * (-z[:, ::-1]) + rng.normal(size=z.shape)  # partly replicates z
    assert np.array_equal(summits.flipped(counter), -counter[:, ::-1])
    gap = summits.facing_gap(z, counter)
    np.testing.assert_allclose(gap, z - summits.flipped(counter), rtol=0, atol=0)
    measured = summits.height_correlation(z, summits.flipped(counter), order=1)
    assert 0.3 < measured.rho < 0.6
    rms = np.std(summits.level(gap, 1))
    want = combined_rms(measured.rms, measured.other_rms, measured.rho)
    assert rms == pytest.approx(want, rel=1e-12)
