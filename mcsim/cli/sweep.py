"""``mcsim sweep``: curves and adhesion summaries over a grid of inputs."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

from mcsim.cli.display import (
    announce,
    environment_notes,
    file_state,
    log_notes,
    print_lines,
    work_notes,
)
from mcsim.cli.options import (
    add_environment,
    add_inputs,
    add_parallel,
    add_preload,
    count_type,
    environment_of,
    inputs_of,
    parse_h,
    parse_turn,
    scheduler_of,
    seed_type,
)
from mcsim.model.errors import ParameterError

#: Failed points of a sweep listed one per line on stderr; the rest are counted.
MAX_FAILED_SHOWN = 20


def run(args) -> int:
    from mcsim.engine.interrupt import Interrupted, interruptible

    with interruptible(), log_notes(args.quiet):  # SIGINT/SIGTERM owned before heavy imports
        from mcsim.physics.adhesion import ValidityWarning
        from mcsim.store.files import checkpoint_path
        from mcsim.studies.sweeps import area_warnings, sweep

        vary = {}
        for item in args.vary:
            name, sep, spec = item.partition("=")
            if not sep:
                raise ParameterError(f"--vary: cannot read {item!r} (give NAME=SPEC, e.g. "
                                     "sigma=0.3nm:20nm:40:log)")  # fmt: skip
            if name.strip() in vary:
                raise ParameterError(f"--vary: {name.strip()!r} is given twice")
            vary[name.strip()] = spec
        if not args.mc and (args.realizations is not None or args.device != "cpu"):
            raise ParameterError("--realizations and --device apply to the Monte Carlo runs only (add --mc)")  # fmt: skip
        if not (args.mc or args.pads) and (args.area is not None or args.seed is not None):
            raise ParameterError("--area and --seed apply to the Monte Carlo runs and pads only (add --mc or --pads N)")  # fmt: skip
        surface, material, pair = inputs_of(args, parts=True)
        given = pair.pop("surface", surface)  # with a counter-surface: the parts, recorded
        environment = environment_of(args)
        if not args.quiet:
            print_lines(environment_notes(surface, environment, varied=vary, material=material))
        out = Path(args.out)
        before = file_state(out)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # printed below, as a line
                result = sweep(
                    given, material, vary, **pair, law=args.law, h=parse_h(args.h), turn=parse_turn(args.turn),
                    environment=environment, mc=args.mc, pads=args.pads, restoring_force=args.restoring_force, preload=args.preload, tail=True if args.tail else None, friction=args.friction, tangential_force=args.tangential_force, area=args.area, realizations=args.realizations or 1, seed=args.seed, device=args.device,
                    workers=args.workers, scheduler=scheduler_of(args, processes=bool(args.pads) and args.device == "cpu"), out=out,
                    overwrite=args.overwrite, resume=args.resume, checkpoint_every=args.checkpoint_every,
                    progress=not args.quiet and sys.stderr.isatty(), command=args.command_line,
                )  # fmt: skip
        except Interrupted as stop:
            partial = checkpoint_path(out)
            saved = f"completed points saved in {partial}: run the same command with --resume to finish it"
            print(f"mcsim: interrupted ({stop}); {saved if partial.exists() else 'no output written'}",
                  file=sys.stderr)  # fmt: skip
            return stop.exit_status
        if before is not None and file_state(out) == before:
            return 0  # --resume of this finished sweep: its notice was the only output
        warned = result.data["regime_warning"]
        n_warned = int((warned != "").sum())
        if n_warned:
            first = next(str(w) for w in warned.ravel() if w)
            print(f"mcsim: warning: {n_warned} of {warned.size} points outside their law set's regime "
                  f"(variable regime_warning), e.g.: {first}", file=sys.stderr)  # fmt: skip
        for line in area_warnings(result):
            print(f"mcsim: warning: {line}", file=sys.stderr)
        if "work_of_separation" in result.data:
            print_lines(work_notes(result.data["work_of_separation"], " (work_of_separation)"))
        _warn_few_contacts(result)
        _p_stick_notes(result)
        _p_slip_notes(result)
        failed = result.failed
        for inputs, error in failed[:MAX_FAILED_SHOWN]:
            shown = ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
                              for k, v in inputs.items())  # fmt: skip
            print(f"mcsim: point {shown} failed: {error}", file=sys.stderr)
        if len(failed) > MAX_FAILED_SHOWN:
            print(f"mcsim: ... and {len(failed) - MAX_FAILED_SHOWN} more failed points (variable "
                  f"error of {out})", file=sys.stderr)  # fmt: skip
        announce(result.path, f"{warned.size} points ({' x '.join(map(str, result.shape))}), "
                 f"{len(result.failed)} failed", quiet=args.quiet)  # fmt: skip
        return 1 if result.failed else 0


def _warn_few_contacts(result) -> None:
    """One line when the pads of some points touch with fewer than ~10 summits each."""
    import numpy as np

    from mcsim.studies.pads import FEW_CONTACTS

    contacts = result.data.get("contacting_summits")
    if contacts is None:
        return
    few = contacts < FEW_CONTACTS
    if few.any():
        print(f"mcsim: warning: at {int(few.sum())} of {few.size} points a pad touches with fewer "
              f"than {FEW_CONTACTS} summits on average (variable contacting_summits, lowest "
              f"{np.nanmin(contacts):.3g}): its tallest summits decide it; trust the Monte Carlo "
              "p_stick there, not a model", file=sys.stderr)  # fmt: skip


def _p_stick_notes(result) -> None:
    """Where p_stick came from importance sampling, where the plain fraction stayed though its
    pads were too few on the rarer side, and where p_stick_model lies outside p_stick's interval."""
    import numpy as np

    from mcsim.studies.rareevent import MIN_ESS, MIN_TAIL_PADS, SWITCH

    d = result.data
    if "p_stick_method" not in d:
        return
    n, done = result.attrs["pads"], np.isfinite(d["p_stick"])
    tail = (d["p_stick_method"] == "importance") & done
    if tail.any():
        print(f"mcsim: note: p_stick by importance sampling at {int(tail.sum())} of {tail.size} "
              f"points (variable p_stick_method; effective pads on the rarer side p_stick_ess, "
              f"lowest {np.min(d['p_stick_ess'][tail]):.3g})", file=sys.stderr)  # fmt: skip
    rare = np.minimum(d["p_stick"], 1 - d["p_stick"]) * n
    asked = result.attrs.get("p_stick_tail")
    plain = done & ~tail & ((np.round(rare) < SWITCH) | (asked == "importance"))
    if plain.any() and asked != "pads":
        why = (f"importance sampling needs at least {MIN_TAIL_PADS} pads (--pads)" if n < MIN_TAIL_PADS
               else f"importance sampling's effective sample size stayed below {MIN_ESS} "
               "(more --pads raise it; it stays 0 where no pad reaches the restoring force), or its "
               "two independent searches disagreed (it cannot tell which holds)")  # fmt: skip
        print(f"mcsim: note: at {int(plain.sum())} of {plain.size} points fewer than {SWITCH} of "
              f"the {n} pads lie on the rarer side (sticking or not), or --tail, but p_stick is "
              f"their fraction (Clopper-Pearson), not importance sampling: {why}", file=sys.stderr)  # fmt: skip
    model = d["p_stick_model"]
    outside = done & ((model < d["p_stick_low"]) | (model > d["p_stick_high"]))
    if outside.any():
        i = np.unravel_index(int(np.flatnonzero(outside.ravel())[0]), outside.shape)
        print(f"mcsim: warning: at {int(outside.sum())} of {outside.size} points p_stick_model "
              f"lies outside the 95 % interval of p_stick (e.g. {model[i]:.3g} against "
              f"[{d['p_stick_low'][i]:.3g}, {d['p_stick_high'][i]:.3g}]): the model does not "
              "hold there", file=sys.stderr)  # fmt: skip


def _p_slip_notes(result) -> None:
    """Where p_slip came from importance sampling."""
    import numpy as np

    d = result.data
    if "p_slip_method" not in d:
        return
    tail = (d["p_slip_method"] == "importance") & np.isfinite(d["p_slip"])
    if tail.any():
        print(f"mcsim: note: p_slip by importance sampling at {int(tail.sum())} of {tail.size} "
              f"points (variable p_slip_method; effective pads on the rarer side p_slip_ess, "
              f"lowest {np.min(d['p_slip_ess'][tail]):.3g})", file=sys.stderr)  # fmt: skip


def add_parser(sub) -> None:
    p = sub.add_parser("sweep", help="curves and adhesion summaries over a grid of inputs, as HDF5",
                       description="Analytic curves over --h, regime numbers and, for law sets with a load and a "
                       "retraction branch, the adhesion summary (as mcsim analytic and mcsim adhesion) at every "
                       "point of the outer product of the --vary inputs; optionally a Monte Carlo run per point. "
                       "One netCDF-compatible HDF5 file: xarray.open_dataset(FILE, engine='h5netcdf').")  # fmt: skip
    add_inputs(p, separations=False)
    add_environment(p)
    p.set_defaults(law=None)
    p.add_argument("--vary", action="append", required=True, metavar="NAME=SPEC",
                   help="input to vary (repeatable; the grid is their outer product, in this order): sigma, R, "
                   "eta, E (both solids), E1, E2, nu (both), nu1, nu2, w (work of adhesion; or gamma), z0, tau, H, law (a list, e.g. "
                   "law=jkr,dmt,maugis-dugdale), area (pad area, with --mc or --pads), restoring_force (with --pads, instead of --restoring-force), tangential_force (with --pads, instead of --tangential-force), preload (instead of --preload), and the environment's rh, hamaker (J), "
                   "contact_angle (degrees when bare), cutoff (m), temperature (K), film_thickness, structured_film, asperity_roughness, retardation_wavelength (m). SPEC: start:stop:num[:log] or a "
                   "list a,b,c; each value with an optional unit, a bare number is SI "
                   "(sigma=0.3nm:20nm:40:log, w=0.05:1:5 in J/m^2)")  # fmt: skip
    p.add_argument("--out", required=True, metavar="FILE.h5", help="sweep file (HDF5)")
    p.add_argument("--h", default="4:-1:51", metavar="SPEC",
                   help="separations d/sigma of the curves (default 4:-1:51)")  # fmt: skip
    p.add_argument("--turn", metavar="H", help="closest approach d/sigma before retraction for the "
                   "adhesion summary (default: where the approach load is zero)")  # fmt: skip
    add_preload(
        p,
        "the adhesion summary's turn balances it on the mean curve; with --pads each pad is "
        "pressed with P*A under force control (not with --turn)",
    )
    p.add_argument("--pads", type=count_type, metavar="N",
                   help="also N finite pads of --area per point through a cycle, from the point's own "
                   "stream of --seed: p_stick with its 95%% Clopper-Pearson interval and the pads' pull-off "
                   "statistics (N) beside the GW mean (as mcsim simulate --cycle + mcsim pads)")  # fmt: skip
    p.add_argument("--tail", action="store_true",
                   help="with --pads (>= 100): p_stick by importance sampling at every point, down to "
                   "1e-6 (default: where fewer than 10 pads lie on the rarer side, else the pads' fraction)")  # fmt: skip
    p.add_argument("--restoring-force", metavar="F",
                   help="with --pads: force pulling a pad off (N or with a unit, '20uN'); a pad sticks "
                   "when its pull-off exceeds it (or --vary restoring_force=...)")  # fmt: skip
    p.add_argument("--friction", action="store_true",
                   help="with --pads: also each pad's static friction at its turn (Savkoor-Briggs for jkr, "
                   "tau x contact area with tau) and mu_s: static_friction_* (N) and mu_static_* (1); "
                   "--restoring-force is then optional")  # fmt: skip
    p.add_argument("--tangential-force", metavar="F",
                   help="with --pads (implies --friction): force pulling a pad sideways (N or with a unit, "
                   "'50uN'); p_slip, the probability that a pad's static friction is below it, with its "
                   "95%% interval (or --vary tangential_force=...)")  # fmt: skip
    p.add_argument("--mc", action="store_true", help="also one Monte Carlo run per point (in memory): "
                   "mean and standard error of each curve")  # fmt: skip
    p.add_argument(
        "--area", help="patch area of the Monte Carlo runs: m^2 or with a unit ('100um^2')"
    )
    p.add_argument("--realizations", type=count_type, help="patches per point (default: 1)")
    p.add_argument("--seed", type=seed_type, help="root seed of the Monte Carlo runs (point i uses its own "
                   "child stream of it; default: fresh entropy, recorded in the file)")  # fmt: skip
    p.add_argument("--device", choices=("cpu", "cuda"), default="cpu",
                   help="where the Monte Carlo runs sample and sum (cuda: this machine's GPU, needs "
                   "mcsim[gpu]; points then run one after another)")  # fmt: skip
    add_parallel(
        p,
        "worker threads (with --pads: worker processes; 1: in this process), or "
        "processes of --dask local",
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing sweep file")
    p.add_argument("--resume", action="store_true", help="continue from the checkpoint beside --out "
                   "(same arguments): completed points are not recomputed; if --out holds this "
                   "finished sweep, do nothing")  # fmt: skip
    p.add_argument("--checkpoint-every", type=float, default=60.0, metavar="SECONDS",
                   help="save the completed points beside --out (FILE.partial.h5) after 10 s, then this "
                   "often (default: 60 s)")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=run)
