"""``mcsim analytic``: the analytic GW curves, versus separation or load."""

from __future__ import annotations

import json
from pathlib import Path

from mcsim.cli.display import (
    announce,
    contact_inputs,
    cutoff_notes,
    describe_inputs,
    dimensional,
    environment_notes,
    print_lines,
    print_rows,
)
from mcsim.cli.options import (
    FORMATS,
    LOAD_UNITS,
    add_environment,
    add_inputs,
    add_preload,
    add_separations_or_loads,
    area_option,
    environment_of,
    inputs_of,
    parse_h,
    pressures_option,
    resolve_law,
    turn_of,
)
from mcsim.model.errors import ParameterError


def _load_control(args, surface, material, law: str, notes: list[str], environment) -> int:

    from mcsim.physics.loadcontrol import load_control

    area = area_option(args)
    inputs = [x for x in (args.surface, args.material) if x and Path(x).is_file()]
    if args.plot is not None:
        from mcsim.store.outputs import check_output

        if not str(args.plot).endswith(".png"):
            raise ParameterError(
                f"--plot: {args.plot}: the figure is a PNG file, its name must end in .png"
            )
        check_output(args.plot, inputs=inputs, overwrite=args.overwrite)
    pressure = pressures_option(args, area)
    result = load_control(surface, material, pressure, law, environment)
    if result.equilibrium.any():
        notes += cutoff_notes(surface, material, law, result.h[result.equilibrium])
    notes += [f"warning: {line}" for line in result.curves.validity_warnings()]
    table = result.columns()
    if area is not None:
        table["force_N"] = pressure * area
        table |= dimensional(result.curves, area)
    columns = list(table)
    rows = [{c: (bool(v[i]) if v.dtype == bool else float(v[i])) for c, v in table.items()}
            for i in range(pressure.size)]  # fmt: skip
    print_lines(notes)
    if result.equilibrium.size and not result.equilibrium.all():
        print_lines(["tensile load beyond the pull-off: no equilibrium (h undefined)"])
    if args.format == "json":
        clean = [{k: (None if isinstance(v, float) and v != v else v) for k, v in r.items()}
                 for r in rows]  # fmt: skip
        out = {"law": result.curves.law, "balanced": result.quantity, "K_Pa": material.K,
               "area_m2": area, "units": {c: LOAD_UNITS[c] for c in columns}, "rows": clean}  # fmt: skip
        print(json.dumps(out, indent=1, allow_nan=False))
    else:
        header = [*describe_inputs(surface, material), f"law set {result.curves.law}: pressure p (Pa) "
                  f"balances {result.quantity} = p/K on the approach branch (K = "
                  f"{material.K / 1e9:.4g} GPa)", "jump: reached through a jump of h; "
                  "equilibrium false: tensile beyond the pull-off"]  # fmt: skip
        print_rows(rows, columns, args.format, header)
    if args.plot is not None:
        from mcsim.figures.loadcontrol import load_control_figure
        from mcsim.figures.style import save

        save(load_control_figure(result), args.plot, overwrite=args.overwrite, inputs=inputs)
        announce(args.plot, "A_r/A_n against p/E* and friction against load", quiet=args.quiet)
    return 0


def run(args) -> int:
    from mcsim.physics.analytic import gw_curves

    surface, material = inputs_of(args)
    law, notes = resolve_law(args, surface, material)
    environment = environment_of(args)
    notes += environment_notes(surface, environment, material=material)
    if args.h is None:
        if args.branch != "approach" or args.turn is not None or args.preload is not None:
            raise ParameterError(
                "--branch/--turn/--preload: load control is on the approach branch only"
            )
        return _load_control(args, surface, material, law, notes, environment)
    if args.plot is not None:
        raise ParameterError("--plot applies to --pressure/--load only")
    if args.preload is not None and args.branch != "retract":
        raise ParameterError(
            "--preload sets the turn of the retraction: use it with --branch retract"
        )
    turn, preload = turn_of(args, surface, material, law, environment)
    if preload is not None:
        notes.append(f"note: retraction after h_turn = {turn!r}, the separation that "
                     f"balances the preload {preload:.6g} Pa on the mean approach curve")  # fmt: skip
    curves = gw_curves(surface, material, parse_h(args.h), law, branch=args.branch, turn=turn,
                       environment=environment)  # fmt: skip
    notes += cutoff_notes(surface, material, curves.law, curves.h)
    notes += [f"warning: {line}" for line in curves.validity_warnings()]
    table = curves.columns()
    area = area_option(args)
    if area is not None:
        table |= dimensional(curves, area)
    columns = list(table)
    rows = [{c: float(table[c][i]) for c in columns} for i in range(curves.h.size)]
    if curves.law == "seed":
        meaning = "dimensionless: P, F, T = force/(A_n K) (Eqs. 3, 5, 7); mu = T/(P+F) (Eq. 8), undefined where w = 0"
    else:
        meaning = ("dimensionless: load = net force/(A_n K), > 0 compressive; area = A_r/A_n; "
                   "friction = tau A_r/(A_n K); mu = friction/load, undefined where load <= 0")  # fmt: skip
    if environment is not None:
        meaning += ("; vdw, capillary = attraction per nominal area/K (> 0 attractive); load = "
                    + ("P - vdw - capillary" if curves.law == "seed" else "contact - vdw - capillary")
                    + ", the net load")  # fmt: skip
    header = describe_inputs(surface, material)
    if curves.law != "seed":
        header.append(contact_inputs(material))
        turn = (
            "" if curves.turn is None else f" after the closest approach h_turn = {curves.turn:g}"
        )
        if preload is not None:
            turn += f" (balances the preload {preload:.6g} Pa on the mean approach curve)"
        header.append(f"law set {curves.law}, branch {curves.branch}{turn}")
    header.append(meaning)
    print_lines(notes)
    print_rows(rows, columns, args.format, header)
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser(
        "analytic",
        help="analytic GW curves (Eqs. 1-8)",
        description="Analytic GW curves versus h = d/sigma (--h), or versus load: the separation on "
        "the approach branch that balances a nominal pressure p (--pressure, or --load with --area), "
        "p = load K. For the seed the balanced load is the paper's external force P (Eq. 3), "
        "P/(A_n K) = p/K; for the other law sets it is load = force/(A_n K). Where adhesion makes the "
        "load non-monotone the stable separation (reached by raising the load from zero) is reported "
        "and a jump on the way is flagged; a tensile load beyond the pull-off has no equilibrium. "
        "Units: pressure Pa; h, contact_fraction, load, area, friction, mu dimensionless as with --h "
        "(under load control the seed has an area column too: A_r/A_n of its Hertz summits, "
        "pi eta R sigma F_1(h), Greenwood & Williamson 1966); "
        "with --area also N_c, force_N (applied), load_N, friction_N, P_N, F_N, T_N (N) and area_m2 (m^2). "
        "With an environment (--hamaker, --rh, ... or an [environment] table) also vdw and capillary, "
        "the attraction per nominal area/K (> 0 attractive), and load is the net load: for the seed a "
        "column P - vdw - capillary, for the other law sets contact - vdw - capillary; --pressure and "
        "--load then balance this net load.",
    )
    add_inputs(p, separations=False)
    add_environment(p)
    add_separations_or_loads(p, "the curves' separations balance them")
    p.add_argument("--area", metavar="AREA", help="nominal area A_n, e.g. 1mm^2 (m^2 unless a unit "
                   "is given): adds dimensional columns (forces in N)")  # fmt: skip
    p.add_argument("--plot", metavar="FILE.png", help="with --pressure/--load: plot A_r/A_n versus "
                   "p/E* and friction versus load")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace an existing --plot file")
    p.add_argument("--branch", choices=("approach", "retract"), default="approach",
                   help="approach from far away (default) or retraction after --turn")  # fmt: skip
    p.add_argument("--turn", metavar="H", help="closest approach d/sigma before retraction "
                   "(default: the lowest --h)")  # fmt: skip
    add_preload(p, "with --branch retract, instead of --turn")
    p.add_argument("--format", choices=FORMATS, default="table")
    p.add_argument("--quiet", action="store_true", help="no 'wrote FILE' line")
    p.set_defaults(func=run)
