"""The /input group of run files: the surface and the material, as written and as read back
(checked), and the JSON forms of a surface's summit heights and radius by height, which sweep
files store too.

.. code-block:: text

    /input/surface    attrs: sigma [m], R [m], eta [m^-2], name, heights (JSON);
                      radius_by_height (JSON: band edges in s, factors of R; absent: one
                      radius R); units (JSON)
    /input/material   attrs: E1, E2 [Pa], nu1, nu2, gamma [J/m^2], H [Pa], name, z0 [m],
                      tau [Pa] (NaN: not given; absent in older files); units (JSON)

With a rough counter-surface /input/surface is the gap's surface that was run, and three root
attributes record its parts (:func:`counterface_attrs`).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from mcsim.model.distributions import GAUSSIAN
from mcsim.model.errors import MCSimError
from mcsim.model.params import Material, RadiusByHeight, Surface
from mcsim.store import schema

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


def heights_to_json(surface: Surface) -> str:
    """The summit-height distribution as run and sweep files store it (JSON text)."""
    heights = surface.heights
    if heights == GAUSSIAN:
        return json.dumps({"name": "gaussian"})
    return json.dumps({"name": heights.name, **heights.to_dict()})


def radius_to_dict(radius: RadiusByHeight) -> dict:
    """A radius by height as run and sweep files store it (as JSON): ``{"edges": [s...],
    "factors": [...]}`` (edges in s = z/σ, factors of R)."""
    return {"edges": list(radius.edges), "factors": list(radius.factors)}


def counterface_attrs(surface: Surface, counter: Surface, correlation: float) -> dict:
    """Root attributes that record the parts of a gap's surface
    (:func:`mcsim.model.counterface.combine`), in run and sweep files: ``surface_as_given``
    and ``counter_surface`` (JSON objects: sigma, R, eta, name, units) and ``correlation`` (ρ).
    ``/input/surface`` (a sweep file's ``surface``) holds their combination, which was run."""

    def plain(s: Surface) -> str:
        return json.dumps({"sigma": s.sigma, "R": s.R, "eta": s.eta, "name": s.name,
                           "units": {"sigma": "m", "R": "m", "eta": "m^-2"}})  # fmt: skip

    return {"surface_as_given": plain(surface), "counter_surface": plain(counter),
            "correlation": float(correlation)}  # fmt: skip


def heights_from_dict(data: dict):
    """Inverse of :func:`heights_to_json`, from the parsed JSON object."""
    if data.get("name") == "gaussian":
        return GAUSSIAN
    from mcsim.topography.empirical import Empirical

    return Empirical.from_dict({k: v for k, v in data.items() if k != "name"})


def write_inputs(f, surface: Surface, material: Material) -> None:
    """The /input group of ``surface`` and ``material`` in the open HDF5 file ``f``."""
    s = f.create_group("input/surface")
    s.attrs.update(sigma=surface.sigma, R=surface.R, eta=surface.eta,
                   name=surface.name, heights=heights_to_json(surface))  # fmt: skip
    if surface.radius_by_height is not None:
        s.attrs["radius_by_height"] = json.dumps(radius_to_dict(surface.radius_by_height))
    s.attrs["units"] = json.dumps({"sigma": "m", "R": "m", "eta": "m^-2"})
    m = f.create_group("input/material")
    mat = material
    m.attrs.update(E1=mat.E1, E2=mat.E2, nu1=mat.nu1, nu2=mat.nu2, gamma=mat.gamma,
                   H=np.nan if mat.H is None else mat.H, name=mat.name)  # fmt: skip
    m.attrs.update({k: np.nan if getattr(mat, k) is None else getattr(mat, k) for k in ("z0", "tau")})  # fmt: skip
    m.attrs["units"] = json.dumps({"E1": "Pa", "E2": "Pa", "nu1": "1", "nu2": "1", "gamma": "J/m^2",
                                   "H": "Pa", "z0": "m", "tau": "Pa"})  # fmt: skip


def read_inputs(path: Path, f, what: str) -> tuple[Surface, Material]:
    """The surface and material of /input, checked against :data:`SURFACE` and :data:`MATERIAL`
    (``what`` names the file's kind in a refusal)."""
    import h5py

    for group in ("input/surface", "input/material"):
        if not isinstance(f.get(group), h5py.Group):
            raise schema.refuse(path, what, f"group {group} is missing")
    s, m = f["input/surface"], f["input/material"]
    radius = None  # optional: absent, one radius R
    if "radius_by_height" in s.attrs:
        radius = schema.attribute(path, s, "radius_by_height", "JSON object", what)
    s = {k: schema.attribute(path, s, k, kind, what) for k, kind in SURFACE.items()}
    optional = {k: kind for k, kind in MATERIAL_OPTIONAL.items() if k in m.attrs}
    m = {k: schema.attribute(path, m, k, kind, what) for k, kind in (MATERIAL | optional).items()}
    try:
        heights = heights_from_dict(s.pop("heights"))
        if radius is not None:
            radius = RadiusByHeight(radius.get("edges", ()), radius.get("factors", ()))
        surface = Surface(**s, heights=heights, radius_by_height=radius)
    except MCSimError as err:
        raise schema.refuse(path, what, f"input/surface: {err}") from None
    for k in MATERIAL_OPTIONAL:
        m[k] = None if math.isnan(m.get(k, math.nan)) else m[k]
    try:
        material = Material(**m)
    except MCSimError as err:
        raise schema.refuse(path, what, f"input/material: {err}") from None
    return surface, material
