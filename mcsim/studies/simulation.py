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
import shlex
import sys
from pathlib import Path

import numpy as np

from mcsim._version import __version__
from mcsim.engine import interrupt
from mcsim.engine.cells import run_cell_sums
from mcsim.engine.montecarlo import DEFAULT_CHUNK, MonteCarloSpec, default_workers, run_sums
from mcsim.model.errors import ParameterError, RunFileError
from mcsim.model.params import Material, Surface, check_range, check_seed, check_separations
from mcsim.model.units import parse_quantity
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.gapheights import gap_heights
from mcsim.physics.laws import LAW_SETS, get_law_set
from mcsim.store import files, runfile
from mcsim.store.results import Run, assemble

log = logging.getLogger(__name__)

#: Assumed speed of one worker, for the up-front estimate of a long run: contacting
#: (summit, separation) pairs per second, and summits above h_min sampled per second
#: (README, Performance, one worker: 1.7e8 pairs/s at h = 4 … −1; 2.3e5 summits
#: sampled and summed in 0.021 s at h = 4 … 2, 1.1e7/s).
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
    from mcsim.physics.loadcontrol import preload_turn  # SciPy's optimizers: not at start-up

    if not cycle:
        raise ParameterError("preload: force control presses each pad before retraction; "
                             "it needs cycle=True (--cycle)")  # fmt: skip
    if environment is not None:
        raise ParameterError("preload with an environment: each pad's force control counts "
                             "its contact loads only (not yet the environment's attraction)")  # fmt: skip
    if "load" not in get_law_set(law).names:
        signed = [name for name in LAW_SETS if "load" in get_law_set(name).names]
        raise ParameterError(f"preload: law = {law!r} has no signed load to balance it "
                             f"(allowed: {', '.join(signed)})")  # fmt: skip
    pressure = check_range("preload", preload, "Pa", low=0)
    turn = preload_turn(surface, material, pressure, law)
    if min(h) > turn:
        raise ParameterError(f"preload = {pressure:g} Pa: the mean approach curve balances it at "
                             f"h = {turn:.4g}, below the lowest h = {min(h):g}; extend h (--h) down "
                             "(pads under force control turn around there, some lower)")  # fmt: skip
    return {"preload": pressure, "preload_unit": "Pa", "preload_turn_mean_field": turn}


def _api_command(**kwargs) -> str:
    shown = ", ".join(f"{k}={v!r}" for k, v in kwargs.items())
    return f"mcsim.simulate({shown})"


def simulate(
    surface: Surface,
    material: Material,
    h,
    area: float | str,
    *,
    realizations: int = 1,
    seed: int | None = None,
    law: str = "seed",
    count: str = "poisson",
    cycle: bool = False,
    preload: float | str | None = None,
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
) -> Run:
    """Simulate ``realizations`` patches of area ``area`` and compare with the GW curves.

    Parameters
    ----------
    surface, material : Surface, Material
        Inputs (see :mod:`mcsim.model.presets` and :mod:`mcsim.store.config`).
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
    preload : float or str, optional
        Nominal pressure, Pa or with a unit (``"1 MPa"``), with ``cycle``: force control,
        as an actuator presses a device. Each pad is pressed until its own approach load
        reaches preload × area and retracts from there (:meth:`Run.pull_off`, which draws
        its summits again); the run records the preload and the turn that balances it on
        the mean curve (:func:`mcsim.physics.loadcontrol.preload_turn`), which must lie
        within ``h``. Law sets with a signed load only, no environment.
    device : {"cpu", "cuda"}
        Sample and sum on the CPU or on the GPU (``mcsim[gpu]``; other random streams,
        so other numbers than the CPU's, equal in distribution); recorded in the run.
    workers : int, optional
        Local worker threads, all cores by default; or worker processes of a local
        Dask cluster. The numbers do not depend on it.
    scheduler : str or dask.distributed.Client, optional
        Run on Dask: ``"local"`` (a local cluster of ``workers`` processes), the
        address of an existing scheduler (``"tcp://host:8786"``) or a client.
    chunk_size : int
        Summits per task; the numbers do not depend on it.
    keep_heights : bool
        Keep the sampled heights (above h_min) in the result and file (no checkpoints).
    out : path, optional
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
        Seconds between checkpoints.
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
        Van der Waals and capillary condensation across the gaps: each patch's pressures
        are sampled over its cells (:mod:`mcsim.engine.cells`: one cell per summit, heights
        from ``surface.rq``/``map_heights`` or the Nayak estimate,
        :func:`mcsim.physics.gapheights.gap_heights`) in a pass after the contact sums
        (local threads, not checkpointed: a resumed run redoes it). The contact sums are
        the same as without it. None: no such pass, and the file is as before.

    Returns
    -------
    Run

    Raises
    ------
    mcsim.engine.interrupt.Interrupted
        On SIGINT (Ctrl-C) or SIGTERM, once the progress is saved (a ``KeyboardInterrupt``).
    """
    environment = as_environment(environment)
    area_m2 = parse_quantity(area, "area", "area")
    seed = check_seed(seed)
    if preload is not None:
        extra_attrs = {**(extra_attrs or {}), **_preload_attrs(
            surface, material, check_separations(h), law, cycle, environment, preload)}  # fmt: skip
    check_range("checkpoint_every", checkpoint_every, "s", low=0.0, low_open=False)
    if resume and out is None:
        raise ParameterError("resume needs the run file to continue (out=...)")
    with interrupt.interruptible(), contextlib.ExitStack() as stack:
        previous = partial = finished = None
        seed_given = seed is not None
        if out is not None:
            out, partial = files.claim(stack, out, overwrite=overwrite, resume=resume)
            if resume and not overwrite and out.exists():
                finished = runfile.read_run(out)  # checksum verified: damage is refused
                seed = finished.spec.entropy if seed is None else seed
            elif resume and partial.exists():
                previous, attrs = runfile.read_state(partial)
                if attrs.get("complete"):
                    raise RunFileError(f"{partial}: damaged checkpoint: it holds a complete run")
                if attrs.get("mcsim_version") != __version__:
                    raise RunFileError(
                        f"{partial}: written by mcsim {attrs.get('mcsim_version')}; resume it with that version"
                    )
                seed = previous.spec.entropy if seed is None else seed
            elif resume:
                log.warning("%s: nothing to resume (no checkpoint %s): starting the run from "
                            "the beginning", out, partial.name)  # fmt: skip
            else:
                partial.unlink(missing_ok=True)  # --overwrite: start again
        entropy = np.random.SeedSequence(seed).entropy
        spec = MonteCarloSpec(
            surface, material, h, area_m2, realizations, entropy, law, count, cycle, device
        )
        if finished is not None:
            return _already_finished(out, finished, spec, keep_heights, extra_attrs, seed_given)
        if previous is not None:
            recorded = {k: attrs.get(k) for k in extra_attrs or {}}
            differs = files.first_difference(
                _inputs(previous.spec, recorded), _inputs(spec, extra_attrs or {})
            )
            if differs:
                raise ParameterError(
                    f"cannot resume {out}: its checkpoint {partial.name} holds a run with a different {differs}"
                )
        if command is None:
            command = _api_command(surface=surface.name or surface, material=material.name or material,
                                   h=[float(x) for x in spec.h], area=area_m2, realizations=realizations,
                                   seed=seed, law=law, count=count,
                                   **({"cycle": True} if cycle else {}),
                                   **({"preload": preload} if preload is not None else {}),
                                   **({"device": device} if device != "cpu" else {}),
                                   **({"environment": environment} if environment is not None else {}))  # fmt: skip
        n_workers = workers if isinstance(workers, int) and workers > 0 else default_workers()
        summits, pairs, seconds = estimate(spec, n_workers)
        if seconds > ESTIMATE_ABOVE:
            log.info("long run: %.3g summits, %.3g contacting (summit, h) pairs: about %s on %d "
                     "worker(s) at an assumed %.2g pairs/s each; Ctrl-C stops it%s", summits, pairs,
                     _duration(seconds), n_workers, PAIRS_PER_SECOND,
                     " (progress is saved)" if out is not None and not keep_heights else "")  # fmt: skip
        checkpoint = None
        if out is not None and not keep_heights:
            checkpoint = functools.partial(
                runfile.write_checkpoint, partial, command=command, extra=extra_attrs
            )
        if progress:
            from tqdm import tqdm

            total = (
                spec.realizations * spec.expected_summits * float(surface.heights.sf(spec.s_min))
            )
            bar = stack.enter_context(
                tqdm(
                    total=round(total),
                    unit=" summits",
                    unit_scale=True,
                    file=sys.stderr,
                    leave=False,
                )
            )
        client = scheduler
        if isinstance(scheduler, str):
            from mcsim.engine.cluster import dask_client

            client = stack.enter_context(dask_client(scheduler, workers))
        ens = run_sums(spec, workers=workers, chunk_size=chunk_size, keep_heights=keep_heights,
                       progress=bar.update if progress else None, client=client, resume=previous,
                       checkpoint=checkpoint, checkpoint_every=checkpoint_every,
                       interrupt=interrupt.check)  # fmt: skip
        cells = None
        if environment is not None:
            cells = run_cell_sums(spec, ens.n_summits, environment, gap_heights(surface),
                                  workers=n_workers, interrupt=interrupt.check)  # fmt: skip
        run = assemble(ens, cells)
        if out is None:  # the attributes a file would hold that the analysis reads (preload)
            return dataclasses.replace(run, attrs=dict(extra_attrs or {}))
        run = runfile.write_run(out, run, command=command, extra=extra_attrs)
        partial.unlink(missing_ok=True)  # after the complete run is in place
        return run


def _inputs(spec: MonteCarloSpec, extra: dict) -> dict:
    """What defines a run, as a resume compares it: the inputs of ``spec`` (its entropy
    named ``seed``) and the ``extra`` root attributes."""
    named = {("seed" if k == "entropy" else k): v for k, v in spec.fields().items()}
    return named | extra


def _already_finished(out: Path, finished: Run, spec: MonteCarloSpec, keep_heights: bool,
                      extra: dict | None, seed_given: bool) -> Run:  # fmt: skip
    """``finished``, the complete run at ``out``, if it is the run asked for: resuming it
    is then a no-op (the file is not touched; a checkpoint left beside it by a kill
    after the final write is removed). Otherwise refuse, naming the first input that
    differs. The mcsim version and whether heights are kept count as inputs."""
    recorded = _inputs(finished.spec, {k: finished.attrs.get(k) for k in extra or {}}) | {
        "keep_heights": finished.heights is not None,
        "mcsim version": finished.attrs.get("mcsim_version"),
    }
    asked = _inputs(spec, extra or {}) | {
        "keep_heights": keep_heights,
        "mcsim version": __version__,
    }
    differs = files.first_difference(recorded, asked)
    if differs:
        raise RunFileError(f"{out}: already holds a finished run with a different {differs}; "
                           "use --overwrite to replace it or another --out")  # fmt: skip
    partial = files.checkpoint_path(out)
    if partial.exists() and runfile.read_state(partial)[0].spec == finished.spec:
        partial.unlink()  # the finished run's own checkpoint: killed before removing it
    seed = "" if seed_given else f" (no seed given: taken as the file's, {spec.entropy})"
    log.warning("%s: already holds this finished run%s: nothing to do", out, seed)
    return finished


def cli_command() -> str:
    """The current command line, quoted, for provenance."""
    return " ".join(shlex.quote(a) for a in ["mcsim", *sys.argv[1:]])
