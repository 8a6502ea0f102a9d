"""DelRio's two thresholds (docs/physics.md, section 'Two thresholds').

RH_dry: liquid bridges form once the adsorbed film passes its structured layers (the
isotherm's 0.30 by default). RH_cr: menisci spread from the contacts across the interface
once the Kelvin band 2 r_K cos θ spans the nano-gap 3σ_n of the asperities' own roughness;
between the two the bridges stay confined to the nano-contacts and their pull is neglected,
so the adhesion keeps its dry value up to RH_cr and jumps there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcsim.model.presets import SURFACES
from mcsim.physics.environment import NANO_GAP, Environment, kelvin_radius
from mcsim.physics.surfaceenvironment import environment_curves


@pytest.mark.parametrize("sigma_n", [0.3e-9, 0.6e-9, 1.2e-9])
@pytest.mark.parametrize("angle", [0.0, math.radians(30)])
def test_rh_cr_is_where_the_kelvin_band_spans_three_sigma_n(sigma_n, angle):
    env = Environment(rh=0.5, contact_angle=angle, asperity_roughness=sigma_n)
    rh_cr = env.critical_rh
    band = 2 * kelvin_radius(rh_cr) * math.cos(angle)
    assert band == pytest.approx(NANO_GAP * sigma_n, rel=1e-12)
    below = Environment(rh=rh_cr * (1 - 1e-9), contact_angle=angle, asperity_roughness=sigma_n)
    above = Environment(rh=rh_cr * (1 + 1e-9), contact_angle=angle, asperity_roughness=sigma_n)
    assert not below.has_capillary and "confined" in below.no_condensation_reason
    assert above.has_capillary


def test_rh_cr_rises_with_the_nanoscale_roughness_and_never_falls_below_rh_dry():
    values = [Environment(asperity_roughness=s).critical_rh for s in (0, 0.1e-9, 0.5e-9, 1e-9)]
    assert values[0] == values[1] == Environment().bridging_rh == pytest.approx(0.30, abs=1e-9)
    assert values[1] < values[2] < values[3] < 1
    assert Environment(contact_angle=math.radians(95), asperity_roughness=1e-9).critical_rh == 1


def test_without_nanoscale_roughness_nothing_changes():
    surface, h = SURFACES["smooth"], np.array([2.0, 1.0, 0.0])
    plain = environment_curves(h, surface, Environment(rh=0.6))
    zero = environment_curves(h, surface, Environment(rh=0.6, asperity_roughness=0.0))
    for k in plain:
        np.testing.assert_array_equal(plain[k], zero[k])


def test_below_rh_cr_the_adhesion_is_dry_and_above_it_the_menisci_pull():
    surface, h = SURFACES["smooth"], np.array([1.0])
    rough = 1e-9  # RH_cr = exp(−0.5228 nm / 1.5 nm) = 0.7057
    dry = environment_curves(h, surface, Environment(hamaker=1.6e-19))
    confined = Environment(hamaker=1.6e-19, rh=0.65, asperity_roughness=rough)
    spread = Environment(hamaker=1.6e-19, rh=0.75, asperity_roughness=rough)
    assert confined.critical_rh == pytest.approx(0.7057, abs=1e-4)
    assert environment_curves(h, surface, confined)["vdw"] == dry["vdw"]
    assert environment_curves(h, surface, confined)["capillary"] == 0
    assert environment_curves(h, surface, spread)["capillary"] > 0


def test_a_given_film_sets_rh_dry_by_its_thickness():
    assert Environment(film_thickness=1e-9).bridging_rh == 0  # thicker than 0.84 nm
    assert Environment(film_thickness=0.5e-9).bridging_rh == 1  # never
    assert Environment(structured_film=0.0).bridging_rh == 0


def test_bad_nanoscale_roughness_is_refused_by_name():
    from mcsim.model.errors import ParameterError, UnitError

    with pytest.raises(ParameterError, match=r"asperity_roughness = -1e-09 m is out of range"):
        Environment(asperity_roughness=-1e-9)
    with pytest.raises(UnitError, match="asperity_roughness: 'nan nm' is not finite"):
        Environment.from_user(asperity_roughness="nan nm")
