"""``mcsim adhesion``: pull-off, work of separation, hysteresis and regime numbers."""

from __future__ import annotations

import json
import math

from mcsim.cli.display import (
    announce,
    contact_inputs,
    cutoff_flag,
    cutoff_notes,
    describe_inputs,
    environment_notes,
    print_lines,
    print_rows,
    work_notes,
)
from mcsim.cli.options import (
    add_environment,
    add_inputs,
    add_preload,
    environment_of,
    inputs_of,
    resolve_law,
    turn_of,
)
from mcsim.model.errors import ParameterError

#: Keys of ``mcsim adhesion``, in order, with unit and meaning.
ADHESION_KEYS = {
    "pull_off": ("1", "pull-off force/(A_n K): most tensile load on retraction (magnitude)"),
    "h_pull_off": ("1", "separation d/sigma of the pull-off"),
    "pull_off_pressure": ("Pa", "pull-off force per nominal area"),
    "work_of_separation": ("J/m^2", "integral of the tensile load over d on retraction"),
    "hysteresis": ("J/m^2", "integral of (approach - retraction load) over d"),
    "tabor": ("1", "Tabor mu_T = (R w^2/(E*^2 z0^3))^(1/3)"),
    "maugis_lambda": ("1", "Maugis lambda = 2 sigma0 (R/(pi w K^2))^(1/3), sigma0 = w/(0.97 z0)"),
    "adhesion_parameter": ("1", "Fuller-Tabor theta = E* sigma^(3/2)/(R^(1/2) w)"),
    "plasticity_index": ("1", "psi = (E*/H) sqrt(sigma/R)"),
    "turn": ("1", "closest approach h_turn = d_turn/sigma before retraction"),
}

#: Keys added with an environment (--hamaker, --rh, ...), with unit and meaning.
ENVIRONMENT_KEYS = {
    "work_of_separation_contact": (
        "J/m^2",
        "contact part of work_of_separation (tensile contact load)",
    ),
    "work_of_separation_vdw": ("J/m^2", "van der Waals work from the turn to infinity"),
    "work_of_separation_capillary": ("J/m^2", "capillary work from the turn to infinity"),
    "kelvin_radius": ("m", "Kelvin radius r_K = gamma_L V_m/(R T ln(1/RH))"),
    "rq": ("m", "rms height about the mean plane used by the environment"),
    "summit_offset": ("m", "mean summit plane above the mean plane used by the environment"),
}


def run(args) -> int:
    import warnings

    from mcsim.physics.adhesion import RegimeWarning, adhesion_summary

    surface, material = inputs_of(args)
    law, notes = resolve_law(args, surface, material)
    environment = environment_of(args)
    notes += environment_notes(surface, environment, material=material)
    if environment is not None and args.plot:
        raise ParameterError("--plot: the figure shows the contact load only; drop the "
                             "environment options or --plot")  # fmt: skip
    if args.plot:
        from mcsim.store.outputs import check_output

        if not str(args.plot).endswith(".png"):
            raise ParameterError(
                f"--plot: {args.plot}: the figure is a PNG file, its name must end in .png"
            )
        check_output(args.plot, overwrite=args.overwrite)  # before the work, not after it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)  # printed once below (with validity)
        turn, preload = turn_of(args, surface, material, law, environment)
        summary = adhesion_summary(surface, material, law, turn=turn,
                                   environment=environment)  # fmt: skip
        if args.plot:
            from mcsim.figures.adhesion import adhesion_figure
            from mcsim.figures.style import save

            save(
                adhesion_figure(surface, material, law, summary),
                args.plot,
                overwrite=args.overwrite,
            )
    if args.plot:
        announce(args.plot, "approach and retraction loads", quiet=args.quiet)
    values = summary.to_dict()
    notes += [f"warning: {line}" for line in summary.validity]
    notes += work_notes(summary.work_of_separation)
    notes += cutoff_notes(surface, material, summary.law, summary.h_pull_off)
    flag = cutoff_flag(surface, material, summary)
    if flag:
        notes.append(f"warning: the pull-off of {summary.pull_off_pressure:.3g} Pa is {flag}")
    notes.append("note: the mean-field curves of an infinite surface (GW integrals); finite "
                 "pads scatter around them and may stick where the mean does not: "
                 "mcsim simulate --cycle + mcsim pads, or mcsim sweep --pads")  # fmt: skip
    turn_from = {"given": "given by --turn", "zero load on approach": "zero approach load"}.get(
        summary.turn_from, summary.turn_from
    )
    if preload is not None:
        turn_from = f"balances the preload {preload:.6g} Pa on the mean approach curve"
    print_lines(notes)
    keys = dict(ADHESION_KEYS)
    if environment is not None:
        keys |= ENVIRONMENT_KEYS
        keys["work_of_separation"] = ("J/m^2", "contact + vdw + capillary parts below")
        keys["pull_off"] = ("1", "pull-off/(A_n K): most tensile net load on retraction, contact "
                            "minus vdw and capillary attraction (magnitude)")  # fmt: skip
    if args.format == "json":
        out = {k: values[k] for k in keys}
        out |= {"turn_from": turn_from, "preload": preload, "law": summary.law,
                "pull_off_flag": flag}  # fmt: skip
        if environment is not None:
            out["heights_source"] = summary.heights_source
        clean = {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                 for k, v in out.items()}  # fmt: skip
        print(json.dumps(clean, indent=1, allow_nan=False))
        return 0
    rows = [{"quantity": k, "value": values[k], "unit": u, "meaning": m}
            for k, (u, m) in keys.items()]  # fmt: skip
    rows = [{**r, "value": math.nan if r["value"] is None else float(r["value"])} for r in rows]
    header = [*describe_inputs(surface, material), contact_inputs(material), f"law set {summary.law}; turn h_turn = "
              f"{summary.turn:.6g} ({turn_from})"]  # fmt: skip
    print_rows(rows, ["quantity", "value", "unit", "meaning"], args.format, header)
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("adhesion", help="pull-off force, work of separation, regime numbers",
                       description="Adhesion summary from the analytic curves: pull-off force and its separation, "
                       "work of separation and hysteresis of an approach-retraction cycle, and the Tabor, "
                       "Maugis, Fuller-Tabor and plasticity numbers. With an environment (--hamaker, --rh, ... or an "
                       "[environment] table) the net load includes the van der Waals and capillary attraction: "
                       "the turn, the pull-off and the work of separation include them, and the output adds "
                       "work_of_separation_contact, _vdw and _capillary (J/m^2), kelvin_radius, rq and "
                       "summit_offset (m).")  # fmt: skip
    add_inputs(p, separations=False, law="auto")
    add_environment(p)
    p.add_argument("--turn", metavar="H", help="closest approach d/sigma before retraction "
                   "(default: where the approach load is zero, resting under no external load)")  # fmt: skip
    add_preload(p, "instead of --turn, the turn is the separation that balances it on approach")
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--plot", metavar="FILE.png", help="also draw the approach and retraction load "
                   "curves with the pull-off marked and the work of separation shaded")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace an existing --plot file")
    p.add_argument("--quiet", action="store_true", help="no 'wrote FILE' line")
    p.set_defaults(func=run)
