"""The ``mcsim`` command line: a thin layer over the Python API.

Errors in the input print one line (``mcsim: error: ...``) and exit with status 2;
``--debug`` shows the traceback instead. Ctrl-C exits with status 130 and leaves no
partial output; ``simulate`` (see :mod:`mcsim.interrupt`) also stops on SIGTERM (status
143) and keeps its progress in the checkpoint beside the run file, for ``--resume``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
from pathlib import Path

from ._version import __version__
from .errors import MCSimError, ParameterError

_FORMATS = ("table", "csv", "json")
#: Most separations one --h spec may ask for (a curve needs tens to hundreds).
MAX_SEPARATIONS = 10_000


def parse_h(spec: str) -> list[float]:
    """``"-1,0,1.5"`` (a list) or ``"4:-1:51"`` (start:stop:num, inclusive) to a list of floats.

    At most :data:`MAX_SEPARATIONS` values.
    """
    import numpy as np

    text = spec.strip()
    if not text:
        raise ParameterError("--h: empty list of separations")
    try:
        if ":" in text:
            start, stop, num = text.split(":")
            start, stop, num = float(start), float(stop), int(num)
        else:
            values = [float(x) for x in text.split(",")]
    except ValueError:
        raise ParameterError(
            f"--h: cannot read {spec!r} (give a list '-1,0,1.5' or start:stop:num '4:-1:51')"
        ) from None
    if ":" in text:
        if not 1 <= num <= MAX_SEPARATIONS:
            raise ParameterError(
                f"--h: {spec!r} asks for {num} points (allowed: 1 <= num <= {MAX_SEPARATIONS})"
            )
        values = np.linspace(start, stop, num).tolist()
    if len(values) > MAX_SEPARATIONS:
        raise ParameterError(
            f"--h: {len(values)} separations, more than the limit of {MAX_SEPARATIONS}"
        )
    bad = [v for v in values if not np.isfinite(v)]
    if bad:
        raise ParameterError(f"--h: separations must be finite, got {bad[0]!r}")
    return values


def _inputs(args):
    from .config import load_material, load_surface, material_in_surface_file

    surface = load_surface(args.surface)
    if args.material is not None:
        material = load_material(args.material)
    else:
        from .presets import MATERIALS

        material = material_in_surface_file(args.surface) or MATERIALS["silicon"]
    return surface, material


def _describe(surface, material) -> list[str]:
    from .params import plasticity_index, surface_energy_parameter

    psi = plasticity_index(surface, material)
    lines = [
        f"surface {surface.name or '(file)'}: sigma = {surface.sigma * 1e9:.4g} nm, R = {surface.R * 1e6:.4g} um, "
        f"eta = {surface.eta * 1e-12:.4g} um^-2, heights {surface.heights.name}",
        f"material {material.name or '(file)'}: K = {material.K / 1e9:.4g} GPa, G = {material.G / 1e9:.4g} GPa, "
        f"gamma = {material.gamma:.4g} J/m^2",
        f"A0 = eta R sigma = {surface.A0:.4g}, B0 = gamma/(K sigma) = {surface_energy_parameter(surface, material):.4g}, "
        f"R0 = R/sigma = {surface.R0:.4g}",
    ]
    if psi is not None:
        note = (
            " (> 1: mostly plastic contacts; the elastic model is questionable)" if psi > 1 else ""
        )
        lines.append(f"plasticity index psi = (E*/H) sqrt(sigma/R) = {psi:.3g}{note}")
    return lines


def _print_rows(
    rows: list[dict], columns: list[str], fmt: str, header: list[str] | None = None
) -> None:
    if fmt == "json":
        clean = [
            {k: (None if isinstance(v, float) and v != v else v) for k, v in r.items()}
            for r in rows
        ]
        print(json.dumps(clean, indent=1, allow_nan=False))  # undefined values are null
        return
    if fmt == "csv":
        import csv

        writer = csv.DictWriter(
            sys.stdout, fieldnames=columns, extrasaction="ignore", lineterminator="\n"
        )
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if isinstance(v, float) and v != v else (repr(v) if isinstance(v, float) else v))
                             for k, v in row.items()})  # fmt: skip
        return
    for line in header or []:
        print(f"# {line}")

    def cell(v):
        if isinstance(v, float):
            return "undefined" if v != v else f"{v:.6g}"
        return str(v)

    table = [[cell(r.get(c, "")) for c in columns] for r in rows]
    widths = [
        max(len(c), *(len(t[i]) for t in table)) if table else len(c) for i, c in enumerate(columns)
    ]
    print("  ".join(c.rjust(w) for c, w in zip(columns, widths)).rstrip())
    for t in table:
        print("  ".join(v.rjust(w) for v, w in zip(t, widths)).rstrip())


# --- commands ----------------------------------------------------------------------------


def _parse_turn(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        raise ParameterError(
            f"--turn: cannot read {text!r} (give a separation d/sigma, e.g. --turn=-0.5)"
        ) from None


def _law(args, surface, material) -> tuple[str, list[str]]:
    """The law set (``auto`` resolved on the adhesion map) and the stderr lines to print."""
    from .adhesion import choose_law, regime_warnings

    lines = []
    law = args.law
    if law == "auto":
        law, reason = choose_law(surface, material)
        lines.append(reason)
    lines += [f"warning: {w}" for w in regime_warnings(surface, material, law)]
    return law, lines


def _cutoff_notes(surface, material, law: str, h) -> list[str]:
    """For ``dmt``: how much of the attraction its tail cutoff drops at separations ``h``."""
    if law != "dmt":
        return []
    import numpy as np

    from .laws import dmt

    h = np.atleast_1d(np.asarray(h, dtype=float))
    frac = dmt.truncated_fraction(surface, material, h)
    where = (f"at h = {h[0]:g}" if h.size == 1 else
             f"from {frac.min():.3g} to {frac.max():.3g} over h = {h.min():g} .. {h.max():g}")  # fmt: skip
    if h.size == 1:
        where = f"{frac[0]:.3g} {where}"
    return [f"note: dmt cuts the van der Waals tail at a gap of {dmt.DEFAULT_CUTOFF:g} z0: "
            f"it drops {where} of the attraction (mcsim.laws.dmt.truncated_fraction)"]  # fmt: skip


def _print_lines(lines: list[str]) -> None:
    for line in lines:
        print(f"mcsim: {line}", file=sys.stderr)


def _contact_inputs(material) -> str:
    def given(value, scale, unit):
        return "not given" if value is None else f"{value * scale:.4g} {unit}"

    return (f"z0 = {given(material.z0, 1e9, 'nm')}, tau = {given(material.tau, 1e-6, 'MPa')}, "
            f"H = {given(material.H, 1e-9, 'GPa')}")  # fmt: skip


def parse_values(spec: str, dimension: str, option: str) -> list[float]:
    """Values of a CLI option (:func:`mcsim.units.parse_values`), at most
    :data:`MAX_SEPARATIONS` of them."""
    from .units import parse_values

    return parse_values(spec, dimension, option, limit=MAX_SEPARATIONS)


#: Unit of each load-control column (``mcsim analytic --pressure``).
LOAD_UNITS = {
    "pressure": "Pa", "h": "1 (d/sigma)", "contact_fraction": "1 (N_c/N)",
    "load": "1 (force/(A_n K))", "area": "1 (A_r/A_n)", "friction": "1 (tau A_r/(A_n K))",
    "P": "1 (P/(A_n K), Eq. 3)", "F": "1 (F/(A_n K), Eq. 5)", "T": "1 (T/(A_n K), Eq. 7)",
    "mu": "1", "jump": "bool", "equilibrium": "bool", "force_N": "N", "N_c": "1 (count)",
    "load_N": "N", "area_m2": "m^2", "friction_N": "N", "P_N": "N", "F_N": "N", "T_N": "N",
}  # fmt: skip


def _area(args) -> float | None:
    from .params import check_range
    from .units import parse_quantity

    if args.area is None:
        return None
    return check_range("--area", parse_quantity(args.area, "area", "--area"), "m^2", low=0)


def _dimensional(curves, area: float) -> dict:
    """Dimensional columns for a nominal area: N_c and forces in N, the area in m^2."""
    forces = curves.forces(area)
    return {("area_m2" if k == "area" else k if k == "N_c" else f"{k}_N"): v
            for k, v in forces.items()}  # fmt: skip


def _pressures(args, area: float | None):
    """Nominal pressures (Pa, > 0) of ``--pressure``, or of ``--load`` over ``--area``."""
    import numpy as np

    if args.load is not None:
        if area is None:
            raise ParameterError("--load needs --area (the nominal area A_n: pressure = load/area)")
        pressure = np.array(parse_values(args.load, "force", "--load")) / area
        option = "--load"
    else:
        pressure = np.array(parse_values(args.pressure, "pressure", "--pressure"))
        option = "--pressure"
    bad = pressure[~(pressure > 0)]
    if bad.size:
        raise ParameterError(f"{option}: {bad[0]:g} Pa is out of range (allowed: > 0, compressive)")
    return pressure


def _load_control(args, surface, material, law: str, notes: list[str]) -> int:

    from .loadcontrol import load_control

    area = _area(args)
    inputs = [x for x in (args.surface, args.material) if x and Path(x).is_file()]
    if args.plot is not None:
        from .outputs import check_output

        if not str(args.plot).endswith(".png"):
            raise ParameterError(
                f"--plot: {args.plot}: the figure is a PNG file, its name must end in .png"
            )
        check_output(args.plot, inputs=inputs, overwrite=args.overwrite)
    pressure = _pressures(args, area)
    result = load_control(surface, material, pressure, law)
    if result.equilibrium.any():
        notes += _cutoff_notes(surface, material, law, result.h[result.equilibrium])
    table = result.columns()
    if area is not None:
        table["force_N"] = pressure * area
        table |= _dimensional(result.curves, area)
    columns = list(table)
    rows = [{c: (bool(v[i]) if v.dtype == bool else float(v[i])) for c, v in table.items()}
            for i in range(pressure.size)]  # fmt: skip
    _print_lines(notes)
    if result.equilibrium.size and not result.equilibrium.all():
        _print_lines(["tensile load beyond the pull-off: no equilibrium (h undefined)"])
    if args.format == "json":
        clean = [{k: (None if isinstance(v, float) and v != v else v) for k, v in r.items()}
                 for r in rows]  # fmt: skip
        out = {"law": result.curves.law, "balanced": result.quantity, "K_Pa": material.K,
               "area_m2": area, "units": {c: LOAD_UNITS[c] for c in columns}, "rows": clean}  # fmt: skip
        print(json.dumps(out, indent=1, allow_nan=False))
    else:
        header = [*_describe(surface, material), f"law set {result.curves.law}: pressure p (Pa) "
                  f"balances {result.quantity} = p/K on the approach branch (K = "
                  f"{material.K / 1e9:.4g} GPa)", "jump: reached through a jump of h; "
                  "equilibrium false: tensile beyond the pull-off"]  # fmt: skip
        _print_rows(rows, columns, args.format, header)
    if args.plot is not None:
        from .plotting import load_control_figure, save

        save(load_control_figure(result), args.plot, overwrite=args.overwrite, inputs=inputs)
    return 0


def cmd_analytic(args) -> int:
    from .analytic import gw_curves

    surface, material = _inputs(args)
    law, notes = _law(args, surface, material)
    if args.h is None:
        if args.branch != "approach" or args.turn is not None:
            raise ParameterError("--branch/--turn: load control is on the approach branch only")
        return _load_control(args, surface, material, law, notes)
    if args.plot is not None:
        raise ParameterError("--plot applies to --pressure/--load only")
    curves = gw_curves(surface, material, parse_h(args.h), law, branch=args.branch,
                       turn=_parse_turn(args.turn))  # fmt: skip
    notes += _cutoff_notes(surface, material, curves.law, curves.h)
    table = curves.columns()
    area = _area(args)
    if area is not None:
        table |= _dimensional(curves, area)
    columns = list(table)
    rows = [{c: float(table[c][i]) for c in columns} for i in range(curves.h.size)]
    if curves.law == "seed":
        meaning = "dimensionless: P, F, T = force/(A_n K) (Eqs. 3, 5, 7); mu = T/(P+F) (Eq. 8)"
    else:
        meaning = ("dimensionless: load = net force/(A_n K), > 0 compressive; area = A_r/A_n; "
                   "friction = tau A_r/(A_n K); mu = friction/load, undefined where load <= 0")  # fmt: skip
    header = _describe(surface, material)
    if curves.law != "seed":
        header.append(_contact_inputs(material))
        turn = (
            "" if curves.turn is None else f" after the closest approach h_turn = {curves.turn:g}"
        )
        header.append(f"law set {curves.law}, branch {curves.branch}{turn}")
    header.append(meaning)
    _print_lines(notes)
    _print_rows(rows, columns, args.format, header)
    return 0


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


def cmd_adhesion(args) -> int:
    import warnings

    from .adhesion import RegimeWarning, adhesion_summary

    surface, material = _inputs(args)
    law, notes = _law(args, surface, material)
    if args.plot:
        from .outputs import check_output

        if not str(args.plot).endswith(".png"):
            raise ParameterError(
                f"--plot: {args.plot}: the figure is a PNG file, its name must end in .png"
            )
        check_output(args.plot, overwrite=args.overwrite)  # before the work, not after it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)  # printed once below
        summary = adhesion_summary(surface, material, law, turn=_parse_turn(args.turn))
        if args.plot:
            from .plotting import adhesion_figure, save

            save(
                adhesion_figure(surface, material, law, summary),
                args.plot,
                overwrite=args.overwrite,
            )
    values = summary.to_dict()
    notes += _cutoff_notes(surface, material, summary.law, summary.h_pull_off)
    turn_from = {"given": "given by --turn", "zero load on approach": "zero approach load"}.get(
        summary.turn_from, summary.turn_from
    )
    _print_lines(notes)
    if args.format == "json":
        out = {k: values[k] for k in ADHESION_KEYS}
        out |= {"turn_from": turn_from, "law": summary.law}
        clean = {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                 for k, v in out.items()}  # fmt: skip
        print(json.dumps(clean, indent=1, allow_nan=False))
        return 0
    rows = [{"quantity": k, "value": values[k], "unit": u, "meaning": m}
            for k, (u, m) in ADHESION_KEYS.items()]  # fmt: skip
    rows = [{**r, "value": math.nan if r["value"] is None else float(r["value"])} for r in rows]
    header = [*_describe(surface, material), _contact_inputs(material), f"law set {summary.law}; turn h_turn = "
              f"{summary.turn:.6g} ({turn_from})"]  # fmt: skip
    _print_rows(rows, ["quantity", "value", "unit", "meaning"], args.format, header)
    return 0


def cmd_paper(args) -> int:
    from .outputs import check_output
    from .paper import paper_monte_carlo, paper_outputs, reproduce_paper

    if Path(args.out).is_dir():  # refuse before the Monte Carlo work, not after it
        for path in paper_outputs(args.out, monte_carlo=not args.no_mc):
            check_output(path, overwrite=args.overwrite)
    mc = None
    if not args.no_mc:
        mc = paper_monte_carlo(args.out, seed=args.seed, overwrite=args.overwrite)
    result = reproduce_paper(out_dir=args.out, mc=mc, overwrite=args.overwrite)
    print(
        f"wrote {len(result['figures'])} figures, {result['curves_csv'].name} and {result['mu_table_csv'].name} to {args.out}"
    )
    return 0


def _default_run_path(surface) -> Path:
    import datetime as dt

    stamp = dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    folder = Path("runs")
    folder.mkdir(exist_ok=True)
    return folder / f"{surface.name or 'surface'}-{stamp}.h5"


@contextlib.contextmanager
def _notes(quiet: bool):
    """Print the library's log records (notices, estimates) as ``mcsim: ...`` lines on stderr."""
    import logging

    logger = logging.getLogger("mcsim")
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("mcsim: %(message)s"))
    handler.setLevel(logging.WARNING if quiet else logging.INFO)
    level, propagate = logger.level, logger.propagate
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    logger.propagate = False
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.setLevel(level)
        logger.propagate = propagate


def cmd_simulate(args) -> int:
    import time

    from .interrupt import Interrupted, interruptible

    with interruptible(), _notes(args.quiet):  # SIGINT/SIGTERM owned before heavy imports
        from .runfile import checkpoint_path
        from .simulation import cli_command, simulate

        surface, material = _inputs(args)
        pressure = None
        if args.h is None:
            h, pressure = _balancing_h(args, surface, material)
        else:
            h = parse_h(args.h)
        out = Path(args.out) if args.out else _default_run_path(surface)
        show_progress = not args.quiet and sys.stderr.isatty()
        t0 = time.perf_counter()
        try:
            run = simulate(
                surface, material, h, args.area, realizations=args.realizations, seed=args.seed, law=args.law,
                count=args.count, cycle=args.cycle, device=args.device, workers=args.workers, scheduler=args.scheduler or args.dask,
                chunk_size=args.chunk_size, keep_heights=args.keep_heights, out=out, overwrite=args.overwrite,
                resume=args.resume, checkpoint_every=args.checkpoint_every, progress=show_progress,
                command=cli_command(),
                extra_attrs=None if pressure is None else {"load_control": json.dumps(
                    {"pressure": pressure.tolist(), "unit": "Pa"})},
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
        if not args.quiet:
            n = run.n_summits
            print(f"wrote {run.path}: {run.spec.realizations} realizations x {len(h)} separations, "
                  f"N = {n.mean():.6g} summits per patch on average, {elapsed:.2f} s")  # fmt: skip
            print(f"next: mcsim compare {run.path}   |   mcsim plot {run.path}")
    return 0


#: Failed points of a sweep listed one per line on stderr; the rest are counted.
MAX_FAILED_SHOWN = 20


def cmd_sweep(args) -> int:
    from .interrupt import Interrupted, interruptible

    with interruptible(), _notes(args.quiet):  # SIGINT/SIGTERM owned before heavy imports
        from .runfile import checkpoint_path
        from .simulation import cli_command
        from .sweeps import sweep

        vary = {}
        for item in args.vary:
            name, sep, spec = item.partition("=")
            if not sep:
                raise ParameterError(f"--vary: cannot read {item!r} (give NAME=SPEC, e.g. "
                                     "sigma=0.3nm:20nm:40:log)")  # fmt: skip
            if name.strip() in vary:
                raise ParameterError(f"--vary: {name.strip()!r} is given twice")
            vary[name.strip()] = spec
        if not args.mc and (
            args.area is not None
            or args.realizations is not None
            or args.seed is not None
            or args.device != "cpu"
        ):
            raise ParameterError("--area, --realizations, --seed and --device apply to the Monte Carlo runs only (add --mc)")  # fmt: skip
        surface, material = _inputs(args)
        out = Path(args.out)
        try:
            result = sweep(
                surface, material, vary, law=args.law, h=parse_h(args.h), turn=_parse_turn(args.turn),
                mc=args.mc, area=args.area, realizations=args.realizations or 1, seed=args.seed, device=args.device,
                workers=args.workers, scheduler=args.scheduler or args.dask, out=out,
                overwrite=args.overwrite, resume=args.resume, checkpoint_every=args.checkpoint_every,
                progress=not args.quiet and sys.stderr.isatty(), command=cli_command(),
            )  # fmt: skip
        except Interrupted as stop:
            partial = checkpoint_path(out)
            saved = f"completed points saved in {partial}: run the same command with --resume to finish it"
            print(f"mcsim: interrupted ({stop}); {saved if partial.exists() else 'no output written'}",
                  file=sys.stderr)  # fmt: skip
            return stop.exit_status
        warned = result.data["regime_warning"]
        n_warned = int((warned != "").sum())
        if n_warned:
            first = next(str(w) for w in warned.ravel() if w)
            print(f"mcsim: warning: {n_warned} of {warned.size} points outside their law set's regime "
                  f"(variable regime_warning), e.g.: {first}", file=sys.stderr)  # fmt: skip
        failed = result.failed
        for inputs, error in failed[:MAX_FAILED_SHOWN]:
            shown = ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
                              for k, v in inputs.items())  # fmt: skip
            print(f"mcsim: point {shown} failed: {error}", file=sys.stderr)
        if len(failed) > MAX_FAILED_SHOWN:
            print(f"mcsim: ... and {len(failed) - MAX_FAILED_SHOWN} more failed points (variable "
                  f"error of {out})", file=sys.stderr)  # fmt: skip
        if not args.quiet:
            print(f"wrote {result.path}: {warned.size} points ({' x '.join(map(str, result.shape))}), "
                  f"{len(result.failed)} failed")  # fmt: skip
        return 1 if result.failed else 0


def _balancing_h(args, surface, material):
    """Separations that balance ``--pressure`` (or ``--load`` over the patch ``--area``)
    on the analytic approach branch (:func:`mcsim.loadcontrol.load_control`), and the
    pressures (Pa)."""
    from .loadcontrol import load_control

    if args.cycle:
        raise ParameterError("--pressure/--load: load control is on the approach branch only "
                             "(not with --cycle)")  # fmt: skip
    pressure = _pressures(args, _area(args))
    result = load_control(surface, material, pressure, args.law)
    if not args.quiet:
        jumped = int(result.jump.sum())
        print(f"mcsim: load control ({result.quantity} = p/K on the approach branch): "
              f"{pressure.size} pressure(s) from {pressure.min():.4g} to {pressure.max():.4g} Pa "
              f"at h = {result.h.max():.6g} .. {result.h.min():.6g}"
              + (f"; {jumped} reached through a jump" if jumped else ""), file=sys.stderr)  # fmt: skip
    return [float(x) for x in result.h], pressure


def cmd_compare(args) -> int:
    from .runfile import read_run

    run = read_run(args.run, allow_incomplete=args.partial)
    rows = run.compare().to_dict("records")
    columns = ["h", "branch", "quantity", "mc_mean", "mc_se", "analytic", "z"]
    notes = sorted({(r["h"], r["note"]) for r in rows if r["note"]}, key=lambda t: -t[0])
    if args.format == "table":
        columns.append("note")
        for r in rows:
            r["note"] = r["note"].split(":")[0]
    _print_rows(
        rows, columns, args.format, header=[f"run {run.path}", "z = (mc_mean - analytic)/mc_se"]
    )
    if not run.complete:
        print(f"mcsim: note: {run.path} is incomplete: compared over its {run.spec.realizations} "
              "completed realization(s)", file=sys.stderr)  # fmt: skip
    if args.format == "csv" and notes:
        for h, note in notes:
            print(f"mcsim: note: h = {h:g}: z left empty: {note}", file=sys.stderr)
    return 0


def cmd_show(args) -> int:
    import numpy as np

    from .runfile import read_run, read_state
    from .sweeps import is_sweep_file, read_sweep

    if is_sweep_file(args.run):
        result = read_sweep(args.run)
        print(result)
        a = result.attrs
        print(
            f"  created  {a.get('created')} by mcsim {a.get('mcsim_version')}\n  command  {a.get('command')}"
        )
        for inputs, error in result.failed[:5]:
            print(f"  failed   {inputs}: {error}")
        return 0
    state, a = read_state(args.run)
    spec = state.spec
    print(f"run file      {args.run}")
    status = "complete" if state.complete else (
        f"INCOMPLETE: {int(state.done_blocks.sum())} of {int(state.n_blocks.sum())} blocks done, "
        f"{int(np.sum(state.done_blocks == state.n_blocks))} of {spec.realizations} realizations complete; "
        "finish it with the same `mcsim simulate` command plus --resume"
    )  # fmt: skip
    print(f"status        {status}")
    print(
        f"created       {a.get('created')} by mcsim {a.get('mcsim_version')} (schema {a.get('schema_version')})"
    )
    print(f"command       {a.get('command')}")
    print(f"seed entropy  {spec.entropy}")
    for line in _describe(spec.surface, spec.material):
        print(f"input         {line}")
    print(f"law set       {spec.law}" + (f" (cycle: approach, then retraction from h = {spec.turn:g})"
                                          if spec.cycle else ""))  # fmt: skip
    print(f"device        {spec.device}")
    print(
        f"patch         A = {spec.area * 1e12:.6g} um^2, N ~ {spec.count}, E[N] = {spec.expected_summits:.6g}"
    )
    print(f"realizations  {spec.realizations}: N = {', '.join(str(int(n)) for n in state.n_summits[:8])}"
          f"{' ...' if spec.realizations > 8 else ''}")  # fmt: skip
    print(f"separations   {spec.h.size}: h = {spec.h.min():g} .. {spec.h.max():g}")
    if "load_control" in a:  # simulate --pressure/--load: the pressures those separations balance
        p = json.loads(a["load_control"])["pressure"]
        print(f"load control  nominal pressure p = {min(p):g} .. {max(p):g} Pa ({len(p)} values)")
    if not np.any(state.done_blocks == state.n_blocks):
        return 0
    z = read_run(args.run, allow_incomplete=True).compare()["z"].to_numpy()
    finite = z[np.isfinite(z)]
    if finite.size:
        part = "" if state.complete else " (completed realizations only)"
        print(f"vs GW         max |z| = {np.max(np.abs(finite)):.2f} over {finite.size} (h, quantity) pairs "
              f"with enough contacts{part}; details: mcsim compare {args.run}")  # fmt: skip
    return 0


def cmd_plot(args) -> int:
    import dataclasses

    import numpy as np

    from .distributions import GAUSSIAN
    from .outputs import check_output
    from .plotting import comparison_figure, run_figure, save
    from .runfile import read_run
    from .sweeps import is_sweep_file

    if len(args.run) > 1 and not args.out:
        raise ParameterError("--out: name the PNG file when plotting several runs")
    out = Path(args.out) if args.out else Path(args.run[0]).with_suffix(".png")
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
        from .plotting import load_run_figure

        if len(runs) > 1:
            raise ParameterError("--versus load: plot one run at a time")
        check_output(out, inputs=args.run, overwrite=args.overwrite)
        save(load_run_figure(run), out, overwrite=args.overwrite, inputs=args.run)
        print(f"wrote {out} (each patch's load and area or friction over the analytic curves)")
        return 0
    other = None  # measured heights: also against the Gaussian GW curves
    if len(runs) == 1 and surface.heights != GAUSSIAN:
        other = out.with_name(f"{out.stem}-vs-gaussian.png")
    for path in (out, other) if other else (out,):  # both refused before either is written
        check_output(path, inputs=args.run, overwrite=args.overwrite)
    figure = run_figure(runs if len(runs) > 1 else run)
    save(figure, out, overwrite=args.overwrite, inputs=args.run)
    print(f"wrote {out}")
    if other:
        gaussian = dataclasses.replace(surface, heights=GAUSSIAN, name=f"{surface.name} (Gaussian)")
        h = np.linspace(run.h.max(), run.h.min(), 200)
        save(comparison_figure(surface, gaussian, run.spec.material, h, run=run), other,
             overwrite=args.overwrite, inputs=args.run)  # fmt: skip
        print(f"wrote {other} (measured heights against the Gaussian of the same sigma, R, eta)")
    return 0


def _plot_sweep(args, sweeps: list[str], out: Path) -> int:
    """``mcsim plot SWEEP.h5``: design curves or design maps (:mod:`mcsim.sweepplots`)."""
    from .outputs import check_output
    from .plotting import save
    from .sweepplots import sweep_figure
    from .sweeps import read_sweep

    if len(args.run) > 1:
        raise ParameterError(f"plot: {sweeps[0]} is a sweep file: plot it on its own (one file)")
    result = read_sweep(sweeps[0])
    if not result.attrs.get("complete", True) and not args.partial:
        raise ParameterError(f"{sweeps[0]}: an incomplete sweep (checkpoint): finish it with the same "
                             "mcsim sweep command plus --resume, or pass --partial to plot its "
                             "completed points")  # fmt: skip
    check_output(out, inputs=args.run, overwrite=args.overwrite)
    figure = sweep_figure(result, kind=args.kind)
    save(figure, out, overwrite=args.overwrite, inputs=args.run)
    print(f"wrote {out}")
    return 0


#: Names of the intervals of ``mcsim pads``, as printed.
_INTERVAL_NAMES = {"clopper-pearson": "Clopper-Pearson", "wilson": "Wilson"}


def cmd_pads(args) -> int:
    from .pads import analytic_pad_pull_off, pad_statistics
    from .runfile import read_run
    from .units import parse_quantity

    fr = None
    if args.restoring_force is not None:
        fr = parse_quantity(args.restoring_force, "force", "--restoring-force")
        if fr < 0:
            raise ParameterError(f"--restoring-force: {args.restoring_force!r} is negative "
                                 "(allowed: a force >= 0, e.g. 2uN)")  # fmt: skip
    if args.plot:
        from .outputs import check_output

        if Path(args.plot).suffix.lower() != ".png":
            raise ParameterError(
                f"--plot: {args.plot}: the figure is a PNG file, its name must end in .png"
            )
        check_output(args.plot, inputs=[args.run], overwrite=args.overwrite)
    run = read_run(args.run, allow_incomplete=args.partial)
    try:
        pull_off = run.pull_off()
    except ParameterError as err:
        raise ParameterError(f"{args.run}: {err}") from None
    stats = pad_statistics(pull_off.force, fr, args.interval)
    analytic = analytic_pad_pull_off(run.spec)
    interval = f"{_INTERVAL_NAMES[args.interval]} 95 %"
    if not run.complete:
        print(f"mcsim: note: {run.path} is incomplete: statistics over its {stats.pads} completed "
              f"pad(s) of {run.attrs.get('realizations')}", file=sys.stderr)  # fmt: skip
    out = stats.to_dict()
    if args.format in ("json", "csv"):
        print(f"mcsim: note: analytic mean {analytic:.6g} N (GW pull-off x A K: minimum of the mean "
              f"curve); per-pad pull-off on the run's grid, spacing {pull_off.resolution:.3g} in h"
              + ("; p_stick_ci: " + interval if args.format == "json" else ""), file=sys.stderr)  # fmt: skip
    if args.format == "json":
        print(json.dumps({k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                          for k, v in out.items()}, indent=1, allow_nan=False))  # fmt: skip
    elif args.format == "csv":
        print("mcsim: note: columns: pad (realization index), pull_off_N (most tensile retraction "
              "load of the pad, a magnitude, N), h_pull_off (its separation d/sigma)", file=sys.stderr)  # fmt: skip
        rows = [{"pad": i, "pull_off_N": float(f), "h_pull_off": float(h)}
                for i, (f, h) in enumerate(zip(pull_off.force, pull_off.h))]  # fmt: skip
        _print_rows(rows, ["pad", "pull_off_N", "h_pull_off"], "csv")
    else:
        ci = out.pop("p_stick_ci", None)
        rows_fr = [] if fr is None else [{"quantity": "restoring_force", "value": fr, "unit": "N"}]
        rows = [{"quantity": k, "value": float(v), "unit": "1" if k in ("pads", "p_stick") else "N"}
                for k, v in out.items()]  # fmt: skip
        rows[7:7] = rows_fr
        if ci is not None:
            rows += [{"quantity": "p_stick_ci_low", "value": ci[0], "unit": "1"},
                     {"quantity": "p_stick_ci_high", "value": ci[1], "unit": "1"}]  # fmt: skip
        rows.append({"quantity": "analytic_mean", "value": analytic, "unit": "N"})
        spec = run.spec
        header = [f"run {run.path}: law {spec.law}, A = {spec.area * 1e12:.4g} um^2, E[N] = "
                  f"{spec.expected_summits:.4g} summits per pad, {stats.pads} pads",
                  "pull-off per pad: most tensile retraction load on the run's grid "
                  f"(spacing {pull_off.resolution:.3g} in h); p_stick = P(pull-off > restoring force), "
                  f"{interval} interval",
                  "analytic_mean: GW pull-off x A K (minimum of the mean curve, not the mean of "
                  "the per-pad minima on the grid)"]  # fmt: skip
        _print_rows(rows, ["quantity", "value", "unit"], "table", header)
    if args.plot:
        from .pads import pads_figure
        from .plotting import save

        fig = pads_figure(pull_off.force, analytic, restoring_force=fr,
                          title=f"{Path(args.run).name}: pull-off of {stats.pads} pads")  # fmt: skip
        save(fig, args.plot, overwrite=args.overwrite, inputs=[args.run])
        print(f"wrote {args.plot}", file=sys.stderr)
    return 0


def cmd_ingest(args) -> int:
    from .ingest import IngestResult, ingest_file
    from .outputs import check_output
    from .simulation import cli_command
    from .units import parse_quantity

    def length(value, option):
        return None if value is None else parse_quantity(value, "length", option)

    out = Path(args.out) if args.out else Path(f"{Path(args.file).stem}.toml")
    extra = IngestResult.companion_paths(out)
    figures = [extra["histogram_figure"]] + ([extra["comparison_figure"]] if args.plot else [])
    for path in [out, extra["histogram"], *figures]:  # all refused before any work or writing
        check_output(path, inputs=[args.file], overwrite=args.overwrite)
    material = None
    if args.plot:
        from .config import load_material

        material = load_material(args.material)
    elif args.material != "silicon":
        raise ParameterError("--material: used only by the --plot figure; add --plot")
    result = ingest_file(
        args.file, unit=args.unit, pixel_size=length(args.pixel_size, "--pixel-size"),
        route=args.route, level=args.level, heights=args.heights, R=length(args.R, "--R"),
        eta=None if args.eta is None else parse_quantity(args.eta, "density", "--eta"),
        channel=args.channel,
    )  # fmt: skip
    for line in result.summary_lines():
        print(line)
    written = result.write_surface(out, overwrite=args.overwrite, command=cli_command())
    from .plotting import comparison_figure, histogram_figure, save

    title = f"{result.heights_from}: {Path(args.file).name}"
    save(histogram_figure(result.distribution, result.distribution.sigma, title=title), figures[0],
         overwrite=args.overwrite, inputs=[args.file])  # fmt: skip
    if args.plot:
        s = result.surface
        fig = comparison_figure(s, result.gaussian_surface, material, parse_h("4:-1:51"))
        save(fig, figures[1], overwrite=args.overwrite, inputs=[args.file])
    print(f"wrote {', '.join(str(p) for p in [*written, *figures])}")
    print(f"next: mcsim analytic --surface {out} --h=4:-1:11")
    return 0


# --- parser ------------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    """argparse with the one-line error contract: ``mcsim: error: ...``, exit status 2."""

    def error(self, message: str):
        text = " ".join(message.split())  # argparse's messages may wrap
        self.exit(2, f"mcsim: error: {text} (see: {self.prog} --help)\n")


def _integer(low: int):
    """argparse type: a whole number >= ``low`` written in digits (``1e9`` is refused)."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not a whole number written in digits (allowed: integer >= {low})"
            ) from None
        if value < low:
            raise argparse.ArgumentTypeError(f"{value} is out of range (allowed: integer >= {low})")
        return value

    return parse


#: A root seed (numpy's SeedSequence takes non-negative integers only) and a count.
_seed, _count = _integer(0), _integer(1)


def _add_inputs(p: argparse.ArgumentParser, separations: bool = True, law: str = "seed") -> None:
    p.add_argument(
        "--surface",
        required=True,
        help="preset (rough, intermediate, smooth, super-smooth, ...) or FILE.toml",
    )
    p.add_argument(
        "--material",
        help="preset (silicon) or FILE.toml; default: the surface file's [material], else silicon",
    )
    meaning = {
        "seed": "the paper as written",
        "auto": "chosen on the Johnson-Greenwood adhesion map",
    }
    p.add_argument("--law", default=law, help=f"law set or auto (default: {law}, {meaning[law]})")
    if not separations:
        return
    p.add_argument("--h", required=True, metavar="SPEC",
                   help="separations d/sigma: a list '--h=-1,0,1.5' or start:stop:num '--h=4:-1:51' "
                        f"(at most {MAX_SEPARATIONS})")  # fmt: skip


def _add_separations_or_loads(p, balance: str) -> None:
    """``--h``, or the pressures (``--pressure``) or forces (``--load``, over ``--area``)
    whose balancing separations on the analytic approach branch are used instead."""
    mode = p.add_mutually_exclusive_group(required=True)
    mode.add_argument("--h", metavar="SPEC",
                      help="separations d/sigma: a list '--h=-1,0,1.5' or start:stop:num '--h=4:-1:51' "
                           f"(at most {MAX_SEPARATIONS})")  # fmt: skip
    mode.add_argument("--pressure", metavar="SPEC", help="instead of --h: nominal pressures (> 0, Pa "
                      "unless a unit is given), a list '1kPa,1MPa' or start:stop:num[:log] "
                      f"'1kPa:10MPa:31:log'; {balance} (seed: P = p/K, Eq. 3; other law sets: "
                      "load = p/K)")  # fmt: skip
    mode.add_argument("--load", metavar="SPEC", help="instead of --h: applied forces (> 0, N unless a "
                      "unit is given), '1uN,10uN' or a range as for --pressure; pressure = load/--area")  # fmt: skip


def _add_parallel(p, workers: str) -> None:
    """``--workers`` (described as ``workers``), ``--scheduler`` and ``--dask``."""
    p.add_argument("--workers", type=_count,
                   help=f"{workers} (default: all cores); results do not depend on it")  # fmt: skip
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on an existing Dask cluster, e.g. tcp://host:8786 (needs mcsim[dask])")  # fmt: skip
    p.add_argument("--dask", choices=("local",),
                   help="'local': start a local Dask cluster of --workers processes")  # fmt: skip


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="mcsim",
        description="Monte Carlo discrete-asperity simulator for adhesion and adhesional friction of rough surfaces.",
    )
    parser.add_argument("--version", action="version", version=f"mcsim {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser(
        "analytic",
        help="analytic GW curves (Eqs. 1-8)",
        description="Analytic GW curves versus h = d/sigma (--h), or versus load: the separation on "
        "the approach branch that balances a nominal pressure p (--pressure, or --load with --area), "
        "p = load K. For the seed the balanced load is the paper's external force P (Eq. 3), "
        "P/(A_n K) = p/K; for the other law sets it is load = force/(A_n K). Where adhesion makes the "
        "load non-monotone the stable separation (reached by raising the load from zero) is reported "
        "and a jump on the way is flagged; a tensile load beyond the pull-off has no equilibrium. "
        "Units: pressure Pa; h, contact_fraction, load, area, friction, mu dimensionless as with --h; "
        "with --area also N_c, force_N (applied), load_N, friction_N, P_N, F_N, T_N (N) and area_m2 (m^2).",
    )
    _add_inputs(p, separations=False)
    _add_separations_or_loads(p, "the curves' separations balance them")
    p.add_argument("--area", metavar="AREA", help="nominal area A_n, e.g. 1mm^2 (m^2 unless a unit "
                   "is given): adds dimensional columns (forces in N)")  # fmt: skip
    p.add_argument("--plot", metavar="FILE.png", help="with --pressure/--load: plot A_r/A_n versus "
                   "p/E* and friction versus load")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace an existing --plot file")
    p.add_argument("--branch", choices=("approach", "retract"), default="approach",
                   help="approach from far away (default) or retraction after --turn")  # fmt: skip
    p.add_argument("--turn", metavar="H", help="closest approach d/sigma before retraction "
                   "(default: the lowest --h)")  # fmt: skip
    p.add_argument("--format", choices=_FORMATS, default="table")
    p.set_defaults(func=cmd_analytic)

    p = sub.add_parser("adhesion", help="pull-off force, work of separation, regime numbers",
                       description="Adhesion summary from the analytic curves: pull-off force and its separation, "
                       "work of separation and hysteresis of an approach-retraction cycle, and the Tabor, "
                       "Maugis, Fuller-Tabor and plasticity numbers.")  # fmt: skip
    _add_inputs(p, separations=False, law="auto")
    p.add_argument("--turn", metavar="H", help="closest approach d/sigma before retraction "
                   "(default: where the approach load is zero, resting under no external load)")  # fmt: skip
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--plot", metavar="FILE.png", help="also draw the approach and retraction load "
                   "curves with the pull-off marked and the work of separation shaded")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace an existing --plot file")
    p.set_defaults(func=cmd_adhesion)

    p = sub.add_parser("paper", help="reproduce the paper's Figs. 2-6", description="Reproduce the paper's Figs. 2-6 "
                       "(analytic curves with Monte Carlo points), a CSV of the curves and a table of mu.")  # fmt: skip
    p.add_argument("--out", default="runs/paper", help="output folder (default: runs/paper)")
    p.add_argument("--no-mc", action="store_true", help="analytic curves only")
    p.add_argument(
        "--seed", type=_seed, default=2026, help="seed of the Monte Carlo patches (default: 2026)"
    )
    p.add_argument("--overwrite", action="store_true",
                   help="replace the files of an earlier reproduction in --out")  # fmt: skip
    p.set_defaults(func=cmd_paper)

    p = sub.add_parser("simulate", help="Monte Carlo run on finite patches, stored as HDF5",
                       description="Sample finite patches, sum the per-summit laws, store the run as HDF5. "
                       "The separations are given (--h), or are those that balance nominal pressures on the "
                       "analytic approach branch (--pressure, or --load over the patch --area), as "
                       "`mcsim analytic --pressure` finds them; `mcsim plot` then draws each patch's "
                       "load and area.")  # fmt: skip
    _add_inputs(p, separations=False)
    _add_separations_or_loads(p, "the run's separations balance them")
    p.add_argument(
        "--area", required=True, help="patch area: m^2 or with a unit ('100um^2', '0.01mm^2')"
    )
    p.add_argument(
        "--realizations", type=_count, default=1, help="independent patches (default: 1)"
    )
    p.add_argument(
        "--seed",
        type=_seed,
        help="root seed, an integer >= 0 (default: fresh entropy, recorded in the file)",
    )
    p.add_argument(
        "--count",
        choices=("poisson", "fixed"),
        default="poisson",
        help="N ~ Poisson(eta A) or round(eta A)",
    )
    p.add_argument(
        "--cycle",
        action="store_true",
        help="approach over the --h grid (descending), then retraction back over the same grid "
        "from its lowest value; both branches stored",
    )
    p.add_argument(
        "--device",
        choices=("cpu", "cuda"),
        default="cpu",
        help="sample and sum on the CPU or on an NVIDIA GPU (needs mcsim[gpu]; other random "
        "streams than the CPU's, recorded in the run file)",
    )
    p.add_argument("--out", help="run file (default: runs/<surface>-<time>.h5)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing run file")
    _add_parallel(p, "worker threads")
    p.add_argument(
        "--chunk-size",
        type=_count,
        default=1 << 18,
        help="summits per task (results do not depend on it)",
    )
    p.add_argument(
        "--keep-heights", action="store_true", help="store the sampled heights (compressed)"
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue from the checkpoint beside --out (same arguments); "
        "without one, start from the beginning",
    )
    p.add_argument("--checkpoint-every", type=float, default=60.0, metavar="SECONDS",
                   help="save progress beside --out (RUN.partial.h5) after 10 s, then this often (default: 60 s)")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=cmd_simulate)

    p = sub.add_parser("sweep", help="curves and adhesion summaries over a grid of inputs, as HDF5",
                       description="Analytic curves over --h, regime numbers and, for law sets with a load and a "
                       "retraction branch, the adhesion summary (as mcsim analytic and mcsim adhesion) at every "
                       "point of the outer product of the --vary inputs; optionally a Monte Carlo run per point. "
                       "One netCDF-compatible HDF5 file: xarray.open_dataset(FILE, engine='h5netcdf').")  # fmt: skip
    _add_inputs(p, separations=False)
    p.set_defaults(law=None)
    p.add_argument("--vary", action="append", required=True, metavar="NAME=SPEC",
                   help="input to vary (repeatable; the grid is their outer product, in this order): sigma, R, "
                   "eta, E (both solids), E1, E2, nu (both), nu1, nu2, gamma, z0, tau, H, law (a list, e.g. "
                   "law=jkr,dmt,maugis-dugdale), area (pad area, with --mc). SPEC: start:stop:num[:log] or a "
                   "list a,b,c; each value with an optional unit, a bare number is SI "
                   "(sigma=0.3nm:20nm:40:log, gamma=0.05:1:5 in J/m^2)")  # fmt: skip
    p.add_argument("--out", required=True, metavar="FILE.h5", help="sweep file (HDF5)")
    p.add_argument("--h", default="4:-1:51", metavar="SPEC",
                   help="separations d/sigma of the curves (default 4:-1:51)")  # fmt: skip
    p.add_argument("--turn", metavar="H", help="closest approach d/sigma before retraction for the "
                   "adhesion summary (default: where the approach load is zero)")  # fmt: skip
    p.add_argument("--mc", action="store_true", help="also one Monte Carlo run per point (in memory): "
                   "mean and standard error of each curve")  # fmt: skip
    p.add_argument(
        "--area", help="patch area of the Monte Carlo runs: m^2 or with a unit ('100um^2')"
    )
    p.add_argument("--realizations", type=_count, help="patches per point (default: 1)")
    p.add_argument("--seed", type=_seed, help="root seed of the Monte Carlo runs (point i uses its own "
                   "child stream of it; default: fresh entropy, recorded in the file)")  # fmt: skip
    p.add_argument("--device", choices=("cpu", "cuda"), default="cpu",
                   help="where the Monte Carlo runs sample and sum (cuda: this machine's GPU, needs "
                   "mcsim[gpu]; points then run one after another)")  # fmt: skip
    _add_parallel(p, "worker threads, or processes of --dask local")
    p.add_argument("--overwrite", action="store_true", help="replace an existing sweep file")
    p.add_argument("--resume", action="store_true", help="continue from the checkpoint beside --out "
                   "(same arguments): completed points are not recomputed")  # fmt: skip
    p.add_argument("--checkpoint-every", type=float, default=60.0, metavar="SECONDS",
                   help="save the completed points beside --out (FILE.partial.h5) after 10 s, then this "
                   "often (default: 60 s)")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=cmd_sweep)

    p = sub.add_parser("compare", help="Monte Carlo versus analytic, with z-scores",
                       description="For every h and quantity: MC mean, its standard error, the analytic value and "
                       "z = (mc - analytic)/se.")  # fmt: skip
    p.add_argument("run", help="run file (.h5)")
    p.add_argument("--format", choices=_FORMATS, default="table")
    p.add_argument(
        "--partial",
        action="store_true",
        help="accept an incomplete run: use its completed realizations",
    )
    p.set_defaults(func=cmd_compare)

    p = sub.add_parser(
        "show",
        help="human summary of a run or sweep file",
        description="Summarise a run or sweep file.",
    )
    p.add_argument("run", help="run file or sweep file (.h5)")
    p.set_defaults(func=cmd_show)

    p = sub.add_parser("plot", help="Monte Carlo points over the analytic curves, or a sweep's design curves/maps",
                       description="Plot a run: Monte Carlo means with error bars over the analytic curves. "
                       "Plot a sweep file (mcsim sweep): pull-off pressure, work of separation and mu against "
                       "one varied input (log axis for a log grid), or maps over two with the adhesion-map "
                       "regime boundaries.")  # fmt: skip
    p.add_argument(
        "run", nargs="+", help="run file(s) (.h5); several are overlaid; or one sweep file"
    )
    p.add_argument("--kind", choices=("auto", "lines", "map"), default="auto",
                   help="sweep files: 'lines' (against the first input, a line per value of the second), "
                   "'map' (two numeric inputs), 'auto' (default: a map for two numeric inputs)")  # fmt: skip
    p.add_argument("--out", help="PNG file (default: next to the run file; required for several)")
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
    p.set_defaults(func=cmd_plot)

    p = sub.add_parser("pads", help="pull-off statistics of finite pads from a --cycle run",
                       description="Per-pad pull-off force of a --cycle Monte Carlo run (one pad per realization): "
                       "mean, standard error, standard deviation, 5/50/95 % quantiles (N) and, with a restoring "
                       "force, the probability that a pad sticks with its 95 % interval (Clopper-Pearson, or "
                       "Wilson's score interval). --format csv lists each pad's pull-off force (N) instead.")  # fmt: skip
    p.add_argument(
        "run", help="run file (.h5) of `mcsim simulate ... --cycle` with a contact law set"
    )
    p.add_argument("--restoring-force", metavar="F",
                   help="force pulling the pad off: N or with a unit ('2uN', '500nN'); a pad sticks when "
                        "its pull-off exceeds it")  # fmt: skip
    p.add_argument("--interval", choices=("clopper-pearson", "wilson"), default="clopper-pearson",
                   help="95 %% interval of the probability of sticking: Clopper-Pearson exact (default; "
                        "coverage never below 95 %%) or Wilson's score interval (Wilson 1927; shorter)")  # fmt: skip
    p.add_argument("--format", choices=_FORMATS, default="table",
                   help="table or json: the statistics; csv: one row per pad (pull-off in N)")  # fmt: skip
    p.add_argument(
        "--partial",
        action="store_true",
        help="accept an incomplete run (a checkpoint RUN.partial.h5): its completed pads",
    )
    p.add_argument(
        "--plot",
        metavar="FILE.png",
        help="histogram and CDF of the pad pull-off with the analytic mean",
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing --plot file")
    p.set_defaults(func=cmd_pads)

    p = sub.add_parser("ingest", help="height map or histogram to a surface file",
                       description="Read a measured height map (.gwy .ibw .nid .npy .xyz, text matrix) or a text "
                       "histogram; print its height and summit statistics (direct and spectral routes); write a "
                       "surface TOML file with the measured summit-height histogram beside it.")  # fmt: skip
    p.add_argument("file", help="height map or text histogram")
    p.add_argument("--channel", help="channel of a multi-channel file (.gwy .ibw .nid; default: the "
                   "height channel); an unknown name lists the file's channels")  # fmt: skip
    p.add_argument("--unit", help="height unit if the file stores none (e.g. nm)")
    p.add_argument("--pixel-size", help="pixel size if the file stores none (e.g. 10nm)")
    p.add_argument("--out", help="surface file (default: <file stem>.toml here)")
    p.add_argument("--overwrite", action="store_true", help="replace existing output files")
    p.add_argument("--route", choices=("direct", "spectral"), default="direct",
                   help="summit statistics written as sigma, R, eta (default: direct)")  # fmt: skip
    p.add_argument("--level", default="plane", choices=("none", "plane", "poly2", "poly3", "poly4", "poly5"),
                   help="levelling before analysis (default: plane; none removes the mean only)")  # fmt: skip
    p.add_argument("--heights", choices=("summits", "map"), default="summits",
                   help="histogram written: direct-route summit heights (default) or all map heights")  # fmt: skip
    p.add_argument("--R", help="summit radius for a histogram input (e.g. 1.7um)")
    p.add_argument("--eta", help="summit density for a histogram input (e.g. 17um^-2)")
    p.add_argument("--plot", action="store_true",
                   help="also plot the analytic curves against the Gaussian GW curves")  # fmt: skip
    p.add_argument("--material", default="silicon",
                   help="material of the --plot curves: preset or FILE.toml (default: silicon)")  # fmt: skip
    p.set_defaults(func=cmd_ingest)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as done:  # --help, --version or a one-line usage error: its status
        return done.code if isinstance(done.code, int) else 2
    try:
        return args.func(args)
    except KeyboardInterrupt:
        print("mcsim: interrupted; no output written", file=sys.stderr)
        return 130
    except BrokenPipeError:  # output piped into `head` and the like
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except (MCSimError, OSError) as err:
        if args.debug:
            raise
        message = (
            str(err)
            if isinstance(err, MCSimError)
            else f"{err.filename or ''}: {err.strerror or err}"
        )
        print(f"mcsim: error: {message}", file=sys.stderr)
        return 2


#: Young collections between two full ones of the cyclic garbage collector in a command
#: (Python's default: 10). See :func:`console`.
FULL_COLLECTION_EVERY = 10_000


def console() -> None:
    """Entry point of the ``mcsim`` command and ``python -m mcsim``.

    Once the exit status is decided, SIGINT and SIGTERM are ignored, so that a late
    signal can neither kill the interpreter while it exits nor print a traceback.

    The cyclic garbage collector leaves the start-up's objects alone: importing NumPy,
    SciPy, h5py and numba's registries makes ~10⁵ long-lived objects and hardly any
    garbage, yet each full collection traverses them all (≈0.1 s for the two a
    ``simulate`` start-up triggers), and the interpreter's last collection at exit
    once more (≈0.3 s). So a command runs full collections only after
    :data:`FULL_COLLECTION_EVERY` young ones (garbage that dies young, the bulk of
    it, is still collected at once), and once the exit status is decided everything is
    frozen (:func:`gc.freeze`): the process ends without traversing it. The API is
    unaffected; nothing here touches the numbers.
    """
    import gc
    import signal

    young, middle, _ = gc.get_threshold()
    gc.set_threshold(young, middle, FULL_COLLECTION_EVERY)
    code = main()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, signal.SIG_IGN)
    gc.freeze()
    raise SystemExit(code)


if __name__ == "__main__":
    console()
