"""Sweep files: the :class:`Sweep` result and its HDF5 layout (the variables, their units and
meanings: :mod:`mcsim.store.sweepvariables`).

File layout (HDF5, netCDF-compatible: ``xarray.open_dataset(path, engine="h5netcdf")``;
every variable has ``units`` and ``long_name`` attributes; schema :data:`SCHEMA_VERSION`):

    dimensions/coordinates  one per varied input, in the order given, named as in
                            ``vary`` (sigma, R, eta, E, E1, E2, nu, nu1, nu2, gamma,
                            z0, tau, H, the pads' restoring_force: float64 SI values;
                            law: strings), except the
                            pad area ``area`` whose dimension is ``pad_area`` (m^2;
                            ``area`` is the real-contact-area curve); then ``h``
                            (d/sigma, the separations of the curves)
    curves (..., h)         contact_fraction and the law set's curves as in ``mcsim
                            analytic`` (seed: P, F, T, mu; others: load, area, and with
                            tau friction, mu; with an environment vdw, capillary and the
                            net load), dimensionless; NaN where a law set in the sweep
                            lacks the curve
    summary (...)           pull_off, h_pull_off (1), pull_off_pressure (Pa),
                            work_of_separation, hysteresis (J/m^2), turn (1): present
                            when a law set of the sweep has a load and a retraction
                            branch; NaN at the points of a law set without; with an
                            environment also work_of_separation_contact, _vdw,
                            _capillary (J/m^2), kelvin_radius, rq, summit_offset (m)
    regime (...)            tabor, maugis_lambda, adhesion_parameter, plasticity_index
                            (1; NaN where undefined: no z0, no H)
    strings (...)           law_used (the law set of the point, ``auto`` resolved),
                            regime_warning ("" or the regime warnings joined by "; "),
                            error ("" or "ErrorType: message" of a failed point)
    Monte Carlo (..., h)    with ``mc``: mc_<q> and mc_<q>_se, the mean over the
                            realizations and its standard error, for every curve q
    pads (...)              with ``pads``: p_stick with its 95 % interval p_stick_low,
                            p_stick_high (1), the pads' pull_off_mean, pull_off_std,
                            pull_off_q05, pull_off_q50, pull_off_q95 and the GW
                            pull_off_analytic (N), their work_of_separation_mean, _std,
                            _q05, _q50, _q95 (J/m^2), p_stick_model, p_stick_ess and
                            contacting_summits (1) (:data:`PADS`), p_stick_method (text,
                            :data:`PAD_STRINGS`); those of p_stick only with a
                            restoring force
    friction (...)          with ``friction`` or a tangential force: the pads' static
                            friction static_friction_mean, _std, _q05, _q50, _q95 (N) and
                            mu_static_mean, ... (1) (:data:`FRICTION`); with a tangential
                            force p_slip, p_slip_low, p_slip_high, p_slip_ess (1,
                            :data:`SLIP`) and p_slip_method (text)
    root attributes         sweep_schema_version, mcsim_version, created, command,
                            law, varied (JSON list of the dimension names), surface,
                            material (JSON of the inputs before variation, SI),
                            turn (NaN: zero approach load), mc, and with mc area,
                            realizations, seed_entropy; with an environment, environment
                            (JSON of its inputs before variation, SI); with a preload
                            preload (Pa); with pads pads, restoring_force (N; absent
                            where it is varied or not given), tangential_force (N;
                            absent where varied or not given), area,
                            seed_entropy, pads_streams; complete; checksum

Strings are fixed-length UTF-8 bytes with ``_Encoding = "utf-8"`` (netCDF readers give
text). Coordinates carry ``units`` and ``long_name`` too (``"1"`` for names). The curve
``load`` is read as ``ds["load"]``: ``ds.load`` is xarray's method that reads a dataset
into memory. Variables above :data:`mcsim.store.files.COMPRESS_ABOVE` bytes are chunked
and gzip-compressed (any HDF5 reader decodes them).

A sweep in progress keeps its completed points in ``<stem>.partial<suffix>`` beside the
output (the same layout plus ``done``, 1 per completed point, and ``complete = False``),
which ``resume`` continues without recomputing them.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError, RunFileError
from mcsim.store import files, schema
from mcsim.store.sweepvariables import (
    CURVES,
    DIMENSION,
    ENVIRONMENT_SUMMARY,
    FRICTION,
    INPUTS,
    PAD_STRINGS,
    PADS,
    REGIME,
    SLIP,
    SLIP_STRINGS,
    STICK,
    STRINGS,
    SUMMARY,
    dimension_name,
    input_unit,
    plain,
)

SCHEMA_VERSION = 1


@dataclass(frozen=True)
class Sweep:
    """The outputs of a sweep on its grid.

    Attributes
    ----------
    coords : dict of str to ndarray
        Values of each varied input by dimension name (SI; strings for ``law``), in
        grid order, then ``h`` (d/σ).
    data : dict of str to ndarray
        Each variable (see the module docstring), shaped like the grid (curves and
        Monte Carlo with a last axis over ``h``).
    dims : dict of str to tuple of str
        Dimension names of each variable.
    units : dict of str to str
        Unit of every coordinate and variable.
    long_names : dict of str to str
        Meaning of every coordinate and variable.
    attrs : dict
        Provenance (the file's root attributes).
    path : Path or None
        The file, if written.
    """

    coords: dict
    data: dict
    dims: dict
    units: dict
    long_names: dict
    attrs: dict = field(default_factory=dict)
    path: Path | None = None

    @property
    def grid(self) -> tuple[str, ...]:
        """Dimension names of the grid, in order (without ``h``)."""
        return tuple(json.loads(self.attrs["varied"]))

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(self.coords[d].size for d in self.grid)

    @property
    def failed(self) -> list[tuple[dict, str]]:
        """Inputs and message of every failed point, in grid order."""
        errors = self.data["error"]
        out = []
        for idx in zip(*np.nonzero(errors != "")):
            inputs = {d: plain(self.coords[d][i]) for d, i in zip(self.grid, idx)}
            out.append((inputs, str(errors[idx])))
        return out

    def table(self):
        """Tidy :class:`pandas.DataFrame`: one row per grid point.

        Columns: the varied inputs (SI), then every per-point output (adhesion
        summary, regime numbers, ``law_used``, ``regime_warning``, ``error``). Units
        in ``df.attrs["units"]``, meanings in ``df.attrs["long_names"]``.
        """
        import pandas as pd

        index = pd.MultiIndex.from_product([self.coords[d] for d in self.grid], names=self.grid)
        columns = {d: index.get_level_values(d) for d in self.grid}
        scalars = [k for k, dims in self.dims.items() if dims == self.grid]
        columns |= {k: self.data[k].ravel() for k in scalars}
        df = pd.DataFrame(columns)
        df.attrs["units"] = {k: self.units[k] for k in df.columns}
        df.attrs["long_names"] = {k: self.long_names[k] for k in df.columns}
        return df

    def to_xarray(self):
        """The sweep as an :class:`xarray.Dataset` (what the file opens as; needs xarray)."""
        import xarray as xr

        coords = {
            d: xr.Variable(d, v, {"units": self.units[d], "long_name": self.long_names[d]})
            for d, v in self.coords.items()
        }
        data = {
            k: xr.Variable(
                self.dims[k], v, {"units": self.units[k], "long_name": self.long_names[k]}
            )
            for k, v in self.data.items()
        }
        return xr.Dataset(data, coords=coords, attrs=dict(self.attrs))

    def __repr__(self) -> str:
        from mcsim.model import display as _display

        rows = [(d, _describe_values(self.coords[d], self.units[d])) for d in self.grid]
        rows.append(("h = d/σ", _describe_values(self.coords["h"], "1")))
        rows.append(("law", str(self.attrs.get("law"))))
        n = int(np.prod(self.shape))
        rows.append(("points", f"{n}, {len(self.failed)} failed"))
        if self.path is not None:
            rows.append(("file", str(self.path)))
        return _display.text("Parameter sweep", rows)


def _describe_values(values: np.ndarray, unit: str) -> str:
    if values.dtype.kind in "US":
        return ", ".join(map(str, values))
    u = "" if unit == "1" else f" {unit}"
    if values.size == 1:
        return f"{values[0]:.4g}{u}"
    return f"{values.size} values from {values.min():.4g} to {values.max():.4g}{u}"


def empty_sweep(
    dims, grid, h, curve_names, summary: bool, mc: bool, environment: bool = False, *,
    pads: bool = False, stick: bool = True, friction: bool = False, slip: bool = False
) -> Sweep:  # fmt: skip
    """The sweep of every variable, all NaN (strings empty). With ``pads`` the pads'
    variables, those of p_stick only with ``stick`` (a restoring force); with ``friction``
    the static friction's, with ``slip`` p_slip's."""
    shape = tuple(len(v) for v in grid)
    curve_shape = (*shape, len(h))
    coords = {d: v for d, v in zip(dims, grid)} | {"h": np.asarray(h)}
    units = {d: input_unit(n) for d, n in zip(dims, [_input_of(d) for d in dims])} | {"h": "1"}
    long_names = {d: INPUTS[_input_of(d)][2] for d in dims} | {"h": "d/sigma, mean separation over the summit-height standard deviation"}  # fmt: skip
    data, vdims = {}, {}
    grid_dims, curve_dims = tuple(dims), (*dims, "h")

    def add(name, unit, meaning, per_h=False):
        data[name] = np.full(curve_shape if per_h else shape, np.nan)
        vdims[name] = curve_dims if per_h else grid_dims
        units[name], long_names[name] = unit, meaning

    for q in curve_names:
        add(q, "1", CURVES.get(q, q), per_h=True)
    if summary:
        for k, (u, m) in (SUMMARY | (ENVIRONMENT_SUMMARY if environment else {})).items():
            add(k, u, m)
    for k, m in REGIME.items():
        add(k, "1", m)
    for k, m in STRINGS.items():
        data[k] = np.full(shape, "", dtype=object)
        vdims[k], units[k], long_names[k] = grid_dims, "1", m
    if mc:
        for q in curve_names:
            add(f"mc_{q}", "1", f"Monte Carlo mean of {q}: {CURVES.get(q, q)}", per_h=True)
            add(f"mc_{q}_se", "1", f"standard error of mc_{q}", per_h=True)
    if pads:
        for k, (u, m) in PADS.items():
            if stick or k not in STICK:
                add(k, u, m)
        strings = (PAD_STRINGS if stick else {}) | (SLIP_STRINGS if slip else {})
        for k, (u, m) in ((FRICTION if friction else {}) | (SLIP if slip else {})).items():
            add(k, u, m)
        for k, m in strings.items():
            data[k] = np.full(shape, "", dtype=object)
            vdims[k], units[k], long_names[k] = grid_dims, "1", m
    attrs = {"varied": json.dumps(list(dims))}
    return Sweep(coords, data, vdims, units, long_names, attrs)


def _input_of(dim: str) -> str:
    return {v: k for k, v in DIMENSION.items()}.get(dim, dim)


def write_sweep(path: Path, result: Sweep, attrs: dict, *, complete: bool, done=None) -> None:
    """Write the sweep (or, incomplete, its completed points and ``done``) atomically."""

    def fill(f):
        f.attrs.update(attrs)
        f.attrs["complete"] = complete
        for d, values in result.coords.items():
            ds = _variable(f, d, values, result.units[d], result.long_names[d])
            ds.make_scale(d)
        for k, values in result.data.items():
            ds = _variable(f, k, values, result.units[k], result.long_names[k])
            for axis, d in enumerate(result.dims[k]):
                ds.dims[axis].attach_scale(f[d])
        if not complete:
            ds = _variable(f, "done", done.astype(np.uint8), "1", "1: point completed")
            for axis, d in enumerate(result.grid):
                ds.dims[axis].attach_scale(f[d])

    files.atomic_write(Path(path), fill)


def _variable(f, name: str, values: np.ndarray, unit: str, long_name: str):
    values = np.asarray(values)
    text = values.dtype.kind in "OUS"
    if text:
        values = np.array([str(v).encode() for v in values.ravel()] or [b""]).reshape(values.shape)
        if values.dtype.itemsize == 0:
            values = values.astype("S1")
    ds = f.create_dataset(name, data=values, **files.storage(values))
    ds.attrs["units"] = unit
    ds.attrs["long_name"] = long_name
    if text:
        ds.attrs["_Encoding"] = "utf-8"
    return ds


#: The file kind, in messages.
WHAT = "sweep file"

#: Root attributes every sweep file holds, and their kinds (:data:`mcsim.store.schema.KINDS`).
ATTRIBUTES = {
    "mcsim_version": "text",
    "created": "text",
    "command": "text",
    "law": "text",
    "varied": "JSON list",
    "surface": "JSON object",
    "material": "JSON object",
    "definition": "JSON object",
    "turn": "number",
    "mc": "boolean",
    "complete": "boolean",
}

#: Root attributes of a sweep with Monte Carlo runs (``mc``).
MC_ATTRIBUTES = {"area": "number", "realizations": "integer", "seed_entropy": "digits",
                 "device": "text"}  # fmt: skip

#: Root attributes of a pads sweep (a file with :data:`PADS` variables or ``pads``).
PADS_ATTRIBUTES = {"pads": "integer", "restoring_force": "number", "area": "number",
                   "seed_entropy": "digits"}  # fmt: skip

#: Ranges of root attributes, ends included (low, high, NaN allowed; NaN area: none).
ATTRIBUTE_RANGES = {
    "pads": (1, np.inf, False),
    "restoring_force": (0, np.inf, False),
    "preload": (0, np.inf, False),
    "tangential_force": (0, np.inf, False),
    "area": (0, np.inf, True),
}

#: Ranges of per-point variables, ends included (low, high, NaN allowed: a failed point,
#: the standard deviation of one pad).
VARIABLE_RANGES = {
    **{k: (0, 1, True) for k in ("p_stick", "p_stick_low", "p_stick_high", "p_stick_model")},
    **{k: (0, 1, True) for k in ("p_slip", "p_slip_low", "p_slip_high")},
    **{k: (0, np.inf, True) for k in FRICTION},
    "pull_off_std": (0, np.inf, True),
    "contacting_summits": (0, np.inf, True),
}


def read_file(path: Path) -> dict:
    """Attributes, datasets (strings decoded), units and long names of a sweep file or
    checkpoint, verified by its checksum and checked against the layout (module docstring)."""
    import h5py

    path = Path(path)
    if not path.is_file():  # absent, or a folder or a pipe (which h5py would block on)
        raise RunFileError(
            f"{path}: " + ("not a regular file" if path.exists() else "no such file")
        )
    try:
        with h5py.File(path, "r") as f:
            return _read(path, f)
    except MCSimError:
        raise
    except (OSError, KeyError, ValueError, TypeError, RuntimeError, IndexError) as err:
        reason = " ".join(str(err).split())[:200]  # HDF5's messages span lines
        raise RunFileError(f"{path}: damaged sweep file ({type(err).__name__}: {reason})") from None


def _read(path: Path, f) -> dict:
    if "sweep_schema_version" not in f.attrs:
        raise RunFileError(f"{path}: not an mcsim sweep file (no sweep_schema_version)")
    version = schema.attribute(path, f, "sweep_schema_version", "integer", WHAT)
    if version != SCHEMA_VERSION:
        raise RunFileError(f"{path}: sweep schema version {version} is not supported "
                           f"(this mcsim reads {SCHEMA_VERSION})")  # fmt: skip
    schema.check_sizes(path, f, WHAT)
    stored = f.attrs.get("checksum")
    if not isinstance(stored, str) or stored != files.checksum(f):
        raise RunFileError(f"{path}: damaged sweep file: checksum mismatch")
    wanted = ATTRIBUTES | (
        MC_ATTRIBUTES if schema.attribute(path, f, "mc", "boolean", WHAT) else {}
    )
    if "pads" in f.attrs or any(k in f for k in PADS):
        wanted |= PADS_ATTRIBUTES
        if "restoring_force" in f or "p_stick" not in f:  # varied (a coordinate), or none
            del wanted["restoring_force"]
    for k in ("preload", "tangential_force"):
        if k in f.attrs:
            wanted |= {k: "number"}
    attrs = {
        k: (v.item() if np.ndim(v) == 0 and hasattr(v, "item") else v) for k, v in f.attrs.items()
    }
    checked = {k: schema.attribute(path, f, k, kind, WHAT) for k, kind in wanted.items()}
    grid = _grid(path, checked["varied"])
    attrs |= {k: v for k, v in checked.items() if not isinstance(v, (dict, list))}  # JSON: as text
    coords = {
        d: schema.dataset(path, f, d, "S" if d == "law" else "f", None, WHAT)[()]
        for d in (*grid, "h")
    }
    for d, values in coords.items():
        if values.ndim != 1 or values.size == 0:
            raise schema.refuse(
                path, WHAT, f"coordinate {d} has shape {values.shape}, expected (n,) with n >= 1"
            )
    shape = tuple(coords[d].size for d in grid)
    per_h = (*shape, coords["h"].size)
    data, units, long_names = {}, {}, {}
    for k in f:
        if k in coords:
            values = coords[k]
        else:
            values = schema.dataset(path, f, k, _dtype(k), None, WHAT)[()]
            expected = _shapes(k, shape, per_h)
            if values.shape not in expected:
                raise schema.refuse(path, WHAT, f"dataset {k} has shape {values.shape}, expected "
                                                f"{' or '.join(map(str, expected))} (the grid {', '.join(grid)}, h)")  # fmt: skip
        if values.dtype.kind == "S":
            values = _decoded(path, k, values)
        data[k] = values
        units[k] = schema.attribute(path, f[k], "units", "text", WHAT)
        long_names[k] = schema.attribute(path, f[k], "long_name", "text", WHAT)
    for k in STRINGS:
        if k not in data:
            raise schema.refuse(path, WHAT, f"dataset {k} is missing")
    _check_ranges(path, checked, data)
    return {"attrs": attrs, "data": data, "units": units, "long_names": long_names}


def _check_ranges(path: Path, attrs: dict, data: dict) -> None:
    """Refuse attributes and variables outside :data:`ATTRIBUTE_RANGES` and
    :data:`VARIABLE_RANGES`, and a p_stick outside its interval."""
    for kind, held, ranges in (
        ("attribute", attrs, ATTRIBUTE_RANGES),
        ("dataset", data, VARIABLE_RANGES),
    ):
        for k, (low, high, nan) in ranges.items():
            if k in held:
                schema.within(path, f"{kind} {k}", held[k], WHAT, low=low, high=high, nan=nan)
    for name in ("p_stick", "p_slip"):
        if name in data and {f"{name}_low", f"{name}_high"} <= data.keys():
            p, low, high = data[name], data[f"{name}_low"], data[f"{name}_high"]
            if np.any((low > p) | (p > high)):  # False where NaN: a failed point
                raise schema.refuse(path, WHAT, f"dataset {name} lies outside its interval "
                                                f"{name}_low .. {name}_high")  # fmt: skip


def _grid(path: Path, varied: list) -> tuple[str, ...]:
    """The dimension names in ``varied``: distinct names of inputs a sweep can vary."""
    allowed = [dimension_name(n) for n in INPUTS]
    if (
        not varied
        or len(set(map(str, varied))) != len(varied)
        or any(not isinstance(d, str) or d not in allowed for d in varied)
    ):
        raise schema.refuse(path, WHAT, f"attribute varied is {schema.shown(json.dumps(varied))}, "
                                        f"not a list of distinct names from {', '.join(allowed)}")  # fmt: skip
    return tuple(varied)


def _dtype(name: str) -> str:
    """Kind of values of variable ``name`` (:data:`mcsim.store.schema.DTYPES`)."""
    strings = name in STRINGS or name in PAD_STRINGS or name in SLIP_STRINGS
    return "S" if strings else "iu" if name == "done" else "f"


def _shapes(name: str, grid: tuple, per_h: tuple) -> tuple[tuple, ...]:
    """Shapes variable ``name`` may have: per point, or per point and separation."""
    if name in CURVES or name.startswith("mc_"):
        return (per_h,)
    if (
        name in SUMMARY
        or name in REGIME
        or name in STRINGS
        or name in PAD_STRINGS
        or name in SLIP_STRINGS
        or name in FRICTION
        or name in SLIP
        or name == "done"
    ):
        return (grid,)
    return (grid, per_h)


def _decoded(path: Path, name: str, values: np.ndarray) -> np.ndarray:
    try:
        text = [v.decode() for v in values.ravel()]
    except UnicodeDecodeError:
        raise schema.refuse(path, WHAT, f"dataset {name} is not UTF-8 text") from None
    return np.array(text, dtype=object).reshape(values.shape)


def read_partial(path: Path) -> dict:
    """A sweep checkpoint: attributes, ``done`` and data."""
    raw = read_file(path)
    if "done" not in raw["data"] or raw["attrs"].get("complete"):
        raise RunFileError(f"{path}: not a sweep checkpoint")
    return {**raw, "done": raw["data"]["done"].astype(bool)}


def is_sweep_file(path: str | Path) -> bool:
    """Whether ``path`` is an HDF5 file written by :func:`sweep` (complete or not)."""
    import h5py

    if not Path(path).is_file():  # a pipe would block h5py: not a sweep file
        return False
    try:
        with h5py.File(path, "r") as f:
            return "sweep_schema_version" in f.attrs
    except Exception:  # not HDF5, or damaged: the run-file reader says what is wrong
        return False


def read_sweep(path: str | Path) -> Sweep:
    """Open a sweep file as a :class:`Sweep` (no xarray needed); refuses a damaged file."""
    path = files.file_path(path)
    raw = read_file(path)
    grid = tuple(json.loads(raw["attrs"]["varied"]))  # checked by read_file
    coords = {d: raw["data"].pop(d) for d in (*grid, "h")}
    coords = {d: v.astype(str) if v.dtype == object else v for d, v in coords.items()}
    raw["data"].pop("done", None)
    dims = {k: (*grid, "h") if v.ndim == len(grid) + 1 else grid for k, v in raw["data"].items()}
    return Sweep(coords, raw["data"], dims, raw["units"], raw["long_names"], raw["attrs"], path)
