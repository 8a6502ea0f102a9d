"""``mcsim plot``: figures of run and sweep files."""

from __future__ import annotations

import sys
from pathlib import Path

from mcsim.cli.display import announce
from mcsim.model.errors import ParameterError


def run(args) -> int:
    import dataclasses

    import numpy as np

    from mcsim.figures.runs import PANELS, run_figure
    from mcsim.figures.style import save
    from mcsim.figures.topography import comparison_figure
    from mcsim.model.distributions import GAUSSIAN
    from mcsim.store.outputs import check_output
    from mcsim.store.runfile import read_run
    from mcsim.store.sweepfile import is_sweep_file

    if len(args.run) > 1 and not args.out:
        raise ParameterError("--out: name the PNG file when plotting several runs")
    # --kind lines or map beside the default figure of the same file: its own name
    suffix = "" if args.kind == "auto" else f"-{args.kind}"
    out = Path(args.out) if args.out else Path(args.run[0]).with_suffix("")
    out = out if args.out else out.with_name(f"{out.name}{suffix}.png")
    if out.suffix.lower() != ".png":
        raise ParameterError(f"--out: {out}: the figure is a PNG file, its name must end in .png")
    sweeps = [path for path in args.run if is_sweep_file(path)]
    if sweeps:
        return _plot_sweep(args, sweeps, out)
    if args.kind != "auto":
        raise ParameterError(
            f"--kind {args.kind}: applies to sweep files; {args.run[0]} is a run file"
        )
    runs = [read_run(path, allow_incomplete=args.partial) for path in args.run]
    run, surface = runs[0], runs[0].spec.surface
    versus = args.versus or ("load" if "load_control" in run.attrs else "h")
    if versus == "load":
        from mcsim.figures.loadcontrol import load_run_figure

        if len(runs) > 1:
            raise ParameterError("--versus load: plot one run at a time")
        check_output(out, inputs=args.run, overwrite=args.overwrite)
        save(load_run_figure(run), out, overwrite=args.overwrite, inputs=args.run)
        announce(
            out, "each patch's load and area or friction over the analytic curves", quiet=args.quiet
        )
        return 0
    other = None  # measured heights: also against the Gaussian GW curves (the seed's panels)
    if len(runs) == 1 and surface.heights != GAUSSIAN:
        if run.spec.cycle or tuple(run.quantities) != PANELS:
            print("mcsim: note: the figure of measured heights against the Gaussian GW curves "
                  "is drawn for runs of the seed law set without --cycle only", file=sys.stderr)  # fmt: skip
        else:
            other = out.with_name(f"{out.stem}-vs-gaussian.png")
    for path in (out, other) if other else (out,):  # both refused before either is written
        check_output(path, inputs=args.run, overwrite=args.overwrite)
    figure = run_figure(runs if len(runs) > 1 else run)
    save(figure, out, overwrite=args.overwrite, inputs=args.run)
    announce(out, quiet=args.quiet)
    if other:
        gaussian = dataclasses.replace(surface, heights=GAUSSIAN, name=f"{surface.name} (Gaussian)")
        h = np.linspace(run.h.max(), run.h.min(), 200)
        save(comparison_figure(surface, gaussian, run.spec.material, h, run=run), other,
             overwrite=args.overwrite, inputs=args.run)  # fmt: skip
        announce(
            other,
            "measured heights against the Gaussian of the same sigma, R, eta",
            quiet=args.quiet,
        )
    return 0


def _plot_sweep(args, sweeps: list[str], out: Path) -> int:
    """``mcsim plot SWEEP.h5``: design curves or design maps (:mod:`mcsim.figures.sweeps`)."""
    from mcsim.figures.friction import friction_figure, is_friction_sweep
    from mcsim.figures.stiction import is_pads_sweep, stiction_figure
    from mcsim.figures.style import save
    from mcsim.figures.sweeps import sweep_figure
    from mcsim.store.outputs import check_output
    from mcsim.store.sweepfile import read_sweep

    if len(args.run) > 1:
        raise ParameterError(f"plot: {sweeps[0]} is a sweep file: plot it on its own (one file)")
    result = read_sweep(sweeps[0])
    if not result.attrs.get("complete", True) and not args.partial:
        raise ParameterError(f"{sweeps[0]}: an incomplete sweep (checkpoint): finish it with the same "
                             "mcsim sweep command plus --resume, or pass --partial to plot its "
                             "completed points")  # fmt: skip
    check_output(out, inputs=args.run, overwrite=args.overwrite)
    if is_friction_sweep(result) and args.kind != "stiction":
        figure = friction_figure(result)
    elif is_pads_sweep(result):
        figure = stiction_figure(result)
    else:
        figure = sweep_figure(result, kind=args.kind)
    save(figure, out, overwrite=args.overwrite, inputs=args.run)
    announce(out, quiet=args.quiet)
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("plot", help="Monte Carlo points over the analytic curves, or a sweep's design curves/maps",
                       description="Plot a run: Monte Carlo means with error bars over the analytic curves. "
                       "Plot a sweep file (mcsim sweep): pull-off pressure, work of separation and mu against "
                       "one varied input (log axis for a log grid), or maps over two with the adhesion-map "
                       "regime boundaries.")  # fmt: skip
    p.add_argument(
        "run", nargs="+", help="run file(s) (.h5); several are overlaid; or one sweep file"
    )
    p.add_argument("--kind", choices=("auto", "lines", "map", "stiction"), default="auto",
                   help="sweep files: 'lines' (against the first input, a line per value of the second), "
                   "'map' (two numeric inputs), 'auto' (default: a map for two numeric inputs; a pads "
                   "sweep with friction: mu_s and p_slip), 'stiction' (a pads sweep's p_stick)")  # fmt: skip
    p.add_argument("--out", help="PNG file (default: next to the file, FILE.png, or with --kind "
                   "lines or map FILE-lines.png, FILE-map.png; required for several)")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace an existing PNG file")
    p.add_argument(
        "--partial",
        action="store_true",
        help="accept an incomplete run or sweep checkpoint: plot its completed realizations or points",
    )
    p.add_argument("--versus", choices=("h", "load"),
                   help="x axis: the separation h, or the load (each patch's load against its area "
                        "and friction, both with SEs); default: load for a run made with --pressure "
                        "or --load, else h")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no 'wrote FILE' line")
    p.set_defaults(func=run)
