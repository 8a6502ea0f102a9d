"""HDF5 run files: atomic, checksummed, resumable; read back as a :class:`~mcsim.store.results.Run`.

Layout (schema version :data:`SCHEMA_VERSION`, netCDF-compatible: ``xarray.open_dataset(path,
group=..., engine="h5netcdf")`` or ``xarray.open_datatree``). Every dataset, coordinates
included, has the CF attributes ``units`` (UDUNITS text: ``"1"`` for dimensionless values
and names, ``"m"``, ``"N m^2"``, ...) and ``long_name`` (words); a dimensionless curve
keeps its normalisation (``"load/(A K)"``) in ``description``. ``rows`` below stands for
the axes ``(h)`` of an approach, or ``(branch, h)`` of a cycle (``--cycle``: the branches
"approach" and "retract", both over the same h):

    /                      attrs: schema_version, mcsim_version, created, command,
                           seed_entropy, law, law_outputs (JSON: name -> unit),
                           quantities (JSON: name -> normalisation), count,
                           area [m^2], realizations, cycle, branches (JSON), turn
                           (d/σ of the closest approach; cycle only),
                           block_size, complete, checksum; load_control (JSON: the
                           nominal pressures, Pa, the separations balance: simulate
                           --pressure/--load only); with a rough counter-surface
                           (simulate --counter-surface): surface_as_given,
                           counter_surface (JSON: sigma [m], R [m], eta [m^-2], name,
                           units) and correlation (rho), the parts of /input/surface
    /input/surface         attrs: sigma [m], R [m], eta [m^-2], name, heights (JSON);
                           radius_by_height (JSON: band edges in s, factors of R; absent:
                           one radius R)
    /input/material        attrs: E1, E2 [Pa], nu1, nu2, gamma [J/m^2], H [Pa], name,
                           z0 [m], tau [Pa] (NaN: not given; absent in older files)
    /h, /d                 coordinate h = d/σ, and d [m] over it (M each)
    /branch                coordinate (2,): "approach", "retract" (cycle only)
    /realizations/N        (realization) summits per patch
    /realizations/sums/<c> (realization, rows) raw sum of column c over the blocks done,
                           c in the law set's sum_columns (n_contact, each output, its
                           square, the products), each with its own units
    /progress/n_blocks, /progress/done_blocks   (realization) blocks per patch, and done
    -- complete runs only --
    /realizations/<q>      (realization, rows) dimensionless curves, q in ``quantities``
    /summary/<stat>/<q>    (rows) stat in mean, se, std, se_between
    /summary/expected_contacts
    /analytic/<q>          (rows) GW curves for the same inputs (expected values)
    /heights/z, /heights/count   optional (``--keep-heights``): the sampled heights above
                           s_min [m] of every patch, one after another (summit), and the
                           number per patch (realization): a CF contiguous ragged array
    -- runs with an environment only (absent otherwise; the summits' caps vdw, capillary
       are outputs of the law set, stored with the sums above) --
    /environment           attrs: hamaker [J], cutoff [m], rh, contact_angle [rad],
                           temperature [K], surface_tension [J/m^2], molar_volume
                           [m^3/mol], film_thickness [m] (NaN: the isotherm),
                           structured_film [m], asperity_roughness [m], retardation_wavelength [m] (NaN: non-retarded;
                           absent in older files, read as non-retarded), kelvin_radius [m], film (the adsorbed
                           film used) [m], band_edge [m], units (JSON),
                           rq [m], summit_offset [m], gap_source (given or the Nayak
                           estimate), map_heights (JSON: "gaussian" or the histogram), model
    /environment/open_gaps/<t>  (rows) open gaps' pressure / K, t in vdw, capillary

Named axes: every group whose datasets have an axis h, branch, realization or summit
holds that axis's coordinate as an HDF5 dimension scale of the same name, attached to
those datasets, so netCDF readers name the dimensions alike in every group and give
their values. A variable named ``load`` (the law sets' net normal force) is read as
``ds["load"]``: ``ds.load`` is xarray's method that reads a dataset into memory.

Storage: datasets above :data:`mcsim.store.files.COMPRESS_ABOVE` bytes (the per-patch
curves and sums, the kept heights) are chunked, byte-shuffled and gzip-compressed,
HDF5's built-in filters that plain h5py and every netCDF reader decode; smaller ones are
contiguous.

Older schemas are still read, with identical results: schema 2 (units in ``unit``, the
sums one (R, rows, C) array ``/realizations/sums`` with attributes ``columns`` and
``units``, a cycle's 2M rows on one axis ``row`` with ``/branch`` the branch of each row,
kept heights one dataset ``/heights/<r>`` per patch) and schema 1 (mcsim 0.1: the seed
law set, approach only, no law_outputs, quantities, cycle, branches, turn, z0, tau or
/branch; files written before the dimension scales read the same).

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
from mcsim.engine.kernels import sum_columns
from mcsim.engine.montecarlo import BLOCK, EnsembleSums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.engine.statistics import Summary, quantities
from mcsim.model.errors import MCSimError, RunFileError
from mcsim.store import schema
from mcsim.store.envgroup import read_environment, write_environment
from mcsim.store.files import atomic_write, checksum, file_path
from mcsim.store.h5layout import (
    AXES,
    STAT_WORDS,
    axis_scale,
    by_branch,
    curve_long_name,
    dataset,
    read_rows,
    row_dims,
    row_shape,
    sum_variables,
)
from mcsim.store.inputgroup import read_inputs, write_inputs
from mcsim.store.results import STATS, Run, assemble, environment_run

SCHEMA_VERSION = 3

#: Schema versions this mcsim reads.
READABLE = (1, 2, 3)

#: The file kind, in messages.
WHAT = "run file"


# --- locking --------------------------------------------------------------------------


# --- writing --------------------------------------------------------------------------


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
    write_inputs(f, spec.surface, spec.material)
    dataset(f, "h", spec.h, *AXES["h"]).make_scale("h")
    dataset(f, "d", spec.d, "m", "mean separation d of the surfaces", dims=("h",))
    if spec.cycle:
        axis_scale(f, "branch", len(spec.branches))
    if spec.environment is not None:  # it sets the sums' columns: checkpoints need it too
        write_environment(f, spec, environment_run(spec))
    return attrs


def _write_state(f, state: EnsembleSums) -> None:
    spec = state.spec
    per_realization = ("realization",)
    dataset(f, "realizations/N", state.n_summits, "1", "summits in the patch", per_realization)
    per_row = ("realization", *row_dims(spec))
    for k, (column, units, words) in enumerate(sum_variables(spec.law_set)):
        dataset(f, f"realizations/sums/{column}", by_branch(spec, state.sums[..., k], 1), units,
                words, per_row, "raw sum of each patch and separation over the blocks done")  # fmt: skip
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
    spec = run.spec

    def fill(f):
        attrs.update(_write_inputs(f, spec, command, complete=True, extra=extra))
        _write_state(f, run.ensemble)
        rows = row_dims(spec)
        for q in run.quantities:
            norm, words = run.normalisation(q), curve_long_name(q, spec.law_set)
            dataset(f, f"realizations/{q}", by_branch(spec, run.realizations[q], 1), "1", words,
                    ("realization", *rows), norm)  # fmt: skip
            dataset(f, f"analytic/{q}", by_branch(spec, run.analytic[q], 0), "1",
                    f"GW expected value of {q}: {words}", rows, norm)  # fmt: skip
            for stat in STATS:
                values = by_branch(spec, getattr(run.summary, stat)[q], 0)
                dataset(f, f"summary/{stat}/{q}", values, "1", f"{STAT_WORDS[stat]} of {q}: {words}",
                        rows, norm)  # fmt: skip
        expected = by_branch(spec, run.summary.expected_contacts, 0)
        dataset(f, "summary/expected_contacts", expected, "1",
                "expected summits carrying force over the whole ensemble", rows, "R E[N] S(s)")  # fmt: skip
        if run.heights is not None:
            _write_heights(f, run.heights)

    atomic_write(path, fill)
    return dataclasses.replace(run, path=path, attrs=attrs)


def _write_heights(f, heights: list[np.ndarray]) -> None:
    """The kept heights as a CF contiguous ragged array: /heights/z (summit), the patches
    one after another, and /heights/count (realization), summits per patch."""
    count = dataset(f, "heights/count", [z.size for z in heights], "1",
                    "summits kept in the patch", ("realization",))  # fmt: skip
    count.attrs["sample_dimension"] = "summit"
    dataset(f, "heights/z", np.concatenate(heights), "m", "sampled summit heights above s_min",
            ("summit",))  # fmt: skip


# --- reading --------------------------------------------------------------------------


def _open(path: Path):
    import h5py

    if not path.is_file():  # absent, or a folder or a pipe (which h5py would block on)
        raise RunFileError(
            f"{path}: " + ("not a regular file" if path.exists() else "no such file")
        )
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise RunFileError(f"{path}: not an HDF5 file, or truncated") from None
    try:
        with _damaged(path):
            version = f.attrs.get("schema_version")
            if version is None and "sweep_schema_version" in f.attrs:
                raise RunFileError(f"{path}: a sweep file (mcsim sweep), not a run file: "
                                   f"read it with mcsim show {path} or mcsim plot {path}")  # fmt: skip
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
OPTIONAL = {"device": "text", "turn": "number", "load_control": "JSON object", "preload": "number",
            "preload_turn_mean_field": "number"}  # fmt: skip


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
    if "preload" in attrs:  # Pa, written only >= 0 (studies.simulation checks it)
        schema.within(path, "attribute preload", attrs["preload"], WHAT, low=0)
    if "preload_turn_mean_field" in attrs:
        schema.within(
            path, "attribute preload_turn_mean_field", attrs["preload_turn_mean_field"], WHAT
        )
    return attrs


def _read_state(path: Path, f) -> tuple[EnsembleSums, dict]:
    """The sums and progress of an open run file, and its root attributes (those a
    reader uses checked against :data:`ATTRIBUTES`; NumPy scalars as Python values)."""
    attrs = _attributes(path, f)
    surface, material = read_inputs(path, f, WHAT)
    h = schema.dataset(path, f, "h", "f", None, WHAT)
    environment, surface = read_environment(path, f, surface)
    try:
        spec = MonteCarloSpec(surface, material, h, attrs["area"], attrs["realizations"],
                              int(attrs["seed_entropy"]), attrs["law"], attrs["count"],
                              attrs.get("cycle", False), attrs.get("device", "cpu"),
                              environment)  # fmt: skip
    except MCSimError as err:
        raise schema.refuse(path, WHAT, f"inputs: {err}") from None
    R, M, rows = spec.realizations, spec.h.size, spec.row_h.size
    columns = sum_columns(spec.law_set)
    version = int(f.attrs["schema_version"])  # checked by _open
    per_row = row_shape(spec, version)
    expected = {
        "d": ("f", (M,)),
        "realizations/N": ("iu", (R,)),
        "progress/n_blocks": ("iu", (R,)),
        "progress/done_blocks": ("iu", (R,)),
    }
    if version >= 3:
        expected |= {f"realizations/sums/{c}": ("f", (R, *per_row)) for c in columns}
    else:
        expected["realizations/sums"] = ("f", (R, rows, len(columns)))
    if version == 2:
        expected["branch"] = ("S", (rows,))
    if version >= 3 and spec.cycle:
        expected["branch"] = ("S", (len(spec.branches),))
    if attrs["complete"]:
        names = _quantities(spec)
        expected |= {f"realizations/{q}": ("f", (R, *per_row)) for q in names}
        expected |= {f"analytic/{q}": ("f", per_row) for q in names}
        expected |= {f"summary/{stat}/{q}": ("f", per_row) for stat in STATS for q in names}
        expected["summary/expected_contacts"] = ("f", per_row)
    for name, (dtype, shape) in expected.items():
        schema.dataset(path, f, name, dtype, shape, WHAT)
    if version == 2:
        stored = f["realizations/sums"].attrs.get("columns")
        if np.ndim(stored) != 1 or [_text(c) for c in stored] != list(columns):
            raise schema.refuse(path, WHAT, f"attribute realizations/sums@columns is "
                                f"{schema.shown(stored)}, law set {spec.law!r} has {list(columns)}")  # fmt: skip
    if version >= 3 and spec.cycle:
        stored = [_text(b) for b in f["branch"][()]]
        if stored != list(spec.branches):
            raise schema.refuse(path, WHAT, f"coordinate branch is {schema.shown(stored)}, "
                                            f"a cycle has {list(spec.branches)}")  # fmt: skip
    if attrs["block_size"] != BLOCK:
        raise RunFileError(
            f"{path}: written with blocks of {attrs['block_size']} summits, this mcsim uses {BLOCK}"
        )
    if version >= 3:
        sums = np.stack([read_rows(f, f"realizations/sums/{c}", spec, version, 1) for c in columns],
                        axis=-1)  # fmt: skip
    else:
        sums = f["realizations/sums"][()]
    state = EnsembleSums(spec, f["realizations/N"][()], sums, f["progress/n_blocks"][()],
                         f["progress/done_blocks"][()])  # fmt: skip
    _check_counts(path, state, version)
    # A checkpoint may have every block done (saved after the last task, before the run
    # file was written); a complete run must.
    if bool(attrs["complete"]) and not state.complete:
        raise RunFileError(f"{path}: damaged run file: progress disagrees with the 'complete' flag")
    plain = {
        k: (v.item() if np.ndim(v) == 0 and hasattr(v, "item") else v) for k, v in f.attrs.items()
    }
    return state, plain | {k: v for k, v in attrs.items() if not isinstance(v, (dict, list))}


def _check_counts(path: Path, state: EnsembleSums, version: int) -> None:
    """Refuse counts and sums that no run can hold: negative summits or blocks, more blocks
    done than planned, sums that are not finite, a negative count of contacts or sum of
    squares."""
    schema.within(path, "dataset realizations/N", state.n_summits, WHAT, low=0)
    schema.within(path, "dataset progress/n_blocks", state.n_blocks, WHAT, low=0)
    schema.within(path, "dataset progress/done_blocks", state.done_blocks, WHAT, low=0)
    if np.any(state.done_blocks > state.n_blocks):
        raise schema.refuse(path, WHAT, "dataset progress/done_blocks counts more blocks than "
                                        "progress/n_blocks plans")  # fmt: skip
    squares = {n + n for n in state.spec.law_set.names}
    for k, c in enumerate(sum_columns(state.spec.law_set)):
        field = (
            f"dataset realizations/sums/{c}"
            if version >= 3
            else f"column {c} of dataset realizations/sums"
        )
        low = 0 if c == "n_contact" or c in squares else -np.inf  # a count, a sum of squares
        schema.within(path, field, state.sums[..., k], WHAT, low=low)


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
    if int(f.attrs["schema_version"]) >= 3:
        return _ragged_heights(path, f, realizations)
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


def _ragged_heights(path: Path, f, realizations: int) -> list[np.ndarray]:
    """The kept heights of a schema-3 file: /heights/z split by /heights/count."""
    count = schema.dataset(path, f, "heights/count", "iu", (realizations,), WHAT)[()]
    z = schema.dataset(path, f, "heights/z", "f", None, WHAT)
    if z.ndim != 1 or np.any(count < 0) or int(count.sum()) != z.shape[0]:
        raise schema.refuse(path, WHAT, f"dataset heights/z has shape {z.shape}, heights/count "
                                        f"asks for ({int(count.sum())},)")  # fmt: skip
    return np.split(z[()], np.cumsum(count)[:-1])


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
    path = file_path(path)
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
    path = file_path(path)
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
        spec, version = state.spec, int(attrs["schema_version"])
        names = _quantities(spec)

        def rows(name: str, axis: int = 0) -> np.ndarray:
            return read_rows(f, name, spec, version, axis)

        stats = {stat: {q: rows(f"summary/{stat}/{q}") for q in names} for stat in STATS}
        heights = _heights(path, f, spec.realizations)
        return Run(
            environment=environment_run(spec),
            ensemble=state,
            realizations={q: rows(f"realizations/{q}", 1) for q in names},
            summary=Summary(**stats, expected_contacts=rows("summary/expected_contacts")),
            analytic={q: rows(f"analytic/{q}") for q in names},
            attrs=attrs,
            path=path,
            heights=heights,
        )
