"""Figures versus load: contact area and friction against nominal pressure, analytic and Monte Carlo."""

from __future__ import annotations

import math

import numpy as np

from mcsim.model.errors import MCSimError
from mcsim.physics.analytic import hertz_area_fraction


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


def load_control_figure(result):
    """A_r/A_n versus p/E* (log–log) and friction versus load, with the GW light-load line.

    Parameters
    ----------
    result : LoadControl
        From :func:`mcsim.physics.loadcontrol.load_control`.

    Returns
    -------
    matplotlib.figure.Figure
        Left: real contact area A_r/A_n against p/E* (seed: the Hertz area of its
        summits, :func:`hertz_area_fraction`, since the seed's balanced load P is the
        Hertz load), with the GW light-load line A_r/A_n = κ(h₀) p/E*
        (:func:`light_load_ratio`, Hertz summits without adhesion) at the lightest
        load's separation h₀ dashed. Right: friction (seed: T, Eq. 7; other sets: τA_r)
        against the applied force per nominal area, both in MPa, with the light-load
        line τ κ p/E* for the contact law sets; points reached through a jump are ringed
        (and named in the legend only if there are any).
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
    light = f"GW light load, Hertz without adhesion: $A_r/A_n$ = {kappa:.3g} $p/E^*$"
    fig = Figure(figsize=(10, 4.2), layout="constrained")
    left, right = fig.subplots(1, 2)
    left.loglog(x, y, "o-", ms=3, label=curves.law + (" (Hertz area, GW Eq. 9)" if seed else ""))
    if x.size:
        left.loglog(x, kappa * x, "k--", lw=1, label=light)
    left.set_xlabel(P_OVER_E)
    left.set_ylabel(AREA_LABEL)
    _limits_to(left, y)  # the light-load line runs on below the curve: cut at the axis
    left.legend(fontsize="small")
    name = "T" if seed else "friction"
    if name in curves.values:
        p_mpa = result.pressure[ok] / 1e6
        friction = curves.values[name][ok] * material.K / 1e6
        right.plot(p_mpa, friction, "o-", ms=3, label=curves.law)
        if not seed and x.size:
            right.plot(p_mpa, material.tau * kappa * x / 1e6, "k--", lw=1,
                       label=f"GW light load: $\\tau A_r/A_n$ = {material.tau * kappa / material.E_star:.3g} $p$")  # fmt: skip
        jumped = result.jump[ok]
        if jumped.any():  # a legend entry only for what is drawn
            right.plot(p_mpa[jumped], friction[jumped], "o", mfc="none",
                       ms=8, color="k", label="reached through a jump")  # fmt: skip
        right.legend(fontsize="small")
    else:
        right.text(0.5, 0.5, "no friction (give $\\tau$)", ha="center", transform=right.transAxes)
    right.set_xlabel(P_LABEL)
    right.set_ylabel(FRICTION_LABEL)
    fig.suptitle(f"{curves.surface.name or 'surface'}, law set {curves.law}: load control")
    return fig


#: Axis labels of the load-control figures.
P_OVER_E = r"Nominal pressure over contact modulus $p/E^*$"
AREA_LABEL = r"Real contact area fraction $A_r/A_n$"
P_LABEL = r"Applied load per nominal area $p$ (MPa)"
FRICTION_LABEL = r"Friction force per nominal area $T/A_n$ (MPa)"


def _limits_to(ax, values) -> None:
    """Log y limits around the positive ``values`` (a factor 1.5 beyond each end): a reference
    line (the GW light-load line) is cut at the axis rather than stretch it over decades where
    no point lies."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size:
        ax.set_ylim(v.min() / 1.5, v.max() * 1.5)


#: Length, in decades, of a bar on a log axis whose lower end is ≤ 0 (drawn with an arrowhead).
ARROW_DECADES = 0.25


def _log_bars(value: np.ndarray, error: np.ndarray, cut) -> np.ndarray:
    """Lower and upper bar lengths: where ``cut`` (a lower end ≤ 0 on a log axis) the lower
    bar is :data:`ARROW_DECADES` long instead."""
    lower = np.where(cut, value * (1 - 10**-ARROW_DECADES), error)
    return np.vstack([lower, error])


def load_run_figure(run):
    """Per-patch Monte Carlo points versus load over the analytic approach curves.

    Each patch (realization) at each separation of an approach run is one point
    (applied force per nominal area p = load·K, area or friction): the patches scatter
    along both axes. The ensemble means carry ±2 SE bars in both directions. The run's
    separations are typically those that balance given pressures (``mcsim simulate
    --pressure``, :func:`mcsim.physics.loadcontrol.load_control`).

    Parameters
    ----------
    run : mcsim.store.results.Run
        An approach run (no ``--cycle``).

    Returns
    -------
    matplotlib.figure.Figure
        Left: A_r/A_n (seed: N_c/N) against p/E*, log–log, with the GW light-load
        line A_r/A_n = κ(h₀) p/E* at the largest h₀ (:func:`light_load_ratio`); right:
        friction per nominal area against p, MPa (seed: T, Eq. 7). Points with p ≤ 0
        (tensile patches) are left off the log–log panel, and counted in its legend; on
        that panel a bar whose lower end is ≤ 0 is drawn :data:`ARROW_DECADES` long and
        ends in an arrowhead (it cannot reach 0 on a log axis; drawn to the axis edge it
        would look like another curve).
    """
    from matplotlib.figure import Figure

    from mcsim.physics.analytic import analytic_curves

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
    curves = analytic_curves(spec.surface, material, fine, spec.law).values
    mean, se = run.summary.mean, run.summary.se
    fig = Figure(figsize=(10, 4.4), layout="constrained")
    left, right = fig.subplots(1, 2)
    panels = [(left, area_q, material.E_star, 1.0, P_OVER_E,
               r"Fraction of summits in contact $N_c/N$" if seed else AREA_LABEL)]  # fmt: skip
    if friction_q in run.quantities:
        panels.append((right, friction_q, 1e6, material.K / 1e6, P_LABEL, FRICTION_LABEL))
    else:
        right.text(0.5, 0.5, "no friction (give $\\tau$)", ha="center", transform=right.transAxes)
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
            f" ({hidden} with $p \\leq 0$ not shown)" if hidden else "")  # fmt: skip
        ax.plot(x[shown], y[shown], ".", ms=3, color="C0", alpha=0.35, label=label)
        keep = (xa > 0) & (ya > 0) if log else np.isfinite(ya)
        ax.plot(xa[keep], ya[keep], "-", color="0.2", lw=1.2, label="analytic GW (approach)")
        ok = (xm > 0) & (ym > 0) if log else np.isfinite(xm) & np.isfinite(ym)
        xm, ym, xe, ye = xm[ok], ym[ok], xe[ok], ye[ok]
        xcut, ycut = (xm - xe <= 0, ym - ye <= 0) if log else (False, False)
        ax.errorbar(xm, ym, xerr=_log_bars(xm, xe, xcut), yerr=_log_bars(ym, ye, ycut), fmt="o",
                    ms=4, color="C3", capsize=2, label="Monte Carlo mean ± 2 SE (both axes)")  # fmt: skip
        short, label = 10**-ARROW_DECADES, "2 SE reaches 0: bar cut, arrow"
        if np.any(xcut):
            ax.plot(xm[xcut] * short, ym[xcut], "<", ms=5, color="C3", label=label)
            label = None
        if np.any(ycut):
            ax.plot(xm[ycut], ym[ycut] * short, "v", ms=5, color="C3", label=label)
        if log:
            ax.set_xscale("log")
            ax.set_yscale("log")
            if not seed and np.any(ok):
                kappa = float(light_load_ratio(spec.surface, [spec.h.max()])[0])
                grid = np.geomspace(xa[keep].min(), xa[keep].max(), 50)
                ax.plot(grid, kappa * grid, "k--", lw=1,
                        label=f"GW light load, Hertz without adhesion: $A_r/A_n$ = {kappa:.3g} $p/E^*$")  # fmt: skip
            _limits_to(
                ax,
                np.concatenate([y[shown], ya[keep], ym + ye, np.where(ycut, ym * short, ym - ye)]),
            )
        ax.set_xlabel(x_label)
        ax.set_ylabel(y_label)
        ax.legend(fontsize="small")
    name = run.path.name if run.path else "(not saved)"
    fig.suptitle(f"{name}: {spec.surface.name or 'surface'}, law set {spec.law}, patch "
                 f"$A_n$ = {spec.area * 1e12:.4g} µm², {spec.realizations} realizations")  # fmt: skip
    return fig
