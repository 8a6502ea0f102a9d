"""Regenerate ``tests/data/seed_golden.npz``: the seed law set's numbers as mcsim 0.1 gave them.

Run once, from the commit that defines the reference (0.1, before the law-set
generalisation); ``tests/test_seed_golden.py`` then checks every later version bit for bit.
Not collected by pytest (no ``test_`` prefix).
"""

from pathlib import Path

import numpy as np

from mcsim.engine.kernels import block_sums
from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.physics.laws import SEED
from mcsim.studies.simulation import simulate
from mcsim.topography.empirical import Empirical

OUT = Path(__file__).parent / "data" / "seed_golden.npz"
H = np.linspace(4.0, -1.0, 11)


def empirical_surface():
    edges = np.array([-3.0, -1.5, -0.5, 0.0, 0.7, 1.5, 3.5]) * 1e-9
    heights = Empirical.from_histogram(edges, [4.0, 30.0, 40.0, 38.0, 20.0, 6.0])
    s = SURFACES["smooth"]
    return type(s)(sigma=heights.sigma, R=s.R, eta=s.eta, heights=heights, name="emp")


def cases():
    silicon = MATERIALS["silicon"]
    smooth = SURFACES["smooth"]
    out = {}
    for name in PAPER_SURFACES:
        c = gw_curves(SURFACES[name], silicon, H)
        out[f"analytic_{name}"] = np.stack([c.contact_fraction, c.P, c.F, c.T, c.mu])
    c = gw_curves(empirical_surface(), silicon, H)
    out["analytic_empirical"] = np.stack([c.contact_fraction, c.P, c.F, c.T, c.mu])
    for label, surface, count in (
        ("gaussian_poisson", smooth, "poisson"),
        ("gaussian_fixed", smooth, "fixed"),
        ("empirical_poisson", empirical_surface(), "poisson"),
    ):
        run = simulate(surface, silicon, H, 2e-10, realizations=3, seed=7, count=count)
        out[f"sums_{label}"] = run.sums
        out[f"N_{label}"] = run.n_summits
        for stat in ("mean", "se"):
            out[f"{stat}_{label}"] = np.stack(
                [getattr(run.summary, stat)[q] for q in run.summary.mean]
            )
    rng = np.random.default_rng(3)
    z = rng.standard_normal(5000) * smooth.sigma
    d = np.sort(H * smooth.sigma)[::-1]
    out["kernel_sums"] = block_sums(z, d, SEED, SEED.arguments(smooth, silicon))
    return out


if __name__ == "__main__":
    np.savez(OUT, **cases())
    print(f"wrote {OUT}")
