"""Worker processes: Dask for runs that outgrow one machine (optional extra ``mcsim[dask]``),
and a plain pool of this machine's cores for tasks that hold Python's lock.

The Monte Carlo tasks (:func:`mcsim.engine.montecarlo.run_task`) are independent and
return small arrays, so any Dask cluster can run them: a local one, or one that
already exists (started by hand, or on a batch system with dask-jobqueue). A sweep's
pads spend a third to half of their time in Python between compiled sums, so that threads
gain little: :func:`process_pool` runs them on every core without Dask. The numbers do not
depend on where the tasks run.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import logging
import multiprocessing
import multiprocessing.connection
import os
import signal
import threading
import warnings
from collections.abc import Callable, Iterator

from mcsim.model.errors import MCSimError, WorkerError

#: Seconds to wait for an existing scheduler to answer before giving up.
CONNECT_TIMEOUT = 5.0
#: The scheduler that runs a sweep's points on :func:`process_pool` (no Dask).
PROCESSES = "processes"


@contextlib.contextmanager
def _quiet_shutdown() -> Iterator[None]:
    """Closing a local cluster, no warnings from distributed: its nannies give each worker
    process 4 s to exit and then kill it, warning "Worker process still alive after 4.0
    seconds, killing" once per worker, which happens with many processes on few cores
    (each tears down NumPy and numba). Every result is in by then; nothing is lost."""
    logger = logging.getLogger("distributed")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


@contextlib.contextmanager
def dask_client(scheduler: str, workers: int | None = None) -> Iterator[object]:
    """A ``dask.distributed.Client`` for ``scheduler``, closed on exit.

    Parameters
    ----------
    scheduler : str
        ``"local"`` starts a local cluster of ``workers`` single-threaded worker
        processes; anything else is the address of an existing scheduler, e.g.
        ``"tcp://10.0.0.5:8786"``.
    workers : int, optional
        Worker processes of a local cluster (all cores by default).
    """
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise MCSimError("Dask is not installed: pip install 'mcsim[dask]'") from None
    if scheduler == "local":
        # the workers' own WARNING lines (a task cancelled by Ctrl-C, ...) are not the user's
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR)  # fmt: skip
        try:
            with Client(cluster) as client:
                yield client
        finally:
            with _quiet_shutdown():
                cluster.close()
        return
    try:
        client = Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError, ValueError) as err:
        raise MCSimError(f"cannot reach the Dask scheduler at {scheduler!r}: {err}") from None
    with client:
        yield client


def _quiet_worker(filters: list) -> None:
    """A pool worker's start: Ctrl-C is this process's parent's to handle (it ends the
    workers), the parent's warning filters apply, and the worker ends with its parent: a
    parent killed outright (SIGKILL, out of memory) cannot end it, and its pool's queues
    would keep it waiting forever."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C pending since the start: dropped
    if hasattr(signal, "pthread_sigmask"):  # not on Windows
        signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT])
    warnings.filters[:] = filters
    parent = multiprocessing.parent_process()
    if parent is not None:
        threading.Thread(target=_end_with, args=(parent.sentinel,), daemon=True).start()


def _end_with(sentinel) -> None:
    """End this process, its task unfinished, when ``sentinel`` (its parent's) fires."""
    multiprocessing.connection.wait([sentinel])
    os._exit(1)


def _filters() -> list:
    """This process's warning filters that another process can read: not those of a warning
    class defined in ``__main__`` (a notebook's or a script's), which it cannot import."""
    return [f for f in warnings.filters if getattr(f[2], "__module__", "") != "__main__"]


@contextlib.contextmanager
def _ctrl_c_blocked() -> Iterator[None]:
    """Ctrl-C held back in this thread meanwhile (delivered after): a process spawned
    meanwhile starts with it blocked."""
    if not hasattr(signal, "pthread_sigmask"):  # Windows
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, [signal.SIGINT])
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


@contextlib.contextmanager
def process_pool(workers: int) -> Iterator[Callable[..., concurrent.futures.Future]]:
    """``submit(fn, *args, **kwargs)`` on a pool of ``workers`` fresh processes, closed on exit.

    The workers are spawned (no thread or lock of this process is inherited) with Ctrl-C
    blocked until they ignore it, and they take this process's warning filters: a Ctrl-C
    reaches this process alone, which ends the pool. Leaving early (an error, an
    interruption) terminates the workers rather than waiting for their tasks. A worker
    that cannot start (a script without ``if __name__ == "__main__":`` runs itself again in
    it) breaks the pool: an error, not a hang.
    """
    context = multiprocessing.get_context("spawn")
    pool = concurrent.futures.ProcessPoolExecutor(
        workers, mp_context=context, initializer=_quiet_worker, initargs=(_filters(),)
    )

    def submit(fn, *args, **kwargs) -> concurrent.futures.Future:
        with _ctrl_c_blocked():  # the pool spawns its workers as tasks come
            return pool.submit(fn, *args, **kwargs)

    try:
        yield submit
    except concurrent.futures.process.BrokenProcessPool:
        _terminate(pool)
        raise WorkerError("a worker process ended abruptly: killed, out of memory, or a script "
                          "that each worker runs again (one without 'if __name__ == "
                          "\"__main__\":', or read from standard input; workers=1 runs in "
                          "this process)") from None  # fmt: skip
    except BaseException:
        _terminate(pool)
        raise
    pool.shutdown(wait=True)


def _terminate(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """End ``pool``'s workers now, their tasks unfinished."""
    if hasattr(pool, "terminate_workers"):  # Python 3.14
        pool.terminate_workers()
        return
    processes = list((pool._processes or {}).values())  # private before 3.14: none public
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        process.terminate()
    for process in processes:
        process.join()
