"""HDF5 run files: atomic, checksummed, resumable; read back as a :class:`~mcsim.store.results.Run`.

Layout (schema version :data:`SCHEMA_VERSION`; every dataset carries a ``unit``
attribute, dimensionless ones ``"1"`` with the normalisation in ``description``):

    /                      attrs: schema_version, mcsim_version, created, command,
                           seed_entropy, law, law_outputs (JSON: name -> unit),
                           quantities (JSON: name -> normalisation), count,
                           area [m^2], realizations, cycle, branches (JSON), turn
                           (d/σ of the closest approach; cycle only),
                           block_size, complete, checksum
    /input/surface         attrs: sigma [m], R [m], eta [m^-2], name, heights (JSON)
    /input/material        attrs: E1, E2 [Pa], nu1, nu2, gamma [J/m^2], H [Pa], name,
                           z0 [m], tau [Pa] (NaN: not given; absent in older files)
    /h, /d                 separations: d/σ and d [m] (M each)
    /branch                (rows,) branch of each row: the M separations on approach,
                           then with ``cycle`` the same M on retraction
    /realizations/N        summits per patch
    /realizations/sums     (R, rows, C) raw sums; attrs columns (sum_columns of the law
                           set) and their units (1, the outputs', their squares, products)
    /progress/n_blocks, /progress/done_blocks   blocks per patch, and done
    -- complete runs only --
    /realizations/<q>      (R, rows) dimensionless curves, q in ``quantities``
    /summary/<stat>/<q>    (rows,) stat in mean, se, std, se_between
    /summary/expected_contacts
    /analytic/<q>          (rows,) GW curves for the same inputs (expected values)
    /heights/<r>           optional: sampled heights above s_min [m]
    -- runs with an environment only (mcsim.engine.cells; absent otherwise) --
    /environment           attrs: hamaker [J], cutoff [m], rh, contact_angle [rad],
                           temperature [K], surface_tension [J/m^2], molar_volume
                           [m^3/mol], kelvin_radius [m], units (JSON), rq [m],
                           summit_offset [m], gap_source (given or the Nayak estimate),
                           map_heights (JSON: "gaussian" or the histogram), cell_model
    /environment/n_cells   cells per patch (one per summit)
    /environment/sums      (R, rows, 4) Σp_vdW, Σp_vdW², Σp_cap, Σp_cap² over the cells
    /environment/realizations/<t>, /environment/summary/{mean,se}/<t>,
    /environment/analytic/<t>   (R, rows) or (rows,) pressures / K, t in vdw, capillary

Schema 1 (mcsim 0.1: the seed law set, approach only, no law_outputs, quantities,
cycle, branches, turn, z0, tau or /branch) is still read, with identical results.

Named axes: every group whose datasets have an axis h (M), realization (R) or column
(the 10 sums columns) holds that axis's coordinate as an HDF5 dimension scale of the same
name, attached to those datasets, so netCDF readers (xarray with h5netcdf) name the
dimensions alike in every group and give their values. Files written before the scales
were added read the same.

Guarantees:

* every file is written under a temporary name in the target folder and moved into
  place with one atomic rename, so the path holds either nothing, an earlier
  complete file or a new complete file — never half a file;
* the file is built in memory and written with plain writes, so a full disk fails
  cleanly (one line, the temporary removed), never inside the HDF5 library;
* a run in progress checkpoints itself beside its path, in :func:`checkpoint_path`
  (``<stem>.partial<suffix>``), as an *incomplete* run (``complete = False``, sums of
  the blocks done so far), which ``--resume`` continues; the path itself only ever
  receives complete runs;
* a complete run is never replaced without ``overwrite``; an ``flock`` on
  ``<name>.lock`` keeps two processes from writing the same path;
* ``checksum`` (SHA-256 over every dataset and attribute) and the shapes are checked
  on every read: a truncated or edited file is refused.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import json
import math
from pathlib import Path

import numpy as np

from mcsim._version import __version__
from mcsim.engine.kernels import sum_columns, sum_units
from mcsim.engine.montecarlo import BLOCK, EnsembleSums, MonteCarloSpec
from mcsim.engine.statistics import Summary, quantities
from mcsim.model.distributions import GAUSSIAN
from mcsim.model.errors import MCSimError, RunFileError
from mcsim.model.params import Material, Surface
from mcsim.store import schema
from mcsim.store.envgroup import read_environment, write_environment
from mcsim.store.files import atomic_write, checksum
from mcsim.store.h5layout import AXES, dataset, row_axis
from mcsim.store.results import STATS, Run, assemble, environment_run

SCHEMA_VERSION = 2

#: Schema versions this mcsim reads.
READABLE = (1, 2)

#: The file kind, in messages.
WHAT = "run file"


# --- locking --------------------------------------------------------------------------


# --- writing --------------------------------------------------------------------------


def heights_to_json(surface: Surface) -> str:
    """The summit-height distribution as run and sweep files store it (JSON text)."""
    heights = surface.heights
    if heights == GAUSSIAN:
        return json.dumps({"name": "gaussian"})
    return json.dumps({"name": heights.name, **heights.to_dict()})


def _heights_from_dict(data: dict):
    """Inverse of :func:`heights_to_json`, from the parsed JSON object."""
    if data.get("name") == "gaussian":
        return GAUSSIAN
    from mcsim.topography.empirical import Empirical

    return Empirical.from_dict({k: v for k, v in data.items() if k != "name"})


def _write_inputs(f, spec: MonteCarloSpec, command: str, complete: bool, extra=None) -> dict:
    attrs = {
        "schema_version": SCHEMA_VERSION,
        "mcsim_version": __version__,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "command": command,
        "seed_entropy": str(spec.entropy),
        "law": spec.law,
        "law_outputs": json.dumps({o.name: o.unit for o in spec.law_set.outputs}),
        "quantities": json.dumps(
            {q: v.normalisation for q, v in quantities(spec.law_set, spec.material).items()}
        ),
        "count": spec.count,
        "area": spec.area,
        "area_unit": "m^2",
        "realizations": spec.realizations,
        "cycle": spec.cycle,
        "device": spec.device,
        "branches": json.dumps(list(spec.branches)),
        **({"turn": spec.turn} if spec.cycle else {}),
        "block_size": BLOCK,
        "complete": complete,
        **(extra or {}),
    }
    f.attrs.update(attrs)
    s = f.create_group("input/surface")
    s.attrs.update(sigma=spec.surface.sigma, R=spec.surface.R, eta=spec.surface.eta,
                   name=spec.surface.name, heights=heights_to_json(spec.surface))  # fmt: skip
    s.attrs["units"] = json.dumps({"sigma": "m", "R": "m", "eta": "m^-2"})
    m = f.create_group("input/material")
    mat = spec.material
    m.attrs.update(E1=mat.E1, E2=mat.E2, nu1=mat.nu1, nu2=mat.nu2, gamma=mat.gamma,
                   H=np.nan if mat.H is None else mat.H, name=mat.name)  # fmt: skip
    m.attrs.update({k: np.nan if getattr(mat, k) is None else getattr(mat, k) for k in ("z0", "tau")})  # fmt: skip
    m.attrs["units"] = json.dumps({"E1": "Pa", "E2": "Pa", "nu1": "1", "nu2": "1", "gamma": "J/m^2",
                                   "H": "Pa", "z0": "m", "tau": "Pa"})  # fmt: skip
    dataset(f, "h", spec.h, *AXES["h"]).make_scale("h")
    dataset(f, "d", spec.d, "m", "mean separation", dims=("h",))
    if spec.cycle:
        dataset(f, "row", spec.row_h, *AXES["row"]).make_scale("row")
    dataset(f, "branch", spec.row_branch.astype("S"), "1", "branch of each row of the sums",
             dims=(row_axis(spec),))  # fmt: skip
    return attrs


def _write_state(f, state: EnsembleSums) -> None:
    per_realization = ("realization",)
    dataset(f, "realizations/N", state.n_summits, "1", "summits in the patch", per_realization)
    sums = dataset(
        f,
        "realizations/sums",
        state.sums,
        "per column, see units",
        "raw per-row sums over the blocks done",
        ("realization", row_axis(state.spec), "column"),
    )
    sums.attrs["columns"] = list(sum_columns(state.spec.law_set))
    sums.attrs["units"] = list(sum_units(state.spec.law_set))
    blocks = f"blocks of {BLOCK} summits above s_min"
    dataset(f, "progress/n_blocks", state.n_blocks, "1", blocks, per_realization)
    dataset(f, "progress/done_blocks", state.done_blocks, "1", "blocks done", per_realization)


def write_checkpoint(
    path: str | Path, state: EnsembleSums, *, command: str, extra: dict | None = None
) -> None:
    """Write a run in progress (``complete = False``), replacing the previous checkpoint.

    ``extra``: further root attributes (numbers or strings), as for :func:`write_run`.
    """

    def fill(f):
        _write_inputs(f, state.spec, command, complete=False, extra=extra)
        _write_state(f, state)

    atomic_write(Path(path), fill)


def write_run(path: str | Path, run, *, command: str, extra: dict | None = None):
    """Write a complete ``run`` (a :class:`mcsim.store.results.Run`); return it with path and attrs.

    The caller holds :func:`lock` and has checked the path with :func:`check_output_path`.
    ``extra``: further root attributes, numbers or strings (provenance such as
    ``load_control``, the JSON list of nominal pressures, Pa, that a load-controlled
    run's separations balance).
    """
    import dataclasses

    path = Path(path)
    attrs: dict = {}

    def fill(f):
        attrs.update(_write_inputs(f, run.spec, command, complete=True, extra=extra))
        _write_state(f, run.ensemble)
        per_row = (row_axis(run.spec),)
        for q in run.quantities:
            norm = run.normalisation(q)
            curves = run.realizations[q]
            dataset(f, f"realizations/{q}", curves, "1", norm, ("realization", per_row[0]))
            dataset(f, f"analytic/{q}", run.analytic[q], "1", norm, per_row)
            for stat in STATS:
                values = getattr(run.summary, stat)[q]
                dataset(f, f"summary/{stat}/{q}", values, "1", norm, per_row)
        expected = run.summary.expected_contacts
        dataset(f, "summary/expected_contacts", expected, "1", "R E[N] S(s)", per_row)
        if run.heights is not None:
            for r, z in enumerate(run.heights):
                dataset(
                    f,
                    f"heights/{r}",
                    z,
                    "m",
                    "sampled heights above s_min",
                    compression="gzip",
                    shuffle=True,
                )

        if run.environment is not None:
            write_environment(f, run)

    atomic_write(path, fill)
    return dataclasses.replace(run, path=path, attrs=attrs)


# --- reading --------------------------------------------------------------------------


def _open(path: Path):
    import h5py

    if not path.is_file():
        raise RunFileError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise RunFileError(f"{path}: not an HDF5 file, or truncated") from None
    try:
        with _damaged(path):
            version = f.attrs.get("schema_version")
            if version is None:
                raise RunFileError(f"{path}: not an mcsim run file (no schema_version)")
            if not (np.ndim(version) == 0 and np.issubdtype(np.asarray(version).dtype, np.integer)):
                raise RunFileError(
                    f"{path}: damaged run file: schema_version is {schema.shown(version)}, not an integer"
                )
            if int(version) not in READABLE:
                raise RunFileError(
                    f"{path}: run-file schema version {int(version)} is not supported "
                    f"(this mcsim {__version__} reads versions {', '.join(map(str, READABLE))})"
                )
            schema.check_sizes(path, f, WHAT)
    except BaseException:
        f.close()
        raise
    return f


#: Root attributes a run file holds (every schema), and their kinds
#: (:data:`mcsim.store.schema.KINDS`).
ATTRIBUTES = {
    "mcsim_version": "text",
    "created": "text",
    "command": "text",
    "seed_entropy": "digits",
    "law": "text",
    "count": "text",
    "area": "number",
    "realizations": "integer",
    "block_size": "integer",
    "complete": "boolean",
}

#: Root attributes of schema 2 (optional ones: absent in files written before them).
ATTRIBUTES_2 = {"law_outputs": "JSON object", "quantities": "JSON object", "cycle": "boolean",
                "branches": "JSON list"}  # fmt: skip
OPTIONAL = {"device": "text", "turn": "number", "load_control": "JSON object"}

#: Attributes of /input/surface and /input/material (NaN: not given), and their kinds.
SURFACE = {
    "sigma": "number",
    "R": "number",
    "eta": "number",
    "name": "text",
    "heights": "JSON object",
}
MATERIAL = {k: "number" for k in ("E1", "E2", "nu1", "nu2", "gamma")} | {"name": "text"}
MATERIAL_OPTIONAL = {k: "number" for k in ("H", "z0", "tau")}


def _attributes(path: Path, f) -> dict:
    """The root attributes a reader uses, checked against :data:`ATTRIBUTES`."""
    version = int(f.attrs["schema_version"])  # checked by _open
    wanted = ATTRIBUTES | (ATTRIBUTES_2 if version >= 2 else {})
    wanted |= {k: kind for k, kind in OPTIONAL.items() if k in f.attrs}
    attrs = {k: schema.attribute(path, f, k, kind, WHAT) for k, kind in wanted.items()}
    if "load_control" in attrs:
        pressure = attrs["load_control"].get("pressure")
        if not (isinstance(pressure, list) and pressure and all(
            isinstance(p, (int, float)) and not isinstance(p, bool) and math.isfinite(p) for p in pressure
        )):  # fmt: skip
            raise schema.refuse(
                path,
                WHAT,
                "attribute load_control has no 'pressure': a list of finite numbers (Pa)",
            )
    return attrs


def _inputs(path: Path, f) -> tuple[Surface, Material]:
    """The surface and material of /input, checked against :data:`SURFACE` and :data:`MATERIAL`."""
    import h5py

    for group in ("input/surface", "input/material"):
        if not isinstance(f.get(group), h5py.Group):
            raise schema.refuse(path, WHAT, f"group {group} is missing")
    s, m = f["input/surface"], f["input/material"]
    s = {k: schema.attribute(path, s, k, kind, WHAT) for k, kind in SURFACE.items()}
    optional = {k: kind for k, kind in MATERIAL_OPTIONAL.items() if k in m.attrs}
    m = {k: schema.attribute(path, m, k, kind, WHAT) for k, kind in (MATERIAL | optional).items()}
    try:
        heights = _heights_from_dict(s.pop("heights"))
        surface = Surface(**s, heights=heights)
    except MCSimError as err:
        raise schema.refuse(path, WHAT, f"input/surface: {err}") from None
    for k in MATERIAL_OPTIONAL:
        m[k] = None if math.isnan(m.get(k, math.nan)) else m[k]
    try:
        material = Material(**m)
    except MCSimError as err:
        raise schema.refuse(path, WHAT, f"input/material: {err}") from None
    return surface, material


def _read_state(path: Path, f) -> tuple[EnsembleSums, dict]:
    """The sums and progress of an open run file, and its root attributes (those a
    reader uses checked against :data:`ATTRIBUTES`; NumPy scalars as Python values)."""
    attrs = _attributes(path, f)
    surface, material = _inputs(path, f)
    h = schema.dataset(path, f, "h", "f", None, WHAT)
    try:
        spec = MonteCarloSpec(surface, material, h, attrs["area"], attrs["realizations"],
                              int(attrs["seed_entropy"]), attrs["law"], attrs["count"],
                              attrs.get("cycle", False), attrs.get("device", "cpu"))  # fmt: skip
    except MCSimError as err:
        raise schema.refuse(path, WHAT, f"inputs: {err}") from None
    R, M, rows = spec.realizations, spec.h.size, spec.row_h.size
    columns = sum_columns(spec.law_set)
    expected = {
        "d": ("f", (M,)),
        "realizations/N": ("iu", (R,)),
        "realizations/sums": ("f", (R, rows, len(columns))),
        "progress/n_blocks": ("iu", (R,)),
        "progress/done_blocks": ("iu", (R,)),
    }
    version = int(f.attrs["schema_version"])  # checked by _open
    if version >= 2:
        expected["branch"] = ("S", (rows,))
    if attrs["complete"]:
        names = _quantities(spec)
        expected |= {f"realizations/{q}": ("f", (R, rows)) for q in names}
        expected |= {f"analytic/{q}": ("f", (rows,)) for q in names}
        expected |= {f"summary/{stat}/{q}": ("f", (rows,)) for stat in STATS for q in names}
        expected["summary/expected_contacts"] = ("f", (rows,))
    for name, (dtype, shape) in expected.items():
        schema.dataset(path, f, name, dtype, shape, WHAT)
    if version >= 2:
        stored = f["realizations/sums"].attrs.get("columns")
        if np.ndim(stored) != 1 or [_text(c) for c in stored] != list(columns):
            raise schema.refuse(path, WHAT, f"attribute realizations/sums@columns is "
                                f"{schema.shown(stored)}, law set {spec.law!r} has {list(columns)}")  # fmt: skip
    if attrs["block_size"] != BLOCK:
        raise RunFileError(
            f"{path}: written with blocks of {attrs['block_size']} summits, this mcsim uses {BLOCK}"
        )
    state = EnsembleSums(spec, f["realizations/N"][()], f["realizations/sums"][()],
                         f["progress/n_blocks"][()], f["progress/done_blocks"][()])  # fmt: skip
    # A checkpoint may have every block done (saved after the last task, before the run
    # file was written); a complete run must.
    if bool(attrs["complete"]) and not state.complete:
        raise RunFileError(f"{path}: damaged run file: progress disagrees with the 'complete' flag")
    plain = {
        k: (v.item() if np.ndim(v) == 0 and hasattr(v, "item") else v) for k, v in f.attrs.items()
    }
    return state, plain | {k: v for k, v in attrs.items() if not isinstance(v, (dict, list))}


def _text(value) -> str | None:
    """A stored name as text (None: not text)."""
    if isinstance(value, bytes):
        return value.decode(errors="replace")
    return value if isinstance(value, str) else None


def _heights(path: Path, f, realizations: int) -> list[np.ndarray] | None:
    """The sampled heights of a run made with ``keep_heights`` (None: not kept)."""
    import h5py

    if "heights" not in f:
        return None
    group = f["heights"]
    names = [str(r) for r in range(realizations)]
    if not isinstance(group, h5py.Group) or sorted(group) != sorted(names):
        raise schema.refuse(
            path, WHAT, f"heights must be a group of datasets {names[0]} .. {names[-1]}"
        )
    out = []
    for r in names:
        z = schema.dataset(path, f, f"heights/{r}", "f", None, WHAT)
        if z.ndim != 1:
            raise schema.refuse(
                path, WHAT, f"dataset heights/{r} has shape {z.shape}, expected (n,)"
            )
        out.append(z[()])
    return out


def _quantities(spec: MonteCarloSpec) -> tuple[str, ...]:
    """Names of the stored curves of a run (schema 1: the seed's)."""
    return tuple(quantities(spec.law_set, spec.material))


def _verified(path: Path, f) -> None:
    stored = f.attrs.get("checksum")
    if not isinstance(stored, str) or checksum(f) != stored:
        raise RunFileError(f"{path}: damaged run file: checksum mismatch (truncated or edited)")


@contextlib.contextmanager
def _damaged(path: Path):
    """Report anything a damaged file makes h5py or the parameter checks raise as damage."""
    try:
        yield
    except MCSimError:
        raise
    except (KeyError, ValueError, TypeError, OSError, RuntimeError, AttributeError, IndexError,
            OverflowError) as err:  # fmt: skip
        reason = " ".join(str(err).split())[:200]  # HDF5's messages span lines
        raise RunFileError(f"{path}: damaged run file ({type(err).__name__}: {reason})") from None


def read_state(path: str | Path) -> tuple[EnsembleSums, dict]:
    """The sums and progress of a run file (complete or not), for resuming, and its attributes."""
    path = Path(path)
    with _open(path) as f, _damaged(path):
        _verified(path, f)
        return _read_state(path, f)


def read_run(path: str | Path, *, allow_incomplete: bool = False):
    """Open a run file as a :class:`mcsim.store.results.Run`.

    Refuses other schema versions, damaged files (checksum, shapes) and, unless
    ``allow_incomplete``, runs that did not finish. With ``allow_incomplete`` an
    unfinished run is summarised over its completed realizations (``run.complete``
    is then False).
    """
    path = Path(path)
    with _open(path) as f, _damaged(path):
        _verified(path, f)
        state, attrs = _read_state(path, f)
        if not attrs["complete"]:
            if not allow_incomplete:
                done = int(np.sum(state.done_blocks == state.n_blocks))
                raise RunFileError(
                    f"{path}: incomplete run ({done} of {state.spec.realizations} realizations done); "
                    "resume it with `mcsim simulate ... --resume`, or use the completed part (--partial)"
                )
            return assemble(state.completed(), attrs=attrs, path=path, complete=False)
        names = _quantities(state.spec)
        stats = {stat: {q: f[f"summary/{stat}/{q}"][()] for q in names} for stat in STATS}
        heights = _heights(path, f, state.spec.realizations)
        cells = read_environment(path, f, state.spec)
        return Run(
            environment=None if cells is None else environment_run(state.spec, cells),
            ensemble=state,
            realizations={q: f[f"realizations/{q}"][()] for q in names},
            summary=Summary(**stats, expected_contacts=f["summary/expected_contacts"][()]),
            analytic={q: f[f"analytic/{q}"][()] for q in names},
            attrs=attrs,
            path=path,
            heights=heights,
        )
