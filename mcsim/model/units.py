"""Quantities as users write them (``"1.4 nm"``, ``"17 um^-2"``, ``"160 GPa"``) to SI floats.

One unit table, refusing anything it does not know. Inside mcsim everything is SI;
this module sits at the edge (TOML files, CLI options).
"""

import difflib
import math
import re
import sys

from mcsim.model.errors import UnitError

# Base units per dimension, as a factor to SI.
_LENGTH = {
    "m": 1.0,
    "cm": 1e-2,
    "mm": 1e-3,
    "um": 1e-6,
    "µm": 1e-6,
    "μm": 1e-6,
    "micron": 1e-6,
    "nm": 1e-9,
    "pm": 1e-12,
    "A": 1e-10,
    "Å": 1e-10,
    "\u212b": 1e-10,  # the ångström sign (U+212B), which looks the same as Å
    "angstrom": 1e-10,
}
_PRESSURE = {
    "Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "TPa": 1e12, "N/m^2": 1.0, "N/mm^2": 1e6,
}  # fmt: skip
_ENERGY_PER_AREA = {"J/m^2": 1.0, "mJ/m^2": 1e-3, "N/m": 1.0, "mN/m": 1e-3}
_FORCE = {"N": 1.0, "mN": 1e-3, "uN": 1e-6, "µN": 1e-6, "μN": 1e-6, "nN": 1e-9, "pN": 1e-12}
# Hamaker constants are ~1e-19 J = 0.1 aJ = 100 zJ.
_ENERGY = {
    "J": 1.0, "mJ": 1e-3, "uJ": 1e-6, "µJ": 1e-6, "μJ": 1e-6, "nJ": 1e-9, "pJ": 1e-12,
    "fJ": 1e-15, "aJ": 1e-18, "zJ": 1e-21,
}  # fmt: skip
_ANGLE = {"rad": 1.0, "mrad": 1e-3, "deg": math.pi / 180, "°": math.pi / 180}
# Kelvin only: a temperature in °C needs an offset, which a table of factors cannot hold.
_TEMPERATURE = {"K": 1.0, "mK": 1e-3}
_MOLAR_VOLUME = {
    "m^3/mol": 1.0, "dm^3/mol": 1e-3, "L/mol": 1e-3, "l/mol": 1e-3, "cm^3/mol": 1e-6,
    "mL/mol": 1e-6, "ml/mol": 1e-6,
}  # fmt: skip
#: Units of the dimensions that are a plain table of factors.
_TABLES = {
    "pressure": _PRESSURE,
    "energy_per_area": _ENERGY_PER_AREA,
    "force": _FORCE,
    "energy": _ENERGY,
    "angle": _ANGLE,
    "temperature": _TEMPERATURE,
    "molar_volume": _MOLAR_VOLUME,
}

#: SI unit of each dimension, as printed in messages and labels.
SI_UNITS = {
    "length": "m",
    "area": "m^2",
    "density": "m^-2",
    "pressure": "Pa",
    "energy_per_area": "J/m^2",
    "force": "N",
    "energy": "J",
    "angle": "rad",
    "temperature": "K",
    "molar_volume": "m^3/mol",
    "dimensionless": "1",
}

_POWER = re.compile(r"^(?P<base>[^\^\s]+?)(?:\^|\*\*)?(?P<exp>-?[0-9]+)?$")
_NUMBER = re.compile(
    r"(?P<num>[-+]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?|inf(?:inity)?|nan))"
    r"\s*(?P<unit>.*)",
    re.IGNORECASE | re.DOTALL,
)
#: Longer unit strings are refused before any pattern is matched (no unit is this long).
_MAX_UNIT_LENGTH = 32


def unit_factor(unit: str, dimension: str) -> float:
    """Factor that converts a value in ``unit`` to the SI unit of ``dimension``.

    Parameters
    ----------
    unit : str
        Unit as written, e.g. ``"nm"``, ``"um^-2"``, ``"µm²"``, ``"GPa"``, ``"J/m^2"``.
    dimension : str
        The dimension the caller expects: ``"length"``, ``"area"``, ``"density"``,
        ``"pressure"``, ``"energy_per_area"``, ``"force"``, ``"energy"``, ``"angle"``,
        ``"temperature"`` (kelvin only: no offset units), ``"molar_volume"`` or
        ``"dimensionless"``.

    Returns
    -------
    float
        Multiply a value in ``unit`` by this to get SI.

    Raises
    ------
    UnitError
        If the unit is unknown or of another dimension.
    """
    if not isinstance(unit, str) or len(unit) > _MAX_UNIT_LENGTH:
        shown = repr(unit) if len(repr(unit)) <= 40 else repr(unit)[:40] + "..."
        raise UnitError(f"unknown unit {shown} for {_allowed(dimension)}")
    u = unit.strip().replace("⁻²", "^-2").replace("²", "^2").replace("⁻", "^-")
    u = u.replace("³", "^3").replace("^-^2", "^-2").replace(" ", "")
    if dimension == "dimensionless":
        if u in ("", "1", "%"):
            return 0.01 if u == "%" else 1.0
    elif dimension in _TABLES:
        if u in _TABLES[dimension]:
            return _TABLES[dimension][u]
    elif dimension in ("length", "area", "density"):
        want = {"length": 1, "area": 2, "density": -2}[dimension]
        m = _POWER.match(u)
        if m and m["base"] in _LENGTH:
            exp = int(m["exp"]) if m["exp"] else 1
            if exp == want:
                return _LENGTH[m["base"]] ** exp
        if dimension == "density" and u.startswith("1/"):
            m = _POWER.match(u[2:])
            if m and m["base"] in _LENGTH and m["exp"] == "2":
                return _LENGTH[m["base"]] ** -2
    else:
        raise ValueError(f"unknown dimension {dimension!r}")
    raise UnitError(f"unknown unit {unit!r} for {_allowed(dimension)}{_suggestion(u, dimension)}")


def _suggestion(unit: str, dimension: str) -> str:
    """'; did you mean 'GPa'?' for a near miss (case, a typo), else ''."""
    power = {"length": "", "area": "^2", "density": "^-2"}.get(dimension)
    if power is not None:
        known = [f"{u}{power}" for u in _LENGTH]
    else:
        known = list(_TABLES.get(dimension, ()))
    same_case = [k for k in known if k.lower() == unit.lower()]
    close = same_case or difflib.get_close_matches(unit, known, n=1, cutoff=0.75)
    return f"; did you mean {close[0]!r}?" if close else ""


def has_unit(value: object) -> bool:
    """Whether ``value`` is a string with a unit after its number (``"1.4 nm"``, not ``1.4``)."""
    if not isinstance(value, str):
        return False
    m = _NUMBER.fullmatch(value.strip())
    return m is None or bool(m["unit"])


def _allowed(dimension: str) -> str:
    """'a length (SI unit m; e.g. m, mm, ...)': the dimension and its units, for messages."""
    article = "an" if dimension[0] in "aeiou" else "a"
    return (
        f"{article} {dimension.replace('_', ' ')} "
        f"(SI unit {SI_UNITS[dimension]}; e.g. {_examples(dimension)})"
    )


def _examples(dimension: str) -> str:
    return {
        "length": "m, mm, um, µm, nm, A, Å, cm",
        "area": "m^2, mm^2, um^2, nm^2, µm², cm^2",
        "density": "m^-2, um^-2, µm^-2, 1/um^2",
        "pressure": "Pa, MPa, GPa, kPa",
        "energy_per_area": "J/m^2, mJ/m^2, N/m",
        "force": "N, mN, uN, µN, nN, pN",
        "energy": "J, mJ, uJ, nJ, aJ, zJ",
        "angle": "deg, °, rad, mrad",
        "temperature": "K (no °C: give kelvin)",
        "molar_volume": "m^3/mol, L/mol, cm^3/mol, mL/mol",
        "dimensionless": "no unit, or %",
    }[dimension]


def parse_quantity(value: object, dimension: str, field: str) -> float:
    """Convert a number (taken as SI) or a string with a unit to an SI float.

    Parameters
    ----------
    value : float, int or str
        ``1.4e-9`` (SI), ``"1.4 nm"``, ``"1.4nm"``, ``"17 um^-2"``.
    dimension : str
        Expected dimension (see :func:`unit_factor`).
    field : str
        Name used in error messages.

    Returns
    -------
    float
        The value in SI units.

    Raises
    ------
    UnitError
        On a malformed string, an unknown unit or a unit of another dimension.
    """
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise UnitError(
            f"{field}: expected a number (SI) or a quantity string, got {value!r}; "
            f"units for {_allowed(dimension)}"
        )
    if isinstance(value, int) and abs(value) > sys.float_info.max:  # float() would overflow
        raise UnitError(f"{field}: an integer of {len(str(abs(value)))} digits is too large "
                        "(no finite float holds it)")  # fmt: skip
    if isinstance(value, int | float):
        return _finite(float(value), value, field)
    m = _NUMBER.fullmatch(value.strip())
    if not m:
        raise UnitError(
            f"{field}: cannot read {value!r} as a number with a unit; "
            f"units for {_allowed(dimension)}"
        )
    if not m["unit"]:
        return _finite(float(m["num"]), value, field)  # a bare number is SI
    try:
        factor = unit_factor(m["unit"], dimension)
    except UnitError as err:
        raise UnitError(f"{field}: {err}") from None
    result = _scaled(m["num"], factor)
    if not math.isfinite(result):
        raise UnitError(f"{field}: {value!r} is not finite; units for {_allowed(dimension)}")
    return result


def _scaled(number: str, factor: float) -> float:
    """``number`` (decimal text) times ``factor``, rounded once to the nearest float.

    The exact decimal product, then one rounding: ``"10"`` µN is 1e-05 N, not
    ``float("10") * 1e-06`` = 9.999999999999999e-06 N, whose spurious digits reappear in every
    value derived from it (a pressure of 99999.99999999999 Pa for 10 µN over 100 µm²).
    """
    import decimal

    context = decimal.Context(prec=80, Emax=decimal.MAX_EMAX, Emin=decimal.MIN_EMIN)
    short = f"{factor:.3g}"  # a factor computed as 1/(1e-6)**2 is 1e12 up to an ulp or two
    exact = short if abs(float(short) - factor) <= 2 * math.ulp(factor) else repr(factor)
    try:
        return float(context.multiply(decimal.Decimal(number), decimal.Decimal(exact)))
    except (decimal.DecimalException, OverflowError):  # out of any float's range
        return float(number) * factor


def _finite(result: float, value: object, field: str) -> float:
    if not math.isfinite(result):
        raise UnitError(f"{field}: {value!r} is not finite")
    return result


def parse_values(spec: str, dimension: str, field: str, *, limit: int,
                 ascending: bool = False) -> list[float]:  # fmt: skip
    """A list ``"1kPa,10kPa"`` or a range ``"1kPa:10MPa:31[:log]"`` (inclusive) to SI floats.

    Parameters
    ----------
    spec : str
        Comma list, or ``start:stop:num`` with ``:log`` for geometric spacing; each number
        may carry a unit of ``dimension`` (:func:`parse_quantity`), a bare number is SI.
    dimension, field : str
        As for :func:`parse_quantity`.
    limit : int
        Most values allowed.
    ascending : bool
        Refuse a range with stop < start (an empty range, for grids that must increase).

    Raises
    ------
    ParameterError
        An empty or unreadable spec, a range of fewer than 1 or more than ``limit``
        values, or a log range through values <= 0.
    UnitError
        A number that cannot be read, or a unit of another dimension.
    """
    import numpy as np

    from mcsim.model.errors import ParameterError

    text = spec.strip()
    if not text:
        raise ParameterError(f"{field}: empty list of values")
    if ":" not in text:
        values = [parse_quantity(x.strip(), dimension, field) for x in text.split(",")]
        if len(values) > limit:
            raise ParameterError(f"{field}: {len(values)} values (allowed: at most {limit})")
        return values
    parts = text.split(":")
    scale = parts.pop() if len(parts) == 4 else "lin"
    if len(parts) != 3 or scale not in ("lin", "log"):
        raise ParameterError(f"{field}: cannot read {spec!r} (give a list 'a,b,c' or "
                             "start:stop:num[:log], e.g. '1kPa:10MPa:31:log')")  # fmt: skip
    start, stop = (parse_quantity(x, dimension, field) for x in parts[:2])
    try:
        num = int(parts[2])
    except ValueError:
        num = None
    if num is None or not 1 <= num <= limit:
        empty = ", an empty range" if num is not None and num < 1 else ""
        raise ParameterError(f"{field}: {spec!r} asks for {parts[2]!r} points{empty} (allowed: "
                             f"a whole number 1 <= num <= {limit})")  # fmt: skip
    if ascending and stop < start:
        raise ParameterError(f"{field}: {spec!r} is an empty range (stop < start; allowed: "
                             "start <= stop)")  # fmt: skip
    if scale == "log":
        if start <= 0 or stop <= 0:
            raise ParameterError(f"{field}: {spec!r} is out of range (allowed: a log range "
                                 "needs start > 0 and stop > 0)")  # fmt: skip
        return np.geomspace(start, stop, num).tolist()
    return np.linspace(start, stop, num).tolist()
