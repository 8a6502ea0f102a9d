"""The Monte Carlo engine: explicit summit populations on finite patches.

A run is ``realizations`` independent patches of nominal area A. Each patch holds N
summits (N ~ Poisson(ηA), or N = round(ηA) fixed). Only summits above the lowest
separation h_min can touch at any separation of the sweep, so the engine draws their
number exactly (Binomial(N, S(h_min)), or Poisson thinning) and their heights from
the distribution truncated to s > h_min: the same law as sampling all N, far less
work at high h_min.

Reproducibility: heights are drawn and summed in fixed blocks of :data:`BLOCK`
summits. Block b of realization r draws from its own stream
``SeedSequence(entropy, spawn_key=(r, 1 + b))`` (the counts use ``(r, 0)``); these are
exactly the children ``SeedSequence(entropy).spawn(...)`` would make. Per-block partial
sums are combined in block order. The result is therefore bit-identical for any
chunk size and any number of workers.
"""

from __future__ import annotations

import contextlib
import itertools
import math
import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from .errors import ParameterError
from .kernels import SUM_COLUMNS, block_sums
from .laws import get_law_set
from .params import Material, Surface, check_range

#: Summits per random stream and per partial sum. Part of the reproducibility contract:
#: changing it changes the numbers.
BLOCK = 1 << 16

#: Default number of summits handled by one task (a whole number of blocks).
DEFAULT_CHUNK = 1 << 20

COUNT_MODES = ("poisson", "fixed")


@dataclass(frozen=True)
class MonteCarloSpec:
    """Everything that defines a Monte Carlo run (and so its numbers).

    Parameters
    ----------
    surface : Surface
        Summit population.
    material : Material
        Material pair.
    h : ndarray
        Dimensionless separations d/σ, any order.
    area : float
        Nominal area of one patch, m².
    realizations : int
        Number of independent patches.
    entropy : int
        Seed entropy of the root :class:`numpy.random.SeedSequence`.
    law : str
        Law-set name.
    count : {"poisson", "fixed"}
        N ~ Poisson(ηA) or N = round(ηA).
    """

    surface: Surface
    material: Material
    h: np.ndarray
    area: float
    realizations: int
    entropy: int
    law: str = "seed"
    count: str = "poisson"

    def __post_init__(self) -> None:
        h = np.atleast_1d(np.asarray(self.h, dtype=float))
        if h.ndim != 1 or h.size == 0:
            raise ParameterError("h must be a non-empty list of separations")
        if not np.all(np.isfinite(h)):
            raise ParameterError(f"h must be finite, got {h[~np.isfinite(h)][0]!r}")
        object.__setattr__(self, "h", h)
        object.__setattr__(self, "area", check_range("area", self.area, "m^2", low=0))
        if (
            isinstance(self.realizations, bool)
            or not isinstance(self.realizations, int | np.integer)
            or self.realizations < 1
        ):
            raise ParameterError(
                f"realizations = {self.realizations!r} is out of range (allowed: integer >= 1)"
            )
        if self.count not in COUNT_MODES:
            raise ParameterError(f"count = {self.count!r} is not one of {', '.join(COUNT_MODES)}")
        if self.count == "fixed" and round(self.surface.eta * self.area) < 1:
            raise ParameterError(
                f"area = {self.area!r} m^2 holds {self.surface.eta * self.area:.3g} summits: "
                "round(eta*area) must be >= 1 for count='fixed'"
            )
        get_law_set(self.law)

    @property
    def d(self) -> np.ndarray:
        """Separations in m."""
        return self.h * self.surface.sigma

    @property
    def expected_summits(self) -> float:
        """E[N] per patch."""
        n = self.surface.eta * self.area
        return float(round(n)) if self.count == "fixed" else n


@dataclass(frozen=True)
class PatchPlan:
    """The summit counts of one realization (drawn before any height)."""

    n_summits: int
    n_above: int

    @property
    def n_blocks(self) -> int:
        return -(-self.n_above // BLOCK)

    def block_size(self, b: int) -> int:
        return min(BLOCK, self.n_above - b * BLOCK)


def _stream(entropy: int, *key: int) -> np.random.Generator:
    return np.random.default_rng(np.random.SeedSequence(entropy, spawn_key=key))


def plan_patch(spec: MonteCarloSpec, r: int) -> PatchPlan:
    """Draw N and the number of summits above h_min for realization ``r``."""
    rng = _stream(spec.entropy, r, 0)
    p = float(spec.surface.heights.sf(spec.h.min()))
    lam = spec.surface.eta * spec.area
    if spec.count == "fixed":
        n = round(lam)
        return PatchPlan(n, int(rng.binomial(n, p)))
    above = int(rng.poisson(lam * p))
    below = int(rng.poisson(lam * (1 - p)))
    return PatchPlan(above + below, above)


def sample_block(spec: MonteCarloSpec, plan: PatchPlan, r: int, b: int) -> np.ndarray:
    """Heights (m) of block ``b`` of realization ``r``: summits above h_min only."""
    rng = _stream(spec.entropy, r, 1 + b)
    s = spec.surface.heights.sample_above(plan.block_size(b), float(spec.h.min()), rng)
    return s * spec.surface.sigma


@dataclass
class EnsembleSums:
    """Raw Monte Carlo totals of a run.

    Attributes
    ----------
    spec : MonteCarloSpec
        The run definition.
    n_summits : ndarray, shape (R,)
        N of each patch.
    sums : ndarray, shape (R, M, 10)
        Per realization and separation (in the order of ``spec.h``): the columns of
        :data:`mcsim.kernels.SUM_COLUMNS`, forces in N.
    heights : list of ndarray or None
        Sampled heights above h_min (m) per realization, when kept.
    """

    spec: MonteCarloSpec
    n_summits: np.ndarray
    sums: np.ndarray
    heights: list[np.ndarray] | None = field(default=None, repr=False)


@dataclass(frozen=True)
class Task:
    """A unit of work: blocks ``start`` to ``stop`` (excluded) of realization ``realization``."""

    realization: int
    start: int
    stop: int
    plan: PatchPlan

    @property
    def n_summits(self) -> int:
        return sum(self.plan.block_size(b) for b in range(self.start, self.stop))


def make_tasks(plans: list[PatchPlan], chunk_size: int) -> list[Task]:
    """Split every patch into tasks of about ``chunk_size`` summits (whole blocks)."""
    chunk_blocks = max(1, math.ceil(chunk_size / BLOCK))
    return [
        Task(r, start, min(start + chunk_blocks, plan.n_blocks), plan)
        for r, plan in enumerate(plans)
        for start in range(0, plan.n_blocks, chunk_blocks)
    ]


def run_task(spec: MonteCarloSpec, task: Task, keep_heights: bool = False):
    """Sample and sum the blocks of one task; runs in a thread, a process or on Dask.

    Returns the per-block partial sums (each ``(M, 10)``, separations in descending
    order of d) and, if asked, the sampled heights.
    """
    law = get_law_set(spec.law)
    args = law.arguments(spec.surface, spec.material)
    d_desc = np.sort(spec.d)[::-1]
    blocks = [
        sample_block(spec, task.plan, task.realization, b) for b in range(task.start, task.stop)
    ]
    partials = [block_sums(z, d_desc, law, args) for z in blocks]
    return partials, (blocks if keep_heights else None)


def default_workers() -> int:
    """All cores available to this process."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def run_sums(
    spec: MonteCarloSpec,
    *,
    workers: int | None = None,
    chunk_size: int = DEFAULT_CHUNK,
    keep_heights: bool = False,
    progress: Callable[[int], None] | None = None,
    client=None,
) -> EnsembleSums:
    """Sample every patch of ``spec`` and sum the per-summit laws at every separation.

    Parameters
    ----------
    spec : MonteCarloSpec
        The run.
    workers : int, optional
        Local worker threads (the numba kernel and NumPy's samplers release the GIL,
        so threads use every core without copying data between processes); all
        cores by default. Ignored when ``client`` is given.
    chunk_size : int
        Summits per task, rounded up to whole blocks.
    keep_heights : bool
        Keep the sampled heights (memory grows with N).
    progress : callable, optional
        Called with the number of summits finished after each task.
    client : dask.distributed.Client, optional
        Run the tasks on this Dask cluster instead.

    Returns
    -------
    EnsembleSums
        Identical, bit for bit, for every ``workers``, ``chunk_size`` and backend:
        the random streams and the partial sums belong to fixed blocks, and the
        partial sums are added in block order.
    """
    workers = default_workers() if workers is None else workers
    if isinstance(workers, bool) or not isinstance(workers, int | np.integer) or workers < 1:
        raise ParameterError(f"workers = {workers!r} is out of range (allowed: integer >= 1)")
    if (
        isinstance(chunk_size, bool)
        or not isinstance(chunk_size, int | np.integer)
        or chunk_size < 1
    ):
        raise ParameterError(f"chunk_size = {chunk_size!r} is out of range (allowed: integer >= 1)")
    plans = [plan_patch(spec, r) for r in range(spec.realizations)]
    tasks = make_tasks(plans, chunk_size)
    sums_desc = np.zeros((spec.realizations, spec.d.size, len(SUM_COLUMNS)))
    kept: list[list[np.ndarray]] = [[] for _ in plans]
    with contextlib.ExitStack() as stack:
        if client is None:
            pool = stack.enter_context(ThreadPoolExecutor(max_workers=workers))
            results = pool.map(
                run_task, itertools.repeat(spec), tasks, itertools.repeat(keep_heights)
            )
        else:
            futures = client.map(
                run_task, [spec] * len(tasks), tasks, keep_heights=keep_heights, pure=False
            )
            stack.callback(client.cancel, futures)
            results = (future.result() for future in futures)
        # results arrive in task order: partial sums are added in block order
        for task, (partials, blocks) in zip(tasks, results):
            for part in partials:
                sums_desc[task.realization] += part
            if blocks is not None:
                kept[task.realization].extend(blocks)
            if progress is not None:
                progress(task.n_summits)
    order = np.argsort(-spec.d, kind="stable")
    sums = np.empty_like(sums_desc)
    sums[:, order] = sums_desc  # back to the order of spec.h
    heights = [np.concatenate(k) if k else np.empty(0) for k in kept] if keep_heights else None
    return EnsembleSums(spec, np.array([p.n_summits for p in plans]), sums, heights)
