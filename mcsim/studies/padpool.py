"""Pads evaluated on worker processes: the plain pads of :func:`mcsim.studies.pads.finite_pads`
and of a run (:meth:`mcsim.Run.pull_off`, as :func:`mcsim.studies.pads.pad_report` calls it),
and the stages of :func:`mcsim.studies.tail.importance_p_stick`.

A pad's search holds Python's lock for about 60 % of its time (NumPy between compiled sums),
so that threads gain little; a :class:`PadPool` of ``workers`` > 1 evaluates a list of pads
in contiguous chunks (:func:`chunks`) on worker processes of
:func:`mcsim.engine.cluster.process_pool` (spawned, Ctrl-C handled by this process, a
broken pool an error), started at its first use and shared by every later one, since a
worker's start (its imports and compiled kernels, about 1 CPU s) is paid once. Each pad's
value is the same function of the same inputs wherever it runs and the chunks' results are
joined in order, so that they do not depend on ``workers``. With one worker everything runs
in this process, as a plain loop.
"""

from __future__ import annotations

import contextlib
import functools
import pickle
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor

from mcsim.engine import interrupt

#: Chunks of a list of pads per worker: a few, so that the last one to finish leaves the
#: others idle for a fraction of a chunk, not of a worker's share.
CHUNKS_PER_WORKER = 4


def chunks(n: int, workers: int) -> list[slice]:
    """Contiguous slices of ``range(n)``, in order, about equal: one for one worker, else
    :data:`CHUNKS_PER_WORKER` per worker (fewer where ``n`` is smaller; one, empty, where
    ``n`` is 0)."""
    parts = 1 if workers == 1 else max(1, min(n, CHUNKS_PER_WORKER * workers))
    return [slice(i * n // parts, (i + 1) * n // parts) for i in range(parts)]


def portable(fn: Callable) -> bool:
    """Whether a worker process can call ``fn``: it pickles, and not by a name of ``__main__``
    (a script's or a notebook's, which a spawned process may not have). A lambda, a closure
    or a function of ``__main__`` is called in this process only."""
    owner = fn.func if isinstance(fn, functools.partial) else fn
    if getattr(owner, "__module__", None) == "__main__":
        return False
    try:
        pickle.dumps(fn)
    except (pickle.PicklingError, AttributeError, TypeError):
        return False
    return True


class PadPool:
    """Where lists of pads are evaluated: in this process (``workers`` 1), else on one pool
    of ``workers`` worker processes started at the first :meth:`map` and closed with
    ``stack``.

    Parameters
    ----------
    stack : contextlib.ExitStack
        Closes the pool (its workers end with it).
    workers : int
        Worker processes (≥ 1).
    """

    def __init__(self, stack: contextlib.ExitStack, workers: int) -> None:
        self.workers = workers
        self._stack = stack
        self._submit = None

    def map(self, fn: Callable, calls: list[tuple], *, processes: bool = True) -> list:
        """``fn(*call)`` of each call, in order: in this process with one worker; else on the
        worker processes, or, where not ``processes`` (``fn`` or its arguments only this
        process can call, :func:`portable`), on as many threads. While it waits a Ctrl-C
        (:func:`mcsim.engine.interrupt.check`) ends it, the pool's tasks unfinished."""
        if self.workers == 1:
            return [fn(*call) for call in calls]
        if not processes:
            with ThreadPoolExecutor(self.workers) as threads:
                return list(threads.map(lambda call: fn(*call), calls))
        from mcsim.engine.cluster import process_pool
        from mcsim.engine.montecarlo import in_order  # numba's import: only where a pool runs

        if self._submit is None:
            self._submit = self._stack.enter_context(process_pool(self.workers))
        submit = self._submit
        results = in_order(lambda call: submit(fn, *call), calls, len(calls), interrupt.check)
        with contextlib.closing(results):
            return [result for _, result in results]


@contextlib.contextmanager
def opened(workers: int | PadPool) -> Iterator[PadPool]:
    """``workers`` if it is an open :class:`PadPool` (a caller's, shared), else a new one of
    ``workers`` processes, closed on exit."""
    if isinstance(workers, PadPool):
        yield workers
        return
    with contextlib.ExitStack() as stack:
        yield PadPool(stack, workers)
