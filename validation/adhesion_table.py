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
"""

from __future__ import annotations

import csv
import warnings

from reporting import parser, write_summary

from mcsim import gw_curves
from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary, choose_law, regime_warnings
from mcsim.physics.laws import get_law_set

LAWS = ("jkr", "dmt", "maugis-dugdale", "elastic-plastic")
FALLBACK_TURN = 0.0


def row(surface, material, law: str) -> dict:
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
    rows = [row(SURFACES[n], material, law) for n in names for law in LAWS]
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
        lines.append(f"law auto for {n}: {choose_law(SURFACES[n], material)[1]}")
    write_summary(args.out / "adhesion_table.txt", lines, args)


if __name__ == "__main__":
    main()
