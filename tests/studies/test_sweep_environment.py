"""Sweeps over the environment (issue 22): rh, hamaker, contact_angle, cutoff, temperature
as varied inputs, the work terms equal to ``adhesion_summary`` point by point."""

import dataclasses
import json
import math
import warnings

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FEW

from mcsim import sweep
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
from mcsim.physics.environment import Environment
from mcsim.store.sweepfile import read_sweep
from mcsim.studies import sweeppoint
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


@pytest.mark.parametrize("law", [LAW, "jkr"])  # jkr: the compiled design map's fast path
def test_a_retardation_wavelength_sweep_equals_adhesion_point_by_point(law):
    wavelengths = (2e-9, 100e-9)
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"],
                   {"retardation_wavelength": "2nm,100nm"}, law=law, h=H,
                   environment=Environment(hamaker=1.6e-19, rh=0.6), workers=1)  # fmt: skip
    assert not result.failed and result.units["retardation_wavelength"] == "m"
    np.testing.assert_allclose(result.coords["retardation_wavelength"], wavelengths, rtol=1e-15)
    for i, wavelength in enumerate(wavelengths):
        env = Environment(hamaker=1.6e-19, rh=0.6, retardation_wavelength=wavelength)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RegimeWarning)
            ref = adhesion_summary(SURFACES["smooth"], MATERIALS["silicon"], law, environment=env)
        # jkr: the design map against adhesion_summary (tests/engine/test_designmap_environment.py)
        for k in ("work_of_separation", "work_of_separation_vdw", "pull_off"):
            assert result.data[k][i] == pytest.approx(getattr(ref, k), rel=2e-10), (k, wavelength)
    vdw = result.data["work_of_separation_vdw"]
    assert 0 < vdw[0] < vdw[1]  # the shorter the wavelength, the weaker the attraction


def test_varying_an_environment_input_alone_starts_from_a_dry_default():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"hamaker": "0.1 aJ,0.2 aJ"}, law=LAW,
                   h=H, workers=1)  # fmt: skip
    vdw = result.data["work_of_separation_vdw"]
    assert np.all(result.data["work_of_separation_capillary"] == 0)
    assert vdw[1] > vdw[0] > 0


def test_a_film_thickness_sweep_bridges_only_films_thicker_than_their_structured_layers():
    """docs/physics.md, section 'Water below the Kelvin gate: adsorbed films': a given film
    replaces the isotherm, and no meniscus forms on a film no thicker than 0.84 nm."""
    env, films = Environment(hamaker=1.6e-19, rh=0.6), "0.5nm,1.5nm"
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"film_thickness": films},
                   law=LAW, h=H, environment=env, workers=1)  # fmt: skip
    assert not result.failed and result.dims["capillary"] == ("film_thickness", "h")
    capillary = result.data["work_of_separation_capillary"]
    assert capillary[0] == 0 and capillary[1] > 0
    thick = parse_values("film_thickness", films)[1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        ref = adhesion_summary(SURFACES["smooth"], MATERIALS["silicon"], LAW,
                               environment=dataclasses.replace(env, film_thickness=thick))  # fmt: skip
    assert capillary[1] == ref.work_of_separation_capillary
    assert json.loads(result.attrs["environment"])["units"]["film_thickness"] == "m"


def test_a_bare_contact_angle_in_a_spec_is_in_degrees():
    # degrees to radians, the same product: ROUNDING_FEW
    np.testing.assert_allclose(
        parse_values("contact_angle", "0:60:3"), np.radians([0, 30, 60]), rtol=ROUNDING_FEW
    )
    np.testing.assert_allclose(
        parse_values("contact_angle", "10,0.5 rad"), [math.radians(10), 0.5], rtol=ROUNDING_FEW
    )


def test_an_environment_value_out_of_range_names_the_varied_input():
    with pytest.raises(ParameterError, match=r"vary rh: rh = 1.0 is out of range"):
        sweep(SURFACES["smooth"], MATERIALS["silicon"], {"rh": "0.5,1"}, law=LAW, h=H)


def test_without_environment_the_sweep_has_no_environment_variables():
    result = sweep(SURFACES["smooth"], MATERIALS["silicon"], {"gamma": "0.3,0.5"}, law=LAW, h=H,
                   workers=1)  # fmt: skip
    assert not {"vdw", "capillary", "work_of_separation_vdw", "kelvin_radius"} & set(result.data)
    assert "environment" not in result.attrs


def test_a_jkr_rh_sigma_sweep_file_equals_mcsim_adhesion_point_by_point(capsys, tmp_path,
                                                                        monkeypatch):  # fmt: skip
    """The compiled fast path (tolerances: tests/engine/test_designmap_environment.py) writes
    what ``mcsim adhesion`` prints at each point, work_of_separation_vdw and _capillary too."""

    def no_reference(*args, **kwargs):
        raise AssertionError("a fast-path point went to adhesion_summary")

    out = tmp_path / "F.h5"
    with monkeypatch.context() as m:
        m.setattr(sweeppoint, "adhesion_summary", no_reference)
        code, _, err = run_cli(capsys, "sweep", "--surface", "intermediate", "--law", "jkr",
                               "--hamaker", "1.6e-19J", "--vary", "rh=0.3:0.9:3", "--vary",
                               "sigma=2nm:6nm:2", "--out", out)  # fmt: skip
    assert code == 0, err
    result = read_sweep(out)
    surface = SURFACES["intermediate"]
    for i, rh in enumerate(result.coords["rh"]):
        for j, sigma in enumerate(result.coords["sigma"]):
            toml = tmp_path / "s.toml"
            toml.write_text(f'[surface]\nsigma = "{float(sigma)!r} m"\nR = "{surface.R!r} m"\n'
                            f'eta = "{surface.eta!r} m^-2"\n')  # fmt: skip
            code, text, err = run_cli(capsys, "adhesion", "--surface", toml, "--law", "jkr",
                                      "--hamaker", "1.6e-19J", "--rh", repr(float(rh)), "--format",
                                      "json")  # fmt: skip
            assert code == 0, err
            ref = json.loads(text)
            # the sweep's design-map kernel against adhesion_summary, through JSON (repr): the
            # tolerances of tests/engine/test_designmap.py, TURN_ATOL and SUMMARY_RTOL (measured
            # here 3.1e-15 in h, absolute as h crosses zero, and 5.4e-14 relative)
            assert result.data["turn"][i, j] == pytest.approx(ref["turn"], rel=0, abs=3e-12)
            for k in ("pull_off", "work_of_separation", "hysteresis", "work_of_separation_contact",
                      "work_of_separation_vdw", "work_of_separation_capillary"):  # fmt: skip
                assert result.data[k][i, j] == pytest.approx(ref[k], rel=2e-10), (k, rh, sigma)
            for k in ("kelvin_radius", "rq", "summit_offset"):
                assert result.data[k][i, j] == ref[k], (k, rh, sigma)
