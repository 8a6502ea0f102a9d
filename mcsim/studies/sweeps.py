"""Parameter sweeps: analytic curves, adhesion summaries (and optionally Monte Carlo) on a grid.

(The module is ``sweeps``, plural, so that the function :func:`mcsim.sweep` is never
shadowed by a submodule of the same name once the module is imported.)

>>> import mcsim
>>> from mcsim.model.presets import SURFACES, MATERIALS
>>> result = mcsim.sweep(SURFACES["smooth"], MATERIALS["silicon"], law="dmt",
...                      vary={"sigma": "0.3nm:20nm:40:log", "gamma": "0.05:1:5"},
...                      out="design.h5")                               # doctest: +SKIP
>>> result.table()                # one row per grid point          # doctest: +SKIP
>>> xarray.open_dataset("design.h5", engine="h5netcdf")             # doctest: +SKIP

The grid is the outer product of the varied inputs, in the order given (C order: the
last varies fastest). Every point is one independent task: the GW curves of
:func:`mcsim.gw_curves` on approach over ``h``, the regime numbers of
:mod:`mcsim.physics.adhesion` and, for a law set with a net load and a retraction branch,
:func:`mcsim.physics.adhesion.adhesion_summary` (the numbers ``mcsim analytic`` and ``mcsim
adhesion`` give for the same inputs, bit for bit; for the ``jkr`` law set without ``mc``
they come from the compiled batch of :mod:`mcsim.engine.maps.designmap`, equal to them within its
stated tolerances, many times faster); with ``mc``, one Monte Carlo run
(:func:`mcsim.simulate`, in memory) whose seed derives from (``seed``, point index)
alone. Points run on threads or on Dask; the numbers do not depend on where or in what
order. A point that fails (an out-of-range combination, a root not found) is recorded
with its message; its outputs from the steps before the failure are kept (e.g. the
curves where only the adhesion summary fails), the others are NaN.

The file's layout is described in :mod:`mcsim.store.sweepfile`.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime as _dt
import functools
import json
import logging
import math
import sys
import time
import warnings
from collections.abc import Mapping
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from mcsim._version import __version__
from mcsim.engine import interrupt
from mcsim.engine.cluster import PROCESSES, process_pool
from mcsim.engine.montecarlo import FIRST_CHECKPOINT, default_workers, in_order
from mcsim.model.counterface import as_counter, check_correlation, gap_surface
from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface, check_range, check_seed, check_separations
from mcsim.model.presets import as_material, as_surface
from mcsim.physics.adhesion import RegimeWarning, ValidityWarning
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.laws import get_law_set
from mcsim.store import inputgroup
from mcsim.store.claim import claim_output
from mcsim.store.sweepfile import SCHEMA_VERSION, Sweep, empty_sweep, read_sweep, write_sweep
from mcsim.store.sweepvariables import (
    ENVIRONMENT_INPUTS,
    PAD_INPUTS,
    dimension_name,
    plain,
)
from mcsim.studies.runoptions import check_checkpoint_every, check_workers
from mcsim.studies.sweepinputs import (
    check_floor,
    check_friction,
    check_monte_carlo,
    check_pads,
    check_values,
    check_vary,
)
from mcsim.studies.sweeppoint import (
    MAX_POINTS,
    Config,
    batches,
    evaluate_batch,
    evaluate_quietly,
    has_summary,
    make_point,
    point_curves,
)
from mcsim.studies.sweepresume import already_finished, read_checkpoint, recorded_seed, restore

log = logging.getLogger(__name__)


#: Fewest pads in all (tasks × pads a point) that a pads sweep on ``"processes"`` sends to
#: worker processes where no importance sampling can run (:func:`_pool_pays`): 100 pads take
#: 0.15–3 CPU s, two workers' start about 2.
POOL_PADS = 100

#: Separations d/σ of the curves unless given.
DEFAULT_H = tuple(np.linspace(4.0, -1.0, 51).tolist())


def sweep(
    surface: Surface | str,
    material: Material | str,
    vary: Mapping,
    *,
    law: str | None = None,
    h=DEFAULT_H,
    turn: float | None = None,
    environment: Environment | None = None,
    mc: bool = False,
    pads: int | None = None,
    restoring_force: float | str | None = None,
    preload: float | str | None = None,
    tail: bool | None = None,
    floor: float = 0.0,
    friction: bool = False,
    tangential_force: float | str | None = None,
    area: float | str | None = None,
    realizations: int = 1,
    seed: int | None = None,
    device: str = "cpu",
    workers: int | None = None,
    scheduler=None,
    out: str | Path | None = None,
    overwrite: bool = False,
    resume: bool = False,
    checkpoint_every: float = 60.0,
    progress: bool = False,
    command: str | None = None,
    counter_surface: Surface | str | None = None,
    correlation: float = 0.0,
) -> Sweep:
    """Analytic curves, adhesion summaries and regime numbers on a grid of inputs.

    Parameters
    ----------
    surface, material : Surface, Material or str
        The inputs at every point, before the varied ones are set, or the names of
        presets (``"smooth"``, ``"silicon"``).
    vary : mapping of str to spec
        Input name to its values, in grid order: ``sigma``, ``R``, ``eta`` (surface),
        ``E`` (both E1 and E2), ``E1``, ``E2``, ``nu`` (both), ``nu1``, ``nu2``,
        ``gamma``, ``z0``, ``tau``, ``H`` (material), ``law`` (law-set names or
        ``auto``), ``area`` (pad area, m², with ``mc`` only), ``preload`` (Pa; the pads
        of points that differ in it alone are the same), with ``pads`` ``restoring_force``
        and ``tangential_force`` (N), and the environment's
        ``rh``, ``hamaker`` (J), ``contact_angle`` (rad; degrees when bare in a
        string), ``cutoff`` (m), ``temperature`` (K), ``film_thickness``,
        ``structured_film``, ``asperity_roughness`` and ``retardation_wavelength`` (m). Values: a string
        ``"start:stop:num[:log]"`` or ``"a,b,c"`` with optional units (a bare number
        is SI), or a sequence (numbers in SI).
    law : str, optional
        Law set at every point (default ``"seed"``), or ``"auto"`` (chosen per point on
        the adhesion map); not together with a varied ``law``.
    h : array_like
        Separations d/σ of the curves (default 4 … −1, 51 values).
    turn : float, optional
        Closest approach d/σ before retraction for the adhesion summary (default:
        zero approach load, as ``mcsim adhesion``).
    environment : Environment or mapping, optional
        An Environment, or its fields as a mapping (:func:`~mcsim.physics.environment.as_environment`).
        Van der Waals and capillary attraction at every point, before the varied
        environment inputs are set (those alone start from the defaults of
        :class:`~mcsim.physics.environment.Environment`: no Hamaker constant, dry). With
        one, the curves gain ``vdw``, ``capillary`` and the net ``load`` and the summary
        the works of the attraction, as ``mcsim analytic`` and ``mcsim adhesion``.
    mc : bool
        Also run :func:`mcsim.simulate` at each point (``realizations`` patches of
        ``area``), storing the mean and standard error of each curve.
    pads : int, optional
        Also simulate this many pads of ``area`` through a cycle at each point, from
        their own stream (:func:`pads_seed`), and store their pull-off statistics and
        probability of sticking (:data:`mcsim.studies.pads.PAD_VARIABLES`). Each pad
        retracts after its own turn under force control with ``preload``, else after the
        adhesion summary's turn.
    restoring_force : float or str, optional
        With ``pads`` (required, unless ``friction`` or a tangential force): F_r, N or with a
        unit; a pad sticks when its pull-off exceeds it.
    preload : float or str, optional
        Nominal pressure P (Pa or with a unit, >= 0): the adhesion summary's turn is the
        approach separation that balances P on the mean curve
        (:func:`mcsim.physics.loadcontrol.preload_turn`), and pads are pressed with P·A.
        Not together with ``turn``; or vary it (``vary={"preload": ...}``).
    tail : bool, optional
        With ``pads``: p_stick (and p_slip) by importance sampling (:mod:`mcsim.studies.tail`)
        where the pads see fewer than 10 on the rarer side (None, needs >= 100 pads, else the
        fraction stays), at every point (True, needs >= 100 pads) or never (False); variables
        ``p_stick_method`` and ``p_stick_ess`` (:func:`mcsim.studies.pads.tail_p_stick`).
    floor : float
        With ``pads``: importance sampling resolves p_stick (and p_slip) only down to this
        probability, in [0, 1): where its stages show the rarer side below it, it stops and
        gives that bound (:func:`mcsim.studies.tail.importance_p_stick`; ``mcsim report``
        sets 0.01 over the devices of the lot). 0: to the estimate.
    friction : bool
        With ``pads``: also each pad's static friction at its turn and μ_s
        (:mod:`mcsim.studies.padfriction`; variables
        :data:`mcsim.store.sweepvariables.FRICTION`).
    tangential_force : float or str, optional
        With ``pads`` (implies ``friction``): F, N or with a unit (finite, >= 0); a pad slips
        when its static friction is below it: ``p_slip`` and its interval
        (:data:`mcsim.store.sweepvariables.SLIP`). Or vary it (``tangential_force``).
    area : float or str, optional
        Patch area of the Monte Carlo runs and the pads, m² or with a unit.
    realizations : int
        Patches per point.
    seed : int, optional
        Root seed of the Monte Carlo runs; point i uses :func:`point_seed` (seed, i).
    device : {"cpu", "cuda"}
        Where the Monte Carlo runs sample and sum (``"cuda"``: this machine's GPU, see
        :func:`mcsim.simulate`; points then run one after another, not on Dask).
    workers : int, optional
        Local worker threads (1 to 1024; all cores by default), or the worker processes of
        ``"processes"`` or of a ``"local"`` Dask cluster.
    scheduler : str or dask.distributed.Client, optional
        ``"local"``, a scheduler address or a client, as in :func:`mcsim.simulate`; or
        ``"processes"``: the points on ``workers`` worker processes of this machine, no
        Dask needed (:func:`mcsim.engine.cluster.process_pool`; faster than threads where
        the points hold pads, whose search runs much in Python; a script that calls it
        needs ``if __name__ == "__main__":``, as for any spawned process). No more
        processes than tasks start; one task (points whose pads act alike are one task)
        runs in this process, and its pads, plain and importance sampling's, on ``workers``
        worker processes (:func:`mcsim.studies.pads.finite_pads`); fewer than
        :data:`POOL_PADS` pads in all, where no importance sampling can run, in this process
        one after another (:func:`_pool_pays`).
    out : str or path-like, optional
        Write the sweep (HDF5, see the module docstring) atomically; completed points
        are checkpointed in ``<stem>.partial<suffix>`` beside it.
    overwrite : bool
        Replace an existing file (and start again from scratch).
    resume : bool
        Continue from the checkpoint beside ``out``: completed points are not recomputed.
        If ``out`` already holds this finished sweep (the same ``definition``; without
        ``seed``, any seed), it is returned untouched with a notice; a finished sweep of
        other inputs is refused, naming the first that differs.
    checkpoint_every : float
        Seconds between checkpoints (a number, s, >= 0; the first after 10 s).
    progress : bool
        A progress bar over the points on stderr.
    command : str, optional
        Provenance string stored in the file (the CLI passes its command line).
    counter_surface : Surface or str, optional
        A rough counter-surface facing ``surface`` (or a preset's name): every point is of
        the gap's surface, :func:`mcsim.model.counterface.combine` of the two with
        ``correlation``, and the file records the parts (root attributes
        ``surface_as_given``, ``counter_surface``, ``correlation``). ``sigma``, ``R`` and
        ``eta`` are then not varied (they are the combination's). None or ``"flat"``
        (default): a flat counter-surface, and the file is as before.
    correlation : float
        ρ, the correlation of the two surfaces' heights, in [-1, 1]; 0 without a
        counter-surface.

    Returns
    -------
    Sweep
        Failed points are in ``Sweep.failed`` (and the ``error`` variable).

    Raises
    ------
    ParameterError
        Bad ``vary`` (unknown input, wrong unit, empty range, duplicate, ``area``
        without ``mc``, more than :data:`MAX_POINTS` points) or other bad input.
    mcsim.engine.interrupt.Interrupted
        On SIGINT or SIGTERM, once the completed points are saved.
    """
    given, material = as_surface(surface), as_material(material)  # resolved here, once
    correlation = check_correlation(correlation)
    counter = as_counter(counter_surface)
    surface, pair = gap_surface(given, counter, correlation), {}
    if counter is not None:  # a rough counter-surface: its parts recorded
        pair = inputgroup.counterface_attrs(given, counter, correlation)
    environment = as_environment(environment)
    names, grid = check_vary(vary, law, mc or bool(pads), bool(pads))
    combined = [n for n in names if n in ("sigma", "R", "eta")]
    if pair and combined:
        raise ParameterError(f"vary {combined[0]}: with a counter-surface the surface's sigma, R "
                             "and eta are the combination's, not inputs: vary them in the "
                             "surfaces and sweep each pair")  # fmt: skip
    tangential_force, friction = check_friction(pads, friction, tangential_force, names)
    if friction and "tau" not in names:  # a law set without friction: refused before any point
        from mcsim.physics.friction import friction_rule

        laws = grid[names.index("law")] if "law" in names else [law or "seed"]
        for name in laws:
            if name != "auto":
                friction_rule(str(name), material)
    restoring_force, preload = check_pads(pads, restoring_force, preload, turn,
                                           "restoring_force" in names, tail, friction,
                                           "preload" in names)  # fmt: skip
    floor = check_floor(floor, pads)
    checkpoint_every = check_checkpoint_every(checkpoint_every)
    workers = check_workers(workers)
    law = "seed" if law is None else law
    if law != "auto":
        get_law_set(law)
    h = tuple(check_separations(h).tolist())
    turn = None if turn is None else check_range("turn", turn, "1")
    area_m2 = check_monte_carlo(mc, pads, area, names, realizations, device, scheduler)
    if mc and device == "cuda":
        workers = 1  # one GPU; each point's run keeps it busy
    if resume and out is None:
        raise ParameterError("resume needs the sweep file to continue (out=...)")
    shape = tuple(len(v) for v in grid)
    if math.prod(shape) > MAX_POINTS:
        raise ParameterError(f"vary: the grid has {math.prod(shape)} points "
                             f"({' x '.join(map(str, shape))}), more than the limit of {MAX_POINTS}")  # fmt: skip
    if environment is None and any(n in ENVIRONMENT_INPUTS for n in names):
        environment = Environment()
    check_values(surface, material, environment, names, grid)
    seed = check_seed(seed)
    dims = [dimension_name(n) for n in names]
    with interrupt.interruptible(), contextlib.ExitStack() as stack:
        if mc:
            stack.enter_context(_quiet_point_runs())
        claim = None
        if out is not None:
            claim = claim_output(stack, out, overwrite=overwrite, resume=resume, what="sweep",
                                 read_finished=read_sweep, read_checkpoint=read_checkpoint)  # fmt: skip
        seed_given = seed is not None
        if seed is None and claim is not None:
            seed = recorded_seed(claim)
        entropy = np.random.SeedSequence(seed).entropy if mc or pads else None
        config = Config(h, turn, mc, realizations, entropy, device, pads, restoring_force, preload,
                        tail, friction, tangential_force, floor)  # fmt: skip
        result = _empty_result(material, law, names, dims, grid, config, environment is not None,
                               "restoring_force" in names, "tangential_force" in names)  # fmt: skip
        if command is None:
            command = (
                f"mcsim.sweep(vary={ {n: _shown(v) for n, v in zip(names, grid)} }, law={law!r})"
            )
        attrs = _attrs(surface, material, environment, law, dims, grid, config, area_m2, command,
                       pair)  # fmt: skip
        if claim is not None and claim.finished is not None:
            return already_finished(claim, attrs, seed_given)
        done = np.zeros(shape, dtype=bool)
        if claim is not None and claim.checkpoint is not None:
            done = restore(claim, result, attrs, shape)
        points = (
            make_point(
                surface,
                material,
                environment,
                law,
                area_m2,
                names,
                values,
                index,
                _pads_index(index, names, shape),
            )
            for index, values in enumerate(_product(grid))
            if not done.flat[index]
        )
        checkpoint = None
        if claim is not None:
            checkpoint = functools.partial(
                write_sweep, claim.partial, result, attrs, complete=False
            )
        # Recorded per point instead; restored only once the last point has stopped.
        stack.enter_context(warnings.catch_warnings())
        warnings.simplefilter("ignore", RegimeWarning)
        _run(stack, points, config, result, done, workers, scheduler, progress, checkpoint,
             checkpoint_every)  # fmt: skip
        if claim is None:
            final = dataclasses.replace(result, attrs=attrs)
        else:
            claim.finish(lambda path: write_sweep(path, result, attrs, complete=True))
            final = dataclasses.replace(result, attrs=attrs, path=claim.out)
    for line in area_warnings(final):
        warnings.warn(line, ValidityWarning, stacklevel=2)
    return final


def area_warnings(result: Sweep) -> list[str]:
    """At most one line: GW's real contact area A_r/A_n of the sweep's curves past the nominal
    area, or past where independent summits hold, at some point and separation
    (:func:`mcsim.physics.validity.area_warnings` on the largest; how many points; which one).

    Parameters
    ----------
    result : Sweep
        A sweep with the curves' variable ``area`` (none: no line).
    """
    from mcsim.physics.validity import INTERACTING_AREA
    from mcsim.physics.validity import area_warnings as lines_of
    from mcsim.store.sweepvariables import plain

    area = result.data.get("area")
    if area is None or not np.any(area > INTERACTING_AREA):
        return []
    h = np.broadcast_to(result.coords["h"], area.shape)
    worst = np.unravel_index(int(np.nanargmax(area)), area.shape)
    limit = 1.0 if area[worst] > 1 else INTERACTING_AREA
    count = int(np.sum(np.nanmax(area, axis=-1) > limit))
    at = ", ".join(f"{d} = {plain(result.coords[d][i])}" for d, i in zip(result.grid, worst))
    line = lines_of(area[worst], h[worst])[0]
    return [f"at {count} of {int(np.prod(result.shape))} points: {line}; largest at {at}"]


@contextlib.contextmanager
def _quiet_point_runs():
    """Each Monte Carlo point's :func:`~mcsim.studies.simulation.simulate` logs its inputs'
    notes (its law set's regime, the environment's) at INFO; the sweep records them per point
    (variable ``regime_warning``) and its caller says them once, so they are dropped here."""
    logger = logging.getLogger("mcsim.studies.simulation")
    level = logger.level
    logger.setLevel(logging.WARNING)
    try:
        yield
    finally:
        logger.setLevel(level)


def _empty_result(material: Material, law: str, names, dims, grid, config: Config,
                  with_env: bool, stick_varied: bool, slip_varied: bool) -> Sweep:  # fmt: skip
    """The sweep of every variable the grid's points give, all NaN (no point done)."""
    laws = list(grid[names.index("law")]) if "law" in names else [law]
    curve_names = _union(point_curves(x, material, with_env) for x in laws)
    if "tau" in names and material.tau is None:
        curve_names = _union([curve_names, point_curves(laws[0], dataclasses.replace(material, tau=1.0), with_env)])  # fmt: skip
    summary = any(has_summary(x) for x in laws)
    stick = config.restoring_force is not None or stick_varied
    slip = config.tangential_force is not None or slip_varied
    return empty_sweep(dims, grid, config.h, curve_names, summary, config.mc, with_env,
                       pads=bool(config.pads), stick=stick, friction=config.friction, slip=slip)  # fmt: skip


def _shown(values: np.ndarray) -> list:
    return [plain(v) for v in values]


def _union(groups) -> tuple[str, ...]:
    out: dict[str, None] = {}
    for g in groups:
        out |= dict.fromkeys(g)
    return tuple(out)


def _product(grid: list[np.ndarray]):
    """Every combination of the grid's values, C order (the last varies fastest)."""
    shape = tuple(len(v) for v in grid)
    for idx in np.ndindex(*shape):
        yield [v[i] for v, i in zip(grid, idx)]


def _attrs(surface, material, environment, law, dims, grid, config: Config, area, command,
           pair: dict) -> dict:  # fmt: skip
    bands = surface.radius_by_height
    surface_json = json.dumps({"sigma": surface.sigma, "R": surface.R, "eta": surface.eta,
                               "name": surface.name, "heights": inputgroup.heights_to_json(surface),
                               **({} if bands is None else
                                  {"radius_by_height": inputgroup.radius_to_dict(bands)}),
                               "units": {"sigma": "m", "R": "m", "eta": "m^-2"}})  # fmt: skip
    material_json = json.dumps({**{k: getattr(material, k) for k in ("E1", "E2", "nu1", "nu2", "gamma", "H", "z0", "tau", "name")},
                                "units": {"E1": "Pa", "E2": "Pa", "nu1": "1", "nu2": "1", "gamma": "J/m^2",
                                          "H": "Pa", "z0": "m", "tau": "Pa"}})  # fmt: skip
    attrs = {
        "sweep_schema_version": SCHEMA_VERSION,
        "mcsim_version": __version__,
        "command": command,
        "law": "varied" if "law" in dims else law,
        "varied": json.dumps(list(dims)),
        "surface": surface_json,
        "material": material_json,
        "turn": math.nan if config.turn is None else config.turn,
        "mc": config.mc,
    }
    if environment is not None:
        attrs["environment"] = json.dumps(dataclasses.asdict(environment) | {"units": {
            "hamaker": "J", "cutoff": "m", "rh": "1", "contact_angle": "rad", "temperature": "K",
            "surface_tension": "J/m^2", "molar_volume": "m^3/mol", "film_thickness": "m",
            "structured_film": "m", "asperity_roughness": "m",
            "retardation_wavelength": "m"}})  # fmt: skip
    if config.mc:
        attrs |= {"area": math.nan if area is None else area, "area_unit": "m^2",
                  "realizations": config.realizations, "seed_entropy": str(config.entropy),
                  "device": config.device}  # fmt: skip
    attrs |= _pads_attrs(config, area, dims) | pair
    # What must match for a resume: everything but the time and the command line.
    attrs["definition"] = json.dumps({k: (None if isinstance(v, float) and math.isnan(v) else v)
                                      for k, v in attrs.items() if k != "command"}
                                     | {"h": list(config.h), "values": [_shown(v) for v in grid]})  # fmt: skip
    attrs["created"] = _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
    return attrs


def _pads_index(index: int, names, shape) -> int:
    """Flat index of grid point ``index`` without its environment, force and preload
    dimensions (:class:`~mcsim.studies.sweeppoint.Point`)."""
    multi = np.unravel_index(index, shape)
    shared = {*ENVIRONMENT_INPUTS, *PAD_INPUTS, "preload"}
    kept = [(i, n) for i, n, name in zip(multi, shape, names) if name not in shared]
    if not kept:
        return 0
    return int(np.ravel_multi_index([i for i, _ in kept], [n for _, n in kept]))


def _pads_attrs(config: Config, area, names=()) -> dict:
    """Root attributes of the pads and the preload (empty without them)."""
    attrs = {}
    shared = "".join(f", {n}" for n in ("tangential_force", "preload") if n in names)
    if config.preload is not None:
        attrs |= {"preload": config.preload, "preload_unit": "Pa"}
    if config.pads:
        if config.restoring_force is not None:  # else varied (a coordinate) or none
            attrs |= {"restoring_force": config.restoring_force, "restoring_force_unit": "N"}
        if config.friction:
            attrs["friction"] = True
        if config.tangential_force is not None:  # else varied (a coordinate) or none
            attrs |= {"tangential_force": config.tangential_force, "tangential_force_unit": "N"}
        attrs |= {"pads": config.pads, "area": math.nan if area is None else area,
                  "area_unit": "m^2", "seed_entropy": str(config.entropy),
                  "pads_streams": "point i: SeedSequence(seed_entropy, spawn_key=(i, 1)), i the "
                                  "point's index without its environment and restoring-force "
                                  f"dimensions{shared} (the same pads there)",
                  "p_stick_tail": {None: "auto", True: "importance", False: "pads"}[config.tail]}  # fmt: skip
        if config.floor:  # importance sampling's floor (only where given: older files have none)
            attrs["p_stick_floor"] = config.floor
    return attrs


def _run(stack, points, config, result: Sweep, done, workers, scheduler, progress,
         checkpoint, checkpoint_every) -> None:  # fmt: skip
    """Evaluate the points on threads or Dask, storing each result as it arrives (in order)."""
    n_workers = default_workers() if workers is None else workers
    tasks = batches(points, config)
    if scheduler == PROCESSES:
        tasks = list(tasks)  # pads' points: already grouped in a list
        if len(tasks) <= 1:  # one task here, its pads on the worker processes
            scheduler = None
            config = dataclasses.replace(config, pad_workers=n_workers)
        elif not _pool_pays(len(tasks), config):  # a few pads: here, one after another
            scheduler, n_workers = None, 1
        n_workers = max(1, min(n_workers, len(tasks)))
    bar = None
    if progress:
        from tqdm import tqdm

        bar = stack.enter_context(tqdm(total=done.size, initial=int(done.sum()), unit=" points",
                                       file=sys.stderr, leave=False))  # fmt: skip
    if scheduler == PROCESSES:
        pool_submit = stack.enter_context(process_pool(n_workers))
        submit = functools.partial(pool_submit, evaluate_quietly, config=config)
        window = 2 * n_workers
    elif scheduler is None:
        pool = ThreadPoolExecutor(max_workers=n_workers)
        stack.callback(pool.shutdown, wait=True, cancel_futures=True)
        submit = functools.partial(pool.submit, evaluate_batch, config=config)
        window = 2 * n_workers
    else:
        client = scheduler
        if isinstance(scheduler, str):
            from mcsim.engine.cluster import dask_client

            client = stack.enter_context(dask_client(scheduler, workers))
        submit = functools.partial(client.submit, evaluate_quietly, config=config, pure=False)
        window = 2 * max(1, sum(client.nthreads().values()))
    next_checkpoint = time.monotonic() + min(FIRST_CHECKPOINT, checkpoint_every)
    unsaved = False
    results = stack.enter_context(
        contextlib.closing(in_order(submit, tasks, window, interrupt.check))
    )
    try:
        for batch, batch_values in results:
            for point, values in zip(batch, batch_values):
                _store(result, done, point.index, values)
            unsaved = True
            if bar is not None:
                bar.update(len(batch))
            if checkpoint is not None and time.monotonic() > next_checkpoint:
                checkpoint(done=done)
                unsaved = False
                next_checkpoint = time.monotonic() + checkpoint_every
    except BaseException:
        results.close()
        if checkpoint is not None and unsaved:
            checkpoint(done=done)
        raise


def _pool_pays(tasks: int, config: Config) -> bool:
    """Whether worker processes pay for their start (about 1 CPU s each: imports, compiled
    kernels) on ``tasks`` tasks of pads: importance sampling may run (its thousands of pads;
    ``tail`` True, or automatic from :data:`~mcsim.studies.rareevent.MIN_TAIL_PADS` pads a
    point), or the tasks hold :data:`POOL_PADS` pads in all. Fewer run in this process one
    after another: threads would contend for Python's lock (the guide's humid sweep of 320
    pads took 13 s and 17.5 CPU s on 2 threads, 5.5–6.9 s and 10–12.5 CPU s on 2 processes)."""
    from mcsim.studies.rareevent import MIN_TAIL_PADS

    if not config.pads:
        return True
    tail = config.tail is True or (config.tail is None and config.pads >= MIN_TAIL_PADS)
    return tail or tasks * config.pads >= POOL_PADS


def _store(result: Sweep, done: np.ndarray, index: int, values: dict) -> None:
    idx = np.unravel_index(index, done.shape)
    for k, v in values.items():
        result.data[k][idx] = v
    done[idx] = True
