"""The Monte Carlo engine: explicit summit populations on finite patches.

A run is ``realizations`` independent patches of nominal area A. Each patch holds N
summits (N ~ Poisson(ηA), or N = round(ηA) fixed). Only summits above the lowest
threshold s_min of the sweep (:attr:`MonteCarloSpec.s_min`: the lowest separation
h_min for the seed, lower for a law set with non-contact attraction or a break-off
below zero) can carry force at any row of the sweep, so the engine draws their
number exactly (Binomial(N, S(s_min)), or Poisson thinning) and their heights from
the distribution truncated to s > s_min: the same law as sampling all N, far less
work at high s_min.

The rows of a run are the separations of ``h`` on approach and, with ``cycle``,
again on retraction after the closest approach min(h) (:meth:`MonteCarloSpec.rows`);
every block is summed over all rows in one pass.

Reproducibility: heights are drawn and summed in fixed blocks of :data:`BLOCK`
summits. Block b of realization r draws from its own stream
``SeedSequence(entropy, spawn_key=(r, 1 + b))`` (the counts use ``(r, 0)``); these are
exactly the children ``SeedSequence(entropy).spawn(...)`` would make. Per-block partial
sums are combined in block order. The result is therefore bit-identical for any
chunk size, number of workers, backend (threads or Dask) and interruption/resume.
"""

from __future__ import annotations

import collections
import concurrent.futures
import contextlib
import dataclasses
import functools
import itertools
import math
import os
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from mcsim.engine.kernels import block_sums, sum_columns
from mcsim.engine.spec import MonteCarloSpec, check_count
from mcsim.model.errors import ParameterError

#: Summits per random stream and per partial sum. Part of the reproducibility contract:
#: changing it changes the numbers.
BLOCK = 1 << 16

#: Default number of summits handled by one task (a whole number of blocks).
DEFAULT_CHUNK = 1 << 18


#: Seconds of work before the first checkpoint (later ones follow ``checkpoint_every``).
FIRST_CHECKPOINT = 10.0

#: Longest wait (s) for a task's result between two calls of the ``interrupt`` hook.
POLL = 0.1


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
    """Draw N and the number of summits above s_min for realization ``r``."""
    rng = _stream(spec.entropy, r, 0)
    p = float(spec.surface.heights.sf(spec.s_min))
    lam = spec.surface.eta * spec.area
    if spec.count == "fixed":
        n = round(lam)
        return PatchPlan(n, int(rng.binomial(n, p)))
    above = int(rng.poisson(lam * p))
    below = int(rng.poisson(lam * (1 - p)))
    return PatchPlan(above + below, above)


def sample_block(spec: MonteCarloSpec, plan: PatchPlan, r: int, b: int) -> np.ndarray:
    """Heights (m) of block ``b`` of realization ``r``: summits above s_min only."""
    rng = _stream(spec.entropy, r, 1 + b)
    s = spec.surface.heights.sample_above(plan.block_size(b), spec.s_min, rng)
    return s * spec.surface.sigma


@dataclass
class EnsembleSums:
    """Raw Monte Carlo totals of a run, complete or in progress.

    Attributes
    ----------
    spec : MonteCarloSpec
        The run definition.
    n_summits : ndarray, shape (R,)
        N of each patch.
    sums : ndarray, shape (R, rows, C)
        Per realization and row (:meth:`MonteCarloSpec.rows`: the separations of
        ``spec.h`` in order, on approach, then on retraction for a cycle): the columns
        :func:`mcsim.engine.kernels.sum_columns` of the law set (for the seed
        :data:`mcsim.engine.kernels.SUM_COLUMNS`, forces in N), summed over the blocks done.
    n_blocks, done_blocks : ndarray, shape (R,)
        Blocks of each patch, and how many of them (from the first, in order) are in
        ``sums``.
    heights : list of ndarray or None
        Sampled heights above s_min (m) per realization, when kept.
    """

    spec: MonteCarloSpec
    n_summits: np.ndarray
    sums: np.ndarray
    n_blocks: np.ndarray
    done_blocks: np.ndarray
    heights: list[np.ndarray] | None = field(default=None, repr=False)

    @property
    def complete(self) -> bool:
        return bool(np.all(self.done_blocks == self.n_blocks))

    @classmethod
    def start(cls, spec: MonteCarloSpec) -> EnsembleSums:
        """Nothing done yet: the counts of every patch drawn, no block summed."""
        plans = [plan_patch(spec, r) for r in range(spec.realizations)]
        R = spec.realizations
        return cls(
            spec=spec,
            n_summits=np.array([p.n_summits for p in plans], dtype=np.int64),
            sums=np.zeros((R, spec.rows()[0].size, len(sum_columns(spec.law_set)))),
            n_blocks=np.array([p.n_blocks for p in plans], dtype=np.int64),
            done_blocks=np.zeros(R, dtype=np.int64),
        )

    def plans(self) -> list[PatchPlan]:
        return [plan_patch(self.spec, r) for r in range(self.spec.realizations)]

    def completed(self) -> EnsembleSums:
        """The realizations whose every block is done, as a complete ensemble."""
        done = np.flatnonzero(self.done_blocks == self.n_blocks)
        spec = dataclasses.replace(self.spec, realizations=max(done.size, 1))
        if done.size == 0:
            raise ParameterError("no realization of this run is complete yet")
        return EnsembleSums(
            spec, self.n_summits[done], self.sums[done], self.n_blocks[done], self.done_blocks[done]
        )


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


def make_tasks(plans: list[PatchPlan], chunk_size: int, first_block=None) -> Iterator[Task]:
    """Split every patch into tasks of about ``chunk_size`` summits (whole blocks),
    starting at ``first_block[r]`` (0 by default) for realization r. A generator:
    memory stays flat however many tasks a patch of any size makes."""
    chunk_blocks = max(1, math.ceil(chunk_size / BLOCK))
    first = [0] * len(plans) if first_block is None else first_block
    return (
        Task(r, start, min(start + chunk_blocks, plan.n_blocks), plan)
        for r, plan in enumerate(plans)
        for start in range(int(first[r]), plan.n_blocks, chunk_blocks)
    )


def run_task(spec: MonteCarloSpec, task: Task, keep_heights: bool = False):
    """Sample and sum the blocks of one task; runs in a thread, a process or on Dask.

    Returns the per-block partial sums (each ``(rows, C)``, rows as in
    :meth:`MonteCarloSpec.rows`) and, if asked, the sampled heights.
    """
    d, d_turn = spec.rows()
    blocks = [
        sample_block(spec, task.plan, task.realization, b) for b in range(task.start, task.stop)
    ]
    partials = [sums(spec, z, d, d_turn) for z in blocks]
    return partials, (blocks if keep_heights else None)


def sums(spec: MonteCarloSpec, z: np.ndarray, d: np.ndarray, d_turn=None) -> np.ndarray:
    """The law set's sums (:func:`~mcsim.engine.kernels.block_sums`) over summits ``z`` (m) at
    separations ``d`` (m; after ``d_turn``, m): one compiled call, or with a radius by height
    one per band, over its summits in their order, added (every column is a sum over
    summits). Bit-reproducible as the kernel is."""
    if spec.surface.radius_by_height is None:
        return block_sums(z, d, spec.law_set, spec.arguments, d_turn=d_turn, edges=spec.edges)
    band = spec.surface.radius_by_height.band_of(z / spec.surface.sigma)
    out = None
    for k, (args, edges) in enumerate(spec.parts):
        part = block_sums(z[band == k], d, spec.law_set, args, d_turn=d_turn, edges=edges)
        out = part if out is None else out + part
    return out


def run_task_cuda(spec: MonteCarloSpec, task: Task, keep_heights: bool = False):
    """:func:`run_task` on the GPU (:func:`mcsim.engine.cuda.patch_block_sums_cuda`): the same
    blocks and rows, heights drawn on the GPU and never copied back."""
    from mcsim.engine.cuda import patch_block_sums_cuda

    law = spec.law_set
    d, d_turn = spec.rows()
    parts = patch_block_sums_cuda(
        law=law, args=law.arguments(spec.surface, spec.material), heights=spec.surface.heights,
        sigma=spec.surface.sigma, s_min=spec.s_min, entropy=spec.entropy,
        realization=task.realization, first_block=task.start, d=d, d_turn=d_turn,
        block_sizes=[task.plan.block_size(b) for b in range(task.start, task.stop)],
        edges=law.edges_for(spec.surface, spec.material),
    )  # fmt: skip
    return [block for part in parts for block in part], None


def default_workers() -> int:
    """All cores available to this process."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _done_within(future, timeout: float) -> bool:
    """Whether ``future`` (a thread pool's or a Dask one) is done, waiting up to ``timeout`` s.

    A Dask future is polled rather than asked for ``result(timeout=...)``: distributed's
    ``sync`` can then lose the result of a task that completes as the timeout fires and
    raise ``UnboundLocalError`` (seen on a loaded 2-core machine with distributed 2026.8 and Python 3.11).
    """
    if isinstance(future, concurrent.futures.Future):
        return bool(concurrent.futures.wait([future], timeout=timeout).done)
    deadline = time.monotonic() + timeout
    while not future.done():
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.005)
    return True


def in_order(submit: Callable, tasks: Iterable[Task], window: int, interrupt: Callable[[], None]):
    """Yield ``(task, result)`` in task order, with at most ``window`` tasks in flight,
    calling ``interrupt()`` at least every :data:`POLL` seconds while waiting.

    Pending tasks are cancelled when the generator is closed (an error, an interruption).
    """
    pending: collections.deque = collections.deque()
    queue = iter(tasks)
    try:
        for task in itertools.islice(queue, window):
            pending.append((task, submit(task)))
        while pending:
            task, future = pending[0]
            interrupt()
            while not _done_within(future, POLL):
                interrupt()
            result = future.result()
            pending.popleft()
            for nxt in itertools.islice(queue, 1):
                pending.append((nxt, submit(nxt)))
            yield task, result
    finally:
        for _, future in pending:
            future.cancel()


def run_sums(
    spec: MonteCarloSpec,
    *,
    workers: int | None = None,
    chunk_size: int = DEFAULT_CHUNK,
    keep_heights: bool = False,
    progress: Callable[[int], None] | None = None,
    client=None,
    resume: EnsembleSums | None = None,
    checkpoint: Callable[[EnsembleSums], None] | None = None,
    checkpoint_every: float = 60.0,
    interrupt: Callable[[], None] | None = None,
) -> EnsembleSums:
    """Sample every patch of ``spec`` and sum the per-summit laws at every separation.

    Parameters
    ----------
    spec : MonteCarloSpec
        The run.
    workers : int, optional
        Local worker threads (the numba kernel and NumPy's samplers release the GIL,
        so threads use every core without copying data between processes); all
        cores by default. On Dask, the tasks in flight are twice the cluster's threads.
    chunk_size : int
        Summits per task, rounded up to whole blocks.
    keep_heights : bool
        Keep the sampled heights (memory grows with N; not with ``resume``).
    progress : callable, optional
        Called with the number of summits finished after each task.
    client : dask.distributed.Client, optional
        Run the tasks on this Dask cluster instead.
    resume : EnsembleSums, optional
        An unfinished run of the same ``spec`` to continue (not modified).
    checkpoint : callable, optional
        Called with the state so far after :data:`FIRST_CHECKPOINT` seconds, then at
        most every ``checkpoint_every`` seconds, and once more if the run is
        interrupted with progress not yet saved (then the interruption propagates).
    checkpoint_every : float
        Seconds between checkpoints.
    interrupt : callable, optional
        Called between tasks and at least every :data:`POLL` seconds while waiting
        for one; whatever it raises stops the run (see :func:`mcsim.engine.interrupt.check`).

    Returns
    -------
    EnsembleSums
        Identical, bit for bit, for every ``workers``, ``chunk_size``, backend and
        interruption: the random streams and the partial sums belong to fixed
        blocks, and the partial sums are added in block order.
    """
    workers = default_workers() if workers is None else workers
    check_count("workers", workers)
    check_count("chunk_size", chunk_size)
    if resume is not None and resume.spec != spec:
        raise ParameterError(
            f"cannot resume: {', '.join(resume.spec.differences(spec))} differ(s) from the run's"
        )
    if resume is not None and keep_heights:
        raise ParameterError("keep_heights cannot be combined with resuming a run")
    task_fn = run_task
    if spec.device == "cuda":
        from mcsim.engine.cuda import blocks_per_launch, require_gpu

        require_gpu()
        if keep_heights or client is not None:
            raise ParameterError(
                "device = 'cuda' runs on this machine's GPU and keeps no heights: "
                "drop keep_heights and the Dask scheduler"
            )
        task_fn, workers = run_task_cuda, 1  # one GPU; big tasks keep it busy
        rows = spec.rows()[0].size  # tasks of one launch at least, its sums within LAUNCH_BYTES
        chunk_size = max(
            chunk_size, blocks_per_launch(rows, len(sum_columns(spec.law_set))) * BLOCK
        )
    if resume is None:
        state = EnsembleSums.start(spec)
    else:  # the inputs are immutable values; only the progress is copied
        state = dataclasses.replace(
            resume, sums=resume.sums.copy(), done_blocks=resume.done_blocks.copy()
        )
    plans = state.plans()
    tasks = make_tasks(plans, chunk_size, state.done_blocks)
    kept: list[list[np.ndarray]] = [[] for _ in plans]
    next_checkpoint = time.monotonic() + min(FIRST_CHECKPOINT, checkpoint_every)
    with contextlib.ExitStack() as stack:
        if client is None:
            pool = ThreadPoolExecutor(max_workers=workers)
            # Queued tasks are dropped, running ones (short) finished, on any exit.
            stack.callback(pool.shutdown, wait=True, cancel_futures=True)
            submit = functools.partial(pool.submit, task_fn, spec, keep_heights=keep_heights)
            window = 2 * workers
        else:
            submit = functools.partial(
                client.submit, run_task, spec, keep_heights=keep_heights, pure=False
            )
            window = 2 * max(1, sum(client.nthreads().values()))
        # Progress of realization r is committed as one (sums, blocks done) pair in a
        # single store, so an interruption (Ctrl-C) sees a task wholly done or not at
        # all, and the checkpoint it writes never counts a block twice on resume.
        committed = {
            r: (state.sums[r], int(state.done_blocks[r])) for r in range(spec.realizations)
        }
        unsaved = False

        def settle() -> EnsembleSums:
            for r, (sums, done) in committed.items():
                state.sums[r], state.done_blocks[r] = sums, done
            return state

        results = stack.enter_context(
            contextlib.closing(in_order(submit, tasks, window, interrupt or (lambda: None)))
        )
        try:
            for task, (partials, blocks) in results:
                sums = committed[task.realization][0].copy()
                for part in partials:  # in block order
                    sums += part
                committed[task.realization] = (sums, task.stop)
                unsaved = True
                if blocks is not None:
                    kept[task.realization].extend(blocks)
                if progress is not None:
                    progress(task.n_summits)
                if checkpoint is not None and time.monotonic() > next_checkpoint:
                    checkpoint(settle())
                    unsaved = False
                    next_checkpoint = time.monotonic() + checkpoint_every
        except BaseException:
            results.close()  # cancel the queued tasks before saving
            if checkpoint is not None and unsaved:
                checkpoint(settle())
            raise
    settle()
    if keep_heights:
        state.heights = [np.concatenate(k) if k else np.empty(0) for k in kept]
    return state
