"""Pads from a map's spectrum: Parseval, the Hurst exponent recovered, pads with the source's rms and
PSD within their sampling errors, reproducible streams, bad input refused by name.

Sampling errors used below (module docstring of mcsim.topography.synthesis):
* a radial bin of n modes of one Gaussian map holds n/2 independent exponential ordinates
  (q and −q are the same number), so ln of its mean has variance ≈ 2/n;
* a pad's mean square s² = Σ_q |H_q|²/N² has variance 2 Σ_q (C_q/A)² (each mode's |H_q|² is
  exponential, or χ²₁ for the self-conjugate ones, and q, −q are equal);
* the mean of M pads' bin averages has relative standard error √(2/(n M)).
"""

import math

import numpy as np
import pytest
from scipy.special import digamma

from mcsim.model.errors import ParameterError
from mcsim.topography.synthesis import (
    radial_psd,
    self_affine_fit,
    synthesize,
    synthesize_like,
    wavevectors,
)

DX = 2e-9
#: Bound on a z-score of one stochastic check with a fixed seed (two-sided p ≈ 6e-5).
Z = 4.0


def rolled_off_map(n: int, hurst: float, roll_off: int, rng) -> np.ndarray:
    """Periodic Gaussian map, PSD flat below q_r = roll_off·2π/L and ∝ q^{-2(1+H)} above.

    Written independently of the module: white noise times the amplitude √C ∝ q^{-(1+H)}.
    """
    k = np.fft.fftfreq(n, 1 / n)
    radius = np.hypot(k[:, None], k[None, :])  # |q| in units of 2π/L
    amplitude = np.zeros_like(radius)
    amplitude[radius > 0] = np.maximum(radius[radius > 0] / roll_off, 1) ** (-(1 + hurst))
    return 1e-9 * np.fft.ifft2(amplitude * np.fft.fft2(rng.standard_normal((n, n)))).real


SOURCE = rolled_off_map(32, 0.7, 3, np.random.default_rng(11))


def test_parseval_the_psd_integrates_to_the_variance_of_a_periodic_map():
    z = np.random.default_rng(2).standard_normal((32, 48)) * 1e-9
    psd = radial_psd(z, DX, periodic=True)
    assert psd.n_modes.sum() == z.size - 1  # every mode but the mean
    dq_x, dq_y = 2 * np.pi / (48 * DX), 2 * np.pi / (32 * DX)
    integral = np.sum(psd.n_modes * psd.C) * dq_x * dq_y / (2 * np.pi) ** 2
    assert integral == pytest.approx(np.var(z), rel=1e-12)
    assert psd.mean_square() == pytest.approx(np.var(z), rel=1e-12)


def test_the_psd_of_a_sinusoid_sits_in_its_annulus():
    """h = a cos(2π·5x/L): ⟨h²⟩ = a²/2 carried by the 2 modes ±5Δq, so C = A a²/4 there."""
    n, a = 64, 3e-9
    z = a * np.cos(2 * np.pi * 5 * np.arange(n) / n)[None, :] * np.ones((n, 1))
    psd = radial_psd(z, DX, periodic=True)
    area = (n * DX) ** 2
    (five,) = np.flatnonzero(psd.index == 5)
    assert psd.C[five] * psd.n_modes[five] == pytest.approx(area * a**2 / 2, rel=1e-12)
    assert np.sum(psd.n_modes * psd.C) - psd.C[five] * psd.n_modes[five] < 1e-12 * area * a**2


def test_the_fit_recovers_the_hurst_exponent_within_its_standard_error():
    """H = 0.8 with a roll-off at 8Δq on 256²: ln C of a bin of n modes scatters by √(2/n);
    the weighted least-squares slope of ln C against −2 ln q above q_r then has standard
    error SE(H), computed here from the mode counts alone. |H_fit − 0.8| < 4 SE; the roll-off
    must land within 2 bins of 8Δq (the corner is spread over a few bins by the scatter)."""
    hurst, roll_off = 0.8, 8
    z = rolled_off_map(256, hurst, roll_off, np.random.default_rng(5))
    psd = radial_psd(z, DX, periodic=True)
    fit = self_affine_fit(psd.q, psd.C, psd.n_modes)
    dq = 2 * np.pi / (256 * DX)
    x = np.stack([np.ones(psd.q.size), -2 * np.maximum(np.log(psd.q / (roll_off * dq)), 0)], 1)
    weight = psd.n_modes / 2
    se = math.sqrt(np.linalg.inv(x.T @ (weight[:, None] * x))[1, 1])
    assert abs(fit.hurst - hurst) < Z * se, (fit.hurst, se)
    assert fit.hurst_se == pytest.approx(se, rel=0.2)
    assert abs(fit.q_r / dq - roll_off) <= 2


def test_the_fit_is_exact_on_the_expected_log_of_a_noiseless_spectrum():
    """ln of a bin's mean of m = n/2 exponentials is low by ln m − ψ(m) on average: a spectrum
    C0 (q/q_r)^{-2(1+H)} times exactly that bias, flat below q_r, is fitted exactly."""
    q = np.arange(1.0, 60.0) * 1e7
    n = 2 * np.pi * np.arange(1.0, 60.0)
    m = n / 2
    model = 3e-36 * np.maximum(q / 12e7, 1) ** (-2 * (1 + 0.65))
    fit = self_affine_fit(q, model * np.exp(digamma(m) - np.log(m)), n)
    assert fit.hurst == pytest.approx(0.65, abs=1e-10)
    assert (fit.q_r, fit.C0) == (12e7, pytest.approx(3e-36, rel=1e-10))


def test_the_window_keeps_a_cut_out_sinusoid_in_its_annulus():
    """A cosine of 5.5 periods across a non-periodic map, symmetric about its centre (so the
    levelling plane is a constant): Hann's leakage at d bins off is (sin πd/(πd(1−d²)))², which
    summed over d = 4.5, 5.5, … is 2e-5 of the power. Without a window it would be ≈ 1/(π²·4)."""
    n = 64
    x = (np.arange(n) + 0.5 - n / 2) / n
    z = np.cos(2 * np.pi * 5.5 * x)[None, :] * np.ones((n, 1)) * 1e-9
    psd = radial_psd(z, DX)
    power = psd.n_modes * psd.C
    assert np.sum(power[psd.index >= 10]) / np.sum(power) < 1e-4


def test_pads_have_the_source_rms_in_expectation():
    """z-test of the mean of M pads' mean squares against the source's, with the standard error
    √(2 Σ_q (C_q/A)² / M) (module docstring)."""
    m = 400
    psd = radial_psd(SOURCE, DX, periodic=True)
    pads = synthesize_like(SOURCE, DX, m, rng=1, periodic=True)
    assert pads.shape == (m, 32, 32)
    mean_square = np.mean(pads**2, axis=(1, 2))
    se = math.sqrt(2 * np.sum(psd.n_modes * (psd.C / psd.area) ** 2) / m)
    z = (mean_square.mean() - np.var(SOURCE)) / se
    assert abs(z) < Z, z


def test_self_affine_pads_have_the_source_rms_in_expectation():
    """As above with the fitted model; the standard error is the pads' own: std/√M."""
    m = 400
    pads = synthesize_like(SOURCE, DX, m, rng=2, method="self-affine", periodic=True)
    mean_square = np.mean(pads**2, axis=(1, 2))
    z = (mean_square.mean() - np.var(SOURCE)) / (mean_square.std(ddof=1) / math.sqrt(m))
    assert abs(z) < Z, z


def test_pads_have_the_source_psd_bin_by_bin():
    """Each annulus's mean over M pads, over the source's: 1 within √(2/(n M)) per bin; the
    largest of the ~20 z-scores below 4.5 (p ≈ 1e-4 for all bins together)."""
    m = 400
    source = radial_psd(SOURCE, DX, periodic=True)
    pads = synthesize_like(SOURCE, DX, m, rng=3, periodic=True)
    mean = np.mean([radial_psd(pad, DX, periodic=True).C for pad in pads], axis=0)
    z = (mean / source.C - 1) / np.sqrt(2 / (source.n_modes * m))
    assert np.max(np.abs(z)) < 4.5, z


def test_pads_are_real_periodic_gaussian_fields_of_zero_mean():
    pads = synthesize((16, 24), DX, lambda q: np.full_like(q, 1e-36), rng=4, n=2)
    assert pads.shape == (2, 16, 24)
    np.testing.assert_allclose(pads.mean(axis=(1, 2)), 0, atol=1e-12 * pads.std())
    assert wavevectors((16, 24), DX).shape == (16, 24)


def test_the_same_rng_gives_identical_pads_and_pad_i_does_not_depend_on_n():
    first = synthesize_like(SOURCE, DX, 5, rng=7, periodic=True)
    again = synthesize_like(SOURCE, DX, 5, rng=np.random.default_rng(7), periodic=True)
    fewer = synthesize_like(SOURCE, DX, 2, rng=7, periodic=True)
    np.testing.assert_array_equal(first, again)
    np.testing.assert_array_equal(first[:2], fewer)


def test_different_streams_give_different_pads():
    pads = synthesize_like(SOURCE, DX, 3, rng=7, periodic=True)
    other = synthesize_like(SOURCE, DX, 3, rng=8, periodic=True)
    assert not np.any(pads[0] == pads[1]) and not np.any(pads[0] == other[0])


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: radial_psd(np.where(np.eye(32) > 0, np.nan, SOURCE), DX), "`z` has 32 non-finite"),
        (lambda: radial_psd(SOURCE[:7], DX), r"`shape` = \(7, 32\) is out of range"),
        (lambda: radial_psd(SOURCE, 0.0), "`pixel_size` = 0.0 m is out of range"),
        (lambda: synthesize((8, 4), DX, lambda q: q), r"`shape` = \(8, 4\)"),
        (lambda: synthesize((8, 8), -DX, lambda q: q), "`pixel_size` = -2e-09 m"),
        (lambda: synthesize((8, 8), DX, lambda q: -q), "`psd` must return finite values ≥ 0"),
        (lambda: synthesize((8, 8), DX, lambda q: q, n=0), "`n` = 0 is out of range"),
        (lambda: synthesize_like(SOURCE, DX, method="fft"), "`method` = 'fft' is not one of"),
        (lambda: self_affine_fit([1.0, 2.0, 3.0, 4.0], [1.0, 0.0, 1.0, 1.0]), "`C` must be"),
    ],
)
def test_bad_input_is_refused_by_name(call, match):
    with pytest.raises(ParameterError, match=match):
        call()
