"""Convergence of the Monte Carlo mean: RMS relative error versus the number of summits N.

Smooth surface, silicon, h = d/σ ∈ {0, 1, 2}. For each patch size N = ηA (log-spaced,
10³ … 10⁷ summits, Poisson count) many independent patches are simulated; the error of
a patch is e = X̂/X_GW − 1 with X̂ its P̄, F̄, T̄ (÷ A·K) or μ and X_GW the analytic
value (Eqs. 3, 5, 7, 8). The RMS of e is compared with the prediction c_X(h)/√N, with
c_X² = E[x²]/E[x]² (Poisson N) and c_μ from the delta method, both from an independent
quadrature of the per-summit laws (``gw_moments.py``). A weighted straight-line fit of
log RMS against log N gives the slope, expected to be −1/2.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL): every measured RMS within 5 SE of
c_X(h)/√N (SE of the RMS by the delta method on the mean square), and every fitted slope
within 5 SE of −1/2; at |z| < 5 a chance exceedance has probability 6e-7 per comparison.

Run: ``python validation/convergence.py`` (≈1 min on 2 cores) or ``--quick`` (seconds:
N = 10³ … 10⁴, three sizes).
Writes ``convergence.png``, ``convergence_ratio.png``, ``convergence.csv`` and
``convergence.txt`` into ``validation/out/``.
"""

from __future__ import annotations

import time

import numpy as np
from gw_moments import scatter_coefficients
from reporting import Checks, child_seeds, parser, save_figure, write_summary

from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.studies.simulation import simulate

SURFACE, MATERIAL = SURFACES["smooth"], MATERIALS["silicon"]
H = np.array([0.0, 1.0, 2.0])
#: |z| bound of the criteria (module docstring).
Z_MAX = 5.0
QUANTITIES = {"P": "load P̄", "F": "adhesion term F̄", "T": "friction T̄", "mu": "friction coeff. μ"}


def realizations_for(n: float, budget: float, r_min: int, r_max: int) -> int:
    """Patches at size n: about ``budget`` summits in all, clipped to [r_min, r_max]."""
    return int(np.clip(round(budget / n), r_min, r_max))


def rms_error(values: np.ndarray, exact: float) -> tuple[float, float, int]:
    """RMS of the relative error, its standard error (delta method on the mean square), patches used.

    Undefined values (μ of a patch without contact) are left out and counted by the caller.
    """
    e = values[np.isfinite(values)] / exact - 1.0
    ms = np.mean(e**2)
    se_ms = np.std(e**2, ddof=1) / np.sqrt(e.size)
    rms = np.sqrt(ms)
    return rms, se_ms / (2 * rms), e.size


def fit_slope(n: np.ndarray, rms: np.ndarray, se: np.ndarray) -> tuple[float, float, float, float]:
    """Weighted least squares of log10 RMS on log10 N: slope, its SE, intercept, reduced χ²."""
    x = np.log10(n)
    y = np.log10(rms)
    sy = se / (rms * np.log(10))
    w = 1 / sy**2
    A = np.column_stack([np.ones_like(x), x])
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    beta = cov @ (A.T @ (w * y))
    chi2 = float(np.sum(w * (y - A @ beta) ** 2)) / max(x.size - 2, 1)
    return float(beta[1]), float(np.sqrt(cov[1, 1])), float(beta[0]), chi2


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    if args.quick:
        n_grid, budget, r_min, r_max = np.logspace(3, 4, 3), 2e6, 50, 400
    else:
        n_grid, budget, r_min, r_max = np.logspace(3, 7, 9), 1e8, 100, 10_000
    exact = gw_curves(SURFACE, MATERIAL, H)
    coeff = {h: scatter_coefficients(SURFACE, MATERIAL, h) for h in H}
    seeds = child_seeds(args.seed, n_grid.size)

    rows = []  # (N, R, h, quantity, rms, se, predicted, used)
    t_start = time.perf_counter()
    for n, seed in zip(n_grid, seeds):
        R = realizations_for(n, budget, r_min, r_max)
        t0 = time.perf_counter()
        run = simulate(SURFACE, MATERIAL, H, n / SURFACE.eta, realizations=R, seed=seed, workers=2)
        print(f"N = {n:9.3g}: {R:6d} patches in {time.perf_counter() - t0:6.1f} s", flush=True)
        for j, h in enumerate(H):
            for q in QUANTITIES:
                rms, se, used = rms_error(run.realizations[q][:, j], getattr(exact, q)[j])
                rows.append((n, R, h, q, rms, se, coeff[h][q] / np.sqrt(n), used))
    wall = time.perf_counter() - t_start
    table = np.array([r[:3] + r[4:] for r in rows], dtype=float)  # N, R, h, rms, se, pred, used
    quantity = np.array([r[3] for r in rows])

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colors = dict(zip(H, ("tab:blue", "tab:orange", "tab:green")))
    fig, axes = plt.subplots(1, 4, figsize=(16, 4.6), sharex=True, sharey=True)
    fig_r, axes_r = plt.subplots(1, 4, figsize=(16, 4.0), sharex=True, sharey=True)
    fits = {}
    for ax, ax_r, q in zip(axes, axes_r, QUANTITIES):
        for h in H:
            sel = (quantity == q) & (table[:, 2] == h)
            n, rms, se, pred = table[sel, 0], table[sel, 3], table[sel, 4], table[sel, 5]
            slope, slope_se, _, chi2 = fit_slope(n, rms, se)
            fits[q, h] = (slope, slope_se, chi2, rms / pred, se / pred, n)
            c = colors[h]
            ax.errorbar(n, rms, yerr=se, fmt="o", color=c, ms=4, capsize=2,
                        label=f"h = {h:g}: slope {slope:+.3f} ± {slope_se:.3f}")  # fmt: skip
            ax.plot(n, pred, "--", color=c, lw=1)
            ax_r.errorbar(n, rms / pred, yerr=se / pred, fmt="o-", color=c, ms=4, capsize=2,
                          label=f"h = {h:g} (c = {coeff[h][q]:.3g})")  # fmt: skip
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(QUANTITIES[q])
        ax.set_xlabel("summits per patch  N = ηA")
        ax.legend(fontsize=8, loc="lower left", title="points: MC;  dashed: c_X(h)/√N",
                  title_fontsize=8)  # fmt: skip
        ax.grid(True, which="both", alpha=0.3)
        ax_r.axhline(1.0, color="k", lw=0.8)
        ax_r.set_xscale("log")
        ax_r.set_title(QUANTITIES[q])
        ax_r.set_xlabel("summits per patch  N = ηA")
        ax_r.legend(fontsize=8)
        ax_r.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("RMS relative error of one patch\n|X̂/X_GW − 1|, over patches")
    axes_r[0].set_ylabel("measured RMS / predicted c_X(h)/√N")
    title = (f"{SURFACE.name} surface (σ = {SURFACE.sigma * 1e9:g} nm, R = {SURFACE.R * 1e6:g} µm, "
             f"η = {SURFACE.eta * 1e-12:g} µm⁻²), {MATERIAL.name}, Poisson N; "
             "error bars: 1 SE of the RMS")  # fmt: skip
    fig.suptitle("Monte Carlo error versus patch size — " + title, fontsize=10)
    fig_r.suptitle("Measured / predicted scatter — " + title, fontsize=10)
    fig.tight_layout()
    fig_r.tight_layout()
    save_figure(fig, args.out / "convergence.png", args)
    save_figure(fig_r, args.out / "convergence_ratio.png", args)

    csv = args.out / "convergence.csv"
    header = "N,realizations,h,quantity,rms_rel_error,se_rms,predicted,patches_used"
    with csv.open("w") as fh:
        fh.write(header + "\n")
        for r in rows:
            fh.write(",".join([f"{r[0]:.6g}", str(r[1]), f"{r[2]:g}", r[3], *(f"{v:.6g}" for v in r[4:7]), str(r[7])]) + "\n")  # fmt: skip
    print(f"wrote {csv}")

    lines = [
        f"Convergence of the Monte Carlo mean: {SURFACE.name} surface, {MATERIAL.name}, Poisson N",
        f"N grid: {', '.join(f'{n:.3g}' for n in n_grid)}; realizations per N: "
        + ", ".join(str(realizations_for(n, budget, r_min, r_max)) for n in n_grid),
        f"simulation wall time: {wall:.1f} s (workers=2)",
        "",
        "Predicted coefficients c_X(h) (relative SE of one patch = c_X/√N; independent quadrature):",
        "  h     " + "".join(f"{q:>9s}" for q in QUANTITIES),
        *(f"  {h:<4g}  " + "".join(f"{coeff[h][q]:9.4g}" for q in QUANTITIES) for h in H),
        "",
        "Fitted slope of log RMS vs log N (expected -0.5), weighted LS; SE statistical;"
        " z = (slope + 0.5)/SE; chi2_red of the straight line:",
        "  quantity  h    slope     SE       z     chi2_red",
    ]
    for (q, h), (slope, slope_se, chi2, *_) in fits.items():
        lines.append(f"  {q:<8s}  {h:<3g} {slope:+.4f}  {slope_se:.4f}  {(slope + 0.5) / slope_se:+6.2f}  {chi2:6.2f}")  # fmt: skip
    lines += ["", "Measured RMS / predicted, per N (± 1 SE):"]
    for (q, h), (*_, ratio, ratio_se, _n) in fits.items():
        cells = "  ".join(f"{r:.3f}±{s:.3f}" for r, s in zip(ratio, ratio_se))
        lines.append(f"  {q:<3s} h={h:g}: {cells}")
    all_ratio = np.concatenate([v[3] for v in fits.values()])
    all_se = np.concatenate([v[4] for v in fits.values()])
    z = (all_ratio - 1) / all_se
    lines += [
        "",
        f"All {all_ratio.size} ratios: mean {all_ratio.mean():.4f}, |z| max {np.abs(z).max():.2f}, "
        f"RMS z {np.sqrt(np.mean(z**2)):.2f} (≈1 if the prediction holds; the 12 ratios at one N"
        " come from the same patches and are correlated)",
        f"Patches without any contact (μ undefined, left out): {int(sum(r[1] - r[7] for r in rows if r[3] == 'mu'))}",
    ]
    checks = Checks()
    checks.at_most(f"max |RMS/predicted - 1|/SE over {all_ratio.size} (N, h, quantity)",
                   float(np.abs(z).max()), Z_MAX)  # fmt: skip
    slope_z = [abs(v[0] + 0.5) / v[1] for v in fits.values()]
    checks.at_most(f"max |slope + 1/2|/SE over {len(slope_z)} fits", max(slope_z), Z_MAX)
    lines += ["", *checks.summary()]
    write_summary(args.out / "convergence.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
