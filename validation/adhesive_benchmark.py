"""Speed, memory and convergence of the adhesive FFT boundary-element solver on a rough map.

A periodic self-affine Gaussian map (Hurst exponent 0.8, 256 x 256 pixels over 10 µm, rms
height 5 nm, seeded; ``--quick``: 64 x 64 and 8 positions) meets a rigid flat with
E* = 100 GPa and w = 0.1 J/m², first under the exponential law of range 1 nm, then under
the Maugis–Dugdale law of the same w and range
(:func:`mcsim.physics.adhesivecycle.cycle`). The flat approaches through 30 mean gaps, from
3 ranges above the highest summit down to the mean gap of the non-adhesive contact at
350 MPa (``mcsim contact``'s largest load, :func:`mcsim.physics.bem.solve_contact`), then
retracts through the same positions. The same map scaled to an rms of 1 nm (where a public
solver failed on approach) must converge as well; its closest position is the gap at 70 MPa,
the same non-adhesive contact fraction (350 MPa there is full contact).

Reported per case: wall time, iterations per step, pull-off (Pa), work of separation and
hysteresis (work of separation less the approach's) and loop work ∮ p̄ dd (J/m²), jumps, whether every step converged, and the ``tracemalloc`` peak of
the cycle and of a cycle of half the positions (memory must not grow with the steps).
(ContactEngineering's ``Adhesion`` 0.93 is not timed here: on its periodic half-space the
mean displacement is a variable of its own, so its ``offset`` is not this mean-gap control;
see validation/README.md.) Criteria: every step converged; the full 5 nm exponential
cycle within 60 s (timing: INFO with ``--quick``); peak memory of the full cycle at most
1.2 times that of the half cycle. Run once with ``uptime`` noted: the machine is shared.
Outputs ``adhesive_benchmark.txt``.
"""

from __future__ import annotations

import os

import numpy as np
from contact_benchmark import measured, self_affine_map
from reporting import Checks, parser, write_summary

from mcsim.physics import adhesivebem, adhesivecycle, bem
from mcsim.physics.interactions import Exponential, MaugisDugdale, mesh_parameter

E_STAR = 1e11  # Pa
W = 0.1  # J/m²
RANGE = 1e-9  # m
SIZE = 10e-6  # m
TOP = 350e6  # Pa: the non-adhesive load that sets the closest position
TIME_TARGET = 60.0  # s, the 5 nm exponential cycle


def positions(z: np.ndarray, dx: float, steps: int, top: float) -> np.ndarray:
    """Mean gaps from 3 ranges above the highest point to the gap of the non-adhesive contact
    at ``top`` (Pa), m, descending."""
    lowest = bem.solve_contact(z, dx, E_STAR, top, periodic=True).mean_gap
    return np.linspace(float((z - z.mean()).max()) + 3 * RANGE, lowest, steps)


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    n, steps = (64, 8) if args.quick else (256, 30)
    dx = SIZE / n
    base = self_affine_map(n, SIZE, 5e-9, 0.8, np.random.default_rng(args.seed))
    checks = Checks(timing_judged=not args.quick)
    load_avg = os.getloadavg()
    lines = [f"map {n} x {n}, pixel {dx * 1e9:.4g} nm, Hurst 0.8, periodic; E* 100 GPa, w {W} J/m^2, "
             f"range {RANGE * 1e9:g} nm, mesh parameter {mesh_parameter(Exponential(W, RANGE), dx, E_STAR):.3f}; "
             f"{steps} mean gaps down to the gap at {TOP / 1e6:g} MPa and back; tol {adhesivebem.TOL:g}; "
             f"load average before {load_avg[0]:.2f} {load_avg[1]:.2f} {load_avg[2]:.2f} "
             f"({os.cpu_count()} CPUs)", "",
             "| rms | law | mean gaps (nm) | time (s) | iterations/step | pull-off (MPa) | "
             "work of sep. (mJ/m^2) | hysteresis (mJ/m^2) | loop work (mJ/m^2) | jumps | converged | "
             "peak (MB) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]  # fmt: skip
    cases = [(5e-9, Exponential), (5e-9, MaugisDugdale), (1e-9, Exponential)]
    for rms, kind in cases:
        z = base * (rms / 5e-9)
        d = positions(z, dx, steps, TOP * rms / 5e-9)  # the same contact fraction
        law = kind(W, RANGE)
        c, seconds, peak = measured(
            lambda z=z, d=d, law=law: adhesivecycle.cycle(
                z, dx, E_STAR, law, d, periodic=True, strict=False
            )
        )
        iterations = [s.iterations for s in c.approach + c.retraction]
        lines.append(
            f"| {rms * 1e9:g} nm | {kind.__name__} | {d[0] * 1e9:.3g} … {d[-1] * 1e9:.3g} | "
            f"{seconds:.1f} | {np.mean(iterations):.0f} (max {max(iterations)}) | "
            f"{c.pull_off / 1e6:.4g} | {c.work_of_separation * 1e3:.4g} | {c.hysteresis * 1e3:.3g} | "
            f"{c.loop_work * 1e3:.3g} | "
            f"{len(c.jumps)} | {c.converged} | {peak:.1f} |"
        )
        name = f"{rms * 1e9:g} nm, {kind.__name__}"
        checks.holds(f"{name}: every step converged", c.converged,
                     f"{2 * steps - len(c.failed)} of {2 * steps}")  # fmt: skip
        if rms == 5e-9 and kind is Exponential:
            checks.at_most(f"{name}: cycle time (s)", seconds, TIME_TARGET, timing=True)
            half = d[::2] if steps > 2 else d
            _, _, half_peak = measured(
                lambda half=half, z=z, law=law: adhesivecycle.cycle(
                    z, dx, E_STAR, law, half, periodic=True, strict=False
                )
            )
            checks.at_most(f"{name}: peak memory, {steps} against {len(half)} positions (ratio)",
                           peak / half_peak, 1.2)  # fmt: skip
    load_avg = os.getloadavg()
    lines += ["", f"load average after {load_avg[0]:.2f} {load_avg[1]:.2f} {load_avg[2]:.2f}", ""]
    lines += checks.summary()
    args.out.mkdir(parents=True, exist_ok=True)
    write_summary(args.out / "adhesive_benchmark.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
