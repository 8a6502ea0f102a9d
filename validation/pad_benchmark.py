"""Cost of one pad, dry and in humid air, against a plain NumPy evaluation of the same pad.

One pad is what ``mcsim pads`` and ``sweep --pads`` compute per pad: its turn under force
control (``padcurves.force_turn``), its exact pull-off (``pull_off``) and its work of
separation (``pad_work``). Cases, on the same summits (smooth surface, jkr, silicon, 30 µm²,
a preload of 1 MPa): dry, and humid (A = 1.6e-19 J, D0 = 0.2 nm, RH 0.7: every summit within
the caps' band edge u_c = D0 + 1/(2πRη) of the flat acts, not only those that touch). Each is
timed with the compiled kernel (``kernels.block_sums``) and with the NumPy reference
(``kernels.block_sums_numpy``, the straightforward baseline) in the same run; peak memory is
the process's maximum resident set.

Issue 30 asks a humid pad to cost at most 1.5× a dry one. Criteria (PASS/FAIL lines; the
timing ones INFO under ``--quick``): the humid pad's pull-off and work equal with both
evaluations (1e-9 relative, the kernel's rounding); peak RSS below 1 GB; humid/dry ≤ 1.5
(timing). Run: ``python validation/pad_benchmark.py`` (10 pads a case) or ``--quick`` (3).
"""

from __future__ import annotations

import resource
import time
import warnings

import numpy as np
from reporting import Checks, parser, write_summary

from mcsim.engine import kernels, padcurves
from mcsim.engine.montecarlo import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment

HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.7)
PRELOAD, AREA = 1e6, 30e-12
H = np.linspace(-2.0, 5.0, 8)
TARGET = 1.5


def one_pad(spec, r):
    z = padcurves.patch_heights(spec, r)
    d_t, _ = padcurves.force_turn(spec, z, PRELOAD * spec.area)
    return padcurves.pull_off(spec, z, d_t)[0], padcurves.pad_work(spec, z, d_t), z.size


def timed(spec, pads, numpy_baseline: bool):
    """Seconds per pad and the pads' (pull-off, work, summits), the kernel or NumPy."""
    original = padcurves.block_sums
    if numpy_baseline:
        padcurves.block_sums = kernels.block_sums_numpy
    try:
        one_pad(spec, pads)  # compile and warm up outside the timing
        start = time.perf_counter()
        out = [one_pad(spec, r) for r in range(pads)]
        return (time.perf_counter() - start) / pads, out
    finally:
        padcurves.block_sums = original


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore")
    pads = 3 if args.quick else 10
    checks = Checks(timing_judged=not args.quick)
    rows, seconds, results = [], {}, {}
    for name, env in (("dry", None), ("humid RH 0.7", HUMID)):
        spec = MonteCarloSpec(SURFACES["smooth"], MATERIALS["silicon"], H, AREA, pads + 1,
                              args.seed, "jkr", cycle=True, environment=env)  # fmt: skip
        for how, baseline in (("kernel", False), ("NumPy", True)):
            seconds[name, how], results[name, how] = timed(spec, pads, baseline)
        summits = np.mean([r[2] for r in results[name, "kernel"]])
        rows.append(f"| {name} | {summits:.0f} | {seconds[name, 'kernel'] * 1e3:.0f} | "
                    f"{seconds[name, 'NumPy'] * 1e3:.0f} | "
                    f"{seconds[name, 'NumPy'] / seconds[name, 'kernel']:.2g} |")  # fmt: skip
    kernel, numpy_ = (np.array(results["humid RH 0.7", k])[:, :2] for k in ("kernel", "NumPy"))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2  # GB (Linux: KiB)
    ratio = seconds["humid RH 0.7", "kernel"] / seconds["dry", "kernel"]
    lines = [f"# One pad (turn at {PRELOAD / 1e6:g} MPa, pull-off, work), {pads} pads a case", "",
             "| case | summits drawn | kernel (ms/pad) | NumPy (ms/pad) | NumPy/kernel |",
             "|---|---|---|---|---|", *rows, "",
             f"humid/dry with the kernel: {ratio:.3g}; peak RSS {peak:.3g} GB", ""]  # fmt: skip
    diff = float(np.max(np.abs(kernel - numpy_) / np.abs(numpy_)))
    checks.at_most("humid pads, kernel against NumPy: largest relative difference", diff, 1e-9)
    checks.at_most("peak RSS (GB)", peak, 1.0)
    checks.at_most("humid pad / dry pad, kernel time", ratio, TARGET, timing=True)
    lines += checks.summary()
    write_summary(args.out / "pad_benchmark.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
