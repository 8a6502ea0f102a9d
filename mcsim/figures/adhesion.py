"""Figures of contact law sets: the approach/retraction cycle and the Fuller-Tabor plot."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from mcsim.figures.style import COLOURS, LINESTYLES, X_LABEL, number


def adhesion_figure(surface, material, law, summary=None, *, points: int = 400):
    """Approach and retraction load of one rough contact, the pull-off point marked.

    Parameters
    ----------
    surface, material : Surface, Material
        The contact.
    law : str or LawSet
        A contact law set with a retraction branch (``jkr``, ``dmt``,
        ``maugis-dugdale``).
    summary : AdhesionSummary, optional
        From :func:`mcsim.physics.adhesion.adhesion_summary` (computed if not given); its
        turn is the closest approach of the cycle.
    points : int
        Separations per branch.

    Returns
    -------
    matplotlib.figure.Figure
        Nominal pressure (MPa, > 0 compressive; right axis: load/(A_n K)) against
        h = d/σ decreasing left to right (top axis: d in nm), the approach and the
        retraction from the turn, the tensile part of the retraction shaded (its area
        is the work of separation) and the pull-off marked.
    """
    import warnings

    from matplotlib.figure import Figure
    from matplotlib.ticker import ScalarFormatter

    from mcsim.physics.adhesion import RegimeWarning, adhesion_summary, top_separation
    from mcsim.physics.analytic import analytic_curves
    from mcsim.physics.laws import get_law_set

    laws = get_law_set(law)
    if summary is None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RegimeWarning)
            summary = adhesion_summary(surface, material, laws)
    turn, K, sigma = summary.turn, material.K, surface.sigma
    h = np.linspace(turn, top_separation(surface, laws, material), points)
    approach = analytic_curves(surface, material, h, laws).load
    retract = analytic_curves(surface, material, h, laws, branch="retract", turn=turn).load
    # show the separations where either branch carries a visible load
    both = np.maximum(np.abs(approach), np.abs(retract))
    visible = np.flatnonzero(both > 1e-3 * both.max())
    keep = h <= h[min(visible[-1] + 1, h.size - 1)] if visible.size else h == h
    h, approach, retract = h[keep], approach[keep], retract[keep]
    mpa = K / 1e6

    fig = Figure(figsize=(7.5, 5.5), layout="constrained")
    ax = fig.add_subplot()
    ax.axhline(0, color="0.6", lw=0.8, zorder=1)
    ax.plot(h, approach * mpa, color="#0072B2", lw=1.8, label="approach (loading)")
    ax.plot(h, retract * mpa, color="#D55E00", lw=1.8, ls="--",
            label=f"retraction from $h_{{turn}} = {turn:.3g}$")  # fmt: skip
    ax.fill_between(h, np.minimum(retract, 0) * mpa, 0, color="#D55E00", alpha=0.15, lw=0,
                    label=f"work of separation {summary.work_of_separation * 1e3:.3g} mJ/m$^2$")  # fmt: skip
    ax.axvline(turn, color="0.45", lw=0.8, ls=":")
    if summary.pull_off > 0:
        p = summary.pull_off_pressure / 1e6
        ax.plot(summary.h_pull_off, -p, "o", color="k", ms=7, zorder=5,
                label=f"pull-off {p:.3g} MPa at $h = {summary.h_pull_off:.3g}$")  # fmt: skip
        ax.annotate("pull-off", (summary.h_pull_off, -p), xytext=(8, -14),
                    textcoords="offset points", fontsize=9)  # fmt: skip
    ax.set_xlim(h.max(), h.min())
    ax.set_xlabel(X_LABEL)
    ax.set_ylabel(r"Nominal pressure $p = P/A_n$ (MPa), > 0 compressive")
    top = ax.secondary_xaxis(
        "top", functions=(lambda x: x * sigma * 1e9, lambda d: d / (sigma * 1e9))
    )
    top.set_xlabel("Mean separation $d$ (nm)")
    # in units of 10^e, named in the label: plain tick labels with minus signs (U+2212), no
    # "-5e-06" and no offset text over the top axis
    e = int(np.floor(np.log10(np.max(np.abs([*approach, *retract]))))) if np.any(both) else 0
    unit = 10.0**e
    right = ax.secondary_yaxis(
        "right", functions=(lambda y: y / mpa / unit, lambda v: v * unit * mpa)
    )
    right.set_ylabel(rf"Load $P/(A_n\,K)$ (units of $10^{{{e}}}$)")
    right.yaxis.set_major_formatter(ScalarFormatter(useOffset=False))
    ax.grid(True, alpha=0.4)
    # below the axes: inside, it covers the curves near the approach's start
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=2, fontsize=8,
               frameon=False)  # fmt: skip
    noise = abs(summary.hysteresis) < 1e-9 * max(summary.work_of_separation, 1e-300)
    hysteresis = "0 (none)" if noise else f"{number(summary.hysteresis * 1e3)} mJ/m$^2$"
    numbers = [f"law set {laws.name}", f"hysteresis {hysteresis}"]
    if summary.maugis_lambda is not None:
        numbers.append(
            rf"Maugis $\lambda$ = {summary.maugis_lambda:.3g}, Tabor $\mu_T$ = {summary.tabor:.3g}"
        )
    numbers.append(rf"Fuller-Tabor $\theta$ = {summary.adhesion_parameter:.3g}")
    if summary.plasticity_index is not None:
        numbers.append(rf"plasticity index $\psi$ = {summary.plasticity_index:.3g}")
    ax.text(0.02, 0.03, "\n".join(numbers), transform=ax.transAxes, ha="left", va="bottom",
            fontsize=8, bbox={"facecolor": "white", "edgecolor": "0.8", "alpha": 0.9})  # fmt: skip
    ax.set_title(f"{surface.name or 'surface'}: approach and retraction ({laws.name})", fontsize=10)
    return fig


def fuller_tabor_figure(theta, pull_off: Mapping[str, np.ndarray], *, title: str | None = None):
    """Normalised pull-off force against the Fuller–Tabor adhesion parameter.

    Parameters
    ----------
    theta : array_like
        Adhesion parameter θ = E* σ^{3/2}/(R^{1/2} w) (:func:`mcsim.physics.adhesion.adhesion_parameter`).
    pull_off : mapping of str to array_like
        Normalised pull-off force, pull-off / (N_turn · (3/2)πwR) with N_turn the
        summits touched at the closest approach, per curve label (e.g. the closest
        approach), one value per θ.
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        θ on a log axis (top axis: Fuller & Tabor's own abscissa σ/δ_c = 0.6216 θ^{2/3},
        δ_c the JKR break-off under fixed grips), normalised pull-off on a linear axis.
    """
    from matplotlib.figure import Figure

    theta = np.asarray(theta, dtype=float)
    fig = Figure(figsize=(7.0, 5.0), layout="constrained")
    ax = fig.add_subplot()
    for position, (label, values) in enumerate(pull_off.items()):
        ax.plot(theta, values, marker="o", ms=3.5, lw=1.6, label=label,
                color=COLOURS[position % len(COLOURS)],
                linestyle=LINESTYLES[position % len(LINESTYLES)])  # fmt: skip
    ax.set_xscale("log")
    ax.set_ylim(0, 1.05)
    ax.set_xlabel(r"Adhesion parameter $\theta = E^* \sigma^{3/2} / (R^{1/2} w)$")
    ax.set_ylabel(r"Pull-off force / $(N_{turn} \cdot \frac{3}{2}\pi w R)$")
    c = 1 / (0.75 * np.pi ** (2 / 3))
    top = ax.secondary_xaxis("top", functions=(lambda t: c * np.abs(t) ** (2 / 3),
                                               lambda x: (np.abs(x) / c) ** 1.5))  # fmt: skip
    top.set_xlabel(r"Fuller & Tabor's $1/\Delta_c = \sigma/|\delta_c|$")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, title="closest approach", title_fontsize=8)
    ax.set_title(title or "Fuller & Tabor (1975): rough-surface pull-off, JKR summits", fontsize=10)
    return fig
