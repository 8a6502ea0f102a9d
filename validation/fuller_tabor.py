"""Fuller & Tabor (1975) reproduced: rough-surface pull-off of JKR summits versus θ.

Greenwood–Williamson summits with Gaussian heights, each obeying exact JKR under fixed
penetration (law set ``jkr``): pressed to a closest approach h_turn, then pulled apart.
The pull-off force (the most tensile load on retraction, :func:`mcsim.physics.adhesion.adhesion_summary`)
is normalised by what the same summits would give if they all sat at one height,
N_turn · (3/2)πwR, N_turn = N·P(S > h_turn) the summits touched at the turn
((3/2)πwR is the least load on a JKR summit's stable branch), and plotted against the
adhesion parameter θ = E* σ^{3/2}/(R^{1/2} w) (:func:`mcsim.physics.adhesion.adhesion_parameter`),
varied through σ at the smooth surface's R and η, silicon's E* and w.

Fuller & Tabor's result: the normalised pull-off falls from 1 for θ → 0 to almost
nothing once the roughness is a few times the JKR range of one summit (θ ≳ 10): the
summits pulled apart together reach their own pull-off at different separations. The
text table adds the surfaces resting under zero external load, normalised by all N
summits. Outputs ``fuller_tabor.png`` and ``fuller_tabor.txt``.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
from reporting import parser, save_figure, write_summary

from mcsim import ParameterError
from mcsim.figures.adhesion import fuller_tabor_figure
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_parameter, adhesion_summary

TURNS = (0.0, 1.0, 2.0)


def normalised_pull_off(surface, material, turn: float | None, all_summits=False) -> float:
    """Pull-off / (N_turn (3/2)πwR), or / (N (3/2)πwR) with ``all_summits``.

    ``turn`` None: the surfaces resting under zero load; 0 where they do not stick.
    """
    try:
        s = adhesion_summary(surface, material, "jkr", turn=turn)
    except ParameterError:  # no separation of zero load: the surfaces do not stick
        return 0.0
    touched = 1.0 if all_summits else float(surface.heights.sf(s.turn))
    single = 1.5 * math.pi * material.gamma * surface.R
    return s.pull_off * material.K / (surface.eta * touched * single)


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    material = MATERIALS["silicon"]
    base = SURFACES["smooth"]
    theta = np.logspace(-1.5, 1.5, 9 if args.quick else 25)
    # σ from θ: θ = E* σ^{3/2}/(R^{1/2} w)
    sigma = (theta * math.sqrt(base.R) * material.gamma / material.E_star) ** (2 / 3)
    curves: dict[str, list[float]] = {f"h_turn = {t:g}": [] for t in TURNS}
    resting = []  # normalised by all N summits: few touch when the surfaces rest
    warnings.simplefilter("ignore", RegimeWarning)  # jkr outside its zone is the point here
    for s in sigma:
        surface = dataclasses.replace(base, sigma=float(s), name="")
        for t in TURNS:
            curves[f"h_turn = {t:g}"].append(normalised_pull_off(surface, material, t))
        resting.append(normalised_pull_off(surface, material, None, all_summits=True))
    check = [adhesion_parameter(dataclasses.replace(base, sigma=float(s)), material) for s in sigma]
    assert np.allclose(check, theta, rtol=1e-12)
    fig = fuller_tabor_figure(theta, {k: np.array(v) for k, v in curves.items()})
    save_figure(fig, args.out / "fuller_tabor.png", args)
    lines = [
        "Fuller-Tabor: normalised pull-off P_off/(N_turn 1.5 pi w R) of JKR summits vs theta",
        f"R = {base.R:g} m, eta = {base.eta:g} m^-2, E* = {material.E_star:g} Pa, "
        f"w = {material.gamma:g} J/m^2; sigma varied",
        "last column: resting under zero load, pull-off/(N 1.5 pi w R) over all N summits",
        "theta      sigma_nm  " + "  ".join(f"{k:>24}" for k in [*curves, "resting"]),
    ]
    for i, t in enumerate(theta):
        values = "  ".join(f"{curves[k][i]:24.6g}" for k in curves)
        lines.append(f"{t:<10.4g} {sigma[i] * 1e9:<9.4g} {values}  {resting[i]:24.6g}")
    write_summary(args.out / "fuller_tabor.txt", lines, args)


if __name__ == "__main__":
    main()
