"""Option blocks and option parsing shared by the commands."""

from __future__ import annotations

import argparse
import sys

from mcsim.model.errors import ParameterError

FORMATS = ("table", "csv", "json")


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


def inputs_of(args, parts: bool = False):
    """The surface (the gap's, with a counter-surface: :func:`surfaces_of`) and the material;
    with ``parts`` also the keywords that give simulate() and sweep() the parts of the gap's
    surface, so that their files record them (``{}`` with a flat counter-surface)."""
    from mcsim.cli.display import counterface_notes, print_lines
    from mcsim.model.counterface import gap_surface

    surface, counter, correlation, material = surfaces_of(args)  # resolved (store/config.py)
    combined = gap_surface(surface, counter, correlation)
    if not getattr(args, "quiet", False):
        print_lines(counterface_notes(surface, counter, correlation, combined))
    if not parts:
        return combined, material
    given = {} if counter is None else {"surface": surface, "counter_surface": counter,
                                         "correlation": correlation}  # fmt: skip
    return combined, material, given


def surfaces_of(args):
    """The surface as given, its counter-surface (None: flat), their correlation and the
    material, from ``--surface``, ``--counter-surface``, ``--correlation`` and ``--material``
    (and the surface file's ``[counter_surface]`` and ``[material]`` tables, which the options
    override; a ``--counter-surface`` drops the file's correlation with its counter-surface)."""
    from mcsim.model.counterface import check_correlation
    from mcsim.model.errors import MCSimError
    from mcsim.store.config import (
        counter_surface_in_file,
        load_counter_surface,
        load_material,
        load_surface,
        material_in_surface_file,
    )

    surface = load_surface(args.surface)
    counter, correlation = counter_surface_in_file(args.surface)
    if args.counter_surface is not None:
        try:
            counter, correlation = load_counter_surface(args.counter_surface), None
        except MCSimError as err:
            raise type(err)(f"--counter-surface: {err}") from None
    if args.correlation is not None:
        correlation = check_correlation(_number(args.correlation, "--correlation"), "--correlation")
        if counter is None and correlation != 0:
            raise ParameterError(f"--correlation = {correlation:g} needs a rough counter-surface "
                                 "(--counter-surface, or the surface file's [counter_surface]); "
                                 "a flat one has no heights to correlate with")  # fmt: skip
    if args.material is not None:
        material = load_material(args.material)
    else:
        from mcsim.model.presets import MATERIALS

        material = material_in_surface_file(args.surface) or MATERIALS["silicon"]
    return surface, counter, 0.0 if correlation is None else correlation, material


def _number(text: str, option: str) -> float:
    """A plain number written on the command line (``nan`` and ``inf`` read, to be refused by
    the range check that follows)."""
    try:
        return float(text)
    except ValueError:
        raise ParameterError(f"{option} = {text!r} is not a number (allowed: a number in [-1, 1], "
                             "e.g. 0.3)") from None  # fmt: skip


def parse_turn(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        raise ParameterError(
            f"--turn: cannot read {text!r} (give a separation d/sigma, e.g. --turn=-0.5)"
        ) from None


def resolve_law(args, surface, material) -> tuple[str, list[str]]:
    """The law set (``auto`` resolved on the adhesion map) and the stderr lines to print."""
    from mcsim.physics.adhesion import choose_law, regime_warnings

    lines = []
    law = args.law
    if law == "auto":
        law, reason = choose_law(surface, material)
        lines.append(reason)
    lines += [f"warning: {w}" for w in regime_warnings(surface, material, law)]
    return law, lines


def parse_values(spec: str, dimension: str, option: str) -> list[float]:
    """Values of a CLI option (:func:`mcsim.model.units.parse_values`), at most
    :data:`MAX_SEPARATIONS` of them."""
    from mcsim.model.units import parse_values

    return parse_values(spec, dimension, option, limit=MAX_SEPARATIONS)


def positive_quantity(text: str | None, dimension: str, option: str) -> float | None:
    """A quantity option (:func:`mcsim.model.units.parse_quantity`) that must be > 0, in SI;
    None if not given."""
    from mcsim.model.units import parse_quantity

    if text is None:
        return None
    value = parse_quantity(text, dimension, option)
    if not value > 0:
        raise ParameterError(f"{option} = {text!r} must be positive (allowed: > 0)")
    return value


def positive_values(spec: str, dimension: str, option: str) -> list[float]:
    """:func:`parse_values`, each value > 0."""
    values = parse_values(spec, dimension, option)
    bad = [v for v in values if not v > 0]
    if bad:
        raise ParameterError(f"{option} = {spec!r}: {bad[0]:g} (SI) must be positive "
                             "(allowed: > 0)")  # fmt: skip
    return values


#: Unit of each load-control column (``mcsim analytic --pressure``).
LOAD_UNITS = {
    "pressure": "Pa", "h": "1 (d/sigma)", "contact_fraction": "1 (N_c/N)",
    "load": "1 (force/(A_n K))", "area": "1 (A_r/A_n)", "friction": "1 (tau A_r/(A_n K))",
    "P": "1 (P/(A_n K), Eq. 3)", "F": "1 (F/(A_n K), Eq. 5)", "T": "1 (T/(A_n K), Eq. 7)",
    "mu": "1", "vdw": "1 (p_vdW/K)", "capillary": "1 (p_cap/K)", "vdw_N": "N", "capillary_N": "N",
    "jump": "bool", "equilibrium": "bool", "force_N": "N", "N_c": "1 (count)",
    "load_N": "N", "area_m2": "m^2", "friction_N": "N", "P_N": "N", "F_N": "N", "T_N": "N",
}  # fmt: skip


def area_option(args) -> float | None:
    from mcsim.model.params import check_range
    from mcsim.model.units import parse_quantity

    if args.area is None:
        return None
    return check_range("--area", parse_quantity(args.area, "area", "--area"), "m^2", low=0)


def pressures_option(args, area: float | None):
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


def balancing_h(args, surface, material, environment=None):
    """Separations that balance ``--pressure`` (or ``--load`` over the patch ``--area``)
    on the analytic approach branch (:func:`mcsim.physics.loadcontrol.load_control`), and the
    pressures (Pa)."""
    from mcsim.physics.loadcontrol import load_control

    if args.cycle:
        raise ParameterError("--pressure/--load: load control is on the approach branch only "
                             "(not with --cycle)")  # fmt: skip
    pressure = pressures_option(args, area_option(args))
    result = load_control(surface, material, pressure, args.law, environment)
    if not args.quiet:
        jumped = int(result.jump.sum())
        print(f"mcsim: load control ({result.quantity} = p/K on the approach branch): "
              f"{pressure.size} pressure(s) from {pressure.min():.4g} to {pressure.max():.4g} Pa "
              f"at h = {result.h.max():.6g} .. {result.h.min():.6g}"
              + (f"; {jumped} reached through a jump" if jumped else ""), file=sys.stderr)  # fmt: skip
    return [float(x) for x in result.h], pressure


def integer(low: int, high: int | None = None):
    """argparse type: a whole number >= ``low`` (and <= ``high``) written in digits (``1e9``
    is refused)."""
    allowed = f"integer >= {low}" if high is None else f"integer from {low} to {high}"

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not a whole number written in digits (allowed: {allowed})"
            ) from None
        if value < low or (high is not None and value > high):
            raise argparse.ArgumentTypeError(f"{value} is out of range (allowed: {allowed})")
        return value

    return parse


#: A root seed (numpy's SeedSequence takes non-negative integers only) and a count.
seed_type, count_type = integer(0), integer(1)
#: Worker threads or processes: more than any machine's cores only slows a run down. 1024 is
#: :data:`mcsim.studies.runoptions.MAX_WORKERS`, the API's bound (not imported: ``--help``
#: loads no NumPy; a test checks that the two agree).
workers_type = integer(1, 1024)


#: The registered law sets, for the help texts (without importing them: ``--help`` stays
#: instant); a test checks it against :data:`mcsim.physics.laws.LAW_SETS`.
LAW_SET_NAMES = ("seed", "jkr", "dmt", "maugis-dugdale", "elastic-plastic")


def add_inputs(p: argparse.ArgumentParser, separations: bool = True, law: str = "seed") -> None:
    p.add_argument(
        "--surface",
        required=True,
        help="preset (rough, intermediate, smooth, super-smooth, ...) or FILE.toml",
    )
    p.add_argument(
        "--material",
        help="preset (silicon) or FILE.toml; default: the surface file's [material], else silicon",
    )
    p.add_argument("--counter-surface", metavar="SURFACE",
                   help="a rough surface facing --surface: preset or FILE.toml (Gaussian heights, "
                        "one radius); the gap's surface combines both through their spectral "
                        "moments (docs/physics.md, section 'Two rough surfaces'); default: the surface "
                        "file's [counter_surface], else flat")  # fmt: skip
    p.add_argument("--correlation", metavar="RHO",
                   help="correlation of the two surfaces' heights, in [-1, 1] (> 0: the counter-"
                        "surface partly replicates the surface); default: the surface file's, "
                        "else 0")  # fmt: skip
    why = {
        "seed": "the paper's Eqs. 2, 4, 6 as written, whose curves this command reproduces",
        "auto": "the seed law set has no net load and so no pull-off",
    }
    p.add_argument("--law", default=law, metavar="LAW",
                   help=f"law set: {', '.join(LAW_SET_NAMES)}, or auto (one of jkr, dmt, "
                        "maugis-dugdale, chosen on the Johnson-Greenwood adhesion map); "
                        f"default here: {law} ({why[law]})")  # fmt: skip
    if not separations:
        return
    p.add_argument("--h", required=True, metavar="SPEC",
                   help="separations d/sigma: a list '--h=-1,0,1.5' or start:stop:num '--h=4:-1:51' "
                        f"(at most {MAX_SEPARATIONS})")  # fmt: skip


def add_separations_or_loads(p, balance: str, required: bool = True) -> None:
    """``--h``, or the pressures (``--pressure``) or forces (``--load``, over ``--area``)
    whose balancing separations on the analytic approach branch are used instead (one of
    them ``required``; else the command checks, e.g. :func:`preload_grid`)."""
    mode = p.add_mutually_exclusive_group(required=required)
    mode.add_argument("--h", metavar="SPEC",
                      help="separations d/sigma: a list '--h=-1,0,1.5' or start:stop:num '--h=4:-1:51' "
                           f"(at most {MAX_SEPARATIONS})")  # fmt: skip
    mode.add_argument("--pressure", metavar="SPEC", help="instead of --h: nominal pressures (> 0, Pa "
                      "unless a unit is given), a list '1kPa,1MPa' or start:stop:num[:log] "
                      f"'1kPa:10MPa:31:log'; {balance} (seed: P = p/K, Eq. 3; other law sets: "
                      "load = p/K)")  # fmt: skip
    mode.add_argument("--load", metavar="SPEC", help="instead of --h: applied forces (> 0, N unless a "
                      "unit is given), '1uN,10uN' or a range as for --pressure; pressure = load/--area")  # fmt: skip


def add_parallel(p, workers: str) -> None:
    """``--workers`` (described as ``workers``), ``--scheduler`` and ``--dask``."""
    p.add_argument("--workers", type=workers_type,
                   help=f"{workers} (default: all cores); results do not depend on it")  # fmt: skip
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on an existing Dask cluster, e.g. tcp://host:8786 (needs mcsim[dask])")  # fmt: skip
    p.add_argument("--dask", choices=("local",),
                   help="'local': start a local Dask cluster of --workers processes")  # fmt: skip


def scheduler_of(args, *, processes: bool):
    """Where a sweep's points run: on Dask where asked (``--scheduler``, ``--dask``); else,
    with ``processes``, on worker processes of this machine (points holding pads, whose
    search holds Python's lock much of the time: threads gain little; the README's report
    took about 100 s against 167 s on threads on 2 cores), in the command's own process with
    ``--workers 1``; else on threads (None)."""
    from mcsim.engine.cluster import PROCESSES

    dask = args.scheduler or args.dask
    if dask or not processes:
        return dask
    return None if args.workers == 1 else PROCESSES


def add_preload(p, what: str) -> None:
    """``--preload P``: the closest approach is where the mean approach load balances P."""
    p.add_argument("--preload", metavar="P", help="nominal pressure pressing the surfaces before "
                   f"retraction (Pa unless a unit is given, e.g. 1MPa): {what}")  # fmt: skip


def turn_of(args, surface, material, law, environment=None) -> tuple[float | None, float | None]:
    """The closest approach from ``--turn`` or ``--preload`` (one of them), and the preload (Pa).

    With ``--preload P`` the turn is the approach separation that balances P on the mean
    curve (:func:`mcsim.physics.loadcontrol.preload_turn`, as ``analytic --pressure P``).
    """
    if args.preload is None:
        return parse_turn(args.turn), None
    if args.turn is not None:
        raise ParameterError("--turn and --preload: give one of them (the preload sets the turn)")
    from mcsim.physics.loadcontrol import preload_turn

    pressure = parse_preload(args.preload)
    return preload_turn(surface, material, pressure, law, environment), pressure


#: Grid of ``simulate --cycle --preload`` without ``--h``: ``sweep``'s default, 4 down to -1
#: in steps of 0.1, reaching further down (same step) when the preload's mean turn is lower.
PRELOAD_GRID = (4.0, -1.0, 0.1)


def preload_grid(args, surface, material, law, environment=None):
    """The separations of ``simulate --cycle --preload P`` when no ``--h`` is given:
    :data:`PRELOAD_GRID`, down to 1 below the preload's mean turn
    (:func:`mcsim.physics.loadcontrol.preload_turn`) if that lies below -1; said on stderr.
    Returns them and the :class:`~mcsim.physics.loadcontrol.Preload`, whose turn simulate()
    takes as it is (found once).

    Raises
    ------
    ParameterError
        Without ``--cycle --preload``: one of ``--h``, ``--pressure``, ``--load`` is needed.
    """
    import math

    if not (args.cycle and args.preload is not None):
        raise ParameterError("one of the arguments --h --pressure --load is required (--h may be "
                             "left out only with --cycle --preload)")  # fmt: skip
    from mcsim.physics.loadcontrol import preload_of

    preload = preload_of(surface, material, parse_preload(args.preload), law, environment)
    turn = preload.turn
    top, low, step = PRELOAD_GRID
    low = min(low, math.floor(turn) - 1.0)
    spec = f"{top:g}:{low:g}:{round((top - low) / step) + 1}"
    if not args.quiet:
        print(f"mcsim: no --h given: the cycle runs over --h={spec} (d/sigma; the preload's mean "
              f"turn is h = {turn:.4g}); give --h to choose another grid", file=sys.stderr)  # fmt: skip
    return parse_h(spec), preload


def parse_preload(text: str) -> float:
    """``--preload``: a nominal pressure > 0, Pa."""
    from mcsim.model.units import parse_quantity

    pressure = parse_quantity(text, "pressure", "--preload")
    if not pressure > 0:
        raise ParameterError(f"--preload: {text!r} (allowed: a pressure > 0, e.g. 1MPa)")
    return pressure


def add_environment(p, rh: bool = True) -> None:
    """The environment's options (van der Waals across the gaps, capillary condensation),
    named as the keys of an ``[environment]`` table in kebab case
    (:data:`mcsim.store.config.ENVIRONMENT_KEYS`); without ``--rh`` where ``rh`` is False (a
    command that takes several)."""
    g = p.add_argument_group(
        "environment", "van der Waals attraction across the gaps and capillary condensation "
        "(proximity model over the height distribution); also an [environment] table in the "
        "surface or material file, which these options override. None given: contact only.",
    )  # fmt: skip
    g.add_argument("--hamaker", metavar="A", help="Hamaker constant across the gaps, >= 0 (J "
                   "unless a unit is given: '1.6e-19 J', '0.16 aJ'); silicon in air ~1.6-2.0e-19 J")  # fmt: skip
    g.add_argument("--cutoff", metavar="D0", help="gap below which the surfaces touch, > 0 (m "
                   "unless a unit is given: '0.2 nm'; default 0.165 nm)")  # fmt: skip
    g.add_argument("--retardation-wavelength", metavar="LAMBDA", help="retardation wavelength of "
                   "the van der Waals attraction, > 0 (m unless a unit is given: '100nm'), or "
                   "'none' (non-retarded); the flats' energy A/(12 pi D^2) falls by "
                   "1/(1 + 5.32 D/LAMBDA) (Gregory 1981; default 100 nm)")  # fmt: skip
    if rh:
        g.add_argument("--rh", metavar="RH", help="relative humidity of the vapour, 0 <= RH < 1 "
                       "(default 0: dry)")  # fmt: skip
    g.add_argument("--contact-angle", metavar="THETA", help="contact angle of the liquid, in "
                   "[0, 180) deg: degrees when bare ('20'), or with a unit ('0.35 rad'); >= 90 deg: "
                   "no condensation (default 0)")  # fmt: skip
    g.add_argument("--temperature", metavar="T", help="temperature, > 0 (K unless a unit is "
                   "given; kelvin only; default 298.15 K)")  # fmt: skip
    g.add_argument("--liquid-surface-tension", metavar="GAMMA_L", help="surface tension of the "
                   "liquid, > 0 (J/m^2 unless a unit is given: '72 mJ/m^2'; default water, 0.072)")  # fmt: skip
    g.add_argument("--molar-volume", metavar="V_M", help="molar volume of the liquid, > 0 "
                   "(m^3/mol unless a unit is given: '18 cm^3/mol'; default water, 1.80e-5)")  # fmt: skip
    g.add_argument("--film-thickness", metavar="T", help="adsorbed water film on each face, >= 0 "
                   "(m unless a unit is given: '1.2 nm'); default: the isotherm t(RH) of water on "
                   "silicon oxide, 0.84 nm at RH 0.3, 1.82 nm at 0.9 (docs/physics.md)")  # fmt: skip
    g.add_argument("--structured-film", metavar="T_S", help="thickness of the ice-like first "
                   "layers of the film, >= 0: liquid bridges form only where the film is at least "
                   "this thick (m unless a unit is given; default 0.84 nm, 3 layers: from RH 0.3)")  # fmt: skip
    g.add_argument("--asperity-roughness", metavar="SIGMA_N", help="rms of the asperities' own "
                   "nanoscale roughness, >= 0 (m unless a unit is given: '0.5 nm'; default 0): "
                   "menisci spread across the interface only from the critical humidity RH_cr "
                   "where the Kelvin band 2 r_K cos(theta) reaches 3 SIGMA_N; below it bridges stay "
                   "at the asperity contacts (DelRio et al. 2009; docs/physics.md)")  # fmt: skip


def environment_of(args):
    """The :class:`~mcsim.physics.environment.Environment` of the options over the
    ``[environment]`` tables of the surface and material files, or None if none gives one."""
    from mcsim.store.config import ENVIRONMENT_KEYS, environment_from_values, environment_in_file

    values = {}
    for spec in (args.surface, args.material):
        if spec is not None:
            values |= environment_in_file(spec)
    given = {k: getattr(args, k) for k in ENVIRONMENT_KEYS if getattr(args, k) is not None}
    for key, value in given.items():  # each option on its own, named as written
        environment_from_values({key: value}, f"--{key.replace('_', '-')}")
    if not values and not given:
        return None
    return environment_from_values(values | given)
