"""Cost of a Monte Carlo run: linear in the contacting pairs, flat in memory.

Seed law set, smooth surface, silicon, one patch (fixed count, A = N/η), one worker,
``run_sums`` with sampling included and the numba compile excluded (warm-up first):

* versus N = 10⁵ … 10⁸ summits (log-spaced; 10⁸ not with ``--quick``) at M = 51
  separations h = d/σ = 4 … −1, each N in its own Python process so that its peak
  resident memory (``ru_maxrss`` at its end) is its own;
* versus M = 6 … 401 separations (h = 4 … −1) at N = 10⁶.

The work of the fused kernel is the number of contacting (summit, separation) pairs,
Σ_j N_c(h_j) (the sum of column 0 of the sums): the time should be proportional to
it, whichever of N or M makes it grow. A least-squares fit of log time against log
pairs gives the slope (1 for linear cost). At fixed N the per-summit work (sampling,
bucketing) is shared by more pairs as M grows, so the model t = c + a·summits + b·pairs
is fitted too. The kernel's arithmetic bound, square-root throughput / 3 pairs per
second (``np.sqrt``, and a loop compiled like the kernel), is drawn for reference.

Run: ``python validation/scaling.py`` (≈1 min on 2 cores) or ``--quick`` (seconds).
Writes ``scaling.png`` and ``scaling.txt`` into ``validation/out/``.

Criterion (PASS/FAIL lines, exit status 1 on a FAIL): the peak RSS of every N below 1 GB
(issue 5's target for 10⁸ summits). The slopes and the cost model are measured, not judged.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np
from benchmark import (
    MIB,
    SQRT_PER_PAIR,
    best_of,
    compiled_sqrt_throughput,
    machine,
    peak_rss,
    spec_for,
    sqrt_throughput,
)
from benchmark import warm_up as warm_up_kernel
from reporting import Checks, child_seeds, parser, save_figure, write_summary

from mcsim.engine.montecarlo import run_sums

H_START, H_STOP = 4.0, -1.0
M_DEFAULT = 51
M_VALUES = (6, 11, 21, 51, 101, 201, 401)
N_FOR_M = 1e6


def time_run(n: float, m: int, seed: int, repeats: int) -> dict:
    """Best wall time of ``run_sums(workers=1)`` on one patch of ``n`` summits, ``m`` separations."""
    spec = spec_for(n, np.linspace(H_START, H_STOP, m), seed)
    wall, run = best_of(repeats, lambda: run_sums(spec, workers=1))
    counts = run.sums[0, :, 0]  # at the lowest separation: every summit sampled (above h_min)
    return {
        "n": n,
        "m": m,
        "wall": wall,
        "pairs": float(counts.sum()),
        "summits": float(counts.max()),
    }


def child(kind: str, n: float, seed: int, repeats: int) -> dict | list[dict]:
    """The measurements of one fresh process: one N (with its peak RSS), or the M series."""
    warm_up_kernel()
    if kind == "n":
        result = time_run(n, M_DEFAULT, seed, repeats)
        result |= {"rss": peak_rss(), "load": os.getloadavg()[0]}
        return result
    return [time_run(N_FOR_M, m, seed, repeats) | {"load": os.getloadavg()[0]} for m in M_VALUES]


def spawn(kind: str, n: float, seed: int, repeats: int):
    """Run :func:`child` in a fresh process and return its numbers."""
    cmd = [sys.executable, __file__, "--child", kind, f"{n:g}", str(seed), str(repeats)]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"{kind} N={n:g} failed:\n{proc.stderr}")
    label = f"N = {n:.2e}" if kind == "n" else f"M = {M_VALUES[0]} … {M_VALUES[-1]}"
    print(f"  {label}: done in {time.perf_counter() - t0:.1f} s", flush=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def fit_slope(pairs, wall) -> tuple[float, float]:
    """Least-squares slope of log10 time on log10 pairs and its standard error."""
    x, y = np.log10(pairs), np.log10(wall)
    (slope, _), cov = np.polyfit(x, y, 1, cov=True)  # needs at least 4 points
    return float(slope), float(np.sqrt(cov[0, 0]))


def fit_cost(rows: list[dict]) -> np.ndarray:
    """Cost model t = c + a·(summits sampled) + b·pairs, least squares in relative error.

    Returns (c in s, a in s per summit, b in s per pair).
    """
    t = np.array([r["wall"] for r in rows])
    design = np.array([[1.0, r["summits"], r["pairs"]] for r in rows]) / t[:, None]
    coef, *_ = np.linalg.lstsq(design, np.ones_like(t), rcond=None)
    return coef


def model(coef: np.ndarray, rows: list[dict]) -> np.ndarray:
    return np.array([coef[0] + coef[1] * r["summits"] + coef[2] * r["pairs"] for r in rows])


def plot(by_n, by_m, bounds: dict, slopes: dict, coef: np.ndarray, args) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(13.5, 5.4))
    pn = np.array([r["pairs"] for r in by_n])
    pm = np.array([r["pairs"] for r in by_m])
    all_pairs = np.concatenate([pn, pm])
    line = np.logspace(np.log10(all_pairs.min()) - 0.2, np.log10(all_pairs.max()) + 0.2, 20)
    for (label, rate), style in zip(bounds.items(), (":", "-.")):
        ax_t.plot(line, line / rate, "k" + style, lw=1,
                  label=f"{label}: {rate * SQRT_PER_PAIR:.2e} roots/s")  # fmt: skip
    for rows, pairs, marker, color, text, key in (
        (by_n, pn, "o", "tab:blue", f"N = 10⁵ … {by_n[-1]['n']:.0e} at M = {M_DEFAULT}", "N"),
        (by_m, pm, "s", "tab:orange", f"M = {M_VALUES[0]} … {M_VALUES[-1]} at N = {N_FOR_M:.0e}", "M"),
    ):  # fmt: skip
        ax_t.plot(pairs, [r["wall"] for r in rows], marker, color=color, ls="none",
                  label=f"measured, {text} (log-log slope {slopes[key][0]:.2f})")  # fmt: skip
        ax_t.plot(pairs, model(coef, rows), "-", color=color, lw=1, alpha=0.7)
    ax_t.plot([], [], "-", color="grey", lw=1,
              label=f"model c + a·summits + b·pairs: a = {coef[1] * 1e9:.1f} ns, "
                    f"b = {coef[2] * 1e9:.2f} ns")  # fmt: skip
    for r in by_n:
        ax_t.annotate(f"N={r['n']:.0e}", (r["pairs"], r["wall"]), textcoords="offset points",
                      xytext=(-6, 6), ha="right", fontsize=7, color="tab:blue")  # fmt: skip
    for r in by_m:
        ax_t.annotate(f"M={r['m']}", (r["pairs"], r["wall"]), textcoords="offset points",
                      xytext=(6, -10), fontsize=7, color="tab:orange")  # fmt: skip
    ax_t.set_xlabel("contacting (summit, separation) pairs  Σ_j N_c(h_j)")
    ax_t.set_ylabel("wall time of run_sums, 1 worker (s)")
    ax_t.set_title(f"time vs work: slope {slopes['N'][0]:.2f} in N at fixed M\n"
                   "(at fixed N, the per-summit cost (sampling, bucketing) is shared by M)",
                   fontsize=10)  # fmt: skip
    ax_t.legend(fontsize=7.5, loc="lower right")

    n = np.array([r["n"] for r in by_n])
    n_line = np.logspace(np.log10(n.min()) - 0.2, np.log10(n.max()) + 0.2, 20)
    ax_m.plot(n_line, 8 * n_line / MIB, "k:", label="all heights stored: 8 B × N (for scale)")
    ax_m.axhline(1e9 / MIB, color="tab:red", ls="--", lw=1, label="target: 1 GB")
    ax_m.plot(n, [r["rss"] / MIB for r in by_n], "o-", color="tab:blue",
              label="peak RSS of the process (ru_maxrss), 1 worker,\n"
                    "interpreter + NumPy + SciPy + numba included")  # fmt: skip
    ax_m.set_xlabel("summits in the patch  N = ηA")
    ax_m.set_ylabel("peak resident memory (MiB)")
    ax_m.set_title("memory does not grow with N (blocks of 65 536 summits)", fontsize=10)
    ax_m.legend(fontsize=7.5, loc="lower right")
    for ax in (ax_t, ax_m):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("mcsim run_sums: seed laws, smooth surface, silicon, one patch (fixed N), "
                 "h = 4 … −1, sampling included, compile excluded, best of repeats",
                 fontsize=10)  # fmt: skip
    fig.tight_layout()
    save_figure(fig, args.out / "scaling.png", args)


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3, help="timing repeats (default %(default)s)")
    p.add_argument("--child", nargs=4, help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child:
        kind, n, seed, repeats = args.child
        print(json.dumps(child(kind, float(n), int(seed), int(repeats))))
        return
    args.out.mkdir(parents=True, exist_ok=True)
    info = machine()
    print(f"machine: {info['cpu']}, {info['cores']} cores, load {info['load']}", flush=True)
    sizes = np.logspace(5, 7, 5) if args.quick else np.logspace(5, 8, 7)
    seeds = child_seeds(args.seed, sizes.size + 1)
    warm_up_kernel()  # the children find the compiled kernel in the cache
    by_n = [spawn("n", n, s, args.repeats if n <= 1e7 else 1) for n, s in zip(sizes.round(), seeds)]
    by_m = spawn("m", N_FOR_M, seeds[-1], args.repeats)
    bounds = {
        "np.sqrt throughput / 3": sqrt_throughput(10_000_000) / SQRT_PER_PAIR,
        "compiled sqrt / 3 (hardware bound)": compiled_sqrt_throughput() / SQRT_PER_PAIR,
    }

    def fit(rows):
        return fit_slope([r["pairs"] for r in rows], [r["wall"] for r in rows])

    slopes = {"N": fit(by_n), "M": fit(by_m), "all": fit(by_n + by_m)}
    coef = fit_cost(by_n + by_m)
    residual = np.array([r["wall"] for r in by_n + by_m]) / model(coef, by_n + by_m) - 1
    lines = [
        "Scaling of run_sums (1 worker): seed laws, smooth surface, silicon, one patch, fixed N,",
        "h = 4 ... -1; sampling included, numba compile excluded; best of "
        f"{args.repeats} (1 for N > 1e7); pairs = sum of column 0 of the sums;",
        "summits = those sampled (above h_min = -1).",
        "",
        f"{'N':>10s} {'M':>4s} {'wall s':>8s} {'summits':>10s} {'pairs':>10s} {'ns/pair':>8s} "
        f"{'peak RSS MiB':>12s} {'load':>5s}",
    ]
    for r in by_n + by_m:
        rss = f"{r['rss'] / MIB:12.0f}" if "rss" in r else f"{'-':>12s}"
        lines.append(
            f"{r['n']:10.3e} {r['m']:4d} {r['wall']:8.4f} {r['summits']:10.3e} "
            f"{r['pairs']:10.3e} {r['wall'] / r['pairs'] * 1e9:8.2f} {rss} {r['load']:5.2f}"
        )
    lines += [""]
    for key, label in (("N", "varying N at M = 51"), ("M", "varying M at N = 1e6"), ("all", "all points")):  # fmt: skip
        slope, se = slopes[key]
        lines.append(f"slope of log time vs log pairs, {label}: {slope:.3f} ± {se:.3f}")
    rss = [r["rss"] / MIB for r in by_n]
    lines += [
        f"cost model t = c + a*summits + b*pairs (all points): c = {coef[0] * 1e3:.2f} ms, "
        f"a = {coef[1] * 1e9:.2f} ns per summit, b = {coef[2] * 1e9:.2f} ns per pair; "
        f"max relative residual {np.max(np.abs(residual)):.1%}",
        f"peak RSS over N = {sizes[0]:.0e} … {sizes[-1]:.0e}: {min(rss):.0f} … {max(rss):.0f} MiB "
        f"(all heights of the largest patch would take {8 * sizes[-1] / MIB:.0f} MiB)",
        *(f"{k}: {v:.3e} pairs/s ({1e9 / v:.2f} ns per pair)" for k, v in bounds.items()),
        f"machine: {info['cpu']}, {info['cores']} cores, NumPy {info['numpy']}, "
        f"numba {info['numba']}; load average at start {info['load'][0]:.2f}, "
        f"at end {os.getloadavg()[0]:.2f}",
    ]
    checks = Checks()
    for r in by_n:
        checks.at_most(f"N = {r['n']:.3g}: peak RSS (MiB)", r["rss"] / MIB, 1e9 / MIB)
    lines += ["", *checks.summary()]
    plot(by_n, by_m, bounds, slopes, coef, args)
    write_summary(args.out / "scaling.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
