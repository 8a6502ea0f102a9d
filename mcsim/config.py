"""Surfaces and materials by preset name or from a small TOML file with units.

.. code-block:: toml

    [surface]                 # or: combine = ["polished-polysilicon", "polished-polysilicon"]
    name = "my-surface"
    sigma = "1.4 nm"          # std of summit heights
    R = "1.7 um"              # summit radius
    eta = "17 um^-2"          # summit density

    [material]                # optional in a surface file; E and nu set both solids
    E = "160 GPa"
    nu = 0.22
    gamma = "0.5 J/m^2"       # work of adhesion
    H = "12.5 GPa"            # optional, for the plasticity index

Plain numbers are SI. Unknown keys, missing keys, unknown units and out-of-range
values raise a :class:`~mcsim.errors.MCSimError` naming the file and the field.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from .errors import MCSimError, ParameterError
from .params import Material, Surface, combine_surfaces
from .presets import MATERIALS, SURFACES
from .units import parse_quantity

_SURFACE_KEYS = {
    "sigma": ("length", "std of summit heights, e.g. '1.4 nm'"),
    "R": ("length", "summit radius, e.g. '1.7 um'"),
    "eta": ("density", "summit density, e.g. '17 um^-2'"),
}
_MATERIAL_KEYS = {
    "E1": ("pressure", "Young's modulus of solid 1, e.g. '160 GPa'"),
    "E2": ("pressure", "Young's modulus of solid 2"),
    "nu1": ("dimensionless", "Poisson's ratio of solid 1, e.g. 0.22"),
    "nu2": ("dimensionless", "Poisson's ratio of solid 2"),
    "gamma": ("energy_per_area", "work of adhesion, e.g. '0.5 J/m^2'"),
    "H": ("pressure", "hardness (optional), e.g. '12.5 GPa'"),
}


def _read_toml(path: Path) -> dict[str, Any]:
    try:
        with path.open("rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise MCSimError(f"{path}: no such file") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise MCSimError(f"{path}: not a valid TOML file ({err})") from None
    except OSError as err:
        raise MCSimError(f"{path}: cannot read ({err.strerror})") from None


def _quantities(table: dict[str, Any], keys: dict, where: str, optional=()) -> dict[str, float]:
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
        out[key] = parse_quantity(table[key], dimension, f"{where}: {key}")
    return out


def surface_from_table(table: dict[str, Any], where: str = "surface") -> Surface:
    """Build a :class:`Surface` from a TOML-like table (see the module docstring)."""
    name = str(table.get("name", ""))
    try:
        if "combine" in table:
            pair = table["combine"]
            if not (isinstance(pair, list) and len(pair) == 2):
                raise ParameterError(f"{where}: combine must list two surfaces, got {pair!r}")
            rest = {k: v for k, v in table.items() if k not in ("combine", "name")}
            eta = _quantities(rest, {"eta": _SURFACE_KEYS["eta"]}, where)["eta"]
            first, second = (load_surface(p) for p in pair)
            return combine_surfaces(first, second, eta=eta, name=name)
        return Surface(**_quantities(table, _SURFACE_KEYS, where), name=name)
    except ParameterError as err:
        if str(err).startswith(where):
            raise
        raise ParameterError(f"{where}: {err}") from None


def material_from_table(table: dict[str, Any], where: str = "material") -> Material:
    """Build a :class:`Material` from a TOML-like table; ``E``/``nu`` set both solids."""
    table = dict(table)
    for both, (one, two) in {"E": ("E1", "E2"), "nu": ("nu1", "nu2")}.items():
        if both in table:
            value = table.pop(both)
            table.setdefault(one, value)
            table.setdefault(two, value)
    values = _quantities(table, _MATERIAL_KEYS, where, optional=("H",))
    try:
        return Material(**values, name=str(table.get("name", "")))
    except ParameterError as err:
        raise ParameterError(f"{where}: {err}") from None


def load_surface(spec: str | Path) -> Surface:
    """A preset name (``smooth``, ...) or a TOML file with a ``[surface]`` table."""
    if str(spec) in SURFACES:
        return SURFACES[str(spec)]
    path = Path(spec)
    if path.suffix != ".toml":
        raise ParameterError(
            f"unknown surface {str(spec)!r}: give a preset ({', '.join(SURFACES)}) or a .toml file"
        )
    data = _read_toml(path)
    if "surface" not in data:
        raise ParameterError(f"{path}: missing table [surface]")
    return surface_from_table(data["surface"], where=f"{path} [surface]")


def load_material(spec: str | Path) -> Material:
    """A preset name (``silicon``) or a TOML file with a ``[material]`` table."""
    if str(spec) in MATERIALS:
        return MATERIALS[str(spec)]
    path = Path(spec)
    if path.suffix != ".toml":
        raise ParameterError(
            f"unknown material {str(spec)!r}: give a preset ({', '.join(MATERIALS)}) or a .toml file"
        )
    data = _read_toml(path)
    if "material" not in data:
        raise ParameterError(f"{path}: missing table [material]")
    return material_from_table(data["material"], where=f"{path} [material]")


def material_in_surface_file(spec: str | Path) -> Material | None:
    """The ``[material]`` table of a surface TOML file, if it has one."""
    path = Path(spec)
    if path.suffix != ".toml" or str(spec) in SURFACES:
        return None
    data = _read_toml(path)
    if "material" not in data:
        return None
    return material_from_table(data["material"], where=f"{path} [material]")
