"""The adhesive FFT-BEM sphere against Maugis–Dugdale's pull-off, λ = 0.1 … 5, on a grid sequence.

A paraboloid z = −r²/2R on n × n pixels (zero-padded, :func:`mcsim.physics.adhesivebem.follow`)
meets a rigid flat through the Dugdale law of Maugis' theory (``MaugisDugdale(w, h0)``,
h0 from λ); it is retracted under displacement control from Δ = 0.5 (a cold start in
contact) past Maugis' pull-off in steps of 0.1 in Δ (tolerance 1e-4 of w/h0), and its most
tensile load is compared with Maugis' load-controlled pull-off
(:func:`mcsim.physics.laws.maugis_dugdale.pull_off`; Maugis, J. Colloid Interface Sci. 150,
243, 1992): 2πwR as λ → 0, 1.5πwR as λ → ∞. Units as in tests/physics/test_adhesivebem.py:
R = 1 m, E* = 1 Pa, w such that A0 = (πwR²/K)^{1/3} = 0.1 m; loads in πwR.

Each λ runs on a grid sequence (pixel dx halved each time, the map's side fixed at
±HALF[λ] A0, enough to hold the Dugdale zone over the retraction) with the sub-pixel
quadrature of the interaction (``subpixel`` = k, φ at k × k points a pixel on the bilinear
interpolant of the gaps), and once with k = 1 (φ at the pixel centres, the default), whose
error is the lattice trapping of the zone. Each row gives the pixel, the Dugdale zone's
width at pull-off in pixels (C − A from Maugis' theory), the mesh parameter
√((w/h0²) dx/E*), the error of the pull-off and the CPU time. The observed order of the
error, log2(|e(n) − e(2n)| / |e(2n) − e(4n)|) over the three finest grids, is printed
(INFO), not judged: for λ ≤ 2 the quadrature's error is already a few tenths of a percent
on the coarsest grids, the size of the sampling below, so those orders measure noise; at
λ = 5 the errors fall cleanly (+1.96, +0.67, +0.14 % on 64², 128², 256²: order 1.3).
Sampling Maugis' curve at steps of 0.1 in Δ misses its minimum by at most 0.16 % (λ = 2),
printed per λ.

Criteria (PASS/FAIL, exit status 1 on a FAIL): at every λ the pull-off on the finest grid
with k = 4 (k = 8 is also shown at λ = 5) within 2 % of Maugis', and every solve converged.

Run: ``python validation/md_sphere.py`` (3 min of CPU on one core, half of it λ = 5 on
256² with k = 4; 16 min wall at load 15 on 2 cores) or ``--quick`` (λ = 0.5 and 2 on 32²
with k = 4, 1 s of CPU).
Writes ``md_sphere.txt``.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
from reporting import Checks, parser, write_summary
from scipy.optimize import brentq

from mcsim.physics import adhesivebem
from mcsim.physics.interactions import MaugisDugdale, mesh_parameter
from mcsim.physics.laws import maugis_dugdale as md

R, E_STAR, A0 = 1.0, 1.0, 0.1
K = 4 * E_STAR / 3
W = K * A0**3 / math.pi
DELTA_UNIT = A0**2 / R
FORCE_UNIT = math.pi * W * R
STEP, TOL, BOUND = 0.1, 1e-4, 0.02
#: Half the map's side per λ, in A0: the Dugdale zone's outer radius C stays inside it.
HALF = {0.1: 4.5, 0.5: 2.2, 1.0: 2.0, 2.0: 1.6, 5.0: 1.4}
#: Full run: (λ, grids with k = 4, grids with k = 8); every λ also on 64² with k = 1.
FULL = [
    (0.1, (32, 64, 128), ()),
    (0.5, (32, 64, 128), ()),
    (1.0, (32, 64, 128), ()),
    (2.0, (32, 64, 128), ()),
    (5.0, (64, 128, 256), (64, 128)),
]
QUICK = [(0.5, (32,), ()), (2.0, (32,), ())]


def sphere(lam: float, n: int):
    """The paraboloid on n × n pixels over ±HALF[λ] A0, its law, the flat's height at which
    the undeformed apex touches, and the map's side."""
    side = 2 * HALF[lam] * A0
    dx = side / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    z = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)
    law = MaugisDugdale(W, 2 * DELTA_UNIT / (math.pi * lam))  # h0/(π²w²R/K²)^{1/3} = 2/(πλ)
    return z, dx, law, -z.mean(), side


def pull_off_error(lam: float, n: int, k: int) -> tuple[float, bool, float]:
    """Relative error of the simulated pull-off, whether every solve converged, CPU s."""
    z, dx, law, apex, side = sphere(lam, n)
    deltas = np.arange(0.5, md.pull_off(lam)[1] - 0.25, -STEP)
    start = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the mesh criterion: its parameter is in the table
        steps = list(adhesivebem.follow(z, dx, E_STAR, law, apex - deltas * DELTA_UNIT,
                                        periodic=False, tol=TOL, subpixel=k))  # fmt: skip
    cpu = time.process_time() - start
    load = min(s.mean_pressure for s in steps) * side**2 / FORCE_UNIT
    return load / md.pull_off(lam)[0] - 1, all(s.converged for s in steps), cpu


def zone_width(lam: float) -> float:
    """C − A at Maugis' pull-off, in A0 (:func:`maugis_dugdale.contact_curve`)."""
    delta = md.pull_off(lam)[1]
    psi = brentq(lambda p: md.contact_curve(p, lam)[2] - delta, 1e-9, md.table(lam).psi_lo)
    a, _, _, c = md.contact_curve(psi, lam)
    return float(c - a)


def sampling_error(lam: float) -> float:
    """How far Maugis' own curve, sampled at the retraction's Δ, misses its minimum (relative)."""
    table = md.table(lam)
    deltas = np.arange(0.5, md.pull_off(lam)[1] - 0.25, -STEP)
    loads = []
    for delta in deltas[deltas >= table.delta_lo]:
        psi = brentq(lambda p, d=delta: md.contact_curve(p, lam)[2] - d, 1e-9, table.psi_lo)
        loads.append(float(md.contact_curve(psi, lam)[1]))
    return min(loads) / md.pull_off(lam)[0] - 1


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    checks = Checks()
    lines = ["| λ | map ±A0 | n | k | dx/A0 | zone/dx | mesh | pull-off error | CPU s |",
             "|---|---|---|---|---|---|---|---|---|"]  # fmt: skip
    orders = []
    for lam, grids, fine in QUICK if args.quick else FULL:
        runs = [(n, 4) for n in grids] + [(n, 8) for n in fine] + ([] if args.quick else [(64, 1)])
        errors, converged = {}, True
        for n, k in runs:
            error, ok, cpu = pull_off_error(lam, n, k)
            errors[n, k], converged = error, converged and ok
            _, dx, law, _, _ = sphere(lam, n)
            lines.append(f"| {lam:g} | {HALF[lam]:g} | {n} | {k} | {dx / A0:.4f} | "
                         f"{zone_width(lam) * A0 / dx:.2f} | {mesh_parameter(law, dx, E_STAR):.2f} | "
                         f"{100 * error:+.2f} % | {cpu:.1f} |")  # fmt: skip
            print(lines[-1], flush=True)
        finest = max(grids)
        checks.at_most(f"lambda = {lam:g}: |pull-off error| on {finest}^2, k = 4",
                       abs(errors[finest, 4]), BOUND, fmt=".4f")  # fmt: skip
        checks.holds(f"lambda = {lam:g}: every solve converged", converged,
                     f"{len(runs)} retractions")  # fmt: skip
        if len(grids) >= 3:
            e = [errors[n, 4] for n in grids[-3:]]
            order = math.log2(abs(e[0] - e[1]) / abs(e[1] - e[2]))
            orders.append(f"λ = {lam:g}, k = 4, {'/'.join(map(str, grids[-3:]))}: errors "
                          f"{', '.join(f'{100 * x:+.2f} %' for x in e)}, observed order "
                          f"{order:.2f}")  # fmt: skip
        orders.append(f"λ = {lam:g}: Maugis' curve sampled at steps of {STEP} in Δ misses its "
                      f"minimum by {100 * sampling_error(lam):+.3f} %")  # fmt: skip
    lines += ["", "zone: C − A at Maugis' pull-off; mesh: sqrt((w/h0^2) dx / E*); error: "
              "(simulated − Maugis)/Maugis of the pull-off", "", "## Grid convergence (INFO)",
              "", *orders, "", *checks.summary()]  # fmt: skip
    write_summary(args.out / "md_sphere.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
