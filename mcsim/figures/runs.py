"""Figures of run files: every curve of a run with its Monte Carlo points, approach and retraction branches."""

from __future__ import annotations

import math

import numpy as np

from mcsim.engine.statistics import MIN_CONTACTS
from mcsim.figures.style import (
    _COLOURS,
    LABELS,
    LOG_QUANTITIES,
    MC_LABEL,
    X_LABEL,
    _errorbars,
    _mc_legend,
)
from mcsim.model.errors import MCSimError

#: Quantities of the multi-panel figures, in panel order.
PANELS = ("contact_fraction", "P", "F", "T", "mu")


def panel_figure(lines, runs, info: list[str]):
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


def inputs_text(surface, material, law: str) -> list[str]:
    s, m = surface, material
    return [
        f"surface {s.name}: $\\sigma$ = {s.sigma * 1e9:.4g} nm, $R$ = {s.R * 1e6:.4g} µm,",
        f"   $\\eta$ = {s.eta * 1e-12:.4g} µm$^{{-2}}$, heights {s.heights.name}",
        f"material {m.name}: $K$ = {m.K * 1e-9:.4g} GPa, $G$ = {m.G * 1e-9:.4g} GPa,",
        f"   $\\gamma$ = {m.gamma:.3g} J/m$^2$; law set '{law}'",
    ]


def run_figure(run):
    """Monte Carlo means (±2 SE) of a run over the analytic GW curves, one panel per quantity.

    Parameters
    ----------
    run : mcsim.store.results.Run or sequence of Run
        A run, fresh or read from a file; several are overlaid, each in its own
        colour with its own analytic curve.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from mcsim.engine.statistics import expected_values
    from mcsim.physics.analytic import gw_curves

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
                *inputs_text(spec.surface, spec.material, spec.law),
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
    return panel_figure(lines, overlays, info)


def _branch_run_figure(run):
    """:func:`run_figure` of a run of any law set, approach and (for a cycle) retraction:
    one panel per quantity on linear axes (the load is signed), analytic curves where
    :func:`mcsim.gw_curves` gives them."""
    from matplotlib.figure import Figure

    from mcsim.engine.statistics import MIN_CONTACTS, expected_values
    from mcsim.store.results import analytic_curves

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
        *inputs_text(spec.surface, spec.material, spec.law),
        f"patch $A$ = {spec.area * 1e12:.4g} µm$^2$, N ~ {spec.count}, E[N] = {spec.expected_summits:.4g}",
        f"{spec.realizations} realization(s), seed entropy {spec.entropy}",
        *([f"cycle: approach, then retraction from h = {spec.turn:g}"] if spec.cycle else []),
    ]
    axes[-1].text(0, 1, "\n".join(info), va="top", fontsize=9, transform=axes[-1].transAxes)
    return fig
