"""Regenerate ``tests/data/seed_golden.npz``: the seed law set's numbers as mcsim 0.1 gave them.

Run once, from the commit that defines the reference (0.1, before the law-set
generalisation); ``tests/program/test_seed_golden.py`` then checks every later version against
them within the tolerances of its table. Not collected by pytest (no ``test_`` prefix).
"""

from pathlib import Path

import numpy as np

from mcsim.engine.kernels import block_sums
from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.physics.laws import SEED
from mcsim.studies.simulation import simulate
from mcsim.topography.empirical import Empirical

OUT = Path(__file__).parent / "data" / "seed_golden.npz"  # where the tests read it
H = np.linspace(4.0, -1.0, 11)
#: The Monte Carlo cases: patch area (m²), realizations, seed.
AREA, REALIZATIONS, ENTROPY = 2e-10, 3, 7


def empirical_surface():
    edges = np.array([-3.0, -1.5, -0.5, 0.0, 0.7, 1.5, 3.5]) * 1e-9
    heights = Empirical.from_histogram(edges, [4.0, 30.0, 40.0, 38.0, 20.0, 6.0])
    s = SURFACES["smooth"]
    return type(s)(sigma=heights.sigma, R=s.R, eta=s.eta, heights=heights, name="emp")


def monte_carlo_cases():
    """Label → (surface, count mode) of the Monte Carlo cases."""
    return {
        "gaussian_poisson": (SURFACES["smooth"], "poisson"),
        "gaussian_fixed": (SURFACES["smooth"], "fixed"),
        "empirical_poisson": (empirical_surface(), "poisson"),
    }


def monte_carlo(label, seed=ENTROPY):
    """The golden entries of one Monte Carlo case: ``sums_``, ``N_``, ``mean_``, ``se_``."""
    surface, count = monte_carlo_cases()[label]
    run = simulate(surface, MATERIALS["silicon"], H, AREA, realizations=REALIZATIONS,
                   seed=seed, count=count)  # fmt: skip
    out = {f"sums_{label}": run.sums, f"N_{label}": run.n_summits}
    for stat in ("mean", "se"):
        out[f"{stat}_{label}"] = np.stack([getattr(run.summary, stat)[q] for q in run.summary.mean])
    return out


def kernel_population():
    """Summit heights (m) and separations (m) of the ``kernel_sums`` case."""
    smooth = SURFACES["smooth"]
    z = np.random.default_rng(3).standard_normal(5000) * smooth.sigma
    return z, np.sort(H * smooth.sigma)[::-1]


def cases():
    silicon = MATERIALS["silicon"]
    smooth = SURFACES["smooth"]
    out = {}
    for name in PAPER_SURFACES:
        c = gw_curves(SURFACES[name], silicon, H)
        out[f"analytic_{name}"] = np.stack([c.contact_fraction, c.P, c.F, c.T, c.mu])
    c = gw_curves(empirical_surface(), silicon, H)
    out["analytic_empirical"] = np.stack([c.contact_fraction, c.P, c.F, c.T, c.mu])
    for label in monte_carlo_cases():
        out |= monte_carlo(label)
    z, d = kernel_population()
    out["kernel_sums"] = block_sums(z, d, SEED, SEED.arguments(smooth, silicon))
    return out


if __name__ == "__main__":
    np.savez(OUT, **cases())
    print(f"wrote {OUT}")
