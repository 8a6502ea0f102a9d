"""``mcsim simulate``: a Monte Carlo run of finite patches, stored as HDF5."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from mcsim.cli.display import announce, environment_notes, file_state, log_notes, print_lines
from mcsim.cli.options import (
    add_environment,
    add_inputs,
    add_parallel,
    add_preload,
    add_separations_or_loads,
    balancing_h,
    count_type,
    environment_of,
    inputs_of,
    parse_h,
    preload_grid,
    resolve_law,
    seed_type,
)


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}{'' if n == 1 else 's'}"


def _default_run_path(surface) -> Path:
    import datetime as dt

    stamp = dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    folder = Path("runs")
    folder.mkdir(exist_ok=True)
    return folder / f"{surface.name or 'surface'}-{stamp}.h5"


def run(args) -> int:
    import time

    from mcsim.engine.interrupt import Interrupted, interruptible

    with interruptible(), log_notes(args.quiet):  # SIGINT/SIGTERM owned before heavy imports
        from mcsim.store.files import checkpoint_path, file_path
        from mcsim.studies.simulation import simulate

        surface, material, pair = inputs_of(args, parts=True)
        given = pair.pop("surface", surface)  # with a counter-surface: the parts, recorded
        environment = environment_of(args)
        if not args.quiet:
            print_lines(environment_notes(surface, environment))
        # Only with an environment, so that the run is exactly as before without one.
        with_environment = {} if environment is None else {"environment": environment}
        pressure, preload = None, args.preload
        law, notes = resolve_law(args, surface, material)
        if args.h is not None:
            h = parse_h(args.h)
        elif args.pressure is None and args.load is None:
            h, preload = preload_grid(args, surface, material, law, environment)
        else:
            h, pressure = balancing_h(args, surface, material, environment)
        extra = {} if pressure is None else {"load_control": json.dumps(
            {"pressure": pressure.tolist(), "unit": "Pa"})}  # fmt: skip
        if args.law == "auto" and not args.quiet:
            print_lines(notes[:1])  # the choice; simulate() logs the regime warnings
        out = file_path(args.out, "--out") if args.out is not None else _default_run_path(surface)
        show_progress = not args.quiet and sys.stderr.isatty()
        before = file_state(out)
        t0 = time.perf_counter()
        try:
            run = simulate(
                given, material, h, args.area, **pair, realizations=args.realizations, seed=args.seed, law=law,
                count=args.count, cycle=args.cycle, preload=preload, device=args.device, workers=args.workers, scheduler=args.scheduler or args.dask,
                chunk_size=args.chunk_size, keep_heights=args.keep_heights, out=out, overwrite=args.overwrite,
                resume=args.resume, checkpoint_every=args.checkpoint_every, progress=show_progress,
                command=args.command_line,
                extra_attrs=extra or None, **with_environment,
            )  # fmt: skip
        except Interrupted as stop:
            partial = checkpoint_path(out)
            if partial.exists() and not args.keep_heights:
                print(f"mcsim: interrupted ({stop}); progress saved in {partial}: run the same "
                      "command with --resume to finish it", file=sys.stderr)  # fmt: skip
            else:
                print(f"mcsim: interrupted ({stop}); no output written", file=sys.stderr)
            return stop.exit_status
        elapsed = time.perf_counter() - t0
        if before is not None and file_state(out) == before:
            return 0  # --resume of this finished run: its notice was the only output
        if not args.quiet:
            n = run.n_summits
            announce(run.path, f"{_count(run.spec.realizations, 'realization')} x {_count(len(h), 'separation')}, "
                     f"N = {n.mean():.6g} summits per patch on average, {elapsed:.2f} s")  # fmt: skip
            pads = f"   |   mcsim pads {run.path}" if args.cycle else ""  # pull-off per pad
            print(f"mcsim: next: mcsim compare {run.path}   |   mcsim plot {run.path}{pads}",
                  file=sys.stderr)  # fmt: skip
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("simulate", help="Monte Carlo run on finite patches, stored as HDF5",
                       description="Sample finite patches, sum the per-summit laws, store the run as HDF5. "
                       "The separations are given (--h), or are those that balance nominal pressures on the "
                       "analytic approach branch (--pressure, or --load over the patch --area), as "
                       "`mcsim analytic --pressure` finds them; `mcsim plot` then draws each patch's "
                       "load and area.")  # fmt: skip
    add_inputs(p, separations=False)
    add_separations_or_loads(p, "the run's separations balance them", required=False)
    add_environment(p)
    p.add_argument(
        "--area", required=True, help="patch area: m^2 or with a unit ('100um^2', '0.01mm^2')"
    )
    p.add_argument(
        "--realizations", type=count_type, default=1, help="independent patches (default: 1)"
    )
    p.add_argument(
        "--seed",
        type=seed_type,
        help="root seed, an integer >= 0 (default: fresh entropy, recorded in the file)",
    )
    p.add_argument(
        "--count",
        choices=("poisson", "fixed"),
        default="poisson",
        help="N ~ Poisson(eta A) or round(eta A) (default: %(default)s)",
    )
    p.add_argument(
        "--cycle",
        action="store_true",
        help="approach over the --h grid (descending), then retraction back over the same grid "
        "from its lowest value; both branches stored",
    )
    add_preload(p, "with --cycle, force control: each pad is pressed until its own approach "
                "load reaches P*area and retracted from there (found from its summits when the run "
                "is read, `mcsim pads`; the stored curves keep the grid's common turn)")  # fmt: skip
    p.add_argument(
        "--device",
        choices=("cpu", "cuda"),
        default="cpu",
        help="sample and sum on the CPU or on an NVIDIA GPU (needs mcsim[gpu]; other random "
        "streams than the CPU's, recorded in the run file)",
    )
    p.add_argument("--out", help="run file (default: runs/<surface>-<time>.h5)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing run file")
    add_parallel(p, "worker threads")
    p.add_argument(
        "--chunk-size",
        type=count_type,
        default=1 << 18,
        help="summits per task (default: %(default)s; results do not depend on it)",
    )
    p.add_argument(
        "--keep-heights", action="store_true", help="store the sampled heights (compressed)"
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue from the checkpoint beside --out (same arguments); "
        "without one, start from the beginning; if --out holds this finished run, do nothing",
    )
    p.add_argument("--checkpoint-every", type=float, default=60.0, metavar="SECONDS",
                   help="save progress beside --out (RUN.partial.h5) after 10 s, then this often (default: 60 s)")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=run)
