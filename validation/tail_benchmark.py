"""Importance sampling of pads against brute force, its coverage, and its reach to p ≈ 1e-6.

The few-summit case of issue 31: the smooth surface's R and η at σ = 3 nm, jkr, silicon,
pads of 30 µm² (~510 summits, ~8.5 touching at the mean-field turn) pressed under force
control with 1 MPa. The saddlepoint model fails here (validation/stiction_model.py);
:func:`mcsim.studies.tail.importance_p_stick` is exact at any summit count.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL):

* **Unbiased:** at restoring forces where brute force reaches (p ≈ 1e-2 and 1e-3),
  |z| < 5 with z = (p_IS − p_BF)/√(se_IS² + se_BF²), se_BF = √(p(1 − p)/n) of the brute-force
  fraction of n plain pads (a chance exceedance: 6e-7 per comparison).
* **Coverage** (full run only): R repeated importance runs at p ≈ 1e-2 (independent
  seeds), each of the size ``sweep --pads`` and ``mcsim pads`` use (max(n, TAIL_PADS) final
  pads, stages of TAIL_PILOT, :func:`mcsim.studies.pads.tail_p_stick`). The brute-force p
  has an error of its own, comparable to a run's (6.7 % against 6–10 % at p ≈ 1e-2), so a
  run covers it when |p_IS − p_BF| ≤ 1.96·√(se_IS² + se_BF²), the 95 % interval of the
  difference; the fraction of runs that cover must be at least 0.95 − 2.3·√(0.95·0.05/R)
  (0.90 at R = 100, 0.858 at R = 30; 2.3 binomial standard errors below the nominal 95 %, a
  chance failure ~1 %). The fraction with the run's own interval alone is printed beside
  it. Every run counts, also those whose effective sample size stays below MIN_ESS, which
  ``sweep --pads`` would not report. The brute-force p carries its own error, which
  lowers the coverage a little: the criterion is conservative against the tail method.
* **Reach:** at p ≈ 1e-6, a relative half-width (high − low)/(2p) ≤ 0.2 from at most
  2·10⁴ pad evaluations, pilot stages included; the time per point is judged against 60 s
  on 2 cores in the full run (the machine's load, ``uptime``, is printed with it).

Run: ``python validation/tail_benchmark.py`` (~35 min on 2 cores under load: 2·10⁴
brute-force pads, 30 repeated runs, the 1e-6 point) or ``--quick`` (600 brute-force pads,
the 1e-2 comparison, a reach point of 200 final pads, judged on its evaluations, timing
not judged). Writes ``tail_benchmark.txt``.
"""

import dataclasses
import math
import os
import time
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from reporting import Checks, child_seeds, parser, write_summary

from mcsim.engine import padcurves
from mcsim.engine.montecarlo import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.loadcontrol import preload_turn
from mcsim.studies.pads import TAIL_PADS, TAIL_PILOT
from mcsim.studies.tail import Z95, importance_p_stick

SIGMA, AREA, PRELOAD = 3e-9, 30e-12, 1e6
H = np.linspace(4, -1, 51)
#: Restoring forces (N) at p ≈ 1e-2 and 1e-3 (measured by brute force) and p ≈ 6e-6.
F_2, F_3, F_6 = 55e-6, 83e-6, 110e-6
Z_MAX = 5.0
REL_HALF_WIDTH = 0.2
MAX_EVALUATIONS = 20_000
SECONDS_PER_POINT = 60.0
WORKERS = 2


def _spec(pads, seed):
    surface = dataclasses.replace(SURFACES["smooth"], sigma=SIGMA)
    return MonteCarloSpec(surface, MATERIALS["silicon"], H, AREA, pads, seed, "jkr", cycle=True)


def _brute_force(spec):
    """Every plain pad's pull-off (N), as ``sweep --pads`` evaluates them."""

    def one(r):
        z = padcurves.patch_heights(spec, r)
        d_t, _ = padcurves.force_turn(spec, z, PRELOAD * AREA)
        return padcurves.pull_off(spec, z, d_t)[0]

    with ThreadPoolExecutor(WORKERS) as pool:
        return np.array(list(pool.map(one, range(spec.realizations))))


def _z(e, k, n):
    p = k / n
    return (e.p_stick - p) / math.sqrt(e.se**2 + p * (1 - p) / n)


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.set_defaults(seed=1)
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore")
    checks = Checks(timing_judged=not args.quick)
    surface = dataclasses.replace(SURFACES["smooth"], sigma=SIGMA)
    turn = preload_turn(surface, MATERIALS["silicon"], PRELOAD, "jkr")
    n_bf, repeats = (600, 0) if args.quick else (20_000, 30)
    seeds = child_seeds(args.seed, 3 + repeats)
    lines = ["| F_r uN | brute force k/n [p] | importance p [95 %] | rel. se | ESS | evaluations | s | z |",
             "|---|---|---|---|---|---|---|---|"]  # fmt: skip
    t0 = time.perf_counter()
    force = _brute_force(_spec(n_bf, seeds[0]))
    t_bf = time.perf_counter() - t0
    lines.insert(
        0, f"brute force: {n_bf} pads in {t_bf:.0f} s ({1e3 * t_bf / n_bf:.1f} ms per pad)"
    )

    def tail(fr, seed, pads, pilot):
        t = time.perf_counter()
        e = importance_p_stick(_spec(pads, seed), fr, turn=turn, preload=PRELOAD, pads=pads,
                               pilot=pilot, workers=WORKERS)  # fmt: skip
        return e, time.perf_counter() - t

    compared = [(F_2, 400, 200)] if args.quick else [(F_2, 2000, 500), (F_3, 2000, 500)]
    for i, (fr, pads, pilot) in enumerate(compared):
        k = int(np.count_nonzero(force > fr))
        e, sec = tail(fr, seeds[1 + i], pads, pilot)
        z = _z(e, k, n_bf)
        lines.append(f"| {fr * 1e6:.0f} | {k}/{n_bf} [{k / n_bf:.3g}] | {e.p_stick:.3g} [{e.low:.3g}, "
                     f"{e.high:.3g}] | {e.se / e.p_stick:.3f} | {e.ess:.0f} | {e.evaluations} | "
                     f"{sec:.0f} | {z:+.2f} |")  # fmt: skip
        checks.at_most(f"F_r {fr * 1e6:.0f} uN: |z| of importance sampling against {n_bf} "
                       "brute-force pads", abs(z), Z_MAX)  # fmt: skip
    if repeats:
        p_bf = float(np.mean(force > F_2))
        se_bf = math.sqrt(p_bf * (1 - p_bf) / n_bf)
        runs = [tail(F_2, s, TAIL_PADS, TAIL_PILOT)[0] for s in seeds[3:]]
        covered = float(
            np.mean([abs(e.p_stick - p_bf) <= Z95 * math.hypot(e.se, se_bf) for e in runs])
        )
        own = float(np.mean([e.low <= p_bf <= e.high for e in runs]))
        bound = 0.95 - 2.3 * math.sqrt(0.95 * 0.05 / repeats)
        lines.append(f"coverage at F_r {F_2 * 1e6:.0f} uN: {covered:.3f} of {repeats} runs "
                     f"({TAIL_PADS} pads, pilot {TAIL_PILOT}) cover p_BF = {p_bf:.4g} "
                     f"(se {se_bf:.2g}) within 1.96 combined standard errors; {own:.3f} with "
                     "their own interval alone; p_IS/p_BF of the runs: "
                     f"{', '.join(f'{e.p_stick / p_bf:.2f}' for e in runs)}")  # fmt: skip
        checks.at_least(f"coverage of the 95 % interval over {repeats} runs", covered, bound)
    pads, pilot = (200, 200) if args.quick else (12_000, 1000)
    e, sec = tail(F_6, seeds[2], pads, pilot)
    half = (e.high - e.low) / (2 * e.p_stick) if e.p_stick > 0 else math.inf
    load = os.getloadavg()[0]
    lines.append(f"| {F_6 * 1e6:.0f} | - | {e.p_stick:.3g} [{e.low:.3g}, {e.high:.3g}] | "
                 f"{e.se / e.p_stick:.3f} | {e.ess:.0f} | {e.evaluations} | {sec:.0f} | - |")  # fmt: skip
    lines.append(f"reach: {e.stages} cross-entropy stages, {e.evaluations} evaluations, {sec:.0f} s "
                 f"on {WORKERS} threads, load average {load:.2f} (uptime)")  # fmt: skip
    if not args.quick:
        checks.at_most("p ~ 1e-6: relative half-width of the 95 % interval", half, REL_HALF_WIDTH)
    checks.at_most("p ~ 1e-6: pad evaluations", e.evaluations, MAX_EVALUATIONS)
    checks.at_most("p ~ 1e-6: seconds per point", sec, SECONDS_PER_POINT, timing=True)
    lines += ["", *checks.summary()]
    write_summary(args.out / "tail_benchmark.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
