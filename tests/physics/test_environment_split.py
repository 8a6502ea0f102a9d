"""The environment acts where the summits are: each summit's cap, and the open gaps between.

Specification (docs/physics.md, sections 'The environment: summits and open gaps' and 'The
environment covers the surface once'): the whole surface's attraction is the proximity model
over its own heights, each local gap u >= D0 once (gaps below D0 are contact and charged
nothing); a summit's cap owns the local gaps D0 <= u < u_c of its paraboloid, the open gaps
the rest. Checked here: the sphere–flat limits of one summit, −dW/dd = F for every part, the
flat limits, and the areas against independent integrals over the surface's own heights.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest
from scipy import integrate
from tolerances import ROUNDING_FORMULA

from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import gap_heights
from mcsim.physics.laws import get_law_set
from mcsim.physics.laws.attraction import (
    capillary_summit,
    capillary_summit_work,
    vdw_summit,
    vdw_summit_work,
)
from mcsim.physics.surfaceenvironment import (
    band_edge,
    environment_curves,
    environment_warnings,
    environment_works,
    summit_parameters,
    with_environment,
)

A, D0, R = 1.6e-19, 0.2e-9, 0.5e-6
GAMMA = 0.072
HUMID = Environment(hamaker=A, cutoff=D0, rh=0.9)
B = HUMID.retardation  # m⁻¹: 5.32/λ, Gregory 1981 (λ = 100 nm, the default)
#: Central differences with a step of 1e-6 of the scale: truncation ~1e-12, rounding
#: ~1e-16/1e-6 = 1e-10 of the value (the works are O(F × scale)).
DERIVATIVE_RTOL = 1e-7


def central(f, x, step):
    return (f(x + step) - f(x - step)) / (2 * step)


# -- one summit ----------------------------------------------------------------------------


@pytest.mark.parametrize("g", [D0, 0.5e-9, 2e-9, 10e-9])
def test_one_summit_van_der_waals_is_the_sphere_flat_force_without_a_band_edge(g):
    # non-retarded (b = 0): Israelachvili Eq. 13.11 with Table 13.1, F = A R / (6 D²);
    # retarded: tests/physics/test_environment_retarded.py
    got = vdw_summit(np.float64(-g), A, R, D0, 1e30, 0.0)
    assert got == pytest.approx(A * R / (6 * g**2), rel=ROUNDING_FORMULA)


@pytest.mark.parametrize("g", [D0, 1e-9, 3e-9, 9e-9])
def test_one_summit_meniscus_is_the_classic_sphere_flat_meniscus(g):
    # no film (t = 0): the wet floor is D0 and g_K = 2 r_K cos θ = 9.92 nm
    env = dataclasses.replace(HUMID, film_thickness=0.0, structured_film=0.0)
    g_k, laplace = env.condensation_gap, env.laplace_pressure
    assert env.wet_floor == D0
    got = capillary_summit(np.float64(-g), laplace, R, D0, g_k)
    expected = 4 * math.pi * R * GAMMA * math.cos(env.contact_angle) * (1 - g / g_k)
    assert got == pytest.approx(expected, rel=ROUNDING_FORMULA)


def test_a_pressed_summit_keeps_its_touch_values_and_a_far_one_feels_nothing():
    g_k, laplace, u_c = HUMID.condensation_gap, HUMID.laplace_pressure, 20e-9
    pressed = np.array([1e-9, 5e-9, 1e-7])  # δ > 0
    np.testing.assert_array_equal(
        vdw_summit(pressed, A, R, D0, u_c, B), vdw_summit(-D0, A, R, D0, u_c, B)
    )
    np.testing.assert_array_equal(capillary_summit(pressed, laplace, R, D0, g_k),
                                  capillary_summit(-D0, laplace, R, D0, g_k))  # fmt: skip
    assert vdw_summit(np.float64(-u_c), A, R, D0, u_c, B) == 0
    assert vdw_summit(np.float64(-2 * u_c), A, R, D0, u_c, B) == 0
    assert capillary_summit(np.float64(-g_k), laplace, R, D0, g_k) == 0
    assert capillary_summit(np.float64(-2 * g_k), laplace, R, D0, g_k) == 0


@pytest.mark.parametrize("b", [0.0, B, 100 * B], ids=["non-retarded", "100nm", "1nm"])
@pytest.mark.parametrize("g", [-5e-9, -0.1e-9, 0.1e-9, 0.3e-9, 2e-9, 8e-9, 15e-9])
def test_one_summit_minus_work_slope_is_its_force(g, b):
    u_c, g_k, laplace = 12e-9, HUMID.condensation_gap, HUMID.laplace_pressure
    step = 1e-6 * u_c
    # d = z − δ: dW/dd = −dW/dδ, so −dW/dd = dW/dδ at δ = −g
    slope = central(lambda x: vdw_summit_work(x, A, R, D0, u_c, b), -g, step)
    force = vdw_summit(np.float64(-g), A, R, D0, u_c, b)
    assert slope == pytest.approx(force, rel=DERIVATIVE_RTOL)
    slope = central(lambda x: capillary_summit_work(x, laplace, R, D0, g_k), -g, step)
    expected = capillary_summit(np.float64(-g), laplace, R, D0, g_k)
    assert slope == pytest.approx(expected, rel=DERIVATIVE_RTOL, abs=DERIVATIVE_RTOL * 1e-6)


# -- the surface: caps and open gaps ---------------------------------------------------------


@pytest.mark.parametrize("name", ["smooth", "intermediate", "rough", "super-smooth"])
@pytest.mark.parametrize("part", ["vdw_caps", "vdw_gaps", "capillary_caps", "capillary_gaps"])
def test_every_part_of_the_attraction_is_minus_the_slope_of_its_work(name, part):
    surface = SURFACES[name]
    h = np.linspace(-1.0, 4.0, 11)
    step = 1e-5
    works = environment_works(h, surface, HUMID)[part]
    slope = -central(lambda x: environment_works(x, surface, HUMID)[part], h, step)
    pressure = environment_curves(h, surface, HUMID)[part]
    # the works are O(1e-2 J/m²) and the differences cancel to ~1e-16/1e-5 of them:
    # an absolute bound of 1e-10 of the largest pressure times σ/step covers that rounding,
    # and a few ε of the largest work over the step σ·2e-5 where the work is mostly pressed
    # area, whose pressure is small (the open gaps of super-smooth, beneath its 2t = 3.6 nm)
    rounding = 10 * np.finfo(float).eps * np.max(works) / (step * surface.sigma)
    np.testing.assert_allclose(slope / surface.sigma, pressure, rtol=1e-7,
                               atol=1e-9 * np.max(np.abs(pressure)) + 1e-9 + rounding)  # fmt: skip


def test_a_flat_pair_attracts_with_the_flat_flat_laws():
    flat = dataclasses.replace(SURFACES["smooth"], rq=1e-12, summit_offset=0.0)
    # heights of rms 1 pm: E[(D − z)⁻³] = D⁻³ (1 + 6 Rq²/D² + ...), 6e-6 at D = 1 nm
    u_c = band_edge(flat.R, flat.eta, HUMID)
    for gap in (0.5 * u_c, u_c * 1.01, 2 * u_c, 30e-9):
        p = environment_curves(np.float64(gap / flat.sigma), flat, HUMID)
        assert p["vdw"] == pytest.approx(retarded_pressure(gap), rel=1e-5)
        # menisci between the films: wet floor 2t <= gap < g_K (every gap here ≫ 1 pm from both)
        inside = HUMID.wet_floor <= gap < HUMID.condensation_gap
        assert p["capillary"] == pytest.approx(HUMID.laplace_pressure * inside, rel=1e-12)


def retarded_pressure(u, b=B):
    """Gregory's flats (1981), −d/du of A/(12π u²(1 + b u)), written out here."""
    return A / (12 * math.pi) * (2 / (u**3 * (1 + b * u)) + b / (u**2 * (1 + b * u) ** 2))


def surface_integral(h, surface, kernel, lo, hi=None):
    """∫ kernel(u) f(u) du over local gaps lo <= u < hi, f the density of the surface's own
    gaps u = D − z (z its Gaussian heights about the mean plane, rms Rq), independently of
    the package: the area of the surface at each local gap, each once."""
    from scipy import stats

    gap = gap_heights(surface)
    D = h * surface.sigma + gap.summit_offset
    hi = max(D, lo) + 40 * gap.rq if hi is None else hi

    def density(u):
        return stats.norm.pdf((D - u) / gap.rq) / gap.rq * kernel(u)

    inner = [D] if lo < D < hi else None
    return integrate.quad(density, lo, hi, points=inner, epsabs=0, epsrel=1e-12, limit=400)[0]


def caps_integral(h, surface, env, kernel):
    """∫ kernel(u) c(u) du over D0 <= u < u_c, c(u) = η 2πR P(summit gap <= u) =
    η 2πR Q(h − u/σ) the area the summits' caps own at local gap u (independently)."""
    from scipy import stats

    sigma, u_c = surface.sigma, band_edge(surface.R, surface.eta, env)

    def caps(u):
        return surface.eta * 2 * math.pi * surface.R * stats.norm.sf(h - u / sigma) * kernel(u)

    steps = env.cutoff * (u_c / env.cutoff) ** np.linspace(0, 1, 17)
    return sum(integrate.quad(caps, a, b, epsabs=0, epsrel=1e-12, limit=200)[0]
               for a, b in itertools.pairwise(steps))  # fmt: skip


@pytest.mark.parametrize("name", ["smooth", "super-smooth", "intermediate"])
@pytest.mark.parametrize("h", [-1.0, 0.5, 2.5])
def test_the_environment_covers_the_surface_once(name, h):
    """Each term is its local law integrated once over the surface's own gaps: the menisci
    (γ_L/r_K on f = max(D0, 2t) <= u < g_K, t the adsorbed film) and van der Waals
    (Gregory's retarded flats on u >= D0). The caps own their
    summits' paraboloids, the open gaps the rest; the caps' part is checked on its own."""
    surface, env = SURFACES[name], HUMID
    got = environment_curves(np.float64(h), surface, env)
    floor = max(env.cutoff, 2 * env.film)
    wetted = surface_integral(h, surface, lambda u: 1.0, floor, env.condensation_gap)
    assert got["capillary"] == pytest.approx(env.laplace_pressure * wetted, rel=1e-8)
    vdw = surface_integral(h, surface, retarded_pressure, D0)
    assert got["vdw"] == pytest.approx(vdw, rel=1e-8)
    caps = caps_integral(h, surface, env, retarded_pressure)
    assert got["vdw_caps"] == pytest.approx(caps, rel=1e-8)
    assert got["vdw_caps"] + got["vdw_gaps"] == pytest.approx(got["vdw"], rel=1e-14)


@pytest.mark.parametrize("name", ["smooth", "intermediate", "rough"])
def test_the_areas_of_contact_and_of_every_gap_band_partition_the_surface(name):
    """With g_K swept, the wetted area at each separation is the surface's own area at local
    gaps f <= u < g_K (f = max(D0, 2t), the films' wet floor); with contact (u < D0) and the
    pressed films (D0 <= u < f) that is all of the surface at g_K → ∞."""
    from scipy import stats

    surface = SURFACES[name]
    gap = gap_heights(surface)
    for h in (-1.0, 0.0, 1.0, 2.5):
        D = h * surface.sigma + gap.summit_offset
        contact = stats.norm.sf((D - D0) / gap.rq)
        for rh in (0.5, 0.9, 0.99, 0.9999999):
            env = Environment(cutoff=D0, rh=rh)
            wetted = environment_curves(np.float64(h), surface, env)["capillary"]
            wetted = wetted / env.laplace_pressure
            pressed = stats.norm.sf((D - env.wet_floor) / gap.rq) - contact
            below = stats.norm.sf((D - env.condensation_gap) / gap.rq)
            assert contact + pressed + wetted == pytest.approx(below, rel=1e-12, abs=1e-15)
        # at RH 1 − 1e-7, g_K ≈ 10 mm: every gap is wetted, pressed or in contact
        assert contact + pressed + wetted == pytest.approx(1, rel=1e-12)


@pytest.mark.parametrize("name", ["smooth", "intermediate", "rough", "super-smooth"])
@pytest.mark.parametrize("rh", [0.5, 0.9, 0.99])
def test_the_capillary_work_never_exceeds_two_gamma_cos_theta(name, rh):
    env = Environment(rh=rh, contact_angle=math.radians(20))
    works = environment_works(np.linspace(-4.0, 6.0, 41), SURFACES[name], env)["capillary"]
    # (γ_L/r_K)(g_K − f) = 2γ_L cos θ once the films' floor 2t passes D0: reached, not passed
    ceiling = 2 * env.surface_tension * math.cos(env.contact_angle)
    band = env.laplace_pressure * (env.condensation_gap - env.wet_floor)
    assert band <= ceiling * (1 + 1e-15)
    assert works.max() <= band * (1 + 1e-12)


def test_the_caps_own_at_most_their_summits_share_of_the_area():
    for surface in SURFACES.values():
        u_c = band_edge(surface.R, surface.eta, HUMID)
        # a pressed cap's open area 2πR(u_c − D0) is exactly 1/η
        assert 2 * math.pi * surface.R * (u_c - D0) * surface.eta == pytest.approx(1, rel=1e-14)


def test_the_law_set_with_an_environment_appends_the_caps_and_reaches_down_to_the_band_edge():
    surface, material = SURFACES["smooth"], MATERIALS["silicon"]
    law = with_environment(get_law_set("jkr"), HUMID)
    assert law.names == ("load", "area", "vdw", "capillary")
    params = summit_parameters(surface, HUMID)
    assert law.edges_for(surface, material).reach == -params["band"]
    assert with_environment(get_law_set("jkr"), Environment()) is get_law_set("jkr")
    z = np.array([3e-9])
    d = np.array([1e-9, 4e-9])
    values = law.evaluate(z - d, surface, material)
    np.testing.assert_array_equal(
        values["vdw"], vdw_summit(z - d, A, surface.R, D0, params["band"], B)
    )


# -- inputs that describe one interface: tests/physics/test_one_interface.py ------------------


@pytest.mark.parametrize(
    ("rh", "meniscus"), [(0.20, False), (0.30, False), (0.31, True), (0.34, True), (0.9, True)]
)
def test_no_meniscus_until_the_film_is_thicker_than_its_structured_layers(rh, meniscus):
    """The Kelvin gate (r_K >= 0.5 nm, RH >= 0.35) gave way to the adsorbed films: bridges form
    above RH_dry = 0.30, where the film exceeds its ice-like 3 layers (tests/physics/test_films.py)."""
    env = Environment(rh=rh)
    assert (env.film > env.structured_film) == meniscus
    assert env.has_capillary == meniscus
    curves = environment_curves(np.array([0.0, 1.0]), SURFACES["smooth"], env)
    if not meniscus:
        assert "structured film" in env.no_condensation_reason
        assert np.all(curves["capillary"] == 0)
    else:
        assert np.all(curves["capillary"] > 0)


# -- where the model leaves its ground -----------------------------------------------------


def test_warnings_name_caps_deeper_than_the_summits_and_merged_menisci():
    smooth = SURFACES["smooth"]  # 1/(2πRη) = 5.5 nm > 3σ = 4.2 nm
    dry = environment_warnings(smooth, Environment(hamaker=A, cutoff=D0))
    assert len(dry) == 1 and "deeper than 3 sigma" in dry[0]
    shallow = dataclasses.replace(smooth, sigma=3e-9)  # 3σ = 9 nm > 5.5 nm
    assert environment_warnings(shallow, Environment(hamaker=A, cutoff=D0)) == []
    u_c = band_edge(shallow.R, shallow.eta, HUMID)
    assert HUMID.condensation_gap > u_c  # RH 0.9: g_K = 9.9 nm
    (merged,) = environment_warnings(shallow, HUMID)
    assert "menisci merge" in merged and f"{u_c * 1e9:.3g} nm" in merged
    assert environment_warnings(shallow, Environment(cutoff=D0, rh=0.5)) == []
    assert environment_warnings(smooth, None) == [] == environment_warnings(smooth, Environment())
