"""``mcsim contact``: the exact elastic contact of a height map, beside GW's on the same map."""

from __future__ import annotations

import argparse
import warnings

from mcsim.cli.display import announce, print_lines, print_rows
from mcsim.cli.options import (
    FORMATS,
    add_environment,
    environment_of,
    positive_quantity,
    positive_values,
)

#: Unit of each printed column.
UNITS = {
    "pressure": "Pa", "area_fraction": "1 (A_r/A_n, exact)", "mean_gap": "m (exact)",
    "patches": "1 (count, exact)", "gw_area_fraction": "1 (A_r/A_n, GW)",
    "gw_mean_gap": "m (GW)", "vdw_pressure": "Pa (attractive, exact gaps)",
    "capillary_pressure": "Pa (attractive, exact gaps)",
    "external_pressure": "Pa (pressure - vdw - capillary)", "iterations": "1 (count)",
    "pixel_size": "m",
}  # fmt: skip


#: Unit of each printed column of ``--adhesion``.
ADHESION_UNITS = {
    "branch": "approach or retract", "position": "m (flat above the mean plane)",
    "mean_gap": "m (exact)", "pressure": "Pa (mean; compressive positive)",
    "area_fraction": "1 (A_r/A_n, exact)", "attractive_fraction": "1 (within the range)",
    "patches": "1 (count)", "iterations": "1 (count)",
}  # fmt: skip


def run_adhesion(args) -> int:
    """``mcsim contact MAP --adhesion``: the exact adhesive cycle beside GW's adhesion."""
    import dataclasses
    import json

    from mcsim.model.errors import ParameterError
    from mcsim.store.config import load_material
    from mcsim.store.outputs import check_output
    from mcsim.studies.maps.adhesivecontact import adhesive_contact

    if environment_of(args) is not None:
        raise ParameterError("--adhesion with an environment (--hamaker, --rh, ...) is not "
                             "available yet: the interaction law is the interface's adhesion")  # fmt: skip
    for path in (args.out, args.plot):  # refused before any work
        if path is not None:
            check_output(path, inputs=[args.file, *_counter(args)], overwrite=args.overwrite)
    material = load_material(args.material)
    pressure = positive_values(args.pressure, "pressure", "--pressure")
    if len(pressure) != 1:
        raise ParameterError(f"--pressure = {args.pressure!r}: with --adhesion give one pressure, "
                             "the non-adhesive load of the deepest position")  # fmt: skip
    quantity = {
        "w": positive_quantity(args.w, "energy_per_area", "--w"),
        "range_": positive_quantity(args.range, "length", "--range"),
        "pixel_size": positive_quantity(args.pixel_size, "length", "--pixel-size"),
    }  # fmt: skip
    if quantity["w"] is not None:  # refused by name, before the solves
        from mcsim.studies.maps.adhesioncalibration import check_inputs

        check_inputs(quantity["w"], quantity["range_"])
    with warnings.catch_warnings():  # the mesh's said once below (result.warnings()); the GW
        warnings.simplefilter("ignore", UserWarning)  # law sets' regimes are compared, not used
        result = adhesive_contact(
            args.file, material, pressure[0], law=args.interaction, steps=args.steps,
            counter=args.counter_surface,
            unit=args.unit, channel=args.channel, level=args.level, periodic=args.periodic,
            keep_fields=bool(args.out), progress=not args.quiet, subpixel=args.subpixel,
            **quantity,
            **({} if args.tol is None else {"tol": args.tol}),
        )  # fmt: skip
    table = result.columns()
    rows = [{c: (v[i].item() if hasattr(v[i], "item") else v[i]) for c, v in table.items()}
            for i in range(table["position"].size)]  # fmt: skip
    summary = result.summary()
    law = result.interaction
    if args.format == "json":
        print(json.dumps({
            "source": str(result.source), "dx_m": result.dx, "dy_m": result.dy,
            "periodic": result.periodic, "periodic_reason": result.periodic_reason,
            "E_star_Pa": result.E_star, "interaction": result.law_name, "w_J_m2": law.w,
            "range_m": law.range, "subpixel": result.subpixel, "units": {c: ADHESION_UNITS[c] for c in table},
            "summary": _json_ready(summary), "stickiness": _json_ready(dataclasses.asdict(result.stickiness)),
            "warnings": result.warnings(), **_facing_json(result), "rows": rows,
        }, indent=1, allow_nan=False))  # fmt: skip
    else:
        header = [
            _geometry(args, result),
            f"E* = {result.E_star / 1e9:.4g} GPa; exact adhesive contact: FFT boundary "
            f"elements, {result.law_name} law, w = {law.w:.4g} J/m^2, range {law.range * 1e9:.4g} "
            f"nm{_subpixel_text(result.subpixel)}; approach to the position where the "
            f"non-adhesive contact carries "
            f"{result.pressure:.4g} Pa, then retraction",
        ]
        print_rows(rows, list(table), args.format, header)
        if args.format == "csv":  # standard output stays one CSV table
            print_lines(_summary_lines(result, summary))
        else:
            print("\n".join(_summary_lines(result, summary)))
    print_lines([f"warning: {w}" for w in result.warnings()])
    from mcsim.figures.contact import adhesion_figure

    return _write(args, result, adhesion_figure)


def _subpixel_text(k: int) -> str:
    return f", the interaction over {k} x {k} points a pixel" if k > 1 else ""


def _write(args, result, figure) -> int:
    """The ``--out`` file and the ``--plot`` figure (``figure(result)``) of a contact result."""

    if args.out:
        announce(result.write(args.out, command=args.command_line, overwrite=args.overwrite),
                 quiet=args.quiet)  # fmt: skip
    if args.plot:
        from mcsim.figures.style import save

        announce(save(figure(result), args.plot, overwrite=args.overwrite, inputs=[args.file, *_counter(args)]),
                 quiet=args.quiet)  # fmt: skip
    return 0


def _counter(args) -> list:
    """The counter-surface's map as an input file (none without one)."""
    return [] if args.counter_surface is None else [args.counter_surface]


def _facing_json(result) -> dict:
    """The counter-surface's map and the measured correlation, for JSON (none without one)."""
    f = result.facing
    return {} if f is None else {"counter_surface": str(f.source), "correlation": f.correlation}


def _geometry(args, result) -> str:
    """The map's first header line: its pixels, levelling and periodicity, and why (and the
    counter-surface facing it)."""
    from pathlib import Path

    facing = "" if result.facing is None else f"counter-surface {result.facing.line()}; "
    return (f"{facing}{Path(args.file).name}: {result.shape[1]} x {result.shape[0]} pixels of "
            f"{result.dx * 1e9:.4g} x {result.dy * 1e9:.4g} nm, levelling {result.level}; "
            f"{'periodic' if result.periodic else 'not periodic (zero-padded)'}: "
            f"{result.periodic_reason}")  # fmt: skip


def _json_ready(value):
    """NaN as None, recursively (JSON has no NaN)."""
    if isinstance(value, dict):
        return {k: _json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_ready(v) for v in value]
    if isinstance(value, float) and value != value:
        return None
    return value


def _summary_lines(result, summary: dict) -> list[str]:
    """The cycle's numbers, GW's beside them with ratios, and the stickiness diagnostics."""
    c, s = result.cycle, result.stickiness
    lines = [
        f"exact: pull-off {summary['pull_off']:.4g} Pa, work of separation "
        f"{summary['work_of_separation']:.4g} J/m^2, hysteresis {summary['hysteresis']:.4g} J/m^2, "
        f"largest approach pressure {summary['max_pressure']:.4g} Pa; "
        f"{len(c.jumps)} jump(s)"
        + "".join(f"; {j.branch} {j.position_before * 1e9:.4g} -> {j.position_after * 1e9:.4g} nm"
                  for j in c.jumps),
        "GW on the same map, pressed to the same largest pressure (law, pull-off Pa, ratio to "
        "exact, work of separation J/m^2, ratio):",
    ]  # fmt: skip
    for law, g in summary["gw"].items():
        lines.append(f"  {law}: {g['pull_off']:.4g} Pa ({g['pull_off_ratio']:.3g}x), "
                     f"{g['work_of_separation']:.4g} J/m^2 ({g['work_ratio']:.3g}x)")  # fmt: skip
    lines.append(
        f"stickiness: Pastewka-Robbins {s.pr_parameter:.3g} ({'sticky' if s.sticky_pr else 'not sticky'}"
        f" below 1; range/g0 = {s.range_over_gap:.3g}), Persson-Tosatti U_el/(w A) = "
        f"{s.energy_ratio:.3g} ({'sticky' if s.sticky_pt else 'not sticky'} below 1), "
        f"Tabor (Muser) {s.tabor:.3g}, mesh {s.mesh:.3g} (< 0.5)"
    )  # fmt: skip
    return lines


def run(args) -> int:
    import json

    from mcsim.store.config import load_material
    from mcsim.store.outputs import check_output
    from mcsim.studies.maps.contact import contact_map

    if args.adhesion:
        return run_adhesion(args)
    for path in (args.out, args.plot):  # refused before any work
        if path is not None:
            check_output(path, inputs=[args.file, *_counter(args)], overwrite=args.overwrite)
    material = load_material(args.material)
    environment = environment_of(args)
    pixel = positive_quantity(args.pixel_size, "length", "--pixel-size")
    result = contact_map(
        args.file, material, positive_values(args.pressure, "pressure", "--pressure"), unit=args.unit, pixel_size=pixel, channel=args.channel,
        level=args.level, periodic=args.periodic, **({} if args.tol is None else {"tol": args.tol}), keep_fields=bool(args.out or args.plot),
        progress=not args.quiet, environment=environment, counter=args.counter_surface,
    )  # fmt: skip
    table = result.columns()
    rows = [{c: (int(v[i]) if v.dtype.kind == "i" else float(v[i])) for c, v in table.items()}
            for i in range(result.pressure.size)]  # fmt: skip
    geometry = _geometry(args, result)
    if args.format == "json":
        environment_json = (None if environment is None else
                            {k: v for k, v in vars(environment).items()})  # fmt: skip
        print(json.dumps({"source": str(result.source), "dx_m": result.dx, "dy_m": result.dy,
                          "environment": environment_json,
                          "periodic": result.periodic, "periodic_reason": result.periodic_reason,
                          "E_star_Pa": result.E_star, "tol": result.tol, **_facing_json(result),
                          "units": {c: UNITS[c] for c in table}, "rows": rows}, indent=1))  # fmt: skip
    else:
        s = result.surface
        header = [geometry,
                  f"E* = {result.E_star / 1e9:.4g} GPa; exact: FFT boundary elements, tolerance "
                  f"{result.tol:g}; GW: Hertz summits, sigma_s = {s.sigma * 1e9:.4g} nm, "
                  f"R = {s.R * 1e6:.4g} um, eta = {s.eta * 1e-12:.4g} um^-2 (direct route)",
                  "pressure Pa; area fractions A_r/A_n; mean gaps m (exact: mean of the gap field; GW: "
                  "the flat above the map's mean plane); exact numbers hold at this pixel size"]  # fmt: skip
        if environment is not None:
            e = environment
            header.append(
                f"environment on the exact gaps, per nominal area: Hamaker A = "
                f"{e.hamaker or 0:.4g} J ({e.retardation_label}), D0 = {e.cutoff * 1e9:.4g} nm, RH = {e.rh:.4g}, Laplace "
                f"pressure {e.laplace_pressure / 1e6:.4g} MPa on gaps from "
                f"{e.wet_floor * 1e9:.4g} nm to g_K = {e.condensation_gap * 1e9:.4g} nm (films "
                f"t = {e.film * 1e9:.4g} nm); the attraction does not deform the surface "
                "(DMT on the exact solve): external_pressure is what must be applied"
            )
        print_rows(rows, list(table), args.format, header)
    from mcsim.figures.contact import contact_figure

    return _write(args, result, contact_figure)


#: Most positions of ``--steps`` (a cycle needs tens; each is an exact solve of the map).
MAX_STEPS = 10_000


def _steps(text: str) -> int:
    if not text.isdigit() or not 2 <= int(text) <= MAX_STEPS:
        raise argparse.ArgumentTypeError(
            f"--steps = {text!r} is out of range (allowed: a whole number from 2 to {MAX_STEPS})"
        )
    return int(text)


def _subpixel(text: str) -> int:
    if not text.isdigit() or not 1 <= int(text) <= 16:
        raise argparse.ArgumentTypeError(f"--subpixel = {text!r} must be a whole number 1 ... 16")
    return int(text)


def add_parser(sub) -> None:
    p = sub.add_parser(
        "contact", help="exact elastic contact of a height map, beside GW",
        description="Solve the frictionless, non-adhesive contact of a height map against a rigid "
        "flat exactly (FFT boundary elements, Polonsky-Keer conjugate gradient) at each nominal "
        "pressure, and print beside it GW's answer on the same map (Hertz summits from the map's "
        "direct-route summit statistics, as mcsim ingest finds them). Columns: pressure (Pa); "
        "area_fraction, the real over nominal contact area; mean_gap (m); patches, the number of "
        "contact spots; gw_area_fraction and gw_mean_gap, the same from GW; iterations; pixel_size "
        "(m): the exact numbers depend on it. With an environment (--hamaker, --rh, ...): "
        "vdw_pressure and capillary_pressure (Pa), the attraction summed over the exact gap field "
        "pixel by pixel (gaps >= the cutoff D0; contacts excluded), and external_pressure = "
        "pressure - vdw - capillary (the attraction does not deform the surface).",
    )  # fmt: skip
    p.add_argument("file", help="height map (.gwy .ibw .nid .npy .xyz, text matrix)")
    p.add_argument(
        "--channel", help="channel of a multi-channel file (default: the height channel)"
    )
    p.add_argument("--unit", help="height unit if the file stores none (e.g. nm)")
    p.add_argument("--pixel-size", help="pixel size if the file stores none (e.g. 10nm)")
    p.add_argument("--counter-surface", metavar="MAP2",
                   help="a counter-surface's height map, measured face up, of the same size and "
                   "pixel size (read with the same --unit, --pixel-size, --channel): turned over "
                   "to face FILE (columns reversed, heights negated), the map solved, and GW's, "
                   "is their gap's topography, FILE - turned-over MAP2; the correlation of the "
                   "two maps' heights is printed")  # fmt: skip
    p.add_argument("--level", choices=("none", "plane", "poly2", "poly3", "poly4", "poly5"),
                   help="levelling before the solve (default: plane, or none on a periodic map; none "
                   "removes the mean only)")  # fmt: skip
    p.add_argument("--material", default="silicon",
                   help="preset or FILE.toml: its contact modulus E* (default: silicon)")  # fmt: skip
    p.add_argument("--pressure", required=True, metavar="SPEC",
                   help="nominal pressures: a list '1MPa,10MPa' or a range '1MPa:100MPa:5:log'")  # fmt: skip
    p.add_argument("--periodic", action=argparse.BooleanOptionalAction, default=None,
                   help="solve the map as periodic (--periodic) or zero-padded (--no-periodic); default: "
                   "periodic when opposite edges join (rms step across them < 1.5 x the rms "
                   "neighbour step), said in the output")  # fmt: skip
    p.add_argument("--tol", type=float,
                   help="solver tolerance: largest gap where loaded and largest overlap elsewhere, over the "
                   "rms height (default: 1e-6)")  # fmt: skip
    p.add_argument("--format", choices=FORMATS, default="table")
    p.add_argument(
        "--out", metavar="FILE.h5", help="write the pressure and gap fields of every load"
    )
    p.add_argument(
        "--plot",
        metavar="FILE.png",
        help="plot the contact map and A_r/A_n against p/E*, exact and GW",
    )
    p.add_argument("--overwrite", action="store_true", help="replace existing --out/--plot files")
    a = p.add_argument_group(
        "adhesive contact (--adhesion)",
        "the exact adhesive approach and retraction under displacement control (FFT boundary "
        "elements, a gap-dependent interaction law against a hard wall), beside GW's pull-off and "
        "work of separation for jkr, dmt and maugis-dugdale on the same map; --pressure then gives "
        "one pressure: the non-adhesive load of the deepest position",
    )  # fmt: skip
    a.add_argument("--adhesion", action="store_true", help="solve the adhesive cycle")
    a.add_argument("--interaction", choices=("exponential", "maugis-dugdale"),
                   default="exponential", help="the interaction law (default: exponential)")  # fmt: skip
    a.add_argument(
        "--w", metavar="W", help="work of adhesion, e.g. 0.1J/m^2 (default: the material's)"
    )
    a.add_argument("--range", metavar="L",
                   help="the law's range, e.g. 1nm (default: the material's z0)")  # fmt: skip
    a.add_argument("--steps", type=_steps, default=30,
                   help="positions of the flat on approach, revisited on retraction (default 30)")  # fmt: skip
    a.add_argument("--subpixel", type=_subpixel, default=1, metavar="K",
                   help="integrate the interaction over K x K points of each pixel (bilinear gap): "
                   "resolves a Maugis-Dugdale zone narrower than a pixel (short range, stiff "
                   "solids), at 1.5-3 (K = 4) to 12 (K = 8) times the cost; default 1, the pixel "
                   "centres")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no progress bar, no 'wrote FILE' line")
    add_environment(p)
    # the map is the surface: no --surface file holds an [environment] table here
    p.set_defaults(func=run, surface=None)
