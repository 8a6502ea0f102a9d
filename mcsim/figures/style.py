"""The look shared by every figure: labels, colours and line styles per surface, Monte Carlo error bars, saving.

Conventions a tribologist expects from the paper's figures:

* x axis: the dimensionless mean separation h = d/σ runs from large to small, left
  to right (4 → −1 in the paper), so reading a figure left to right follows the
  surfaces being pressed together (loading);
* y axis: logarithmic for the forces P̄, F̄, P̄ + F̄ and T̄ (they grow by six
  decades over 4 ≥ h ≥ −1), linear for μ and for the contact fraction;
* one colour and line style per surface, the same in every figure.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mcsim.engine.statistics import MIN_CONTACTS
from mcsim.model.presets import PAPER_SURFACES
from mcsim.physics.analytic import AnalyticCurves

#: Axis label of each plottable quantity; forces are divided by A_n K (Eqs. 3, 5, 7).
LABELS = {
    "P": r"External force $\bar P = P/(A_n K)$",
    "F": r"Adhesion term $\bar F = F/(A_n K)$ (Eq. 5)",
    "total": r"Total force $\bar P + \bar F = (P + F)/(A_n K)$",
    "T": r"Friction force $\bar T = T/(A_n K)$",
    "mu": r"Friction coefficient $\mu = \bar T/(\bar P + \bar F)$",
    "contact_fraction": r"Contact fraction $N_c/N$",
}


#: Label of the x axis of every figure.
X_LABEL = r"Dimensionless mean separation $h = d/\sigma$"


#: Quantities drawn on a logarithmic y axis.
LOG_QUANTITIES = frozenset({"P", "F", "total", "T"})


#: Colour-blind-safe colours (Okabe & Ito 2008): the paper's surfaces
#: first, in its order, so each keeps its colour in every figure; others follow.
COLOURS = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#D55E00", "#56B4E9", "#000000")

#: Line styles, cycled with :data:`COLOURS` (:func:`surface_style`).
LINESTYLES = ("-", "--", "-.", ":")


def surface_style(name: str, position: int = 0) -> dict[str, str]:
    """Colour and line style of a surface: fixed for the paper's four surfaces.

    Parameters
    ----------
    name : str
        Surface name.
    position : int
        Position of the surface in its figure, used for surfaces that are not
        among :data:`mcsim.model.presets.PAPER_SURFACES`.

    Returns
    -------
    dict
        ``color`` and ``linestyle`` keyword arguments for matplotlib.
    """
    if name in PAPER_SURFACES:
        index = PAPER_SURFACES.index(name)
    else:
        index = len(PAPER_SURFACES) + position
    return {
        "color": COLOURS[index % len(COLOURS)],
        "linestyle": LINESTYLES[index % len(LINESTYLES)],
    }


def surface_label(name: str, curves: AnalyticCurves) -> str:
    """Legend entry: the surface name with σ in nm, R in µm and η in µm⁻²."""
    s = curves.surface
    return (
        f"{name} ($\\sigma$ = {s.sigma * 1e9:.3g} nm, $R$ = {s.R * 1e6:.3g} µm, "
        f"$\\eta$ = {s.eta * 1e-12:.3g} µm$^{{-2}}$)"
    )


def number(value: float, spec: str = ".3g") -> str:
    """``value`` formatted by ``spec`` with a true minus sign (U+2212), as tick labels have it
    (``axes.unicode_minus``): for numbers written into a text outside mathtext."""
    return format(value, spec).replace("-", "\u2212")


def save(fig, path, *, overwrite: bool = False, inputs=()) -> Path:
    """Write ``fig`` as a PNG at 150 dpi, with the mcsim version in its metadata.

    Written atomically under the rule of :mod:`mcsim.store.outputs`: an existing file is
    replaced only with ``overwrite``, an input never, a non-regular file never.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : str or Path
        Output file; its folder must exist.
    overwrite : bool
        Replace an existing regular file.
    inputs : iterable of path-like
        Files the figure was made from: never written.

    Returns
    -------
    Path
        The path written.
    """
    from mcsim._version import __version__
    from mcsim.store.outputs import write_atomic

    def write(tmp: Path) -> None:
        fig.savefig(tmp, dpi=150, format="png", metadata={"Software": f"mcsim {__version__}"})

    return write_atomic(path, write, inputs=inputs, overwrite=overwrite)


#: Legend text of Monte Carlo points, and of those with too few contacts for a z-score.
MC_LABEL = "Monte Carlo mean ± 2 SE"


FEW_LABEL = f"Monte Carlo, < {MIN_CONTACTS} contacts expected: no z-score"


def mc_legend(few: bool) -> list:
    """Legend handles of the Monte Carlo markers of :func:`errorbars`: open circles, and
    with ``few`` the crosses of points with too few expected contacts for a z-score."""
    from matplotlib.lines import Line2D

    style = {"color": "0.3", "linestyle": "none", "markerfacecolor": "none"}
    handles = [Line2D([], [], marker="o", label=MC_LABEL, **style)]
    if few:
        handles.append(Line2D([], [], marker="x", label=FEW_LABEL, **style))
    return handles


def errorbars(ax, h, mean, se, log: bool, colour: str, label: str | None = None, few=None) -> None:
    """Monte Carlo means as open markers with ±2 SE bars; undefined (and, on a log
    axis, zero) means are left out, and bars are clipped above zero on a log axis.
    Points flagged in ``few`` (too few expected contacts for a normal z-score) are
    drawn as crosses with faint bars."""
    h, mean = np.asarray(h, dtype=float), np.asarray(mean, dtype=float)
    few = (
        np.zeros(h.shape, bool) if few is None else np.broadcast_to(np.asarray(few, bool), h.shape)
    )
    for group, marker, alpha in ((~few, "o", 1.0), (few, "x", 0.5)):
        keep = group & np.isfinite(mean) & (mean > 0 if log else True)
        if not np.any(keep):
            continue
        yerr = None if se is None else 2 * np.asarray(se, dtype=float)[keep]
        if yerr is not None and log:
            yerr = np.vstack([np.minimum(yerr, 0.999 * mean[keep]), yerr])
        bars = ax.errorbar(h[keep], mean[keep], yerr=yerr, color=colour, marker=marker, markersize=4,
                           markerfacecolor="none", linestyle="none", capsize=2, elinewidth=0.9,
                           label=label if marker == "o" else None)  # fmt: skip
        for artist in bars.lines[2]:
            artist.set_alpha(alpha)
