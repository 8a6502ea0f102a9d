"""Figures of measured surfaces: height histograms against a Gaussian, measured against Gaussian GW curves."""

from __future__ import annotations

import math

import numpy as np

from mcsim.figures.runs import inputs_text, panel_figure
from mcsim.figures.style import COLOURS, MC_LABEL
from mcsim.model.errors import MCSimError

#: Most bars a histogram figure draws; finer histograms are drawn merged (same probability).
MAX_DRAWN_BINS = 1000


def drawn_bins(edges, densities, limit: int = MAX_DRAWN_BINS):
    """Merge runs of adjacent bins so that at most ``limit`` bars remain.

    Each merged bar keeps the probability of its bins (density = Σ density·width / Σ width),
    so the drawing stays a faithful, coarser view of the same distribution.

    Returns
    -------
    (ndarray, ndarray)
        Edges and densities of the bars (unchanged if there are at most ``limit``).
    """
    edges, densities = np.asarray(edges, dtype=float), np.asarray(densities, dtype=float)
    n = densities.size
    if n <= limit:
        return edges, densities
    k = -(-n // limit)  # bins per bar
    starts = np.arange(0, n, k)
    mass = np.add.reduceat(densities * np.diff(edges), starts)
    new_edges = np.append(edges[starts], edges[-1])
    return new_edges, mass / np.diff(new_edges)


def histogram_figure(empirical, gaussian_sigma: float, *, title: str | None = None):
    """A measured height histogram against the Gaussian of the same mean and σ.

    Parameters
    ----------
    empirical : mcsim.topography.empirical.Empirical
        The measured distribution; drawn in physical heights (its ``mean`` and
        ``sigma``), as a probability density per nm.
    gaussian_sigma : float
        Standard deviation of the Gaussian drawn for comparison, m: usually the σ of the
        surface built from the histogram (``mcsim ingest`` prints it as ``surface sigma``),
        written in the legend as the printout writes it (4 digits). The histogram's own
        binned σ (:attr:`Empirical.sigma`) includes the w²/12 of its bins and is not shown.
    title : str, optional
        Figure title; by default the histogram's ``source``.

    Returns
    -------
    matplotlib.figure.Figure
        Linear and logarithmic density panels side by side (the log panel shows the
        upper tail, where contact starts), one legend below them.
    """
    from matplotlib.figure import Figure

    if not (math.isfinite(gaussian_sigma) and gaussian_sigma > 0):
        raise MCSimError(f"`gaussian_sigma` must be positive, got {gaussian_sigma!r} m.")
    edges, densities = drawn_bins(empirical.edges, empirical.densities)
    edges_nm = (empirical.mean + edges * empirical.sigma) * 1e9
    density_nm = densities / (empirical.sigma * 1e9)
    shown = "" if densities.size == empirical.densities.size else f", drawn as {densities.size}"
    z = np.linspace(
        min(edges_nm[0], empirical.mean * 1e9 - 4 * gaussian_sigma * 1e9),
        max(edges_nm[-1], empirical.mean * 1e9 + 4 * gaussian_sigma * 1e9),
        400,
    )
    s_nm = gaussian_sigma * 1e9
    gauss = np.exp(-0.5 * ((z - empirical.mean * 1e9) / s_nm) ** 2) / (
        s_nm * math.sqrt(2 * math.pi)
    )
    fig = Figure(figsize=(10, 4), layout="constrained")
    for ax, log in zip(fig.subplots(1, 2), (False, True)):
        ax.stairs(density_nm, edges_nm, fill=True, color=COLOURS[0], alpha=0.45,
                  label=f"measured ({empirical.densities.size} bins{shown})")  # fmt: skip
        ax.plot(z, gauss, color=COLOURS[4], lw=1.5, label=f"Gaussian, $\\sigma$ = {s_nm:.4g} nm")
        ax.set_xlabel("Height above the mean plane $z$ (nm)")
        ax.set_ylabel("Probability density (1/nm)")
        ax.grid(True, alpha=0.4)
        if log:
            positive = density_nm[density_nm > 0]
            ax.set_yscale("log")
            ax.set_ylim(0.3 * positive.min(), 3 * max(positive.max(), gauss.max()))
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=2, fontsize=8,
               frameon=False)  # below the panels: it covers no bar  # fmt: skip
    fig.suptitle(title or empirical.source, fontsize=10)
    return fig


def comparison_figure(surface_measured, surface_gaussian, material, h, run=None):
    """Analytic GW curves of a measured surface against the Gaussian GW curves.

    Parameters
    ----------
    surface_measured : mcsim.model.params.Surface
        The surface with its measured (e.g. :class:`~mcsim.topography.empirical.Empirical`)
        summit heights.
    surface_gaussian : mcsim.model.params.Surface
        The Gaussian reference, usually the same (σ, R, η).
    material : mcsim.model.params.Material
        The material pair.
    h : array_like
        Separations d/σ for the curves (each surface's own σ and mean summit height).
    run : mcsim.store.results.Run, optional
        A Monte Carlo run of ``surface_measured``: its means ± 2 standard errors
        are drawn over the measured curves.

    Returns
    -------
    matplotlib.figure.Figure
        Contact fraction, P̄, F̄, T̄ (divided by A_n K, Eqs. 3, 5, 7) and μ versus h.
    """
    from mcsim.physics.analytic import analytic_curves

    h = np.sort(np.atleast_1d(np.asarray(h, dtype=float)))[::-1]
    lines = [
        (h, analytic_curves(surface_measured, material, h).columns(), {"color": COLOURS[0], "linestyle": "-"},
         "measured heights (analytic)"),
        (h, analytic_curves(surface_gaussian, material, h).columns(), {"color": COLOURS[4], "linestyle": "--"},
         "Gaussian GW, same ($\\sigma$, $R$, $\\eta$)"),
    ]  # fmt: skip
    info = [
        *inputs_text(surface_measured, material, "seed"),
        "forces divided by $A_n K$ (Eqs. 3, 5, 7)",
        "h = d/$\\sigma$, d from the mean summit height",
    ]
    overlay = [] if run is None else [(run, COLOURS[0], MC_LABEL)]
    return panel_figure(lines, overlay, info)
