"""``simulate()``: the Monte Carlo engine, its statistics and storage joined, and the result.

>>> from mcsim import simulate
>>> from mcsim.model.presets import SURFACES, MATERIALS
>>> run = simulate(SURFACES["smooth"], MATERIALS["silicon"], h=[2, 1, 0], area="1000 um^2",
...                realizations=4, seed=1)                                  # doctest: +SKIP
>>> run.compare()                                                           # doctest: +SKIP
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import logging
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mcsim._version import __version__
from mcsim.engine import interrupt
from mcsim.engine.montecarlo import DEFAULT_CHUNK, default_workers, run_sums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.counterface import as_counter, check_correlation, gap_surface
from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface, check_range, check_seed, check_separations
from mcsim.model.presets import as_material, as_surface
from mcsim.model.units import parse_quantity
from mcsim.physics.adhesion import regime_warnings
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.laws import LAW_SETS, get_law_set
from mcsim.physics.surfaceenvironment import (
    EQUILIBRIUM_NOTE,
    environment_warnings,
    interface_notes,
)
from mcsim.store import runfile
from mcsim.store.claim import Claim, claim_output
from mcsim.store.inputgroup import counterface_attrs
from mcsim.store.results import Run, assemble
from mcsim.studies.runoptions import check_checkpoint_every, check_workers

if TYPE_CHECKING:
    from mcsim.physics.loadcontrol import Preload

log = logging.getLogger(__name__)

#: Assumed speed of one worker, for the up-front estimate of a long run: contacting
#: (summit, separation) pairs per second, and summits above h_min sampled per second
#: (``validation/benchmark.py``, one worker, once: 1.7e8 pairs/s at h = 4 … −1; 2.3e5
#: summits sampled and summed in 0.021 s at h = 4 … 2, 1.1e7/s; README, Performance, has
#: today's figures).
PAIRS_PER_SECOND = 1.5e8
SAMPLES_PER_SECOND = 1e7

#: Runs expected to take longer (s) get an up-front estimate.
ESTIMATE_ABOVE = 60.0


def _duration(seconds: float) -> str:
    for unit, size in (("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


def estimate(spec: MonteCarloSpec, workers: int) -> tuple[float, float, float]:
    """Expected summits, evaluated (summit, row) pairs and seconds of a run.

    The time assumes :data:`PAIRS_PER_SECOND` and :data:`SAMPLES_PER_SECOND` per worker.
    """
    heights = spec.surface.heights
    summits = spec.realizations * spec.expected_summits
    above = summits * float(heights.sf(spec.s_min))
    pairs = summits * float(np.sum(heights.sf(spec.row_s)))
    return summits, pairs, (pairs / PAIRS_PER_SECOND + above / SAMPLES_PER_SECOND) / workers


def _preload_attrs(surface, material, h, law, cycle, environment, preload) -> dict:
    """Run attributes of force control: the preload (Pa) and its mean-field turn d/σ.

    Each pad's own turn (the largest h where its approach load reaches P·A) is found when the
    run is read (:meth:`mcsim.store.results.Run.pull_off`) from its summits drawn again; the
    grid must reach below the turns, since no summit below its lowest separation is drawn.
    """
    from mcsim.physics.loadcontrol import Preload, preload_turn  # SciPy: not at start-up

    if not cycle:
        raise ParameterError("preload: force control presses each pad before retraction; "
                             "it needs cycle=True (--cycle)")  # fmt: skip
    if "load" not in get_law_set(law).names:
        signed = [name for name in LAW_SETS if "load" in get_law_set(name).names]
        raise ParameterError(f"preload: law = {law!r} has no signed load to balance it "
                             f"(allowed: {', '.join(signed)})")  # fmt: skip
    given = preload.pressure if isinstance(preload, Preload) else preload
    pressure = check_range("preload", given, "Pa", low=0, low_open=False)
    if isinstance(preload, Preload) and preload.is_for(surface, material, law, environment):
        turn = preload.turn  # found once already (the command line's grid needed it)
    else:
        turn = preload_turn(surface, material, pressure, law, environment)
    if min(h) > turn:
        raise ParameterError(f"preload = {pressure:g} Pa: the mean approach curve balances it at "
                             f"h = {turn:.4g}, below the lowest h = {min(h):g}; extend h (--h) down "
                             "(pads under force control turn around there, some lower)")  # fmt: skip
    return {"preload": pressure, "preload_unit": "Pa", "preload_turn_mean_field": turn}


def simulate(
    surface: Surface | str,
    material: Material | str,
    h,
    area: float | str,
    *,
    realizations: int = 1,
    seed: int | None = None,
    law: str = "seed",
    count: str = "poisson",
    cycle: bool = False,
    preload: float | str | Preload | None = None,
    device: str = "cpu",
    workers: int | None = None,
    scheduler=None,
    chunk_size: int = DEFAULT_CHUNK,
    keep_heights: bool = False,
    out: str | Path | None = None,
    overwrite: bool = False,
    resume: bool = False,
    checkpoint_every: float = 60.0,
    progress: bool = False,
    command: str | None = None,
    extra_attrs: dict | None = None,
    environment: Environment | None = None,
    counter_surface: Surface | str | None = None,
    correlation: float = 0.0,
) -> Run:
    """Simulate ``realizations`` patches of area ``area`` and compare with the GW curves.

    Parameters
    ----------
    surface, material : Surface, Material or str
        Inputs, or the names of presets (``"smooth"``, ``"silicon"``; see
        :mod:`mcsim.model.presets` and :mod:`mcsim.store.config`).
    h : array_like
        Dimensionless separations d/σ.
    area : float or str
        Nominal patch area, m² or with a unit (``"100 um^2"``).
    realizations : int
        Independent patches.
    seed : int or None
        Root seed; None draws fresh entropy (recorded in the result), or, with
        ``resume``, takes the one recorded in the file.
    law : str
        Law set (``"seed"``: the paper as written; see :data:`mcsim.physics.laws.LAW_SETS`).
    count : {"poisson", "fixed"}
        N ~ Poisson(ηA) or N = round(ηA).
    cycle : bool
        Approach over ``h`` (descending), then retraction back over the same ``h``
        after the closest approach min(h); both branches are stored.
    preload : float or str or Preload, optional
        Nominal pressure, Pa or with a unit (``"1 MPa"``), with ``cycle``: force control,
        as an actuator presses a device. Each pad is pressed until its own approach load
        reaches preload × area and retracts from there (:meth:`Run.pull_off`, which draws
        its summits again); the run records the preload and the turn that balances it on
        the mean curve (:func:`mcsim.physics.loadcontrol.preload_turn`), which must lie
        within ``h``. Law sets with a signed load only; with an environment its net load.
        A :class:`~mcsim.physics.loadcontrol.Preload` found for these very inputs (the
        command line's, which needed the turn for its grid) passes its turn on.
    device : {"cpu", "cuda"}
        Sample and sum on the CPU or on the GPU (``mcsim[gpu]``; other random streams,
        so other numbers than the CPU's, equal in distribution); recorded in the run.
    workers : int, optional
        Local worker threads (1 to 1024), all cores by default; or worker processes of a
        local Dask cluster. The numbers do not depend on it.
    scheduler : str or dask.distributed.Client, optional
        Run on Dask: ``"local"`` (a local cluster of ``workers`` processes), the
        address of an existing scheduler (``"tcp://host:8786"``) or a client.
    chunk_size : int
        Summits per task; the numbers do not depend on it.
    keep_heights : bool
        Keep the sampled heights (above h_min) in the result and file (no checkpoints).
    out : str or path-like, optional
        Write the complete run to this HDF5 file, atomically, when it ends. While it
        runs, its checkpoint (an incomplete, resumable run) is
        :func:`mcsim.store.files.checkpoint_path` (``<stem>.partial<suffix>`` beside
        ``out``), written atomically after about 10 s of work, then every
        ``checkpoint_every`` seconds, and on interruption; it is removed once the
        complete run is in place. So ``out`` always holds nothing, the earlier file
        or the new complete run. An existing file, or another run's checkpoint, is
        refused unless ``overwrite``.
    resume : bool
        Continue from the checkpoint beside ``out``; the result is bit-identical to
        an uninterrupted run. Without a checkpoint, the run starts from the
        beginning (and logs a warning saying so). If ``out`` already holds this
        finished run (same inputs, mcsim version and ``keep_heights``; without
        ``seed``, any seed), it is returned untouched with a notice; a finished run
        of other inputs is refused, naming the first that differs.
    checkpoint_every : float
        Seconds between checkpoints (a number, s, >= 0).
    progress : bool
        Show a progress bar on stderr.
    command : str, optional
        Provenance string stored in the file (the CLI passes its command line).
    extra_attrs : dict, optional
        Further root attributes of the file and its checkpoints (numbers or strings),
        e.g. ``{"load_control": '{"pressure": [...], "unit": "Pa"}'}`` (JSON) for the
        nominal pressures that the separations balance (``mcsim simulate --pressure``).
    environment : Environment or mapping, optional
        An Environment, or its fields as a mapping (:func:`~mcsim.physics.environment.as_environment`).
        Van der Waals and capillary condensation: each summit's cap adds the outputs
        ``vdw`` and ``capillary`` to the law set (summed like the contact loads, and
        drawn down to the caps' band edge, so the sums differ from a dry run's), and the
        open gaps between the caps add a deterministic pressure
        (:func:`mcsim.physics.surfaceenvironment.open_gap_pressures`, heights about the mean
        plane from ``surface.rq``/``map_heights`` or the Nayak estimate). A preload is
        then balanced by the net load, and ``preload=0`` is a device resting under its
        own attraction. None: the contact alone, and the file is as before.
    counter_surface : Surface or str, optional
        A rough counter-surface facing ``surface`` (or a preset's name); the run is of the
        gap's surface, :func:`mcsim.model.counterface.combine` of the two with
        ``correlation`` (stored as ``/input/surface``), and the file records the parts as
        root attributes ``surface_as_given``, ``counter_surface`` and ``correlation``
        (:func:`mcsim.store.inputgroup.counterface_attrs`). None or ``"flat"`` (default):
        a flat counter-surface, and the file is as before.
    correlation : float
        ρ, the correlation of the two surfaces' heights, in [-1, 1]; 0 without a
        counter-surface.

    Returns
    -------
    Run

    Raises
    ------
    mcsim.engine.interrupt.Interrupted
        On SIGINT (Ctrl-C) or SIGTERM, once the progress is saved (a ``KeyboardInterrupt``).
    """
    given, material = as_surface(surface), as_material(material)  # resolved here, once
    correlation = check_correlation(correlation)
    counter = as_counter(counter_surface)
    surface, pair = gap_surface(given, counter, correlation), None
    if counter is not None:  # a rough counter-surface: its parts recorded
        pair = (given, counter, correlation)
        extra_attrs = {**(extra_attrs or {}), **counterface_attrs(*pair)}
    environment = as_environment(environment)
    area_m2 = parse_quantity(area, "area", "area")
    seed = check_seed(seed)
    workers = check_workers(workers)
    checkpoint_every = check_checkpoint_every(checkpoint_every)
    if preload is not None:
        extra_attrs = {**(extra_attrs or {}), **_preload_attrs(
            surface, material, check_separations(h), law, cycle, environment, preload)}  # fmt: skip
    extra_attrs = extra_attrs or {}
    if resume and out is None:
        raise ParameterError("resume needs the run file to continue (out=...)")
    with interrupt.interruptible(), contextlib.ExitStack() as stack:
        claim = None
        if out is not None:
            claim = claim_output(stack, out, overwrite=overwrite, resume=resume, what="run",
                                 read_finished=runfile.read_run, read_checkpoint=runfile.read_state)  # fmt: skip
        seed_given = seed is not None
        if seed is None and claim is not None:
            seed = _recorded_seed(claim)
        entropy = np.random.SeedSequence(seed).entropy
        spec = MonteCarloSpec(surface, material, h, area_m2, realizations, entropy, law, count,
                              cycle, device, environment)  # fmt: skip
        if claim is not None and claim.finished is not None:
            return _already_finished(claim, spec, keep_heights, extra_attrs, seed_given)
        if claim is not None and claim.checkpoint is not None:
            recorded = {k: claim.checkpoint_attrs.get(k) for k in extra_attrs}
            claim.check_checkpoint(
                _inputs(claim.checkpoint.spec, recorded), _inputs(spec, extra_attrs)
            )
        if command is None:
            command = _api_command(
                spec, seed=seed, preload=preload, environment=environment, pair=pair
            )
        checkpoint = None
        if claim is not None and not keep_heights:
            checkpoint = functools.partial(
                runfile.write_checkpoint, claim.partial, command=command, extra=extra_attrs
            )
        run = _run(stack, spec, workers=workers, scheduler=scheduler,
                   chunk_size=chunk_size, keep_heights=keep_heights, progress=progress,
                   resume=None if claim is None else claim.checkpoint, checkpoint=checkpoint,
                   checkpoint_every=checkpoint_every)  # fmt: skip
        if claim is None:  # the attributes a file would hold that the analysis reads (preload)
            return dataclasses.replace(run, attrs=dict(extra_attrs))
        return claim.finish(
            lambda path: runfile.write_run(path, run, command=command, extra=extra_attrs)
        )


def _recorded_seed(claim: Claim) -> int | None:
    """The seed of the finished run or checkpoint a resume found (None: neither)."""
    found = claim.finished if claim.finished is not None else claim.checkpoint
    return None if found is None else found.spec.entropy


def _api_command(spec: MonteCarloSpec, *, seed, preload, environment, pair=None) -> str:
    """The call that makes ``spec``, for the provenance of a run the Python API started
    (``pair``: the surface as given, its counter-surface and their correlation, or None)."""
    s = spec
    parts = {"surface": s.surface.name or s.surface}
    if pair is not None:
        given, counter, correlation = pair
        parts = {"surface": given.name or given, "counter_surface": counter.name or counter,
                 "correlation": correlation}  # fmt: skip
    kwargs = {**parts, "material": s.material.name or s.material,
              "h": [float(x) for x in s.h], "area": s.area, "realizations": s.realizations,
              "seed": seed, "law": s.law, "count": s.count,
              **({"cycle": True} if s.cycle else {}),
              **({"preload": getattr(preload, "pressure", preload)} if preload is not None else {}),
              **({"device": s.device} if s.device != "cpu" else {}),
              **({"environment": environment} if environment is not None else {})}  # fmt: skip
    return f"mcsim.simulate({', '.join(f'{k}={v!r}' for k, v in kwargs.items())})"


def _run(stack, spec: MonteCarloSpec, *, workers, scheduler, chunk_size,
         keep_heights, progress, resume, checkpoint, checkpoint_every) -> Run:  # fmt: skip
    """The sums of ``spec`` (continuing ``resume``): contacts, and the environment's caps."""
    notes = regime_warnings(spec.surface, spec.material, spec.law)
    for warning in notes:
        log.info("warning: %s", warning)  # once the inputs are accepted: no error follows
    if spec.environment is not None:  # a dry run has no interface notes or warnings
        for note in interface_notes(spec.surface, spec.material, spec.environment):
            log.info("note: %s", note)
        for warning in environment_warnings(spec.surface, spec.environment):
            log.info("warning: %s", warning)
        if spec.environment.has_capillary:
            log.info("note: %s", EQUILIBRIUM_NOTE)
    n_workers = default_workers() if workers is None else workers
    summits, pairs, seconds = estimate(spec, n_workers)
    if seconds > ESTIMATE_ABOVE:
        log.info("long run: %.3g summits, %.3g contacting (summit, h) pairs: about %s on %d "
                 "worker(s) at an assumed %.2g pairs/s each; Ctrl-C stops it%s", summits, pairs,
                 _duration(seconds), n_workers, PAIRS_PER_SECOND,
                 " (progress is saved)" if checkpoint is not None else "")  # fmt: skip
    bar = None
    if progress:
        from tqdm import tqdm

        total = (
            spec.realizations * spec.expected_summits * float(spec.surface.heights.sf(spec.s_min))
        )
        bar = stack.enter_context(tqdm(total=round(total), unit=" summits", unit_scale=True,
                                       file=sys.stderr, leave=False))  # fmt: skip
    client = scheduler
    if isinstance(scheduler, str):
        from mcsim.engine.cluster import dask_client

        client = stack.enter_context(dask_client(scheduler, workers))
    ens = run_sums(spec, workers=workers, chunk_size=chunk_size, keep_heights=keep_heights,
                   progress=None if bar is None else bar.update, client=client, resume=resume,
                   checkpoint=checkpoint, checkpoint_every=checkpoint_every,
                   interrupt=interrupt.check)  # fmt: skip
    return assemble(ens)


def _inputs(spec: MonteCarloSpec, extra: dict) -> dict:
    """What defines a run, as a resume compares it: the inputs of ``spec`` (its entropy
    named ``seed``) and the ``extra`` root attributes."""
    named = {("seed" if k == "entropy" else k): v for k, v in spec.fields().items()}
    return named | extra


def _already_finished(claim: Claim, spec: MonteCarloSpec, keep_heights: bool, extra: dict,
                      seed_given: bool) -> Run:  # fmt: skip
    """The complete run at the claimed output, if it is the run asked for (see
    :meth:`mcsim.store.claim.Claim.already_finished`). The mcsim version and whether
    heights are kept count as inputs."""
    finished = claim.finished
    recorded = _inputs(finished.spec, {k: finished.attrs.get(k) for k in extra}) | {
        "keep_heights": finished.heights is not None,
        "mcsim version": finished.attrs.get("mcsim_version"),
    }
    asked = _inputs(spec, extra) | {"keep_heights": keep_heights, "mcsim version": __version__}
    return claim.already_finished(
        recorded, asked,
        own_checkpoint=lambda partial: runfile.read_state(partial)[0].spec == finished.spec,
        seed_note="" if seed_given else f" (no seed given: taken as the file's, {spec.entropy})",
    )  # fmt: skip
