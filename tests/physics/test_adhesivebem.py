"""The adhesive FFT boundary-element solver against Maugis, Johnson, Hertz and its own energy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from mcsim.model.errors import ParameterError
from mcsim.physics import adhesivebem, adhesivecycle, bem
from mcsim.physics.interactions import Exponential, MaugisDugdale, mesh_parameter
from mcsim.physics.laws import maugis_dugdale as md
from mcsim.physics.subpixel import gather, spread

# The Maugis–Dugdale sphere in convenient units (SI numbers of order one): R = 1 m, E* = 1 Pa,
# so K = 4/3 Pa; w is chosen so that the contact-radius unit (πwR²/K)^{1/3} is A0 = 0.1 m,
# hence the penetration unit (π²w²R/K²)^{1/3} = A0²/R, and δc from λ (Maugis:
# h0/(π²w²R/K²)^{1/3} = 2/(πλ)).
R, E_STAR, A0 = 1.0, 1.0, 0.1
K = 4 * E_STAR / 3
W = K * A0**3 / math.pi
DELTA_UNIT = A0**2 / R
FORCE_UNIT = math.pi * W * R


def md_sphere(lam: float, n: int, half: float):
    """Paraboloid z = −r²/2R on n × n pixels over ±half·A0 (zero-padded), its MD law, the
    flat's height at which the undeformed apex touches, and the map's side."""
    side = 2 * half * A0
    dx = side / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    z = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)
    law = MaugisDugdale(W, 2 * DELTA_UNIT / (math.pi * lam))
    return z, dx, law, -z.mean(), side


def retraction(lam: float, n: int, half: float, step: float = 0.1, subpixel: int = 1):
    """Retraction of the MD sphere from Δ = 0.5 (a cold start in contact) past the pull-off
    of Maugis' theory, in steps of Δ; returns Δ, P̄ (load per πwR) and the solutions."""
    z, dx, law, apex, side = md_sphere(lam, n, half)
    deltas = np.arange(0.5, md.pull_off(lam)[1] - 0.25, -step)
    steps = list(adhesivebem.follow(z, dx, E_STAR, law, apex - deltas * DELTA_UNIT,
                                    periodic=False, tol=1e-4, subpixel=subpixel))  # fmt: skip
    loads = np.array([s.mean_pressure * side**2 / FORCE_UNIT for s in steps])
    return deltas, loads, steps


def maugis_load(lam: float, delta: float) -> float:
    """P̄ on Maugis' contact branch at penetration Δ (`maugis_dugdale.contact_curve`)."""
    psi_lo = md.table(lam).psi_lo
    psi = brentq(lambda p: md.contact_curve(p, lam)[2] - delta, 1e-9, psi_lo, xtol=1e-14)
    return float(md.contact_curve(psi, lam)[1])


@pytest.fixture(scope="module")
def sphere_half():
    """λ = 0.5 on 64² pixels over ±2.2 A0 (Dugdale zone at pull-off: C = 1.63 A0 outer radius,
    width 0.96 A0 = 14 pixels; mesh parameter 0.13)."""
    return retraction(0.5, 64, 2.2)


# Pull-off measured (these grids, tol 1e-4, steps of 0.1 in Δ): λ = 0.1: −0.03 %, λ = 0.5:
# +0.74 %, λ = 1: +1.80 %; the bound is 2 %. Grids: the Dugdale zone at pull-off (outer
# radius C, width C − A in units of A0) must lie inside the map and span many pixels:
# λ = 0.1: C = 3.5, width 3.3 = 24 pixels of 0.14 A0 (64² over ±4.5 A0); λ = 0.5: C = 1.63,
# width 0.96 = 14 pixels of 0.069 A0 (64² over ±2.2 A0); λ = 1: C = 1.33, width 0.43 = 14
# pixels of 0.031 A0 (128² over ±2 A0). The discrete zone traps the crack (each pixel it
# releases snaps off), which makes the pull-off too tensile, roughly in proportion to the
# pixel: at λ = 1, +4.1 % on 64² over ±2 A0 (dx = 0.0625 A0). At λ = 2 and 5 the zone is
# 0.15 and 0.029 A0 wide and 2 % needs finer grids than a test affords (λ = 2: 512², 586 s,
# +1.41 %; see the grid test), or the sub-pixel quadrature of the tests below.
# λ = 1 with the sub-pixel quadrature (k = 4) on 64²: −0.09 % (validation/md_sphere.py), at a
# quarter of the 128² plain grid's cost.
@pytest.mark.parametrize(("lam", "n", "half", "subpixel"),
                         [(0.1, 64, 4.5, 1), (0.5, 64, 2.2, 1), (1.0, 64, 2.0, 4)])  # fmt: skip
def test_md_sphere_pull_off_within_two_percent_of_maugis(lam, n, half, subpixel):
    _, loads, steps = retraction(lam, n, half, subpixel=subpixel)
    assert all(s.converged for s in steps)
    np.testing.assert_allclose(loads.min(), md.pull_off(lam)[0], rtol=0.02,
                               err_msg=f"pull-off at lambda = {lam}")  # fmt: skip


def test_md_sphere_load_follows_maugis_contact_branch(sphere_half):
    # λ = 0.5, retraction in contact (Δ = 0.5 … −0.3): P̄(Δ) against Maugis' branch. Measured:
    # 0.0003–0.0204 πwR above it (largest at Δ = 0.2); bound 0.05 πwR (3 % of the pull-off),
    # the pixel rings of contact and zone (a pixel is 0.07 A0) moving P̄ by a few hundredths.
    deltas, loads, _ = sphere_half
    for delta, load in zip(deltas, loads, strict=True):
        if delta >= -0.3:
            assert abs(load - maugis_load(0.5, delta)) < 0.05, (delta, load)


def test_padding_carries_no_pressure(sphere_half):
    # The pressure on the zero padding is the gradient there: it vanishes at the minimum,
    # to the solver's tolerance (1e-4 of w/δc).
    _, _, steps = sphere_half
    assert max(s.padding_residual for s in steps) <= 1e-4


def test_pull_off_error_shrinks_with_the_grid():
    # λ = 2 over ±1.6 A0 (Dugdale zone width 0.15 A0): measured +13.4 % on 64² (dx = 0.05 A0,
    # mesh parameter 0.46), +5.7 % on 128² (0.025 A0, 0.32), +2.9 % on 256² (0.0125 A0, 0.23;
    # 63 s, not run here), +1.41 % on 512² (0.0063 A0, 0.16; 586 s); λ = 5 over ±1.4 A0:
    # +27 % on 128², +15.5 % on 256² (113 s). The error is the lattice trapping of a zone of
    # 3, 6, 12, 24 pixels; it falls roughly as dx (ratios 0.43, 0.50, 0.49).
    errors = []
    for n in (64, 128):
        _, loads, _ = retraction(2.0, n, 1.6)
        errors.append(loads.min() / md.pull_off(2.0)[0] - 1)
    assert 0 < errors[1] < 0.6 * errors[0], errors


# Sub-pixel quadrature of the interaction (adhesivebem, "Sub-pixel quadrature"): φ at k × k
# points a pixel on the bilinear interpolant of the gaps. Measured pull-off (tol 1e-4, steps
# of 0.1 in Δ): λ = 2 on 64² over ±1.6 A0 with k = 4: +0.17 % (k = 1: +13.4 %; 3 s);
# λ = 5 on 64² over ±1.4 A0 with k = 8: +0.57 % (k = 1: +41.8 %; 6 s). Sampling Maugis'
# curve at these steps misses its minimum by at most 0.16 % (λ = 2), well inside the 2 %.
# At λ = 5 the pixel (0.044 A0) is wider than the zone (0.029 A0), and the mesh parameter
# is 1.07 > 0.5, so the solver warns; the k² = 64 points a pixel resolve the zone all the
# same (the grid convergence: validation/md_sphere.py).
@pytest.fixture(scope="module")
def sphere_two():
    """λ = 2 on 64² pixels over ±1.6 A0 with 4 × 4 quadrature points a pixel (the Dugdale
    zone at pull-off: C = 1.20 A0, width 0.15 A0 = 3 pixels, 12 quadrature points)."""
    return retraction(2.0, 64, 1.6, subpixel=4)


def test_subpixel_md_sphere_pull_off_within_two_percent_at_lambda_2(sphere_two):
    _, loads, steps = sphere_two
    assert all(s.converged for s in steps)
    np.testing.assert_allclose(loads.min(), md.pull_off(2.0)[0], rtol=0.02)


def test_subpixel_md_sphere_pull_off_within_two_percent_at_lambda_5():
    with pytest.warns(UserWarning, match="mesh parameter"):
        _, loads, steps = retraction(5.0, 64, 1.4, subpixel=8)
    assert all(s.converged for s in steps)
    np.testing.assert_allclose(loads.min(), md.pull_off(5.0)[0], rtol=0.02)


def test_subpixel_md_sphere_load_follows_maugis_contact_branch_at_lambda_2(sphere_two):
    # λ = 2, Δ = 0.4 … −0.7: through the pull-off (Δ = −0.45) to the unstable part of the
    # branch under load control, which displacement control follows. Measured: within
    # 0.026 πwR of Maugis' branch (largest at Δ = 0.3); bound 0.05 πwR (3 % of the
    # pull-off), as at λ = 0.5. The first step, a cold start from the undeformed sphere at
    # Δ = 0.5, is left out: its zone edge lands where the descent stops it (0.049 πwR off).
    deltas, loads, _ = sphere_two
    for delta, load in zip(deltas[1:], loads[1:], strict=True):
        assert abs(load - maugis_load(2.0, delta)) < 0.05, (delta, load)


@pytest.mark.parametrize("k", [1, 2, 3, 4])
@pytest.mark.parametrize("wrap", [False, True])
def test_subpixel_interpolation_is_bilinear_and_gather_is_its_transpose(k, wrap):
    # spread: constants stay, a linear field is exact inside the map (its edge pixels see the
    # edge value beyond, or the periodic image); gather: <B g, t> = <g, Bᵀ t> to rounding,
    # and Bᵀ 1 = k² (φ linear over a pixel and its neighbours: the pixel-centre law again).
    rng = np.random.default_rng(5)
    g, t = rng.standard_normal((6, 7)), rng.standard_normal((6 * k, 7 * k))
    np.testing.assert_allclose(np.sum(spread(g, k, wrap) * t), np.sum(g * gather(t, k, wrap)),
                               rtol=1e-12)  # fmt: skip
    np.testing.assert_allclose(gather(np.ones((6 * k, 7 * k)), k, wrap), k * k, rtol=1e-14)
    np.testing.assert_allclose(spread(np.full((6, 7), 3.0), k, wrap), 3.0, rtol=1e-15)
    rows, cols = np.arange(6.0), np.arange(7.0)
    sub = (np.arange(7 * k) + 0.5) / k - 0.5
    linear = spread(np.add.outer(2 * rows, 3 * cols), k, wrap)
    exact = np.add.outer(2 * ((np.arange(6 * k) + 0.5) / k - 0.5), 3 * sub)
    np.testing.assert_allclose(linear[k:-k, k:-k], exact[k:-k, k:-k], atol=1e-12)


@pytest.mark.parametrize("subpixel", [0, -2, 2.5, True, "4"])
def test_bad_subpixel_is_refused(subpixel):
    z, dx, law, apex, _ = md_sphere(1.0, 32, 2.0)
    with pytest.raises(ParameterError, match=r"`subpixel` must be an integer >= 1, got"):
        adhesivebem.solve_gap(z, dx, E_STAR, law, apex, periodic=False, subpixel=subpixel)


@pytest.mark.parametrize("subpixel", [1, 3])
def test_mean_pressure_is_minus_the_derivative_of_the_energy(subpixel):
    # p̄ = −de/dd (the envelope theorem), on a periodic map (mean-gap control, the Lagrange
    # multiplier) and on a padded one: central differences of the energy at ±1e-4 of the
    # range, converged to 1e-9; agreement to 1e-5 relative (the difference's rounding). With
    # sub-pixel quadrature too: its traction is the derivative of its energy.
    rng = np.random.default_rng(3)
    n = 32
    z = np.cumsum(rng.standard_normal((n, n)), axis=1) * 1e-10
    z = np.fft.irfft2(np.fft.rfft2(z) * np.exp(-np.arange(n // 2 + 1) / 4.0), s=(n, n))
    z *= 2e-9 / z.std()
    law = Exponential(0.05, 0.5e-9)
    for periodic in (True, False):
        d = 1.5e-9
        s0 = adhesivebem.solve_gap(z, 10e-9, 1e11, law, d, periodic=periodic, tol=1e-9,
                                   subpixel=subpixel)  # fmt: skip
        e = []
        for shift in (1e-4, -1e-4):
            s = adhesivebem.solve_gap(z, 10e-9, 1e11, law, d + shift * law.range,
                                      periodic=periodic, tol=1e-9, subpixel=subpixel,
                                      initial=s0.displacement_field)  # fmt: skip
            e.append(s.energy)
        slope = -(e[0] - e[1]) / (2e-4 * law.range)
        np.testing.assert_allclose(s0.mean_pressure, slope, rtol=1e-5, err_msg=f"{periodic=}")


def test_small_adhesion_approaches_the_non_adhesive_contact():
    # w = 1e-6 of the sphere's w (its tension over the zone ~1e-5 of the load): at Δ = 1 the
    # mean pressure and the contact area are those of bem.solve_contact at that pressure
    # (Hertz on the same pixels): mean gaps within 1e-3 of the penetration unit (measured
    # below 1e-4), contact fractions within one pixel ring (2πa/dx pixels).
    z, dx, _, apex, side = md_sphere(1.0, 64, 2.0)
    law = MaugisDugdale(1e-6 * W, 0.2 * DELTA_UNIT)
    s = adhesivebem.solve_gap(z, dx, E_STAR, law, apex - DELTA_UNIT, periodic=False, tol=1e-6)
    exact = bem.solve_contact(z, dx, E_STAR, s.mean_pressure, periodic=False)
    a = math.sqrt(exact.area_fraction * side**2 / math.pi)
    assert abs(s.contact_fraction - exact.area_fraction) <= 2 * math.pi * a * dx / side**2
    assert abs(s.mean_gap - exact.mean_gap) < 1e-3 * DELTA_UNIT


@pytest.fixture(scope="module")
def sphere_cycle():
    """λ = 1 on 48² pixels over ±2 A0: approach from the jump-in region to Δ = 0.6 and back."""
    z, dx, law, apex, side = md_sphere(1.0, 48, 2.0)
    deltas = np.arange(-1.4, 0.61, 0.1)
    return adhesivecycle.cycle(z, dx, E_STAR, law, apex - deltas * DELTA_UNIT, periodic=False,
                             tol=1e-4), apex, side  # fmt: skip


def test_cycle_jumps_in_on_approach_and_out_higher_on_retraction(sphere_cycle):
    # Maugis (λ = 1): jump-in where the apex gap reaches δc (Δ = −h̄0 = −0.637), jump-out near
    # the turning point Δ_b = −0.99 (displacement control), so the flat leaves higher than it
    # arrived. Measured after 4 bisections: jump-in at Δ = −0.634, jump-out at −1.034 (the
    # discrete zone holds on a little longer, as for the pull-off). Bound: 0.1 (a step). On
    # this coarse grid (dx = 0.083 A0) the retraction also snaps twice, by 0.068 and 0.026
    # πwR (at Δ = −0.60 and −0.76), where the crack crosses a ring of pixels: jumps of the
    # discrete system, bounded here by a tenth of the pull-off.
    c, apex, side = sphere_cycle
    force = side**2 / FORCE_UNIT  # mean pressure to P̄
    jump_in = next(j for j in c.jumps if j.branch == "approach")
    retract = [j for j in c.jumps if j.branch == "retraction"]
    jump_out = retract[-1]
    assert abs(jump_in.pressure_before * force) < 1e-9 and jump_in.pressure_after * force < -1
    assert jump_out.pressure_before * force < -0.5 and abs(jump_out.pressure_after * force) < 1e-3
    assert all(abs(j.pressure_after - j.pressure_before) * force < 0.16 for j in retract[:-1])
    assert jump_out.position_after > jump_in.position_after
    delta_in = (apex - jump_in.position_after) / DELTA_UNIT
    delta_out = (apex - jump_out.position_after) / DELTA_UNIT
    assert abs(delta_in + md.table(1.0).h0) < 0.1, delta_in
    assert abs(delta_out - md.table(1.0).delta_break) < 0.1, delta_out


def test_cycle_hysteresis_and_work_of_separation(sphere_cycle):
    # The work of separation is the tensile area under the retraction; it exceeds the
    # approach's (hysteresis > 0). The closed loop's work ∮ p̄ dd is positive (energy lost in
    # the jumps) and equals the loss in energy the trapezoids leave between the steps, since
    # the energy returns to its start (both ends out of contact): checked to 1e-9 w.
    c, _, _ = sphere_cycle
    assert c.converged and c.hysteresis > 0 and c.loop_work > 0
    d = np.array([s.position for s in c.retraction])
    tensile = -np.minimum([s.mean_pressure for s in c.retraction], 0)
    trapezoids = np.sum(0.5 * (tensile[1:] + tensile[:-1]) * np.diff(d))
    assert c.work_of_separation == pytest.approx(trapezoids)
    assert c.hysteresis == pytest.approx(c.work_of_separation - c.approach_work)
    assert c.retraction[-1].energy == pytest.approx(c.approach[0].energy, abs=1e-9 * W)


def test_non_convergence_is_flagged_never_silent():
    z, dx, law, apex, _ = md_sphere(1.0, 32, 2.0)
    s = adhesivebem.solve_gap(z, dx, E_STAR, law, apex - 0.5 * DELTA_UNIT, periodic=False,
                              max_iter=1)  # fmt: skip
    assert not s.converged and s.residual > adhesivebem.TOL
    positions = apex - np.array([-0.5, 0.5]) * DELTA_UNIT
    with pytest.raises(adhesivecycle.ConvergenceError, match="did not converge"):
        adhesivecycle.cycle(z, dx, E_STAR, law, positions, periodic=False, max_iter=1)
    c = adhesivecycle.cycle(z, dx, E_STAR, law, positions, periodic=False, max_iter=1, strict=False)
    assert not c.converged and c.failed
    assert math.isnan(c.pull_off) and math.isnan(c.work_of_separation)


@pytest.mark.parametrize("kind", [MaugisDugdale, Exponential])
def test_law_energy_starts_at_minus_w_and_its_traction_is_minus_its_slope(kind):
    # φ(0) = −w, φ → 0 far apart, and pressure = −dφ/dg (central differences of 1e-6 of the
    # range, away from the Dugdale kink at g = range; to 1e-6 relative).
    law = kind(0.1, 1e-9)
    assert law.energy(0.0) == pytest.approx(-0.1)
    assert abs(law.energy(50e-9)) < 1e-20
    g = np.array([0.1, 0.5, 0.9, 1.5, 3.0]) * 1e-9
    h = 1e-6 * law.range
    slope = (law.energy(g + h) - law.energy(g - h)) / (2 * h)
    np.testing.assert_allclose(law.pressure(g), -slope, rtol=1e-6, atol=1e-6 * law.max_traction)
    assert np.all(law.pressure(g) <= 0)  # tensile


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"w": 0.0}, r"`w` must be positive and finite, J/m\^2, got 0.0"),
        ({"w": -1.0}, r"`w` must be positive"),
        ({"range": float("nan")}, r"`range` must be positive and finite, m, got nan"),
        ({"range": 0.0}, r"`range` must be positive"),
    ],
)
@pytest.mark.parametrize("kind", [MaugisDugdale, Exponential])
def test_bad_law_is_refused(kind, kwargs, match):
    values = {"w": 0.1, "range": 1e-9} | kwargs
    with pytest.raises(ParameterError, match=match):
        kind(**values)


def flat_map(n: int = 16) -> np.ndarray:
    return np.random.default_rng(1).standard_normal((n, n)) * 1e-9


def test_nan_in_the_map_is_refused():
    z = flat_map()
    z[3, 4] = np.nan
    with pytest.raises(ParameterError, match="`heights` must be finite"):
        adhesivebem.solve_gap(z, 1e-8, 1e11, Exponential(0.1, 1e-9), 1e-9, periodic=True)


def test_range_far_below_the_pixel_is_refused():
    with pytest.raises(ParameterError, match=r"`range` = 1e-12 m is below 0.001 of the pixel"):
        adhesivebem.solve_gap(flat_map(), 1e-8, 1e11, Exponential(0.1, 1e-12), 1e-9, periodic=True)


def test_range_above_the_height_range_is_refused():
    with pytest.raises(ParameterError, match="above the map's height range"):
        adhesivebem.solve_gap(flat_map(), 1e-8, 1e11, Exponential(0.1, 1e-6), 1e-9, periodic=True)


def test_bad_modulus_position_and_tolerance_are_refused():
    z, law = flat_map(), Exponential(0.1, 1e-9)
    with pytest.raises(ParameterError, match="`E_star` must be positive and finite, Pa"):
        adhesivebem.solve_gap(z, 1e-8, -1.0, law, 1e-9, periodic=True)
    with pytest.raises(ParameterError, match="`position` must be positive on a periodic map"):
        adhesivebem.solve_gap(z, 1e-8, 1e11, law, 0.0, periodic=True)
    with pytest.raises(ParameterError, match=r"`tol` must lie in \(0, 1\)"):
        adhesivebem.solve_gap(z, 1e-8, 1e11, law, 1e-9, periodic=True, tol=0.0)
    with pytest.raises(
        ParameterError, match="`positions` must be at least two strictly descending"
    ):
        adhesivecycle.cycle(z, 1e-8, 1e11, law, [1e-9, 2e-9], periodic=True)


def test_unresolved_law_warns_with_the_mesh_criterion():
    # Wang, Zhou & Müser (2021): √(|φ''| Δx / E*) = √(0.1/(1e-10)² · 1e-8 / 1e11) = 3.2 > 0.5.
    law = Exponential(0.1, 1e-10)
    assert mesh_parameter(law, 1e-8, 1e11) == pytest.approx(math.sqrt(0.1 / 1e-20 * 1e-8 / 1e11))
    with pytest.warns(UserWarning, match="mesh parameter"):
        adhesivebem.check_inputs(flat_map(), 1e-8, 1e11, law)


def test_wavy_surface_follows_johnson_within_the_lattice_band():
    """Johnson (Int. J. Solids Struct. 32, 423, 1995): a wavy surface z = h cos(2πx/λ) on a
    flat, plane strain, in the JKR limit,

        p̄/p* = sin²(πa/λ) − α √tan(πa/λ),  p* = πE*h/λ,  α = √(2wλ/E*)/(πh),

    written here from its two ingredients (the paper's equation numbers not checked):
    Westergaard's non-adhesive p̄ = p* sin²(πa/λ) plus a periodic array of flat punches of
    width 2a, p(x) = p̄₁ cos(πx/λ)/√(sin²(πa/λ) − sin²(πx/λ)), whose stress intensity
    K_I = |p̄₁| √(λ cot(πa/λ)) meets Griffith's G = K_I²/(2E*) = w. (The same form and α as
    ContactEngineering's `Adhesion.ReferenceSolutions.sinewave.JKR.mean_pressure`, read for
    the check, not run.) Its load-controlled pull-off: −0.16627 p* at a = 0.0789 λ here.

    The map: λ = 1 m on 4096 × 2 pixels (periodic), h = 0.01 m, E* = 1 Pa, w = 1e-4 J/m²
    (α = 0.45), MD range δc from a mesh parameter of 0.2 (δc = 7.8e-4 m); the Dugdale zone
    (π/8)(2E*w)/σ0² = 4.8e-3 m is 0.06–0.12 of the half-widths a reached (0.04–0.21), the
    JKR limit to that order. Mean-gap control from m = 1.8h to 0.6h and back (19 steps).

    Measured: the discrete zone traps the contact edge (each pixel snaps on or off), so the
    states lie in a band about Johnson's curve: on retraction 0.0059–0.0100 p* below it, on
    approach (after the jump-in lands) 0.014–0.018 p* above it; pull-off −0.1737 p*, 0.0074
    p* below Johnson's minimum. Bounds: retraction and pull-off within (−0.012 p*, 0),
    approach within (0, +0.025 p*), the band with a fifth to a third to spare.
    """
    n, wavelength, h, w = 4096, 1.0, 0.01, 1e-4
    dx = wavelength / n
    law = MaugisDugdale(w, math.sqrt(w * dx / (0.2**2 * E_STAR)))
    x = (np.arange(n) + 0.5) * dx - wavelength / 2
    z = np.tile(h * np.cos(2 * np.pi * x / wavelength), (2, 1))
    p_star = math.pi * E_STAR * h / wavelength

    def johnson(a):
        psi = math.pi * a / wavelength
        return p_star * math.sin(psi) ** 2 - math.sqrt(2 * E_STAR * w * math.tan(psi) / wavelength)

    c = adhesivecycle.cycle(z, dx, E_STAR, law, np.linspace(1.8 * h, 0.6 * h, 19), periodic=True)
    assert c.converged
    jump_in, jump_out = c.jumps[0], c.jumps[-1]
    assert jump_in.branch == "approach" and abs(jump_in.pressure_before) < 1e-12 * p_star
    assert jump_out.branch == "retraction" and abs(jump_out.pressure_after) < 1e-3 * p_star
    landed = next(i for i, s in enumerate(c.approach) if s.contact_fraction > 0)
    for s in c.approach[landed + 1 :]:
        difference = (s.mean_pressure - johnson(s.contact_fraction * wavelength / 2)) / p_star
        assert 0 < difference < 0.025, (s.position / h, difference)
    for s in c.retraction[1:]:  # the first is the approach's last state, at the same d
        if s.contact_fraction > 0:
            difference = (s.mean_pressure - johnson(s.contact_fraction * wavelength / 2)) / p_star
            assert -0.012 < difference < 0, (s.position / h, difference)
    pull_off = -0.1662672636765236 * p_star  # Johnson's minimum over a (scipy, bounded)
    assert -0.012 * p_star < c.pull_off - pull_off < 0, c.pull_off / p_star
