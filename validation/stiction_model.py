"""p_stick_model against brute force: where the saddlepoint model holds and where it fails.

For each case (smooth surface's R and η, jkr, silicon; a preload under force control, or
a common turn without one) the pads' pull-offs are simulated once (``mcsim.studies.pads.finite_pads``); p_stick at several
restoring forces is their fraction above it, with its Clopper-Pearson 95 % interval, beside
:func:`mcsim.studies.stiction.p_stick_model`; z = (p̂ − p_model)/√(p_model(1 − p_model)/n).
The model assumes many contacting summits (a compound-Poisson sum, linearised turn, the
extremum over a grid of separations by a Gaussian copula): it holds at hundreds of contacting summits and fails at ~10, where
a pad is decided by its tallest summits (the sweep warns there).

Run: ``python validation/stiction_model.py`` (about a minute on one core).
"""

import dataclasses
import math
import warnings

import numpy as np

from mcsim.engine import padcurves
from mcsim.engine.montecarlo import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import adhesion_summary
from mcsim.physics.loadcontrol import preload_turn
from mcsim.studies.pads import clopper_pearson
from mcsim.studies.stiction import p_stick_model

#: Turn d/σ of the pads without a preload (a common turn, no force control).
COMMON_TURN = 0.0
#: (σ m, area m², preload Pa or None: a common turn at COMMON_TURN, pads, restoring forces N)
CASES = [
    (1.4e-9, 30e-12, None, 400, (150e-6, 190e-6, 210e-6, 260e-6, 300e-6)),
    (1.4e-9, 30e-12, 5e6, 300, (100e-6, 150e-6, 200e-6, 250e-6)),
    (1.4e-9, 30e-12, 1e6, 300, (20e-6, 40e-6, 60e-6, 80e-6)),
    (2.5e-9, 30e-12, 1e6, 300, (5e-6, 20e-6, 40e-6, 60e-6)),
]


def main() -> None:
    warnings.simplefilter("ignore")
    material = MATERIALS["silicon"]
    print("| sigma nm | preload MPa | contacting | F_r uN | p_MC [95 %] | p_model | z |")
    print("|---|---|---|---|---|---|---|")
    for sigma, area, preload, pads, forces in CASES:
        surface = dataclasses.replace(SURFACES["smooth"], sigma=sigma)
        turn = COMMON_TURN if preload is None else preload_turn(surface, material, preload, "jkr")
        h_off = adhesion_summary(surface, material, "jkr", turn).h_pull_off
        spec = MonteCarloSpec(surface, material, np.linspace(4, -1, 51), area, pads, 1, "jkr", cycle=True)  # fmt: skip
        pull = []
        for r in range(pads):
            z = padcurves.patch_heights(spec, r)
            if preload is None:  # a common turn
                d_t = turn * surface.sigma
            else:  # force control
                d_t, _ = padcurves.force_turn(spec, z, preload * area)
            pull.append(padcurves.pull_off(spec, z, d_t)[0])
        pull = np.array(pull)
        contacting = surface.eta * area * float(surface.heights.sf(turn))
        for fr in forces:
            k = int(np.count_nonzero(pull > fr))
            lo, hi = clopper_pearson(k, pads)
            p = p_stick_model(spec, fr, turn=turn, h_pull_off=h_off, preload=preload)
            z_score = (k / pads - p) / math.sqrt(max(p * (1 - p), 1e-12) / pads)
            shown = "none" if preload is None else f"{preload / 1e6:g}"
            print(f"| {sigma * 1e9:.2f} | {shown} | {contacting:.0f} | {fr * 1e6:.0f} | {k / pads:.3f} "
                  f"[{lo:.3f}, {hi:.3f}] | {p:.3g} | {z_score:+.1f} |")  # fmt: skip


if __name__ == "__main__":
    main()
