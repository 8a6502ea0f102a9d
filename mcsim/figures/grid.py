"""A sweep's grid as its figures show it: the display unit and label of each input, which
grids are log-spaced, the cells of a map around its grid values, and the sweep squeezed to the
inputs it varies (:mod:`mcsim.figures.sweeps`, and the pads sweeps' figures,
:mod:`mcsim.figures.stiction` and :mod:`mcsim.figures.friction`)."""

from __future__ import annotations

import dataclasses
import functools
import json

import numpy as np

from mcsim.model.errors import ParameterError

#: Display scale, unit and symbol of each grid dimension (values are SI in the file).
DISPLAY = {
    "sigma": (1e9, "nm", r"$\sigma$"),
    "R": (1e6, "µm", "$R$"),
    "eta": (1e-12, "µm$^{-2}$", r"$\eta$"),
    "E": (1e-9, "GPa", "$E$"),
    "E1": (1e-9, "GPa", "$E_1$"),
    "E2": (1e-9, "GPa", "$E_2$"),
    "nu": (1.0, "", r"$\nu$"),
    "nu1": (1.0, "", r"$\nu_1$"),
    "nu2": (1.0, "", r"$\nu_2$"),
    "gamma": (1.0, "J/m$^2$", r"$w = \gamma$"),
    "w": (1.0, "J/m$^2$", "$w$"),
    "z0": (1e9, "nm", "$z_0$"),
    "tau": (1e-6, "MPa", r"$\tau$"),
    "H": (1e-9, "GPa", "$H$"),
    "pad_area": (1e12, "µm$^2$", "$A_n$"),
    "restoring_force": (1e6, "µN", "$F_r$"),
    "tangential_force": (1e6, "µN", "$F_t$"),
    "preload": (1e-6, "MPa", "$P$"),
    "law": (1.0, "", "law set"),
}


def squeezed(sweep, dims: list[str]):
    """The sweep without its grid dimensions of one value (C order is kept by reshape)."""
    shape = tuple(sweep.coords[d].size for d in dims)
    data, var_dims = {}, {}
    for k, v in sweep.data.items():
        per_h = sweep.dims[k][-1] == "h"
        data[k] = np.asarray(v).reshape(*shape, *v.shape[-1:] if per_h else ())
        var_dims[k] = (*dims, "h") if per_h else tuple(dims)
    coords = {d: sweep.coords[d] for d in (*dims, "h")}
    attrs = {**sweep.attrs, "varied": json.dumps(dims)}
    return dataclasses.replace(sweep, coords=coords, data=data, dims=var_dims, attrs=attrs)


def pads_varied(sweep, what: str):
    """A pads sweep squeezed to its one or two varied inputs: (sweep, their names).

    Raises
    ------
    ParameterError
        No input, or more than two, varied over more than one value (``what`` names the
        sweep in the message, e.g. "a pads sweep"). A sweep of one input at one value (a
        report at one humidity) is drawn as its one point.
    """
    dims = [d for d in sweep.grid if sweep.coords[d].size > 1]
    if not dims and len(sweep.grid) == 1:
        dims = list(sweep.grid)
    if not dims or len(dims) > 2:
        raise ParameterError(f"plot: {what} is drawn against one or two varied inputs, this one "
                             f"varies {len(dims)} ({', '.join(sweep.grid)})")  # fmt: skip
    return squeezed(sweep, dims), dims


def pads_title(sweep) -> str:
    """First lines of a pads figure's title: the surface and law set, then the pads."""
    a = sweep.attrs
    name = json.loads(a["surface"]).get("name") if isinstance(a.get("surface"), str) else None
    law = f"law {a['law']}" if "law" in a else ""
    text = ", ".join(x for x in (name and f"surface {name}", law) if x)
    return (text + "\n" if text else "") + f"{a['pads']} pads of {a['area'] * 1e12:.4g} µm²"


def is_log_grid(values) -> bool:
    """Whether grid values are log-spaced: positive, at least 3, with a constant ratio
    (and not a constant step); two positive values a decade or more apart count too."""
    v = np.asarray(values)
    if v.dtype.kind not in "fi" or v.size < 2 or np.any(v <= 0):
        return False
    v = np.sort(v.astype(float))
    if v.size == 2:
        return v[1] / v[0] >= 10
    ratio, step = np.diff(np.log(v)), np.diff(v)
    constant = functools.partial(np.allclose, rtol=1e-6, atol=0.0)
    return bool(constant(ratio, ratio[0]) and not constant(step, step[0]))


def axis_label(sweep, dim: str) -> str:
    """Label of a grid dimension: symbol, meaning and display unit."""
    _, unit, symbol = DISPLAY.get(dim, (1.0, sweep.units.get(dim, ""), dim))
    meaning = sweep.long_names.get(dim, dim)
    text = meaning if symbol == meaning else f"{symbol}, {meaning}"
    return text + (f" ({unit})" if unit else "")


def display_values(sweep, dim: str) -> np.ndarray:
    """The grid values of ``dim`` in its display unit (:data:`DISPLAY`); text (a law set's
    name) as strings."""
    values = sweep.coords[dim]
    if values.dtype.kind in "US" or values.dtype == object:
        return values.astype(str)
    return values.astype(float) * DISPLAY.get(dim, (1.0,))[0]


def cell_edges(values: np.ndarray, log: bool) -> np.ndarray:
    """Cell edges around grid values: midpoints (geometric on a log axis)."""
    v = np.log(values) if log else values.astype(float)
    if v.size == 1:
        e = np.array([v[0] - 0.5, v[0] + 0.5])
    else:
        mid = (v[1:] + v[:-1]) / 2
        e = np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])
    if log:
        return np.exp(e)
    return np.maximum(e, 0.0) if values.min() >= 0 else e  # no negative w, σ, ... on the axis
