"""One point of a sweep: its inputs, and their evaluation (curves, regime numbers, adhesion
summary, and optionally Monte Carlo or finite pads), alone or in compiled batches.

:func:`mcsim.studies.sweeps.sweep` builds the points and runs them; every point is an
independent task whose numbers depend on nothing but its inputs and the seed.
"""

from __future__ import annotations

import dataclasses
import difflib
import logging
import math
import threading
import warnings
from collections import OrderedDict
from concurrent.futures import Future
from dataclasses import dataclass, field

import numpy as np

from mcsim.engine.maps.designmap import REFERENCE, jkr_summaries
from mcsim.model import units
from mcsim.model.distributions import GAUSSIAN, Gaussian
from mcsim.model.errors import MCSimError, ParameterError, WorkerError
from mcsim.model.params import Material, Surface, plasticity_index
from mcsim.model.units import parse_quantity
from mcsim.physics.adhesion import (
    RegimeWarning,
    adhesion_parameter,
    adhesion_summary,
    choose_law,
    maugis_parameter,
    regime_warnings,
    tabor_parameter,
)
from mcsim.physics.analytic import analytic_curves, quantities
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import gap_heights
from mcsim.physics.laws import get_law_set
from mcsim.physics.loadcontrol import preload_turn
from mcsim.store.sweepvariables import (
    ENVIRONMENT_INPUTS,
    ENVIRONMENT_SUMMARY,
    INPUTS,
    SUMMARY,
    plain,
)
from mcsim.studies.pads import finite_pads

log = logging.getLogger(__name__)


# --- the values of the inputs ---------------------------------------------------------


#: Most points of one sweep.
MAX_POINTS = 1_000_000


_SURFACE_FIELDS = {"sigma", "R", "eta"}


def unknown_input(name: str) -> ParameterError:
    close = difflib.get_close_matches(name, INPUTS, n=1)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    return ParameterError(f"vary: unknown input {name!r} (allowed: {', '.join(INPUTS)}){hint}")


def parse_values(name: str, spec) -> np.ndarray:
    """The values of one varied input: SI floats (strings for ``law``).

    ``spec`` is a range ``"start:stop:num[:log]"`` (inclusive, start <= stop), a comma
    list ``"0.3nm,1nm"``, or a sequence of numbers (SI) or quantity strings. A bare
    number is SI, as in every other option (``gamma=0.05:1:5`` is in J/m²), except in a
    string for ``contact_angle``, where it is in degrees, as ``--contact-angle``
    (``contact_angle=0:80:9``; ``"0.5 rad"`` with its unit).
    """
    if name not in INPUTS:
        raise unknown_input(name)
    dimension = INPUTS[name][0]
    where = f"vary {name}"
    if name == "contact_angle" and isinstance(spec, str):
        spec = _in_degrees(spec)
    if isinstance(spec, str):
        text = spec.strip()
        if not text:
            raise ParameterError(f"{where}: empty list of values")
        if ":" in text and name != "law":
            values = units.parse_values(text, dimension, where, limit=MAX_POINTS, ascending=True)
        else:
            values = [x.strip() for x in text.split(",")]
    else:
        values = list(np.atleast_1d(spec)) if not isinstance(spec, list | tuple) else list(spec)
        if not values:
            raise ParameterError(f"{where}: empty list of values")
    if name == "law":
        laws = []
        for v in values:
            if v != "auto":
                get_law_set(v)  # unknown: names the allowed ones
            laws.append(str(v))
        values = np.array(laws, dtype=str)
    else:
        values = np.array([parse_quantity(plain(v), dimension, where) for v in values])
    if values.size > MAX_POINTS:
        raise ParameterError(f"{where}: {values.size} values, more than a sweep's "
                             f"{MAX_POINTS} points")  # fmt: skip
    unique, counts = np.unique(values, return_counts=True)
    if np.any(counts > 1):
        raise ParameterError(f"{where}: value {unique[counts > 1][0]!r} appears more than once")
    return values


def _in_degrees(spec: str) -> str:
    """A contact-angle spec with ``deg`` after each bare number (its values, or a range's
    start and stop): a bare angle is in degrees, as on the command line."""

    def unit(x: str) -> str:
        return x if units.has_unit(x) else f"{x.strip()} deg"

    if ":" in spec:
        parts = spec.split(":")
        return ":".join([unit(parts[0]), unit(parts[1]), *parts[2:]])
    return ",".join(unit(x) for x in spec.split(","))


@dataclass(frozen=True)
class Point:
    """One grid point: its flat index (C order), its inputs, and the index its pads draw from.

    ``pads_index`` is the flat index of the point in the grid without its environment inputs
    (rh, hamaker, ...), the restoring and tangential forces and the preload: points that
    differ in these alone draw the same pads (common random numbers, so that a curve against
    RH or the preload is the physics, not the draw); without such inputs it is ``index``.
    """

    index: int
    surface: Surface
    material: Material
    law: str
    area: float | None
    environment: Environment | None = None
    pads_index: int | None = None
    restoring_force: float | None = None  # N, where varied; else the Config's
    tangential_force: float | None = None  # N, where varied; else the Config's
    preload: float | None = None  # Pa, where varied; else the Config's


class SharedPads:
    """The pads of a sweep's points whose pads act alike, evaluated once.

    Points that differ only by a humidity below the liquid bridges' onset (where it acts on
    nothing: :meth:`mcsim.physics.environment.Environment.acting`) have the same pads, drawn
    from the same stream (the environment's dimensions share it), under the same physics: the
    first point to ask evaluates them and the others, concurrent or later, take its result.
    ``mcsim report`` at RH 0 and 0.3 evaluated the same pads twice, importance sampling
    included. A copy sent to another process (a Dask worker, a process pool's) starts empty:
    the sweep sends such points there as one task (:func:`batches`).
    """

    #: Most pads results kept (a few floats each).
    SIZE = 64

    def __init__(self):
        self._lock = threading.Lock()
        self._results: OrderedDict = OrderedDict()

    def __reduce__(self):
        return SharedPads, ()

    def get(self, key, compute) -> dict:
        """``compute()`` for the first caller with ``key``; the same result (a copy) for the
        others, who wait for it. A failure is not kept: each later caller computes again."""
        with self._lock:
            future = self._results.get(key)
            owner = future is None
            if owner:
                future = self._results[key] = Future()
                while len(self._results) > self.SIZE:
                    self._results.popitem(last=False)
        if owner:
            try:
                future.set_result(compute())
            except BaseException as err:
                with self._lock:
                    self._results.pop(key, None)
                future.set_exception(err)
                raise
        return dict(future.result())


@dataclass(frozen=True)
class Config:
    """What every point shares."""

    h: tuple[float, ...]
    turn: float | None
    mc: bool
    realizations: int
    entropy: int | None
    device: str = "cpu"
    pads: int | None = None
    restoring_force: float | None = None
    preload: float | None = None
    tail: bool | None = None
    friction: bool = False
    tangential_force: float | None = None
    floor: float = 0.0
    #: Worker processes of a point's pads (:func:`mcsim.studies.pads.finite_pads`): more than
    #: 1 only where the sweep's pads run as one task in its own process, never inside a pool.
    pad_workers: int = 1
    shared: SharedPads = field(default_factory=SharedPads, compare=False, repr=False)


def make_point(base_surface, base_material, base_environment, law, area, names, values,
               index, pads_index=None) -> Point:  # fmt: skip
    """The inputs at one point; a bad combination raises ParameterError (a failed point)."""
    surface_changes, material_changes, environment_changes = {}, {}, {}
    forces = {}
    for name, value in zip(names, values):
        if name == "law":
            law = str(value)
        elif name in ("restoring_force", "tangential_force", "preload"):
            forces[name] = float(value)
        elif name == "area":
            area = float(value)
        elif name in ENVIRONMENT_INPUTS:
            environment_changes[name] = float(value)
        else:
            for f in INPUTS[name][1]:
                (surface_changes if f in _SURFACE_FIELDS else material_changes)[f] = float(value)
    environment = base_environment
    if environment_changes:
        environment = dataclasses.replace(environment, **environment_changes)
    return Point(index, dataclasses.replace(base_surface, **surface_changes),
                  dataclasses.replace(base_material, **material_changes), law, area,
                  environment, index if pads_index is None else pads_index, **forces)  # fmt: skip


def has_summary(law: str) -> bool:
    """Whether ``law`` (or ``auto``) has a net load and a retraction branch."""
    if law == "auto":
        return True
    laws = get_law_set(law)
    return "load" in laws.names and laws.retract


def point_curves(law: str, material: Material, environment: bool = False) -> tuple[str, ...]:
    return quantities("jkr" if law == "auto" else law, material, environment)


def evaluate(point: Point, config: Config) -> dict:
    """Every output at one point (a dict of floats, arrays over h and strings).

    Where a step fails, the outputs of the steps before it (curves, regime numbers,
    adhesion summary, Monte Carlo, in that order) are kept and ``error`` says why.
    """
    out: dict = {}
    try:
        _evaluate(point, config, out)
    except WorkerError:  # the pads' worker processes failed, not this point: every one would
        raise
    except (MCSimError, ArithmeticError, ValueError, RuntimeError) as err:
        out["error"] = f"{type(err).__name__}: {' '.join(str(err).split())}"
    return out


def evaluate_quietly(points: list[Point], config: Config) -> list[dict]:
    """:func:`evaluate_batch` on a Dask worker, without printing the regime warnings it records."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        return evaluate_batch(points, config)


def _evaluate(point: Point, config: Config, out: dict) -> None:
    surface, material = point.surface, point.material
    law = choose_law(surface, material)[0] if point.law == "auto" else point.law
    out["law_used"] = law
    environment = point.environment
    # The environment only where there is one: without, every call is as before it existed.
    with_environment = {} if environment is None else {"environment": environment}
    curves = analytic_curves(surface, material, np.asarray(config.h), law, **with_environment)
    out |= curves.values
    out |= _regime(surface, material, law)
    preload = config.preload if point.preload is None else point.preload
    known = None  # (its inputs, the summary): the pads' analytic pull-off, where the same
    if has_summary(law):
        turn = config.turn
        if preload is not None:
            turn = preload_turn(surface, material, preload, law, environment)
        summary = adhesion_summary(surface, material, law, turn=turn, **with_environment)
        known = (surface, material, law, turn, environment), summary
        out |= {k: getattr(summary, k) for k in SUMMARY}
        if environment is not None:
            out |= {k: getattr(summary, k) for k in ENVIRONMENT_SUMMARY}
    if config.mc:
        from mcsim.studies.simulation import simulate

        run = simulate(surface, material, np.asarray(config.h), point.area,
                       realizations=config.realizations, seed=point_seed(config.entropy, point.index),
                       law=law, device=config.device, workers=1, command="mcsim.sweep",
                       **with_environment)  # fmt: skip
        for q in run.quantities:
            out[f"mc_{q}"] = run.summary.mean[q]
            out[f"mc_{q}_se"] = run.summary.se[q]
    if config.pads:
        out |= _pads(point, config, law, out.get("turn", math.nan), out.get("h_pull_off", math.nan),
                     preload, known)  # fmt: skip


def _pads(point: Point, config: Config, law: str, turn: float, h_pull_off: float,
          preload: float | None, known=None) -> dict:  # fmt: skip
    """The pads of one point: ``config.pads`` pads of the point's area from its own stream.
    ``known``: ((surface, material, law, turn, environment), adhesion summary) of the point,
    passed on to the pads where they are the pads' own inputs (the same objects, the same turn):
    their analytic pull-off is then not computed twice."""
    from mcsim.engine.spec import MonteCarloSpec

    if not math.isfinite(turn):
        raise ParameterError(f"pads need the adhesion summary's turn; law {law!r} has none")
    spec = MonteCarloSpec(point.surface, point.material, np.asarray(config.h), point.area,
                          config.pads, pads_seed(config.entropy, point.pads_index), law, cycle=True,
                          environment=point.environment)  # fmt: skip
    force = config.restoring_force if point.restoring_force is None else point.restoring_force
    lateral = config.tangential_force if point.tangential_force is None else point.tangential_force
    acting = (
        spec
        if spec.environment is None
        else dataclasses.replace(spec, environment=spec.environment.acting())
    )  # the same pads as every such point's
    summary = None
    if known is not None:
        (k_surface, k_material, k_law, k_turn, k_environment), k_summary = known
        if (k_surface is acting.surface and k_material is acting.material and k_law == acting.law
                and k_turn == turn and k_environment is acting.environment):  # fmt: skip
            summary = k_summary
    return config.shared.get(
        (acting, force, lateral, preload, turn, h_pull_off),
        lambda: finite_pads(acting, force, preload=preload, turn=turn, h_pull_off=h_pull_off,
                            tail=config.tail, friction=config.friction, tangential_force=lateral,
                            floor=config.floor, workers=config.pad_workers, summary=summary),
    )  # fmt: skip


def pads_seed(entropy: int, index: int) -> int:
    """Root seed of the pads at grid point ``index``: 128 bits drawn from
    ``SeedSequence(entropy, spawn_key=(index, 1))``, a stream apart from :func:`point_seed`'s
    (``mcsim simulate --cycle --seed`` with it draws the same pads)."""
    a, b = np.random.SeedSequence(entropy, spawn_key=(index, 1)).generate_state(2, np.uint64)
    return (int(a) << 64) | int(b)


def _regime(surface: Surface, material: Material, law: str) -> dict:
    """The regime numbers of one summit and the regime warnings."""
    return {
        "tabor": _number(tabor_parameter(surface, material)),
        "maugis_lambda": _number(maugis_parameter(surface, material)),
        "adhesion_parameter": adhesion_parameter(surface, material),
        "plasticity_index": _number(plasticity_index(surface, material)),
        "regime_warning": "; ".join(regime_warnings(surface, material, law)),
    }


#: Points per batch of the compiled fast path (:func:`evaluate_batch`).
BATCH = 64


def _fast(point: Point, config: Config) -> bool:
    """Whether :func:`mcsim.engine.maps.designmap.jkr_summaries` computes this point: the jkr law
    set on Gaussian summit heights, without Monte Carlo, pads or a preload, and either
    without an environment or with one over Gaussian heights about the mean plane (not a
    measured height histogram, which the compiled kernel does not know), with one radius."""
    surface = point.surface
    gaussian_gaps = point.environment is None or surface.map_heights is None
    return (point.law == "jkr" and not config.mc and isinstance(surface.heights, Gaussian)
            and gaussian_gaps and config.preload is None and point.preload is None
            and not config.pads
            and surface.radius_by_height is None)  # fmt: skip


def _alike(point: Point) -> tuple:
    """What a point's pads depend on besides the sweep's shared inputs: points equal in it
    share their pads (:class:`SharedPads`; its key adds what follows from these)."""
    environment = None if point.environment is None else point.environment.acting()
    return (point.pads_index, point.surface, point.material, point.law, point.area, environment,
            point.restoring_force, point.tangential_force, point.preload)  # fmt: skip


def batches(points, config: Config):
    """Consecutive points in lists: up to :data:`BATCH` fast-path points, others alone; with
    pads, the points whose pads act alike (:func:`_alike`) in one list, in the order of their
    first, so that a point waiting for another's pads never holds a worker (a thread, or a
    Dask process that would evaluate them again)."""
    if config.pads:
        groups: dict = {}
        for point in points:
            groups.setdefault(_alike(point), []).append(point)
        yield from groups.values()
        return
    batch: list[Point] = []
    for point in points:
        if not _fast(point, config):
            if batch:
                yield batch
                batch = []
            yield [point]
            continue
        batch.append(point)
        if len(batch) == BATCH:
            yield batch
            batch = []
    if batch:
        yield batch


def evaluate_batch(points: list[Point], config: Config) -> list[dict]:
    """:func:`evaluate` of each point; fast-path points (:func:`_fast`) in one compiled call.

    The fast path gives the approach curves and the adhesion summary of
    :func:`mcsim.engine.maps.designmap.jkr_summaries`: the same quantities as
    :func:`mcsim.physics.adhesion.adhesion_summary` and :func:`mcsim.gw_curves` (with the
    environment's curves and works where the points have one), equal to them within that
    module's stated tolerances (not bit for bit). A point the fast path leaves to the
    reference (or a batch it fails on, or one that mixes points with and without an
    environment) is evaluated by :func:`evaluate`.
    """
    environments = [p.environment for p in points]
    with_environment = environments[0] is not None
    if not all(_fast(p, config) for p in points) or any(
        (e is not None) != with_environment for e in environments
    ):
        return [evaluate(p, config) for p in points]
    h = np.asarray(config.h)
    s = [p.surface for p in points]
    m = [p.material for p in points]
    environment = {}
    if with_environment:
        gaps = [gap_heights(x) for x in s]
        environment = {"environment": environments, "rq": [g.rq for g in gaps],
                       "summit_offset": [g.summit_offset for g in gaps]}  # fmt: skip
    try:
        fast = jkr_summaries([x.sigma for x in s], [x.R for x in s], [x.eta for x in s],
                             [x.E_star for x in m], [x.K for x in m], [x.gamma for x in m], h,
                             turn=config.turn, **environment)  # fmt: skip
    except (MCSimError, ArithmeticError, ValueError, RuntimeError):
        return [evaluate(p, config) for p in points]
    contact = np.asarray(GAUSSIAN.sf(h), dtype=float)
    summary = [*SUMMARY, *(ENVIRONMENT_SUMMARY if with_environment else ())]
    summary.remove("pull_off_pressure")
    curves = ("load", "area", *(("vdw", "capillary") if with_environment else ()))
    out = []
    for i, point in enumerate(points):
        if fast["status"][i] == REFERENCE:
            out.append(evaluate(point, config))
            continue
        material = point.material
        values = {"law_used": "jkr", "contact_fraction": contact}
        values |= {k: fast[k][i] for k in curves}
        if material.tau is not None:  # Bowden-Tabor friction, as mcsim.gw_curves
            values["friction"] = material.tau / material.K * values["area"]
            with np.errstate(invalid="ignore", divide="ignore"):
                values["mu"] = np.where(values["load"] > 0, values["friction"] / values["load"],
                                        np.nan)  # fmt: skip
        values |= _regime(point.surface, material, "jkr")
        values |= {k: float(fast[k][i]) for k in summary}
        values["pull_off_pressure"] = values["pull_off"] * material.K
        out.append(values)
    return out


def _number(value: float | None) -> float:
    return math.nan if value is None else float(value)


def point_seed(entropy: int, index: int) -> int:
    """Root seed of the Monte Carlo run at grid point ``index``: 128 bits drawn from
    ``SeedSequence(entropy, spawn_key=(index,))``, the point's own child stream."""
    a, b = np.random.SeedSequence(entropy, spawn_key=(index,)).generate_state(2, np.uint64)
    return (int(a) << 64) | int(b)
