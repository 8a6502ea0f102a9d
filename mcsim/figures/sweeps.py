"""Figures of parameter sweeps (:mod:`mcsim.studies.sweeps`): design curves and design maps.

>>> from mcsim.store.sweepfile import read_sweep
>>> from mcsim.figures.sweeps import sweep_figure
>>> fig = sweep_figure(read_sweep("map.h5"))                          # doctest: +SKIP
>>> mcsim.figures.style.save(fig, "map.png", inputs=["map.h5"])           # doctest: +SKIP

* **one varied input** (or two, one of them the law set or with ``kind="lines"``):
  the adhesion summary against the input, what a designer reads: the pull-off force per
  nominal area (Pa) and the work of separation (J/m²), both on log axes, then μ at a few
  separations d/σ (with ``mc``: the Monte Carlo means ± 2 SE at the same separations).
  For a σ sweep, the σ of the paper's four Table-1 surfaces are marked (dotted lines, and
  a ◆ on the curve where that σ is a point of the grid, e.g. ``sigma=0.42nm,1.4nm,...``):
  the seed paper's thesis (adhesion and friction grow as the surfaces get smoother) as
  a continuous curve. A law set without a net load (``seed``) has no pull-off: its
  panels are the adhesion term F̄ (Eq. 5), the friction T̄ (Eq. 7) and μ (Eq. 8) at
  those separations.
* **relative humidity alone** (``rh``, with an adhesion summary): the work of separation
  and its parts against RH with the capillary ceiling and the humidity regimes
  (:func:`mcsim.figures.environment.humidity_figure`).
* **two numeric inputs**: maps of the pull-off pressure and of the work of separation
  (seed: F̄ and T̄ at one separation) over the grid, with the regime boundaries of the
  Johnson–Greenwood (1997) adhesion map drawn on top: contours of Maugis' λ at
  :data:`mcsim.physics.adhesion.DMT_BELOW` and :data:`mcsim.physics.adhesion.JKR_ABOVE` (the thresholds
  of ``--law auto``, :func:`mcsim.physics.adhesion.choose_law`; λ = 1.162 μ_T, Tabor's
  parameter), regions labelled DMT / Maugis–Dugdale / JKR, and the plasticity index
  ψ = 1 (Greenwood & Williamson 1966) where it is defined.

Axes carry units; an input whose grid is log-spaced gets a log axis. Failed points
(the ``error`` variable) are gaps in the curves and grey cells in the maps. A log axis shows
:data:`DECADES` below its largest value: smaller values are marked ▼ at its edge and counted
above the panel, as are the zeros it cannot show.
"""

from __future__ import annotations

import json
import math

import numpy as np

from mcsim.figures.grid import (
    DISPLAY,
    axis_label,
    cell_edges,
    display_values,
    is_log_grid,
    squeezed,
)
from mcsim.figures.style import COLOURS, LINESTYLES, errorbars
from mcsim.model.errors import ParameterError
from mcsim.model.presets import PAPER_SURFACES, SURFACES
from mcsim.physics.adhesion import DMT_BELOW, JKR_ABOVE

#: Axis label of each plotted variable (curves: at one separation, added to the label).
LABELS = {
    "pull_off_pressure": "Pull-off force per nominal area $F_{po}/A_n$ (Pa)",
    "work_of_separation": r"Work of separation $\Delta\gamma$ (J/m$^2$)",
    "mu": r"Friction coefficient $\mu$ (blank: load $\leq$ 0)",
    "load": r"Net load $W/(A_n\,K)$ (compressive > 0)",
    "F": r"Adhesion term $\bar F = F/(A_n K)$ (Eq. 5)",
    "T": r"Friction force $\bar T = T/(A_n K)$ (Eq. 7)",
    "contact_fraction": r"Contact fraction $N_c/N$",
}

#: Variables drawn on log axes (log colour scale in maps).
#: (μ too: with adhesion it diverges where the net load crosses zero, a log axis keeps
#: the rest of the curve readable.)
LOG_VARIABLES = frozenset({"pull_off_pressure", "work_of_separation", "F", "T", "mu"})

#: Decades shown below the largest value on a log axis or colour scale: smaller values
#: (e.g. the 1e-20 J/m² tail of a rough surface) sit at the bottom, the colour bar extended.
DECADES = 9

#: Separations d/σ at which the curves (μ, F̄, T̄) are shown, nearest grid values.
DEFAULT_H = (0.0, 1.0, 2.0)


def sweep_figure(sweep, *, kind: str = "auto", h=DEFAULT_H):
    """The figure of a sweep: design curves (one or two inputs) or design maps (two).

    Parameters
    ----------
    sweep : mcsim.store.sweepfile.Sweep or path-like
        A sweep result or its file (:func:`mcsim.store.sweepfile.read_sweep`).
    kind : {"auto", "lines", "map"}
        ``"lines"``: variables against the first numeric input, one line per value of
        the other input (or per separation for a single input); ``"map"``: two numeric
        inputs as colour maps with the regime boundaries. ``"auto"``: a map for two
        numeric inputs, lines otherwise.
    h : sequence of float
        Separations d/σ (nearest values of the sweep's ``h``) at which curves such as μ
        are shown; lines and maps with a second input use the first.

    Returns
    -------
    matplotlib.figure.Figure
        Built without pyplot (headless).

    Raises
    ------
    ParameterError
        More than two inputs varied over more than one value, a map asked for a law-set
        dimension, or a sweep without any variable to plot (one line).
    """
    from mcsim.store.sweepfile import Sweep, read_sweep

    if not isinstance(sweep, Sweep):
        sweep = read_sweep(sweep)
    if kind not in ("auto", "lines", "map"):
        raise ParameterError(f"kind = {kind!r} is not one of 'auto', 'lines', 'map'")
    dims = [d for d in sweep.grid if sweep.coords[d].size > 1] or list(sweep.grid[:1])
    name = sweep.path.name if sweep.path is not None else "the sweep"
    if len(dims) > 2:
        raise ParameterError(
            f"plot: {name} varies {len(dims)} inputs ({', '.join(dims)}); a figure shows 1 or 2: "
            "select a slice with Sweep.to_xarray() and plot it yourself"
        )
    sweep = squeezed(sweep, dims)
    if dims == ["rh"] and kind != "map" and "work_of_separation_capillary" in sweep.data:
        from mcsim.figures.environment import humidity_figure

        return humidity_figure(sweep)
    numeric = [d for d in dims if d != "law"]
    if kind == "map" and len(numeric) != 2:
        raise ParameterError(f"plot: a map needs two numeric inputs; {name} varies "
                             f"{', '.join(dims)}")  # fmt: skip
    h_grid = np.asarray(sweep.coords["h"], dtype=float)
    rows = list(dict.fromkeys(int(np.argmin(np.abs(h_grid - x))) for x in np.atleast_1d(h)))
    if kind == "map" or (kind == "auto" and len(numeric) == 2):
        return _map_figure(sweep, numeric, rows[0], name)
    return _lines_figure(sweep, dims, rows, name)


# --- helpers --------------------------------------------------------------------------------


def _number(v: float, digits: int = 6) -> str:
    """A tick label (or a bound, to ``digits`` significant digits): plain between 1e-3 and
    1e4, else m×10^e."""
    if v <= 0 or 1e-3 <= v < 1e4:
        return f"{v:.{digits}g}"
    e = math.floor(math.log10(v))
    m = v / 10**e
    return f"$10^{{{e}}}$" if round(m, 6) == 1 else f"${m:.3g}\\times 10^{{{e}}}$"


def _readable_log_ticks(axis) -> None:
    """On a log axis spanning less than two decades, ticks at 1, 2, 5 × 10^k written as
    plain numbers (the default would label only minor ticks, as 4×10⁰)."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    low, high = sorted(axis.get_view_interval())
    if axis.get_scale() != "log" or not 0 < low or high / low >= 100:
        return
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: _number(v)))
    axis.set_minor_formatter(NullFormatter())


def _panels(sweep, name: str) -> list[str]:
    """Variables of the figure: the adhesion summary where it exists, else the seed's curves."""
    have = [k for k in ("pull_off_pressure", "work_of_separation") if _finite(sweep, k)]
    if have:
        if "mu" in sweep.data:
            return [*have, "mu"]
        # without friction (no tau) the Monte Carlo curves are drawn on the net load
        return [*have, *(["load"] if "mc_load" in sweep.data else [])]
    curves = [k for k in ("F", "T", "mu") if k in sweep.data]
    if not curves:
        raise ParameterError(f"plot: {name} has no pull_off_pressure, work_of_separation or "
                             "seed curves (F, T, mu) with a value: nothing to plot")  # fmt: skip
    return curves


def _finite(sweep, key: str) -> bool:
    return key in sweep.data and bool(np.any(np.isfinite(sweep.data[key])))


def _values(sweep, key: str, row: int | None) -> np.ndarray:
    values = np.asarray(sweep.data[key], dtype=float)
    return values if sweep.dims[key][-1] != "h" else values[..., row]


def _label(key: str, h: float | None) -> str:
    return LABELS.get(key, key) + ("" if h is None else f" at $d/\\sigma$ = {h:.3g}")


def _title(sweep, name: str, diamonds: bool = True) -> str:
    """The figure's title; ``diamonds``: the figure marks Table-1 σ that are grid points."""
    a = sweep.attrs
    law = a.get("law", "?")
    surface = json.loads(a["surface"]) if "surface" in a else {}
    material = json.loads(a["material"]) if "material" in a else {}
    base = f"surface {surface.get('name') or '(file)'}, material {material.get('name') or '(file)'}"
    if law == "auto":
        used = sorted({str(v) for v in np.asarray(sweep.data["law_used"]).ravel() if v})
        law = f"auto ({', '.join(used)})"
    title = f"{name}: law set {law}; other inputs as {base}"
    sigma = sweep.coords.get("sigma")
    if sigma is not None and any(
        sigma.min() <= SURFACES[s].sigma <= sigma.max() for s in PAPER_SURFACES
    ):
        title += "\ndotted lines: σ of the paper's Table-1 surfaces (at this R and η)"
        if diamonds and _table1_points(sigma.astype(float)):
            title += "; ◆ where that σ is a grid point"
    if not sweep.attrs.get("complete", True):
        title += "\nincomplete sweep (checkpoint): the points not yet computed are blank"
    errors = [str(e) for e in np.asarray(sweep.data["error"]).ravel() if e]
    if errors:
        title += f"\n{len(errors)} failed points, left blank (see the variable error)"
    return title


# --- lines ----------------------------------------------------------------------------------


def _lines_figure(sweep, dims: list[str], rows: list[int], name: str):
    """Variables against one input; one line per value of the other input or per separation."""
    from matplotlib.figure import Figure

    x_dim = next((d for d in dims if d != "law"), dims[0])
    other = next((d for d in dims if d != x_dim), None)
    panels = _panels(sweep, name)
    h_grid = sweep.coords["h"]
    x = display_values(sweep, x_dim)
    categorical = x.dtype.kind in "US"
    log_x = not categorical and is_log_grid(sweep.coords[x_dim])
    fig = Figure(figsize=(4.2 * len(panels) + 0.6, 4.6), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(panels)))
    x_axis = sweep.grid.index(x_dim)
    for ax, key in zip(axes, panels):
        per_h = sweep.dims[key][-1] == "h"
        log_y = key in LOG_VARIABLES
        lines = _line_set(sweep, key, x_axis, other, rows if per_h else [None], per_h)
        zeros = sum(int(np.sum(y == 0)) for _, y, _, _ in lines)
        shades = _shades(sweep, other) if len(lines) > MAX_LEGEND_LINES else None
        for i, (label, y, row, index) in enumerate(lines):
            style = {
                "color": COLOURS[i % len(COLOURS)],
                "linestyle": LINESTYLES[i % len(LINESTYLES)],
            }
            if shades is not None:  # many lines: one colour scale, a colour bar for a legend
                style = {
                    "color": shades.to_rgba(display_values(sweep, other)[index]),
                    "linestyle": "-",
                }
                label = None
            y = np.where(y > 0, y, np.nan) if log_y else y
            marker = "o" if categorical or x.size <= 12 else None
            if categorical:  # law sets: no line between them
                style["linestyle"] = "none"
            ax.plot(x, y, lw=1.7, marker=marker, ms=5, label=label, **style)
            mc = f"mc_{key}"
            if per_h and mc in sweep.data:
                mean = _take(sweep, mc, x_axis, index)[:, row]
                se = _take(sweep, f"{mc}_se", x_axis, index)[:, row]
                errorbars(ax, x, mean, se, log_y, style["color"],
                           label="Monte Carlo mean ± 2 SE" if i == 0 else None)  # fmt: skip
        if log_x:
            ax.set_xscale("log")
        if categorical:
            ax.set_xlim(-0.5, x.size - 0.5)
        notes, total = [], sum(y.size for _, y, _, _ in lines)
        if log_y and zeros:  # the surfaces rest apart there: nothing pulls off (above the panel)
            notes.append(f"0 at {zeros} of {total} points (not drawn on a log axis):\n"
                         "no adhesive contact at rest")  # fmt: skip
        if log_y:
            ax.set_yscale("log")
            top = ax.dataLim.y1
            if np.isfinite(top) and ax.dataLim.y0 < top / 10**DECADES:
                ax.set_ylim(top / 10**DECADES, top * 3)
                below = _mark_below(ax, x, lines, shades, sweep, other)
                if below:
                    notes.append(f"{below} of {total} points below the axis "
                                 f"(< {_number(top / 10**DECADES, 3)}): ▼ at its edge")  # fmt: skip
        if notes:
            ax.set_title("\n".join(notes), fontsize=8)
        if x_dim == "sigma":
            _mark_table1(ax, sweep, lines, log_y)
        h_shown = float(h_grid[rows[0]]) if per_h and other is not None else None
        _readable_log_ticks(ax.xaxis)
        _readable_log_ticks(ax.yaxis)
        ax.set_ylabel(_label(key, h_shown), fontsize=9)
        ax.set_xlabel(axis_label(sweep, x_dim), fontsize=9)
        ax.grid(True, which="major", alpha=0.4)
        if log_x or log_y:
            ax.grid(True, which="minor", alpha=0.12)
        if shades is not None:
            bar = fig.colorbar(shades, ax=ax, pad=0.01)
            bar.set_label(axis_label(sweep, other), fontsize=8)
        elif len(lines) > 1 or f"mc_{key}" in sweep.data:
            ax.legend(fontsize=7, title=_legend_title(sweep, other, per_h), title_fontsize=7,
                      loc="lower left")  # fmt: skip
    fig.suptitle(_title(sweep, name), fontsize=9)
    return fig


def _mark_below(ax, x, lines, shades, sweep, other) -> int:
    """The positive values of ``lines`` below the log axis' lower limit: a ▼ each at the axis'
    edge, in its line's colour (gid ``below-axis``); returns how many."""
    bottom = ax.get_ylim()[0]
    count = 0
    for i, (_, y, _, index) in enumerate(lines):
        low = (y > 0) & (y < bottom)
        if not low.any():
            continue
        count += int(low.sum())
        colour = COLOURS[i % len(COLOURS)] if shades is None else shades.to_rgba(
            display_values(sweep, other)[index])  # fmt: skip
        (mark,) = ax.plot(x[low], np.full(low.sum(), bottom), "v", color=colour, ms=6,
                          clip_on=False, zorder=6, label="_below")  # fmt: skip
        mark.set_gid("below-axis")
    return count


#: Most lines of one panel told apart by a legend; beyond, a colour scale and a colour bar.
MAX_LEGEND_LINES = 6


def _shades(sweep, other):
    """A colour scale (``ScalarMappable``) over the values of the second input, log-spaced
    for a log grid; None for a categorical input (law sets: a legend stays readable)."""
    from matplotlib import cm, colors

    values = display_values(sweep, other)
    if values.dtype.kind in "US":
        return None
    log = is_log_grid(sweep.coords[other])
    norm = (colors.LogNorm if log else colors.Normalize)(values.min(), values.max())
    return cm.ScalarMappable(norm=norm, cmap="viridis")


def _line_set(sweep, key, x_axis, other, rows, per_h):
    """(label, y over x, h row, index of the other input) for every line of one panel."""
    if other is None:
        y = np.asarray(sweep.data[key], dtype=float)
        if not per_h:
            return [(None, y, None, None)]
        h = sweep.coords["h"]
        return [(f"$d/\\sigma$ = {h[r]:.3g}", y[:, r], r, None) for r in rows]
    values = display_values(sweep, other)
    scale_unit = DISPLAY.get(other, (1.0, ""))[1]
    out = []
    for j, v in enumerate(values):
        y = _take(sweep, key, x_axis, j)
        if per_h:
            y = y[:, rows[0]]
        text = (
            str(v)
            if values.dtype.kind in "US"
            else f"{v:.3g}" + (f" {scale_unit}" if scale_unit else "")
        )
        out.append((text, y, rows[0] if per_h else None, j))
    return out


def _take(sweep, key: str, x_axis: int, index: int | None) -> np.ndarray:
    """The variable along the x input, at position ``index`` of the other input (if any)."""
    values = np.asarray(sweep.data[key], dtype=float)
    return values if index is None else np.moveaxis(values, x_axis, 0)[:, index]


def _legend_title(sweep, other, per_h) -> str | None:
    if other is None:
        return None if not per_h else "separation"
    return DISPLAY.get(other, (1, "", other))[2]


def _mark_table1(ax, sweep, lines, log_y: bool) -> None:
    """The σ of the paper's four Table-1 surfaces: a dotted line each, named on a top axis
    (over the curves a name would hide them), and a ◆ on the first line of the panel where
    that σ is a point of the grid (the computed value there; between grid points a marker
    would show an interpolation, not a computed value)."""
    sigma = sweep.coords["sigma"].astype(float)
    lo, hi = sigma.min(), sigma.max()
    _, y, *_ = lines[0]
    points = _table1_points(sigma)
    for name in PAPER_SURFACES:
        s = SURFACES[name].sigma
        if lo <= s <= hi:
            ax.axvline(s * 1e9, color="0.55", lw=0.7, ls=":", zorder=0.5)
        if name in points and np.isfinite(y[points[name]]) and (y[points[name]] > 0 or not log_y):
            ax.plot(s * 1e9, y[points[name]], "D", color="k", ms=5, zorder=5, label="_table1")
    _table1_names(ax, [n for n in PAPER_SURFACES if lo <= SURFACES[n].sigma <= hi])


def _table1_points(sigma: np.ndarray) -> dict[str, int]:
    """The paper's Table-1 surfaces whose σ is a point of the grid ``sigma`` (m): its index."""
    found = {}
    for name in PAPER_SURFACES:
        at = np.flatnonzero(np.isclose(sigma, SURFACES[name].sigma, rtol=1e-9, atol=0.0))
        if at.size:
            found[name] = int(at[0])
    return found


# --- maps -----------------------------------------------------------------------------------


def _map_figure(sweep, dims: list[str], row: int, name: str):
    """Colour maps over two numeric inputs with the adhesion-map regime boundaries."""
    from matplotlib import colormaps
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.figure import Figure

    x_dim, y_dim = dims
    panels = _panels(sweep, name)[:2]
    h = float(sweep.coords["h"][row])
    x, y = display_values(sweep, x_dim), display_values(sweep, y_dim)
    log_x, log_y = is_log_grid(sweep.coords[x_dim]), is_log_grid(sweep.coords[y_dim])
    xe, ye = cell_edges(x, log_x), cell_edges(y, log_y)
    transpose = sweep.grid.index(x_dim) < sweep.grid.index(y_dim)

    def grid_values(key):  # rows over y, columns over x (as pcolormesh takes them)
        v = _values(sweep, key, row)
        return v.T if transpose else v

    failed = np.asarray(sweep.data["error"]) != ""
    failed = failed.T if transpose else failed
    fig = Figure(figsize=(6.2 * len(panels), 5.2), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(panels)))
    zeros = False
    for ax, key in zip(axes, panels):
        z = grid_values(key)
        log = key in LOG_VARIABLES
        zeros |= bool(log and np.any(z == 0))
        shown = np.where(z > 0, z, np.nan) if log else z
        finite = shown[np.isfinite(shown)]
        norm, extend = None, "neither"
        if finite.size:
            low, high = finite.min(), finite.max()
            if log and low < high / 10**DECADES:
                low, extend = high / 10**DECADES, "min"
            norm = LogNorm(low, high) if log else Normalize(low, high)
        if np.any(failed):
            ax.pcolormesh(xe, ye, np.where(failed, 1.0, np.nan), cmap="Greys", vmin=0, vmax=4)
        cmap = colormaps["viridis"].with_extremes(under="#2a0a3a")
        mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(shown), cmap=cmap, norm=norm)
        per_h = sweep.dims[key][-1] == "h"
        fig.colorbar(mesh, ax=ax, label=_label(key, h if per_h else None), extend=extend)
        if log_x:
            ax.set_xscale("log")
        if log_y:
            ax.set_yscale("log")
        ax.set_xlim(xe[0], xe[-1])
        ax.set_ylim(ye[0], ye[-1])
        _regimes(ax, sweep, x, y, grid_values, blank=~np.isfinite(shown) & ~failed)
        _readable_log_ticks(ax.xaxis)
        _readable_log_ticks(ax.yaxis)
        ax.set_xlabel(axis_label(sweep, x_dim), fontsize=9)
        ax.set_ylabel(axis_label(sweep, y_dim), fontsize=9)
        if x_dim == "sigma":
            _table1_axis(ax, x)
    title = _title(sweep, name, diamonds=False).replace("left blank", "grey")
    title += ("\nregime boundaries: Johnson-Greenwood (1997) adhesion map (Maugis $\\lambda$ = "
              f"{DMT_BELOW:g}, {JKR_ABOVE:g}), plasticity index $\\psi$ = 1")  # fmt: skip
    if zeros:
        title += "; white: 0, no adhesive contact at rest"
    fig.suptitle(title, fontsize=9)
    return fig


def _table1_axis(ax, x) -> None:
    """The σ of the paper's Table-1 surfaces: dotted lines, named on a top axis."""
    marks = {s: SURFACES[s].sigma * 1e9 for s in PAPER_SURFACES}
    marks = {s: v for s, v in marks.items() if x.min() <= v <= x.max()}
    for v in marks.values():
        ax.axvline(v, color="w", lw=0.7, ls=":")
    _table1_names(ax, list(marks))


def _table1_names(ax, names: list[str]) -> None:
    """The Table-1 surfaces ``names`` on a top axis, at their σ (nm)."""
    top = ax.secondary_xaxis("top")
    top.set_xticks([SURFACES[s].sigma * 1e9 for s in names], names, fontsize=7, rotation=30,
                   ha="left")  # fmt: skip
    top.minorticks_off()


#: Region names of the Johnson–Greenwood map at low load, by Maugis λ.
REGIONS = (
    ("DMT", None, DMT_BELOW),
    ("Maugis–Dugdale", DMT_BELOW, JKR_ABOVE),
    ("JKR", JKR_ABOVE, None),
)


def _regimes(ax, sweep, x, y, grid_values, blank=None) -> None:
    """Contours of Maugis' λ at the map's thresholds (gid ``regime-boundaries``), the
    regions named (in blank cells of the map where the region has some, so that no name
    covers a value), and ψ = 1 (gid ``plasticity-boundary``) where ψ is defined."""
    if _finite(sweep, "maugis_lambda"):
        lam = grid_values("maugis_lambda")
        levels = [v for v in (DMT_BELOW, JKR_ABOVE) if np.nanmin(lam) < v < np.nanmax(lam)]
        if levels:
            cs = ax.contour(x, y, lam, levels=levels, colors="w", linewidths=1.6)
            cs.set_gid("regime-boundaries")
            _contour_labels(ax, cs, {v: f"λ = {v:g}" for v in levels})
        for label, low, high in REGIONS:
            inside = np.isfinite(lam) & (lam >= (low or -np.inf)) & (lam < (high or np.inf))
            _region_label(ax, x, y, inside, label, blank=blank)
    if _finite(sweep, "plasticity_index"):
        psi = grid_values("plasticity_index")
        if np.nanmin(psi) < 1 < np.nanmax(psi):
            cs = ax.contour(x, y, psi, levels=[1.0], colors="orangered", linewidths=1.6,
                            linestyles="--")  # fmt: skip
            cs.set_gid("plasticity-boundary")
            _contour_labels(ax, cs, {1.0: "ψ = 1"})
            _region_label(ax, x, y, psi > 1, "ψ > 1:\nplastic", colour="orangered", right=True)


def _contour_labels(ax, cs, fmt: dict) -> None:
    """Each level named beside its line, not over it: a quarter of the way along its longest
    piece (clear of the region names, which sit mid-region), above a line that runs across the
    map, left of one that runs up it (the axes' scales and limits must be set first)."""
    to_axes = ax.transScale + ax.transLimits
    for level, path in zip(cs.levels, cs.get_paths()):
        pieces = [p for p in path.to_polygons(closed_only=False) if len(p)]
        if level not in fmt or not pieces:
            continue
        piece = to_axes.transform(max(pieces, key=len))
        across = np.ptp(piece[:, 0]) >= np.ptp(piece[:, 1])
        along = np.argsort(piece[:, 0] if across else piece[:, 1])
        ax.annotate(fmt[level], piece[along[len(along) // 4]], xycoords="axes fraction",
                    xytext=(0, 4) if across else (-4, 0), textcoords="offset points",
                    ha="center" if across else "right", va="bottom" if across else "center",
                    rotation=0 if across else 90, fontsize=7,
                    bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none", "pad": 1})  # fmt: skip


def _region_label(ax, x, y, inside: np.ndarray, label: str, colour: str = "k",
                  right: bool = False, blank=None) -> None:  # fmt: skip
    """Name a region of the map at a cell near its middle (``right``: its right edge); where
    ``blank`` cells (no value drawn) lie in the region, in the middle of its longest row of
    them instead, without a background: the name then covers no value."""
    if not inside.any():
        return
    if blank is not None and (inside & blank).any():
        free = inside & blank
        middle = np.median(np.nonzero(inside)[0])
        best = (0, 0.0, 0, 0)  # (run length, -distance to the middle row, row, first column)
        for i in np.unique(np.nonzero(free)[0]):
            j = 0
            while j < free.shape[1]:
                if free[i, j]:
                    k = j
                    while k + 1 < free.shape[1] and free[i, k + 1]:
                        k += 1
                    best = max(best, (k - j + 1, -abs(i - middle), int(i), j))
                    j = k + 1
                else:
                    j += 1
        n, _, i, j = best
        ends = x[j], x[j + n - 1]
        at = math.sqrt(ends[0] * ends[1]) if ax.get_xscale() == "log" else (ends[0] + ends[1]) / 2
        ax.text(at, y[i], label, ha="center", va="center", fontsize=9, weight="bold", color=colour)
        return
    rows, cols = np.nonzero(inside)
    i, j = int(np.median(rows)), int(cols.max() if right else np.median(cols))
    if not inside[i, j]:
        i, j = rows[len(rows) // 2], cols[len(cols) // 2]
    ax.text(x[j], y[i], label, ha="right" if right else "center", va="center", fontsize=9,
            weight="bold", color=colour, bbox={"facecolor": "white", "alpha": 0.75, "edgecolor": "none"})  # fmt: skip
