"""``mcsim pads``: pull-off statistics of finite pads from a cycle run, and their static friction."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from mcsim.cli.display import announce, print_rows
from mcsim.cli.options import FORMATS, workers_type
from mcsim.model.errors import ParameterError

#: Names of the intervals of ``mcsim pads``, as printed.
_INTERVAL_NAMES = {"clopper-pearson": "Clopper-Pearson", "wilson": "Wilson"}


def run(args) -> int:
    from mcsim.engine.montecarlo import default_workers
    from mcsim.model.units import parse_quantity
    from mcsim.store.runfile import read_run
    from mcsim.studies.pads import FEW_CONTACTS, pad_report

    fr = None
    if args.restoring_force is not None:
        fr = parse_quantity(args.restoring_force, "force", "--restoring-force")
        if fr < 0:
            raise ParameterError(f"--restoring-force: {args.restoring_force!r} is negative "
                                 "(allowed: a force >= 0, e.g. 2uN)")  # fmt: skip
    ft = None
    if args.tangential_force is not None:
        ft = parse_quantity(args.tangential_force, "force", "--tangential-force")
        if not (math.isfinite(ft) and ft >= 0):
            raise ParameterError(f"--tangential-force: {args.tangential_force!r} (allowed: a finite "
                                 "force >= 0, e.g. 50uN)")  # fmt: skip
    if args.tail and fr is None and ft is None:
        raise ParameterError("--tail: importance sampling estimates p_stick or p_slip; add "
                             "--restoring-force or --tangential-force")  # fmt: skip
    if args.plot:
        from mcsim.store.outputs import check_output

        if Path(args.plot).suffix.lower() != ".png":
            raise ParameterError(
                f"--plot: {args.plot}: the figure is a PNG file, its name must end in .png"
            )
        check_output(args.plot, inputs=[args.run], overwrite=args.overwrite)
    run = read_run(args.run, allow_incomplete=args.partial)
    try:
        report = pad_report(run, fr, args.interval, tail=True if args.tail else None,
                            friction=args.friction, tangential_force=ft,
                            progress=not args.quiet and sys.stderr.isatty(),
                            workers=args.workers or default_workers())  # fmt: skip
    except ParameterError as err:
        raise ParameterError(f"{args.run}: {err}") from None
    pull_off, stats = report.pull_off, report.statistics
    interval = f"{_INTERVAL_NAMES[args.interval]} 95 %"
    if pull_off.past_grid_top:
        print(f"mcsim: note: {pull_off.past_grid_top} of {stats.pads} pad(s) pull off beyond the top "
              f"of the run's grid (h = {pull_off.top:g}), where its most tensile point was wrong; "
              "the pull-off here retracts each pad until every summit has let go", file=sys.stderr)  # fmt: skip
    if not run.complete:
        print(f"mcsim: note: {run.path} is incomplete: statistics over its {stats.pads} completed "
              f"pad(s) of {run.attrs.get('realizations')}", file=sys.stderr)  # fmt: skip
    if fr is not None and report.contacts < FEW_CONTACTS:
        print(f"mcsim: warning: a pad touches with {report.contacts:.3g} summits on average (fewer "
              f"than {FEW_CONTACTS}): its tallest summits decide it; trust the Monte Carlo p_stick, "
              "not p_stick_model", file=sys.stderr)  # fmt: skip
    if fr is not None:
        _p_stick_notes(report, stats.pads, args.tail)
        if report.stick["p_stick_method"] == "importance":
            interval = "Clopper-Pearson 95 % on the effective sample size (importance sampling)"
    if report.friction is not None:
        _friction_notes(report, run.spec)
    fields = report.quantities()
    method = _method(pull_off)
    if args.format == "json":  # the same fields as the table, with their units
        clean = {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                 for k, (v, _) in fields.items()}  # fmt: skip
        if fr is not None:
            clean["p_stick_method"] = report.stick["p_stick_method"]
        if ft is not None:
            clean["p_slip_method"] = report.slip["p_slip_method"]
        clean |= {"interval": interval, "pull_off_method": method,
                  "units": {k: u for k, (_, u) in fields.items()}}  # fmt: skip
        print(json.dumps(clean, indent=1, allow_nan=False))
    elif args.format == "csv":  # a row per pad; the statistics as a note
        values = (f"{k} = {v:.6g}" + ("" if u == "1" else f" {u}")  # no unit on a number
                  for k, (v, u) in fields.items() if v is not None)  # fmt: skip
        print(f"mcsim: note: {', '.join(values)}; "
              f"{interval} interval; per-pad pull-off: {method}", file=sys.stderr)  # fmt: skip
        _print_pads(pull_off)
    else:
        spec = run.spec
        header = [f"run {run.path}: law {spec.law}, A = {spec.area * 1e12:.4g} um^2, E[N] = "
                  f"{spec.expected_summits:.4g} summits per pad, {stats.pads} pads",
                  f"pull-off per pad: {method}; p_stick = P(pull-off > restoring force), "
                  f"{interval} interval",
                  "analytic_mean: GW pull-off x A K (minimum of the mean curve, not the mean of "
                  "the per-pad minima on the grid)"]  # fmt: skip
        rows = [{"quantity": k, "value": v, "unit": u} for k, (v, u) in fields.items()]
        print_rows(rows, ["quantity", "value", "unit"], "table", header)
    if args.plot:
        from mcsim.figures.stiction import pads_figure
        from mcsim.figures.style import save

        stick = {}
        if fr is not None:
            stick = {"p_stick": fields["p_stick"][0], "interval_name": interval, "interval": (
                fields["p_stick_ci_low"][0], fields["p_stick_ci_high"][0])}  # fmt: skip
        fig = pads_figure(pull_off.force, report.analytic_mean, restoring_force=fr, **stick,
                          title=f"{Path(args.run).name}: pull-off of {stats.pads} pads")  # fmt: skip
        save(fig, args.plot, overwrite=args.overwrite, inputs=[args.run])
        announce(args.plot, quiet=args.quiet)
    return 0


def _p_stick_notes(report, n: int, asked: bool) -> None:
    """How p_stick was found; a warning where p_stick_model lies outside its interval."""
    from mcsim.studies.rareevent import MIN_ESS, MIN_TAIL_PADS, SWITCH

    s = report.stick
    rare = round(min(s["p_stick"], 1 - s["p_stick"]) * n)
    if s["p_stick_method"] == "importance":
        print(f"mcsim: note: p_stick by importance sampling (pads of a tilted law found in "
              "cross-entropy stages, each weighted by its likelihood ratio; effective pads on the "
              f"rarer side {s['p_stick_ess']:.3g}): the run's {n} pads give the pull-off "
              "statistics", file=sys.stderr)  # fmt: skip
    elif rare < SWITCH or asked:
        why = (f"importance sampling needs at least {MIN_TAIL_PADS} pads" if n < MIN_TAIL_PADS
               else f"importance sampling's effective sample size stayed below {MIN_ESS} "
               "(more pads raise it; it stays 0 where no pad reaches the restoring force), its two "
               "independent searches disagreed (it cannot tell which holds), or the summit count "
               "is fixed")  # fmt: skip
        print(f"mcsim: note: fewer than {SWITCH} of the {n} pads lie on the rarer side (sticking or "
              f"not), or --tail, but p_stick is their fraction, not importance sampling: {why}",
              file=sys.stderr)  # fmt: skip
    model = report.p_stick_model
    if math.isnan(model):
        print("mcsim: note: p_stick_model is not given with an environment or a radius by height "
              "(the model is not checked there): the pads' own p_stick is the answer",
              file=sys.stderr)  # fmt: skip
    elif not s["p_stick_low"] <= model <= s["p_stick_high"]:
        print(f"mcsim: warning: p_stick_model {model:.3g} lies outside the 95 % interval of "
              f"p_stick [{s['p_stick_low']:.3g}, {s['p_stick_high']:.3g}]: the model does not "
              "hold here", file=sys.stderr)  # fmt: skip


def _friction_notes(report, spec) -> None:
    """What T_s and μ_s are, and how p_slip was found."""
    from mcsim.engine.pads.friction import check_friction

    rule = {"savkoor-briggs": "Savkoor-Briggs (Eq. 6) of each touching summit's load",
            "shear": "tau x each touching summit's contact area"}[check_friction(spec)]  # fmt: skip
    preload = report.pull_off.preload
    load = ("the environment's pull at the turn (menisci and van der Waals; none dry: mu_s "
            "undefined)" if preload == 0 else "the preload force P*A" if preload is not None
            else "the pad's net approach load at the turn")  # fmt: skip
    f = report.friction
    print(f"mcsim: note: static friction T_s at each pad's turn: {rule}; mu_s = T_s / {load} "
          f"(defined for {f.mu_pads} of {f.pads} pads)", file=sys.stderr)  # fmt: skip
    if report.slip is not None and report.slip["p_slip_method"] == "importance":
        print(f"mcsim: note: p_slip = P(T_s < tangential force) by importance sampling "
              f"(effective pads on the rarer side {report.slip['p_slip_ess']:.3g})", file=sys.stderr)  # fmt: skip


def _print_pads(pull_off) -> None:
    """``--format csv``: one row per pad, the columns of
    :meth:`mcsim.store.results.PullOff.to_dataframe` (without pandas: ≈0.4 s of its import)."""
    import numpy as np

    columns = pull_off.columns()
    meaning = "; ".join(f"{name} ({long_name}, {unit})" for name, unit, long_name, _ in columns)
    print(f"mcsim: note: columns: pad (realization index), {meaning}", file=sys.stderr)
    rows = [{"pad": i, **{name: np.asarray(v)[i].item() for name, _, _, v in columns}}
            for i in range(len(pull_off.force))]  # fmt: skip
    print_rows(rows, ["pad", *(name for name, *_ in columns)], "csv")


def _method(pull_off) -> str:
    """How the per-pad pull-off was found, for the notes and the table's header."""
    import numpy as np

    if not pull_off.exact:
        return (f"most tensile point of the run's grid (spacing {pull_off.resolution:.3g} in h; a "
                "GPU run's heights cannot be drawn again)")  # fmt: skip
    if pull_off.preload is not None:
        turn = (f"each pad's own turn under force control, preload {pull_off.preload:.6g} Pa "
                f"(h_turn {np.min(pull_off.h_turn):.4g} to {np.max(pull_off.h_turn):.4g})")  # fmt: skip
    else:
        turn = f"the run's turn h = {pull_off.h_turn[0]:g}"
    return f"minimum of its own retraction curve in continuous h (1e-7) after {turn}"


def add_parser(sub) -> None:
    p = sub.add_parser("pads", help="pull-off statistics of finite pads from a --cycle run",
                       description="Per-pad pull-off force of a --cycle Monte Carlo run (one pad per realization): "
                       "mean, standard error, standard deviation, 5/50/95 % quantiles (N) and, with a restoring "
                       "force, the probability that a pad sticks with its 95 % interval (Clopper-Pearson, or "
                       "Wilson's score interval). With --friction or --tangential-force: each pad's static friction at "
                       "its turn and mu_s (mean, std, quantiles), and the probability that a pad slips. --format csv "
                       "lists each pad's pull-off force (N) instead.")  # fmt: skip
    p.add_argument(
        "run", help="run file (.h5) of `mcsim simulate ... --cycle` with a contact law set"
    )
    p.add_argument("--restoring-force", metavar="F",
                   help="force pulling the pad off: N or with a unit ('2uN', '500nN'); a pad sticks when "
                        "its pull-off exceeds it")  # fmt: skip
    p.add_argument("--interval", choices=("clopper-pearson", "wilson"), default="clopper-pearson",
                   help="95 %% interval of the probability of sticking: Clopper-Pearson exact (default; "
                        "coverage never below 95 %%) or Wilson's score interval (Wilson 1927; shorter)")  # fmt: skip
    p.add_argument("--tail", action="store_true",
                   help="with --restoring-force and >= 100 pads: p_stick by importance sampling, down "
                   "to 1e-6 (default: where fewer than 10 pads lie on the rarer side, else the pads' fraction)")  # fmt: skip
    p.add_argument("--friction", action="store_true",
                   help="also each pad's static friction T_s at its turn (Savkoor-Briggs for jkr, tau x "
                   "contact area with the material's tau) and mu_s = T_s / normal load: mean, std, "
                   "5/50/95 %% quantiles")  # fmt: skip
    p.add_argument("--tangential-force", metavar="F",
                   help="force pulling the pad sideways (N or with a unit, '50uN'; implies --friction): "
                   "p_slip, the fraction of pads whose static friction is below it, with its 95 %% interval")  # fmt: skip
    p.add_argument("--workers", type=workers_type,
                   help="worker processes of the run's pads (where there are many) and of "
                   "importance sampling (--tail, and where it switches on by itself); default: all "
                   "cores; 1: in this process; results do not depend on it")  # fmt: skip
    p.add_argument("--format", choices=FORMATS, default="table",
                   help="table or json: the statistics; csv: one row per pad (pull-off in N)")  # fmt: skip
    p.add_argument(
        "--partial",
        action="store_true",
        help="accept an incomplete run (a checkpoint RUN.partial.h5): its completed pads",
    )
    p.add_argument(
        "--plot",
        metavar="FILE.png",
        help="histogram of the pad pull-off with the analytic mean, and the fraction of pads whose pull-off exceeds each force (p_stick marked)",
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing --plot file")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no 'wrote FILE' line")
    p.set_defaults(func=run)
