"""``mcsim ingest``: a height map or histogram to a surface file."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from mcsim.cli.display import announce
from mcsim.cli.options import parse_h, positive_quantity
from mcsim.model.errors import ParameterError

#: Default pixels along a side of a ``--synthesize`` pad.
PAD_PIXELS = 32


def run(args) -> int:
    from mcsim.store.outputs import check_output
    from mcsim.studies.maps.ingest import ingest_file
    from mcsim.studies.maps.ingested import IngestResult

    def length(value, option):
        return positive_quantity(value, "length", option)

    def quantity(value, dimension, option):
        from mcsim.model.units import parse_quantity

        return None if value is None else parse_quantity(value, dimension, option)

    default = Path(args.file).stem
    if args.counter_surface is not None:
        default = f"{default}-on-{Path(args.counter_surface).stem}"
        if args.synthesize is not None:
            raise ParameterError("--synthesize: pads from the map file's spectrum, not the gap's: "
                                 "not with --counter-surface")  # fmt: skip
    out = Path(args.out) if args.out else Path(f"{default}.toml")
    pads_out = _pads_options(args, out)
    inputs = [args.file, *([args.counter_surface] if args.counter_surface else [])]
    extra = IngestResult.companion_paths(out)
    figures = [extra["histogram_figure"]] + ([extra["comparison_figure"]] if args.plot else [])
    # every file an ingest to `out` may write, whatever its options: those this one does not
    # write are an earlier ingest's, refused as any output is and removed with --overwrite
    outputs = dict.fromkeys([out, *extra.values(), *([pads_out] if pads_out else []),
                             _default_pads(out)])  # fmt: skip
    for path in outputs:  # all refused before any work or writing
        check_output(path, inputs=inputs, overwrite=args.overwrite)
    if (args.w is not None or args.range is not None) and not args.calibrate:
        raise ParameterError("--w: used only with --calibrate (the adhesion calibration); add it")
    if args.range is not None and args.w is None:
        raise ParameterError("--range: used only with --w (the adhesion calibration); add it")
    material = None
    if args.plot or args.calibrate:
        from mcsim.store.config import load_material

        material = load_material(args.material)
    elif args.material != "silicon":
        raise ParameterError("--material: used only by --plot and --calibrate; add one")
    result = ingest_file(
        args.file, unit=args.unit, pixel_size=length(args.pixel_size, "--pixel-size"),
        route=args.route, level=args.level, heights=args.heights, R=length(args.R, "--R"),
        eta=positive_quantity(args.eta, "density", "--eta"),
        channel=args.channel, periodic=args.periodic,
        calibrate=material if args.calibrate else None, radius_by_height=args.radius_by_height,
        adhesion_w=quantity(args.w, "energy_per_area", "--w"),  # checked > 0 by the study
        adhesion_range=quantity(args.range, "length", "--range"), counter=args.counter_surface,
        progress=not args.quiet and sys.stderr.isatty(),
    )  # fmt: skip
    for line in result.summary_lines():
        print(line)
    written = result.write_surface(out, overwrite=args.overwrite, command=args.command_line)
    from mcsim.figures.style import save
    from mcsim.figures.topography import comparison_figure, histogram_figure

    title = f"{result.heights_from}: {Path(args.file).name}" + (
        f" facing {Path(args.counter_surface).name}" if args.counter_surface else ""
    )
    save(histogram_figure(result.distribution, result.surface.sigma, title=title), figures[0],
         overwrite=args.overwrite, inputs=inputs)  # fmt: skip
    if args.plot:
        s = result.surface
        fig = comparison_figure(s, result.gaussian_surface, material, parse_h("4:-1:51"))
        save(fig, figures[1], overwrite=args.overwrite, inputs=inputs)
    if pads_out:
        from mcsim.studies.maps.synthpads import synthesize_pads

        pads = synthesize_pads(args.file, args.synthesize, args.pad_pixels, args.seed,
                               unit=args.unit, pixel_size=length(args.pixel_size, "--pixel-size"),
                               channel=args.channel, periodic=args.periodic)  # fmt: skip
        rms_pad, rms_map = (x**0.5 * 1e9 for x in pads.mean_square)
        print(f"pads       {args.synthesize} periodic pads of {args.pad_pixels} x {args.pad_pixels} "
              f"pixels from the map's radial PSD, seed {pads.seed}: expected rms {rms_pad:.4g} nm "
              f"(the map's {rms_map:.4g} nm; a pad lacks the wavelengths longer than its side)")  # fmt: skip
        written = [
            *written,
            pads.write(pads_out, overwrite=args.overwrite, command=args.command_line),
        ]
    for path in [*written, *figures]:
        announce(path, quiet=args.quiet)
    done = {Path(p) for p in [*written, *figures]}
    for path in (p for p in outputs if p not in done):
        if path.is_file():  # an earlier ingest's, left stale by this one (checked above)
            path.unlink()
            if not args.quiet:
                print(f"mcsim: removed {path} (an earlier ingest's, not written by this one)",
                      file=sys.stderr)  # fmt: skip
    print(f"next: mcsim analytic --surface {out} --h=4:-1:11")
    return 0


def _pads_options(args, out: Path) -> Path | None:
    """The pads file of ``--synthesize`` (default ``<out stem>-pads.h5``), its options checked
    before any work; None without ``--synthesize``."""
    if args.synthesize is None:
        for option, value in (("--pad-pixels", args.pad_pixels), ("--pads-out", args.pads_out),
                              ("--seed", args.seed)):  # fmt: skip
            if value is not None:
                raise ParameterError(f"{option}: used only with --synthesize N; add it")
        return None
    from mcsim.studies.maps.synthpads import check_pads

    if args.pad_pixels is None:
        args.pad_pixels = PAD_PIXELS
    try:
        check_pads(args.synthesize, args.pad_pixels, args.seed, args.file)
    except ParameterError as err:
        option = {"`n`": "--synthesize", "`pixels`": "--pad-pixels", "`seed`": "--seed",
                  "`path`": "--synthesize"}  # fmt: skip
        name = str(err).split(" = ")[0]
        raise ParameterError(f"{option.get(name, name)}: {err}") from None
    return Path(args.pads_out) if args.pads_out else _default_pads(out)


def _default_pads(out: Path) -> Path:
    """The pads file of ``--synthesize`` without ``--pads-out``: ``<out stem>-pads.h5``."""
    return out.with_name(f"{out.stem}-pads.h5")


def add_parser(sub) -> None:
    p = sub.add_parser("ingest", help="height map or histogram to a surface file",
                       description="Read a measured height map (.gwy .ibw .nid .npy .xyz, text matrix) or a text "
                       "histogram; print its height and summit statistics (direct and spectral routes); write a "
                       "surface TOML file with the measured summit-height histogram beside it.")  # fmt: skip
    p.add_argument("file", help="height map or text histogram")
    p.add_argument("--channel", help="channel of a multi-channel file (.gwy .ibw .nid; default: the "
                   "height channel); an unknown name lists the file's channels")  # fmt: skip
    p.add_argument("--unit", help="height unit if the file stores none (e.g. nm)")
    p.add_argument("--pixel-size", help="pixel size if the file stores none (e.g. 10nm)")
    p.add_argument("--counter-surface", metavar="MAP2",
                   help="a counter-surface's height map, measured face up, of the same size and "
                   "pixel size: turned over to face FILE (columns reversed, heights negated), the "
                   "surface written is their gap's topography, FILE - turned-over MAP2, and the "
                   "correlation of the two maps' heights is measured and printed (maps only; not "
                   "with --calibrate or --synthesize)")  # fmt: skip
    p.add_argument("--out", help="surface file (default: <file stem>.toml here, "
                   "<file stem>-on-<MAP2 stem>.toml with --counter-surface)")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace existing output files, and "
                   "remove those of an earlier ingest to the same surface file that this one does "
                   "not write (e.g. its --plot figure)")  # fmt: skip
    p.add_argument("--route", choices=("direct", "spectral"), default="direct",
                   help="summit statistics written as sigma, R, eta (default: direct)")  # fmt: skip
    p.add_argument("--level", choices=("none", "plane", "poly2", "poly3", "poly4", "poly5"),
                   help="levelling before analysis (default: plane, or none on a periodic map; none "
                   "removes the mean only)")  # fmt: skip
    p.add_argument("--periodic", action=argparse.BooleanOptionalAction, default=None,
                   help="analyse the map as periodic, summit neighbours wrapping across its edges "
                   "(--periodic) or not (--no-periodic); default: periodic when opposite edges join "
                   "(rms step across them < 1.5 x the rms neighbour step), said in the output")  # fmt: skip
    p.add_argument("--heights", choices=("summits", "map"), default="summits",
                   help="histogram written: direct-route summit heights (default) or all map heights")  # fmt: skip
    p.add_argument("--R", help="summit radius for a histogram input (e.g. 1.7um)")
    p.add_argument("--eta", help="summit density for a histogram input (e.g. 17um^-2)")
    p.add_argument("--plot", action="store_true",
                   help="also plot the analytic curves against the Gaussian GW curves")  # fmt: skip
    p.add_argument("--calibrate", action="store_true",
                   help="fit GW's summit-radius scale to exact elastic solves of the map (mcsim contact) "
                   "at p/E* = 1e-4 .. 1e-2, so that GW's real contact area follows the exact one, "
                   "on top of a radius by height (--radius-by-height, on with it); recorded in the "
                   "surface file and used by every command that reads it (the mean gap is not "
                   "calibrated); its error out of sample (each load left out of the fit in turn, "
                   "and at p/E* = 3e-2 above the range) is printed, recorded and warned about "
                   "above 10 %%")  # fmt: skip
    p.add_argument("--radius-by-height", action=argparse.BooleanOptionalAction, default=None,
                   help="give each bin of summit heights its own summit radius, fitted to the "
                   "summits' curvatures (taller summits are sharper; maps only; default: with "
                   "--calibrate)")  # fmt: skip
    p.add_argument("--w", metavar="W",
                   help="with --calibrate: also calibrate GW's pull-off on exact adhesive cycles of "
                   "the map (exponential law of this work of adhesion, e.g. 0.1J/m^2) at p/E* = 1e-4, "
                   "1e-3, 1e-2: per law set (jkr, dmt, maugis-dugdale) one work-of-adhesion factor, "
                   "the best law set chosen; its error out of sample (leave-one-out, and at p/E* = "
                   "3e-2) printed, recorded and warned about above 20 %%; recorded in the surface "
                   "file, not applied")  # fmt: skip
    p.add_argument("--range", metavar="L",
                   help="with --w: the law's range, e.g. 1nm (default: the material's z0, else 1nm)")  # fmt: skip
    p.add_argument("--material", default="silicon",
                   help="material of the --plot curves and of the --calibrate solves (its E*): preset "
                   "or FILE.toml (default: silicon)")  # fmt: skip
    p.add_argument("--synthesize", type=int, metavar="N",
                   help="also write N periodic pads synthesised from the map's radial PSD (maps "
                   "only; at the map's pixel size; HDF5, --pads-out)")  # fmt: skip
    p.add_argument(
        "--pad-pixels",
        type=int,
        metavar="M",
        help=f"pixels along each side of a --synthesize pad, >= 8 (default {PAD_PIXELS})",
    )
    p.add_argument("--pads-out", help="pads file of --synthesize (default: <out stem>-pads.h5)")
    p.add_argument("--seed", type=int, help="root seed of --synthesize (default: fresh, recorded)")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no 'wrote FILE' line")
    p.set_defaults(func=run)
