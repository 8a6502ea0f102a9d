"""Surfaces and materials by preset name or from a small TOML file with units.

.. code-block:: toml

    [surface]                 # or: combine = ["polished-polysilicon", "polished-polysilicon"]
    name = "my-surface"
    sigma = "1.4 nm"          # std of summit heights
    R = "1.7 um"              # summit radius
    eta = "17 um^-2"          # summit density
    heights = "gaussian"      # optional: "gaussian" (default) or a histogram file
    rq = "1.6 nm"             # optional: rms height about the mean plane (the environment)
    summit_offset = "1.5 nm"  # optional: mean summit plane above the mean plane
    map_heights = "gaussian"  # optional: the whole map's height histogram (the environment)

    [material]                # optional in a surface file; E and nu set both solids
    E = "160 GPa"
    nu = 0.22
    gamma = "0.5 J/m^2"       # work of adhesion
    H = "12.5 GPa"            # optional: hardness (plasticity index, elastic-plastic)
    z0 = "0.3 nm"             # optional: equilibrium spacing (dmt, maugis-dugdale, Tabor)
    tau = "100 MPa"           # optional: interfacial shear strength (friction tau*A)

    [environment]             # optional, in a surface or material file: van der Waals and humidity
    hamaker = "1.6e-19 J"     # Hamaker constant across the gaps
    cutoff = "0.2 nm"         # gaps below it are contact (default 0.165 nm)
    rh = 0.6                  # relative humidity, 0 <= rh < 1
    contact_angle = 20        # degrees when bare, or "0.35 rad"
    temperature = "298.15 K"  # default 298.15 K
    liquid_surface_tension = "72 mJ/m^2"   # default water
    molar_volume = "18 cm^3/mol"           # default water
    film_thickness = "1.2 nm"  # adsorbed film on each face (default: the isotherm t(RH))
    structured_film = "0.84 nm"  # ice-like first layers: no bridges below (default 0.84 nm)
    retardation_wavelength = "100 nm"      # van der Waals retardation (default), or "none"
    asperity_roughness = "0.5 nm"  # asperities' nanoscale roughness: menisci spread from RH_cr

A second rough surface facing this one (default: a flat one) and the correlation ρ of the
two surfaces' heights, in [-1, 1] (default 0), combined into the gap's surface by
:func:`mcsim.model.counterface.combine` (docs/physics.md, section 'Two rough surfaces'); the
command-line options ``--counter-surface`` and ``--correlation`` override them
(:func:`counter_surface_in_file`):

.. code-block:: toml

    [counter_surface]         # the keys of [surface] (Gaussian heights, one radius) ...
    sigma = "1.0 nm"
    R = "2.4 um"
    eta = "17 um^-2"
    correlation = 0.3         # optional: rho in [-1, 1], default 0 (independent)

    [counter_surface]         # ... or a preset or another surface file (relative to this one)
    surface = "polished-polysilicon"
    correlation = 0.3

The summit-height distribution is Gaussian unless ``heights`` names a measured
histogram: a text file (read by :mod:`mcsim.topography.readers.histogram`, its path relative
to the TOML file's folder), or a table with the file or the bins inline:

.. code-block:: toml

    [surface.heights]
    file = "hist.csv"         # or, inline: edges = [...] with counts = [...] (or densities = [...])
    unit = "nm"               # height unit of the file or of the edges, if the file names none

With a measured histogram, ``sigma`` is optional and defaults to the histogram's
own standard deviation (of its piecewise-uniform density,
:class:`~mcsim.topography.empirical.Empirical`); a given ``sigma`` rescales its shape.

``rq``, ``summit_offset`` and ``map_heights`` are used only by the environment
(:func:`mcsim.physics.gapheights.gap_heights`; Nayak estimates where absent).
``map_heights`` takes the same forms as ``heights`` (``[surface.map_heights] file =
"map-heights.csv"``, as ``mcsim ingest`` writes it): the heights of every point about the
mean plane, whose shape is kept and scaled by ``rq``; ``rq`` defaults to its own standard
deviation.

A summit radius that depends on height (``mcsim ingest --radius-by-height``,
:class:`~mcsim.model.params.RadiusByHeight`) is a table of band edges in s = z/σ and the
radius of each band over R:

.. code-block:: toml

    [surface.radius_by_height]
    edges = [-2.3, -1.2, 0.0, 1.2, 2.4]   # the outermost bands extend beyond
    factors = [1.4, 1.1, 0.9, 0.7]

Dimensional quantities in a file must carry their unit (``sigma = "1.4 nm"``): a bare
number is refused, since ``sigma = 1.4`` would otherwise be read as 1.4 m. (The
dataclasses and the table builders called from Python take bare numbers as SI.)
Unknown keys, missing keys, unknown units and out-of-range values raise a
:class:`~mcsim.model.errors.MCSimError` naming the file and the field as written.
"""

from __future__ import annotations

import difflib
import sys
from pathlib import Path
from typing import Any

from mcsim.model.counterface import FLAT, check_correlation
from mcsim.model.errors import MCSimError, ParameterError, UnitError
from mcsim.model.params import Material, RadiusByHeight, Surface, combine_surfaces
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.model.units import parse_quantity
from mcsim.store.tomlfile import is_bare, is_number, quantities, read_toml, toml_table
from mcsim.topography.empirical import Empirical

_SURFACE_KEYS = {
    "sigma": ("length", "std of summit heights, e.g. '1.4 nm'"),
    "R": ("length", "summit radius, e.g. '1.7 um'"),
    "eta": ("density", "summit density, e.g. '17 um^-2'"),
}
_GAP_KEYS = {
    "rq": ("length", "rms height about the mean plane, e.g. '1.6 nm'"),
    "summit_offset": ("length", "mean summit plane above the mean plane, e.g. '1.5 nm'"),
}
_HEIGHTS_KEYS = {"file", "edges", "counts", "densities", "unit"}
#: Keys of ``[surface.calibration]`` (:mod:`mcsim.studies.maps.calibration`): ``radius_scale`` is
#: applied, the rest record how it was fitted: at the fitted loads (``in_sample_*``), leaving
#: each load out in turn (``loo_*``) and at one load above them (``extrapolated_*``).
#: ``worst_error`` and ``rms_error`` are the in-sample errors of files written before the
#: out-of-sample ones were recorded (still read).
_CALIBRATION_KEYS = {"radius_scale", "material", "E_star", "pixel_size", "periodic", "load",
                     "exact_area_fraction", "gw_area_fraction", "uncalibrated_area_fraction",
                     "exact_mean_gap_nm", "gw_mean_gap_nm", "in_sample_worst_error",
                     "in_sample_rms_error", "loo_radius_scale", "loo_error", "loo_worst_error",
                     "loo_rms_error", "extrapolated_load", "extrapolated_exact_area_fraction",
                     "extrapolated_gw_area_fraction", "extrapolated_error", "worst_error",
                     "rms_error"}  # fmt: skip
#: Keys of ``[surface.adhesion_calibration]`` (:mod:`mcsim.studies.maps.adhesioncalibration`): a
#: record of GW's pull-off fitted to exact adhesive cycles, not applied.
ADHESION_CALIBRATION_KEYS = ("law", "factor", "interaction", "w", "range", "material", "E_star",
                             "pixel_size", "periodic", "steps", "preload", "exact_pull_off_kPa",
                             "laws", "gw_pull_off_kPa", "factors", "in_sample_worst_error",
                             "loo_factor", "loo_error", "loo_worst_error", "extrapolated_preload",
                             "extrapolated_exact_pull_off_kPa", "extrapolated_gw_pull_off_kPa",
                             "extrapolated_error")  # fmt: skip
_MATERIAL_KEYS = {
    "E1": ("pressure", "Young's modulus of solid 1, e.g. '160 GPa'"),
    "E2": ("pressure", "Young's modulus of solid 2, e.g. '160 GPa'"),
    "nu1": ("dimensionless", "Poisson's ratio of solid 1, e.g. 0.22"),
    "nu2": ("dimensionless", "Poisson's ratio of solid 2"),
    "gamma": ("energy_per_area", "work of adhesion w (key w or gamma), e.g. '0.5 J/m^2'"),
    "H": ("pressure", "hardness (optional), e.g. '12.5 GPa'"),
    "z0": ("length", "equilibrium spacing (optional), e.g. '0.3 nm'"),
    "tau": ("pressure", "interfacial shear strength (optional), e.g. '100 MPa'"),
}


def _heights_from_value(
    value: Any, where: str, base_dir: Path | None, units_required: bool = False
) -> Empirical | None:
    """The ``heights`` entry of a surface table: None for Gaussian, else the histogram."""
    from mcsim.topography.readers import read_histogram

    if isinstance(value, str) and value.strip().lower() == "gaussian":
        return None
    if isinstance(value, str):
        value = {"file": value}
    if not isinstance(value, dict):
        raise ParameterError(
            f"{where}: heights must be 'gaussian', a histogram file or a table, got {value!r}"
        )
    unknown = set(value) - _HEIGHTS_KEYS
    if unknown:
        raise ParameterError(
            f"{where}: heights: unknown key(s) {', '.join(sorted(unknown))} "
            f"(allowed: {', '.join(sorted(_HEIGHTS_KEYS))})"
        )
    unit = value.get("unit")
    if unit is not None and not isinstance(unit, str):
        raise ParameterError(f"{where}: heights: unit must be a string, got {unit!r}")
    if "file" in value and not isinstance(value["file"], str):
        raise ParameterError(f"{where}: heights: file must be a string, got {value['file']!r}")
    if "file" in value:
        if {"edges", "counts", "densities"} & set(value):
            raise ParameterError(f"{where}: heights: give either file or edges, not both")
        path = Path(value["file"])
        if base_dir is not None and not path.is_absolute():
            path = base_dir / path
        try:
            return read_histogram(path, unit=unit).to_empirical()
        except MCSimError as err:
            raise ParameterError(f"{where}: heights: {err}") from None
    if "edges" not in value or ("counts" in value) == ("densities" in value):
        raise ParameterError(
            f"{where}: heights: give file, or edges with one of counts or densities"
        )
    if unit is None and units_required:
        raise UnitError(f'{where}: heights: inline edges need their unit, e.g. unit = "nm"')
    factor = (
        1.0 if unit is None else parse_quantity(f"1 {unit}", "length", f"{where}: heights: unit")
    )
    weights = value.get("counts", value.get("densities"))
    edges = value["edges"]
    if not (isinstance(edges, list) and all(is_number(e) for e in edges)):
        raise ParameterError(f"{where}: heights: edges must be a list of numbers, got {edges!r}")
    if any(isinstance(e, int) and abs(e) > sys.float_info.max for e in edges):
        raise ParameterError(f"{where}: heights: histogram edges and weights must be finite")
    try:
        return Empirical.from_histogram(
            [factor * e for e in edges],
            weights,
            density="densities" in value,
            source=f"{where}: inline histogram",
        )
    except (ParameterError, TypeError) as err:
        raise ParameterError(f"{where}: heights: {err}") from None


def surface_from_table(
    table: dict[str, Any],
    where: str = "surface",
    base_dir: Path | None = None,
    *,
    including: tuple[Path, ...] = (),
    units_required: bool = False,
) -> Surface:
    """Build a :class:`Surface` from a TOML-like table (see the module docstring).

    ``base_dir`` is the folder that relative histogram paths in ``heights`` start
    from (the TOML file's folder); the working directory if None. ``including`` lists
    the surface files being read (for ``combine``), so that files including each
    other are refused. ``units_required``: refuse bare numbers for dimensional
    quantities (files).
    """
    strict = {"units_required": units_required}
    name = str(table.get("name", ""))
    try:
        if "combine" in table:
            pair = table["combine"]
            if not (
                isinstance(pair, list) and len(pair) == 2 and all(isinstance(p, str) for p in pair)
            ):
                raise ParameterError(f"{where}: combine must list two surfaces, got {pair!r}")
            rest = {k: v for k, v in table.items() if k not in ("combine", "name")}
            eta = quantities(rest, {"eta": _SURFACE_KEYS["eta"]}, where, **strict)["eta"]
            try:
                first, second = (
                    load_surface(_relative_to(p, base_dir), including=including) for p in pair
                )
            except MCSimError as err:
                raise type(err)(f"{where}: combine: {err}") from None
            return combine_surfaces(first, second, eta=eta, name=name)
        table = dict(table)
        heights = _heights_from_value(
            table.pop("heights", "gaussian"), where, base_dir, units_required
        )
        map_heights = _heights_from_value(
            table.pop("map_heights", "gaussian"), f"{where}: map_heights", base_dir, units_required
        )
        scale = _radius_scale(table.pop("calibration", None), where)
        _adhesion_calibration(table.pop("adhesion_calibration", None), where)
        bands = _radius_by_height(table.pop("radius_by_height", None), where)
        optional = ("rq", "summit_offset") if heights is None else ("sigma", "rq", "summit_offset")
        values = quantities(table, _SURFACE_KEYS | _GAP_KEYS, where, optional=optional, **strict)
        values["R"] *= scale
        if heights is not None:
            values.setdefault("sigma", heights.sigma)
            values["heights"] = heights
        if map_heights is not None:
            values.setdefault("rq", map_heights.sigma)
        return Surface(**values, map_heights=map_heights, name=name, radius_by_height=bands)
    except ParameterError as err:
        if str(err).startswith(where):
            raise
        raise ParameterError(f"{where}: {err}") from None


def _radius_by_height(table: Any, where: str) -> RadiusByHeight | None:
    """The ``[surface.radius_by_height]`` table: ``edges`` (in s) and ``factors`` (of R)."""
    if table is None:
        return None
    if not isinstance(table, dict) or set(table) != {"edges", "factors"}:
        raise ParameterError(f"{where}: radius_by_height must be a table of 'edges' (band edges "
                             "in s = z/sigma) and 'factors' (radius over R), got "
                             f"{table!r}")  # fmt: skip
    edges, factors = table["edges"], table["factors"]
    if not all(isinstance(v, list) and all(is_number(x) for x in v) for v in (edges, factors)):
        raise ParameterError(f"{where}: radius_by_height: edges and factors must be lists of "
                             "numbers")  # fmt: skip
    return RadiusByHeight(tuple(edges), tuple(factors))


def _radius_scale(table: Any, where: str) -> float:
    """The ``radius_scale`` of a ``[surface.calibration]`` table (1 without one)."""
    if table is None:
        return 1.0
    if not isinstance(table, dict):
        raise ParameterError(f"{where}: calibration must be a table, got {table!r}")
    unknown = set(table) - _CALIBRATION_KEYS
    if unknown:
        raise ParameterError(f"{where}: calibration: unknown key(s) {', '.join(sorted(unknown))} "
                             f"(allowed: {', '.join(sorted(_CALIBRATION_KEYS))})")  # fmt: skip
    scale = table.get("radius_scale")
    if not (is_number(scale) and 0 < scale < float("inf")):
        raise ParameterError(f"{where}: calibration: radius_scale = {scale!r} is out of range "
                             "(allowed: a number > 0)")  # fmt: skip
    return float(scale)


def _adhesion_calibration(table: Any, where: str) -> None:
    """Check a ``[surface.adhesion_calibration]`` table: a record (not applied), known keys,
    a law set of ``laws`` and a ``factor`` > 0."""
    if table is None:
        return
    if not isinstance(table, dict):
        raise ParameterError(f"{where}: adhesion_calibration must be a table, got {table!r}")
    unknown = set(table) - set(ADHESION_CALIBRATION_KEYS)
    if unknown:
        raise ParameterError(f"{where}: adhesion_calibration: unknown key(s) "
                             f"{', '.join(sorted(unknown))} (allowed: {', '.join(ADHESION_CALIBRATION_KEYS)})")  # fmt: skip
    factor = table.get("factor")
    if not (is_number(factor) and 0 < factor < float("inf")):
        raise ParameterError(f"{where}: adhesion_calibration: factor = {factor!r} is out of range "
                             "(allowed: a number > 0)")  # fmt: skip


def material_from_table(
    table: dict[str, Any], where: str = "material", *, units_required: bool = False
) -> Material:
    """Build a :class:`Material` from a TOML-like table; ``E``/``nu`` set both solids.

    ``units_required``: refuse bare numbers for dimensional quantities (files).
    """
    table = dict(table)
    written = {}
    if "w" in table:  # the work of adhesion by its name; gamma is the paper's symbol for it
        if "gamma" in table:
            raise ParameterError(f"{where}: give either w or gamma (the same work of adhesion), "
                                 "not both")  # fmt: skip
        table["gamma"] = table.pop("w")
        written["gamma"] = "w"
    for both, (one, two) in {"E": ("E1", "E2"), "nu": ("nu1", "nu2")}.items():
        if both in table and (one in table or two in table):
            raise ParameterError(f"{where}: give either {both} or {one} and {two}, not both")
        if both in table:
            value = table.pop(both)
            table.setdefault(one, value)
            table.setdefault(two, value)
            written |= {one: both, two: both}
    values = quantities(
        table, _MATERIAL_KEYS, where, optional=("H", "z0", "tau"), units_required=units_required,
        written=written,
    )  # fmt: skip
    try:
        return Material(**values, name=str(table.get("name", "")))
    except ParameterError as err:
        raise ParameterError(f"{where}: {err}") from None


def load_surface(spec: str | Path, *, including: tuple[Path, ...] = ()) -> Surface:
    """A preset name (``smooth``, ...) or a TOML file with a ``[surface]`` table.

    ``including``: the surface files whose ``combine`` led here (refused if repeated).
    """
    if str(spec) in SURFACES:
        return SURFACES[str(spec)]
    path = Path(spec)
    if path.suffix != ".toml":
        raise ParameterError(
            f"unknown surface {str(spec)!r}{_closest(spec, SURFACES)}: give a preset "
            f"({', '.join(SURFACES)}) or a .toml file"
        )
    table = toml_table(read_toml(path), "surface", path)
    if path.resolve() in including:
        raise ParameterError(f"{path}: combine: the surface files include each other")
    return surface_from_table(
        table,
        where=f"{path} [surface]",
        base_dir=path.parent,
        including=(*including, path.resolve()),
        units_required=True,
    )


def load_counter_surface(spec: str | Path) -> Surface | None:
    """A counter-surface as :func:`load_surface` reads a surface, or None for ``"flat"`` (the
    default: no counter-surface, :data:`mcsim.model.counterface.FLAT`)."""
    if str(spec) == FLAT:
        return None
    return load_surface(spec)


def counter_surface_in_file(spec: str | Path) -> tuple[Surface | None, float | None]:
    """The ``[counter_surface]`` table of a surface TOML file: the counter-surface (None for
    ``surface = "flat"``) and the correlation as written (None if not given; checked to lie in
    [-1, 1]); ``(None, None)`` for a preset or a file without it (module docstring)."""
    path = Path(spec)
    if path.suffix != ".toml" or str(spec) in SURFACES:
        return None, None
    data = read_toml(path)
    if "counter_surface" not in data:
        return None, None
    table, where = dict(toml_table(data, "counter_surface", path)), f"{path} [counter_surface]"
    correlation = table.pop("correlation", None)
    if correlation is not None:
        correlation = check_correlation(correlation, f"{where}: correlation")
    if "surface" not in table:
        surface = surface_from_table(table, where, base_dir=path.parent, units_required=True)
        return surface, correlation
    other = table.pop("surface")
    if table:
        raise ParameterError(f"{where}: give either surface = (a preset or file) or the keys of "
                             f"a surface, not both (found {', '.join(sorted(table))})")  # fmt: skip
    if not isinstance(other, str):
        raise ParameterError(
            f"{where}: surface must be a preset name or a .toml file, got {other!r}"
        )
    try:
        return load_counter_surface(_relative_to(other, path.parent)), correlation
    except MCSimError as err:
        raise type(err)(f"{where}: surface: {err}") from None


def _closest(spec: str | Path, names) -> str:
    """' (did you mean 'smooth'?)' for the preset nearest a mistyped name, else ''."""
    close = difflib.get_close_matches(str(spec).lower(), list(names), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _relative_to(spec: str, base: Path | None) -> str | Path:
    """A surface file named in ``combine``, relative to the including file's folder."""
    if base is None or Path(spec).suffix != ".toml" or Path(spec).is_absolute():
        return spec
    return base / spec


def load_material(spec: str | Path) -> Material:
    """A preset name (``silicon``) or a TOML file with a ``[material]`` table."""
    if str(spec) in MATERIALS:
        return MATERIALS[str(spec)]
    path = Path(spec)
    if path.suffix != ".toml":
        raise ParameterError(
            f"unknown material {str(spec)!r}{_closest(spec, MATERIALS)}: give a preset "
            f"({', '.join(MATERIALS)}) or a .toml file"
        )
    table = toml_table(read_toml(path), "material", path)
    return material_from_table(table, where=f"{path} [material]", units_required=True)


#: Keys of an ``[environment]`` table (and of the command-line options, in kebab case): the
#: field of :class:`~mcsim.physics.environment.Environment` each sets, its dimension and meaning.
ENVIRONMENT_KEYS = {
    "hamaker": ("hamaker", "energy", "Hamaker constant, e.g. '1.6e-19 J'"),
    "cutoff": ("cutoff", "length", "cutoff gap D0, e.g. '0.2 nm'"),
    "rh": ("rh", "dimensionless", "relative humidity, e.g. 0.6"),
    "contact_angle": ("contact_angle", "angle", "contact angle, e.g. 20 (deg) or '0.35 rad'"),
    "temperature": ("temperature", "temperature", "temperature, e.g. '298.15 K'"),
    "liquid_surface_tension": ("surface_tension", "energy_per_area", "e.g. '72 mJ/m^2'"),
    "molar_volume": ("molar_volume", "molar_volume", "e.g. '18 cm^3/mol'"),
    "film_thickness": ("film_thickness", "length", "adsorbed film on each face, e.g. '1.2 nm'"),
    "structured_film": ("structured_film", "length", "ice-like first layers, e.g. '0.84 nm'"),
    "asperity_roughness": ("asperity_roughness", "length",
                           "rms of the asperities' nanoscale roughness, e.g. '0.5 nm'"),
    "retardation_wavelength": ("retardation_wavelength", "length",
                               "van der Waals retardation wavelength, e.g. '100 nm' or 'none'"),
}  # fmt: skip


def environment_from_values(values: dict[str, Any], where: str = "environment"):
    """An :class:`~mcsim.physics.environment.Environment` from values keyed as in
    :data:`ENVIRONMENT_KEYS` (numbers SI, a bare contact angle in degrees, or strings with
    units); a bad value raises an MCSimError that names ``where`` and the key."""
    from mcsim.physics.environment import Environment, environment_fields

    try:
        return Environment.from_user(**environment_fields(values))
    except MCSimError as err:
        raise type(err)(f"{where}: {err}") from None


def environment_in_file(spec: str | Path) -> dict[str, Any]:
    """The ``[environment]`` table of a surface or material TOML file (empty if none).

    Values as written (checked: known keys, units on dimensional values, in range), keyed
    as in :data:`ENVIRONMENT_KEYS` whichever name the file gives a field
    (:func:`mcsim.physics.environment.environment_fields`), for
    :func:`environment_from_values` after command-line options override them.
    """
    path = Path(spec)
    if path.suffix != ".toml" or str(spec) in SURFACES or str(spec) in MATERIALS:
        return {}
    data = read_toml(path)
    if "environment" not in data:
        return {}
    from mcsim.physics.environment import environment_fields

    table, where = toml_table(data, "environment", path), f"{path} [environment]"
    try:
        fields = environment_fields(table)
    except MCSimError as err:
        raise type(err)(f"{where}: {err}") from None
    key_of = {field: key for key, (field, _, _) in ENVIRONMENT_KEYS.items()}
    for (written, value), field in zip(table.items(), fields, strict=True):
        _, dimension, meaning = ENVIRONMENT_KEYS[key_of[field]]
        if dimension not in ("dimensionless", "angle") and is_bare(value):
            raise UnitError(f"{where}: {written} = {value!r} has no unit (a bare number in a file "
                            f"is refused); write it with its unit, {meaning}")  # fmt: skip
    environment_from_values(table, where)
    return {key_of[field]: value for field, value in fields.items()}


def calibration_in_surface_file(spec: str | Path) -> dict[str, Any] | None:
    """The ``[surface.calibration]`` table of a surface TOML file, as written; None without one.

    Checked as :func:`load_surface` checks it (known keys, ``radius_scale`` > 0).
    """
    return _surface_table(spec, "calibration", _radius_scale)


def adhesion_calibration_in_surface_file(spec: str | Path) -> dict[str, Any] | None:
    """The ``[surface.adhesion_calibration]`` table of a surface TOML file, as written; None
    without one. Checked as :func:`load_surface` checks it."""
    return _surface_table(spec, "adhesion_calibration", _adhesion_calibration)


def _surface_table(spec: str | Path, key: str, check) -> dict[str, Any] | None:
    """The ``[surface.<key>]`` table of a surface TOML file, checked by ``check``; None for a
    preset, another kind of file, or a file without it."""
    path = Path(spec)
    if path.suffix != ".toml" or str(spec) in SURFACES:
        return None
    table = toml_table(read_toml(path), "surface", path).get(key)
    if table is None:
        return None
    check(table, f"{path} [surface]")
    return dict(table)


def material_in_surface_file(spec: str | Path) -> Material | None:
    """The ``[material]`` table of a surface TOML file, if it has one."""
    path = Path(spec)
    if path.suffix != ".toml" or str(spec) in SURFACES:
        return None
    data = read_toml(path)
    if "material" not in data:
        return None
    return material_from_table(
        toml_table(data, "material", path), where=f"{path} [material]", units_required=True
    )
