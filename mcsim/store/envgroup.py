"""The environment's part of a run file: the ``/environment`` group.

Written only for a run with an environment: the Environment's inputs with their units
(its adsorbed films too, and the film used), the band edge of the summits' caps, the
heights about the mean plane (rq, summit offset and their source), and the open gaps'
pressures per row (the whole surface's less the caps'). The summits'
caps are outputs of the run's law set (``vdw``, ``capillary``), stored with the other sums.
Files without it are exactly as before (:mod:`mcsim.store.runfile`). A file written with
the cell model of mcsim 0.2 (``cell_model`` attribute) is refused: its sums mean another
model; so is one of an earlier model (its ``model`` attribute differs from :data:`MODEL`).
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError, RunFileError
from mcsim.physics.environment import Environment
from mcsim.physics.surfaceenvironment import band_edge
from mcsim.store.h5layout import by_branch, dataset, row_dims
from mcsim.store.sweepvariables import CURVES

#: Fields of the Environment as stored, with their units.
_ENVIRONMENT_UNITS = {"hamaker": "J", "cutoff": "m", "rh": "1", "contact_angle": "rad",
                      "temperature": "K", "surface_tension": "J/m^2", "molar_volume": "m^3/mol",
                      "film_thickness": "m", "structured_film": "m", "asperity_roughness": "m",
                      "retardation_wavelength": "m"}  # fmt: skip

#: Fields stored as NaN when None (no van der Waals; the isotherm; non-retarded).
_NONE_AS_NAN = ("hamaker", "film_thickness", "retardation_wavelength")

#: The model of the environment, as recorded in run files.
MODEL = ("the proximity model over the heights about the mean plane, each local gap once, "
         "shared between the summits' caps (per-summit van der Waals and menisci, local gaps "
         "below band_edge) and the open gaps (the rest: the whole less the caps' expectation); "
         "menisci bridge adsorbed films (film_thickness, structured_film) and spread from a "
         "critical humidity (asperity_roughness)")  # fmt: skip


def write_environment(f, spec, part) -> None:
    """The /environment group of a run of ``spec`` (see the module docstring); ``part`` is
    :func:`mcsim.store.results.environment_run` of it. Written with every file, checkpoints
    too: resuming needs the environment, which sets the run's sums."""
    env, gap = part.environment, part.gap
    g = f.create_group("environment")
    g.attrs.update(
        {k: np.nan if getattr(env, k) is None else getattr(env, k) for k in _ENVIRONMENT_UNITS}
    )
    g.attrs.update(kelvin_radius=env.kelvin_radius, film=env.film, rq=gap.rq,
                   summit_offset=gap.summit_offset, band_edge=band_edge(spec.surface.R, spec.surface.eta, env),
                   gap_source=gap.source, model=MODEL,
                   map_heights=json.dumps("gaussian" if isinstance(gap.heights, float)
                                          else gap.heights.to_dict()))  # fmt: skip
    g.attrs["units"] = json.dumps(
        _ENVIRONMENT_UNITS
        | {"kelvin_radius": "m", "film": "m", "rq": "m", "summit_offset": "m", "band_edge": "m"}
    )
    rows = row_dims(spec)
    for t, values in part.open_gaps.items():
        dataset(f, f"environment/open_gaps/{t}", by_branch(spec, values, 0), "1",
                f"open gaps between the summits' caps: {CURVES[t]}", rows, f"p_{t}/K")  # fmt: skip


def read_environment(path: Path, f, surface):
    """The Environment of a run file (None if it has none) and ``surface`` with the heights
    about the mean plane the run used where they were given (rq, summit offset, measured
    histogram); the open gaps' curves are recomputed from them
    (:func:`mcsim.store.results.environment_run`)."""
    if "environment" not in f:
        return None, surface
    a = f["environment"].attrs
    if "model" not in a:
        raise RunFileError(f"{path}: this run's environment was sampled over cells (mcsim 0.2's "
                           "model, which counted the area near contact twice); run it again")  # fmt: skip
    if str(a["model"]) != MODEL:
        raise RunFileError(f"{path}: this run's environment follows an earlier model of mcsim "
                           f"({a['model']}), whose open gaps did not cover the surface once; "
                           "run it again")  # fmt: skip
    if "structured_film" not in a and a["rh"] > 0 and a["contact_angle"] < np.pi / 2:
        raise RunFileError(f"{path}: this run's menisci predate the adsorbed films (a Kelvin "
                           "radius of 0.5 nm gated them); run it again")  # fmt: skip
    values = {k: float(a[k]) for k in _ENVIRONMENT_UNITS if k in a}  # dry, before films: defaults
    # a file written before retardation has no wavelength: its sums are non-retarded (NaN)
    values["retardation_wavelength"] = float(a.get("retardation_wavelength", np.nan))
    for k in _NONE_AS_NAN:
        values[k] = None if np.isnan(values.get(k, np.nan)) else values[k]
    try:
        env = Environment(**values)
        if str(a["gap_source"]) == "given":
            shape = json.loads(a["map_heights"])
            if shape != "gaussian":
                from mcsim.topography.empirical import Empirical

                shape = Empirical.from_dict(shape)
            surface = dataclasses.replace(surface, rq=float(a["rq"]),
                                          summit_offset=float(a["summit_offset"]),
                                          map_heights=None if shape == "gaussian" else shape)  # fmt: skip
    except MCSimError as err:
        raise RunFileError(f"{path}: damaged run file: environment: {err}") from None
    return env, surface
