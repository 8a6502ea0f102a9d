"""The environment on the exact gap field (issue 32, point 2): the pixel sums of van der Waals and
capillary attraction over each load's elastic gaps, beside the exact contact."""

import math

import numpy as np
import pytest
from tolerances import ROUNDING_SUM

from mcsim.model.presets import MATERIALS
from mcsim.physics.capillary import capillary_pressure
from mcsim.physics.environment import Environment
from mcsim.physics.vanderwaals import vdw_pressure
from mcsim.studies.maps.contact import contact_map, gap_attraction

SCAN = "examples/scan.npy"  # periodic, 100 x 100 pixels of 10 nm, heights in m
#: films t = 1.00 nm: the bridges pull on 2t = 2.00 nm <= g < g_K = 2 r_K + 2t = 3.51 nm with
#: gamma_L/r_K = 95 MPa
HUMID = Environment(hamaker=1.6e-19, rh=0.5)


def flat_pressure(g, b=HUMID.retardation):
    """Gregory's retarded flats (1981), −d/dg of A/(12π g²)/(1 + b g), Pa; b = 0:
    A/(6π g³), Israelachvili Eq. 13.11."""
    return 1.6e-19 / (12 * math.pi) * (2 / (g**3 * (1 + b * g)) + b / (g**2 * (1 + b * g) ** 2))


@pytest.mark.parametrize(("g", "bridged"), [(0.2e-9, False), (1.0e-9, False), (3.0e-9, True),
                                            (4.0e-9, False)])  # fmt: skip
def test_a_uniform_gap_is_the_flat_flat_pressure_and_the_full_laplace_pressure_in_the_band(
    g, bridged
):
    vdw, cap = gap_attraction(np.full((8, 8), g), HUMID)
    # the flats' pressure on every pixel; the mean of 64 equal terms: ROUNDING_SUM
    assert vdw == pytest.approx(flat_pressure(g), rel=ROUNDING_SUM)
    assert (HUMID.wet_floor <= g < HUMID.condensation_gap) == bridged
    assert cap == (HUMID.laplace_pressure if bridged else 0.0)


def test_contacts_and_gaps_below_the_cutoff_are_left_out():
    gap = np.array([[0.0, 0.1e-9], [0.5e-9, 2.5e-9]])  # a contact, a gap below D0 = 0.165 nm
    vdw, cap = gap_attraction(gap, HUMID)
    expected = (flat_pressure(0.5e-9) + flat_pressure(2.5e-9)) / 4
    assert vdw == pytest.approx(expected, rel=ROUNDING_SUM)  # a sum of two terms
    # only the 2.5 nm gap is bridged: the 0.5 nm one lies within the films (2t = 2.00 nm)
    assert cap == HUMID.laplace_pressure / 4


def test_no_hamaker_and_a_dry_vapour_attract_nothing():
    assert gap_attraction(np.full((4, 4), 1e-9), Environment()) == (0.0, 0.0)


def test_pixel_sums_of_gaussian_gaps_are_the_proximity_model_s_integrals():
    # gaps g = D - z with z Gaussian (rq 1 nm): the pixel sums are sample means of the
    # integrands whose expectations physics.environment integrates (DelRio's proximity model)
    rng = np.random.default_rng(3)
    rq, D, n = 1e-9, 2e-9, 400_000
    gap = D - rq * rng.standard_normal((n // 400, 400))
    vdw, cap = gap_attraction(gap, HUMID)
    open_ = gap >= HUMID.cutoff
    per_pixel_vdw = np.where(open_, flat_pressure(np.where(open_, gap, 1.0)), 0)
    filled = (gap >= HUMID.wet_floor) & (gap < HUMID.condensation_gap)
    se_vdw = per_pixel_vdw.std() / math.sqrt(n)
    se_cap = HUMID.laplace_pressure * filled.std() / math.sqrt(n)
    expected_vdw = vdw_pressure(D, rq, 1.6e-19, HUMID.cutoff, HUMID.retardation)
    expected_cap = capillary_pressure(D, rq, HUMID.cutoff, HUMID.surface_tension,
                                      HUMID.kelvin_radius, HUMID.contact_angle, HUMID.film)  # fmt: skip
    # sample means of independent pixels: |z| < 5 on their standard errors
    assert abs(vdw - expected_vdw) < 5 * se_vdw
    assert abs(cap - expected_cap) < 5 * se_cap


def test_each_load_s_attraction_is_the_sum_over_its_own_gap_field():
    r = contact_map(SCAN, MATERIALS["silicon"], [1e7, 1e9], unit="m", pixel_size=1e-8,
                    keep_fields=True, environment={"hamaker": "1.6e-19 J", "rh": 0.5})  # fmt: skip
    for i, gap in enumerate(r.gap_fields):
        assert (r.vdw_pressure[i], r.capillary_pressure[i]) == gap_attraction(gap, r.environment)
    columns = r.columns()
    np.testing.assert_array_equal(
        columns["external_pressure"], r.pressure - r.vdw_pressure - r.capillary_pressure
    )
    # the gaps close under load: more attraction at 1 GPa than at 10 MPa
    assert (
        r.vdw_pressure[1] > r.vdw_pressure[0] and r.capillary_pressure[1] > r.capillary_pressure[0]
    )


def test_without_an_environment_there_are_no_attraction_columns():
    r = contact_map(SCAN, MATERIALS["silicon"], [1e8], unit="m", pixel_size=1e-8)
    assert r.vdw_pressure is None and "vdw_pressure" not in r.columns()
