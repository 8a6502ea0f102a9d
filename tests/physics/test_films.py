"""Water below the Kelvin gate: adsorbed films (docs/physics.md, section 'Water below the
Kelvin gate: adsorbed films').

Specification: the FHH isotherm t(RH) through its two anchors (Asay & Kim 2005: 3 layers by RH
0.30; Verdaguer et al. 2007: 6–7 layers at ~90 %) and, out of sample, Verdaguer et al.'s 4–5
layers at 75 %; liquid bridges between the films pull with γ_L/r_K on the band
max(D0, 2t) <= g < g_K = 2 r_K cos θ + 2t, so the flat–flat work stays <= 2γ_L cos θ (equal
once 2t >= D0) and a touching summit pulls 4πRγ_L cos θ; −dW/dd = F with a film, per summit
and per surface; bridges only above the structured (ice-like) film (RH_dry); bad inputs.
"""

import math

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FORMULA

from mcsim.model.errors import ParameterError, UnitError
from mcsim.model.presets import SURFACES
from mcsim.physics import films
from mcsim.physics.capillary import capillary_pressure, capillary_work
from mcsim.physics.environment import Environment, kelvin_radius
from mcsim.physics.laws.attraction import capillary_summit, capillary_summit_work
from mcsim.physics.surfaceenvironment import (
    environment_curves,
    environment_works,
    summit_parameters,
)
from mcsim.topography.empirical import Empirical

LAYER = films.WATER_LAYER
GAMMA, D0, R = 0.072, 0.2e-9, 0.5e-6
FLAT = 1e-15  # m: Rq of flat surfaces, 5e-6 D0
#: Central differences with a step of 1e-6 of the scale (as test_environment_split.py).
DERIVATIVE_RTOL = 1e-7


def central(f, x, step):
    return (f(x + step) - f(x - step)) / (2 * step)


# -- the isotherm ------------------------------------------------------------------------------


def test_isotherm_passes_through_its_two_anchors_with_an_exponent_near_fhh_3():
    assert films.film_thickness(0.30) == 3 * LAYER == pytest.approx(0.84e-9)  # Asay & Kim
    assert films.film_thickness(0.90) == pytest.approx(6.5 * LAYER, rel=ROUNDING_FORMULA)
    # n = ln(ln(1/0.3)/ln(1/0.9)) / ln(6.5/3) = 3.1506
    assert films.FHH_EXPONENT == pytest.approx(3.1506, abs=5e-5)


def test_isotherm_predicts_verdaguer_at_75_percent_out_of_sample():
    """Verdaguer et al. 2007: 4–5 layers up to ~75 % RH; no anchor of the fit lies there."""
    layers = float(films.film_thickness(0.75)) / LAYER
    assert 4 <= layers <= 5
    assert layers == pytest.approx(4.7255, abs=5e-5)


def test_isotherm_is_vectorised_rising_from_zero_to_infinity_and_inverted_by_film_humidity():
    rh = np.linspace(0, 1, 21).reshape(3, 7)
    t = films.film_thickness(rh)
    assert t.shape == rh.shape and t.flat[0] == 0 and t.flat[-1] == math.inf
    assert np.all(np.diff(t.ravel()) > 0)
    inner = rh.ravel()[1:-1]
    np.testing.assert_allclose(films.film_humidity(films.film_thickness(inner)), inner,
                               rtol=ROUNDING_FORMULA)  # fmt: skip
    assert films.film_humidity(0.0) == 0


# -- where bridges start: RH_dry -------------------------------------------------------------


@pytest.mark.parametrize(
    ("rh", "bridges"), [(0.05, False), (0.29, False), (0.30, False), (0.31, True), (0.9, True)]
)
def test_bridges_form_only_on_a_film_thicker_than_its_structured_layers(rh, bridges):
    env = Environment(rh=rh)
    assert films.film_humidity(env.structured_film) == pytest.approx(0.30)  # RH_dry
    assert env.has_capillary == bridges
    if not bridges:
        reason = env.no_condensation_reason
        assert f"adsorbed film t = {env.film * 1e9:.3g} nm" in reason
        assert "structured film 0.84 nm" in reason and "above RH 0.3" in reason
        curves = environment_curves(np.array([-1.0, 0.0, 1.0]), SURFACES["smooth"], env)
        assert np.all(curves["capillary"] == 0) and env.condensation_gap == 0


def test_a_given_film_replaces_the_isotherm_everywhere():
    thin = Environment(rh=0.9, film_thickness=0.5e-9)  # humid, but no liquid-like water
    assert not thin.has_capillary and "0.5 nm <= structured film" in thin.no_condensation_reason
    thick = Environment(rh=0.2, film_thickness=1.2e-9, contact_angle=0.3)
    assert thick.has_capillary and thick.film == 1.2e-9
    assert thick.condensation_gap == 2 * thick.kelvin_radius * math.cos(0.3) + 2.4e-9
    assert thick.wet_floor == 2.4e-9


def test_no_film_and_no_structured_layers_is_the_kelvin_band_from_the_cutoff():
    env = Environment(rh=0.3, cutoff=D0, film_thickness=0.0, structured_film=0.0)
    assert env.has_capillary and env.wet_floor == D0
    assert env.condensation_gap == 2 * env.kelvin_radius
    D = np.array([0.1, 0.5, 1.0]) * 1e-9
    args = D0, GAMMA, kelvin_radius(0.3), 0.0
    np.testing.assert_array_equal(capillary_work(D, 1e-9, *args, env.film),
                                  capillary_work(D, 1e-9, *args))  # fmt: skip


# -- the band: flat surfaces ------------------------------------------------------------------


@pytest.mark.parametrize("theta_deg", [0, 40])
@pytest.mark.parametrize("rh", [0.35, 0.6, 0.95])
def test_flat_work_at_contact_is_the_ceiling_once_the_films_span_the_cutoff(rh, theta_deg):
    """(γ_L/r_K)(g_K − max(D0, 2t)) = 2γ_L cos θ for 2t >= D0: the films fill the pressed gaps."""
    theta = math.radians(theta_deg)
    t = float(films.film_thickness(rh))
    assert 2 * t >= D0
    got = capillary_work(D0, FLAT, D0, GAMMA, kelvin_radius(rh), theta, t)
    assert got == pytest.approx(2 * GAMMA * math.cos(theta), rel=ROUNDING_FORMULA)


def test_flat_work_with_a_film_thinner_than_half_the_cutoff_falls_short_by_the_unfilled_part():
    t, r_k = 0.05e-9, float(kelvin_radius(0.6))
    got = capillary_work(D0, FLAT, D0, GAMMA, r_k, 0.0, t)
    expected = 2 * GAMMA - GAMMA * (D0 - 2 * t) / r_k
    assert got == pytest.approx(expected, rel=2 * FLAT / D0)


def test_capillary_work_with_films_never_exceeds_two_gamma_cos_theta():
    D = np.array([-3.0, -0.5, 0.0, 0.2, 1.0, 5.0])[:, None, None, None] * 1e-9
    rq = np.array([FLAT, 0.3e-9, 1.5e-9, 20e-9])[:, None, None]
    rh = np.array([0.31, 0.6, 0.9, 0.999])[:, None]
    theta = np.radians([0.0, 30.0, 80.0])
    work = capillary_work(D, rq, D0, GAMMA, kelvin_radius(rh), theta, films.film_thickness(rh))
    ceiling = 2 * GAMMA * np.cos(theta)
    assert work.shape == (6, 4, 4, 3) and np.all(work >= 0) and np.any(work > 0)
    assert np.all(work <= ceiling * (1 + ROUNDING_FORMULA))


# -- the band: −dW/dD = p, per surface and per summit ---------------------------------------


def _heights():
    edges = np.array([-3.0, -1.7, -0.4, 0.05, 0.3, 1.1, 2.9]) * 1e-9
    return {"gaussian": 1.5e-9, "histogram": Empirical.from_histogram(edges, [1, 3, 2, 5, 4, 1])}


@pytest.mark.parametrize("kind", ["gaussian", "histogram"])
def test_minus_slope_of_the_capillary_work_is_its_pressure_with_a_film(kind):
    heights = _heights()[kind]
    args = D0, GAMMA, kelvin_radius(0.7), math.radians(20), films.film_thickness(0.7)
    step = 1e-15
    for D in np.array([-1.0, 0.4, 1.3, 2.5, 4.0]) * 1e-9:
        slope = -central(lambda x: capillary_work(x, heights, *args), D, step)
        pressure = capillary_pressure(D, heights, *args)
        # rounding of the works (~0.1 J/m², 1e-16 relative) over the step: ~1e4 Pa
        assert slope == pytest.approx(pressure, rel=1e-6, abs=2e4)


@pytest.mark.parametrize(
    ("name", "part"),
    # rough: the band lies in the caps (u_c = 93 nm); super-smooth: in the open gaps (the
    # films, 2t = 3.6 nm, fill its caps, u_c = 2 nm)
    [("smooth", "capillary_caps"), ("smooth", "capillary_gaps"), ("rough", "capillary_caps"),
     ("super-smooth", "capillary_gaps")],
)  # fmt: skip
def test_every_capillary_part_of_a_surface_is_minus_the_slope_of_its_work_with_a_film(name, part):
    surface, env = SURFACES[name], Environment(rh=0.9, contact_angle=0.2)
    h = np.linspace(-1.0, 4.0, 11)
    step = 1e-5
    slope = -central(lambda x: environment_works(x, surface, env)[part], h, step)
    pressure = environment_curves(h, surface, env)[part]
    assert np.any(pressure > 0)
    # works in h = d/σ; their rounding (a few ε of the largest) over the step σ·2e-5
    rounding = 10 * np.finfo(float).eps * np.max(environment_works(h, surface, env)[part])
    np.testing.assert_allclose(slope / surface.sigma, pressure, rtol=1e-7,
                               atol=rounding / (step * surface.sigma))  # fmt: skip


HUMID = Environment(rh=0.6, cutoff=D0, contact_angle=math.radians(20))


def _summit():
    """The summit parameters of HUMID on the rough surface (u_c = 93 nm: g_K lies in the cap)."""
    p = summit_parameters(SURFACES["rough"], HUMID)
    assert p["gap_k"] == HUMID.condensation_gap and p["wet_floor"] == 2 * HUMID.film
    return p["laplace"], p["wet_floor"], p["gap_k"]


@pytest.mark.parametrize("tip", [-10.0, 0.0, 0.05, 0.5, 1.0])
def test_a_summit_touching_or_pressed_pulls_the_classic_four_pi_r_gamma_cos_theta(tip):
    """Where its tip gap lies below the wet floor 2t (``tip`` in units of it): 4πRγ_L cos θ,
    the sphere–flat meniscus at contact (Israelachvili Eq. 17.21), whatever the film."""
    laplace, floor, gap_k = _summit()
    got = capillary_summit(np.float64(-tip * floor), laplace, R, floor, gap_k)
    expected = 4 * math.pi * R * GAMMA * math.cos(HUMID.contact_angle)
    assert got == pytest.approx(expected, rel=ROUNDING_FORMULA)


@pytest.mark.parametrize("tip", [1.01, 1.3, 1.9, 2.5])
def test_a_summit_above_the_films_pulls_the_meniscus_across_the_rest_of_the_band(tip):
    """4πRγ_L cos θ (g_K − g)/(g_K − 2t): the classic meniscus on the band of width 2 r_K cos θ."""
    laplace, floor, gap_k = _summit()
    g = tip * floor  # 2t = 2.21 nm, g_K = 4.13 nm
    got = capillary_summit(np.float64(-g), laplace, R, floor, gap_k)
    expected = 4 * math.pi * R * GAMMA * math.cos(HUMID.contact_angle)
    expected *= max(gap_k - g, 0) / (gap_k - 2 * HUMID.film)
    assert got == pytest.approx(expected, rel=ROUNDING_FORMULA)


@pytest.mark.parametrize("g", [-2e-9, 0.1e-9, 1.0e-9, 2.5e-9, 3.5e-9, 6e-9])
def test_one_summit_minus_work_slope_is_its_force_with_a_film(g):
    laplace, floor, gap_k = _summit()
    step = 1e-6 * gap_k
    slope = central(lambda x: capillary_summit_work(x, laplace, R, floor, gap_k), -g, step)
    expected = capillary_summit(np.float64(-g), laplace, R, floor, gap_k)
    assert slope == pytest.approx(expected, rel=DERIVATIVE_RTOL, abs=DERIVATIVE_RTOL * 1e-6)


# -- bad input ------------------------------------------------------------------------------


@pytest.mark.parametrize("field", ["film_thickness", "structured_film"])
@pytest.mark.parametrize("value", [-1e-9, math.nan, math.inf])
def test_a_film_must_be_finite_and_not_negative(field, value):
    message = rf"^{field} = .* m is out of range \(allowed: >= 0 m\)"
    with pytest.raises(ParameterError, match=message):
        Environment(rh=0.5, **{field: value})


def test_from_user_reads_film_lengths_and_refuses_other_units():
    env = Environment.from_user(rh=0.5, film_thickness="1.2 nm", structured_film="0.6 nm")
    assert env.film_thickness == pytest.approx(1.2e-9)
    assert env.structured_film == pytest.approx(0.6e-9)
    assert Environment.from_user(rh=0.5).film_thickness is None
    with pytest.raises(UnitError, match="film_thickness"):
        Environment.from_user(rh=0.5, film_thickness="1 J")


@pytest.mark.parametrize("option", ["--film-thickness", "--structured-film"])
def test_a_negative_film_on_the_command_line_is_one_line_and_writes_nothing(capsys, tmp_path,
                                                                           option):  # fmt: skip
    out = tmp_path / "run.h5"
    code, stdout, err = run_cli(capsys, "simulate", "--surface", "smooth", "--area", "5um^2",
                                "--h=1:0:2", "--rh", "0.6", f"{option}=-1nm", "--out", out)  # fmt: skip
    field = option[2:].replace("-", "_")
    lines = err.strip().splitlines()
    assert code != 0 and stdout == "" and not out.exists()
    assert len(lines) == 1 and f"{option}: {field} = -1e-09 m is out of range" in lines[0], err
