"""Quantities as users write them become SI floats; anything else is refused by name."""

import math
import re

import pytest
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

from mcsim.model.errors import MCSimError, ParameterError, UnitError
from mcsim.model.units import parse_quantity, parse_values, unit_factor

LENGTH_UNITS = r"m, mm, um, µm, nm, A"
AREA_UNITS = r"m\^2, mm\^2, um\^2, nm\^2"
DENSITY_UNITS = r"m\^-2, um\^-2, µm\^-2, 1/um\^2"
PRESSURE_UNITS = r"Pa, MPa, GPa"
ENERGY_UNITS = r"J/m\^2, mJ/m\^2, N/m"


@pytest.mark.parametrize(
    ("text", "dimension", "si"),
    [
        ("1.4 nm", "length", 1.4e-9),
        ("1.4nm", "length", 1.4e-9),
        ("1.7 um", "length", 1.7e-6),
        ("1.7 µm", "length", 1.7e-6),  # micro sign U+00B5
        ("1.7 μm", "length", 1.7e-6),  # Greek mu U+03BC
        ("3 A", "length", 3e-10),
        ("2 m", "length", 2.0),
        ("  2e-3 m  ", "length", 2e-3),
        ("5 um^2", "area", 5e-12),
        ("5 µm²", "area", 5e-12),
        ("5 mm^2", "area", 5e-6),
        ("17 um^-2", "density", 17e12),
        ("17 µm⁻²", "density", 17e12),
        ("17 1/um^2", "density", 17e12),
        ("17 1/µm²", "density", 17e12),
        ("3 Pa", "pressure", 3.0),
        ("3 MPa", "pressure", 3e6),
        ("160 GPa", "pressure", 160e9),
        ("0.5 J/m^2", "energy_per_area", 0.5),
        ("500 mJ/m^2", "energy_per_area", 0.5),
        ("0.5 N/m", "energy_per_area", 0.5),
        ("0.22", "dimensionless", 0.22),
        ("1.4e-9", "length", 1.4e-9),  # a bare number in a string is SI too
    ],
)
def test_quantity_string_converts_to_si(text, dimension, si):
    assert parse_quantity(text, dimension, "field") == pytest.approx(si, rel=1e-14)


@pytest.mark.parametrize("dimension", ["length", "area", "density", "pressure", "dimensionless"])
@pytest.mark.parametrize("number", [1.4e-9, 17, 0.0, -2.5])
def test_plain_number_is_taken_as_si(number, dimension):
    value = parse_quantity(number, dimension, "field")
    assert value == number
    assert type(value) is float


@pytest.mark.parametrize(
    ("unit", "dimension", "factor"),
    [("nm", "length", 1e-9), ("um^2", "area", 1e-12), ("um^-2", "density", 1e12)],
)
def test_unit_factor_converts_a_unit_to_si(unit, dimension, factor):
    # a prefix times a base factor, possibly through a power (um^-2): a few roundings
    assert unit_factor(unit, dimension) == pytest.approx(factor, rel=ROUNDING_FORMULA)


def test_unit_factor_refuses_an_unknown_dimension():
    with pytest.raises(ValueError, match="unknown dimension 'volume'"):
        unit_factor("m^3", "volume")


def test_unit_error_is_an_mcsim_error():
    assert issubclass(UnitError, MCSimError)


@pytest.mark.parametrize(
    ("text", "dimension", "message"),
    [
        ("1.4 furlong", "length", rf"sigma: unknown unit 'furlong' for a length .*{LENGTH_UNITS}"),
        ("1.4 GPa", "length", rf"sigma: unknown unit 'GPa' for a length .*{LENGTH_UNITS}"),
        ("1.4 um^2", "length", rf"sigma: unknown unit 'um\^2' for a length .*{LENGTH_UNITS}"),
        ("5 nm", "area", rf"sigma: unknown unit 'nm' for an area .*{AREA_UNITS}"),
        ("17 um^2", "density", rf"sigma: unknown unit 'um\^2' for a density .*{DENSITY_UNITS}"),
        ("17 1/um", "density", rf"sigma: unknown unit '1/um' for a density .*{DENSITY_UNITS}"),
        ("17 /um^2", "density", rf"sigma: unknown unit '/um\^2' for a density .*{DENSITY_UNITS}"),
        (
            "160 GPa/m",
            "pressure",
            rf"sigma: unknown unit 'GPa/m' for a pressure .*{PRESSURE_UNITS}",
        ),
        (
            "0.5 J",
            "energy_per_area",
            rf"sigma: unknown unit 'J' for an energy per area .*{ENERGY_UNITS}",
        ),
        (
            "0.22 GPa",
            "dimensionless",
            r"sigma: unknown unit 'GPa' for a dimensionless .*no unit, or %",
        ),
    ],
)
def test_unknown_or_wrong_dimension_unit_names_field_and_allowed_units(text, dimension, message):
    with pytest.raises(UnitError, match=message):
        parse_quantity(text, dimension, "sigma")


@pytest.mark.parametrize("text", ["", "  ", "nm", "nm 1.4", "one nm", "--1 nm"])
def test_string_without_leading_number_names_field_and_allowed_units(text):
    with pytest.raises(UnitError, match=rf"^R: cannot read '{text}' as a number .*{LENGTH_UNITS}"):
        parse_quantity(text, "length", "R")


@pytest.mark.parametrize(("text", "rest"), [("1.4.2 nm", ".2 nm"), ("1,4 nm", ",4 nm")])
def test_junk_after_the_number_is_refused_as_a_unit(text, rest):
    with pytest.raises(
        UnitError, match=rf"^R: unknown unit '{rest}' for a length .*{LENGTH_UNITS}"
    ):
        parse_quantity(text, "length", "R")


@pytest.mark.parametrize("text", ["inf nm", "-inf nm", "Infinity nm", "nan nm", "1e400 nm"])
def test_non_finite_string_names_field_and_allowed_units(text):
    with pytest.raises(UnitError, match=rf"^R: '{text}' is not finite; .*{LENGTH_UNITS}"):
        parse_quantity(text, "length", "R")


@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan])
def test_non_finite_plain_number_names_the_field(value):
    with pytest.raises(UnitError, match=rf"^R: {value!r} is not finite"):
        parse_quantity(value, "length", "R")


@pytest.mark.parametrize(
    ("value", "shown"), [(True, "True"), (False, "False"), (None, "None"), ([1.4], r"\[1.4\]")]
)
def test_non_number_value_names_field_and_allowed_units(value, shown):
    with pytest.raises(
        UnitError, match=rf"^E1: expected a number .* got {shown}; .*{PRESSURE_UNITS}"
    ):
        parse_quantity(value, "pressure", "E1")


@pytest.mark.parametrize(
    ("text", "dimension", "si"),
    [
        ("1 cm^2", "area", 1e-4), ("1 cm²", "area", 1e-4), ("1 mm^2", "area", 1e-6),
        ("1 µm²", "area", 1e-12), ("1 μm²", "area", 1e-12), ("1 um2", "area", 1e-12),
        ("1 um**2", "area", 1e-12), ("2 cm", "length", 2e-2), ("1 Å", "length", 1e-10),
        ("1 \u212b", "length", 1e-10), ("1 angstrom", "length", 1e-10), ("3 kPa", "pressure", 3e3),
        ("1 TPa", "pressure", 1e12), ("1 N/mm^2", "pressure", 1e6),
        ("1 J/m²", "energy_per_area", 1.0), ("17 µm⁻²", "density", 17e12),
    ],
)  # fmt: skip
def test_common_unit_spellings_are_accepted(text, dimension, si):
    assert parse_quantity(text, dimension, "field") == pytest.approx(si, rel=ROUNDING_FORMULA)


@pytest.mark.parametrize(
    ("text", "dimension", "closest"),
    [("79 GPA", "pressure", "GPa"), ("1 NM", "length", "nm"), ("1 mj/m^2", "energy_per_area", "mJ/m^2"),
     ("1 UM^2", "area", "um^2")],
)  # fmt: skip
def test_a_near_miss_unit_suggests_the_intended_one(text, dimension, closest):
    with pytest.raises(
        UnitError, match=rf"^E: unknown unit .*; did you mean {re.escape(repr(closest))}\?$"
    ):
        parse_quantity(text, dimension, "E")


def test_values_are_a_list_or_an_inclusive_range_with_units_a_bare_number_being_si():
    assert parse_values("1kPa, 2MPa", "pressure", "p", limit=10) == [1e3, 2e6]
    assert parse_values("1kPa:100kPa:3:log", "pressure", "p", limit=10) == pytest.approx(
        [1e3, 1e4, 1e5], rel=ROUNDING_FEW
    )
    assert parse_values("3:1:3", "pressure", "p", limit=10) == [3.0, 2.0, 1.0]


@pytest.mark.parametrize(
    ("spec", "kwargs", "message"),
    [
        ("", {}, "empty list of values"),
        ("1:2", {}, "cannot read '1:2'"),
        ("1:2:0", {}, "asks for '0' points, an empty range"),
        ("1:2:x", {}, "asks for 'x' points"),
        ("1:2:11", {}, r"allowed: a whole number 1 <= num <= 10"),
        ("1,2,3,4,5,6,7,8,9,10,11", {}, r"11 values \(allowed: at most 10\)"),
        ("2:1:3", {"ascending": True}, r"empty range \(stop < start"),
        ("0:1:3:log", {}, "a log range needs start > 0"),
    ],
)
def test_bad_value_specs_name_the_field_and_what_is_allowed(spec, kwargs, message):
    with pytest.raises(ParameterError, match=message) as err:
        parse_values(spec, "pressure", "p", limit=10, **kwargs)
    assert str(err.value).startswith("p: ")


# --- the environment's dimensions -------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "dimension", "si"),
    [
        ("1.6e-19 J", "energy", 1.6e-19),
        ("0.16 aJ", "energy", 1.6e-19),
        ("160 zJ", "energy", 1.6e-19),
        ("2 uJ", "energy", 2e-6),
        ("180 deg", "angle", math.pi),
        ("90°", "angle", math.pi / 2),
        ("0.5 rad", "angle", 0.5),
        ("298.15 K", "temperature", 298.15),
        ("18 cm^3/mol", "molar_volume", 18e-6),
        ("18 cm³/mol", "molar_volume", 18e-6),
        ("0.018 L/mol", "molar_volume", 18e-6),
        ("1.8e-5 m^3/mol", "molar_volume", 1.8e-5),
    ],
)
def test_environment_dimensions_convert_to_si(text, dimension, si):
    assert parse_quantity(text, dimension, "x") == pytest.approx(si, rel=ROUNDING_FEW)


@pytest.mark.parametrize(
    ("text", "dimension"),
    [("1 J/m^2", "energy"), ("20 K", "angle"), ("25 degC", "temperature"),
     ("25 °C", "temperature"), ("18 cm^3", "molar_volume"), ("1 nm", "energy")],
)  # fmt: skip
def test_environment_dimensions_refuse_units_of_another_dimension(text, dimension):
    with pytest.raises(
        UnitError, match=rf"field: unknown unit .* for an? {dimension.replace('_', ' ')}"
    ):
        parse_quantity(text, dimension, "field")


def test_temperature_message_says_kelvin_only():
    with pytest.raises(UnitError, match=r"no °C: give kelvin"):
        parse_quantity("25 °C", "temperature", "temperature")


def test_a_fraction_may_be_written_in_percent():
    assert parse_quantity("50%", "dimensionless", "rh") == 0.5
    assert parse_quantity("7.5 %", "dimensionless", "rh") == 0.075
    assert parse_quantity("0.5", "dimensionless", "rh") == 0.5
