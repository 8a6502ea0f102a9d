"""The environment's part of a run file: the ``/environment`` group.

Written only for a run with an environment (:mod:`mcsim.engine.cells`): the Environment's
inputs with their units, the gap heights used (rq, summit offset and their source), the
cell model and the cells' sums; read back into a :class:`~mcsim.engine.cells.CellSums`.
Files without it are exactly as before (:mod:`mcsim.store.runfile`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mcsim.engine.cells import CELL_COLUMNS, CELL_UNITS, CellSums
from mcsim.engine.montecarlo import MonteCarloSpec
from mcsim.model.errors import RunFileError
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import GapHeights
from mcsim.store.h5layout import STAT_WORDS, by_branch, dataset, read_rows, row_dims, row_shape
from mcsim.store.sweepfile import CURVES

#: Fields of the Environment as stored, with their units.
_ENVIRONMENT_UNITS = {"hamaker": "J", "cutoff": "m", "rh": "1", "contact_angle": "rad",
                      "temperature": "K", "surface_tension": "J/m^2", "molar_volume": "m^3/mol"}  # fmt: skip


def write_environment(f, run) -> None:
    """The /environment group (see the module docstring)."""
    part = run.environment
    env, gap = part.cells.environment, part.cells.gap
    g = f.create_group("environment")
    g.attrs.update(
        {k: np.nan if getattr(env, k) is None else getattr(env, k) for k in _ENVIRONMENT_UNITS}
    )
    g.attrs.update(kelvin_radius=env.kelvin_radius, rq=gap.rq, summit_offset=gap.summit_offset,
                   gap_source=gap.source, cell_model=CELL_MODEL,
                   map_heights=json.dumps("gaussian" if isinstance(gap.heights, float)
                                          else gap.heights.to_dict()))  # fmt: skip
    g.attrs["units"] = json.dumps(
        _ENVIRONMENT_UNITS | {"kelvin_radius": "m", "rq": "m", "summit_offset": "m"}
    )
    spec = run.spec
    rows = row_dims(spec)
    dataset(
        f, "environment/n_cells", part.cells.n_cells, "1", "cells in the patch", ("realization",)
    )
    for k, (column, units, words) in enumerate(
        zip(CELL_COLUMNS, CELL_UNITS, CELL_WORDS, strict=True)
    ):
        dataset(f, f"environment/sums/{column}", by_branch(spec, part.cells.sums[..., k], 1), units,
                words, ("realization", *rows), "raw sum of each patch and separation over its cells")  # fmt: skip
    est = part.estimates
    for t in est.mean:
        norm, words = f"p_{t}/K", CURVES[t]
        per_patch = by_branch(spec, est.realizations[t], 1)
        dataset(f, f"environment/realizations/{t}", per_patch, "1", words, ("realization", *rows),
                norm)  # fmt: skip
        for stat, values in (("mean", est.mean[t]), ("se", est.se[t])):
            dataset(f, f"environment/summary/{stat}/{t}", by_branch(spec, values, 0), "1",
                    f"{STAT_WORDS[stat]} of {t}: {words}", rows, norm)  # fmt: skip
        dataset(f, f"environment/analytic/{t}", by_branch(spec, part.analytic[t], 0), "1",
                f"proximity-model expected value of {t}: {words}", rows, norm)  # fmt: skip


#: Words for the columns of the cells' sums (:data:`~mcsim.engine.cells.CELL_COLUMNS`).
CELL_WORDS = (
    "sum over the cells of the van der Waals pressure p_vdW",
    "sum over the cells of p_vdW^2",
    "sum over the cells of the capillary pressure p_cap",
    "sum over the cells of p_cap^2",
)

#: The cell model of the environment pass, as recorded in run files.
CELL_MODEL = ("one cell of area A/N per summit, heights iid from the map_heights (or Gaussian) "
              "distribution scaled by rq, uncorrelated with each other and with the summits")  # fmt: skip


def read_environment(path: Path, f, spec: MonteCarloSpec, version: int) -> CellSums | None:
    """The environment's cell sums of a run file of schema ``version``, or None if it has none."""
    if "environment" not in f:
        return None
    a = f["environment"].attrs
    values = {k: float(a[k]) for k in _ENVIRONMENT_UNITS}
    values["hamaker"] = None if np.isnan(values["hamaker"]) else values["hamaker"]
    env = Environment(**values)
    shape = json.loads(a["map_heights"])
    rq = float(a["rq"])
    heights = rq
    if shape != "gaussian":
        from mcsim.topography.empirical import Empirical

        heights = Empirical.from_dict(shape)
    gap = GapHeights(heights, rq, float(a["summit_offset"]), str(a["gap_source"]))
    R = spec.realizations
    if version >= 3:
        wanted = {f"environment/sums/{c}": (R, *row_shape(spec, version)) for c in CELL_COLUMNS}
    else:
        wanted = {"environment/sums": (R, spec.row_h.size, len(CELL_COLUMNS))}
    for name, want in {"environment/n_cells": (R,), **wanted}.items():
        if f[name].shape != want:
            raise RunFileError(
                f"{path}: damaged run file: {name} has shape {f[name].shape}, the inputs ask for {want}"
            )
    if version >= 3:
        sums = np.stack([read_rows(f, name, spec, version, 1) for name in wanted], axis=-1)
    else:
        sums = f["environment/sums"][()]
    return CellSums(env, gap, f["environment/n_cells"][()], sums)
