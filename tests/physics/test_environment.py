"""The environment (issue 22): van der Waals across the gaps and capillary condensation.

Oracles: the closed-form limits and water numbers of docs/physics.md ("The environment"), an
independent adaptive quadrature (``scipy.integrate.quad``) of the model's definitions,
−dW/dD = p by central differences, and a finely binned Gaussian histogram.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy import integrate, stats
from tolerances import QUAD_RTOL, ROUNDING_FEW

from mcsim.model.errors import ParameterError, UnitError
from mcsim.model.presets import SURFACES
from mcsim.physics.capillary import capillary_pressure, capillary_work
from mcsim.physics.environment import DEFAULT_CUTOFF, Environment, kelvin_radius
from mcsim.physics.gapheights import nayak_heights
from mcsim.physics.surfaceenvironment import environment_curves, environment_works
from mcsim.physics.vanderwaals import vdw_pressure, vdw_work
from mcsim.topography.empirical import Empirical

A = 1.6e-19  # J, silicon across air
D0 = 0.2e-9  # m
#: b = 0: the local laws here are the non-retarded ones (DelRio et al.); the retarded ones
#: (Gregory 1981), against the same kinds of reference: tests/physics/test_environment_retarded.py
FLAT_LAW = 0.0
GAMMA = 0.072  # J/m², water
NM = 1e-9


def water(rh, theta=0.0):
    """Capillary arguments (cutoff, γ_L, r_K, θ) for water at 25 °C."""
    return D0, GAMMA, kelvin_radius(rh), theta


def gaussian_histogram(rq, width):
    """Empirical heights: N(0, rq²) binned at ``width`` (m) over ±12 rq, exact bin masses."""
    edges = np.arange(-12 * rq, 12 * rq + width / 2, width)
    return Empirical.from_histogram(edges, np.diff(stats.norm.cdf(edges / rq)))


# -- references by adaptive quadrature, straight from docs/physics.md's definitions ----------


def quad_gap_expectation(D, rq, f, lower=D0, step=None):
    """E[f(g); g >= lower] for g = D − z, z ~ N(0, rq²): quad in t = (g − lower)/rq, split at
    the scales of f near the cutoff, of the Gaussian and at a step of f (a gap)."""
    a = (D - lower) / rq

    def integrand(t):
        return f(lower + rq * t) * stats.norm.pdf(a - t)

    scales = [lower / rq * k for k in (0.1, 1, 10)] + [a + k for k in (-8, -3, -1, 0, 1, 3, 8)]
    if step is not None:
        scales.append((step - lower) / rq)
    points = sorted({0.0, *(p for p in scales if 0 < p < a + 12)})
    pieces = zip(points, [*points[1:], max(a, 0) + 12])
    return sum(
        integrate.quad(integrand, lo, hi, epsabs=0, epsrel=1e-13, limit=200)[0] for lo, hi in pieces
    )


def quad_vdw_pressure(D, rq):
    return A / (6 * math.pi) * quad_gap_expectation(D, rq, lambda g: g**-3)


def quad_vdw_work(D, rq):
    in_contact = stats.norm.sf((D - D0) / rq)
    return A / (12 * math.pi) * (quad_gap_expectation(D, rq, lambda g: g**-2) + in_contact / D0**2)


def quad_capillary(D, rq, rh, theta):
    """(p_cap, W_cap) by quad: P(D0 <= g < g_K) and E[(g_K − max(D0, g))⁺]."""
    r_k = float(kelvin_radius(rh))
    g_k = 2 * r_k * math.cos(theta)
    filled = quad_gap_expectation(D, rq, lambda g: float(g < g_k), step=g_k)
    open_depth = quad_gap_expectation(D, rq, lambda g: max(g_k - g, 0.0), step=g_k)
    depth = open_depth + (g_k - D0) * stats.norm.sf((D - D0) / rq)
    return GAMMA / r_k * filled, GAMMA / r_k * depth


# -- limits and water numbers ----------------------------------------------------------------


# 0.436 and 4.98 nm follow from γ_L V_m/(R_g T) = 0.525 nm, i.e. V_m = 18.07 cm³/mol; the
# default V_m = 1.80e-5 m³/mol gives 0.5228 nm: 0.434, 0.754 and 4.96 nm (docs/physics.md).
# The tolerance, 0.5 %, covers that 0.4 % spread between the two molar volumes.
@pytest.mark.parametrize(
    ("rh", "r_k"), [(0.3, 0.436e-9), (0.5, 0.754e-9), (0.9, 4.98e-9)], ids=["30%", "50%", "90%"]
)
def test_kelvin_radius_of_water_matches_physics_notes(rh, r_k):
    # the notes' three digits; 0.5 %: the molar volumes' 0.4 % spread (above)
    assert Environment(rh=rh).kelvin_radius == pytest.approx(r_k, rel=5e-3)


def test_laplace_pressure_of_water_at_50_percent_is_95_mpa():
    # 95 MPa in the notes, two digits: half a unit of the last
    assert Environment(rh=0.5).laplace_pressure == pytest.approx(95e6, abs=0.5e6)


def test_kelvin_radius_vanishes_when_dry():
    assert kelvin_radius(0.0) == 0.0


@pytest.mark.parametrize(
    ("name", "rq", "offset", "half_unit"),
    [("smooth", 1.55e-9, 1.59e-9, 0.005e-9), ("rough", 19.4e-9, 26.9e-9, 0.05e-9)],
)
def test_nayak_estimate_matches_physics_notes(name, rq, offset, half_unit):
    s = SURFACES[name]
    est = nayak_heights(s.sigma, s.R, s.eta)
    # the notes' values, to half a unit of their last digit
    assert est.rq == pytest.approx(rq, abs=half_unit)
    assert est.summit_offset == pytest.approx(offset, abs=half_unit)
    assert 2.5 <= est.alpha <= 4.9  # docs/physics.md: the seed's surfaces have α 2.5–4.9


FLAT = 1e-15  # m: Rq 2e-4 D0, flat for every purpose below


def test_flat_vdw_work_at_contact_is_hamaker_over_12_pi_cutoff_squared():
    # First correction ~ Rq/D0 (the open half of the heights lies ~Rq beyond D0).
    expected = A / (12 * math.pi * D0**2)
    assert vdw_work(D0, FLAT, A, D0, FLAT_LAW) == pytest.approx(expected, rel=2 * FLAT / D0)


@pytest.mark.parametrize("theta_deg", [0, 40])
def test_flat_capillary_work_at_contact_is_ceiling_less_laplace_times_cutoff(theta_deg):
    theta = math.radians(theta_deg)
    r_k = float(kelvin_radius(0.8))
    expected = 2 * GAMMA * math.cos(theta) - GAMMA * D0 / r_k
    got = capillary_work(D0, FLAT, *water(0.8, theta))
    # a roughness FLAT shifts the work by O(FLAT/D0) relative: twice that
    assert got == pytest.approx(expected, rel=2 * FLAT / D0)


def test_flat_capillary_work_tends_to_two_gamma_as_rh_tends_to_one():
    got = capillary_work(D0, FLAT, *water(1 - 1e-7))
    # γ_L D0/r_K = 1.1e-8 J/m² at this RH: the ceiling 0.1440 J/m² to 1e-6 relative.
    assert got == pytest.approx(0.1440, rel=1e-6)


# -- against an independent quadrature -------------------------------------------------------

# (Rq, D, RH, θ): rough and smooth, near and far, wetting and not; none used to tune the rule.
CASES = [
    (0.37e-9, 0.31e-9, 0.42, 0.0),
    (1.55e-9, 2.7e-9, 0.65, math.radians(25)),
    (4.1e-9, 1.3e-9, 0.93, math.radians(60)),
    (19.4e-9, 26.9e-9, 0.88, math.radians(10)),
    (7.3e-9, 35e-9, 0.97, math.radians(5)),
    (0.9e-9, 0.15e-9, 0.75, math.radians(80)),
]


@pytest.mark.parametrize(("rq", "D", "rh", "theta"), CASES)
def test_gaussian_vdw_matches_quadrature(rq, D, rh, theta):
    assert vdw_pressure(D, rq, A, D0, FLAT_LAW) == pytest.approx(
        quad_vdw_pressure(D, rq), rel=QUAD_RTOL
    )
    assert vdw_work(D, rq, A, D0, FLAT_LAW) == pytest.approx(quad_vdw_work(D, rq), rel=QUAD_RTOL)


@pytest.mark.parametrize(("rq", "D", "rh", "theta"), CASES)
def test_gaussian_capillary_matches_quadrature(rq, D, rh, theta):
    pressure, work = quad_capillary(D, rq, rh, theta)
    assert capillary_pressure(D, rq, *water(rh, theta)) == pytest.approx(pressure, rel=QUAD_RTOL)
    assert capillary_work(D, rq, *water(rh, theta)) == pytest.approx(work, rel=QUAD_RTOL)


# -- −dW/dD = p ------------------------------------------------------------------------------

# Mean-plane gaps, at least 0.02 nm from where a histogram bin edge of
# gaussian_histogram(rq, 0.05 nm) meets the cutoff (D − z_k = D0, multiples of 0.05 nm): p'
# jumps there, and a central difference straddling the jump errs at first order.
GAPS = np.array([0.27, 0.63, 1.57, 3.11, 6.23]) * NM
# Central differences with a step of 1e-13 m: truncation (step/ℓ)²/6 <= 2e-7 for W varying
# on ℓ >= 0.1 nm (the smallest gap and Rq here); round-off ~1e-16 W/(step p) <= 1e-11.
STEP = 1e-13
DERIVATIVE_RTOL = 1e-6


def central_difference(work, D):
    return -(work(D + STEP) - work(D - STEP)) / (2 * STEP)


@pytest.mark.parametrize(
    "heights", [1.2e-9, gaussian_histogram(1.2e-9, 0.05e-9)], ids=["gaussian", "histogram"]
)
def test_minus_derivative_of_vdw_work_is_vdw_pressure(heights):
    slope = central_difference(lambda D: vdw_work(D, heights, A, D0, FLAT_LAW), GAPS)
    # DERIVATIVE_RTOL: truncation and round-off of the central difference (above)
    np.testing.assert_allclose(
        slope, vdw_pressure(GAPS, heights, A, D0, FLAT_LAW), rtol=DERIVATIVE_RTOL
    )


@pytest.mark.parametrize(
    "heights", [1.2e-9, gaussian_histogram(1.2e-9, 0.05e-9)], ids=["gaussian", "histogram"]
)
def test_minus_derivative_of_capillary_work_is_capillary_pressure(heights):
    args = water(0.85, math.radians(30))
    slope = central_difference(lambda D: capillary_work(D, heights, *args), GAPS)
    # DERIVATIVE_RTOL: the central difference's error (above)
    np.testing.assert_allclose(
        slope, capillary_pressure(GAPS, heights, *args), rtol=DERIVATIVE_RTOL
    )


# -- histogram heights -----------------------------------------------------------------------


def test_histogram_terms_are_exact_integrals_of_the_piecewise_constant_density():
    """A coarse, lopsided histogram against quad over its own density, bin by bin."""
    edges = np.array([-3.0, -1.7, -0.4, 0.05, 0.3, 1.1, 2.9]) * NM
    heights = Empirical.from_histogram(edges, [1, 3, 2, 5, 4, 1])
    z_edges, density = heights.sigma * heights.edges, heights.densities / heights.sigma
    r_k, theta = float(kelvin_radius(0.9)), math.radians(15)
    g_k = 2 * r_k * math.cos(theta)

    def expect(f, D):
        pieces = zip(z_edges[:-1], z_edges[1:], density)
        return sum(
            c * integrate.quad(f, lo, hi, args=(D,), points=[D - D0, D - g_k], epsrel=1e-13)[0]
            for lo, hi, c in pieces
        )

    for D in np.array([-0.5, 0.35, 1.2, 2.4]) * NM:
        p_vdw = A / (6 * math.pi) * expect(lambda z, D: (D - z) ** -3 * (D - z >= D0), D)
        w_vdw = A / (12 * math.pi) * expect(lambda z, D: max(D - z, D0) ** -2, D)
        p_cap = GAMMA / r_k * expect(lambda z, D: float(D0 <= D - z < g_k), D)
        w_cap = GAMMA / r_k * expect(lambda z, D: max(g_k - max(D - z, D0), 0.0), D)
        args = water(0.9, theta)
        assert vdw_pressure(D, heights, A, D0, FLAT_LAW) == pytest.approx(p_vdw, rel=QUAD_RTOL)
        assert vdw_work(D, heights, A, D0, FLAT_LAW) == pytest.approx(w_vdw, rel=QUAD_RTOL)
        assert capillary_pressure(D, heights, *args) == pytest.approx(p_cap, rel=QUAD_RTOL)
        assert capillary_work(D, heights, *args) == pytest.approx(w_cap, rel=QUAD_RTOL)


def test_fine_histogram_of_a_gaussian_converges_to_the_gaussian():
    """Binning error at bin width w: the piecewise-constant density errs by O((w/Rq)²) over
    whole bins, and by O(w/Rq) over the one bin cut at the cutoff, where an integrand such as
    g⁻³ holds its mass within ~D0: relative error below w²/(D0 Rq) (3.3e-4 at w = 0.01 nm)."""
    rq, args = 1.5e-9, water(0.8, math.radians(20))
    terms = {
        "p_vdw": lambda h: vdw_pressure(GAPS, h, A, D0, FLAT_LAW),
        "w_vdw": lambda h: vdw_work(GAPS, h, A, D0, FLAT_LAW),
        "p_cap": lambda h: capillary_pressure(GAPS, h, *args),
        "w_cap": lambda h: capillary_work(GAPS, h, *args),
    }
    for name, term in terms.items():
        exact = term(rq)
        errors = [
            np.max(np.abs(term(gaussian_histogram(rq, w)) / exact - 1))
            for w in (0.02e-9, 0.01e-9, 0.005e-9)
        ]
        assert errors[1] < (0.01e-9) ** 2 / (D0 * rq), name
        assert errors[0] > errors[1] > errors[2], name


# -- bounds and monotonicity -----------------------------------------------------------------


def test_capillary_work_rises_with_rh_and_stays_below_two_gamma_cos_theta():
    rh = np.linspace(0.05, 0.995, 200)
    theta = math.radians(30)
    for rq in (0.5e-9, 2e-9, 20e-9):
        work = capillary_work(D0 + rq, rq, *water(rh, theta))
        assert np.all(np.diff(work) >= 0)
        assert np.all(work[-20:] > 0)
        assert np.all(work <= 2 * GAMMA * math.cos(theta))


def test_vdw_work_falls_with_roughness_and_stays_below_flat_contact():
    rq = np.geomspace(0.01e-9, 50e-9, 100)
    for rms_from_contact in (0.0, 1.0, 2.5):
        work = vdw_work(D0 + rms_from_contact * rq, rq, A, D0, FLAT_LAW)
        assert np.all(np.diff(work) < 0)
        assert np.all(work <= A / (12 * math.pi * D0**2))


def test_works_broadcast_over_gap_and_humidity():
    D = np.array([0.3, 1.0, 4.0])[:, None] * NM
    rh = np.array([0.2, 0.6, 0.9])
    grid = capillary_work(D, 1.5e-9, *water(rh))
    one_by_one = [[capillary_work(d, 1.5e-9, *water(r)) for r in rh] for d in D[:, 0]]
    np.testing.assert_array_equal(grid, np.array(one_by_one))


# -- terms switched off ----------------------------------------------------------------------


def test_contact_angle_of_90_degrees_or_more_condenses_nothing():
    for theta_deg in (90, 120):
        env = Environment(rh=0.9, contact_angle=math.radians(theta_deg))
        assert not env.has_capillary
        assert "contact angle" in env.no_condensation_reason
        assert capillary_work(D0, 1e-9, *water(0.9, math.radians(theta_deg))) == 0


def test_dry_vapour_condenses_nothing():
    env = Environment(hamaker=A)
    assert env.is_dry and not env.has_capillary and env.has_vdw
    assert "dry" in env.no_condensation_reason
    assert environment_works(np.float64(0.0), SURFACES["smooth"], env)["capillary"] == 0
    assert capillary_work(D0, 1e-9, *water(0.0)) == 0


def test_zero_hamaker_gives_no_vdw():
    env = Environment(hamaker=0.0, rh=0.5)
    assert not env.has_vdw and env.active
    curves = environment_curves(np.linspace(-1, 3, 5), SURFACES["smooth"], env)
    assert np.all(curves["vdw"] == 0) and np.all(curves["capillary"] > 0)


def test_default_environment_is_inactive():
    env = Environment()
    assert not env.active and env.cutoff == DEFAULT_CUTOFF


def test_the_attraction_measures_the_gap_from_the_mean_plane():
    """The GW separation d is from the mean summit plane, y_s above the mean plane: the
    whole surface's attraction is the proximity model at D = hσ + y_s with the cutoff D0,
    which the caps and the open gaps share."""
    surface = dataclasses.replace(SURFACES["smooth"], rq=1.55e-9, summit_offset=1.59e-9)
    env = Environment(hamaker=A, cutoff=D0, rh=0.7)
    h = np.array([-0.5, 0.0, 2.0])
    curves = environment_curves(h, surface, env)
    D = h * surface.sigma + 1.59e-9
    np.testing.assert_array_equal(curves["vdw"], vdw_pressure(D, 1.55e-9, A, D0, env.retardation))
    np.testing.assert_array_equal(curves["vdw_gaps"], curves["vdw"] - curves["vdw_caps"])


# -- validation messages ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("field", "value", "match"),
    [
        ("rh", 1.0, r"rh = 1\.0 is out of range \(allowed: \[0, 1\)\)"),
        ("rh", -0.1, r"rh = -0\.1 is out of range"),
        ("hamaker", -1e-20, r"hamaker = -1e-20 J is out of range \(allowed: \[0, 1e-16\] J\)"),
        ("cutoff", 0.0, r"cutoff = 0\.0 m is out of range \(allowed: > 0 m\)"),
        (
            "contact_angle",
            math.pi,
            r"contact_angle = 3\.14\d* rad is out of range \(allowed: \[0, 3\.14",
        ),
        ("contact_angle", -0.1, r"contact_angle = -0\.1 rad is out of range"),
        ("temperature", 0.0, r"temperature = 0\.0 K is out of range \(allowed: > 0 K\)"),
        ("surface_tension", -0.07, r"surface_tension = -0\.07 J/m\^2 is out of range"),
        ("molar_volume", 0.0, r"molar_volume = 0\.0 m\^3/mol is out of range"),
        ("rh", float("nan"), r"rh = nan is out of range"),
    ],
)
def test_out_of_range_field_is_refused_with_its_name_value_and_range(field, value, match):
    with pytest.raises(ParameterError, match=match):
        Environment(**{field: value})


def test_from_user_reads_degrees_and_units():
    env = Environment.from_user(hamaker=1.6e-19, cutoff="0.2 nm", rh="0.6", contact_angle=20,
                                surface_tension="72 mJ/m^2")  # fmt: skip
    assert env.contact_angle == pytest.approx(math.radians(20), rel=ROUNDING_FEW)
    assert env.cutoff == pytest.approx(0.2e-9, rel=ROUNDING_FEW)
    assert env.surface_tension == pytest.approx(0.072, rel=ROUNDING_FEW)
    assert env.rh == 0.6


def test_from_user_refuses_angle_outside_0_to_180_degrees():
    with pytest.raises(ParameterError, match=r"contact_angle = 180\.0 deg is out of range"):
        Environment.from_user(contact_angle=180)


def test_from_user_refuses_a_length_unit_for_the_cutoff_of_another_dimension():
    with pytest.raises(UnitError, match="cutoff"):
        Environment.from_user(cutoff="0.2 GPa")
