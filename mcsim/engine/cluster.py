"""Dask for runs that outgrow one machine (optional extra ``mcsim[dask]``).

The Monte Carlo tasks (:func:`mcsim.engine.montecarlo.run_task`) are independent and
return small arrays, so any Dask cluster can run them: a local one, or one that
already exists (started by hand, or on a batch system with dask-jobqueue). The
numbers do not depend on where the tasks run.
"""

from __future__ import annotations

import contextlib
import logging
from collections.abc import Iterator

from mcsim.model.errors import MCSimError

#: Seconds to wait for an existing scheduler to answer before giving up.
CONNECT_TIMEOUT = 5.0


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
