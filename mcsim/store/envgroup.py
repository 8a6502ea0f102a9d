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
from mcsim.store.h5layout import dataset, row_axis

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
    rows = (row_axis(run.spec),)
    dataset(
        f, "environment/n_cells", part.cells.n_cells, "1", "cells in the patch", ("realization",)
    )
    sums = dataset(f, "environment/sums", part.cells.sums, "per column, see units",
                    "per-row sums over the cells", ("realization", rows[0], "cell_column"))  # fmt: skip
    sums.attrs["columns"], sums.attrs["units"] = list(CELL_COLUMNS), list(CELL_UNITS)
    est = part.estimates
    for t in est.mean:
        norm = f"p_{t}/K"
        dataset(
            f,
            f"environment/realizations/{t}",
            est.realizations[t],
            "1",
            norm,
            ("realization", rows[0]),
        )
        dataset(f, f"environment/summary/mean/{t}", est.mean[t], "1", norm, rows)
        dataset(f, f"environment/summary/se/{t}", est.se[t], "1", norm, rows)
        dataset(f, f"environment/analytic/{t}", part.analytic[t], "1", norm, rows)


#: The cell model of the environment pass, as recorded in run files.
CELL_MODEL = ("one cell of area A/N per summit, heights iid from the map_heights (or Gaussian) "
              "distribution scaled by rq, uncorrelated with each other and with the summits")  # fmt: skip


def read_environment(path: Path, f, spec: MonteCarloSpec) -> CellSums | None:
    """The environment's cell sums of a run file, or None if it has none."""
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
    R, rows = spec.realizations, spec.row_h.size
    for name, want in (
        ("environment/n_cells", (R,)),
        ("environment/sums", (R, rows, len(CELL_COLUMNS))),
    ):
        if f[name].shape != want:
            raise RunFileError(
                f"{path}: damaged run file: {name} has shape {f[name].shape}, the inputs ask for {want}"
            )
    return CellSums(env, gap, f["environment/n_cells"][()], f["environment/sums"][()])
