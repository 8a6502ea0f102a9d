"""The environment acts where the summits are: each summit's cap, and the open gaps between.

Specification (docs/physics.md, section 'The environment: summits and open gaps'): a summit's
cap owns the local gaps D0 <= u < u_c, the open gaps between the caps own u >= u_c over the
surface's heights; gaps below D0 are contact and charged nothing. Checked here: the
sphere–flat limits of one summit, −dW/dd = F for every part, the flat limits of the open
gaps, and that no area is counted twice (nor lost) against an independent integral over the
area each part owns.
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
from mcsim.physics.environment import MIN_KELVIN_RADIUS, Environment
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
    environment_works,
    open_gap_pressures,
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
    env = HUMID  # g_K = 9.92 nm
    g_k, laplace = env.condensation_gap, env.laplace_pressure
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
    slope = -central(lambda x: environment_works(x, surface, HUMID)[part], h, step)
    pressure = environment_curves(h, surface, HUMID)[part]
    # the works are O(1e-2 J/m²) and the differences cancel to ~1e-16/1e-5 of them:
    # an absolute bound of 1e-10 of the largest pressure times σ/step covers that rounding
    np.testing.assert_allclose(slope / surface.sigma, pressure, rtol=1e-7,
                               atol=1e-9 * np.max(np.abs(pressure)) + 1e-9)  # fmt: skip


def test_the_open_gaps_of_a_flat_pair_are_the_flat_flat_laws():
    flat = dataclasses.replace(SURFACES["smooth"], rq=1e-12, summit_offset=0.0)
    # heights of rms 1 pm: E[(D − z)⁻³] = D⁻³ (1 + 6 Rq²/D² + ...), 6e-6 at D = 1 nm
    u_c = band_edge(flat.R, flat.eta, HUMID)
    sigma = flat.sigma
    for gap in (u_c * 1.01, 2 * u_c, 30e-9):
        p = open_gap_pressures(np.float64(gap / sigma), flat, HUMID)
        assert p["vdw"] == pytest.approx(retarded_pressure(gap), rel=1e-5)
        inside = HUMID.condensation_gap > gap  # every gap here lies ≫ 1 pm from g_K
        assert p["capillary"] == pytest.approx(HUMID.laplace_pressure * inside, rel=1e-12)
    # nearer than u_c the flat is the caps' alone: nothing charged to the open gaps
    p = open_gap_pressures(np.float64(0.5 * u_c / sigma), flat, HUMID)
    assert p["vdw"] == 0 and p["capillary"] == 0


def retarded_pressure(u, b=B):
    """Gregory's flats (1981), −d/du of A/(12π u²(1 + b u)), written out here."""
    return A / (12 * math.pi) * (2 / (u**3 * (1 + b * u)) + b / (u**2 * (1 + b * u) ** 2))


def owned_area_integral(h, surface, env, kernel):
    """∫ kernel(u) ρ(u) du over open local gaps u >= D0, with ρ the area per nominal area that
    each part owns at local gap u, computed here independently of the package:
    caps (u < u_c): η 2πR P(summit gap <= u) = η 2πR Q(h − u/σ);
    open gaps (u >= u_c): the surface's height density at z = D − u (Gaussian, rms Rq)."""
    from scipy import stats

    sigma, gap = surface.sigma, gap_heights(surface)
    u_c = band_edge(surface.R, surface.eta, env)
    D = h * sigma + gap.summit_offset

    def caps(u):
        return surface.eta * 2 * math.pi * surface.R * stats.norm.sf(h - u / sigma) * kernel(u)

    def gaps(u):
        return stats.norm.pdf((D - u) / gap.rq) / gap.rq * kernel(u)

    steps = env.cutoff * (u_c / env.cutoff) ** np.linspace(0, 1, 17)
    cap_part = sum(integrate.quad(caps, a, b, epsabs=0, epsrel=1e-12, limit=200)[0]
                   for a, b in itertools.pairwise(steps))  # fmt: skip
    top = max(D, u_c) + 40 * gap.rq
    gap_part = integrate.quad(gaps, u_c, top, points=[D] if u_c < D < top else None, epsabs=0,
                              epsrel=1e-12, limit=400)[0]  # fmt: skip
    return cap_part + gap_part


@pytest.mark.parametrize("name", ["smooth", "super-smooth", "intermediate"])
@pytest.mark.parametrize("h", [-1.0, 0.5, 2.5])
def test_no_area_is_counted_twice_nor_lost(name, h):
    """Each term is its local law integrated once over the area each part owns: the menisci
    (γ_L/r_K on D0 <= u < g_K) and van der Waals (retarded A/(6πu³)). Charging the open gaps from D0
    instead of u_c (the area nearer the flat counted by caps and gaps both) fails this."""
    surface, env = SURFACES[name], HUMID
    g_k = env.condensation_gap
    got = environment_curves(np.float64(h), surface, env)
    wetted = owned_area_integral(h, surface, env, lambda u: (u < g_k) * 1.0)
    assert got["capillary"] == pytest.approx(env.laplace_pressure * wetted, rel=1e-8)
    vdw = owned_area_integral(h, surface, env, retarded_pressure)
    assert got["vdw"] == pytest.approx(vdw, rel=1e-8)


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
    ("rh", "meniscus"), [(0.30, False), (0.34, False), (0.36, True), (0.9, True)]
)
def test_no_continuum_meniscus_below_a_kelvin_radius_of_half_a_nanometre(rh, meniscus):
    env = Environment(rh=rh)
    assert (env.kelvin_radius >= MIN_KELVIN_RADIUS) == meniscus
    assert env.has_capillary == meniscus
    if not meniscus:
        assert "Kelvin radius" in env.no_condensation_reason
        curves = environment_curves(np.array([0.0, 1.0]), SURFACES["smooth"], env)
        assert np.all(curves["capillary"] == 0)
