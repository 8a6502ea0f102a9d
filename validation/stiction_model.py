"""p_stick_model against brute force: where the saddlepoint model holds and where it fails.

For each case (smooth surface's R and η, jkr, silicon; a preload under force control, or
a common turn without one) the pads' pull-offs are simulated once (``mcsim.studies.pads.finite_pads``); p_stick at several
restoring forces is their fraction above it, with its Clopper-Pearson 95 % interval, beside
:func:`mcsim.studies.stiction.p_stick_model`; z = (p̂ − p_model)/√(p_model(1 − p_model)/n).
The model assumes many contacting summits (a compound-Poisson sum, linearised turn, the
extremum over a grid of separations by a Gaussian copula): it holds at hundreds of contacting summits and fails at ~10, where
a pad is decided by its tallest summits (the sweep warns there).

Criterion (PASS/FAIL lines, exit status 1 on a FAIL): |z| < 5 at every restoring force of
the cases with at least MODEL_FROM = 100 contacting summits, where the model is claimed to
hold (the first two); at |z| < 5 a chance exceedance has probability 6e-7 per comparison.
The cases below (75 and 13 contacting summits) are printed, not judged: there the model is
known to fail. The full run then takes the first case again with 20 000 pads (RESOLVED),
printed, not judged: it resolves the model's own error, a tail that runs low by tens of
percent (validation/README.md).

Run: ``python validation/stiction_model.py`` (~3 min on one core, most of it the 20 000
pads; seed 1) or ``--quick`` (the two judged cases, 100 pads each). Writes
``stiction_model.txt``.
"""

import dataclasses
import math
import warnings

import numpy as np
from reporting import Checks, parser, write_summary

from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import adhesion_summary
from mcsim.physics.loadcontrol import preload_turn
from mcsim.studies.intervals import clopper_pearson
from mcsim.studies.stiction import p_stick_model

#: Turn d/σ of the pads without a preload (a common turn, no force control).
COMMON_TURN = 0.0
#: Contacting summits at the turn from which the model is judged (module docstring).
MODEL_FROM = 100
Z_MAX = 5.0
#: (σ m, area m², preload Pa or None: a common turn at COMMON_TURN, pads, restoring forces N)
CASES = [
    (1.4e-9, 30e-12, None, 400, (150e-6, 190e-6, 210e-6, 260e-6, 300e-6)),
    (1.4e-9, 30e-12, 5e6, 300, (100e-6, 150e-6, 200e-6, 250e-6)),
    (1.4e-9, 30e-12, 1e6, 300, (20e-6, 40e-6, 60e-6, 80e-6)),
    (2.5e-9, 30e-12, 1e6, 300, (5e-6, 20e-6, 40e-6, 60e-6)),
]
#: The first case again with 20 000 pads (full run only; printed with the ratio model/brute
#: force, not judged): enough pads to resolve the model's own error, which 400 do not.
RESOLVED = (1.4e-9, 30e-12, None, 20_000, (150e-6, 190e-6, 210e-6, 260e-6, 300e-6, 340e-6, 370e-6))


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.set_defaults(seed=1)
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore")
    material = MATERIALS["silicon"]
    checks = Checks()
    lines = ["| sigma nm | preload | contacting | pads | F_r uN | p_MC [95 %] | p_model | "
             "p_model/p_MC | z |", "|---|---|---|---|---|---|---|---|---|"]  # fmt: skip
    cases = [(*case[:3], 100, case[4]) for case in CASES[:2]] if args.quick else CASES
    for sigma, area, preload, pads, forces in cases + ([] if args.quick else [RESOLVED]):
        surface = dataclasses.replace(SURFACES["smooth"], sigma=sigma)
        turn = COMMON_TURN if preload is None else preload_turn(surface, material, preload, "jkr")
        h_off = adhesion_summary(surface, material, "jkr", turn).h_pull_off
        spec = MonteCarloSpec(surface, material, np.linspace(4, -1, 51), area, pads, args.seed,
                              "jkr", cycle=True)  # fmt: skip
        pull = []
        for r in range(pads):
            z = padload.patch_heights(spec, r)
            if preload is None:  # a common turn
                d_t = turn * surface.sigma
            else:  # force control
                d_t, _ = padcurves.force_turn(spec, z, preload * area)
            pull.append(padcurves.pull_off(spec, z, d_t)[0])
        pull = np.array(pull)
        contacting = surface.eta * area * float(surface.heights.sf(turn))
        worst = 0.0
        for fr in forces:
            k = int(np.count_nonzero(pull > fr))
            lo, hi = clopper_pearson(k, pads)
            p = p_stick_model(spec, fr, turn=turn, h_pull_off=h_off, preload=preload)
            z_score = (k / pads - p) / math.sqrt(max(p * (1 - p), 1e-12) / pads)
            shown = "none" if preload is None else f"{preload / 1e6:g} MPa"
            lines.append(f"| {sigma * 1e9:.2f} | {shown} | {contacting:.0f} | {pads} | {fr * 1e6:.0f} | "
                         f"{k / pads:.4g} [{lo:.4g}, {hi:.4g}] | {p:.3g} | {p / (k / pads):.3f} | "
                         f"{z_score:+.1f} |")  # fmt: skip
            worst = max(worst, abs(z_score))
        if contacting >= MODEL_FROM and pads < RESOLVED[3]:
            checks.at_most(f"sigma {sigma * 1e9:.2f} nm, preload {shown}, {contacting:.0f} "
                           f"contacting, {pads} pads: max |z| over {len(forces)} forces",
                           worst, Z_MAX)  # fmt: skip
    lines += ["", "z = (p_MC - p_model)/sqrt(p_model (1 - p_model)/pads); cases with fewer than "
              f"{MODEL_FROM} contacting summits are not judged", "", *checks.summary()]  # fmt: skip
    write_summary(args.out / "stiction_model.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
