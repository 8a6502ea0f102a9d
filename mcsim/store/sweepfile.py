"""Sweep files: the :class:`Sweep` result, its variables and their HDF5 layout.

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
                            :data:`PAD_STRINGS`)
    root attributes         sweep_schema_version, mcsim_version, created, command,
                            law, varied (JSON list of the dimension names), surface,
                            material (JSON of the inputs before variation, SI),
                            turn (NaN: zero approach load), mc, and with mc area,
                            realizations, seed_entropy; with an environment, environment
                            (JSON of its inputs before variation, SI); with a preload
                            preload (Pa); with pads pads, restoring_force (N; absent
                            where it is varied), area,
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
from mcsim.model.units import SI_UNITS
from mcsim.store import files, schema

SCHEMA_VERSION = 1


#: Inputs a sweep can vary: dimension of their values, the fields they set, meaning.
INPUTS: dict[str, tuple[str, tuple[str, ...], str]] = {
    "sigma": ("length", ("sigma",), "standard deviation of the summit heights"),
    "R": ("length", ("R",), "summit radius"),
    "eta": ("density", ("eta",), "summit density"),
    "E": ("pressure", ("E1", "E2"), "Young's modulus of both solids"),
    "E1": ("pressure", ("E1",), "Young's modulus of solid 1"),
    "E2": ("pressure", ("E2",), "Young's modulus of solid 2"),
    "nu": ("dimensionless", ("nu1", "nu2"), "Poisson's ratio of both solids"),
    "nu1": ("dimensionless", ("nu1",), "Poisson's ratio of solid 1"),
    "nu2": ("dimensionless", ("nu2",), "Poisson's ratio of solid 2"),
    "gamma": ("energy_per_area", ("gamma",), "work of adhesion"),
    "w": ("energy_per_area", ("gamma",), "work of adhesion"),
    "z0": ("length", ("z0",), "equilibrium spacing"),
    "tau": ("pressure", ("tau",), "interfacial shear strength"),
    "H": ("pressure", ("H",), "hardness"),
    "law": ("", ("law",), "law set"),
    "area": ("area", ("area",), "nominal pad area of the Monte Carlo patches"),
    "rh": ("dimensionless", ("rh",), "relative humidity of the environment"),
    "hamaker": ("energy", ("hamaker",), "Hamaker constant across the gaps"),
    "contact_angle": ("angle", ("contact_angle",), "contact angle of the condensing liquid"),
    "cutoff": ("length", ("cutoff",), "cutoff gap D0 of the environment (contact below it)"),
    "temperature": ("temperature", ("temperature",), "temperature of the environment"),
    "restoring_force": ("force", ("restoring_force",), "restoring force pulling each pad off"),
}

#: Inputs of :data:`INPUTS` that set the environment (:class:`mcsim.physics.environment.Environment`).
ENVIRONMENT_INPUTS = ("rh", "hamaker", "contact_angle", "cutoff", "temperature")


#: Dimension name of each input whose name is taken by an output.
DIMENSION = {"area": "pad_area"}


#: Adhesion-summary variables: unit and meaning.
SUMMARY = {
    "pull_off": ("1", "pull-off force/(A_n K): most tensile load on retraction (magnitude)"),
    "h_pull_off": ("1", "separation d/sigma of the pull-off"),
    "pull_off_pressure": ("Pa", "pull-off force per nominal area"),
    "work_of_separation": ("J/m^2", "integral of the tensile load over d on retraction"),
    "hysteresis": ("J/m^2", "integral of (approach - retraction load) over d"),
    "turn": ("1", "closest approach h_turn = d_turn/sigma before retraction"),
}


#: Adhesion-summary variables of a sweep with an environment: unit and meaning.
ENVIRONMENT_SUMMARY = {
    "work_of_separation_contact": ("J/m^2", "contact part of work_of_separation"),
    "work_of_separation_vdw": (
        "J/m^2",
        "van der Waals work of separation from the turn to infinity",
    ),
    "work_of_separation_capillary": (
        "J/m^2",
        "capillary work of separation from the turn to infinity",
    ),
    "kelvin_radius": ("m", "Kelvin radius r_K = gamma_L V_m/(R T ln(1/RH))"),
    "rq": ("m", "rms height about the mean plane used by the environment"),
    "summit_offset": ("m", "mean summit plane above the mean plane used by the environment"),
}

#: Per-point variables of a pads sweep (``mcsim sweep --pads``): unit and meaning.
PADS = {
    "p_stick": (
        "1",
        "probability that a pad's pull-off exceeds the restoring force (p_stick_method)",
    ),
    "p_stick_low": (
        "1",
        "lower end of the 95 % interval of p_stick (pads: Clopper-Pearson; importance: Clopper-Pearson on the effective sample size)",
    ),
    "p_stick_high": (
        "1",
        "upper end of the 95 % interval of p_stick (pads: Clopper-Pearson; importance: Clopper-Pearson on the effective sample size)",
    ),
    "p_stick_ess": (
        "1",
        "effective number of pads on the rarer side, sticking or not (pads: their count)",
    ),
    "pull_off_mean": ("N", "mean pull-off force of the pads"),
    "pull_off_std": ("N", "standard deviation of the pads' pull-off force (ddof = 1)"),
    "pull_off_q05": ("N", "5 % quantile of the pads' pull-off force"),
    "pull_off_q50": ("N", "median of the pads' pull-off force"),
    "pull_off_q95": ("N", "95 % quantile of the pads' pull-off force"),
    "work_of_separation_mean": ("J/m^2", "mean work of separation of the pads, -int F dd / A"),
    "work_of_separation_std": ("J/m^2", "standard deviation of the pads' work of separation"),
    "work_of_separation_q05": ("J/m^2", "5 % quantile of the pads' work of separation"),
    "work_of_separation_q50": ("J/m^2", "median of the pads' work of separation"),
    "work_of_separation_q95": ("J/m^2", "95 % quantile of the pads' work of separation"),
    "pull_off_analytic": (
        "N",
        "GW mean pull-off of one pad: pull_off x A K after the mean-field turn",
    ),
    "p_stick_model": (
        "1",
        "model p_stick: compound-Poisson pull-off, Lugannani-Rice saddlepoint tail (mcsim.studies.stiction)",
    ),
    "contacting_summits": (
        "1",
        "expected summits per pad above the mean-field turn, eta A S(h_turn)",
    ),
}

#: Text variables of a pads sweep: meaning.
PAD_STRINGS = {
    "p_stick_method": "how p_stick was estimated: pads (fraction of the pads) or importance "
    "(importance sampling, mcsim.studies.tail)",
}


#: Regime numbers of one summit: meaning (all dimensionless).
REGIME = {
    "tabor": "Tabor mu_T = (R w^2/(E*^2 z0^3))^(1/3)",
    "maugis_lambda": "Maugis lambda = 2 sigma0 (R/(pi w K^2))^(1/3), sigma0 = w/(0.97 z0)",
    "adhesion_parameter": "Fuller-Tabor theta = E* sigma^(3/2)/(R^(1/2) w)",
    "plasticity_index": "psi = (E*/H) sqrt(sigma/R)",
}


#: Per-point strings.
STRINGS = {
    "law_used": "law set of the point (auto resolved on the adhesion map)",
    "regime_warning": "regime warnings of the point, joined by '; ' (empty: none)",
    "error": "why the point failed (empty: it did not)",
}


#: Normalisation of each curve (its long_name).
CURVES = {
    "contact_fraction": "N_c/N, fraction of summits in contact",
    "P": "Hertz load P/(A_n K) (Eq. 3)",
    "F": "JKR adhesion term F/(A_n K) (Eq. 5)",
    "T": "adhesional friction T/(A_n K) (Eq. 7)",
    "mu": "friction coefficient: T/(P + F) (seed, Eq. 8), friction/load (other law sets)",
    "load": "net normal force/(A_n K), positive when compressive",
    "area": "real contact area A_r/A_n",
    "friction": "friction tau A_r/(A_n K) (Bowden-Tabor)",
    "vdw": "van der Waals attraction across the gaps per nominal area/K, > 0 attractive",
    "capillary": "capillary attraction per nominal area/K, > 0 attractive",
}


def plain(value):
    """A NumPy scalar as a Python number (what :func:`parse_quantity` takes)."""
    return value.item() if isinstance(value, np.generic) else value


def dimension_name(name: str) -> str:
    """Name of the file's dimension for the varied input ``name`` (``area`` → ``pad_area``)."""
    return DIMENSION.get(name, name)


def _unit(name: str) -> str:
    dimension = INPUTS[name][0]
    return "1" if name == "law" else SI_UNITS[dimension]


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
    pads: bool = False
) -> Sweep:  # fmt: skip
    shape = tuple(len(v) for v in grid)
    curve_shape = (*shape, len(h))
    coords = {d: v for d, v in zip(dims, grid)} | {"h": np.asarray(h)}
    units = {d: _unit(n) for d, n in zip(dims, [_input_of(d) for d in dims])} | {"h": "1"}
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
            add(k, u, m)
        for k, m in PAD_STRINGS.items():
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
    "area": (0, np.inf, True),
}

#: Ranges of per-point variables, ends included (low, high, NaN allowed: a failed point,
#: the standard deviation of one pad).
VARIABLE_RANGES = {
    **{k: (0, 1, True) for k in ("p_stick", "p_stick_low", "p_stick_high", "p_stick_model")},
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
        if "restoring_force" in f:  # varied: a coordinate, not an attribute
            del wanted["restoring_force"]
    if "preload" in f.attrs:
        wanted |= {"preload": "number"}
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
    if "p_stick" in data and {"p_stick_low", "p_stick_high"} <= data.keys():
        p, low, high = data["p_stick"], data["p_stick_low"], data["p_stick_high"]
        if np.any((low > p) | (p > high)):  # False where NaN: a failed point
            raise schema.refuse(path, WHAT, "dataset p_stick lies outside its interval "
                                            "p_stick_low .. p_stick_high")  # fmt: skip


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
    return "S" if name in STRINGS or name in PAD_STRINGS else "iu" if name == "done" else "f"


def _shapes(name: str, grid: tuple, per_h: tuple) -> tuple[tuple, ...]:
    """Shapes variable ``name`` may have: per point, or per point and separation."""
    if name in CURVES or name.startswith("mc_"):
        return (per_h,)
    if (
        name in SUMMARY
        or name in REGIME
        or name in STRINGS
        or name in PAD_STRINGS
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
