"""Speed and memory of the Monte Carlo engine against a straightforward NumPy baseline.

Seed law set (Hertz, Johnson, Savkoor–Briggs), smooth surface, silicon, one patch of
N = ηA summits (fixed count, A = N/η), one realization. Cases:

* **baseline**: what one would write first: draw all N heights with
  ``default_rng().standard_normal``; per separation mask the contacting summits,
  evaluate ``SEED.load``, ``SEED.adhesion`` and ``SEED.friction`` (with
  ``SEED.arguments``) and sum them;
* **mcsim, 1 worker** and **mcsim, all workers**: ``run_sums(spec, workers=...)``,
  sampling included (it draws only the summits above h_min, in blocks);

for the sweep h = d/σ = 4 … −1 and for h = 4 … 2 (51 values each) at N = 10⁷, and for
N = 10⁸ streamed (mcsim only; the baseline would hold 0.8 GB per array: ``--full``).
Also the analytic curves (``gw_curves``: P, F, T, μ, N_c/N) at 1000 separations, the
numba compile (cold, into an empty ``MCSIM_CACHE_DIR``) and the cached start-up, the
split of mcsim's time between sampling (``sample_block``) and the kernel
(``block_sums``), and the arithmetic bound: the kernel takes 3 square roots per
contacting pair, so ``np.sqrt`` throughput / 3 bounds the pairs per second. Finally the
kernel's cost per contacting pair for every registered law set (``mcsim.physics.laws.LAW_SETS``,
silicon with z0 = 0.3 nm and τ = 100 MPa), on approach and over a cycle (approach, then
retraction from h = −1), against the seed's.

End to end (issue 12): the user's command ``mcsim simulate`` (N = 5·10⁷ summits, fixed
count, h = 4 … −1, one realization, all cores) timed as a whole process, interpreter
start-up, imports, kernel loading, file writing and exit included, against the NumPy
baseline at the same N in the same run; and a tiny run (10³ summits) as a whole
process: the start-up and exit alone. ``--only end-to-end`` runs just this part (≈3
min; the baseline at 5·10⁷ summits peaks at ≈3.7 GB resident).

Every case runs in its own Python process (``--case``), so that its peak resident
memory (``ru_maxrss`` at its end) is its own; timings are the best of a few repeats,
after a warm-up that loads the compiled kernel. A pair is one (summit, separation)
with the summit in contact; the baseline and mcsim count the same pairs (up to the
random draw), so pairs/s compare like with like.

Run: ``python validation/benchmark.py`` (≈5 min on 2 cores), ``--quick`` (N = 10⁶,
streamed 10⁷, seconds) or ``--full`` (adds the baseline at N = 10⁸, ≈6 GB, minutes).
Prints a markdown table and writes it to ``validation/out/benchmark.md``.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL): the targets above (speed-ups, the
analytic curves' time, peak RSS < 1 GB streamed) and the baseline's sums against mcsim's
(independent draws of the same N summits: max |z| < 5). With ``--quick`` the timing
targets are reported as INFO, not judged (N = 10⁶ is too small for them); the memory and
agreement criteria are judged in every run.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import resource
import shlex
import subprocess
import sys
import tempfile
import time

import numpy as np
from reporting import Checks, child_seeds, parser, provenance

from mcsim.engine.montecarlo import default_workers, run_sums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import SEED

SURFACE, MATERIAL = SURFACES["smooth"], MATERIALS["silicon"]
#: Separation sweeps d/σ: (start, stop, count) for np.linspace.
SWEEPS = {"full": (4.0, -1.0, 51), "high": (4.0, 2.0, 51)}
SWEEP_LABEL = {"full": "h = 4 … −1", "high": "h = 4 … 2"}
MIB = 2**20
#: Targets of issue 5.
SPEEDUP_FULL, SPEEDUP_HIGH, RSS_STREAMED, ANALYTIC_S = 10.0, 20.0, 1e9, 0.050
#: Issues 12 and 23: summits of the end-to-end command, and its target against the baseline
#: (issue 23: ≥ 12× here, so that ≥ 10× holds on other machines).
N_END_TO_END, SPEEDUP_END_TO_END = 5e7, 12.0
SQRT_PER_PAIR = 3  # the fused kernel's square roots per contacting pair (one per law)
#: |z| bound of the baseline-against-mcsim check (independent draws; chance 6e-7 per sum).
Z_MAX = 5.0


def peak_rss() -> int:
    """Peak resident memory of this process so far, bytes (Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def machine() -> dict:
    """Cores, CPU model, library versions and load average of this machine."""
    import numba

    model = "unknown"
    try:
        with open("/proc/cpuinfo") as fh:
            model = next(line.split(":", 1)[1].strip() for line in fh if "model name" in line)
    except (OSError, StopIteration):
        pass
    return {
        "cores": default_workers(),
        "cpu": model,
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "numba": numba.__version__,
        "load": os.getloadavg(),
    }


def sweep(name: str) -> np.ndarray:
    """Separations d/σ of a named sweep."""
    return np.linspace(*SWEEPS[name])


def spec_for(n: float, h: np.ndarray, seed: int) -> MonteCarloSpec:
    """One patch of exactly ``n`` summits (fixed count, A = n/η)."""
    return MonteCarloSpec(
        SURFACE, MATERIAL, h, area=n / SURFACE.eta, realizations=1, entropy=seed, count="fixed"
    )


def baseline(n: int, h: np.ndarray, seed: int) -> tuple[np.ndarray, float]:
    """The straightforward NumPy sweep: all N heights, mask and evaluate per separation.

    Returns the sums (n_contact, P, F, T in N) per separation and the sampling time (s).
    """
    t0 = time.perf_counter()
    z = SURFACE.sigma * np.random.default_rng(seed).standard_normal(n)
    t_sample = time.perf_counter() - t0
    args = SEED.arguments(SURFACE, MATERIAL)
    out = np.empty((h.size, 4))
    for j, d in enumerate(h * SURFACE.sigma):
        delta = z[z > d] - d
        p, f, t = (law(delta, *a) for law, a in zip(SEED.laws, args))
        out[j] = delta.size, p.sum(), f.sum(), t.sum()
    return out, t_sample


def best_of(repeats: int, fn, clock=time.perf_counter) -> tuple[float, object]:
    """Smallest time of ``repeats`` calls of ``fn()`` (wall time by default) and the last
    result."""
    best = np.inf
    for _ in range(repeats):
        t0 = clock()
        result = fn()
        best = min(best, clock() - t0)
    return best, result


def warm_up() -> None:
    """A tiny run: loads (or compiles) the numba kernel before anything is timed."""
    run_sums(spec_for(1e3, sweep("full"), 0), workers=1)


def sqrt_throughput(n: int, repeats: int = 5) -> float:
    """``np.sqrt`` evaluations per second on an array of ``n`` doubles (in place, best of 5)."""
    a = np.random.default_rng(0).random(n) + 1.0
    out = np.empty_like(a)
    reps = max(1, 10_000_000 // n)  # about 10⁷ roots per timing

    def roots():
        for _ in range(reps):
            np.sqrt(a, out=out)

    t, _ = best_of(repeats, roots)
    return reps * n / t


def compiled_sqrt_throughput(repeats: int = 5) -> float:
    """Square roots per second in a numba loop compiled like the kernel (best of 5).

    The loop sums √a_i over 2¹⁶ doubles in cache with the kernel's fastmath flags, so
    LLVM vectorises it with the widest packed square root of the CPU: the hardware's
    own bound, which ``np.sqrt`` need not reach.
    """
    import numba

    @numba.njit(fastmath={"reassoc", "contract", "nsz"})
    def sum_sqrt(a):
        s = 0.0
        for i in range(a.size):
            s += np.sqrt(a[i])
        return s

    a = np.random.default_rng(0).random(1 << 16) + 1.0
    sum_sqrt(a)
    reps = 10_000_000 // a.size

    def roots():
        for _ in range(reps):
            sum_sqrt(a)

    t, _ = best_of(repeats, roots)
    return reps * a.size / t


def run_case(case: str, n: float, sweep_name: str, repeats: int, seed: int) -> dict:
    """One measurement in this (fresh) process; returns its numbers."""
    h = sweep(sweep_name)
    result: dict = {"case": case, "n": n, "sweep": sweep_name}
    if case == "startup":  # import already done: time the first and a second tiny call
        for key in ("t_first", "t_second"):
            t0 = time.perf_counter()
            warm_up()
            result[key] = time.perf_counter() - t0
    elif case == "baseline":
        best, (sums, t_sample) = best_of(repeats, lambda: baseline(round(n), h, seed))
        result |= {"wall": best, "t_sample": t_sample, "pairs": float(sums[:, 0].sum())}
        result["sums"] = sums.tolist()
    elif case in ("mcsim1", "mcsimall"):
        warm_up()
        workers = 1 if case == "mcsim1" else default_workers()
        spec = spec_for(n, h, seed)
        best, run = best_of(repeats, lambda: run_sums(spec, workers=workers))
        sums = run.sums[0]
        result |= {"wall": best, "workers": workers, "pairs": float(sums[:, 0].sum())}
        result["sums"] = sums.tolist()
    elif case == "parts":
        from mcsim.engine.kernels import block_sums
        from mcsim.engine.montecarlo import plan_patch, sample_block

        warm_up()
        spec = spec_for(n, h, seed)
        plan = plan_patch(spec, 0)
        args = SEED.arguments(SURFACE, MATERIAL)
        d_desc = np.sort(spec.d)[::-1]
        t_sample, blocks = best_of(
            repeats, lambda: [sample_block(spec, plan, 0, b) for b in range(plan.n_blocks)]
        )
        t_kernel, partials = best_of(
            repeats, lambda: [block_sums(z, d_desc, SEED, args) for z in blocks]
        )
        t_normal, _ = best_of(
            repeats, lambda: np.random.default_rng(seed).standard_normal(round(n))
        )
        result |= {
            "t_sample": t_sample,
            "t_kernel": t_kernel,
            "t_normal": t_normal,
            "n_above": plan.n_above,
            "pairs": float(sum(p[:, 0].sum() for p in partials)),
        }
    elif case == "laws":
        result["laws"] = law_costs(n, h, repeats, seed)
    elif case == "analytic":
        from mcsim.physics.analytic import gw_curves

        h_dense = np.linspace(4.0, -1.0, 1000)
        gw_curves(SURFACE, MATERIAL, h_dense)
        result["wall"], _ = best_of(20, lambda: gw_curves(SURFACE, MATERIAL, h_dense))
    elif case == "sqrt":
        result["large"] = sqrt_throughput(10_000_000)
        result["in_cache"] = sqrt_throughput(32_768)
        result["compiled"] = compiled_sqrt_throughput()
    else:
        raise ValueError(f"unknown case {case!r}")
    result["rss"] = peak_rss()
    result["load"] = os.getloadavg()[0]
    return result


def law_costs(n: float, h: np.ndarray, repeats: int, seed: int) -> dict:
    """Kernel time per contacting and per evaluated (summit, row) pair of every law set.

    Each law set samples its own summits (down to its own lowest threshold) for one patch
    of ``n`` summits; the kernel is timed on those blocks (best of ``repeats``, compile
    excluded) by the CPU time of this thread, which runs it: other jobs sharing the
    machine do not inflate it, as they do wall time. The law sets take turns, one call
    each per round, so that a change of load during the measurement reaches all of them
    alike and the ratios to the seed hold. Evaluated pairs are those above the rows'
    thresholds (attraction included); contacting pairs are those in contact.
    """
    import dataclasses

    from mcsim.engine.kernels import block_sums
    from mcsim.engine.montecarlo import plan_patch, sample_block
    from mcsim.physics.laws import LAW_SETS

    material = dataclasses.replace(MATERIAL, z0=0.3e-9, tau=100e6)
    out, kernels = {}, {}
    for name, law in LAW_SETS.items():
        for cycle in (False, True) if law.retract else (False,):
            spec = MonteCarloSpec(SURFACE, material, h, area=n / SURFACE.eta, realizations=1,
                                  entropy=seed, law=name, count="fixed", cycle=cycle)  # fmt: skip
            plan = plan_patch(spec, 0)
            blocks = [sample_block(spec, plan, 0, b) for b in range(plan.n_blocks)]
            d, d_turn = spec.rows()
            thresholds = spec.edges.threshold(d, d_turn)

            def kernel(spec=spec, blocks=blocks, d=d, d_turn=d_turn, law=law):
                return [block_sums(z, d, law, spec.arguments, d_turn=d_turn, edges=spec.edges)
                        for z in blocks]  # fmt: skip

            key = f"{name}, {'cycle' if cycle else 'approach'}"
            kernels[key] = kernel
            partials = kernel()  # compile or load
            out[key] = {
                "t": np.inf,
                "contacts": float(sum(p[:, 0].sum() for p in partials)),
                "evaluated": sum(
                    float(np.sum(z.size - np.searchsorted(np.sort(z), thresholds, side="right")))
                    for z in blocks
                ),
                "rows": int(d.size),
            }
    for _ in range(repeats):
        for key, kernel in kernels.items():
            out[key]["t"] = min(out[key]["t"], best_of(1, kernel, clock=time.thread_time)[0])
    return out


def spawn(case: str, n: float, sweep_name: str, repeats: int, seed: int, cache: str) -> dict:
    """Run one case in a fresh process with kernel cache ``cache``; return its numbers."""
    cmd = [sys.executable, __file__, "--case", case, "--n", f"{n:g}", "--sweep", sweep_name]
    cmd += ["--repeats", str(repeats), "--seed", str(seed)]
    t0 = time.perf_counter()
    proc = subprocess.run(
        cmd, capture_output=True, text=True, env={**os.environ, "MCSIM_CACHE_DIR": cache}
    )
    if proc.returncode != 0:
        sys.exit(f"case {case} N={n:g} {sweep_name} failed:\n{proc.stderr}")
    result = json.loads(proc.stdout.strip().splitlines()[-1])
    result["process"] = time.perf_counter() - t0
    print(f"  {case:9s} N={n:8.0e} {sweep_name:5s} done in {result['process']:5.1f} s", flush=True)
    return result


def simulate_command(n: float, seed: int, out: str) -> list[str]:
    """The user's ``mcsim simulate`` of one patch of exactly ``n`` summits (fixed count,
    A = n/η in m²), h = 4 … −1 (51 values), one realization, all cores, no progress bar."""
    return [sys.executable, "-m", "mcsim", "simulate", "--surface", "smooth",
            "--material", "silicon", "--area", repr(n / SURFACE.eta), "--count", "fixed",
            "--h", "4:-1:51", "--realizations", "1", "--seed", str(seed), "--out", out,
            "--overwrite", "--quiet"]  # fmt: skip


def whole_process(n: float, repeats: int, seed: int, cache: str) -> dict:
    """Wall time of :func:`simulate_command` as a fresh process, start-up and exit included.

    A first, untimed run loads the kernel into ``cache`` (compiling it if needed) and
    caches mcsim's bytecode, as an installed package has it (``PYTHONDONTWRITEBYTECODE``
    is dropped); then the best of ``repeats`` runs.
    """
    env = {**os.environ, "MCSIM_CACHE_DIR": cache}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    walls = []
    with tempfile.TemporaryDirectory() as tmp:
        cmd = simulate_command(n, seed, os.path.join(tmp, "run.h5"))
        for _ in range(repeats + 1):
            t0 = time.perf_counter()
            proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
            walls.append(time.perf_counter() - t0)
            if proc.returncode != 0:
                sys.exit(f"{shlex.join(cmd)} failed:\n{proc.stderr}")
    best = min(walls[1:])
    print(f"  mcsim simulate N={n:8.0e} whole process: best {best:5.2f} s", flush=True)
    return {"n": n, "wall": best, "walls": walls[1:], "load": os.getloadavg()[0]}


def end_to_end(n: float, repeats: int, seed: int, cache: str) -> dict:
    """The whole-process timings of issue 12 and their references (see the module doc)."""
    return {
        "cli-tiny": whole_process(1e3, repeats, seed, cache),
        "cli-big": whole_process(n, repeats, seed, cache),
        "mcsimall-cli": spawn("mcsimall", n, "full", repeats, seed, cache),
        "baseline-cli": spawn("baseline", n, "full", repeats, seed, cache),
    }


def end_to_end_lines(res: dict, repeats: int, checks: Checks) -> list[str]:
    """Report of :func:`end_to_end`."""
    big, tiny = res["cli-big"], res["cli-tiny"]
    base, kernel = res["baseline-cli"], res["mcsimall-cli"]
    n = big["n"]
    ratio = base["wall"] / big["wall"]
    cmd = shlex.join(["mcsim", *simulate_command(n, 1, "RUN.h5")[3:]]).replace(
        "--seed 1", "--seed S"
    )
    return [
        f"End to end, as a user runs it (issues 12, 23): `{cmd}` (N = {n:.0e} summits, "
        f"{kernel['workers']} workers) as a whole process, interpreter start-up, imports, "
        "kernel loading, file writing and exit included (numba cache and bytecode warm "
        f"from an untimed first run; best of {repeats}), against the NumPy baseline at "
        "the same N in this run:",
        "- "
        + checks.judge(
            ratio >= SPEEDUP_END_TO_END,
            f"whole process ≥ "
            f"{SPEEDUP_END_TO_END:g}× the baseline: {base['wall']:.2f} s / {big['wall']:.2f} s "
            f"= **{ratio:.1f}×** (runs: {', '.join(f'{w:.2f}' for w in big['walls'])} s)",
            timing=True,
        ),
        f"- start-up and exit: the same command for 10³ summits takes {tiny['wall']:.2f} s "
        f"as a whole process; the run itself in process (`run_sums`, warm, "
        f"{kernel['workers']} workers): {kernel['wall']:.2f} s, "
        f"{base['wall'] / kernel['wall']:.1f}× the baseline",
    ]


# --- analytic design maps (issue 23) ---------------------------------------------------------

#: The design map: σ log-spaced × w linear, the jkr law set, smooth surface on silicon.
DESIGN_MAP = {"sigma": "0.3nm:20nm:50:log", "gamma": "0.05:1:40"}
#: Issue 23's target: points per second ≥ this × the NumPy baseline's, start-up included.
SPEEDUP_DESIGN_MAP = 100.0
#: The baseline's height nodes, JKR-radius bisection steps and retraction separations.
BASELINE_NODES, BISECTION_STEPS, RETRACTION_ROWS = 4000, 60, 51


def design_points() -> tuple[np.ndarray, np.ndarray]:
    """σ (m) and w (J/m²) of every point of :data:`DESIGN_MAP`, C order (w fastest)."""
    sigma = np.geomspace(0.3e-9, 20e-9, 50)
    gamma = np.linspace(0.05, 1.0, 40)
    s, g = np.meshgrid(sigma, gamma, indexing="ij")
    return s.ravel(), g.ravel()


def jkr_radius(delta: np.ndarray, R: float, E_star: float, w: float) -> np.ndarray:
    """Contact radius a (m) on the stable JKR branch, δ = a²/R − √(2πwa/E*) (Johnson, Kendall
    & Roberts 1971), by bisection between the fold a_c = (πwR²/(8E*))^{1/3} and an upper
    bound, all elements at once (``delta`` ≥ δ_c)."""
    c = np.sqrt(2 * np.pi * w / E_star)
    lo = np.full_like(delta, np.cbrt(np.pi * w * R * R / (8 * E_star)))
    hi = 2 * np.sqrt(R * np.maximum(delta, 0.0)) + 4 * np.cbrt(c * R) ** 2 + lo
    for _ in range(BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        above = mid * mid / R - c * np.sqrt(mid) > delta
        hi = np.where(above, mid, hi)
        lo = np.where(above, lo, mid)
    return 0.5 * (lo + hi)


def design_baseline(sigma: float, w: float) -> tuple[float, float, float]:
    """The straightforward NumPy pull-off of one design point (jkr, Gaussian heights).

    Heights on a fixed grid of :data:`BASELINE_NODES` nodes over ±√82 (trapezoid weights);
    per summit the JKR load P = 4E*a³/(3R) − √(8πwE*a³) with a from :func:`jkr_radius`;
    the turn is the zero of the approach load (bisection in h, 50 steps), the pull-off
    the most tensile load of :data:`RETRACTION_ROWS` separations from the turn to the top,
    and the work of separation their trapezoid rule. Returns (turn, pull_off/(A_n K),
    work J/m²).
    """
    R, eta, E, K = SURFACE.R, SURFACE.eta, MATERIAL.E_star, MATERIAL.K
    s = np.linspace(-np.sqrt(82.0), np.sqrt(82.0), BASELINE_NODES)
    weight = np.exp(-0.5 * s * s) / np.sqrt(2 * np.pi) * (s[1] - s[0])
    delta_c = -0.75 * np.cbrt(np.pi**2 * w * w * R / E**2)

    def load(h: np.ndarray, turn: float | None) -> np.ndarray:
        delta = sigma * (s[None, :] - h[:, None])
        touching = delta > 0 if turn is None else (s[None, :] > turn) & (delta > delta_c)
        a = jkr_radius(delta[touching], R, E, w)  # only the summits in contact
        force = np.zeros_like(delta)
        force[touching] = 4 * E * a**3 / (3 * R) - np.sqrt(8 * np.pi * w * E * a**3)
        return eta / K * (force @ weight)

    top = np.sqrt(82.0) - delta_c / sigma
    lo, hi = -np.sqrt(82.0), top
    if load(np.array([lo]), None)[0] <= 0 or np.all(load(np.linspace(lo, hi, 51), None) >= 0):
        return top, 0.0, 0.0  # never tensile: the surfaces rest apart
    for _ in range(50):  # compressive below the zero, tensile above it
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if load(np.array([mid]), None)[0] > 0 else (lo, mid)
    turn = 0.5 * (lo + hi)
    h = np.linspace(turn, top, RETRACTION_ROWS)
    retract = load(h, turn)
    work = K * sigma * float(np.sum(np.diff(h) * 0.5 * (np.maximum(-retract[1:], 0) +
                                                         np.maximum(-retract[:-1], 0))))  # fmt: skip
    return turn, max(-float(retract.min()), 0.0), work


def design_map_cmd(out: str) -> list[str]:
    """The user's ``mcsim sweep`` of :data:`DESIGN_MAP` with ``--law jkr``."""
    vary = [x for k, v in DESIGN_MAP.items() for x in ("--vary", f"{k}={v}")]
    return [sys.executable, "-m", "mcsim", "sweep", "--surface", "smooth", "--material",
            "silicon", "--law", "jkr", *vary, "--out", out, "--overwrite", "--quiet"]  # fmt: skip


def design_map(repeats: int, cache: str) -> dict:
    """Issue 23: points per second of the design map, mcsim against the baseline, one process.

    In this process, alternately (so that the machine's load reaches both alike):
    the baseline on every 100th point, ``mcsim.sweep`` of all 2000 points in memory, and
    the reference path (``gw_curves`` and ``adhesion_summary``, what a sweep computed per
    point before the fast path) on every 400th point. Then the command
    :func:`design_map_cmd` as a whole process (start-up, import, kernel loading, file
    writing and exit included; an untimed first run fills the caches).
    """
    import warnings

    from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
    from mcsim.physics.analytic import gw_curves
    from mcsim.studies.sweeps import DEFAULT_H
    from mcsim.studies.sweeps import sweep as run_sweep

    warnings.simplefilter("ignore", RegimeWarning)
    sigma, gamma = design_points()
    t0 = time.perf_counter()
    run_sweep(SURFACE, MATERIAL, {"sigma": "1nm,2nm"}, law="jkr", workers=1)  # load the kernel
    first = time.perf_counter() - t0

    def reference(i: int) -> None:
        s = dataclasses.replace(SURFACE, sigma=sigma[i])
        m = dataclasses.replace(MATERIAL, gamma=gamma[i])
        gw_curves(s, m, np.asarray(DEFAULT_H), "jkr")
        adhesion_summary(s, m, "jkr")

    t = {"baseline": np.inf, "mcsim": np.inf, "reference": np.inf, "baseline_cpu": np.inf}
    base_points, ref_points = range(0, sigma.size, 100), range(0, sigma.size, 400)
    for _ in range(repeats):
        t["baseline"] = min(t["baseline"], best_of(1, lambda: [design_baseline(sigma[i], gamma[i])
                                                                for i in base_points])[0])  # fmt: skip
        t["baseline_cpu"] = min(t["baseline_cpu"], best_of(1, lambda: [design_baseline(sigma[i], gamma[i])
                                                                        for i in base_points],
                                                            clock=time.process_time)[0])  # fmt: skip
        wall, result = best_of(1, lambda: run_sweep(SURFACE, MATERIAL, DESIGN_MAP, law="jkr"))
        t["mcsim"] = min(t["mcsim"], wall)
        t["reference"] = min(t["reference"], best_of(1, lambda: [reference(i) for i in ref_points])[0])  # fmt: skip
    base = [design_baseline(sigma[i], gamma[i]) for i in base_points]
    po = result.data["pull_off"].ravel()
    rel = [abs(b[1] / po[i] - 1) for b, i in zip(base, base_points) if po[i] > 1e-12]
    env = {**os.environ, "MCSIM_CACHE_DIR": cache}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    walls, cpus = [], []
    with tempfile.TemporaryDirectory() as tmp:
        cmd = design_map_cmd(os.path.join(tmp, "map.h5"))
        for _ in range(repeats + 1):
            t0, c0 = time.perf_counter(), children_cpu()
            proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
            walls.append(time.perf_counter() - t0)
            cpus.append(children_cpu() - c0)
            if proc.returncode != 0:
                sys.exit(f"{shlex.join(cmd)} failed:\n{proc.stderr}")
    return {
        "points": int(sigma.size),
        "s_baseline": t["baseline"] / len(base_points),
        "s_reference": t["reference"] / len(ref_points),
        "s_mcsim": t["mcsim"] / sigma.size,
        "s_cli": min(walls[1:]) / sigma.size,
        "s_baseline_cpu": t["baseline_cpu"] / len(base_points),
        "s_cli_cpu": min(cpus[1:]) / sigma.size,
        "cli_walls": walls[1:],
        "first_call": first,
        "baseline_vs_mcsim": max(rel) if rel else math.nan,
        "load": os.getloadavg(),
    }


def children_cpu() -> float:
    """CPU time (user + system, s) of this process's finished children so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def design_map_lines(r: dict, repeats: int, checks: Checks) -> list[str]:
    """Report of :func:`design_map`."""
    rate = {k: 1 / r[f"s_{k}"] for k in ("baseline", "reference", "mcsim", "cli")}
    cmd = shlex.join(["mcsim", *design_map_cmd("MAP.h5")[3:]])
    cli = rate["cli"] / rate["baseline"]
    return [
        f"Analytic design map (issue 23): `{cmd}`, {r['points']} points (curves at 51 h, "
        "regime numbers, zero-load turn, pull-off located to 1e-8 in h, work of separation, "
        "hysteresis). Points per second, best of "
        f"{repeats}, each measured alternately in one process (load average "
        "{:.2f} {:.2f} {:.2f} at its end; the machine is shared):".format(*r["load"]),
        "",
        "| path | s per point | points/s | vs baseline |",
        "|---|---:|---:|---:|",
        f"| NumPy baseline ({BASELINE_NODES} height nodes, {BISECTION_STEPS}-step bisection "
        f"for a, {RETRACTION_ROWS} retraction rows) | {r['s_baseline']:.4f} | "
        f"{rate['baseline']:.1f} | 1 (reference) |",
        f"| mcsim reference path (`gw_curves` + `adhesion_summary` per point) | "
        f"{r['s_reference']:.4f} | {rate['reference']:.1f} | "
        f"{rate['reference'] / rate['baseline']:.1f}× |",
        f"| mcsim `sweep()` in process (fast path, kernel loaded) | {r['s_mcsim']:.5f} | "
        f"{rate['mcsim']:.0f} | {rate['mcsim'] / rate['baseline']:.0f}× |",
        f"| `mcsim sweep` whole process (start-up, imports, kernel, file) | {r['s_cli']:.5f} | "
        f"{rate['cli']:.0f} | {cli:.0f}× |",
        "",
        "- "
        + checks.judge(
            cli >= SPEEDUP_DESIGN_MAP,
            f"whole process ≥ {SPEEDUP_DESIGN_MAP:g}× "
            f"the baseline per point: **{cli:.0f}×** (runs: "
            f"{', '.join(f'{w:.2f}' for w in r['cli_walls'])} s for {r['points']} points)",
            timing=True,
        ),
        f"- CPU time (user + system, less sensitive to the other jobs on the machine): "
        f"baseline {r['s_baseline_cpu']:.4f} s per point, whole process "
        f"{r['s_cli_cpu']:.5f} s per point (both threads): "
        f"**{r['s_baseline_cpu'] / r['s_cli_cpu']:.0f}×**",
        f"- check: the baseline's grid pull-off is within {r['baseline_vs_mcsim']:.1e} "
        "(relative) of mcsim's at its points (51 rows, 4000 nodes: its own error)",
        f"- first `sweep()` call of the process (kernel loaded from the disk cache): "
        f"{r['first_call']:.2f} s",
    ]


def agreement(base: dict, mc: dict) -> tuple[float, int]:
    """Largest |z| between the baseline's and mcsim's sums of P, F, T over the separations.

    The two are independent draws of the same N summits, so their difference has
    standard error √2 · SE, with SE² = N·Var(x) estimated from mcsim's sums of squares.
    """
    b = np.array(base["sums"])
    m = np.array(mc["sums"])
    n = base["n"]
    zs = []
    for col, sq in ((1, 4), (2, 5), (3, 6)):
        var = m[:, sq] / n - (m[:, col] / n) ** 2
        se = np.sqrt(2 * n * np.maximum(var, 0))
        ok = se > 0
        zs.append((b[ok, col] - m[ok, col]) / se[ok])
    z = np.concatenate(zs)
    return float(np.max(np.abs(z))), z.size


def law_table(laws: dict, n: float, repeats: int) -> list[str]:
    """Markdown rows of :func:`law_costs`: cost per contacting and per force-carrying pair."""
    seed = {kind: laws[f"seed, {kind}"] for kind in ("approach", "cycle")}
    lines = [
        "",
        f"Kernel cost per pair of each registered law set (`block_sums`, one patch of "
        f"N = {n:.0e}, {SWEEP_LABEL['full']}; a cycle adds the retraction rows; best of "
        f"{repeats}, CPU time of the thread). Target (issue 10, not a test): cost per "
        "contacting pair within 2× of "
        "the seed's. Force-carrying pairs are those the kernel evaluates (above the row's "
        "threshold): the contacting pairs, plus for dmt the summits out of contact that feel "
        "the van der Waals attraction (down to the cutoff gap); for the other sets the two "
        "are the same.",
        "",
        "| law set, rows | contacting pairs | force-carrying pairs | ns per contacting pair "
        "| × seed | ns per force-carrying pair | × seed |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for key, v in laws.items():
        base = seed[key.split(", ")[1]]
        cost, cost_eval = v["t"] / v["contacts"], v["t"] / v["evaluated"]
        ratio = cost / (base["t"] / base["contacts"])
        ratio_eval = cost_eval / (base["t"] / base["evaluated"])
        mark = "" if key.startswith("seed") else (" (≤ 2×)" if ratio <= 2.0 else " (> 2×)")
        lines.append(
            f"| {key} | {v['contacts']:.3e} | {v['evaluated']:.3e} | {cost * 1e9:.2f} | "
            f"{ratio:.2f}{mark} | {cost_eval * 1e9:.2f} | {ratio_eval:.2f} |"
        )
    return lines


def report(res: dict, info: dict, args: argparse.Namespace, n: float, n_big: float,
           checks: Checks) -> list[str]:  # fmt: skip
    """The markdown report: table, targets, bounds, start-up and machine."""
    cores = info["cores"]
    lines = [
        f"Benchmark: seed law set, smooth surface, silicon, one patch of N summits (fixed count), "
        f"51 separations, one realization. Wall time = best of {args.repeats} (sampling "
        "included, numba compile excluded); pairs = contacting (summit, separation) "
        "evaluations; peak RSS = `ru_maxrss` of the case's own process.",
        "",
        "| case | N | sweep | wall (s) | pairs | pairs/s | vs baseline | peak RSS (MiB) | load |",
        "|---|---:|---|---:|---:|---:|---:|---:|---:|",
    ]

    def row(key: str, label: str, base: str | None) -> None:
        r = res.get(key)
        if r is None:
            return
        if base is None:
            ratio = "1 (reference)"
        else:
            ratio = f"{res[base]['wall'] / r['wall']:.1f}×" if base in res else "–"
        lines.append(
            f"| {label} | {r['n']:.0e} | {SWEEP_LABEL[r['sweep']]} | {r['wall']:.3f} | "
            f"{r['pairs']:.3e} | {r['pairs'] / r['wall']:.3e} | {ratio} | "
            f"{r['rss'] / MIB:.0f} | {r['load']:.2f} |"
        )

    for sw in ("full", "high"):
        row(f"baseline-{sw}", "NumPy baseline", None)
        row(f"mcsim1-{sw}", "mcsim, 1 worker", f"baseline-{sw}")
        row(f"mcsimall-{sw}", f"mcsim, {cores} workers", f"baseline-{sw}")
    row("baseline-big", "NumPy baseline", None)
    row("mcsim1-big", "mcsim streamed, 1 worker", "baseline-big")
    row("mcsimall-big", f"mcsim streamed, {cores} workers", "baseline-big")
    an = res["analytic"]
    lines.append(
        f"| analytic `gw_curves` (P, F, T, μ, N_c/N), best of 20 | – | 1000 h, 4 … −1 | "
        f"{an['wall']:.4f} | – | – | – | {an['rss'] / MIB:.0f} | {an['load']:.2f} |"
    )

    def speedup(key: str, base: str) -> float:
        return res[base]["wall"] / res[key]["wall"]

    lines += ["", "Targets (issue 5):", ""]
    for key, label in (("mcsim1", "1 worker"), ("mcsimall", f"{cores} workers")):
        s = speedup(f"{key}-full", "baseline-full")
        lines.append("- " + checks.judge(s >= SPEEDUP_FULL, f"mcsim {label} ≥ {SPEEDUP_FULL:g}× "
                                         f"the baseline, N = {n:.0e}, h = 4 … −1: {s:.1f}×", timing=True))  # fmt: skip
    for key, label in (("mcsim1", "1 worker"), ("mcsimall", f"{cores} workers")):
        s = speedup(f"{key}-high", "baseline-high")
        lines.append("- " + checks.judge(s >= SPEEDUP_HIGH, f"mcsim {label} ≥ {SPEEDUP_HIGH:g}× "
                                         f"the baseline, N = {n:.0e}, h = 4 … 2: {s:.1f}×", timing=True))  # fmt: skip
    for key, label in (("mcsim1", "1 worker"), ("mcsimall", f"{cores} workers")):
        rss = res[f"{key}-big"]["rss"]
        lines.append("- " + checks.judge(rss < RSS_STREAMED, f"peak RSS < 1 GB, N = {n_big:.0e} "
                                         f"streamed, {label}: {rss / 1e9:.3f} GB ({rss / MIB:.0f} MiB)"))  # fmt: skip
    lines.append("- " + checks.judge(an["wall"] < ANALYTIC_S, f"analytic curves at 1000 h < "
                                     f"{ANALYTIC_S * 1e3:g} ms: {an['wall'] * 1e3:.1f} ms", timing=True))  # fmt: skip

    sq = res["sqrt"]
    bound = sq["large"] / SQRT_PER_PAIR
    hw_bound = sq["compiled"] / SQRT_PER_PAIR
    parts = res["parts"]
    kernel_rate = parts["pairs"] / parts["t_kernel"]
    mc1 = res["mcsim1-full"]
    run_rate = mc1["pairs"] / mc1["wall"]
    base = res["baseline-full"]
    lines += [
        "",
        f"Arithmetic bound: `np.sqrt` on 10⁷ doubles (in place, best of 5): "
        f"{sq['large']:.3e} roots/s (on 32 768 doubles in cache: {sq['in_cache']:.3e}/s); "
        f"{SQRT_PER_PAIR} roots per pair, so {bound:.3e} pairs/s per core. A numba loop "
        f"compiled like the kernel (packed square roots, in cache) takes {sq['compiled']:.3e} "
        f"roots/s: the hardware bound is {hw_bound:.3e} pairs/s per core.",
        f"- mcsim, 1 worker, end to end (N = {n:.0e}, h = 4 … −1): {run_rate:.3e} pairs/s = "
        f"**{run_rate / bound:.2f}** of the sqrt-throughput bound "
        f"({run_rate / hw_bound:.2f} of the compiled-sqrt bound)",
        f"- kernel alone (`block_sums` on the same blocks): {kernel_rate:.3e} pairs/s = "
        f"**{kernel_rate / bound:.2f}** of the sqrt-throughput bound "
        f"({kernel_rate / hw_bound:.2f} of the compiled-sqrt bound)",
        "",
        f"Where one worker's time goes (N = {n:.0e}, h = 4 … −1, {parts['n_above']:.3e} summits "
        f"above h_min = −1, {parts['pairs']:.3e} pairs, best of {args.repeats}):",
        f"- sampling (`sample_block`, all blocks): {parts['t_sample']:.3f} s "
        f"({parts['t_sample'] / parts['n_above'] * 1e9:.1f} ns per summit); for scale, "
        f"`standard_normal({n:.0e})` alone: {parts['t_normal']:.3f} s",
        f"- kernel (`block_sums`, all blocks): {parts['t_kernel']:.3f} s "
        f"({parts['t_kernel'] / parts['pairs'] * 1e9:.2f} ns per pair)",
        f"- `run_sums(workers=1)`: {mc1['wall']:.3f} s (sampling + kernel = "
        f"{parts['t_sample'] + parts['t_kernel']:.3f} s)",
        f"- baseline: {base['wall']:.3f} s, of which sampling {base['t_sample']:.3f} s",
    ]
    for sw in ("full", "high"):
        zmax, count = agreement(res[f"baseline-{sw}"], res[f"mcsim1-{sw}"])
        lines.append("- " + checks.judge(zmax < Z_MAX, f"{SWEEP_LABEL[sw]}: baseline and mcsim sums "
                                         f"of P, F, T agree within their sampling error, max |z| = "
                                         f"{zmax:.2f} over {count} comparisons (bound < {Z_MAX:g})"))  # fmt: skip
    lines += law_table(res["laws"]["laws"], n, args.repeats)
    cold, cached = res["startup-cold"], res["startup-cached"]
    lines += [
        "",
        "Start-up (fresh process each, tiny run of 10³ summits, not in the timings above):",
        f"- cold (empty `MCSIM_CACHE_DIR`): first call {cold['t_first']:.2f} s, second "
        f"{cold['t_second'] * 1e3:.1f} ms: numba compile ≈ "
        f"{cold['t_first'] - cold['t_second']:.2f} s; whole process {cold['process']:.2f} s",
        f"- cached (kernel from the on-disk cache): first call {cached['t_first']:.2f} s, "
        f"second {cached['t_second'] * 1e3:.1f} ms; whole process {cached['process']:.2f} s",
        "",
        *end_to_end_lines(res, args.repeats, checks),
        "",
        *design_map_lines(res["designmap"], args.repeats, checks),
        "",
        f"Machine: {info['cpu']}, {cores} cores available (`os.sched_getaffinity`); "
        f"Python {info['python']}, NumPy {info['numpy']}, numba {info['numba']}. "
        "Load average (1, 5, 15 min) at start {:.2f} {:.2f} {:.2f}, at end {:.2f} {:.2f} {:.2f} "
        "(other jobs share this machine: the load column is the 1-min load at the end of "
        "each case).".format(*info["load"], *os.getloadavg()),
    ]
    return lines


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--full", action="store_true", help="also the baseline at N = 1e8 (≈6 GB)")
    p.add_argument("--repeats", type=int, default=3, help="timing repeats (default %(default)s)")
    p.add_argument("--only", choices=("end-to-end", "designmap"),
                   help="only this part: the whole-process timing of issue 12 (minutes), or "
                        "the analytic design map of issue 23 (a minute)")  # fmt: skip
    p.add_argument("--case", help=argparse.SUPPRESS)
    p.add_argument("--n", type=float, default=1e7, help=argparse.SUPPRESS)
    p.add_argument("--sweep", default="full", choices=SWEEPS, help=argparse.SUPPRESS)
    p.add_argument("--device", choices=("cpu", "cuda"), default="cpu",
                   help="cuda: the GPU backend against a bare CUDA kernel (benchmark_cuda.py)")  # fmt: skip
    args = p.parse_args()
    if args.device == "cuda":
        import benchmark_cuda

        benchmark_cuda.main(*((10**7, 10**6) if args.quick else ()))
        return
    if args.case:
        result = run_case(args.case, args.n, args.sweep, args.repeats, args.seed)
        if args.case == "laws":  # run alone, it shows its table (on stderr: stdout is JSON)
            print("\n".join(law_table(result["laws"], args.n, args.repeats)), file=sys.stderr)
        print(json.dumps(result))
        return
    args.out.mkdir(parents=True, exist_ok=True)
    checks = Checks(timing_judged=not args.quick)
    info = machine()
    print(f"machine: {info['cpu']}, {info['cores']} cores, load {info['load']}", flush=True)
    n, n_big = (1e6, 1e7) if args.quick else (1e7, 1e8)
    seed, seed_big = child_seeds(args.seed, 2)
    r = args.repeats
    r_big = 1 if args.quick else 2
    res: dict = {}
    n_end = N_END_TO_END / 10 if args.quick else N_END_TO_END
    if args.only == "designmap":
        with tempfile.TemporaryDirectory() as cache:
            lines = design_map_lines(design_map(r, cache), r, checks)
        lines += ["", f"Machine: {info['cpu']}, {info['cores']} cores available."]
        write([*lines, "", *checks.summary()], args, args.out / "benchmark-designmap.md")
        checks.exit()
    if args.only == "end-to-end":
        with tempfile.TemporaryDirectory() as cache:
            lines = end_to_end_lines(end_to_end(n_end, r, seed, cache), r, checks)
        load = (
            "Load average (1, 5, 15 min) at start {:.2f} {:.2f} {:.2f}, at end {:.2f} {:.2f} {:.2f}"
        )
        lines += ["", f"Machine: {info['cpu']}, {info['cores']} cores available. "
                  + load.format(*info["load"], *os.getloadavg())]  # fmt: skip
        write([*lines, "", *checks.summary()], args, args.out / "benchmark-end-to-end.md")
        checks.exit()
    with tempfile.TemporaryDirectory() as cache:
        res["startup-cold"] = spawn("startup", 1e3, "full", 1, seed, cache)
        res["startup-cached"] = spawn("startup", 1e3, "full", 1, seed, cache)
        res["sqrt"] = spawn("sqrt", 0, "full", 1, seed, cache)
        res["analytic"] = spawn("analytic", 0, "full", 1, seed, cache)
        for sw in ("full", "high"):
            for case in ("baseline", "mcsim1", "mcsimall"):
                res[f"{case}-{sw}"] = spawn(case, n, sw, r, seed, cache)
        res["parts"] = spawn("parts", n, "full", r, seed, cache)
        res["laws"] = spawn("laws", n, "full", r, seed, cache)
        if args.full:
            res["baseline-big"] = spawn("baseline", n_big, "full", 1, seed_big, cache)
        for case in ("mcsim1", "mcsimall"):
            res[f"{case}-big"] = spawn(case, n_big, "full", r_big, seed_big, cache)
        res |= end_to_end(n_end, r, seed, cache)  # after the cold start-up: the cache is warm
        res["designmap"] = design_map(r, cache)
    lines = report(res, info, args, n, n_big, checks)
    write([*lines, "", *checks.summary()], args, args.out / "benchmark.md")
    checks.exit()


def write(lines: list[str], args: argparse.Namespace, path) -> None:
    """Print the report and write it to ``path`` with the provenance as a header."""
    text = "\n".join(lines)
    print()
    print(text)
    prov = provenance(args)
    prov["mode"] = "quick" if args.quick else ("full" if args.full else "default")
    header = "".join(f"<!-- {k}: {v} -->\n" for k, v in prov.items())
    path.write_text(header + text + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
