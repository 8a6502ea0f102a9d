"""Parameter sweeps: analytic curves, adhesion summaries (and optionally Monte Carlo) on a grid.

(The module is ``sweeps``, plural, so that the function :func:`mcsim.sweep` is never
shadowed by a submodule of the same name once the module is imported.)

>>> import mcsim
>>> from mcsim.presets import SURFACES, MATERIALS
>>> result = mcsim.sweep(SURFACES["smooth"], MATERIALS["silicon"], law="dmt",
...                      vary={"sigma": "0.3nm:20nm:40:log", "gamma": "0.05:1:5"},
...                      out="design.h5")                               # doctest: +SKIP
>>> result.table()                # one row per grid point          # doctest: +SKIP
>>> xarray.open_dataset("design.h5", engine="h5netcdf")             # doctest: +SKIP

The grid is the outer product of the varied inputs, in the order given (C order: the
last varies fastest). Every point is one independent task: the GW curves of
:func:`mcsim.gw_curves` on approach over ``h``, the regime numbers of
:mod:`mcsim.adhesion` and, for a law set with a net load and a retraction branch,
:func:`mcsim.adhesion.adhesion_summary` (the numbers ``mcsim analytic`` and ``mcsim
adhesion`` give for the same inputs, bit for bit); with ``mc``, one Monte Carlo run
(:func:`mcsim.simulate`, in memory) whose seed derives from (``seed``, point index)
alone. Points run on threads or on Dask; the numbers do not depend on where or in what
order. A point that fails (an out-of-range combination, a root not found) is recorded
with its message; its outputs from the steps before the failure are kept (e.g. the
curves where only the adhesion summary fails), the others are NaN.

File layout (HDF5, netCDF-compatible: ``xarray.open_dataset(path, engine="h5netcdf")``;
every variable has ``units`` and ``long_name`` attributes; schema :data:`SCHEMA_VERSION`):

    dimensions/coordinates  one per varied input, in the order given, named as in
                            ``vary`` (sigma, R, eta, E, E1, E2, nu, nu1, nu2, gamma,
                            z0, tau, H: float64 SI values; law: strings), except the
                            pad area ``area`` whose dimension is ``pad_area`` (m^2;
                            ``area`` is the real-contact-area curve); then ``h``
                            (d/sigma, the separations of the curves)
    curves (..., h)         contact_fraction and the law set's curves as in ``mcsim
                            analytic`` (seed: P, F, T, mu; others: load, area, and with
                            tau friction, mu), dimensionless; NaN where a law set in the
                            sweep lacks the curve
    summary (...)           pull_off, h_pull_off (1), pull_off_pressure (Pa),
                            work_of_separation, hysteresis (J/m^2), turn (1): present
                            when a law set of the sweep has a load and a retraction
                            branch; NaN at the points of a law set without
    regime (...)            tabor, maugis_lambda, adhesion_parameter, plasticity_index
                            (1; NaN where undefined: no z0, no H)
    strings (...)           law_used (the law set of the point, ``auto`` resolved),
                            regime_warning ("" or the regime warnings joined by "; "),
                            error ("" or "ErrorType: message" of a failed point)
    Monte Carlo (..., h)    with ``mc``: mc_<q> and mc_<q>_se, the mean over the
                            realizations and its standard error, for every curve q
    root attributes         sweep_schema_version, mcsim_version, created, command,
                            law, varied (JSON list of the dimension names), surface,
                            material (JSON of the inputs before variation, SI),
                            turn (NaN: zero approach load), mc, and with mc area,
                            realizations, seed_entropy; complete; checksum

Strings are fixed-length UTF-8 bytes with ``_Encoding = "utf-8"`` (netCDF readers give
text). A sweep in progress keeps its completed points in ``<stem>.partial<suffix>``
beside the output (the same layout plus ``done``, 1 per completed point, and
``complete = False``), which ``resume`` continues without recomputing them.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime as _dt
import functools
import json
import logging
import math
import sys
import time
import warnings
from collections.abc import Mapping
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import interrupt, runfile, units
from ._version import __version__
from .adhesion import (
    RegimeWarning,
    adhesion_parameter,
    adhesion_summary,
    choose_law,
    maugis_parameter,
    regime_warnings,
    tabor_parameter,
)
from .analytic import gw_curves, quantities
from .errors import MCSimError, ParameterError, RunFileError
from .laws import get_law_set
from .montecarlo import FIRST_CHECKPOINT, default_workers, in_order
from .params import Material, Surface, check_range, check_separations, plasticity_index
from .units import SI_UNITS, parse_quantity

log = logging.getLogger(__name__)

SCHEMA_VERSION = 1

#: Most points of one sweep.
MAX_POINTS = 1_000_000

#: Separations d/σ of the curves unless given.
DEFAULT_H = tuple(np.linspace(4.0, -1.0, 51).tolist())

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
    "z0": ("length", ("z0",), "equilibrium spacing"),
    "tau": ("pressure", ("tau",), "interfacial shear strength"),
    "H": ("pressure", ("H",), "hardness"),
    "law": ("", ("law",), "law set"),
    "area": ("area", ("area",), "nominal pad area of the Monte Carlo patches"),
}
_SURFACE_FIELDS = {"sigma", "R", "eta"}
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
}


# --- the grid ----------------------------------------------------------------------------


def parse_values(name: str, spec) -> np.ndarray:
    """The values of one varied input: SI floats (strings for ``law``).

    ``spec`` is a range ``"start:stop:num[:log]"`` (inclusive, start <= stop), a comma
    list ``"0.3nm,1nm"``, or a sequence of numbers (SI) or quantity strings. A bare
    number is SI, as in every other option (``gamma=0.05:1:5`` is in J/m²).
    """
    if name not in INPUTS:
        raise ParameterError(f"vary: unknown input {name!r} (allowed: {', '.join(INPUTS)})")
    dimension = INPUTS[name][0]
    where = f"vary {name}"
    if isinstance(spec, str):
        text = spec.strip()
        if not text:
            raise ParameterError(f"{where}: empty list of values")
        if ":" in text and name != "law":
            values = units.parse_values(text, dimension, where, limit=MAX_POINTS, ascending=True)
        else:
            values = [x.strip() for x in text.split(",")]
    else:
        values = list(np.atleast_1d(spec)) if not isinstance(spec, list | tuple) else list(spec)
        if not values:
            raise ParameterError(f"{where}: empty list of values")
    if name == "law":
        laws = []
        for v in values:
            if v != "auto":
                get_law_set(v)  # unknown: names the allowed ones
            laws.append(str(v))
        values = np.array(laws, dtype=str)
    else:
        values = np.array([parse_quantity(_plain(v), dimension, where) for v in values])
    if values.size > MAX_POINTS:
        raise ParameterError(f"{where}: {values.size} values, more than a sweep's "
                             f"{MAX_POINTS} points")  # fmt: skip
    unique, counts = np.unique(values, return_counts=True)
    if np.any(counts > 1):
        raise ParameterError(f"{where}: value {unique[counts > 1][0]!r} appears more than once")
    return values


def _plain(value):
    """A NumPy scalar as a Python number (what :func:`parse_quantity` takes)."""
    return value.item() if isinstance(value, np.generic) else value


def dimension_name(name: str) -> str:
    """Name of the file's dimension for the varied input ``name`` (``area`` → ``pad_area``)."""
    return DIMENSION.get(name, name)


def _unit(name: str) -> str:
    dimension = INPUTS[name][0]
    return "1" if name == "law" else SI_UNITS[dimension]


@dataclass(frozen=True)
class _Point:
    """One grid point: its flat index (C order) and its inputs."""

    index: int
    surface: Surface
    material: Material
    law: str
    area: float | None


@dataclass(frozen=True)
class _Config:
    """What every point shares."""

    h: tuple[float, ...]
    turn: float | None
    mc: bool
    realizations: int
    entropy: int | None
    device: str = "cpu"


def _point(base_surface, base_material, law, area, names, values, index) -> _Point:
    """The inputs at one point; a bad combination raises ParameterError (a failed point)."""
    surface_changes, material_changes = {}, {}
    for name, value in zip(names, values):
        if name == "law":
            law = str(value)
        elif name == "area":
            area = float(value)
        else:
            for f in INPUTS[name][1]:
                (surface_changes if f in _SURFACE_FIELDS else material_changes)[f] = float(value)
    return _Point(index, dataclasses.replace(base_surface, **surface_changes),
                  dataclasses.replace(base_material, **material_changes), law, area)  # fmt: skip


# --- one point -----------------------------------------------------------------------------


def has_summary(law: str) -> bool:
    """Whether ``law`` (or ``auto``) has a net load and a retraction branch."""
    if law == "auto":
        return True
    laws = get_law_set(law)
    return "load" in laws.names and laws.retract


def _curve_names(law: str, material: Material) -> tuple[str, ...]:
    return quantities("jkr" if law == "auto" else law, material)


def evaluate(point: _Point, config: _Config) -> dict:
    """Every output at one point (a dict of floats, arrays over h and strings).

    Where a step fails, the outputs of the steps before it (curves, regime numbers,
    adhesion summary, Monte Carlo, in that order) are kept and ``error`` says why.
    """
    out: dict = {}
    try:
        _evaluate(point, config, out)
    except (MCSimError, ArithmeticError, ValueError, RuntimeError) as err:
        out["error"] = f"{type(err).__name__}: {' '.join(str(err).split())}"
    return out


def _evaluate_quietly(point: _Point, config: _Config) -> dict:
    """:func:`evaluate` on a Dask worker, without printing the regime warnings it records."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        return evaluate(point, config)


def _evaluate(point: _Point, config: _Config, out: dict) -> None:
    surface, material = point.surface, point.material
    law = choose_law(surface, material)[0] if point.law == "auto" else point.law
    out["law_used"] = law
    curves = gw_curves(surface, material, np.asarray(config.h), law)
    out |= curves.values
    out["tabor"] = _number(tabor_parameter(surface, material))
    out["maugis_lambda"] = _number(maugis_parameter(surface, material))
    out["adhesion_parameter"] = adhesion_parameter(surface, material)
    out["plasticity_index"] = _number(plasticity_index(surface, material))
    out["regime_warning"] = "; ".join(regime_warnings(surface, material, law))
    if has_summary(law):
        summary = adhesion_summary(surface, material, law, turn=config.turn)
        out |= {k: getattr(summary, k) for k in SUMMARY}
    if config.mc:
        from .simulation import simulate

        run = simulate(surface, material, np.asarray(config.h), point.area,
                       realizations=config.realizations, seed=point_seed(config.entropy, point.index),
                       law=law, device=config.device, workers=1, command="mcsim.sweep")  # fmt: skip
        for q in run.quantities:
            out[f"mc_{q}"] = run.summary.mean[q]
            out[f"mc_{q}_se"] = run.summary.se[q]


def _number(value: float | None) -> float:
    return math.nan if value is None else float(value)


def point_seed(entropy: int, index: int) -> int:
    """Root seed of the Monte Carlo run at grid point ``index``: 128 bits drawn from
    ``SeedSequence(entropy, spawn_key=(index,))``, the point's own child stream."""
    a, b = np.random.SeedSequence(entropy, spawn_key=(index,)).generate_state(2, np.uint64)
    return (int(a) << 64) | int(b)


# --- the result ----------------------------------------------------------------------------


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
            inputs = {d: _plain(self.coords[d][i]) for d, i in zip(self.grid, idx)}
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
        from . import _display

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


# --- the sweep -----------------------------------------------------------------------------


def sweep(
    surface: Surface,
    material: Material,
    vary: Mapping,
    *,
    law: str | None = None,
    h=DEFAULT_H,
    turn: float | None = None,
    mc: bool = False,
    area: float | str | None = None,
    realizations: int = 1,
    seed: int | None = None,
    device: str = "cpu",
    workers: int | None = None,
    scheduler=None,
    out: str | Path | None = None,
    overwrite: bool = False,
    resume: bool = False,
    checkpoint_every: float = 60.0,
    progress: bool = False,
    command: str | None = None,
) -> Sweep:
    """Analytic curves, adhesion summaries and regime numbers on a grid of inputs.

    Parameters
    ----------
    surface, material : Surface, Material
        The inputs at every point, before the varied ones are set.
    vary : mapping of str to spec
        Input name to its values, in grid order: ``sigma``, ``R``, ``eta`` (surface),
        ``E`` (both E1 and E2), ``E1``, ``E2``, ``nu`` (both), ``nu1``, ``nu2``,
        ``gamma``, ``z0``, ``tau``, ``H`` (material), ``law`` (law-set names or
        ``auto``), ``area`` (pad area, m², with ``mc`` only). Values: a string
        ``"start:stop:num[:log]"`` or ``"a,b,c"`` with optional units (a bare number
        is SI), or a sequence (numbers in SI).
    law : str, optional
        Law set at every point (default ``"seed"``), or ``"auto"`` (chosen per point on
        the adhesion map); not together with a varied ``law``.
    h : array_like
        Separations d/σ of the curves (default 4 … −1, 51 values).
    turn : float, optional
        Closest approach d/σ before retraction for the adhesion summary (default:
        zero approach load, as ``mcsim adhesion``).
    mc : bool
        Also run :func:`mcsim.simulate` at each point (``realizations`` patches of
        ``area``), storing the mean and standard error of each curve.
    area : float or str, optional
        Patch area of the Monte Carlo runs, m² or with a unit.
    realizations : int
        Patches per point.
    seed : int, optional
        Root seed of the Monte Carlo runs; point i uses :func:`point_seed` (seed, i).
    device : {"cpu", "cuda"}
        Where the Monte Carlo runs sample and sum (``"cuda"``: this machine's GPU, see
        :func:`mcsim.simulate`; points then run one after another, not on Dask).
    workers : int, optional
        Local worker threads (all cores by default), or processes of ``"local"`` Dask.
    scheduler : str or dask.distributed.Client, optional
        ``"local"``, a scheduler address or a client, as in :func:`mcsim.simulate`.
    out : path, optional
        Write the sweep (HDF5, see the module docstring) atomically; completed points
        are checkpointed in ``<stem>.partial<suffix>`` beside it.
    overwrite : bool
        Replace an existing file (and start again from scratch).
    resume : bool
        Continue from the checkpoint beside ``out``: completed points are not recomputed.
    checkpoint_every : float
        Seconds between checkpoints (the first after 10 s).
    progress : bool
        A progress bar over the points on stderr.
    command : str, optional
        Provenance string stored in the file (the CLI passes its command line).

    Returns
    -------
    Sweep
        Failed points are in ``Sweep.failed`` (and the ``error`` variable).

    Raises
    ------
    ParameterError
        Bad ``vary`` (unknown input, wrong unit, empty range, duplicate, ``area``
        without ``mc``, more than :data:`MAX_POINTS` points) or other bad input.
    mcsim.interrupt.Interrupted
        On SIGINT or SIGTERM, once the completed points are saved.
    """
    names, grid = _check_vary(vary, law, mc)
    check_range("checkpoint_every", checkpoint_every, "s", low=0.0, low_open=False)
    law = "seed" if law is None else law
    if law != "auto":
        get_law_set(law)
    h = tuple(check_separations(h).tolist())
    turn = None if turn is None else check_range("turn", turn, "1")
    area_m2 = None
    if mc:
        if area is None and "area" not in names:
            raise ParameterError("mc needs the patch area (area=..., --area)")
        if area is not None:
            if "area" in names:
                raise ParameterError("area: given both as a value and as a varied input")
            area_m2 = check_range("area", parse_quantity(area, "area", "area"), "m^2", low=0)
        if isinstance(realizations, bool) or not isinstance(realizations, int) or realizations < 1:
            raise ParameterError(f"realizations = {realizations!r} is out of range (allowed: integer >= 1)")  # fmt: skip
        if device not in ("cpu", "cuda"):
            raise ParameterError(f"device = {device!r} is not one of cpu, cuda")
        if device == "cuda":
            from .cuda import require_gpu

            require_gpu()
            if scheduler is not None:
                raise ParameterError(
                    "device = 'cuda' runs on this machine's GPU: drop the Dask scheduler"
                )
            workers = 1  # one GPU; each point's run keeps it busy
    elif device != "cpu":
        raise ParameterError(
            f"device = {device!r}: the device applies to the Monte Carlo runs only (add mc / --mc)"
        )
    elif area is not None:
        raise ParameterError(
            "area: the pad area applies to the Monte Carlo runs only (add mc / --mc)"
        )
    if resume and out is None:
        raise ParameterError("resume needs the sweep file to continue (out=...)")
    shape = tuple(len(v) for v in grid)
    if math.prod(shape) > MAX_POINTS:
        raise ParameterError(f"vary: the grid has {math.prod(shape)} points "
                             f"({' x '.join(map(str, shape))}), more than the limit of {MAX_POINTS}")  # fmt: skip
    _check_values(surface, material, names, grid)
    dims = [dimension_name(n) for n in names]
    with interrupt.interruptible(), contextlib.ExitStack() as stack:
        previous = None
        if out is not None:
            out = runfile.check_output_path(out, overwrite=overwrite, resume=resume)
            stack.enter_context(runfile.lock(out))
            runfile.check_output_path(out, overwrite=overwrite, resume=resume)
            partial = runfile.checkpoint_path(out)
            if resume and partial.exists():
                previous = _read_partial(partial)
                recorded = previous["attrs"].get("seed_entropy")
                if seed is None and recorded:
                    seed = int(recorded)
            elif resume:
                log.warning("%s: nothing to resume (no checkpoint %s): starting the sweep from "
                            "the beginning", out, partial.name)  # fmt: skip
            else:
                partial.unlink(missing_ok=True)
        entropy = np.random.SeedSequence(seed).entropy if mc else None
        config = _Config(h, turn, mc, realizations, entropy, device)
        laws = list(grid[names.index("law")]) if "law" in names else [law]
        curve_names = _union(_curve_names(x, material) for x in laws)
        if "tau" in names and material.tau is None:
            curve_names = _union([curve_names, _curve_names(laws[0], dataclasses.replace(material, tau=1.0))])  # fmt: skip
        summary = any(has_summary(x) for x in laws)
        result = _empty(dims, grid, h, curve_names, summary, mc)
        if command is None:
            command = (
                f"mcsim.sweep(vary={ {n: _shown(v) for n, v in zip(names, grid)} }, law={law!r})"
            )
        attrs = _attrs(surface, material, law, dims, grid, config, area_m2, command)
        key = attrs["definition"]
        done = np.zeros(shape, dtype=bool)
        if previous is not None:
            if previous["attrs"].get("mcsim_version") != __version__:
                raise RunFileError(f"{partial}: written by mcsim "
                                   f"{previous['attrs'].get('mcsim_version')}; resume it with that version")  # fmt: skip
            if previous["attrs"].get("definition") != key:
                raise ParameterError(f"cannot resume {out}: the inputs differ from the recorded "
                                     "sweep's (same surface, material, law, vary, h, turn, mc "
                                     "options needed)")  # fmt: skip
            done = previous["done"]
            for k in result.data:
                result.data[k][done] = previous["data"][k][done]
        points = (
            _point(surface, material, law, area_m2, names, values, index)
            for index, values in enumerate(_product(grid))
            if not done.flat[index]
        )
        checkpoint = None
        if out is not None:
            checkpoint = functools.partial(_write, partial, result, attrs, complete=False)
        # Recorded per point instead; restored only once the last point has stopped.
        stack.enter_context(warnings.catch_warnings())
        warnings.simplefilter("ignore", RegimeWarning)
        _run(stack, points, config, result, done, workers, scheduler, progress, checkpoint,
             checkpoint_every)  # fmt: skip
        if out is None:
            return dataclasses.replace(result, attrs=attrs)
        _write(out, result, attrs, complete=True)
        partial.unlink(missing_ok=True)
        return dataclasses.replace(result, attrs=attrs, path=out)


def _shown(values: np.ndarray) -> list:
    return [_plain(v) for v in values]


def _union(groups) -> tuple[str, ...]:
    out: dict[str, None] = {}
    for g in groups:
        out |= dict.fromkeys(g)
    return tuple(out)


def _product(grid: list[np.ndarray]):
    """Every combination of the grid's values, C order (the last varies fastest)."""
    shape = tuple(len(v) for v in grid)
    for idx in np.ndindex(*shape):
        yield [v[i] for v, i in zip(grid, idx)]


def _check_vary(vary: Mapping, law: str | None, mc: bool) -> tuple[list[str], list[np.ndarray]]:
    if not isinstance(vary, Mapping) or not vary:
        raise ParameterError("vary: give at least one input to vary (e.g. --vary sigma=0.3nm:20nm:40:log)")  # fmt: skip
    names = list(vary)
    fields: dict[str, str] = {}
    for name in names:
        if name not in INPUTS:
            raise ParameterError(f"vary: unknown input {name!r} (allowed: {', '.join(INPUTS)})")
        for f in INPUTS[name][1]:
            if f in fields:
                raise ParameterError(f"vary: {name!r} and {fields[f]!r} both set {f}: vary one of them")  # fmt: skip
            fields[f] = name
    if "law" in names and law is not None:
        raise ParameterError("law: given both as --law and as a varied input (--vary law=...)")
    if "area" in names and not mc:
        raise ParameterError("vary area: the pad area applies to the Monte Carlo runs only (add --mc)")  # fmt: skip
    return names, [parse_values(n, vary[n]) for n in names]


def _check_values(surface: Surface, material: Material, names, grid) -> None:
    """Each value on its own (with the other inputs at their base values) must be valid."""
    for name, values in zip(names, grid):
        if name in ("law", "area"):
            if name == "area":
                for v in values:
                    check_range("vary area", v, "m^2", low=0)
            continue
        for v in values:
            changes = dict.fromkeys(INPUTS[name][1], float(v))
            base = surface if name in ("sigma", "R", "eta") else material
            try:
                dataclasses.replace(base, **changes)
            except ParameterError as err:
                raise ParameterError(f"vary {name}: {err}") from None


def _empty(dims, grid, h, curve_names, summary: bool, mc: bool) -> Sweep:
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
        for k, (u, m) in SUMMARY.items():
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
    attrs = {"varied": json.dumps(list(dims))}
    return Sweep(coords, data, vdims, units, long_names, attrs)


def _input_of(dim: str) -> str:
    return {v: k for k, v in DIMENSION.items()}.get(dim, dim)


def _attrs(surface, material, law, dims, grid, config: _Config, area, command) -> dict:
    surface_json = json.dumps({"sigma": surface.sigma, "R": surface.R, "eta": surface.eta,
                               "name": surface.name, "heights": runfile.heights_to_json(surface),
                               "units": {"sigma": "m", "R": "m", "eta": "m^-2"}})  # fmt: skip
    material_json = json.dumps({**{k: getattr(material, k) for k in ("E1", "E2", "nu1", "nu2", "gamma", "H", "z0", "tau", "name")},
                                "units": {"E1": "Pa", "E2": "Pa", "nu1": "1", "nu2": "1", "gamma": "J/m^2",
                                          "H": "Pa", "z0": "m", "tau": "Pa"}})  # fmt: skip
    attrs = {
        "sweep_schema_version": SCHEMA_VERSION,
        "mcsim_version": __version__,
        "command": command,
        "law": "varied" if "law" in dims else law,
        "varied": json.dumps(list(dims)),
        "surface": surface_json,
        "material": material_json,
        "turn": math.nan if config.turn is None else config.turn,
        "mc": config.mc,
    }
    if config.mc:
        attrs |= {"area": math.nan if area is None else area, "area_unit": "m^2",
                  "realizations": config.realizations, "seed_entropy": str(config.entropy),
                  "device": config.device}  # fmt: skip
    # What must match for a resume: everything but the time and the command line.
    attrs["definition"] = json.dumps({k: (None if isinstance(v, float) and math.isnan(v) else v)
                                      for k, v in attrs.items() if k != "command"}
                                     | {"h": list(config.h), "values": [_shown(v) for v in grid]})  # fmt: skip
    attrs["created"] = _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
    return attrs


def _run(stack, points, config, result: Sweep, done, workers, scheduler, progress,
         checkpoint, checkpoint_every) -> None:  # fmt: skip
    """Evaluate the points on threads or Dask, storing each result as it arrives (in order)."""
    n_workers = default_workers() if workers is None else workers
    if isinstance(n_workers, bool) or not isinstance(n_workers, int) or n_workers < 1:
        raise ParameterError(f"workers = {workers!r} is out of range (allowed: integer >= 1)")
    bar = None
    if progress:
        from tqdm import tqdm

        bar = stack.enter_context(tqdm(total=done.size, initial=int(done.sum()), unit=" points",
                                       file=sys.stderr, leave=False))  # fmt: skip
    client = scheduler
    if isinstance(scheduler, str):
        from .cluster import dask_client

        client = stack.enter_context(dask_client(scheduler, workers))
    if client is None:
        pool = ThreadPoolExecutor(max_workers=n_workers)
        stack.callback(pool.shutdown, wait=True, cancel_futures=True)
        submit = functools.partial(pool.submit, evaluate, config=config)
        window = 2 * n_workers
    else:
        submit = functools.partial(client.submit, _evaluate_quietly, config=config, pure=False)
        window = 2 * max(1, sum(client.nthreads().values()))
    next_checkpoint = time.monotonic() + min(FIRST_CHECKPOINT, checkpoint_every)
    unsaved = False
    results = stack.enter_context(
        contextlib.closing(in_order(submit, points, window, interrupt.check))
    )
    try:
        for point, values in results:
            _store(result, done, point.index, values)
            unsaved = True
            if bar is not None:
                bar.update(1)
            if checkpoint is not None and time.monotonic() > next_checkpoint:
                checkpoint(done=done)
                unsaved = False
                next_checkpoint = time.monotonic() + checkpoint_every
    except BaseException:
        results.close()
        if checkpoint is not None and unsaved:
            checkpoint(done=done)
        raise


def _store(result: Sweep, done: np.ndarray, index: int, values: dict) -> None:
    idx = np.unravel_index(index, done.shape)
    for k, v in values.items():
        result.data[k][idx] = v
    done[idx] = True


# --- the file -------------------------------------------------------------------------------


def _write(path: Path, result: Sweep, attrs: dict, *, complete: bool, done=None) -> None:
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

    runfile.atomic_write(Path(path), fill)


def _variable(f, name: str, values: np.ndarray, unit: str, long_name: str):
    values = np.asarray(values)
    text = values.dtype.kind in "OUS"
    if text:
        values = np.array([str(v).encode() for v in values.ravel()] or [b""]).reshape(values.shape)
        if values.dtype.itemsize == 0:
            values = values.astype("S1")
    ds = f.create_dataset(name, data=values)
    ds.attrs["units"] = unit
    ds.attrs["long_name"] = long_name
    if text:
        ds.attrs["_Encoding"] = "utf-8"
    return ds


def _read_file(path: Path) -> dict:
    """Attributes, datasets (strings decoded), units and long names of a sweep file or
    checkpoint, verified by its checksum."""
    import h5py

    path = Path(path)
    if not path.is_file():
        raise RunFileError(f"{path}: no such file")
    try:
        with h5py.File(path, "r") as f:
            if "sweep_schema_version" not in f.attrs:
                raise RunFileError(f"{path}: not an mcsim sweep file (no sweep_schema_version)")
            if int(f.attrs["sweep_schema_version"]) != SCHEMA_VERSION:
                raise RunFileError(f"{path}: sweep schema version {f.attrs['sweep_schema_version']} "
                                   f"is not supported (this mcsim reads {SCHEMA_VERSION})")  # fmt: skip
            if f.attrs.get("checksum") != runfile.checksum(f):
                raise RunFileError(f"{path}: damaged sweep file: checksum mismatch")
            attrs = {k: (v.item() if hasattr(v, "item") else v) for k, v in f.attrs.items()}
            data, units, long_names = {}, {}, {}
            for k, ds in f.items():
                values = ds[()]
                if values.dtype.kind == "S":
                    values = np.array([v.decode() for v in values.ravel()], dtype=object)
                    values = values.reshape(ds.shape)
                data[k] = values
                units[k], long_names[k] = str(ds.attrs["units"]), str(ds.attrs["long_name"])
    except MCSimError:
        raise
    except (OSError, KeyError, ValueError, TypeError, RuntimeError) as err:
        reason = " ".join(str(err).split())[:200]  # HDF5's messages span lines
        raise RunFileError(f"{path}: damaged sweep file ({type(err).__name__}: {reason})") from None
    return {"attrs": attrs, "data": data, "units": units, "long_names": long_names}


def _read_partial(path: Path) -> dict:
    """A sweep checkpoint: attributes, ``done`` and data."""
    raw = _read_file(path)
    if "done" not in raw["data"] or raw["attrs"].get("complete"):
        raise RunFileError(f"{path}: not a sweep checkpoint")
    return {**raw, "done": raw["data"]["done"].astype(bool)}


def is_sweep_file(path: str | Path) -> bool:
    """Whether ``path`` is an HDF5 file written by :func:`sweep` (complete or not)."""
    import h5py

    try:
        with h5py.File(path, "r") as f:
            return "sweep_schema_version" in f.attrs
    except Exception:  # not HDF5, or damaged: the run-file reader says what is wrong
        return False


def read_sweep(path: str | Path) -> Sweep:
    """Open a sweep file as a :class:`Sweep` (no xarray needed); refuses a damaged file."""
    path = Path(path)
    raw = _read_file(path)
    grid = tuple(json.loads(raw["attrs"]["varied"]))
    coords = {d: raw["data"].pop(d) for d in (*grid, "h")}
    coords = {d: v.astype(str) if v.dtype == object else v for d, v in coords.items()}
    raw["data"].pop("done", None)
    dims = {k: (*grid, "h") if v.ndim == len(grid) + 1 else grid for k, v in raw["data"].items()}
    return Sweep(coords, raw["data"], dims, raw["units"], raw["long_names"], raw["attrs"], path)
