"""``mcsim contact``: the exact elastic contact of a height map, beside GW's on the same map."""

from __future__ import annotations

import argparse

from mcsim.cli.display import announce, print_rows
from mcsim.cli.options import FORMATS, add_environment, environment_of, parse_values

#: Unit of each printed column.
UNITS = {
    "pressure": "Pa", "area_fraction": "1 (A_r/A_n, exact)", "mean_gap": "m (exact)",
    "patches": "1 (count, exact)", "gw_area_fraction": "1 (A_r/A_n, GW)",
    "gw_mean_gap": "m (GW)", "vdw_pressure": "Pa (attractive, exact gaps)",
    "capillary_pressure": "Pa (attractive, exact gaps)",
    "external_pressure": "Pa (pressure - vdw - capillary)", "iterations": "1 (count)",
    "pixel_size": "m",
}  # fmt: skip


def run(args) -> int:
    import json
    from pathlib import Path

    from mcsim.model.units import parse_quantity
    from mcsim.store.config import load_material
    from mcsim.store.outputs import check_output
    from mcsim.studies.contact import contact_map
    from mcsim.studies.simulation import cli_command

    for path in (args.out, args.plot):  # refused before any work
        if path is not None:
            check_output(path, inputs=[args.file], overwrite=args.overwrite)
    material = load_material(args.material)
    environment = environment_of(args)
    pixel = (
        None
        if args.pixel_size is None
        else parse_quantity(args.pixel_size, "length", "--pixel-size")
    )
    result = contact_map(
        args.file, material, parse_values(args.pressure, "pressure", "--pressure"), unit=args.unit, pixel_size=pixel, channel=args.channel,
        level=args.level, periodic=args.periodic, **({} if args.tol is None else {"tol": args.tol}), keep_fields=bool(args.out or args.plot),
        progress=not args.quiet, environment=environment,
    )  # fmt: skip
    table = result.columns()
    rows = [{c: (int(v[i]) if v.dtype.kind == "i" else float(v[i])) for c, v in table.items()}
            for i in range(result.pressure.size)]  # fmt: skip
    geometry = (f"{Path(args.file).name}: {result.shape[1]} x {result.shape[0]} pixels of "
                f"{result.dx * 1e9:.4g} x {result.dy * 1e9:.4g} nm, levelling {result.level}; "
                f"{'periodic' if result.periodic else 'not periodic (zero-padded)'}: "
                f"{result.periodic_reason}")  # fmt: skip
    if args.format == "json":
        environment_json = (None if environment is None else
                            {k: v for k, v in vars(environment).items()})  # fmt: skip
        print(json.dumps({"source": str(result.source), "dx_m": result.dx, "dy_m": result.dy,
                          "environment": environment_json,
                          "periodic": result.periodic, "periodic_reason": result.periodic_reason,
                          "E_star_Pa": result.E_star, "tol": result.tol,
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
                f"{e.hamaker or 0:.4g} J, D0 = {e.cutoff * 1e9:.4g} nm, RH = {e.rh:.4g}, Laplace "
                f"pressure {e.laplace_pressure / 1e6:.4g} MPa on gaps below g_K = "
                f"{e.condensation_gap * 1e9:.4g} nm; the attraction does not deform the surface "
                "(DMT on the exact solve): external_pressure is what must be applied"
            )
        print_rows(rows, list(table), args.format, header)
    if args.out:
        announce(result.write(args.out, command=cli_command(), overwrite=args.overwrite),
                 quiet=args.quiet)  # fmt: skip
    if args.plot:
        from mcsim.figures.contact import contact_figure
        from mcsim.figures.style import save

        announce(save(contact_figure(result), args.plot, overwrite=args.overwrite,
                      inputs=[args.file]), quiet=args.quiet)  # fmt: skip
    return 0


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
    p.add_argument("--quiet", action="store_true", help="no progress bar, no 'wrote FILE' line")
    add_environment(p)
    # the map is the surface: no --surface file holds an [environment] table here
    p.set_defaults(func=run, surface=None)
