"""Figures of a pads sweep (``mcsim sweep --pads``): the probability that a pad sticks.

* One varied input: p_stick (points) with its 95 % interval (bars) and the model estimate
  ``p_stick_model`` (line, a × on it where fewer than 10 summits touch: the model is then
  unreliable) against the input, p on a log axis from half the smallest p, interval end or
  model value drawn (1e-6 and below with importance sampling) to 1.5: circles for the
  fraction of the pads (Clopper-Pearson), squares for importance sampling (Clopper-Pearson
  on the effective sample size; ``p_stick_method``).
* Two: p_stick over the map in log colour, with the contours of :data:`LEVELS` (1e-6, 1e-3,
  and 0.5: the stiction boundary) that its range holds; hatched where the interval
  straddles a level, i.e. where the data cannot tell on which side of it the point lies.
"""

from __future__ import annotations

import numpy as np

from mcsim.figures.grid import (
    axis_label,
    cell_edges,
    display_values,
    is_log_grid,
    pads_title,
    pads_varied,
)

#: Probabilities drawn as contours on a 2-D map.
LEVELS = (1e-6, 1e-3, 0.5)


def is_pads_sweep(sweep) -> bool:
    """Whether the sweep holds pads (``p_stick``)."""
    return "p_stick" in sweep.data


def stiction_figure(sweep):
    """p_stick of a pads sweep against its one or two varied inputs (module docstring).

    Returns
    -------
    matplotlib.figure.Figure
        Built without pyplot (headless).
    """
    sweep, dims = pads_varied(sweep, "a pads sweep")
    return _line(sweep, dims[0]) if len(dims) == 1 else _map(sweep, dims)


def _title(sweep) -> str:
    a = sweep.attrs
    force = a.get("restoring_force")  # absent where varied
    text = pads_title(sweep) + ("" if force is None else f", restoring force {force * 1e6:.4g} µN")
    if "preload" in a:
        text += f", preload {a['preload'] / 1e6:.4g} MPa (force control)"
    return text


def _line(sweep, dim: str):
    from matplotlib.figure import Figure

    x = display_values(sweep, dim)
    d = sweep.data
    floor = _floor(sweep)  # p = 0 drawn at the floor, marked as an upper bound
    p = np.maximum(d["p_stick"], floor)
    bottom = floor * 0.2
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    tail = _importance(sweep)
    none = ~tail & (d["p_stick"] == 0)  # no pad sticks: only the interval's top says anything
    for mask, fmt, label in ((~tail & ~none, "o", "pads: fraction sticking, 95 % Clopper-Pearson interval"),
                             (none, "v", "pads: none sticks (drawn at the floor), 95 % interval"),
                             (tail, "s", "importance sampling, 95 % interval on the effective sample size")):  # fmt: skip
        if mask.any():
            low = np.maximum(d["p_stick_low"][mask], bottom)
            ax.errorbar(x[mask], p[mask], yerr=[p[mask] - low, d["p_stick_high"][mask] - p[mask]],
                        fmt=fmt, color="k", capsize=3, label=f"Monte Carlo p_stick, {label}")  # fmt: skip
    drawn = [p, np.maximum(d["p_stick_low"], bottom)]  # the points and their bars' lower ends
    model = np.clip(d.get("p_stick_model", np.full(p.shape, np.nan)), 1e-12, None)
    if np.any(np.isfinite(model)):
        ax.plot(x, model, color="C3", label="model (compound Poisson, saddlepoint)")
        # the model is what is unreliable there: the cross sits on its line
        few = (d["contacting_summits"] < 10) & np.isfinite(model)
        if few.any():
            ax.plot(x[few], model[few], "x", color="C1", ms=10,
                    label="< 10 contacting summits: model unreliable")  # fmt: skip
        drawn.append(model)
    elif "p_stick_model" in d:  # NaN everywhere: pads with an environment
        ax.plot([], [], " ", label="no model estimate with an environment")
    for level in LEVELS:
        ax.axhline(level, color="0.6", ls=":", lw=1)
    ax.set_yscale("log")
    low = np.concatenate([np.ravel(v) for v in drawn])  # from half the lowest value drawn
    ax.set_ylim(np.nanmin(np.where(low > 0, low, np.nan)) / 2, 1.5)
    if is_log_grid(sweep.coords[dim]):
        ax.set_xscale("log")
    ax.set_xlabel(axis_label(sweep, dim))
    ax.set_ylabel("probability that a pad sticks, p_stick")
    ax.set_title(_title(sweep), fontsize="medium")
    # below the axes: inside, it covers the bars at the floor (the dry points of a humid sweep)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", fontsize="small")
    return fig


def _importance(sweep) -> np.ndarray:
    """Where p_stick came from importance sampling (``p_stick_method``; none in older files)."""
    method = sweep.data.get("p_stick_method")
    return np.zeros(sweep.data["p_stick"].shape, bool) if method is None else method == "importance"


def _floor(sweep) -> float:
    """Where p = 0 is drawn: half a pad, or below the smallest p of importance sampling."""
    p = sweep.data["p_stick"][_importance(sweep)]
    p = p[np.isfinite(p) & (p > 0)]
    floor = 0.5 / sweep.attrs["pads"]
    return min(floor, p.min() / 2) if p.size else floor


def _map(sweep, dims: list[str]):
    from matplotlib.colors import LogNorm
    from matplotlib.figure import Figure

    (xd, yd), d = dims, sweep.data
    x, y = display_values(sweep, xd), display_values(sweep, yd)
    floor = _floor(sweep)
    p = np.maximum(d["p_stick"], floor).T  # rows: y
    fig = Figure(figsize=(7.5, 5.5), layout="constrained")
    ax = fig.subplots()
    logx, logy = is_log_grid(sweep.coords[xd]), is_log_grid(sweep.coords[yd])
    mesh = ax.pcolormesh(cell_edges(x, logx), cell_edges(y, logy), p,
                         norm=LogNorm(vmin=floor, vmax=1), cmap="viridis", shading="flat")  # fmt: skip
    fig.colorbar(mesh, ax=ax, label="probability that a pad sticks, p_stick (Monte Carlo)")
    if x.size > 1 and y.size > 1:
        names = {1e-6: "1e-6", 1e-3: "1e-3", 0.5: "0.5: stiction boundary"}
        levels = [v for v in LEVELS if np.nanmin(p) < v < np.nanmax(p)]
        if levels:
            cs = ax.contour(x, y, p, levels=levels, linewidths=1.5,
                            colors=["r" if v == 0.5 else "w" for v in levels])  # fmt: skip
            ax.clabel(cs, fmt={v: names[v] for v in levels}, fontsize="small")
        low, high = d["p_stick_low"].T, d["p_stick_high"].T
        for level in LEVELS:
            unsure = ((low < level) & (high > level)).astype(float)
            if unsure.any():
                ax.contourf(x, y, unsure, levels=[0.5, 1.5], colors="none", hatches=["//"])
    ax.set_xlabel(axis_label(sweep, xd))
    ax.set_ylabel(axis_label(sweep, yd))
    if logx:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_title(_title(sweep) + "\nhatched: the 95 % interval straddles a contour level",
                 fontsize="medium")  # fmt: skip
    return fig


def pads_figure(force, analytic_mean: float | None = None, *, restoring_force: float | None = None,
                p_stick: float | None = None, interval: tuple[float, float] | None = None,
                interval_name: str = "", title: str | None = None):  # fmt: skip
    """Histogram and survival function (1 − empirical CDF) of per-pad pull-off forces (µN),
    analytic mean marked and, with a restoring force, the probability of sticking and its
    interval.

    Parameters
    ----------
    force : array_like
        Pull-off force of each pad, N.
    analytic_mean : float, optional
        GW mean pad pull-off (:func:`mcsim.studies.pads.analytic_pad_pull_off`), N: a dashed line.
    restoring_force : float, optional
        F_r, N: a dotted line (pads to its right stick).
    p_stick, interval : float and (float, float), optional
        P(pull-off > F_r) and its interval: drawn on the right panel (the fraction of pads
        with a pull-off above F) at F_r, with the interval as an error bar, and written in
        the legend.
    interval_name : str
        Name of the interval (e.g. "Clopper-Pearson 95 %").
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        Built without pyplot (headless); one legend for both panels, below them.
    """
    from matplotlib.figure import Figure

    f = np.sort(np.asarray(force, dtype=float).ravel()) * 1e6
    fig = Figure(figsize=(9, 4.4), layout="constrained")
    hist, ecdf = fig.subplots(1, 2)
    hist.hist(f, bins=max(10, min(60, int(np.sqrt(f.size)))), density=True, color="0.7",
              edgecolor="0.4", label=f"Monte Carlo, {f.size} pads")  # fmt: skip
    hist.set_ylabel("density (1/µN)")
    # the fraction of pads that hold on against a restoring force F: p_stick at F = F_r
    ecdf.step(f, 1 - np.arange(1, f.size + 1) / f.size, where="post", color="k",
              label="fraction of pads with pull-off > F (1 − empirical CDF)")  # fmt: skip
    ecdf.set_ylabel("fraction of pads with pull-off > F")
    for ax in (hist, ecdf):
        ax.axvline(np.mean(f), color="C0", label=f"mean {np.mean(f):.4g} µN")
        if analytic_mean is not None:
            ax.axvline(analytic_mean * 1e6, color="C3", ls="--",
                       label=f"GW analytic mean {analytic_mean * 1e6:.4g} µN")  # fmt: skip
        if restoring_force is not None:
            ax.axvline(restoring_force * 1e6, color="C2", ls=":",
                       label=f"restoring force {restoring_force * 1e6:.4g} µN")  # fmt: skip
        ax.set_xlabel("pad pull-off force F (µN)")
    if restoring_force is not None and p_stick is not None:
        low, high = interval if interval is not None else (p_stick, p_stick)
        ecdf.errorbar([restoring_force * 1e6], [p_stick], yerr=[[p_stick - low], [high - p_stick]],
                      color="C2", marker="o", capsize=3,
                      label=f"$p_{{stick}}$ = {p_stick:.3g} [{low:.3g}, {high:.3g}] {interval_name}")  # fmt: skip
    # one legend for both panels (the lines are the same), below them: it covers no bar and no step
    handles, labels = hist.get_legend_handles_labels()
    for handle, label in zip(*ecdf.get_legend_handles_labels()):
        if label not in labels:
            handles.append(handle)
            labels.append(label)
    fig.legend(
        handles, labels, loc="outside lower center", ncols=3, fontsize="small", frameon=False
    )
    if title:
        fig.suptitle(title)
    return fig
