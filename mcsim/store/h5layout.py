"""How a run file lays out its datasets: units and descriptions beside the data, named axes.

Shared by :mod:`mcsim.store.runfile` and :mod:`mcsim.store.envgroup`.
"""

from __future__ import annotations

import numpy as np

from mcsim.engine.cells import CELL_COLUMNS
from mcsim.engine.kernels import sum_columns
from mcsim.engine.montecarlo import MonteCarloSpec
from mcsim.physics.laws import get_law_set


def dataset(f, name: str, data, unit: str, description: str, dims=(), **options):
    """Create dataset ``name`` with its unit; ``dims`` name its axes (see :func:`axis_scale`)."""
    ds = f.create_dataset(name, data=np.asarray(data), **options)
    ds.attrs["unit"] = unit
    ds.attrs["description"] = description
    for k, axis in enumerate(dims):
        ds.dims[k].attach_scale(axis_scale(ds.parent, axis, ds.shape[k]))
    return ds


#: Named axes: unit and meaning of each coordinate.
AXES = {
    "h": ("1", "d/sigma"),
    "row": ("1", "d/sigma of each row of a cycle: approach, then retraction (see branch)"),
    "realization": ("1", "realization index"),
    "column": ("1", "column of realizations/sums"),
    "cell_column": ("1", "column of environment/sums"),
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
            "row": lambda: group.file["row"][()],
            "realization": lambda: np.arange(size),
            "column": lambda: np.array(sum_columns(get_law_set(group.file.attrs["law"])), "S"),
            "cell_column": lambda: np.array(CELL_COLUMNS, "S"),
        }[axis]()
        scale = dataset(group, axis, values, *AXES[axis])
        if axis in ("column", "cell_column"):
            scale.attrs["_Encoding"] = "utf-8"  # netCDF readers decode the names to text
        scale.make_scale(axis)
    return group[axis]


def row_axis(spec: MonteCarloSpec) -> str:
    """Name of the row axis of the sums and curves: ``h`` (approach only), or ``row``
    (a cycle: the M approach rows, then the M retraction rows)."""
    return "row" if spec.cycle else "h"
