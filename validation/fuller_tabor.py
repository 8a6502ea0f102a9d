"""Fuller & Tabor (1975) against mcsim: rough-surface pull-off of JKR summits versus θ.

Greenwood–Williamson summits with Gaussian heights, each obeying exact JKR under fixed
penetration (law set ``jkr``): pressed to a closest approach h_turn, then pulled apart.
mcsim's pull-off (the most tensile load on retraction of its analytic curves,
:func:`mcsim.physics.adhesion.adhesion_summary`) is normalised by what the same summits
would give if they all sat at one height, N_turn · (3/2)πwR, N_turn = N·P(S > h_turn) the
summits touched at the turn ((3/2)πwR is the most tensile load of one JKR summit's
fixed-grip curve, its pull-off under load control), and plotted against the adhesion
parameter θ = E* σ^{3/2}/(R^{1/2} w) (:func:`mcsim.physics.adhesion.adhesion_parameter`),
varied through σ at the smooth surface's R and η, silicon's E* and w. Fuller & Tabor's own
abscissa is σ/|δ_c| = θ^{2/3}/(¾π^{2/3}), δ_c = −¾(π²w²R/E*²)^{1/3}.

The reference is Fuller & Tabor's theory (their §2: GW asperities at one separation on a
rigid backing, so each asperity is held at fixed interference and follows its JKR curve
down to δ_c), integrated here by adaptive quadrature over each asperity's contact radius
(``jkr_quadrature.py``), independently of mcsim's closed-form inversion and Gauss–Legendre
rule. mcsim's ``jkr`` set models the same fixed-grip asperities, so like is compared with
like: the same turns (h_turn = 0, 1, 2, and the rest under zero load, whose separation
the quadrature finds on its own).

Criterion: |mcsim − theory| ≤ 1e-9 |theory| + 1e-12 for every normalised pull-off (the
quadrature's relative tolerance is 1e-11 and its absolute one 1e-14 P_c σ per panel; mcsim's
curves are accurate to ~1e-13), and the two zero-load rests within 1e-9 in h (both solved
to 1e-12). Outputs ``fuller_tabor.png`` and ``fuller_tabor.txt``.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
from jkr_quadrature import JKRSurface
from reporting import Checks, parser, save_figure, write_summary
from scipy import stats

from mcsim.figures.adhesion import fuller_tabor_figure
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_parameter, adhesion_summary

TURNS = (0.0, 1.0, 2.0)
#: Criterion on the normalised pull-off: |mcsim − theory| ≤ RTOL |theory| + ATOL (docstring).
RTOL, ATOL = 1e-9, 1e-12
#: Criterion on the zero-load rest h = d/σ (both sides solve it to ≤ 1e-12).
REST_TOL = 1e-9
COLUMNS = (*(f"h_turn = {t:g}" for t in TURNS), "resting")


def mcsim_row(surface, material) -> tuple[list[float], float]:
    """mcsim's normalised pull-offs at TURNS and at rest (resting: over all N summits, 0
    where the surfaces rest apart), and the rest h (NaN if none)."""
    single = 1.5 * math.pi * material.gamma * surface.R
    row = []
    for turn in (*TURNS, None):
        s = adhesion_summary(surface, material, "jkr", turn=turn)
        touched = float(surface.heights.sf(s.turn)) if turn is not None else 1.0
        row.append(s.pull_off * material.K / (surface.eta * touched * single))
    rested = not s.turn_from.startswith("none")
    return row, s.turn if rested else math.nan


def theory_row(surface, material) -> tuple[list[float], float]:
    """The same from Fuller & Tabor's theory by quadrature (``jkr_quadrature``)."""
    q = JKRSurface.of(surface, material)
    unit = q.eta * q.p_c
    row = [q.pull_off(t * q.sigma)[0] / (unit * stats.norm.sf(t)) for t in TURNS]
    rest = q.rest()
    row.append(0.0 if rest is None else q.pull_off(rest)[0] / unit)
    return row, math.nan if rest is None else rest / q.sigma


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    material = MATERIALS["silicon"]
    base = SURFACES["smooth"]
    theta = np.logspace(-1.5, 1.5, 5 if args.quick else 25)
    # σ from θ: θ = E* σ^{3/2}/(R^{1/2} w)
    sigma = (theta * math.sqrt(base.R) * material.gamma / material.E_star) ** (2 / 3)
    warnings.simplefilter("ignore", RegimeWarning)  # jkr outside its zone is the point here
    mc, ref, rest_mc, rest_ref = [], [], [], []
    for s in sigma:
        surface = dataclasses.replace(base, sigma=float(s), name="")
        row, rest = mcsim_row(surface, material)
        mc.append(row)
        rest_mc.append(rest)
        row, rest = theory_row(surface, material)
        ref.append(row)
        rest_ref.append(rest)
    mc, ref = np.array(mc), np.array(ref)
    check = [adhesion_parameter(dataclasses.replace(base, sigma=float(s)), material) for s in sigma]
    assert np.allclose(check, theta, rtol=1e-12)
    fig = fuller_tabor_figure(theta, {k: mc[:, j] for j, k in enumerate(COLUMNS[:-1])})
    save_figure(fig, args.out / "fuller_tabor.png", args)

    rel = np.abs(mc - ref) / np.where(ref > 0, ref, np.inf)
    lines = [
        "Fuller-Tabor: normalised pull-off P_off/(N_turn 1.5 pi w R) of JKR summits vs theta "
        "(mcsim; in brackets Fuller & Tabor's theory by quadrature)",
        f"R = {base.R:g} m, eta = {base.eta:g} m^-2, E* = {material.E_star:g} Pa, "
        f"w = {material.gamma:g} J/m^2; sigma varied",
        "resting: under zero load, pull-off/(N 1.5 pi w R) over all N summits; "
        "rel = largest |mcsim/theory - 1| of the row",
        "",
        "| θ | σ/(−δ_c) | σ (nm) | " + " | ".join(COLUMNS) + " | rel |",
        "|" + "---|" * (len(COLUMNS) + 4),
    ]
    for i, t in enumerate(theta):
        cells = " | ".join(f"{mc[i, j]:.6g} ({ref[i, j]:.6g})" for j in range(len(COLUMNS)))
        ft = t ** (2 / 3) / (0.75 * math.pi ** (2 / 3))
        lines.append(
            f"| {t:.4g} | {ft:.4g} | {sigma[i] * 1e9:.4g} | {cells} | {rel[i].max():.1e} |"
        )
    checks = Checks()
    excess = np.abs(mc - ref) / (RTOL * np.abs(ref) + ATOL)
    checks.at_most(f"max |mcsim - theory|/({RTOL:g}|theory| + {ATOL:g}), normalised pull-off, "
                   f"{mc.size} points", float(excess.max()), 1.0)  # fmt: skip
    d_rest = np.abs(np.array(rest_mc) - np.array(rest_ref))
    same_sides = np.array_equal(np.isnan(rest_mc), np.isnan(rest_ref))
    checks.at_most("max |h_rest mcsim - h_rest theory|, zero-load rest",
                   float(np.nanmax(d_rest)) if same_sides else math.nan, REST_TOL)  # fmt: skip
    lines += ["", *checks.summary()]
    write_summary(args.out / "fuller_tabor.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
