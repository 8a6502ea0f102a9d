"""Device-to-device variability of stiction: many small patches of 10 µm × 10 µm.

For each of the paper's four combined surfaces (Table 1, simulations A–D) and silicon,
500 independent patches of nominal area A = 10⁻¹⁰ m² (ηA ≈ 1100–2600 summits, Poisson
count) are simulated at separations h = d/σ from 4 to 0. Per patch: the dimensional
JKR adhesion term F = F̄·A·K (Eq. 5; the paper's "adhesive force", not a pull-off
force) and the friction coefficient μ = T/(P + F) (Eq. 8). Reported: histograms at
h ∈ {2, 1, 0}, the coefficient of variation (CV = std/mean over patches) against the
prediction c_X(h)/√(ηA) (``gw_moments.py``), the 5th/95th percentiles and the fraction
of patches with no contacting summit at all (prediction exp(−ηA·F₀(h)), Poisson).

Criteria (PASS/FAIL lines, exit status 1 on a FAIL), each the largest |z| over the
surfaces and separations, bound 5 (a chance exceedance has probability 6e-7 per
comparison): the mean F of the patches against the GW mean (z with the SE std/√patches;
Poisson N makes the GW mean exact for any patch); the fraction of patches with no contact
against exp(−ηA·F₀(h)) (binomial SE); the CVs of F and μ against c_X(h)/√(ηA) (bootstrap
SE) where E[N_c] ≥ 20: the CV of a compound-Poisson sum is exactly c_F/√(ηA), but the
bootstrap SE of a CV is unreliable for a handful of summits, and μ's prediction is the
delta method, which needs many.

Run: ``python validation/finite_patch.py`` (≈10 s) or ``--quick`` (200 patches, h = 3 … 0:
enough that a prediction 20 % off fails, |z| ≈ 7).
Writes ``finite_patch_F.png``, ``finite_patch_mu.png``, ``finite_patch_cv.png`` and
``finite_patch.txt`` into ``validation/out/``.
"""

from __future__ import annotations

import time

import numpy as np
from gw_moments import scatter_coefficients
from reporting import Checks, child_seeds, parser, save_figure, write_summary

from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.studies.simulation import simulate

MATERIAL = MATERIALS["silicon"]
AREA = 1e-10  # m², a 10 µm × 10 µm patch
HIST_H = (2.0, 1.0, 0.0)
MICRO = 1e6  # N → µN
#: |z| bound of the criteria, and the expected contacts from which the CVs are judged.
Z_MAX, CONTACTS_FOR_CV = 5.0, 20.0
COLORS = dict(zip(PAPER_SURFACES, ("tab:red", "tab:orange", "tab:green", "tab:blue")))


def cv_with_se(x: np.ndarray, rng: np.random.Generator, n_boot: int = 400) -> tuple[float, float]:
    """CV = std/mean (ddof 1) of the finite values and its bootstrap standard error."""
    x = x[np.isfinite(x)]
    if x.size < 3 or x.mean() == 0:
        return np.nan, np.nan
    cv = x.std(ddof=1) / x.mean()
    boot = rng.choice(x, size=(n_boot, x.size))
    with np.errstate(invalid="ignore", divide="ignore"):
        b = boot.std(axis=1, ddof=1) / boot.mean(axis=1)
    return float(cv), float(np.nanstd(b))


def criteria(stats: dict, patches: int) -> Checks:
    """The largest |z| of each criterion (module docstring) over surfaces and separations."""
    z: dict[str, dict] = {"mean F - GW": {}, "no-contact fraction - Poisson": {},
                          "CV_F - pred": {}, "CV_mu - pred": {}}  # fmt: skip
    for (name, h), r in stats.items():
        where = f"{name}, h = {h:g}"
        z["mean F - GW"][where] = r["z_F"]
        p = r["none_pred"]
        z["no-contact fraction - Poisson"][where] = (r["none"] - p) / np.sqrt(
            max(p * (1 - p), 1e-300) / patches
        )
        if r["contacts"] >= CONTACTS_FOR_CV:
            z["CV_F - pred"][where] = (r["cv_F"] - r["pred_F"]) / r["se_F"]
            z["CV_mu - pred"][where] = (r["cv_mu"] - r["pred_mu"]) / r["se_mu"]
    checks = Checks()
    for what, values in z.items():
        worst = max(values, key=lambda k: abs(values[k]))
        checks.at_most(f"{what}: max |z| of {len(values)} (at {worst})", abs(values[worst]), Z_MAX)
    return checks


def label(surface) -> str:
    return f"{surface.name} (σ = {surface.sigma * 1e9:g} nm, ηA = {surface.eta * AREA:.0f})"


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    patches = 200 if args.quick else 500
    h = np.array([3.0, 2.0, 1.0, 0.0]) if args.quick else np.arange(4.0, -0.25, -0.5)
    *seeds, boot_seed = child_seeds(args.seed, len(PAPER_SURFACES) + 1)
    rng = np.random.default_rng(boot_seed)  # bootstrap of the CVs

    results = {}
    t0 = time.perf_counter()
    for name, seed in zip(PAPER_SURFACES, seeds):
        surface = SURFACES[name]
        run = simulate(surface, MATERIAL, h, AREA, realizations=patches, seed=seed, workers=2)
        scale = AREA * MATERIAL.K * MICRO
        results[name] = {
            "surface": surface,
            "F": run.realizations["F"] * scale,  # (patches, M), µN
            "mu": run.realizations["mu"],  # NaN where no contact
            "no_contact": (run.sums[..., 0] == 0).mean(axis=0),
            "F_gw": run.analytic["F"] * scale,
            "mu_gw": run.analytic["mu"],
            "coeff": [scatter_coefficients(surface, MATERIAL, hj) for hj in h],
            "sf": np.asarray(surface.heights.sf(h)),
        }
    wall = time.perf_counter() - t0

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    def number(v: float) -> str:
        return f"{v:,.0f}" if abs(v) >= 100 else f"{v:.4g}"

    def histograms(q: str, xlabel: str, path: str, title: str) -> None:
        fig, axes = plt.subplots(len(PAPER_SURFACES), len(HIST_H), figsize=(13, 12))
        for i, name in enumerate(PAPER_SURFACES):
            res = results[name]
            n = res["surface"].eta * AREA
            for k, hk in enumerate(HIST_H):
                ax = axes[i, k]
                j = int(np.flatnonzero(h == hk)[0])
                x = res[q][:, j]
                x = x[np.isfinite(x)]
                p5, p95 = np.percentile(x, [5, 95])
                cv, _ = cv_with_se(x, rng, n_boot=2)
                pred = res["coeff"][j]["F" if q == "F" else "mu"] / np.sqrt(n)
                ax.hist(x, bins=30, color=COLORS[name], alpha=0.75)
                ax.axvline(res[q + "_gw"][j], color="k", lw=1.5, label="GW mean (analytic)")
                ax.axvline(p5, color="k", ls=":", lw=1, label="5th / 95th percentile of patches")
                ax.axvline(p95, color="k", ls=":", lw=1)
                ax.text(0.02, 0.97, f"CV {cv:.3g} (pred. {pred:.3g})\n"
                        f"P5–P95: {number(p5)} – {number(p95)}\n"
                        f"E[N_c] = {n * res['sf'][j]:.3g} contacts",
                        transform=ax.transAxes, va="top", fontsize=8,
                        bbox={"fc": "white", "alpha": 0.8, "lw": 0})  # fmt: skip
                ax.ticklabel_format(axis="x", style="plain", useOffset=False)
                ax.xaxis.set_major_locator(MaxNLocator(5))
                if i == 0:
                    ax.set_title(f"h = d/σ = {hk:g}")
                if k == 0:
                    ax.set_ylabel(f"{name}, ηA = {n:.0f}\npatches per bin")
                if i == len(PAPER_SURFACES) - 1:
                    ax.set_xlabel(xlabel)
        fig.suptitle(title, fontsize=11)
        handles, labels = axes[0, 0].get_legend_handles_labels()
        fig.legend(handles[:2], labels[:2], loc="upper center", ncol=2, fontsize=9,
                   bbox_to_anchor=(0.5, 0.975), frameon=False)  # fmt: skip
        fig.tight_layout(rect=(0, 0, 1, 0.955))
        save_figure(fig, args.out / path, args)

    common = (f"{patches} patches of 10 µm × 10 µm per surface, {MATERIAL.name}, "
              "GW model (Eqs. 4–8); CV = std/mean across patches")  # fmt: skip
    histograms("F", "JKR adhesion term F of the patch (µN)", "finite_patch_F.png",
               f"Adhesion term F per patch (Eq. 5, dimensional: F̄·A·K) — {common}")  # fmt: skip
    histograms("mu", "friction coefficient μ = T/(P + F) of the patch", "finite_patch_mu.png",
               f"Friction coefficient per patch (Eq. 8) — {common}")  # fmt: skip

    stats = {}
    for name, res in results.items():
        n = res["surface"].eta * AREA
        for j, hj in enumerate(h):
            cv_f, se_f = cv_with_se(res["F"][:, j], rng)
            cv_m, se_m = cv_with_se(res["mu"][:, j], rng)
            f = res["F"][:, j]
            m = res["mu"][:, j]
            m = m[np.isfinite(m)]
            stats[name, hj] = {
                "n": n, "contacts": n * res["sf"][j],
                "F_mean": f.mean(), "F_gw": res["F_gw"][j], "F_p5": np.percentile(f, 5),
                "F_p95": np.percentile(f, 95), "cv_F": cv_f, "se_F": se_f,
                "pred_F": res["coeff"][j]["F"] / np.sqrt(n),
                "mu_mean": m.mean() if m.size else np.nan, "mu_gw": res["mu_gw"][j],
                "mu_p5": np.percentile(m, 5) if m.size else np.nan,
                "mu_p95": np.percentile(m, 95) if m.size else np.nan,
                "cv_mu": cv_m, "se_mu": se_m, "pred_mu": res["coeff"][j]["mu"] / np.sqrt(n),
                "none": res["no_contact"][j], "none_pred": np.exp(-n * res["sf"][j]),
                "z_F": (f.mean() - res["F_gw"][j]) / (f.std(ddof=1) / np.sqrt(f.size)),
            }  # fmt: skip

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    for name in PAPER_SURFACES:
        c = COLORS[name]
        s = [stats[name, hj] for hj in h]
        for ax, q in zip(axes[:2], ("F", "mu")):
            ax.errorbar(h, [r["cv_" + q] for r in s], yerr=[r["se_" + q] for r in s], fmt="o",
                        color=c, ms=4, capsize=2, label=label(results[name]["surface"]))  # fmt: skip
            ax.plot(h, [r["pred_" + q] for r in s], "-", color=c, lw=1)
        axes[2].plot(h, [r["none"] for r in s], "o", color=c, ms=4, label=label(results[name]["surface"]))  # fmt: skip
        fine = np.linspace(h.min(), h.max(), 200)
        axes[2].plot(fine, np.exp(-results[name]["surface"].eta * AREA * results[name]["surface"].heights.sf(fine)), "-", color=c, lw=1)  # fmt: skip
    axes[0].set_title("adhesion term F: CV across patches")
    axes[1].set_title("friction coefficient μ: CV across patches\n(over patches with contact)")
    axes[1].text(0.03, 0.03, "h ≳ 3: a few contacts per patch;\nthe √N prediction (delta method) fails",
                 transform=axes[1].transAxes, fontsize=8)  # fmt: skip
    axes[2].set_title("patches with no contacting summit")
    for ax in axes[:2]:
        ax.set_yscale("log")
        ax.set_ylabel("coefficient of variation  std/mean")
    axes[2].set_ylabel("fraction of patches")
    axes[0].legend(fontsize=8, title="points: MC (±1 SE, bootstrap); lines: c_X(h)/√(ηA)",
                   title_fontsize=8)  # fmt: skip
    axes[2].legend(fontsize=8, title="points: MC; lines: exp(−ηA·F₀(h)), Poisson", title_fontsize=8)
    for ax in axes:
        ax.set_xlabel("separation  h = d/σ")
        ax.grid(True, which="both", alpha=0.3)
        ax.invert_xaxis()
    fig.suptitle(f"Patch-to-patch variability versus separation — {common}", fontsize=10)
    fig.tight_layout()
    save_figure(fig, args.out / "finite_patch_cv.png", args)

    lines = [
        "Device-to-device variability: patches of A = 1e-10 m² (10 µm × 10 µm), "
        f"{MATERIAL.name}, {patches} patches per surface, Poisson N",
        f"simulation wall time: {wall:.1f} s (workers=2)",
        "F: JKR adhesion term of the patch (Eq. 5, dimensional F̄·A·K), µN (1 µN = 1000 nN); "
        "μ = T/(P+F) per patch (Eq. 8), over patches with contact",
        "CV = std/mean across patches (± bootstrap SE); pred = c_X(h)/√(ηA); "
        "none = fraction of patches with no contact (pred exp(-ηA F0(h)))",
        "",
    ]
    head = (f"{'surface':<13s} {'h':>4s} {'ηA':>5s} {'E[Nc]':>8s} | {'F mean':>9s} {'F GW':>9s} "
            f"{'F P5':>9s} {'F P95':>9s} {'CV_F':>17s} {'pred':>6s} | {'μ mean':>6s} {'μ GW':>6s} "
            f"{'μ P5':>6s} {'μ P95':>6s} {'CV_μ':>17s} {'pred':>8s} | {'none':>5s} {'pred':>8s}")  # fmt: skip
    lines += [head, "-" * len(head)]

    def pm(value: float, se: float) -> str:
        return f"{f'{value:.3g} ± {se:.2g}':>17s}"

    for name in PAPER_SURFACES:
        for hj in h:
            r = stats[name, hj]
            lines.append(
                f"{name:<13s} {hj:4.1f} {r['n']:5.0f} {r['contacts']:8.3g} | {r['F_mean']:9.5g} "
                f"{r['F_gw']:9.5g} {r['F_p5']:9.5g} {r['F_p95']:9.5g} {pm(r['cv_F'], r['se_F'])} "
                f"{r['pred_F']:6.3g} | {r['mu_mean']:6.3f} {r['mu_gw']:6.3f} {r['mu_p5']:6.3f} "
                f"{r['mu_p95']:6.3f} {pm(r['cv_mu'], r['se_mu'])} {r['pred_mu']:8.3g} | "
                f"{r['none']:5.3f} {r['none_pred']:8.2g}"
            )
        lines.append("")
    lines.append("CV predictions assume many contacts per patch; where E[Nc] is a few or less "
                 "(h ≥ 3) the distribution is a handful of summits and the CV of μ is conditional "
                 "on contact.")  # fmt: skip
    checks = criteria(stats, patches)
    lines += ["", *checks.summary()]
    write_summary(args.out / "finite_patch.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
