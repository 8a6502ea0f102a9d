"""Sweeps over the environment (issue 22): rh, hamaker, contact_angle, cutoff, temperature
as varied inputs, the work terms equal to ``adhesion_summary`` point by point."""

import math
import warnings

import numpy as np
import pytest

from mcsim import sweep
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
from mcsim.physics.environment import Environment
from mcsim.studies.sweeppoint import parse_values

ENV = Environment(hamaker=1.6e-19)
LAW = "maugis-dugdale"
H = (2.0, 0.0)


def test_rh_sweep_equals_adhesion_point_by_point():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"rh": "0.3,0.6,0.9"}, law=LAW,
                   h=H, environment=ENV, workers=1)  # fmt: skip
    assert not result.failed
    for i, rh in enumerate((0.3, 0.6, 0.9)):
        env = Environment(hamaker=1.6e-19, rh=rh)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RegimeWarning)
            ref = adhesion_summary(SURFACES["smooth"], MATERIALS["silicon"], LAW, environment=env)
        for k in ("work_of_separation", "work_of_separation_contact", "work_of_separation_vdw",
                  "work_of_separation_capillary", "kelvin_radius", "rq", "summit_offset", "pull_off"):  # fmt: skip
            assert result.data[k][i] == getattr(ref, k), f"{k} at rh = {rh}"
    assert (
        result.units["work_of_separation_vdw"] == "J/m^2" and result.units["kelvin_radius"] == "m"
    )
    assert result.dims["capillary"] == ("rh", "h")


def test_varying_an_environment_input_alone_starts_from_a_dry_default():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"hamaker": "0.1 aJ,0.2 aJ"}, law=LAW,
                   h=H, workers=1)  # fmt: skip
    vdw = result.data["work_of_separation_vdw"]
    assert np.all(result.data["work_of_separation_capillary"] == 0)
    assert vdw[1] > vdw[0] > 0


def test_a_bare_contact_angle_in_a_spec_is_in_degrees():
    np.testing.assert_allclose(parse_values("contact_angle", "0:60:3"), np.radians([0, 30, 60]))
    np.testing.assert_allclose(parse_values("contact_angle", "10,0.5 rad"), [math.radians(10), 0.5])


def test_an_environment_value_out_of_range_names_the_varied_input():
    with pytest.raises(ParameterError, match=r"vary rh: rh = 1.0 is out of range"):
        sweep(SURFACES["smooth"], MATERIALS["silicon"], {"rh": "0.5,1"}, law=LAW, h=H)


def test_without_environment_the_sweep_has_no_environment_variables():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"gamma": "0.3,0.5"}, law=LAW, h=H,
                   workers=1)  # fmt: skip
    assert not {"vdw", "capillary", "work_of_separation_vdw", "kelvin_radius"} & set(result.data)
    assert "environment" not in result.attrs
