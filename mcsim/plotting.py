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
from pathlib import Path

import numpy as np

from .analytic import AnalyticCurves
from .errors import MCSimError
from .presets import PAPER_SURFACES
from .statistics import MIN_CONTACTS

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

#: The paper's figure number and caption for each quantity it plots.
PAPER_FIGURES = {
    "P": (2, "External force vs. mean separation"),
    "F": (3, 'Adhesion term (paper: "adhesive force") vs. mean separation'),
    "total": (4, "Total force vs. mean separation"),
    "T": (5, "Friction force vs. mean separation"),
    "mu": (6, "Coefficient of friction vs. mean separation"),
}

#: Quantities drawn on a logarithmic y axis.
LOG_QUANTITIES = frozenset({"P", "F", "total", "T"})

# Colour-blind-safe colours (Okabe & Ito 2008) and line styles: the paper's surfaces
# first, in its order, so each keeps its colour in every figure; others follow.
_COLOURS = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#D55E00", "#56B4E9", "#000000")
_LINESTYLES = ("-", "--", "-.", ":")


def surface_style(name: str, position: int = 0) -> dict[str, str]:
    """Colour and line style of a surface: fixed for the paper's four surfaces.

    Parameters
    ----------
    name : str
        Surface name.
    position : int
        Position of the surface in its figure, used for surfaces that are not
        among :data:`mcsim.presets.PAPER_SURFACES`.

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
        "color": _COLOURS[index % len(_COLOURS)],
        "linestyle": _LINESTYLES[index % len(_LINESTYLES)],
    }


def surface_label(name: str, curves: AnalyticCurves) -> str:
    """Legend entry: the surface name with σ in nm, R in µm and η in µm⁻²."""
    s = curves.surface
    return (
        f"{name} ($\\sigma$ = {s.sigma * 1e9:.3g} nm, $R$ = {s.R * 1e6:.3g} µm, "
        f"$\\eta$ = {s.eta * 1e-12:.3g} µm$^{{-2}}$)"
    )


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
        flags points with fewer than :data:`~mcsim.statistics.MIN_CONTACTS`
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
        handles += _mc_legend(any(np.any(r.get("few", False)) for r in mc.values()))

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
        if limit is not None:  # beneath the curves, named in the legend: it hides nothing
            handles.append(ax.axhline(limit, color="0.6", lw=0.8, linestyle=(0, (6, 3)), zorder=0.5,
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


def save(fig, path, *, overwrite: bool = False, inputs=()) -> Path:
    """Write ``fig`` as a PNG at 150 dpi, with the mcsim version in its metadata.

    Written atomically under the rule of :mod:`mcsim.outputs`: an existing file is
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
    from ._version import __version__
    from .outputs import write_atomic

    def write(tmp: Path) -> None:
        fig.savefig(tmp, dpi=150, format="png", metadata={"Software": f"mcsim {__version__}"})

    return write_atomic(path, write, inputs=inputs, overwrite=overwrite)


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
    _errorbars(ax, h, mean, se, log, colour, few=result.get("few"))
    return h


#: Legend text of Monte Carlo points, and of those with too few contacts for a z-score.
MC_LABEL = "Monte Carlo mean ± 2 SE"
FEW_LABEL = f"Monte Carlo, < {MIN_CONTACTS} contacts expected: no z-score"


def _mc_legend(few: bool) -> list:
    from matplotlib.lines import Line2D

    style = {"color": "0.3", "linestyle": "none", "markerfacecolor": "none"}
    handles = [Line2D([], [], marker="o", label=MC_LABEL, **style)]
    if few:
        handles.append(Line2D([], [], marker="x", label=FEW_LABEL, **style))
    return handles


def _errorbars(ax, h, mean, se, log: bool, colour: str, label: str | None = None, few=None) -> None:
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


#: Quantities of the multi-panel figures, in panel order.
PANELS = ("contact_fraction", "P", "F", "T", "mu")


def _panel_figure(lines, runs, info: list[str]):
    """Five panels (N_c/N, P̄, F̄, T̄, μ versus h, h decreasing to the right) with the
    curves ``lines`` = [(h, {quantity: values}, style, label)], the Monte Carlo means
    of ``runs`` = [(run, colour, label)] and a panel of ``info`` text.

    A curve at a single h is drawn as a marker (a line would be invisible); μ and
    N_c/N axes start at zero, so that a small difference looks small."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 7), layout="constrained")
    axes = fig.subplots(2, 3).ravel()
    h_all = np.concatenate([h for h, *_ in lines] + [run.h for run, *_ in runs])
    lo, hi = float(h_all.min()), float(h_all.max())
    pad = 0.03 * (hi - lo) if hi > lo else 0.5
    few_any = False
    for ax, q in zip(axes, PANELS):
        log = q in LOG_QUANTITIES
        for h, values, style, label in lines:
            y = np.asarray(values[q], dtype=float)
            y = np.where(y > 0, y, np.nan) if log else y
            if np.unique(h).size == 1:
                ax.plot(h[:1], y[:1], marker="_", markersize=22, markeredgewidth=2.2, linestyle="none",
                        label=label, **style)  # fmt: skip
            else:
                ax.plot(h, y, label=label, **{"lw": 1.6, **style})
        for run, colour, label in runs:
            few = run.summary.expected_contacts < MIN_CONTACTS
            few_any |= bool(np.any(few))
            _errorbars(
                ax, run.h, run.summary.mean[q], run.summary.se[q], log, colour, label=label, few=few
            )
        ax.set_xlim(hi + pad, lo - pad)
        ax.set_yscale("log" if log else "linear")
        if not log:  # from zero, with headroom above the highest point or bar
            top = ax.dataLim.y1
            ax.set_ylim(0, 1.08 * top if np.isfinite(top) and top > 0 else 1.0)
        ax.set_xlabel(X_LABEL, fontsize=8)
        ax.set_ylabel(LABELS[q], fontsize=8)
        ax.grid(True, alpha=0.4)
    handles, _ = axes[0].get_legend_handles_labels()
    if few_any:
        handles += _mc_legend(True)[1:]
    axes[5].axis("off")  # the spare panel holds the inputs and the legend: no curve hidden
    axes[5].text(0, 1, "\n".join(info), va="top", fontsize=9, transform=axes[5].transAxes)
    axes[5].legend(handles=handles, fontsize=8, loc="lower left", frameon=False)
    return fig


def _inputs_text(surface, material, law: str) -> list[str]:
    s, m = surface, material
    return [
        f"surface {s.name}: $\\sigma$ = {s.sigma * 1e9:.4g} nm, $R$ = {s.R * 1e6:.4g} µm,",
        f"   $\\eta$ = {s.eta * 1e-12:.4g} µm$^{{-2}}$, heights {s.heights.name}",
        f"material {m.name}: $K$ = {m.K * 1e-9:.4g} GPa, $G$ = {m.G * 1e-9:.4g} GPa,",
        f"   $\\gamma$ = {m.gamma:.3g} J/m$^2$; law set '{law}'",
    ]


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


def run_figure(run):
    """Monte Carlo means (±2 SE) of a run over the analytic GW curves, one panel per quantity.

    Parameters
    ----------
    run : mcsim.results.Run or sequence of Run
        A run, fresh or read from a file; several are overlaid, each in its own
        colour with its own analytic curve.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from .analytic import gw_curves
    from .statistics import expected_values

    runs = [run] if hasattr(run, "spec") else list(run)
    branched = [r for r in runs if r.spec.cycle or tuple(r.quantities) != PANELS]
    if branched and len(runs) == 1:
        return _branch_run_figure(run if hasattr(run, "spec") else runs[0])
    if branched:
        raise MCSimError(
            "overlaying runs needs the seed law set without --cycle; "
            f"plot {branched[0].path or 'that run'} on its own"
        )
    lines, overlays, info = [], [], []
    for i, r in enumerate(runs):
        spec = r.spec
        name = r.path.name if r.path else "(not saved)"
        fine = np.linspace(spec.h.max(), spec.h.min(), 200)
        curves = expected_values(spec, gw_curves(spec.surface, spec.material, fine, spec.law))
        colour = _COLOURS[i % len(_COLOURS)]
        if len(runs) == 1:
            lines.append((fine, curves, {"color": "0.2"}, "analytic GW"))
            overlays.append((r, colour, MC_LABEL))
            info += [
                f"run: {name}",
                *_inputs_text(spec.surface, spec.material, spec.law),
                f"patch $A_n$ = {spec.area * 1e12:.4g} µm$^2$, N ~ {spec.count}, E[N] = {spec.expected_summits:.4g}",
                f"{spec.realizations} realization(s), seed entropy {spec.entropy}",
            ]
        else:
            lines.append((fine, curves, {"color": colour, "lw": 1.0}, f"{name}: analytic GW"))
            overlays.append((r, colour, f"{name}: Monte Carlo ± 2 SE"))
            info += [
                f"{name}: {spec.surface.name or '(file)'} on {spec.material.name or '(file)'}, "
                f"$A_n$ = {spec.area * 1e12:.4g} µm$^2$, {spec.realizations} real., law '{spec.law}'"
            ]
    info.append("forces divided by $A_n K$ (Eqs. 3, 5, 7)")
    return _panel_figure(lines, overlays, info)


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


def _branch_run_figure(run):
    """:func:`run_figure` of a run of any law set, approach and (for a cycle) retraction:
    one panel per quantity on linear axes (the load is signed), analytic curves where
    :func:`mcsim.gw_curves` gives them."""
    from matplotlib.figure import Figure

    from .results import analytic_curves
    from .statistics import MIN_CONTACTS, expected_values

    spec = run.spec
    fine = np.linspace(spec.h.max(), spec.h.min(), 200)
    curves = analytic_curves(spec, fine)
    few = run.summary.expected_contacts < MIN_CONTACTS
    names = run.quantities
    fig = Figure(figsize=(12, 7), layout="constrained")
    axes = fig.subplots(2, math.ceil((len(names) + 1) / 2)).ravel()
    pad = 0.03 * (fine[0] - fine[-1]) if fine[0] > fine[-1] else 0.5
    M = spec.h.size
    for k, branch in enumerate(spec.branches):
        colour = _COLOURS[k]
        analytic = expected_values(spec, curves[k])
        rows = slice(k * M, (k + 1) * M)
        for ax, q in zip(axes, names):
            ax.plot(fine, analytic[q], lw=1.6, color=colour, label=f"analytic GW, {branch}")
            _errorbars(ax, spec.h, run.summary.mean[q][rows], run.summary.se[q][rows], False,
                       colour, label=f"Monte Carlo mean ± 2 SE, {branch}", few=few[rows])  # fmt: skip
    for ax, q in zip(axes, names):
        ax.set_xlim(fine[0] + pad, fine[-1] - pad)
        ax.set_xlabel(X_LABEL, fontsize=8)
        ax.set_ylabel(f"{q} = {run.normalisation(q)}", fontsize=8)
        ax.grid(True, alpha=0.4)
    axes[0].legend(fontsize=7)
    for ax in axes[len(names) :]:
        ax.axis("off")
    info = [
        f"run: {run.path.name if run.path else '(not saved)'}",
        *_inputs_text(spec.surface, spec.material, spec.law),
        f"patch $A$ = {spec.area * 1e12:.4g} µm$^2$, N ~ {spec.count}, E[N] = {spec.expected_summits:.4g}",
        f"{spec.realizations} realization(s), seed entropy {spec.entropy}",
        *([f"cycle: approach, then retraction from h = {spec.turn:g}"] if spec.cycle else []),
    ]
    axes[-1].text(0, 1, "\n".join(info), va="top", fontsize=9, transform=axes[-1].transAxes)
    return fig


def histogram_figure(empirical, gaussian_sigma: float, *, title: str | None = None):
    """A measured height histogram against the Gaussian of the same mean and σ.

    Parameters
    ----------
    empirical : mcsim.empirical.Empirical
        The measured distribution; drawn in physical heights (its ``mean`` and
        ``sigma``), as a probability density per nm.
    gaussian_sigma : float
        Standard deviation of the Gaussian drawn for comparison, m (usually
        ``empirical.sigma``).
    title : str, optional
        Figure title; by default the histogram's ``source``.

    Returns
    -------
    matplotlib.figure.Figure
        Linear and logarithmic density panels side by side (the log panel shows the
        upper tail, where contact starts).
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
        ax.stairs(density_nm, edges_nm, fill=True, color=_COLOURS[0], alpha=0.45,
                  label=f"measured ({empirical.densities.size} bins{shown}, $\\sigma$ = "
                  f"{empirical.sigma * 1e9:.3g} nm)")  # fmt: skip
        ax.plot(z, gauss, color=_COLOURS[4], lw=1.5, label=f"Gaussian, $\\sigma$ = {s_nm:.3g} nm")
        ax.set_xlabel("Height above the mean plane $z$ (nm)")
        ax.set_ylabel("Probability density (1/nm)")
        ax.grid(True, alpha=0.4)
        if log:
            positive = density_nm[density_nm > 0]
            ax.set_yscale("log")
            ax.set_ylim(0.3 * positive.min(), 3 * max(positive.max(), gauss.max()))
        else:
            ax.legend(fontsize=8)
    fig.suptitle(title or empirical.source, fontsize=10)
    return fig


def comparison_figure(surface_measured, surface_gaussian, material, h, run=None):
    """Analytic GW curves of a measured surface against the Gaussian GW curves.

    Parameters
    ----------
    surface_measured : mcsim.params.Surface
        The surface with its measured (e.g. :class:`~mcsim.empirical.Empirical`)
        summit heights.
    surface_gaussian : mcsim.params.Surface
        The Gaussian reference, usually the same (σ, R, η).
    material : mcsim.params.Material
        The material pair.
    h : array_like
        Separations d/σ for the curves (each surface's own σ and mean summit height).
    run : mcsim.results.Run, optional
        A Monte Carlo run of ``surface_measured``: its means ± 2 standard errors
        are drawn over the measured curves.

    Returns
    -------
    matplotlib.figure.Figure
        Contact fraction, P̄, F̄, T̄ (divided by A_n K, Eqs. 3, 5, 7) and μ versus h.
    """
    from .analytic import gw_curves

    h = np.sort(np.atleast_1d(np.asarray(h, dtype=float)))[::-1]
    lines = [
        (h, gw_curves(surface_measured, material, h).columns(), {"color": _COLOURS[0], "linestyle": "-"},
         "measured heights (analytic)"),
        (h, gw_curves(surface_gaussian, material, h).columns(), {"color": _COLOURS[4], "linestyle": "--"},
         "Gaussian GW, same ($\\sigma$, $R$, $\\eta$)"),
    ]  # fmt: skip
    info = [
        *_inputs_text(surface_measured, material, "seed"),
        "forces divided by $A_n K$ (Eqs. 3, 5, 7)",
        "h = d/$\\sigma$, d from the mean summit height",
    ]
    overlay = [] if run is None else [(run, _COLOURS[0], MC_LABEL)]
    return _panel_figure(lines, overlay, info)


# --- contact law sets: approach/retraction cycle and the Fuller-Tabor plot -------------------


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
        From :func:`mcsim.adhesion.adhesion_summary` (computed if not given); its
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
    from matplotlib.ticker import FuncFormatter

    from .adhesion import RegimeWarning, _top, adhesion_summary
    from .analytic import gw_curves
    from .laws import get_law_set

    laws = get_law_set(law)
    if summary is None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RegimeWarning)
            summary = adhesion_summary(surface, material, laws)
    turn, K, sigma = summary.turn, material.K, surface.sigma
    h = np.linspace(turn, _top(surface, laws, material), points)
    approach = gw_curves(surface, material, h, laws).load
    retract = gw_curves(surface, material, h, laws, branch="retract", turn=turn).load
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
            label=f"retraction from $h_{{turn}}$ = {turn:.3g}")  # fmt: skip
    ax.fill_between(h, np.minimum(retract, 0) * mpa, 0, color="#D55E00", alpha=0.15, lw=0,
                    label=f"work of separation {summary.work_of_separation * 1e3:.3g} mJ/m$^2$")  # fmt: skip
    ax.axvline(turn, color="0.45", lw=0.8, ls=":")
    if summary.pull_off > 0:
        p = summary.pull_off_pressure / 1e6
        ax.plot(summary.h_pull_off, -p, "o", color="k", ms=7, zorder=5,
                label=f"pull-off {p:.3g} MPa at h = {summary.h_pull_off:.3g}")  # fmt: skip
        ax.annotate("pull-off", (summary.h_pull_off, -p), xytext=(8, -14),
                    textcoords="offset points", fontsize=9)  # fmt: skip
    ax.set_xlim(h.max(), h.min())
    ax.set_xlabel(X_LABEL)
    ax.set_ylabel(r"Nominal pressure $p = P/A_n$ (MPa), > 0 compressive")
    top = ax.secondary_xaxis(
        "top", functions=(lambda x: x * sigma * 1e9, lambda d: d / (sigma * 1e9))
    )
    top.set_xlabel("Mean separation d (nm)")
    right = ax.secondary_yaxis("right", functions=(lambda y: y / mpa, lambda v: v * mpa))
    right.set_ylabel(r"Load $P/(A_n K)$")
    right.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.2g}"))
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="upper left")
    noise = abs(summary.hysteresis) < 1e-9 * max(summary.work_of_separation, 1e-300)
    hysteresis = "0 (none)" if noise else f"{summary.hysteresis * 1e3:.3g} mJ/m$^2$"
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
        Adhesion parameter θ = E* σ^{3/2}/(R^{1/2} w) (:func:`mcsim.adhesion.adhesion_parameter`).
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
                color=_COLOURS[position % len(_COLOURS)],
                linestyle=_LINESTYLES[position % len(_LINESTYLES)])  # fmt: skip
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


def light_load_ratio(surface, h) -> np.ndarray:
    """GW light-load ratio κ(h) = (A_r/A_n)/(p/E*) of elastic (Hertz) summits.

    With A_r/A_n = π η R σ F_1(h) and p = (4/3) E* η R^½ σ^{3/2} F_{3/2}(h)
    (Greenwood & Williamson 1966, Eqs. 9-10; F_n(h) = ∫_h^∞ (s − h)^n φ(s) ds),
    κ = (3π/4) √(R/σ) F_1(h)/F_{3/2}(h). For Gaussian heights F_1/F_{3/2} →
    √h/Γ(5/2) as h → ∞, so κ grows only as √h: A_r is nearly proportional to the
    load at light load, the GW result. The integrals use the surface's own heights.
    """
    h = np.atleast_1d(np.asarray(h, dtype=float))
    _, integral = surface.heights.gw_integrals(lambda d: np.stack([d, d**1.5]), h)
    return 0.75 * math.pi * math.sqrt(surface.R / surface.sigma) * integral[0] / integral[1]


def hertz_area_fraction(surface, h) -> np.ndarray:
    """GW real contact area of Hertz summits, A_r/A_n = π η R σ F_1(h) (GW 1966, Eq. 9)."""
    h = np.atleast_1d(np.asarray(h, dtype=float))
    scale, integral = surface.heights.gw_integrals(lambda d: d[None], h)
    return math.pi * surface.eta * surface.R * surface.sigma * scale * integral[0]


def load_control_figure(result):
    """A_r/A_n versus p/E* (log–log) and friction versus load, with the GW light-load line.

    Parameters
    ----------
    result : LoadControl
        From :func:`mcsim.loadcontrol.load_control`.

    Returns
    -------
    matplotlib.figure.Figure
        Left: real contact area A_r/A_n against p/E* (seed: the Hertz area of its
        summits, :func:`hertz_area_fraction`, since the seed's balanced load P is the
        Hertz load), with the GW light-load line A_r/A_n = κ(h₀) p/E*
        (:func:`light_load_ratio`, Hertz summits without adhesion) at the lightest
        load's separation h₀ dashed. Right: friction (seed: T, Eq. 7; other sets: τA_r)
        against the applied force per nominal area, both in MPa, with the light-load
        line τ κ p/E* for the contact law sets; points reached through a jump are ringed.
    """
    from matplotlib.figure import Figure

    curves = result.curves
    material = curves.material
    ok = result.equilibrium & (result.pressure > 0)
    x = result.pressure[ok] / material.E_star
    seed = curves.law == "seed"
    y = hertz_area_fraction(curves.surface, result.h[ok]) if seed else curves.values["area"][ok]
    kappa = (
        float(light_load_ratio(curves.surface, [result.h[ok][np.argmin(x)]])[0]) if x.size else 0
    )
    light = f"GW light load, Hertz without adhesion: A_r/A_n = {kappa:.3g} p/E*"
    fig = Figure(figsize=(10, 4.2), layout="constrained")
    left, right = fig.subplots(1, 2)
    left.loglog(x, y, "o-", ms=3, label=curves.law + (" (Hertz area, GW Eq. 9)" if seed else ""))
    if x.size:
        left.loglog(x, kappa * x, "k--", lw=1, label=light)
    left.set_xlabel("nominal pressure over contact modulus p/E*")
    left.set_ylabel("real contact area fraction A_r/A_n")
    left.legend(fontsize="small")
    name = "T" if seed else "friction"
    if name in curves.values:
        p_mpa = result.pressure[ok] / 1e6
        friction = curves.values[name][ok] * material.K / 1e6
        right.plot(p_mpa, friction, "o-", ms=3, label=curves.law)
        if not seed and x.size:
            right.plot(p_mpa, material.tau * kappa * x / 1e6, "k--", lw=1,
                       label=f"GW light load: tau A_r = {material.tau * kappa / material.E_star:.3g} p")  # fmt: skip
        jumped = result.jump[ok]
        right.plot(p_mpa[jumped], friction[jumped], "o", mfc="none",
                   ms=8, color="k", label="reached through a jump")  # fmt: skip
        right.legend(fontsize="small")
    else:
        right.text(0.5, 0.5, "no friction (give tau)", ha="center", transform=right.transAxes)
    right.set_xlabel("applied load per nominal area p (MPa)")
    right.set_ylabel("friction force per nominal area (MPa)")
    fig.suptitle(f"{curves.surface.name or 'surface'}, law set {curves.law}: load control")
    return fig


def load_run_figure(run):
    """Per-patch Monte Carlo points versus load over the analytic approach curves.

    Each patch (realization) at each separation of an approach run is one point
    (applied force per nominal area p = load·K, area or friction): the patches scatter
    along both axes. The ensemble means carry ±2 SE bars in both directions. The run's
    separations are typically those that balance given pressures (``mcsim simulate
    --pressure``, :func:`mcsim.loadcontrol.load_control`).

    Parameters
    ----------
    run : mcsim.results.Run
        An approach run (no ``--cycle``).

    Returns
    -------
    matplotlib.figure.Figure
        Left: A_r/A_n (seed: N_c/N) against p/E*, log–log, with the GW light-load
        line A_r/A_n = κ(h₀) p/E* at the largest h₀ (:func:`light_load_ratio`); right:
        friction per nominal area against p, MPa (seed: T, Eq. 7). Points with p ≤ 0
        (tensile patches) are left off the log–log panel, and counted in its legend.
    """
    from matplotlib.figure import Figure

    from .analytic import gw_curves

    spec = run.spec
    if spec.cycle:
        raise MCSimError(f"{run.path or 'run'}: plotting versus load needs an approach run "
                         "(no --cycle)")  # fmt: skip
    seed = spec.law == "seed"
    load_q, area_q, friction_q = ("P", "contact_fraction", "T") if seed else ("load", "area", "friction")  # fmt: skip
    if load_q not in run.quantities:
        raise MCSimError(f"{run.path or 'run'}: law set {spec.law!r} has no load to plot against")
    material = spec.material
    fine = np.linspace(spec.h.max(), spec.h.min(), 400)
    curves = gw_curves(spec.surface, material, fine, spec.law).values
    mean, se = run.summary.mean, run.summary.se
    fig = Figure(figsize=(10, 4.4), layout="constrained")
    left, right = fig.subplots(1, 2)
    panels = [(left, area_q, material.E_star, 1.0, "nominal pressure over contact modulus p/E*",
               "fraction of summits in contact N_c/N" if seed else "real contact area fraction A_r/A_n")]  # fmt: skip
    if friction_q in run.quantities:
        panels.append((right, friction_q, 1e6, material.K / 1e6,
                       "applied load per nominal area p (MPa)", "friction force per nominal area (MPa)"))  # fmt: skip
    else:
        right.text(0.5, 0.5, "no friction (give tau)", ha="center", transform=right.transAxes)
    for ax, q, x_unit, y_scale, x_label, y_label in panels:
        log = ax is left
        x = run.realizations[load_q] * material.K / x_unit
        y = run.realizations[q] * y_scale
        xa, ya = curves[load_q] * material.K / x_unit, curves[q] * y_scale
        xm, ym = mean[load_q] * material.K / x_unit, mean[q] * y_scale
        xe, ye = 2 * se[load_q] * material.K / x_unit, 2 * se[q] * y_scale
        shown = (x > 0) & (y > 0) if log else np.isfinite(x) & np.isfinite(y)
        hidden = int(np.count_nonzero(~shown))
        label = f"{spec.realizations} patches × {spec.h.size} loads" + (
            f" ({hidden} with p ≤ 0 not shown)" if hidden else "")  # fmt: skip
        ax.plot(x[shown], y[shown], ".", ms=3, color="C0", alpha=0.35, label=label)
        keep = (xa > 0) & (ya > 0) if log else np.isfinite(ya)
        ax.plot(xa[keep], ya[keep], "-", color="0.2", lw=1.2, label="analytic GW (approach)")
        ok = (xm > 0) & (ym > 0) if log else np.isfinite(xm) & np.isfinite(ym)
        ax.errorbar(xm[ok], ym[ok], xerr=xe[ok], yerr=ye[ok], fmt="o", ms=4, color="C3",
                    capsize=2, label="Monte Carlo mean ± 2 SE (both axes)")  # fmt: skip
        if log:
            ax.set_xscale("log")
            ax.set_yscale("log")
            if not seed and np.any(ok):
                kappa = float(light_load_ratio(spec.surface, [spec.h.max()])[0])
                grid = np.geomspace(xa[keep].min(), xa[keep].max(), 50)
                ax.plot(grid, kappa * grid, "k--", lw=1,
                        label=f"GW light load, Hertz without adhesion: A_r/A_n = {kappa:.3g} p/E*")  # fmt: skip
        ax.set_xlabel(x_label)
        ax.set_ylabel(y_label)
        ax.legend(fontsize="small")
    name = run.path.name if run.path else "(not saved)"
    fig.suptitle(f"{name}: {spec.surface.name or 'surface'}, law set {spec.law}, patch "
                 f"A_n = {spec.area * 1e12:.4g} µm², {spec.realizations} realizations")  # fmt: skip
    return fig
