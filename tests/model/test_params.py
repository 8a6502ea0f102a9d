"""Material and Surface: derived quantities against the paper, and every invalid value refused."""

import dataclasses
import math
import re

import numpy as np
import pytest
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

from mcsim import (
    Material,
    ParameterError,
    Surface,
    combine_surfaces,
    plasticity_index,
    surface_energy_parameter,
)
from mcsim.model.errors import MCSimError
from mcsim.model.params import check_seed
from mcsim.model.presets import MATERIALS, PAPER_PAIRS, SURFACES
from mcsim.model.units import parse_quantity

SILICON = MATERIALS["silicon"]
GPa = 1e9


def printed_tolerance(printed: str) -> float:
    """Half a unit of the last printed digit: the most a correctly rounded value can be off."""
    decimals = len(printed.partition(".")[2])
    return 0.5 * 10.0**-decimals


def material(**changes) -> Material:
    values = {"E1": 160e9, "E2": 160e9, "nu1": 0.22, "nu2": 0.22, "gamma": 0.5, "H": 12.5e9}
    return Material(**{**values, **changes})


def surface(**changes) -> Surface:
    return Surface(**{"sigma": 1.4e-9, "R": 1.7e-6, "eta": 17e12, **changes})


# --- Material ---------------------------------------------------------------------------------


def test_silicon_K_matches_physics_notes():
    # docs/physics.md prints K = 112.092 GPa: three decimals in GPa
    assert SILICON.K / GPa == pytest.approx(112.092, abs=printed_tolerance("112.092"))


def test_silicon_G_matches_physics_notes():
    # docs/physics.md prints G = 18.420 GPa: three decimals in GPa
    assert SILICON.G / GPa == pytest.approx(18.420, abs=printed_tolerance("18.420"))


@pytest.mark.parametrize("mat", [SILICON, material(E2=70e9, nu2=0.35)], ids=["same", "dissimilar"])
def test_E_star_is_three_quarters_of_K(mat):
    assert mat.E_star == pytest.approx(0.75 * mat.K, rel=ROUNDING_FEW)


def test_K_of_dissimilar_materials_follows_the_formula_after_eq_2():
    mat = material(E1=160e9, nu1=0.22, E2=70e9, nu2=0.35)
    expected = 1 / (0.75 * ((1 - 0.22**2) / 160e9 + (1 - 0.35**2) / 70e9))
    assert mat.K == pytest.approx(expected, rel=ROUNDING_FORMULA)


def test_K_is_symmetric_in_the_two_solids():
    one = material(E1=160e9, nu1=0.22, E2=70e9, nu2=0.35)
    other = material(E1=70e9, nu1=0.35, E2=160e9, nu2=0.22)
    assert one.K == pytest.approx(other.K, rel=ROUNDING_FEW)
    assert one.G == pytest.approx(other.G, rel=ROUNDING_FEW)


def test_K_of_identical_solids_with_zero_poisson_ratio_is_two_thirds_of_E():
    # 1/K = (3/4)(2/E)  =>  K = 2E/3
    assert material(nu1=0.0, nu2=0.0).K == pytest.approx(2 / 3 * 160e9, rel=1e-15)


def test_K_against_a_rigid_counterface_is_four_thirds_of_the_plane_strain_modulus():
    mat = material(E2=1e300)
    # 1/E2 = 1e-300 vanishes beside 1/E1: the same formula, a few roundings (measured 1.4e-16)
    assert mat.K == pytest.approx(4 / 3 * 160e9 / (1 - 0.22**2), rel=ROUNDING_FORMULA)


def test_G_of_dissimilar_materials_follows_eq_7():
    mat = material(E1=160e9, nu1=0.22, E2=70e9, nu2=0.35)
    G1, G2 = 160e9 / (2 * 1.22), 70e9 / (2 * 1.35)
    assert mat.G == pytest.approx(1 / ((2 - 0.22) / G1 + (2 - 0.35) / G2), rel=ROUNDING_FORMULA)


def test_material_is_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        SILICON.E1 = 1.0


def test_zero_work_of_adhesion_is_allowed():
    assert material(gamma=0.0).gamma == 0.0


def test_hardness_is_optional():
    assert material(H=None).H is None


def test_integer_inputs_are_stored_as_floats():
    mat = material(E1=160_000_000_000, gamma=1)
    assert type(mat.E1) is float
    assert type(mat.gamma) is float


# --- Surface ----------------------------------------------------------------------------------


def test_A0_is_eta_R_sigma():
    # smooth: 17 µm⁻² · 1.7 µm · 1.4 nm = 0.04046
    assert SURFACES["smooth"].A0 == pytest.approx(0.04046, rel=1e-12)


def test_R0_is_R_over_sigma():
    # smooth: 1.7 µm / 1.4 nm = 1214.2857...
    assert SURFACES["smooth"].R0 == pytest.approx(1700 / 1.4, rel=1e-12)


def test_surface_energy_parameter_is_gamma_over_K_sigma():
    expected = 0.5 / (SILICON.K * 1.4e-9)
    assert surface_energy_parameter(SURFACES["smooth"], SILICON) == pytest.approx(
        expected, rel=ROUNDING_FEW
    )


def test_plasticity_index_of_rough_silicon_matches_physics_notes():
    # docs/physics.md prints ψ = 2.48 for the rough surface: two decimals
    psi = plasticity_index(SURFACES["rough"], SILICON)
    assert psi == pytest.approx(2.48, abs=printed_tolerance("2.48"))


def test_plasticity_index_is_E_star_over_H_times_root_sigma_over_R():
    s, m = SURFACES["smooth"], SILICON
    expected = m.E_star / m.H * math.sqrt(s.sigma / s.R)
    assert plasticity_index(s, m) == pytest.approx(expected, rel=ROUNDING_FEW)


def test_plasticity_index_is_none_without_hardness():
    assert plasticity_index(SURFACES["smooth"], material(H=None)) is None


def test_surface_is_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        SURFACES["smooth"].sigma = 1.0


# Table 1, combined rows as printed: σ in nm, R in µm.
TABLE_1_COMBINED = {
    "rough": ("15.8", "0.116"),
    "intermediate": ("6.8", "0.45"),
    "smooth": ("1.4", "1.7"),
    "super-smooth": ("0.42", "3.36"),
}


@pytest.mark.parametrize("name", list(TABLE_1_COMBINED))
def test_combining_table_1_individual_surfaces_reproduces_its_combined_sigma(name):
    first, second = (SURFACES[n] for n in PAPER_PAIRS[name])
    combined = combine_surfaces(first, second, eta=SURFACES[name].eta)
    printed = TABLE_1_COMBINED[name][0]
    assert combined.sigma / 1e-9 == pytest.approx(float(printed), abs=printed_tolerance(printed))


@pytest.mark.parametrize("name", list(TABLE_1_COMBINED))
def test_combining_table_1_individual_surfaces_reproduces_its_combined_R(name):
    first, second = (SURFACES[n] for n in PAPER_PAIRS[name])
    combined = combine_surfaces(first, second, eta=SURFACES[name].eta)
    printed = TABLE_1_COMBINED[name][1]
    assert combined.R / 1e-6 == pytest.approx(float(printed), abs=printed_tolerance(printed))


@pytest.mark.parametrize("name", list(TABLE_1_COMBINED))
def test_presets_hold_table_1_combined_rows(name):
    sigma, R = TABLE_1_COMBINED[name]
    assert SURFACES[name].sigma == pytest.approx(float(sigma) * 1e-9, rel=ROUNDING_FEW)
    assert SURFACES[name].R == pytest.approx(float(R) * 1e-6, rel=ROUNDING_FEW)


def test_combined_surface_takes_the_given_density_and_name():
    one = SURFACES["polished-polysilicon"]
    combined = combine_surfaces(one, one, eta=3e12, name="mine")
    assert combined.eta == 3e12
    assert combined.name == "mine"


def test_combining_is_symmetric():
    a, b = SURFACES["deposited-polysilicon"], SURFACES["typical-substrate"]
    ab, ba = combine_surfaces(a, b, eta=1e12), combine_surfaces(b, a, eta=1e12)
    assert (ab.sigma, ab.R) == pytest.approx((ba.sigma, ba.R), rel=ROUNDING_FEW)


# --- invalid values ---------------------------------------------------------------------------

NON_FINITE = [math.nan, math.inf, -math.inf]
POSITIVE = [0.0, -1.0, *NON_FINITE]

INVALID_SURFACE = (
    [("sigma", v, " m", "[1e-12, 0.01] m") for v in [*POSITIVE, 1e-300, 1.0]]
    + [("R", v, " m", "[1e-10, 10] m") for v in [*POSITIVE, 1e-300, 1e300]]
    + [("eta", v, " m^-2", "[1, 1e+20] m^-2") for v in [*POSITIVE, 1e-300, 1e300]]
)
INVALID_MATERIAL = (
    [("E1", v, " Pa", ">= 1 Pa") for v in [*POSITIVE, 1e-300]]
    + [("E2", v, " Pa", ">= 1 Pa") for v in [*POSITIVE, 1e-300]]
    + [("nu1", v, "", "(-1, 0.5)") for v in [-1.0, -1.5, 0.5, 0.7, *NON_FINITE]]
    + [("nu2", v, "", "(-1, 0.5)") for v in [-1.0, -1.5, 0.5, 0.7, *NON_FINITE]]
    + [("gamma", v, " J/m^2", "[0, 1000] J/m^2") for v in [-0.1, *NON_FINITE, 1e300]]
    + [("H", v, " Pa", "[1, 1e+13] Pa") for v in [*POSITIVE, 1e-300, 1e300]]
)


def out_of_range(field: str, value: float, unit: str, allowed: str) -> str:
    """The message: field, value with its SI unit, allowed range."""
    return re.escape(f"{field} = {value!r}{unit} is out of range (allowed: {allowed})")


@pytest.mark.parametrize(("field", "value", "unit", "allowed"), INVALID_SURFACE)
def test_invalid_surface_value_names_field_value_and_allowed_range(field, value, unit, allowed):
    with pytest.raises(ParameterError, match=f"^{out_of_range(field, value, unit, allowed)}$"):
        surface(**{field: value})


@pytest.mark.parametrize(("field", "value", "unit", "allowed"), INVALID_MATERIAL)
def test_invalid_material_value_names_field_value_and_allowed_range(field, value, unit, allowed):
    with pytest.raises(ParameterError, match=f"^{out_of_range(field, value, unit, allowed)}$"):
        material(**{field: value})


def test_two_near_rigid_solids_are_refused_by_the_bound_on_K():
    with pytest.raises(
        ParameterError, match=r"^K = 7\.006e\+299 Pa \(from E1, E2, nu1, nu2\) is out"
    ):
        material(E1=1e300, E2=1e300)


@pytest.mark.parametrize(
    ("make", "field"), [(surface, "sigma"), (surface, "eta"), (material, "E1"), (material, "H")]
)
def test_non_numeric_value_names_the_field(make, field):
    with pytest.raises(MCSimError, match=f"^{field}: cannot read 'thick' as a number with a unit"):
        make(**{field: "thick"})


def test_the_python_api_accepts_the_unit_strings_of_the_command_line():
    assert Material(E1="160 GPa", E2="160e9", nu1=0.22, nu2="0.22", gamma="500 mJ/m^2",
                    H="12.5 GPa", z0="0.3 nm", tau="50 MPa") == dataclasses.replace(
        SILICON, name="", tau=50e6)  # fmt: skip
    # the same parser as the command line and TOML files: the same floats
    si = {k: parse_quantity(v, d, k) for k, v, d in
          [("sigma", "1.4 nm", "length"), ("R", "1.7 um", "length"), ("eta", "17 um^-2", "density")]}  # fmt: skip
    assert Surface(sigma="1.4 nm", R="1.7 um", eta="17 um^-2") == Surface(**si)


def test_the_work_of_adhesion_is_given_as_w_or_its_alias_gamma_exactly_once():
    by_w = Material(E1="160 GPa", E2="160 GPa", nu1=0.22, nu2=0.22, w="500 mJ/m^2")
    assert by_w == Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5) and by_w.w == 0.5
    assert dataclasses.replace(by_w, gamma=0.1).w == 0.1  # replace() uses the field's name
    with pytest.raises(ParameterError, match=r"^w: give the work of adhesion once.*got neither"):
        Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22)
    with pytest.raises(ParameterError, match=r"got both \(w = 0.5, gamma = 0.5\)"):
        Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, w=0.5, gamma=0.5)
    with pytest.raises(ParameterError, match=r"^w = -0.5 J/m\^2 is out of range"):
        Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, w=-0.5)  # the name the caller used
    with pytest.raises(ParameterError, match=r"^gamma = -0.5 J/m\^2 is out of range"):
        Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=-0.5)


@pytest.mark.parametrize("seed", [-1, 1.5, "1", True, 2.0])
def test_a_seed_that_numpy_would_refuse_or_reinterpret_is_a_parameter_error(seed):
    with pytest.raises(ParameterError, match=rf"^seed = {re.escape(repr(seed))} is out of range"):
        check_seed(seed)


def test_a_seed_is_none_or_a_whole_number_kept_as_python_int():
    assert check_seed(None) is None
    assert check_seed(np.uint64(2**63)) == 2**63 and type(check_seed(np.int32(7))) is int


@pytest.mark.parametrize(
    ("field", "value", "says"),
    [("E1", "160 nm", "unknown unit 'nm' for a pressure"), ("sigma", "1.4 GPa", "for a length")],
)
def test_a_unit_of_the_wrong_dimension_is_refused_naming_the_field(field, value, says):
    make = surface if field == "sigma" else material
    with pytest.raises(MCSimError, match=f"^{field}: .*{says}"):
        make(**{field: value})


def test_combining_refuses_an_invalid_density():
    one = SURFACES["polished-polysilicon"]
    with pytest.raises(ParameterError, match=re.escape("eta = 0.0 m^-2 is out of range")):
        combine_surfaces(one, one, eta=0.0)


def test_parameter_error_is_an_mcsim_error_and_a_value_error():
    assert issubclass(ParameterError, MCSimError)
    assert issubclass(ParameterError, ValueError)
