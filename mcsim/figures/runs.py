"""Figures of run files: every curve of a run with its Monte Carlo points, approach and retraction branches."""

from __future__ import annotations

import math

import numpy as np

from mcsim.engine.statistics import MIN_CONTACTS
from mcsim.figures.style import (
    COLOURS,
    LABELS,
    LOG_QUANTITIES,
    MC_LABEL,
    X_LABEL,
    errorbars,
    mc_legend,
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
        # a log axis needs a positive value (F and T are 0 everywhere without adhesion)
        log = q in LOG_QUANTITIES and any(np.any(np.asarray(v[q]) > 0) for _, v, *_ in lines)
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
            errorbars(
                ax, run.h, run.summary.mean[q], run.summary.se[q], log, colour, label=label, few=few
            )
        if not any(np.any(np.isfinite(np.asarray(v[q], dtype=float))) for _, v, *_ in lines):
            ax.text(0.5, 0.5, "undefined", ha="center", transform=ax.transAxes)  # μ at w = 0
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
        handles += mc_legend(True)[1:]
    axes[5].axis("off")  # the spare panel holds the inputs and the legend: no curve hidden
    axes[5].text(0, 1, "\n".join(info), va="top", fontsize=9, transform=axes[5].transAxes)
    axes[5].legend(handles=handles, fontsize=8, loc="lower left", frameon=False)
    return fig


def inputs_text(surface, material, law: str) -> list[str]:
    s, m = surface, material
    return [
        f"surface {s.name}: $\\sigma$ = {s.sigma * 1e9:.4g} nm, $R$ = {s.R * 1e6:.4g} µm,",
        f"   $\\eta$ = {s.eta * 1e-12:.4g} µm$^{{-2}}$, heights {s.heights.name}"
        + (
            ""
            if s.radius_by_height is None
            else f", radius by height ($R$ × {min(s.radius_by_height.factors):.3g} … "
            f"{max(s.radius_by_height.factors):.3g})"
        ),
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
    from mcsim.physics.analytic import analytic_curves

    runs = [run] if hasattr(run, "spec") else list(run)
    if any(r.spec.cycle or tuple(r.quantities) != PANELS for r in runs):
        return branch_runs_figure(runs)
    lines, overlays, info = [], [], []
    for i, r in enumerate(runs):
        spec = r.spec
        name = r.path.name if r.path else "(not saved)"
        fine = np.linspace(spec.h.max(), spec.h.min(), 200)
        curves = expected_values(spec, analytic_curves(spec.surface, spec.material, fine, spec.law))
        colour = COLOURS[i % len(COLOURS)]
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


#: Axis labels of the law sets' quantities (the seed's are :data:`LABELS`).
BRANCH_LABELS = {
    "contact_fraction": LABELS["contact_fraction"],
    "load": r"Net load $W/(A_n\,K)$ (compressive > 0)",
    "area": r"Real contact area $A_r/A_n$",
    "friction": r"Friction $\tau A_r/(A_n K)$ (Bowden–Tabor)",
    "mu": r"Friction coefficient $\mu$ = friction/load",
}

#: A positive quantity whose values span more than this ratio is drawn on a log axis.
DECADES_FOR_LOG = 100.0


def _log_worthy(values) -> bool:
    """Whether values (of one panel) are all >= 0 and their positive ones span decades."""
    v = np.concatenate([np.ravel(np.asarray(x, dtype=float)) for x in values])
    v = v[np.isfinite(v)]
    positive = v[v > 0]
    return bool(v.size and np.all(v >= 0) and positive.size
                and positive.max() > DECADES_FOR_LOG * positive.min())  # fmt: skip


def branch_runs_figure(runs):
    """:func:`run_figure` of runs of any law set, approach and (for a cycle) retraction,
    overlaid: one colour per run, a line style per branch (approach solid, retraction
    dashed), analytic curves where :func:`mcsim.gw_curves` gives them. A quantity that
    stays positive and spans decades is drawn on a log axis; the signed load on a linear
    one with its zero marked."""
    from matplotlib.figure import Figure

    from mcsim.engine.statistics import MIN_CONTACTS, expected_values
    from mcsim.store.results import branch_curves

    names = list(runs[0].quantities)
    for r in runs[1:]:
        if list(r.quantities) != names:
            raise MCSimError(f"plot: {r.path or 'a run'} has the quantities {', '.join(r.quantities)}, "
                             f"the first run {', '.join(names)}: overlay runs of one law set")  # fmt: skip
    fig = Figure(figsize=(12, 7), layout="constrained")
    axes = fig.subplots(2, math.ceil((len(names) + 1) / 2)).ravel()
    drawn = {q: [] for q in names}
    h_all = np.concatenate([r.spec.h for r in runs])
    lo, hi = float(h_all.min()), float(h_all.max())
    pad = 0.03 * (hi - lo) if hi > lo else 0.5
    info = []
    for i, run in enumerate(runs):
        spec = run.spec
        fine = np.linspace(spec.h.max(), spec.h.min(), 200)
        curves = branch_curves(spec, fine)
        few = run.summary.expected_contacts < MIN_CONTACTS
        colour = COLOURS[i % len(COLOURS)]
        who = "" if len(runs) == 1 else f"{run.path.name if run.path else f'run {i + 1}'}, "
        M = spec.h.size
        for k, branch in enumerate(spec.branches):
            analytic = expected_values(spec, curves[k])
            rows = slice(k * M, (k + 1) * M)
            style = {"color": colour if len(runs) > 1 else COLOURS[k], "ls": ("-", "--")[k]}
            for ax, q in zip(axes, names):
                mean, se = run.summary.mean[q][rows], run.summary.se[q][rows]
                drawn[q] += [analytic[q], mean]
                ax.plot(fine, analytic[q], lw=1.6, label=f"analytic GW, {who}{branch}", **style)
                errorbars(ax, spec.h, mean, se, False, style["color"],
                           label=f"Monte Carlo mean ± 2 SE, {who}{branch}", few=few[rows])  # fmt: skip
        info += [
            f"run: {run.path.name if run.path else '(not saved)'}",
            *inputs_text(spec.surface, spec.material, spec.law),
            f"patch $A$ = {spec.area * 1e12:.4g} µm$^2$, N ~ {spec.count}, E[N] = {spec.expected_summits:.4g}",
            f"{spec.realizations} realization(s), seed entropy {spec.entropy}",
            *([f"cycle: approach, then retraction from $h = {spec.turn:g}$"] if spec.cycle else []),
        ]
    for ax, q in zip(axes, names):
        ax.set_xlim(hi + pad, lo - pad)
        if _log_worthy(drawn[q]):
            ax.set_yscale("log")
            # around the curves and means: a bar whose lower end nears 0 is cut at the axis
            # (drawn to 0.999 of its mean, it would stretch the axis over decades)
            v = np.concatenate([np.ravel(np.asarray(x, dtype=float)) for x in drawn[q]])
            v = v[np.isfinite(v) & (v > 0)]
            ax.set_ylim(v.min() / 2, v.max() * 2)
        elif q == "load":
            ax.axhline(0.0, color="0.4", lw=0.8, zorder=0.5)
        ax.set_xlabel(X_LABEL, fontsize=8)
        ax.set_ylabel(BRANCH_LABELS.get(q, f"{q} = {runs[0].normalisation(q)}"), fontsize=8)
        ax.grid(True, alpha=0.4)
    for ax in axes[len(names) :]:
        ax.axis("off")
    # the spare panel holds the inputs and the legend: no curve hidden
    axes[-1].text(0, 1, "\n".join(info), va="top", fontsize=8 if len(runs) > 1 else 9,
                  transform=axes[-1].transAxes)  # fmt: skip
    axes[-1].legend(*axes[0].get_legend_handles_labels(), fontsize=8, loc="lower left",
                    frameon=False)  # fmt: skip
    return fig
