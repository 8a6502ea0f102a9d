"""Summit statistics of height maps: exact maxima, plateau/border/NaN rules, two routes agree."""

import math
import warnings

import numpy as np
import pytest
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

from mcsim.model.errors import ParameterError
from mcsim.topography.summits import (
    SaturationWarning,
    level,
    periodic_edges,
    summit_statistics,
)

# Synthetic maps with exact plateaus and repeated extremes trip the saturation check.
pytestmark = pytest.mark.filterwarnings("ignore::mcsim.topography.summits.SaturationWarning")


def egg_crate(n: int = 33, period: int = 8, dx: float = 1e-8) -> np.ndarray:
    """z = cos(2πx/L) cos(2πy/L): maxima (z = 1) where i, j ≡ 0 or both ≡ L/2 (mod L).

    n = 4k+1 pixels centred on a maximum: the map is symmetric, so the fitted plane is
    flat and levelling only removes the mean.
    """
    i = np.arange(n) - n // 2
    c = np.cos(2 * np.pi * i / period)
    return np.outer(c, c)


def gaussian_surface(n: int, ell: float, seed: int) -> np.ndarray:
    """Periodic Gaussian random surface with autocorrelation exp(−r²/ℓ²) (ℓ in pixels), unit rms."""
    rng = np.random.default_rng(seed)
    k = 2 * np.pi * np.fft.fftfreq(n)
    k2 = k[:, None] ** 2 + k[None, :] ** 2
    # PSD ∝ exp(−k²ℓ²/4): the amplitude filter is its square root
    z = np.fft.ifft2(np.fft.fft2(rng.standard_normal((n, n))) * np.exp(-k2 * ell**2 / 8)).real
    return z / z.std()


def test_egg_crate_summits_are_counted_exactly():
    """Interior indices 1..31 centred on 16: 3×3 maxima with i,j ≡ 0 and 4×4 with i,j ≡ 4 (mod 8)."""
    result = summit_statistics(egg_crate(), 1e-8)
    assert result.direct.count == 25
    assert result.direct.eta == pytest.approx(25 / (31 * 31 * 1e-16), rel=ROUNDING_FEW)


def test_egg_crate_curvature_is_the_exact_central_difference():
    """At a maximum z_xx = z_yy = 2(cos(2π/8) − 1)/dx², so κ = 2(1 − cos(π/4))/dx²."""
    dx = 1e-8
    result = summit_statistics(egg_crate(dx=dx), dx)
    # the same central difference of cosines: ROUNDING_FORMULA (measured 5.8e-16)
    assert result.direct.R == pytest.approx(
        dx**2 / (2 * (1 - math.cos(math.pi / 4))), rel=ROUNDING_FORMULA
    )


def test_egg_crate_summit_heights_are_all_equal():
    result = summit_statistics(egg_crate(), 1e-8)
    # zero spread: absolute, 1e-14 of the unit amplitude: rounding of cosines (measured 9e-17)
    assert result.direct.sigma_s == pytest.approx(0.0, abs=1e-14)


def test_plateau_counts_once():
    z = np.zeros((5, 6))
    z[2, 2:4] = 1.0
    assert summit_statistics(z, 1.0, order=0).direct.count == 1


def test_border_pixels_are_never_summits():
    z = -np.add.outer(np.arange(5.0) ** 2, np.arange(5.0) ** 2)  # highest at the corner
    assert summit_statistics(z, 1.0, order=0).direct.count == 0


def test_nan_pixels_are_counted_and_excluded():
    z = egg_crate()
    z[4, 4] = np.nan  # a maximum
    result = summit_statistics(z, 1e-8)
    assert (result.n_nan, result.direct.count) == (1, 24)


def test_plane_levelling_removes_a_tilt_exactly():
    y, x = np.mgrid[0:20, 0:30]
    # absolute (the result is zero): rounding of a least-squares fit to values ≤ 18
    np.testing.assert_allclose(level(3.0 + 0.5 * x - 0.2 * y), 0.0, atol=1e-12)


def test_quadratic_levelling_removes_a_bow():
    y, x = np.mgrid[0:20, 0:30]
    # absolute (the result is zero): a quadratic least-squares fit to values ≤ 60, ill
    # conditioned in x²: 1e-10 (measured 3.6e-14)
    np.testing.assert_allclose(level(1e-3 * (x - 7.0) ** 2 + 0.1 * x * y, order=2), 0.0, atol=1e-10)


def test_saturated_map_warns():
    z = egg_crate()
    z[z > 0.5] = 0.5
    with pytest.warns(SaturationWarning, match="sit at the map's maximum"):
        summit_statistics(z, 1e-8)


def test_unsaturated_map_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        summit_statistics(gaussian_surface(64, 4, 0), 1e-8)


def test_direct_and_spectral_routes_agree_on_gaussian_surface():
    """1024² pixels, ℓ = 6 pixels: about 5 300 summits.

    Tolerance: 3 standard errors of each direct-route estimate (Poisson count for η;
    0.5/√N for ⟨κ⟩, whose summit-to-summit spread is about half its mean; σ_s/√N for the mean height; σ_s/√(2N) for σ_s) plus 1 % for the
    discretisation of the 8-neighbour rule and McCool's constants (observed ≲ 2.5 % on
    η over seeds).
    """
    dx = 1e-8
    z = gaussian_surface(1024, 6.0, seed=1) * 1e-9
    result = summit_statistics(z, dx)
    d, s = result.direct, result.spectral
    n = d.count
    # standard errors of the direct route, relative
    se = {"eta": 1 / math.sqrt(n), "sigma_s": 1 / math.sqrt(2 * n), "R": 0.5 / math.sqrt(n),
          "mean_height": d.sigma_s / d.mean_height / math.sqrt(n)}  # fmt: skip
    for name, rel in se.items():
        got, expected = getattr(d, name), getattr(s, name)
        assert abs(got / expected - 1) < 3 * rel + 0.01, f"{name}: {got:.4g} vs {expected:.4g}"


def test_result_reports_the_sampling():
    result = summit_statistics(egg_crate(), 2e-8, 3e-8)
    assert (result.dx, result.dy, result.shape, result.order) == (2e-8, 3e-8, (33, 33), 1)


def test_tiny_map_is_refused():
    with pytest.raises(ParameterError, match="at least 3×3 pixels"):
        summit_statistics(np.zeros((2, 5)), 1.0)


def test_bad_pixel_size_is_refused():
    with pytest.raises(ParameterError, match=r"dx = -1.0 m is out of range"):
        summit_statistics(np.zeros((5, 5)), -1.0)


def test_bad_order_is_refused():
    with pytest.raises(ParameterError, match="`order` must be a non-negative integer"):
        level(np.zeros((5, 5)), order=-1)


@pytest.mark.parametrize("value", [0.0, 3.7, -1e-9])
def test_a_constant_map_is_refused_as_flat(value):
    with pytest.raises(ParameterError, match=r"^the height map is flat"):
        summit_statistics(np.full((16, 16), value), 1e-8)


def test_a_tilted_plane_is_refused_as_flat():
    y, x = np.mgrid[0:16, 0:16]
    with pytest.raises(ParameterError, match=r"^the height map is flat"):
        summit_statistics(1e-9 * (3 * x - 2 * y + 5.0), 1e-8)


@pytest.mark.parametrize("scale", [1e-310, 1e-160])
def test_heights_too_small_for_floating_point_moments_are_refused(scale):
    z = np.random.default_rng(0).random((16, 16)) * scale
    with pytest.raises(
        ParameterError, match=r"spectral moments .* outside the floating-point range"
    ):
        summit_statistics(z, 1e-8)


def test_spectral_moments_do_not_depend_on_the_height_scale_used_to_compute_them():
    z = np.random.default_rng(1).standard_normal((32, 32))
    one, small = summit_statistics(z * 1e-9, 1e-8), summit_statistics(z * 1e-140, 1e-8)
    # the same heights 1e-131 smaller: a rounding or two per scaled value, relative
    assert small.moments.alpha == pytest.approx(one.moments.alpha, rel=ROUNDING_FORMULA)
    assert small.moments.m0 == pytest.approx(one.moments.m0 * 1e-262, rel=ROUNDING_FORMULA)


def test_periodic_egg_crate_counts_every_maximum_across_the_edges():
    """32 x 32 pixels, period 8: 4 x 4 maxima with i, j ≡ 0 and 4 x 4 with i, j ≡ 4 (mod 8)."""
    z = np.outer(*2 * [np.cos(2 * np.pi * np.arange(32) / 8)])
    assert summit_statistics(z, 1e-8, order=0, periodic=True).direct.count == 32
    # without wrapping, row and column 0 are border pixels: 3 x 3 + 4 x 4 remain
    assert summit_statistics(z, 1e-8, order=0).direct.count == 25


def test_periodic_statistics_do_not_depend_on_where_the_map_is_cut():
    z = gaussian_surface(64, 3.0, seed=11)
    a = summit_statistics(z, 1e-8, order=0, periodic=True)
    b = summit_statistics(np.roll(z, (17, 40), axis=(0, 1)), 1e-8, order=0, periodic=True)
    # the same numbers summed in another order: ROUNDING_FEW
    for key in ("count", "sigma_s", "R", "mean_height"):
        assert getattr(b.direct, key) == pytest.approx(getattr(a.direct, key), rel=ROUNDING_FEW)
    for key in ("m2", "m4"):
        assert getattr(b.moments, key) == pytest.approx(getattr(a.moments, key), rel=ROUNDING_FEW)
    c = summit_statistics(np.roll(z, (17, 40), axis=(0, 1)), 1e-8, order=0)
    assert c.direct.count != a.direct.count  # the non-periodic count depends on the cut


def test_opposite_edges_that_join_make_a_map_periodic():
    z = gaussian_surface(64, 3.0, seed=12)
    assert periodic_edges(z)[0]
    assert not periodic_edges(z[:40, :50])[0]  # cut out: the edges do not join
    tilted = z + np.arange(64)[None, :] * 0.2  # a tilt does not repeat
    assert not periodic_edges(tilted)[0]
    z[0, 5] = np.nan
    assert not periodic_edges(z)[0]
