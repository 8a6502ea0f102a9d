"""A pad's static friction at its own turn (issue 42, mcsim.engine.pads.friction): a pad of
identical summits reproduces the single-summit law; the normal load of μ_s."""

import dataclasses
import math

import numpy as np
import pytest

from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import friction as padfriction
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment

SILICON = MATERIALS["silicon"]
SMOOTH = SURFACES["smooth"]
H = np.linspace(4.0, -3.0, 8)
#: Relative accuracy of the loads at a turn bisected to XTOL = 1e-7 in h (a summit's load
#: changes by ~1e-6 of itself over it).
TURN_RTOL = 1e-5


def spec_of(material=SILICON, law="jkr", environment=None, surface=SMOOTH, pads=3):
    return MonteCarloSpec(surface, material, H, 30e-12, pads, 5, law, cycle=True,
                          environment=environment)  # fmt: skip


@pytest.mark.parametrize("force", [1e-6, 3e-5, 1e-3])
def test_identical_jkr_summits_under_force_control_carry_savkoor_briggs_of_their_share(force):
    # N equal summits pressed with F turn where each carries F/N: T_s = N T_a(F/N), T_a the
    # seed's Eq. 6 of a summit's normal load, written out here
    spec, n = spec_of(), 40
    z = np.full(n, 1.0 * SMOOTH.sigma)
    d_turn, _ = padcurves.force_turn(spec, z, force)
    c = np.pi * SILICON.gamma * SMOOTH.R
    single = 4 * math.sqrt(SILICON.G / SILICON.K) * math.sqrt(2 * c * force / n + 3 * c * c)
    assert padfriction.static_friction(spec, z, d_turn) == pytest.approx(n * single, rel=TURN_RTOL)


def test_identical_dmt_summits_with_tau_carry_tau_times_their_hertz_area():
    # DMT in contact: K R^½ δ^{3/2} − 2πwR = F/N, area πRδ (Derjaguin, Muller & Toporov)
    tau = dataclasses.replace(SILICON, tau=2e8)
    spec, n, force = spec_of(tau, "dmt"), 25, 2e-5
    z = np.full(n, 0.5 * SMOOTH.sigma)
    d_turn, _ = padcurves.force_turn(spec, z, force)
    R, K, w = SMOOTH.R, SILICON.K, SILICON.gamma
    delta = ((force / n + 2 * np.pi * w * R) / (K * math.sqrt(R))) ** (2 / 3)
    expected = n * 2e8 * np.pi * R * delta
    assert padfriction.static_friction(spec, z, d_turn) == pytest.approx(expected, rel=TURN_RTOL)


def test_a_pads_friction_is_the_sum_of_its_touching_summits_laws():
    spec = spec_of()
    law = spec.law_set
    for r in range(3):
        z = padload.patch_heights(spec, r)
        d_turn, _ = padcurves.force_turn(spec, z, 30e-6)
        delta = z - d_turn
        out = law.evaluate(delta, SMOOTH, SILICON)
        c = np.pi * SILICON.gamma * SMOOTH.R
        each = (
            4
            * np.sqrt(SILICON.G / SILICON.K)
            * np.sqrt(np.maximum(2 * c * out["load"] + 3 * c * c, 0))
        )
        expected = np.sum(np.where(delta > 0, each, 0.0))
        assert padfriction.static_friction(spec, z, d_turn) == pytest.approx(expected, rel=1e-14)


def test_no_summit_touching_means_no_friction():
    spec = spec_of()
    assert padfriction.static_friction(spec, np.array([0.0, 1e-9]), 2e-9) == 0.0
    assert padfriction.static_friction(spec, np.empty(0), 0.0) == 0.0


def test_the_normal_load_is_the_applied_force_else_the_environments_pull_else_undefined():
    z = padload.patch_heights(spec_of(), 0)
    dry = spec_of()
    d_turn, _ = padcurves.force_turn(dry, z, 0.0)
    assert padfriction.normal_load(dry, z, d_turn, 3e-5) == 3e-5
    assert math.isnan(padfriction.normal_load(dry, z, d_turn, 0.0))  # dry and unpressed
    assert padfriction.attraction(dry, z, d_turn) == 0.0
    # at a common turn without a preload: the pad's own net approach load there
    d = 0.5 * SMOOTH.sigma
    assert padfriction.normal_load(dry, z, d) == padload.pad_load(dry, z, [d])[0] > 0
    humid = spec_of(environment=Environment(hamaker=1.6e-19, rh=0.6))
    z = padload.patch_heights(humid, 0)
    d_turn, _ = padcurves.force_turn(humid, z, 0.0)
    pull = padfriction.attraction(humid, z, d_turn)
    contact = padload.contact_load(humid, z, [d_turn])[0]
    assert pull > 0 and padfriction.normal_load(humid, z, d_turn, 0.0) == pull
    # at the zero-load turn the contacts carry the environment's pull
    assert contact == pytest.approx(pull, rel=1e-6)


def test_a_law_set_without_friction_is_refused_naming_those_that_have():
    with pytest.raises(ParameterError, match="'dmt' has no friction without a shear strength tau"):
        padfriction.check_friction(spec_of(law="dmt"))
