"""How a run file lays out its datasets: CF attributes, named axes, compression.

Shared by :mod:`mcsim.store.runfile` and :mod:`mcsim.store.envgroup`. Every dataset,
coordinates included, carries the CF attributes ``units`` (UDUNITS text, ``"1"`` for
dimensionless values and names) and ``long_name`` (words); a dimensionless curve keeps
its normalisation (``"load/(A K)"``) in ``description``. Large datasets are stored
chunked and gzip-compressed (:func:`mcsim.store.files.storage`).
"""

from __future__ import annotations

import json

import numpy as np

from mcsim.engine.kernels import sum_columns, sum_units
from mcsim.engine.spec import MonteCarloSpec
from mcsim.physics.laws import LawSet
from mcsim.store.files import storage
from mcsim.store.sweepvariables import CURVES


def dataset(f, name: str, data, units: str, long_name: str, dims=(), description=None):
    """Create dataset ``name`` with its CF ``units`` and ``long_name``; ``dims`` name its
    axes (see :func:`axis_scale`); large data is chunked and compressed."""
    data = np.asarray(data)
    if not data.flags.c_contiguous:
        data = data.copy()  # a column of the sums
    ds = f.create_dataset(name, data=data, **storage(data))
    ds.attrs["units"] = units
    ds.attrs["long_name"] = long_name
    if description is not None:
        ds.attrs["description"] = description
    if data.dtype.kind == "S":
        ds.attrs["_Encoding"] = "utf-8"  # netCDF readers decode the names to text
    for k, axis in enumerate(dims):
        ds.dims[k].attach_scale(axis_scale(ds.parent, axis, ds.shape[k]))
    return ds


#: Named axes: units and meaning of each coordinate.
AXES = {
    "h": ("1", "d/sigma, mean separation over the summit-height standard deviation"),
    "branch": (
        "1",
        "branch of the load cycle: approach, then retraction from the closest approach",
    ),
    "realization": ("1", "realization (patch) index"),
    "summit": ("1", "index of a kept summit, the patches one after another"),
}


def axis_scale(group, axis: str, size: int):
    """The coordinate ``axis`` of ``group``, created on first use.

    Each group that uses an axis holds its own copy as an HDF5 dimension scale named
    after it, so that netCDF readers (``xarray.open_dataset(path, group=...,
    engine="h5netcdf")``, ``open_datatree``) name the dimension and give its values,
    with the same name in every group.
    """
    if axis not in group:
        values = {
            "h": lambda: group.file["h"][()],
            "branch": lambda: np.array(json.loads(group.file.attrs["branches"]), "S"),
            "realization": lambda: np.arange(size),
            "summit": lambda: np.arange(size),
        }[axis]()
        dataset(group, axis, values, *AXES[axis]).make_scale(axis)
    return group[axis]


def row_dims(spec: MonteCarloSpec) -> tuple[str, ...]:
    """Axes of a run's rows in the file: ``(h,)``, or for a cycle ``(branch, h)``."""
    return ("branch", "h") if spec.cycle else ("h",)


def by_branch(spec: MonteCarloSpec, values, axis: int) -> np.ndarray:
    """``values`` with its row axis ``axis`` (the M approach rows, then with a cycle the M
    retraction rows: :meth:`MonteCarloSpec.rows`) split into (branch, h) for a cycle."""
    values = np.asarray(values)
    if not spec.cycle:
        return values
    shape = values.shape
    return values.reshape((*shape[:axis], len(spec.branches), spec.h.size, *shape[axis + 1 :]))


def as_rows(spec: MonteCarloSpec, values, axis: int) -> np.ndarray:
    """Inverse of :func:`by_branch`: the (branch, h) axes at ``axis`` joined into rows."""
    if not spec.cycle:
        return values
    shape = values.shape
    return values.reshape((*shape[:axis], -1, *shape[axis + 2 :]))


def row_shape(spec: MonteCarloSpec, version: int) -> tuple[int, ...]:
    """Shape of a run's rows in a file of schema ``version``: before 3 one axis (a cycle's
    approach rows, then its retraction rows); from 3 (h,), or for a cycle (branch, h)."""
    if version < 3:
        return (spec.row_h.size,)
    return tuple(len(spec.branches) if d == "branch" else spec.h.size for d in row_dims(spec))


def read_rows(f, name: str, spec: MonteCarloSpec, version: int, axis: int) -> np.ndarray:
    """Dataset ``name`` (checked against :func:`row_shape`) with its rows on one axis at
    ``axis``, as the engine and :class:`~mcsim.store.results.Run` hold them."""
    values = f[name][()]
    return as_rows(spec, values, axis) if version >= 3 else values


#: Words for each ensemble statistic (:data:`~mcsim.store.results.STATS`), in long names.
STAT_WORDS = {
    "mean": "ensemble mean",
    "se": "standard error of the ensemble mean (summit-level moments)",
    "std": "standard deviation between the patches",
    "se_between": "standard error of the ensemble mean from the spread between the patches",
}


def sum_variables(law: LawSet) -> list[tuple[str, str, str]]:
    """(name, units, long_name) of each raw-sum column of ``law`` (:func:`sum_columns`)."""
    names = list(law.names)
    pairs = [(a, b) for i, a in enumerate(names) for b in names[i + 1 :]]
    words = (
        "summits in contact",
        *(f"sum of {o.name} ({o.description}) over the summits" for o in law.outputs),
        *(f"sum of {n}^2 over the summits" for n in names),
        *(f"sum of {a}*{b} over the summits" for a, b in pairs),
    )
    return list(zip(sum_columns(law), sum_units(law), words, strict=True))


def curve_long_name(q: str, law: LawSet) -> str:
    """Words for the dimensionless curve ``q`` (its normalisation goes in ``description``)."""
    if q in CURVES:
        return CURVES[q]
    meaning = {o.name: o.description for o in law.outputs}.get(q, q)
    return f"{meaning}, normalised (see description)"
