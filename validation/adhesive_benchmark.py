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
When ContactEngineering's ``Adhesion`` and ``ContactMechanics`` (MIT; ``pip install -e
'.[crosscheck]'``) import, each exponential case's approach is also solved by their public
solver (``BoundedSmoothContactSystem.minimize_proxy``, SciPy's L-BFGS-B on the displacements,
in nm and GPa, to the same force balance: projected gradient ``TOL`` × (w/range) × ΔA,
``ftol`` 0), each position warm-started from the previous displacement, and timed next to
mcsim's approach (:func:`mcsim.physics.adhesivebem.follow`, warm-started) on the same map
and mean gaps; the ratio of the times is printed. Their q = 0 mode is a variable held by a
spring of stiffness π E*/L, so their ``offset`` is a rigid shift behind it: the offset of
mean gap d is p̄(d)/(π E*/L) − d, p̄(d) mcsim's mean pressure there, and their state lands
on d (the mean gap each reaches is printed). mcsim is then solved at the mean gaps they
reached (untimed) and the largest differences of mean pressure (per w/range) and gap (per
range) are printed, and where their solver stopped short, its message
(tests/physics/test_adhesive_crosscheck.py judges the agreement on a small map). SciPy's
L-BFGS-B calls BLAS at every iteration: on a shared machine run with
``OPENBLAS_NUM_THREADS=1`` (the header says what was set), else BLAS's threads wait on each
other and their times grow many-fold. Without the packages the script says so and goes on.
Criteria: every step converged; the full 5 nm exponential
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
NM, GPA = 1e-9, 1e9  # the public solver's units: lengths in nm, pressures in GPa


def positions(z: np.ndarray, dx: float, steps: int, top: float) -> np.ndarray:
    """Mean gaps from 3 ranges above the highest point to the gap of the non-adhesive contact
    at ``top`` (Pa), m, descending."""
    lowest = bem.solve_contact(z, dx, E_STAR, top, periodic=True).mean_gap
    return np.linspace(float((z - z.mean()).max()) + 3 * RANGE, lowest, steps)


def public_solver() -> tuple | None:
    """ContactEngineering's exponential law, bounded smooth system, periodic half-space and
    topography classes, or None when ``Adhesion`` or ``ContactMechanics`` does not import."""
    try:
        from Adhesion.Interactions import Exponential as TheirExponential
        from Adhesion.System import BoundedSmoothContactSystem
        from ContactMechanics import PeriodicFFTElasticHalfSpace
        from SurfaceTopography import Topography
    except ImportError:
        return None
    return TheirExponential, BoundedSmoothContactSystem, PeriodicFFTElasticHalfSpace, Topography


def their_approach(modules: tuple, z: np.ndarray, dx: float, d: np.ndarray,
                   pressures: np.ndarray) -> list[dict]:  # fmt: skip
    """Adhesion's approach through the mean gaps ``d`` (m), each position warm-started from the
    previous displacement (module docstring).

    Parameters
    ----------
    modules : tuple
        :func:`public_solver`'s classes.
    z : ndarray
        Heights, m (periodic, square pixels of ``dx`` m).
    dx : float
        Pixel size, m.
    d : ndarray
        Mean gaps, m, descending.
    pressures : ndarray
        mcsim's mean pressures there, Pa: they set the offsets behind the q = 0 spring.

    Returns
    -------
    list of dict
        Per position: the mean gap reached (m), the mean pressure (Pa), the gap field (m),
        the iterations, whether SciPy reported success, and its message.
    """
    their_law, system_class, half_space, topography = modules
    side = z.shape[0] * dx / NM
    substrate = half_space(z.shape, E_STAR / GPA, (side, side))
    system = system_class(substrate, their_law(W / (GPA * NM), RANGE / NM),
                          topography((z - z.mean()) / NM, (side, side), periodic=True))  # fmt: skip
    k0 = float(substrate.surface_stiffness[0, 0].real)  # π E*/L, GPa/nm
    options = {"gtol": adhesivebem.TOL * W / RANGE / GPA * (dx / NM) ** 2, "ftol": 0.0,
               "maxiter": adhesivebem.MAX_ITER}  # fmt: skip
    u, states = None, []
    for position, pressure in zip(d, pressures, strict=True):
        offset = pressure / GPA / k0 - position / NM
        result = system.minimize_proxy(offset=offset, initial_displacements=u, options=options)
        u = result.x
        states.append({"mean_gap": float(system.gap.mean()) * NM, "gap": system.gap * NM,
                       "pressure": system.compute_normal_force() / side**2 * GPA,
                       "iterations": int(result.nit), "success": bool(result.success),
                       "message": str(result.message)})  # fmt: skip
    return states


def crosscheck(modules: tuple, z: np.ndarray, dx: float, d: np.ndarray, law) -> list[str]:
    """Time mcsim's approach and Adhesion's on the same map and mean gaps; compare their states
    at the mean gaps Adhesion reached (module docstring). Returns the report's lines."""
    ours, seconds, _ = measured(
        lambda: list(adhesivebem.follow(z, dx, E_STAR, law, d, periodic=True))
    )
    pressures = np.array([s.mean_pressure for s in ours])
    theirs, their_seconds, _ = measured(lambda: their_approach(modules, z, dx, d, pressures))
    done = [s for s in theirs if s["success"]]
    again = list(adhesivebem.follow(z, dx, E_STAR, law, [s["mean_gap"] for s in done],
                                    periodic=True, keep_fields=True))  # fmt: skip
    dp = max((abs(a.mean_pressure - s["pressure"]) for a, s in zip(again, done, strict=True)),
             default=float("nan")) / law.max_traction  # fmt: skip
    dg = max((float(np.abs(a.gap_field - s["gap"]).max()) for a, s in zip(again, done, strict=True)),
             default=float("nan")) / law.range  # fmt: skip
    landed = max(abs(s["mean_gap"] - x) for s, x in zip(theirs, d, strict=True)) / law.range
    mine = [s.iterations for s in ours]
    their_iterations = [s["iterations"] for s in theirs]
    lines = [
        f"| mcsim (follow) | {seconds:.2f} | {np.mean(mine):.0f} (max {max(mine)}) | "
        f"{sum(s.converged for s in ours)} of {len(ours)} | 1 |",
        f"| Adhesion (minimize_proxy) | {their_seconds:.2f} | {np.mean(their_iterations):.0f} "
        f"(max {max(their_iterations)}) | {len(done)} of {len(theirs)} | "
        f"{their_seconds / seconds:.2f} |",
        "",
        f"Adhesion's mean gaps within {landed:.2g} range of mcsim's; at them (converged steps, mcsim "
        f"{sum(a.converged for a in again)} of {len(again)} converged) mean pressures within "
        f"{dp:.2g} w/range and gaps within {dg:.2g} range of mcsim's (tol {adhesivebem.TOL:g} each).",
    ]
    lines += [f"Adhesion stopped short at the mean gap {x * 1e9:.4g} nm: {s['message']}"
              for s, x in zip(theirs, d, strict=True) if not s["success"]]  # fmt: skip
    return lines


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
             f"({os.cpu_count()} CPUs); OPENBLAS_NUM_THREADS "
             f"{os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}", "",
             "| rms | law | mean gaps (nm) | time (s) | iterations/step | pull-off (MPa) | "
             "work of sep. (mJ/m^2) | hysteresis (mJ/m^2) | loop work (mJ/m^2) | jumps | converged | "
             "peak (MB) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]  # fmt: skip
    cases = [(5e-9, Exponential), (5e-9, MaugisDugdale), (1e-9, Exponential)]
    modules, compared = public_solver(), []
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
        if kind is Exponential and modules is not None:  # Adhesion has no smooth Dugdale law
            compared += ["", f"### {rms * 1e9:g} nm, exponential: approach through the {steps} mean gaps",
                         "", "| solver | time (s) | iterations/step | converged | time / mcsim's |",
                         "|---|---|---|---|---|", *crosscheck(modules, z, dx, d, law)]  # fmt: skip
    if modules is None:
        compared = ["", "ContactEngineering's Adhesion and ContactMechanics do not import: the "
                    "public solver is not timed (pip install -e '.[crosscheck]')."]  # fmt: skip
    lines += ["", "## Against ContactEngineering's Adhesion (public solver)", *compared]
    load_avg = os.getloadavg()
    lines += ["", f"load average after {load_avg[0]:.2f} {load_avg[1]:.2f} {load_avg[2]:.2f}", ""]
    lines += checks.summary()
    args.out.mkdir(parents=True, exist_ok=True)
    write_summary(args.out / "adhesive_benchmark.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
