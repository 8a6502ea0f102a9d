"""Figures of the GW curves versus mean separation, as in the paper's Figs. 2-6.

Plots sit at the edge of mcsim: matplotlib is imported inside the functions, and
figures are built as :class:`matplotlib.figure.Figure` objects without pyplot, so
they work headless, in scripts and in Jupyter (a ``Figure`` displays itself there)
without touching the global backend.

Conventions a tribologist expects from the paper's figures:

* x axis: the dimensionless mean separation h = d/σ runs from large to small, left
  to right (4 → −1 in the paper), so reading a figure left to right follows the
  surfaces being pressed together (loading);
* y axis: logarithmic for the forces P̄, F̄, P̄ + F̄ and T̄ (they grow by six
  decades over 4 ≥ h ≥ −1), linear for μ and for the contact fraction;
* one colour and line style per surface, the same in every figure.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from mcsim.figures.style import (
    LABELS,
    LOG_QUANTITIES,
    X_LABEL,
    errorbars,
    mc_legend,
    surface_label,
    surface_style,
)
from mcsim.model.errors import MCSimError
from mcsim.physics.analytic import AnalyticCurves

#: The paper's figure number and caption for each quantity it plots.
PAPER_FIGURES = {
    "P": (2, "External force vs. mean separation"),
    "F": (3, 'Adhesion term (paper: "adhesive force") vs. mean separation'),
    "total": (4, "Total force vs. mean separation"),
    "T": (5, "Friction force vs. mean separation"),
    "mu": (6, "Coefficient of friction vs. mean separation"),
}


def quantity_values(curves: AnalyticCurves, quantity: str) -> np.ndarray:
    """Values of ``quantity`` (a key of :data:`LABELS`) from analytic curves; total = P̄ + F̄."""
    _check_quantity(quantity)
    if quantity == "total":
        return curves.P + curves.F
    return getattr(curves, quantity)


def curve_figure(
    quantity: str,
    curves: Mapping[str, AnalyticCurves],
    mc: Mapping[str, Mapping] | None = None,
):
    """One quantity versus h, one line per surface, optionally with Monte Carlo points.

    Parameters
    ----------
    quantity : str
        A key of :data:`LABELS`: ``"P"``, ``"F"``, ``"total"`` (P̄ + F̄), ``"T"``,
        ``"mu"`` or ``"contact_fraction"``. Forces are dimensionless, divided by
        A_n K.
    curves : mapping of str to AnalyticCurves
        Analytic curves by surface name, drawn as lines in this order.
    mc : mapping of str to dict, optional
        Monte Carlo results by surface name (each must also be in ``curves``):
        ``{"h": array, "mean": {quantity: array}, "se": {quantity: array}}``, with
        the same scaling as the curves. Drawn as markers in the surface's colour with
        error bars of ±2 standard errors. A surface whose ``mean`` lacks
        ``quantity`` is not overlaid in this figure; one whose ``se`` lacks it gets
        markers without error bars. On a log axis non-positive means (e.g. no
        summit in contact) are left out. An optional boolean array ``"few"``
        flags points with fewer than :data:`~mcsim.engine.statistics.MIN_CONTACTS`
        expected contacts (no z-score): drawn as crosses, named in the legend.

    Returns
    -------
    matplotlib.figure.Figure
        The figure, h decreasing from left to right; its title names the paper's
        figure where the paper has one.
    """
    from matplotlib.figure import Figure

    _check_quantity(quantity)
    if not curves:
        raise MCSimError("`curves` must contain at least one surface.")
    mc = dict(mc or {})
    unknown = sorted(set(mc) - set(curves))
    if unknown:
        raise MCSimError(f"Monte Carlo results for {unknown} have no analytic curve to match.")
    log = quantity in LOG_QUANTITIES

    fig = Figure(figsize=(7.5, 6.0), layout="constrained")
    ax = fig.add_subplot()
    handles = []
    h_all = []
    for position, (name, c) in enumerate(curves.items()):
        style = surface_style(name, position)
        y = np.asarray(quantity_values(c, quantity), dtype=float)
        if log:
            y = np.where(y > 0, y, np.nan)
        (line,) = ax.plot(c.h, y, lw=1.8, label=surface_label(name, c), **style)
        handles.append(line)
        h_all.append(c.h)
        if name in mc:
            h_all.append(_overlay(ax, mc[name], quantity, style["color"], log))
    if mc:
        handles += mc_legend(any(np.any(r.get("few", False)) for r in mc.values()))

    h_all = np.concatenate([np.ravel(x) for x in h_all])
    # h decreasing, left to right: the surfaces approach; a margin keeps end markers whole
    h_max, h_min = np.nanmax(h_all), np.nanmin(h_all)
    pad = 0.015 * (h_max - h_min) if mc else 0.0
    if h_max == h_min:  # a single separation: show it mid-axis
        pad = 0.5
    ax.set_xlim(h_max + pad, h_min - pad)
    if log:
        ax.set_yscale("log")
    else:
        ax.set_ylim(bottom=0)
    if quantity == "mu":
        limit = _single_summit_mu_limit(curves)
        if limit is not None:  # a broad pale band under the curves: super-smooth runs along it
            handles.append(ax.axhline(limit, color="0.8", lw=5, solid_capstyle="butt", zorder=1,
                                      label=f"single-summit limit $(2/\\sqrt{{3}})\\sqrt{{G/K}}$ = {limit:.3f}"))  # fmt: skip
            ax.set_ylim(0, max(ax.get_ylim()[1], 1.15 * limit))
    ax.set_xlabel(X_LABEL)
    ax.set_ylabel(LABELS[quantity])
    ax.grid(True, which="major", alpha=0.5)
    if log:
        ax.grid(True, which="minor", alpha=0.15)
    # below the axes, where it cannot hide a curve whatever the surfaces
    ax.legend(
        handles=handles,
        fontsize=8,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.11),
        ncols=2,
        frameon=False,
    )
    ax.set_title(_title(quantity, curves), fontsize=10)
    return fig


def _check_quantity(quantity: str) -> None:
    if quantity not in LABELS:
        raise MCSimError(f"`quantity` must be one of {sorted(LABELS)}, got {quantity!r}.")


def _overlay(ax, result: Mapping, quantity: str, colour: str, log: bool) -> np.ndarray:
    """Draw one surface's Monte Carlo means (open markers, ±2 SE bars); return its h."""
    h = np.asarray(result["h"], dtype=float)
    if quantity not in result.get("mean", {}):
        return h
    mean = np.asarray(result["mean"][quantity], dtype=float)
    se = result.get("se", {}).get(quantity)
    if mean.shape != h.shape or (se is not None and np.shape(se) != h.shape):
        raise MCSimError(
            f"Monte Carlo {quantity!r}: `h`, `mean` and `se` must have one shape, "
            f"got {h.shape}, {mean.shape} and {np.shape(se)}."
        )
    errorbars(ax, h, mean, se, log, colour, few=result.get("few"))
    return h


def _single_summit_mu_limit(curves: Mapping[str, AnalyticCurves]) -> float | None:
    """(2/√3)√(G/K), the supremum of T_a/(P_a + F_a) per summit, if all curves share it."""
    if {c.law for c in curves.values()} != {"seed"}:
        return None
    limits = {
        round(2 / math.sqrt(3) * math.sqrt(c.material.G / c.material.K), 12)
        for c in curves.values()
    }
    return limits.pop() if len(limits) == 1 else None


def _title(quantity: str, curves: Mapping[str, AnalyticCurves]) -> str:
    """Paper figure and caption, then the material and law set if shared by all curves."""
    if quantity in PAPER_FIGURES:
        number, caption = PAPER_FIGURES[quantity]
        first = f"Fig. {number} of the paper: {caption}"
        if quantity in LOG_QUANTITIES:
            first += ", divided by $A_n K$"
    else:
        first = f"{LABELS[quantity].split(' $')[0]} vs. mean separation"
    materials = {c.material for c in curves.values()}
    laws = {c.law for c in curves.values()}
    if len(materials) != 1 or len(laws) != 1:
        return first
    m = materials.pop()
    name = f"{m.name}: " if m.name else ""
    return (
        f"{first}\n{name}$K$ = {m.K * 1e-9:.4g} GPa, $G$ = {m.G * 1e-9:.4g} GPa, "
        f"$\\gamma$ = {m.gamma:.3g} J/m$^2$; analytic GW, law set '{laws.pop()}'"
    )
