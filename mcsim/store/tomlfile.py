"""TOML input files read at the edge: the file parsed, a table taken from it, its quantities
read with their units (a bare number refused where a unit is required, with the key's example
unit in the message). :mod:`mcsim.store.config` builds surfaces, materials and environments
from them."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from mcsim.model.errors import MCSimError, ParameterError, UnitError
from mcsim.model.units import SI_UNITS, has_unit, parse_quantity


def read_toml(path: Path) -> dict[str, Any]:
    """The TOML file at ``path`` as a dict; every failure a one-line :class:`MCSimError` naming
    the file."""
    try:
        with path.open("rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise MCSimError(f"{path}: no such file") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise MCSimError(f"{path}: not a valid TOML file ({err})") from None
    except RecursionError:
        raise MCSimError(f"{path}: not a valid TOML file (nested too deeply)") from None
    except OSError as err:
        raise MCSimError(f"{path}: cannot read ({err.strerror})") from None
    except ValueError:  # a NUL byte in the name
        raise MCSimError(f"{path!r}: not a valid file name") from None


def toml_table(data: dict[str, Any], key: str, path: Path) -> dict[str, Any]:
    """The table ``[key]`` of ``data`` (read from ``path``), checked to be a table."""
    if key not in data:
        raise ParameterError(f"{path}: missing table [{key}]")
    if not isinstance(data[key], dict):
        raise ParameterError(f"{path}: [{key}] must be a table, got {data[key]!r}")
    return data[key]


def quantities(
    table: dict[str, Any],
    keys: dict,
    where: str,
    optional=(),
    *,
    units_required: bool = False,
    written: dict[str, str] | None = None,
) -> dict[str, float]:
    """Parse ``keys`` of ``table``; ``written`` maps a key to the name the user wrote
    (``E1`` came from ``E``), for messages."""
    written = written or {}
    unknown = set(table) - set(keys) - {"name"}
    if unknown:
        raise ParameterError(
            f"{where}: unknown key(s) {', '.join(sorted(unknown))} (allowed: {', '.join(keys)}, name)"
        )
    out = {}
    for key, (dimension, meaning) in keys.items():
        if key not in table:
            if key in optional:
                continue
            raise ParameterError(f"{where}: missing key '{key}' ({meaning})")
        name = written.get(key, key)
        value = table[key]
        if units_required and dimension != "dimensionless" and is_bare(value):
            parse_quantity(value, dimension, f"{where}: {name}")  # not finite: says so
            raise UnitError(
                f"{where}: {name} = {value!r} has no unit (a bare number in a file is refused); "
                f"write it with its unit, e.g. {name} = {with_unit(value, dimension, meaning)}"
            )
        out[key] = parse_quantity(value, dimension, f"{where}: {name}")
    return out


def with_unit(value: Any, dimension: str, meaning: str) -> str:
    """``"1.4 nm"``: the bare ``value`` with the unit of the key's example, or with the SI
    unit where the number looks like SI already (|value| >= 1e3 or <= 1e-3)."""
    number = float(value)
    typical = meaning.split("e.g. '")[-1].rstrip("'").split(" ", 1)[-1]
    looks_si = number != 0 and not 1e-3 < abs(number) < 1e3
    return f'"{value} {SI_UNITS[dimension] if looks_si else typical}"'


def is_bare(value: Any) -> bool:
    """A number, or a string holding only a number: no unit given."""
    return is_number(value) or (isinstance(value, str) and not has_unit(value))


def is_number(value: Any) -> bool:
    """An int or a float as TOML gives it (not a bool)."""
    return isinstance(value, int | float) and not isinstance(value, bool)
