"""The FFT boundary-element contact solver against closed forms, its own equations and ContactMechanics."""

import math

import numpy as np
import pytest
from scipy import ndimage

from mcsim.model.errors import ParameterError
from mcsim.physics import bem

E_STAR = 1e11  # Pa


def random_map(n: int, seed: int = 1, rms: float = 1e-9) -> np.ndarray:
    """A smooth periodic random map, m: white noise filtered by a Gaussian of 2 pixels."""
    z = ndimage.gaussian_filter(np.random.default_rng(seed).standard_normal((n, n)), 2, mode="wrap")
    return z * rms / z.std()


def test_hertz_contact_radius_and_peak_pressure_within_one_percent():
    # A paraboloid z = -r²/2R, zero-padded (non-periodic), contact radius a = L/5 = 25.6 pixels:
    # Hertz (Johnson Eqs. 4.22-4.23) a³ = 3FR/4E*, p0 = 3F/2πa². The rim is resolved to a pixel
    # (measured: radius 0.5 %, peak pressure 0.03 % off); 1 % is the bound.
    n, L, R = 128, 1e-6, 1e-6
    dx = L / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    z = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)
    a = L / 5
    force = 4 * E_STAR * a**3 / (3 * R)
    s = bem.solve_contact(z, dx, E_STAR, force / L**2, periodic=False)
    radius = math.sqrt(s.area_fraction * L**2 / math.pi)
    assert s.converged and s.patches == 1
    # the bound: the discretisation (a radius of ~30 pixels) is the error, 0.5 % measured
    np.testing.assert_allclose(radius, a, rtol=0.01, err_msg="contact radius")
    np.testing.assert_allclose(s.pressure_field.max(), 3 * force / (2 * math.pi * a**2),
                               rtol=0.01, err_msg="peak pressure")  # fmt: skip


@pytest.mark.parametrize("periodic", [True, False])
def test_rectangular_pixels_keep_the_hertz_circle(periodic):
    # Pixels twice as long in x as in y (96 x 192 pixels over a square 1 µm): the contact stays
    # a circle of the Hertz radius (a = L/5: 19 pixels in x, 38 in y) in both directions, to
    # 1.5 pixels in x (the rim's sampling). A periodic map's images at L barely load it (a/L = 0.2).
    L, R = 1e-6, 1e-6
    dx, dy = L / 96, L / 192
    x = (np.arange(96) - 48 + 0.5) * dx
    y = (np.arange(192) - 96 + 0.5) * dy
    z = -(x[None, :] ** 2 + y[:, None] ** 2) / (2 * R)
    a = L / 5
    s = bem.solve_contact(
        z, (dx, dy), E_STAR, 4 * E_STAR * a**3 / (3 * R) / L**2, periodic=periodic
    )
    on = s.pressure_field > 0
    width_x, width_y = on.any(axis=0).sum() * dx, on.any(axis=1).sum() * dy
    # a width counted in whole pixels: ± one pixel at each edge's rounding, with a half to spare
    np.testing.assert_allclose([width_x, width_y], [2 * a, 2 * a], atol=1.5 * dx)


@pytest.mark.parametrize("load", [0.1, 0.3, 0.6])
def test_westergaard_sinusoid_area_within_one_percent(load):
    # z = h cos(2πx/λ), periodic: p/p* = sin²(πa/λ), p* = π E* h/λ (Westergaard 1939; Johnson
    # §13.2), area fraction 2a/λ. 2048 pixels a wavelength: ≤ 2 pixels of 2a ≥ 420 pixels, 0.5 %.
    n, lam, h = 2048, 1e-6, 1e-8
    dx = lam / n
    z = np.tile(h * np.cos(2 * np.pi * np.arange(n) * dx / lam), (2, 1))
    s = bem.solve_contact(z, dx, E_STAR, load * math.pi * E_STAR * h / lam, periodic=True)
    exact = 2 / math.pi * math.asin(math.sqrt(load))
    # the bound for Westergaard's sinusoid: the contact edge within a pixel of 2048
    np.testing.assert_allclose(s.area_fraction, exact, rtol=0.01, err_msg=f"p/p* = {load}")


@pytest.mark.parametrize("periodic", [True, False])
def test_displacement_of_a_sinusoidal_pressure(periodic):
    # p = p1 cos(qx) on a periodic half-space: u = 2 p1 cos(qx)/(E* q) (Johnson §13.2), exact
    # for the FFT multiplier (rounding only). Zero-padded, the 32-pixel-period load in the middle
    # of a 512-pixel map feels its finite extent little: 1 % there.
    n, dx, p1 = 512, 1e-8, 1e6
    q = 2 * math.pi / (32 * dx)
    p = np.tile(p1 * np.cos(q * np.arange(n) * dx), (n if not periodic else 2, 1))
    u = bem.displacement_operator(p.shape, dx, E_STAR, periodic)(p)
    expected = 2 * p1 * np.cos(q * np.arange(n) * dx) / (E_STAR * q)
    if periodic:
        # exact in the periodic Green's function: the FFT's rounding, ~1e-16 of the amplitude
        # per element times log n, and the values cross zero: absolute, of the amplitude
        np.testing.assert_allclose(u[0], expected, rtol=0, atol=1e-12 * expected.max())
    else:
        middle = slice(n // 2 - 16, n // 2 + 16)
        # zero-padded: a finite patch, whose far field bends the middle by ~1 % of the
        # amplitude; absolute (the values cross zero)
        np.testing.assert_allclose(u[n // 2, middle] - u[n // 2, middle].mean(), expected[middle],
                                   rtol=0, atol=0.01 * expected.max())  # fmt: skip


def dense_displacement(shape, dx, p):
    """Displacement, m, by summing Love's one-pixel solution over every pixel pair (no FFT)."""
    ny, nx = shape
    u = np.zeros(shape)
    h = dx / 2
    for j in range(ny):
        for i in range(nx):
            y = (np.arange(ny)[:, None] - j) * dx
            x = (np.arange(nx)[None, :] - i) * dx
            k = (bem._love(x + h, y + h) - bem._love(x + h, y - h) - bem._love(x - h, y + h)
                 + bem._love(x - h, y - h)) / (math.pi * E_STAR)  # fmt: skip
            u += k * p[j, i]
    return u


@pytest.mark.parametrize("tol", [1e-4, 1e-8])
def test_force_balance_and_complementarity_at_the_solution(tol):
    # Checked against a displacement summed pixel by pixel, independent of the FFT: the mean
    # pressure is imposed, p >= 0, the gap u - z + d vanishes where p > 0 and is >= 0 elsewhere,
    # each to the stated tolerance relative to the rms height.
    z, dx, p0 = random_map(12, seed=3), 1e-8, 1e-3 * E_STAR
    s = bem.solve_contact(z, dx, E_STAR, p0, periodic=False, tol=tol)
    p = s.pressure_field
    np.testing.assert_allclose(p.mean(), p0, rtol=1e-12, err_msg="force balance")
    assert p.min() >= 0
    u = dense_displacement(z.shape, dx, p)
    zc = z - z.mean()
    on = p > 0
    d = np.mean(zc[on] - u[on])
    gap = u - zc + d
    scale = zc.std()
    assert np.abs(gap[on]).max() <= 2 * tol * scale, "gap where loaded"
    assert gap[~on].min() >= -2 * tol * scale, "overlap where unloaded"
    np.testing.assert_allclose(
        s.gap_field[~on], gap[~on], atol=2 * tol * scale, err_msg="gap field"
    )


def test_converges_with_the_tolerance():
    # The pressure field's distance from a tight solve shrinks with the tolerance, roughly in
    # proportion (here within a factor 100 of tol·p0 each).
    z, dx, p0 = random_map(64), 1e-8, 3e-3 * E_STAR
    ref = bem.solve_contact(z, dx, E_STAR, p0, periodic=True, tol=1e-11).pressure_field
    errors = []
    for tol in (1e-3, 1e-5, 1e-7):
        s = bem.solve_contact(z, dx, E_STAR, p0, periodic=True, tol=tol)
        assert s.converged and s.residual <= tol
        errors.append(np.abs(s.pressure_field - ref).max() / p0)
        assert errors[-1] < 100 * tol, (tol, errors[-1])
    assert errors[0] > errors[1] > errors[2]


def test_warm_starts_agree_with_cold_solves_in_fewer_iterations():
    z, dx = random_map(64), 1e-8
    loads = E_STAR * np.array([1e-3, 2e-3, 4e-3])
    warm = list(bem.solve_loads(z, dx, E_STAR, loads, periodic=True, tol=1e-8))
    cold = [bem.solve_contact(z, dx, E_STAR, p, periodic=True, tol=1e-8) for p in loads]
    for w, c in zip(warm, cold, strict=True):
        # two solutions at tol = 1e-8, each within 100 tol of the exact pressure field (relative
        # to the mean pressure, as the convergence test above requires): 2e-6 apart at most
        # (measured 3.3e-7)
        np.testing.assert_allclose(
            w.pressure_field, c.pressure_field, atol=2 * 100 * 1e-8 * w.pressure
        )
    assert sum(w.iterations for w in warm[1:]) < sum(c.iterations for c in cold[1:])


def test_patches_join_across_the_edges_of_a_periodic_map():
    mask = np.zeros((6, 6), bool)
    mask[2:4, 0] = mask[2:4, -1] = True  # one patch cut by the left/right edge
    mask[0, 3] = mask[-1, 3] = True  # another cut by the top/bottom edge
    assert bem.count_patches(mask, periodic=False) == 4
    assert bem.count_patches(mask, periodic=True) == 2


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"heights": np.zeros(5)}, "2-D map"),
        ({"heights": np.full((4, 4), np.nan)}, "must be finite"),
        ({"pressure": -1.0}, "`pressure` must be positive"),
        ({"E_star": 0.0}, "`E_star` must be positive"),
        ({"tol": 2.0}, r"`tol` must lie in \(0, 1\)"),
        ({"pixel_size": 0.0}, "`pixel_size` must be positive"),
    ],
)
def test_inputs_are_refused_with_their_name(kwargs, message):
    args = {"heights": random_map(8), "pixel_size": 1e-8, "E_star": E_STAR, "pressure": 1e6}
    args |= kwargs
    with pytest.raises(ParameterError, match=message):
        bem.solve_contact(args.pop("heights"), args.pop("pixel_size"), args.pop("E_star"),
                          args.pop("pressure"), periodic=True, **args)  # fmt: skip


@pytest.mark.parametrize("periodic", [True, False])
def test_agrees_with_contactmechanics_on_a_random_map(periodic):
    # ContactEngineering's ContactMechanics (MIT; optional): same Polonsky-Keer problem, solved
    # by its own code to a penetration tolerance 1e-10 of the rms height; both pressure fields
    # agree to 1e-6 of the mean pressure, the gap fields to 1e-6 of the rms height.
    pytest.importorskip(
        "ContactMechanics", reason="ContactMechanics is not installed (optional, test extra)"
    )
    from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization.ConstrainedConjugateGradients import (
        constrained_conjugate_gradients,
    )
    from SurfaceTopography import Topography

    n, dx, p0 = 32, 1e-8, 1e-3 * E_STAR
    z = random_map(n, seed=7)
    size = (n * dx, n * dx)
    half_space = PeriodicFFTElasticHalfSpace if periodic else FreeFFTElasticHalfSpace
    theirs = constrained_conjugate_gradients(
        half_space((n, n), E_STAR, size), Topography(z, size, periodic=periodic),
        external_force=p0 * size[0] * size[1], pentol=1e-10 * z.std(), forcetol=1e-12,
    )  # fmt: skip
    assert theirs.success
    ours = bem.solve_contact(z, dx, E_STAR, p0, periodic=periodic, tol=1e-10)
    pressure = theirs.jac / dx**2
    x = theirs.x[:n, :n]
    gap = np.where(pressure > 0, 0.0, x - z - theirs.offset)
    np.testing.assert_allclose(ours.pressure_field, pressure, atol=1e-6 * p0, err_msg="pressure")
    np.testing.assert_allclose(ours.gap_field, gap, atol=1e-6 * z.std(), err_msg="gap")
