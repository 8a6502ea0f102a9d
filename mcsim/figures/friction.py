"""Figures of a pads sweep with friction (``mcsim sweep --pads --friction`` or
``--tangential-force``): the pads' static friction coefficient and the probability that a
pad slips.

* Top: μ_s of the pads against the varied input (RH, the preload, ...): the mean (points) with
  the 95 % interval of the mean (bars, ±1.96 std/√n over the n pads), and the spread from pad
  to pad, the 5–95 % quantiles (band) with the median (dashed); on a log axis where they span
  more than a factor 30. A second varied input draws a line per value.
* Bottom, with a tangential force: p_slip with its 95 % interval (Clopper–Pearson; squares
  where importance sampling estimated it, ``p_slip_method``).
"""

from __future__ import annotations

import numpy as np

from mcsim.figures.grid import axis_label, display_values, is_log_grid, pads_title, pads_varied

#: z of the two-sided 95 % interval of the mean.
Z95 = 1.959963984540054


def is_friction_sweep(sweep) -> bool:
    """Whether the sweep holds the pads' friction (``mu_static_mean``)."""
    return "mu_static_mean" in sweep.data


def friction_figure(sweep):
    """μ_s (and p_slip) of a pads sweep against its one or two varied inputs (module docstring).

    Returns
    -------
    matplotlib.figure.Figure
        Built without pyplot (headless).
    """
    from matplotlib.figure import Figure

    sweep, dims = pads_varied(sweep, "a friction sweep")
    slip = "p_slip" in sweep.data
    fig = Figure(figsize=(7, 7.5 if slip else 4.5), layout="constrained")
    axes = fig.subplots(2 if slip else 1, 1, sharex=True, squeeze=False)[:, 0]
    x = display_values(sweep, dims[0])
    lines = [(slice(None), "")]
    if len(dims) == 2:
        values = display_values(sweep, dims[1])
        lines = [((slice(None), j), f"{dims[1]} = {v:.4g}") for j, v in enumerate(values)]
    n = sweep.attrs["pads"]
    d = sweep.data
    for k, (at, name) in enumerate(lines):
        colour = f"C{k}"
        mean, std = d["mu_static_mean"][at], d["mu_static_std"][at]
        axes[0].fill_between(x, d["mu_static_q05"][at], d["mu_static_q95"][at], color=colour,
                             alpha=0.15, lw=0, label=f"{name} 5-95 % of the pads".strip())  # fmt: skip
        axes[0].plot(x, d["mu_static_q50"][at], "--", color=colour, lw=1,
                     label=f"{name} median".strip())  # fmt: skip
        axes[0].errorbar(x, mean, yerr=Z95 * std / np.sqrt(n), fmt="o-", color=colour, capsize=3,
                         label=f"{name} mean, 95 % interval of the mean".strip())  # fmt: skip
        if slip:
            p = d["p_slip"][at]
            tail = d["p_slip_method"][at] == "importance"
            err = [p - d["p_slip_low"][at], d["p_slip_high"][at] - p]
            for mask, fmt in ((~tail, "o"), (tail, "s")):
                if mask.any():
                    axes[1].errorbar(x[mask], p[mask], yerr=[e[mask] for e in err], fmt=fmt,
                                     color=colour, capsize=3, label=(f"{name} " + (
                                         "importance sampling" if fmt == "s" else
                                         "fraction of the pads, Clopper-Pearson")).strip())  # fmt: skip
    axes[0].set_ylabel(r"static friction coefficient $\mu_s = T_s/W$")
    low, high = np.nanmin(d["mu_static_q05"]), np.nanmax(d["mu_static_q95"])
    if low > 0 and high / low > 30:  # μ_s ∝ 1/P over a decade or more of the preload
        axes[0].set_yscale("log")
    else:
        axes[0].set_ylim(bottom=0)
    axes[0].legend(fontsize="small")
    if slip:
        axes[1].set_ylabel("probability that a pad slips, p_slip")
        axes[1].set_ylim(-0.03, 1.03)
        axes[1].legend(fontsize="small", title="95 % intervals", title_fontsize="small")
    if is_log_grid(sweep.coords[dims[0]]):
        axes[-1].set_xscale("log")
    axes[-1].set_xlabel(axis_label(sweep, dims[0]))
    axes[0].set_title(_title(sweep), fontsize="medium")
    return fig


def _title(sweep) -> str:
    a = sweep.attrs
    text = pads_title(sweep)
    if "preload" in a:
        text += f", preload {a['preload'] / 1e6:.4g} MPa"
    if "tangential_force" in a:
        text += f", tangential force {a['tangential_force'] * 1e6:.4g} µN"
    return text
