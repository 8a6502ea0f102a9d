"""Pull-off force and work of separation of the paper's four surfaces under each law set.

For the four combined surfaces of Table 1 (rough, intermediate, smooth, super-smooth)
and silicon (z0 from the preset), every contact law set (``jkr``, ``dmt``,
``maugis-dugdale``, ``elastic-plastic``) is put through an approach–retraction cycle
on the analytic GW curves (:func:`mcsim.physics.adhesion.adhesion_summary`): the surfaces
rest under zero external load (the default turn), or, where the approach load is
never tensile (no adhesive rest), are pressed to h_turn = 0. Reported: the turn,
pull-off (force/(A_n K) and MPa) and its separation, work of separation and
hysteresis (mJ/m²), the fraction of summits in contact at the turn, the regime
numbers and the regime flags (Johnson–Greenwood map,
plasticity index), with what ``--law auto`` picks. Outputs ``adhesion_table.txt``
(also printed, a Markdown table) and ``adhesion_table.csv``.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL):

* ``jkr``: pull-off, work of separation and hysteresis at the table's turn against Fuller &
  Tabor's theory integrated independently (``jkr_quadrature.py``, adaptive quadrature over
  each asperity's contact radius): pull-off within 1e-9 relative (both sides are accurate
  to ~1e-12), the two works within 1e-7 relative: mcsim integrates them on 64 panels of 8
  Gauss–Legendre nodes, and its difference from the quadrature (up to 6.2e-8, hysteresis of
  the intermediate surface at h_turn = 0) falls to 6e-9 with 256 panels and 2e-10 with
  1024, so it is mcsim's rule that sets the bound; each plus an absolute 1e-12 η(3/2)πwR
  (times σ for the works) for the rows where both are ~0; and the zero-load rest within
  1e-9 in h where mcsim finds one (both solved to ≤ 1e-12);
* ``dmt``: no hysteresis (its load depends on the interference only, the same on approach
  and retraction): |hysteresis| ≤ 1e-9 × work of separation + 1e-12 η(3/2)πwRσ;
* ``--law auto`` picks the zone of the Johnson–Greenwood map its λ falls in (DMT < 0.1 <
  Maugis–Dugdale < 5 < JKR).

``maugis-dugdale`` and ``elastic-plastic`` are tabulated without an independent check here.
"""

from __future__ import annotations

import csv
import math
import warnings

from jkr_quadrature import JKRSurface
from reporting import Checks, parser, write_summary

from mcsim import gw_curves
from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.adhesion import (
    RegimeWarning,
    adhesion_summary,
    choose_law,
    maugis_parameter,
    regime_warnings,
)
from mcsim.physics.laws import get_law_set

LAWS = ("jkr", "dmt", "maugis-dugdale", "elastic-plastic")
FALLBACK_TURN = 0.0
#: Criteria (module docstring): relative bounds on the jkr pull-off and works, the absolute
#: bound in units of η(3/2)πwR (times σ for the works), the bound on the rest h.
RTOL_PULL_OFF, RTOL_WORK, ATOL, REST_TOL = 1e-9, 1e-7, 1e-12, 1e-9


def check_jkr(surface, material, summary, checks: Checks) -> None:
    """The jkr row against Fuller & Tabor's theory by quadrature at the same turn."""
    q = JKRSurface.of(surface, material)
    unit = q.eta * q.p_c
    turn = summary.turn * q.sigma
    pull_off = q.pull_off(turn)[0]
    work, hysteresis = q.works(turn)
    name = f"{surface.name}, jkr"
    for what, got, want, rtol, scale in (
        ("pull-off", summary.pull_off * material.K, pull_off, RTOL_PULL_OFF, unit),
        ("work of separation", summary.work_of_separation, work, RTOL_WORK, unit * q.sigma),
        ("hysteresis", summary.hysteresis, hysteresis, RTOL_WORK, unit * q.sigma),
    ):
        checks.at_most(f"{name}: |{what} - theory|/({rtol:g}|theory| + {ATOL:g} scale), "
                       f"theory {want:.6g}", abs(got - want) / (rtol * abs(want) + ATOL * scale), 1.0)  # fmt: skip
    if summary.turn_from.startswith("zero load"):
        rest = q.rest()
        diff = math.nan if rest is None else abs(rest / q.sigma - summary.turn)
        checks.at_most(f"{name}: |h_rest - theory's|", diff, REST_TOL)


def row(surface, material, law: str, checks: Checks) -> dict:
    flags = "; ".join(regime_warnings(surface, material, law)) or "in regime"
    out = {"surface": surface.name, "law": law, "flags": flags}
    if not get_law_set(law).retract:
        return out | {"turn": "n/a: approach only (no unloading law), non-adhesive"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        s = adhesion_summary(surface, material, law)
        turn = f"{s.turn:.4g} (zero load)"
        if s.turn_from.startswith("none"):  # no adhesive rest: nothing to pull off at rest
            s = adhesion_summary(surface, material, law, turn=FALLBACK_TURN)
            turn = f"{s.turn:.4g} (no adhesive rest)"
    if law == "jkr":
        check_jkr(surface, material, s, checks)
    if law == "dmt":
        scale = surface.eta * 1.5 * math.pi * material.gamma * surface.R * surface.sigma
        checks.at_most(f"{surface.name}, dmt: |hysteresis|/(1e-9 work + {ATOL:g} scale), work "
                       f"{s.work_of_separation:.4g} J/m^2",
                       abs(s.hysteresis) / (1e-9 * s.work_of_separation + ATOL * scale), 1.0)  # fmt: skip
    touching = gw_curves(surface, material, [s.turn], law).contact_fraction[0]
    return out | {
        "turn": turn,
        "contact_at_turn": f"{touching:.3g}",
        "pull_off": f"{s.pull_off:.4g}",
        "pull_off_MPa": f"{s.pull_off_pressure / 1e6:.4g}",
        "h_pull_off": f"{s.h_pull_off:.4g}",
        "work_mJ_m2": f"{s.work_of_separation * 1e3:.4g}",
        "hysteresis_mJ_m2": f"{s.hysteresis * 1e3:.3g}",
        "maugis_lambda": f"{s.maugis_lambda:.3g}",
        "theta": f"{s.adhesion_parameter:.3g}",
        "psi": f"{s.plasticity_index:.3g}",
    }


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    material = MATERIALS["silicon"]
    names = PAPER_SURFACES[2:] if args.quick else PAPER_SURFACES
    checks = Checks()
    rows = [row(SURFACES[n], material, law, checks) for n in names for law in LAWS]
    columns = ["surface", "law", "turn", "contact_at_turn", "pull_off", "pull_off_MPa", "h_pull_off", "work_mJ_m2",
               "hysteresis_mJ_m2", "maugis_lambda", "theta", "psi", "flags"]  # fmt: skip
    with open(args.out / "adhesion_table.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, restval="")
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {args.out / 'adhesion_table.csv'}")
    lines = [
        f"silicon: E* = {material.E_star / 1e9:.4g} GPa, w = {material.gamma} J/m^2, "
        f"z0 = {material.z0 * 1e9:g} nm, H = {material.H / 1e9:g} GPa",
        "pull_off = force/(A_n K); turn = closest approach h_turn = d_turn/sigma; "
        "contact_at_turn = N_c/N there (a rest in the far tail, N_c/N ~ 1e-15, means no contact "
        "in practice)",
        "",
        "| " + " | ".join(columns) + " |",
        "|" + "---|" * len(columns),
    ]
    lines += ["| " + " | ".join(r.get(c, "") for c in columns) + " |" for r in rows]
    lines.append("")
    for n in names:
        law, why = choose_law(SURFACES[n], material)
        lines.append(f"law auto for {n}: {why}")
        lam = maugis_parameter(SURFACES[n], material)
        zone = "dmt" if lam < 0.1 else "jkr" if lam > 5 else "maugis-dugdale"
        checks.holds(f"{n}: law auto picks the zone of lambda = {lam:.3g}", law == zone,
                     f"{law} (map: {zone})")  # fmt: skip
    lines += ["", *checks.summary()]
    write_summary(args.out / "adhesion_table.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()
