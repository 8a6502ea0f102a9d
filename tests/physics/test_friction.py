"""Per-summit static friction (issue 42): which law each law set takes, Savkoor–Briggs of a JKR
summit's own load, and the GW expectation against an independent quadrature."""

import dataclasses

import numpy as np
import pytest
from scipy import integrate, optimize, stats
from tolerances import QUAD_RTOL, ROUNDING_FEW, ROUNDING_FORMULA

from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.physics.friction import (
    friction_rule,
    gw_static_friction,
    has_friction,
    savkoor_briggs,
    summit_friction,
)
from mcsim.physics.laws import LawSet, Output, get_law_set, jkr, seed

SILICON = MATERIALS["silicon"]
SMOOTH = SURFACES["smooth"]
TAU = dataclasses.replace(SILICON, tau=1e8)
H = np.array([-1.0, 0.0, 1.0, 2.0, 3.0])


def test_savkoor_briggs_is_the_seeds_eq_6_of_a_load_and_vanishes_at_the_jkr_pull_off():
    R, K, G, w = SMOOTH.R, SILICON.K, SILICON.G, SILICON.gamma
    delta = np.array([1e-11, 1e-10, 1e-9])
    hertz = seed.hertz_load(delta, R, K)
    assert savkoor_briggs(hertz, R, K, G, w) == pytest.approx(
        seed.savkoor_briggs_friction(delta, R, K, G, w), rel=ROUNDING_FORMULA
    )
    c = np.pi * w * R
    assert savkoor_briggs(-1.5 * c, R, K, G, w) == 0.0  # the JKR pull-off: nothing to peel
    assert savkoor_briggs(-2 * c, R, K, G, w) == 0.0  # below it: no contact, no friction
    assert savkoor_briggs(0.0, R, K, G, w) == pytest.approx(
        4 * np.sqrt(G / K) * np.sqrt(3) * c, rel=ROUNDING_FEW
    )


@pytest.mark.parametrize(
    "law, material, rule",
    [("seed", SILICON, "savkoor-briggs"), ("jkr", SILICON, "savkoor-briggs"),
     ("jkr", TAU, "shear"), ("dmt", TAU, "shear"), ("maugis-dugdale", TAU, "shear"),
     ("elastic-plastic", TAU, "shear")],
)  # fmt: skip
def test_each_law_set_takes_savkoor_briggs_or_tau_times_area(law, material, rule):
    assert friction_rule(law, material) == rule and has_friction(law, material)


@pytest.mark.parametrize("law", ["dmt", "maugis-dugdale", "elastic-plastic"])
def test_a_law_set_without_tau_has_no_friction_and_the_error_names_those_that_have(law):
    assert not has_friction(law, SILICON)
    with pytest.raises(ParameterError) as err:
        friction_rule(law, SILICON)
    message = str(err.value)
    assert "\n" not in message and "tau" in message and f"{law!r}" in message
    for name in ("seed", "jkr", "dmt", "maugis-dugdale", "elastic-plastic"):
        assert name in message


def test_a_law_set_without_a_friction_flag_has_none_at_all():
    toy = LawSet("toy", "no friction", (Output("load", "N", seed.hertz_load),))
    with pytest.raises(ParameterError, match="'toy' has no friction at all"):
        friction_rule(toy, TAU)


@pytest.mark.parametrize("tau", [0.0, -1e6, float("nan")])
def test_a_shear_strength_at_or_below_zero_is_refused_naming_tau(tau):
    with pytest.raises(ParameterError, match="tau"):
        dataclasses.replace(SILICON, tau=tau)


def test_jkr_summit_friction_is_savkoor_briggs_of_its_own_jkr_load_where_it_touches():
    law = get_law_set("jkr")
    params = law.parameters(SMOOTH, SILICON)
    delta = np.array([-1e-9, 0.0, 1e-11, 2e-10, 1e-9])  # out, at the edge (no contact), in
    load = jkr.jkr_load(delta, delta, *(params[p] for p in law.outputs[0].parameter_names))
    expected = np.where(delta > 0, savkoor_briggs(load, SMOOTH.R, SILICON.K, SILICON.G, 0.5), 0)
    assert np.array_equal(summit_friction(law, params, delta, "savkoor-briggs"), expected)
    # at jump-in the summit carries −(4/3)πwR, above the pull-off: it has friction
    assert summit_friction(law, params, np.array([1e-15]), "savkoor-briggs")[0] > 0


def test_shear_friction_is_tau_times_the_law_sets_area():
    for name in ("jkr", "dmt"):
        law = get_law_set(name)
        params = law.parameters(SMOOTH, TAU)
        delta = np.array([-1e-10, 1e-11, 1e-9])
        area = law.evaluate(delta, SMOOTH, TAU)["area"]
        assert np.array_equal(summit_friction(law, params, delta, "shear"), 1e8 * area)


def test_gw_friction_of_the_seed_and_of_tau_area_is_the_curve_gw_curves_already_gives():
    assert gw_static_friction(SMOOTH, SILICON, H, "seed") == pytest.approx(
        gw_curves(SMOOTH, SILICON, H, "seed").T, rel=ROUNDING_FEW
    )
    for law in ("jkr", "dmt", "maugis-dugdale", "elastic-plastic"):
        assert gw_static_friction(SMOOTH, TAU, H, law) == pytest.approx(
            gw_curves(SMOOTH, TAU, H, law).friction, rel=ROUNDING_FORMULA
        ), law


def test_gw_savkoor_briggs_friction_of_jkr_summits_against_an_independent_quadrature():
    # (η/K) ∫_h^∞ T(P_jkr(σ(s − h))) φ(s) ds, P_jkr through the contact radius a (the
    # law's own inversion not used): δ(a) = a²/R − √(2πwa/E*), P(a) = 4E*a³/(3R) − √(8πwE*a³)
    R, E, K, G, w = SMOOTH.R, SILICON.E_star, SILICON.K, SILICON.G, SILICON.gamma
    sigma, eta = SMOOTH.sigma, SMOOTH.eta
    a_jump = (2 * np.pi * w * R**2 / E) ** (1 / 3)  # δ = 0 on the stable branch

    def friction_at(delta):
        def f(a):
            return a * a / R - np.sqrt(2 * np.pi * w * a / E) - delta

        a = optimize.brentq(f, a_jump, 1e-3, xtol=1e-30, rtol=1e-15)
        load = 4 * E * a**3 / (3 * R) - np.sqrt(8 * np.pi * w * E * a**3)
        return 4 * np.sqrt(G / K) * np.sqrt(2 * np.pi * w * R * load + 3 * (np.pi * w * R) ** 2)

    for h in (0.0, 1.5):
        value = integrate.quad(lambda s, h=h: friction_at(sigma * (s - h)) * stats.norm.pdf(s),
                               h, h + 12, epsabs=0, epsrel=1e-12, limit=200)[0]  # fmt: skip
        assert gw_static_friction(SMOOTH, SILICON, [h], "jkr")[0] == pytest.approx(
            eta / K * value, rel=QUAD_RTOL
        ), h


def test_a_radius_by_height_sums_its_bands():
    from mcsim.model.params import RadiusByHeight

    bands = RadiusByHeight(edges=(-1.0, 1.0, 3.0), factors=(1.0, 0.5))
    surface = dataclasses.replace(SMOOTH, radius_by_height=bands)
    total = sum(gw_static_friction(part, SILICON, H, "jkr") for part in surface.components())
    assert gw_static_friction(surface, SILICON, H, "jkr") == pytest.approx(total, rel=ROUNDING_FEW)
