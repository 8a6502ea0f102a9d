"""Speed and memory of ``mcsim contact``'s solver against a plain NumPy solver and ContactMechanics.

A periodic self-affine Gaussian map (Hurst exponent 0.8, 512 x 512 pixels over 10 µm, rms
height 5 nm; ``--quick``: 128 x 128) is pressed against a rigid flat at p/E* = 1e-4,
1.4e-3 and 1e-2, each solved cold to the same tolerance by:

* ``mcsim.physics.bem.solve_contact`` (real FFTs from ``scipy.fft`` on all cores);
* the straightforward NumPy version of the same Polonsky & Keer (1999) algorithm, written
  out below (complex ``numpy.fft``, one thread): the baseline the issue names;
* ContactEngineering's ContactMechanics, if installed (``constrained_conjugate_gradients``
  with its penetration tolerance set to the same fraction of the rms height).

Reported per load and solver: wall time, iterations, area fraction (the three must agree),
and the ``tracemalloc`` peak of the solve; then the warm-started sequence of all three
loads (:func:`mcsim.physics.bem.solve_loads`) and its peak, which does not grow with the
number of loads. Run once with ``uptime`` noted: the machine is shared. Outputs
``contact_benchmark.txt``.
"""

from __future__ import annotations

import os
import time
import tracemalloc

import numpy as np
from reporting import parser, write_summary

from mcsim.physics import bem

E_STAR = 1e11  # Pa
LOADS = (1e-4, 1.4e-3, 1e-2)  # p/E*
TOL = 1e-6


def self_affine_map(n: int, size: float, rms: float, hurst: float, rng) -> np.ndarray:
    """Periodic Gaussian heights, m, with PSD ∝ q^{-2(1+H)} from 2π/size to the pixel scale."""
    q = 2 * np.pi * np.hypot(*np.meshgrid(np.fft.fftfreq(n, size / n), np.fft.fftfreq(n, size / n)))
    amplitude = np.zeros_like(q)
    amplitude[q > 0] = q[q > 0] ** (-(1 + hurst))
    z = np.fft.ifft2(amplitude * np.fft.fft2(rng.standard_normal((n, n)))).real
    return z * rms / z.std()


def plain_numpy(z, dx, p0, tol):
    """Polonsky & Keer (1999) with the periodic Green's function 2/(E*|q|), plain complex NumPy FFTs."""
    n = z.shape[0]
    q = 2 * np.pi * np.hypot(*np.meshgrid(np.fft.fftfreq(n, dx), np.fft.fftfreq(n, dx)))
    q[0, 0] = np.inf
    green = 2 / (E_STAR * q)
    z = z - z.mean()
    scale = z.std()
    p = np.full(z.shape, p0)
    t = np.zeros_like(z)
    old, conjugate, iterations = 1.0, False, 0
    while True:
        g = np.fft.ifft2(green * np.fft.fft2(p)).real - z
        c = p > 0
        g -= g[c].mean()
        if max(np.abs(g[c]).max(), -g[~c].min(initial=0)) / scale <= tol:
            return p, iterations
        iterations += 1
        new = np.sum(g[c] ** 2)
        t = np.where(c, g + (new / old if conjugate else 0) * t, 0)
        old = new
        r = np.fft.ifft2(green * np.fft.fft2(t)).real
        r -= r[c].mean()
        tau = np.sum(g[c] * t[c]) / np.sum(r[c] * t[c])
        p = np.maximum(p - tau * t, 0)
        overlap = (p == 0) & (g < 0)
        conjugate = not overlap.any()
        p[overlap] -= tau * g[overlap]
        p *= p0 * p.size / p.sum()


def contact_mechanics(z, dx, p0, tol):
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization.ConstrainedConjugateGradients import (
        constrained_conjugate_gradients,
    )
    from SurfaceTopography import Topography

    n = z.shape[0]
    size = (n * dx, n * dx)
    r = constrained_conjugate_gradients(
        PeriodicFFTElasticHalfSpace((n, n), E_STAR, size), Topography(z, size, periodic=True),
        external_force=p0 * size[0] * size[1], pentol=tol * z.std(), maxiter=100000,
    )  # fmt: skip
    return r.jac / dx**2, r.nit


def measured(solve):
    """(result, seconds, tracemalloc peak in MB) of ``solve()``."""
    tracemalloc.start()
    start = time.perf_counter()
    result = solve()
    seconds = time.perf_counter() - start
    peak = tracemalloc.get_traced_memory()[1] / 1e6
    tracemalloc.stop()
    return result, seconds, peak


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    n = 128 if args.quick else 512
    size = 10e-6
    dx = size / n
    z = self_affine_map(n, size, 5e-9, 0.8, np.random.default_rng(args.seed))
    try:
        import ContactMechanics  # noqa: F401

        solvers = ("mcsim", "numpy", "ContactMechanics")
    except ImportError:
        solvers = ("mcsim", "numpy")
    load_avg = os.getloadavg()
    lines = [f"map {n} x {n}, pixel {dx * 1e9:.4g} nm, rms 5 nm, Hurst 0.8, periodic; tol {TOL:g}; "
             f"load average before {load_avg[0]:.2f} {load_avg[1]:.2f} {load_avg[2]:.2f} "
             f"({os.cpu_count()} CPUs)", "",
             "| p/E* | solver | time (s) | iterations | area fraction | peak (MB) |",
             "|---|---|---|---|---|---|"]  # fmt: skip
    for load in LOADS:
        p0 = load * E_STAR
        for name in solvers:
            if name == "mcsim":
                (s, seconds, peak) = measured(
                    lambda p0=p0: bem.solve_contact(z, dx, E_STAR, p0, periodic=True, tol=TOL)
                )
                field, iterations = s.pressure_field, s.iterations
            else:
                run = plain_numpy if name == "numpy" else contact_mechanics
                (field, iterations), seconds, peak = measured(
                    lambda p0=p0, run=run: run(z, dx, p0, TOL)
                )
            lines.append(f"| {load:g} | {name} | {seconds:.2f} | {iterations} | "
                         f"{np.mean(field > 0):.6f} | {peak:.0f} |")  # fmt: skip
    for count in (1, len(LOADS)):
        pressures = [x * E_STAR for x in LOADS[-count:]]

        def sequence(pressures=pressures):
            return [
                s.iterations
                for s in bem.solve_loads(z, dx, E_STAR, pressures, periodic=True, tol=TOL)
            ]

        iterations, seconds, peak = measured(sequence)
        lines.append(f"warm-started sequence of {count} load(s) up to 1e-2: {seconds:.2f} s, "
                     f"iterations {iterations}, peak {peak:.0f} MB")  # fmt: skip
    load_avg = os.getloadavg()
    lines.append(f"load average after {load_avg[0]:.2f} {load_avg[1]:.2f} {load_avg[2]:.2f}")
    args.out.mkdir(parents=True, exist_ok=True)
    write_summary(args.out / "contact_benchmark.txt", lines, args)


if __name__ == "__main__":
    main()
